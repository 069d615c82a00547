// The sampling passes' parameters (the sampling pass and the sender-sky march, bind group 1,
// binding 3). Mirrors `SamplingParams` in src/render/uniforms.rs field for field (checked in
// tests/it/cpu/shaders.rs). The passes that filter the samples read `FilterParams` instead
// (common/filter_params.wgsl).

const MAX_SAMPLES: u32 = 256u;

struct SamplingParams {
    // xyz: offset in tangent space (z along the normal), unit radius; w: unused
    kernel: array<vec4<f32>, 256>,
    // The 16 per-pixel rotations of a 4x4 tile: xy = (cos, sin) of the angle (default variant)
    // or a random tangent-plane vector (classic variant); zw unused.
    rotations: array<vec4<f32>, 16>,
    // sampling radius and depth bias (a length: the bias fraction times the radius), in view units
    radius: f32,
    bias_length: f32,
    // samples per pixel (points and classic variants)
    sample_count: u32,
    // the sky cube map's mip level a sample's solid angle reads
    sky_mip: f32,
    // multiply SSDO's sky light and its bounce
    sky_strength: f32,
    indirect_strength: f32,
    // the user's sky strength for the bounce's senders (the debug views' overrides of
    // `sky_strength` leave it alone, so the DO-indirect view still bounces sky light)
    sender_sky_strength: f32,
    _pad0: f32,
    // The march (shaders/common/march.wgsl): slices and steps per side...
    slices: u32,
    steps: u32,
    // ...reach (view units: how far the sky's visibility and the bounce are looked for) and
    // thickness (view units: how deep a surface in the depth buffer is taken to be)
    reach: f32,
    thickness: f32,
    // This frame's entry of the sample schedule (src/render/kernel.rs `schedule`): xy added to
    // the march's slice and step offsets (mod 1), zw the (cos, sin) the points' rotation turns
    // by; (0, 0, 1, 0) on a frame that does not accumulate.
    schedule: vec4<f32>,
}

// At half resolution a sampling pass's pixel (x, y) samples the full-resolution pixel (2x, 2y),
// with the rotation tile of its own pixel.
#include "common/sample_grid.wgsl"

// The full-resolution pixel centre a sampling pass's fragment at `frag` samples (`frag` itself
// at full resolution).
fn sampled_position(frag: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(surface_pixel(vec2<i32>(frag))) + 0.5;
}

// A material has a normal map: the G-buffer's normals are the maps', not the geometry's. The
// samples' hemisphere is then cut at the surface's own plane, taken from the depth buffer, so a
// flat surface whose mapped normals lean never occludes itself (its own depth lies in its plane,
// not above it: `depth_normal` in common/gbuffer_read.wgsl); the cosines stay the mapped
// normal's. Off: the G-buffer's normal is both.
override NORMAL_MAPPED: bool = false;
