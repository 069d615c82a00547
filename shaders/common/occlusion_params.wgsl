// Sampling parameters shared by the occlusion pass (bind group 1, binding 3 there). Mirrors
// `OcclusionUniforms` in src/render/uniforms.rs.

const MAX_SAMPLES: u32 = 256u;

struct OcclusionParams {
    // xyz: offset in tangent space (z along the normal), unit radius; w: unused
    kernel: array<vec4<f32>, 256>,
    // The 16 per-pixel rotations of a 4x4 tile: xy = (cos, sin) of the angle (default variant)
    // or a random tangent-plane vector (classic variant); zw unused.
    rotations: array<vec4<f32>, 16>,
    // radius (view units), bias (view units), sample count, sky mip level
    params: vec4<f32>,
    // sky-light strength, indirect strength, unused, unused
    strengths: vec4<f32>,
    // The march (shaders/march.wgsl): slices, steps per side, reach (view units: how far the
    // sky's visibility and the bounce are looked for), thickness (view units: how deep a surface
    // in the depth buffer is taken to be)
    march: vec4<f32>,
}
