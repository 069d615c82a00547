// The sky's unoccluded irradiance, E(n)/π, from the frame uniforms' quadratic form in the
// view-space normal: the composite's sky light in Off and SSAO, and the sky light the lighting
// pass gives the bounce's senders.

#include "common/uniforms.wgsl"

// E(n)/π of the sky for view-space unit normal `n` (pre-exposed). The three SH bands are a
// quadratic polynomial of the direction; the CPU turns them into view space each frame
// (`irradiance_quadratic` in src/scene/skybox.rs), so a pixel pays nine multiply-adds and no
// transform of its normal. Three bands can ring below 0 opposite a bright sun: clamped.
fn sky_irradiance(n: vec3<f32>) -> vec3<f32> {
    let q = frame.sky_irradiance;
    let e = q[0].rgb * (n.x * n.x) + q[1].rgb * (n.y * n.y) + q[2].rgb * (n.x * n.y)
        + q[3].rgb * (n.x * n.z) + q[4].rgb * (n.y * n.z)
        + q[5].rgb * n.x + q[6].rgb * n.y + q[7].rgb * n.z + q[8].rgb;
    return max(e, vec3<f32>(0.0));
}
