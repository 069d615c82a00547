// What both sampling shaders (march.wgsl and points.wgsl) read beside the G-buffer: their
// parameters, the senders of the bounce, the sky, and which of AO and DO the mode computes.

@group(1) @binding(3) var<uniform> occ: SamplingParams;
// The senders: radiance and facing, packed (pack_sender in common/surface_pack.wgsl).
@group(1) @binding(4) var bounce_map: texture_2d<u32>;
#include "common/sky.wgsl"

// What the mode computes: AO, DO, or both (the composite and the tone mapper have the same two).
override HAS_AO: bool = true;
override HAS_DO: bool = true;
// The scene has point lights, so there is a bounce buffer to read.
override INDIRECT: bool = true;

#include "common/sky_quadratic.wgsl"

// The DO is written over the sky's unoccluded irradiance at the sample's normal, for the
// upsample to multiply by that at each pixel's own (half resolution under a normal map or smooth
// shading, whose normals turn faster than the samples are spaced: common/upsample.wgsl,
// `Plan::do_over_irradiance`).
override DO_OVER_IRRADIANCE: bool = false;

// The DO a sample at full-resolution `pixel` writes: by DO_OVER_IRRADIANCE, `value`'s DO over
// E(n) there; otherwise `value`.
fn stored_do(value: vec4<f32>, pixel: vec2<i32>) -> vec4<f32> {
    if !DO_OVER_IRRADIANCE {
        return value;
    }
    let e = irradiance_floored(frame_sky_quadratic(), load_normal(pixel));
    return vec4<f32>(value.rgb / e, value.a);
}
