// The sky's unoccluded irradiance E(n)/π as a quadratic polynomial of the view-space unit normal
// (the three SH bands; the CPU turns them into view space each frame, `irradiance_quadratic` in
// src/scene/skybox.rs), packed for nine multiply-adds a colour: a channel's first eight weights
// in two vectors (red: r0, r1), the constant term's three in k. The passes that light every
// pixel hand it down as flat varyings (common/frame_varyings.wgsl); the sampling and upsample
// passes read it from the frame's uniforms where they need it (DO_OVER_IRRADIANCE).

#include "common/uniforms.wgsl"

struct SkyQuadratic {
    r0: vec4<f32>,
    r1: vec4<f32>,
    g0: vec4<f32>,
    g1: vec4<f32>,
    b0: vec4<f32>,
    b1: vec4<f32>,
    k: vec4<f32>,
}

// The frame's weights (frame.sky_irradiance: rgb weights of x², y², xy, xz, yz, x, y, z, 1) as
// `SkyQuadratic` packs them.
fn frame_sky_quadratic() -> SkyQuadratic {
    let q = frame.sky_irradiance;
    return SkyQuadratic(
        vec4<f32>(q[0].r, q[1].r, q[2].r, q[3].r),
        vec4<f32>(q[4].r, q[5].r, q[6].r, q[7].r),
        vec4<f32>(q[0].g, q[1].g, q[2].g, q[3].g),
        vec4<f32>(q[4].g, q[5].g, q[6].g, q[7].g),
        vec4<f32>(q[0].b, q[1].b, q[2].b, q[3].b),
        vec4<f32>(q[4].b, q[5].b, q[6].b, q[7].b),
        vec4<f32>(q[8].rgb, 0.0),
    );
}

// E(n)/π for view-space unit normal `n` (pre-exposed). Three bands can ring below 0 opposite a
// bright sun: clamped.
fn irradiance_at(s: SkyQuadratic, n: vec3<f32>) -> vec3<f32> {
    let terms0 = vec4<f32>(n.x * n.x, n.y * n.y, n.x * n.y, n.x * n.z);
    let terms1 = vec4<f32>(n.y * n.z, n.x, n.y, n.z);
    let e = vec3<f32>(
        dot(terms0, s.r0) + dot(terms1, s.r1),
        dot(terms0, s.g0) + dot(terms1, s.g1),
        dot(terms0, s.b0) + dot(terms1, s.b1),
    ) + s.k.rgb;
    return max(e, vec3<f32>(0.0));
}

// The irradiance a half-size sample's DO is held over and a pixel's is multiplied by under a
// normal map (DO_OVER_IRRADIANCE, common/upsample.wgsl): E(n)/π, but at least a quarter of its
// mean over all normals (the constant and a third of x²'s and y²'s weights), plus 10⁻³. A sample
// facing a dark part of the sky holds mostly bounce, which a ratio of sky irradiances does not
// describe: the floor keeps the ratio between two normals under four times the sky's brightest
// irradiance over its mean, and a black sky's at 1.
fn irradiance_floored(s: SkyQuadratic, n: vec3<f32>) -> vec3<f32> {
    let mean = s.k.rgb + (vec3<f32>(s.r0.x, s.g0.x, s.b0.x) + vec3<f32>(s.r0.y, s.g0.y, s.b0.y)) / 3.0;
    return max(irradiance_at(s, n), 0.25 * mean) + 1e-3;
}
