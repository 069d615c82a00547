// The sky's unoccluded irradiance, E(n)/π, from the 9 spherical-harmonic coefficients in the frame
// uniforms: the composite's sky light in Off and SSAO, and the sky light the lighting pass gives
// the bounce's senders.

#include "common/uniforms.wgsl"

// E(n)/π of the sky for world-space unit normal `n` (pre-exposed), from the 9 coefficients in
// the order of `sh_basis` (src/scene/skybox.rs). Three bands can ring below 0 opposite a bright
// sun: clamped.
fn sky_irradiance(n: vec3<f32>) -> vec3<f32> {
    let c = frame.sky_sh;
    let e = c[0].rgb * 0.282095
        + (c[1].rgb * n.y + c[2].rgb * n.z + c[3].rgb * n.x) * 0.488603
        + (c[4].rgb * (n.x * n.y) + c[5].rgb * (n.y * n.z) + c[7].rgb * (n.x * n.z)) * 1.092548
        + c[6].rgb * (0.315392 * (3.0 * n.z * n.z - 1.0))
        + c[8].rgb * (0.546274 * (n.x * n.x - n.y * n.y));
    return max(e, vec3<f32>(0.0));
}
