// The sky's unoccluded irradiance E(n)/π as a quadratic polynomial of the view-space unit normal
// (the three SH bands; the CPU turns them into view space each frame, `irradiance_quadratic` in
// src/scene/skybox.rs), packed for nine multiply-adds a colour: a channel's first eight weights
// in two vectors (red: r0, r1), the constant term's three in k. The passes that light every
// pixel hand it down as flat varyings (common/frame_varyings.wgsl); the sampling and upsample
// passes read it from the frame's uniforms where they need it (DO_OVER_IRRADIANCE).

#include "common/uniforms.wgsl"

// Added to the irradiance a half-size sample's DO is divided by and a pixel's multiplied by
// under a normal map (common/upsample.wgsl), so a black sky's ratio stays finite.
const NORMAL_RATIO_FLOOR: f32 = 1e-3;

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
