// The full-size copy of a half-size sampling chain's last stage, for what reads one besides the
// composite (which upsamples as it reads): see common/upsample.wgsl.

#include "common/uniforms.wgsl"
#include "common/gbuffer_read.wgsl"
#include "common/filter_params.wgsl"
#include "common/fullscreen.wgsl"

@group(1) @binding(3) var<uniform> params: FilterParams;
// The chain's last half-size stage (the average over frames, or the samples, blurred where the
// plan blurs): AO (r) or DO + AO (rgb + a).
@group(1) @binding(4) var current: texture_2d<f32>;

// The input is DO + AO (SSDO, SSAO+SSDO) rather than the one-channel AO target (SSAO).
override HAS_DO: bool = true;

// The surface of the sample at half-size `texel`, the full-resolution pixel `pixel`: its depth
// (f32 bits) and packed normal, from the G-buffer.
fn sample_surface(texel: vec2<i32>, pixel: vec2<i32>) -> vec2<u32> {
    return vec2<u32>(bitcast<u32>(load_depth(pixel)), textureLoad(g_normal, pixel, 0).r);
}

#include "common/upsample.wgsl"

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4<f32> {
    return upsample(vec2<i32>(in.position.xy), in.position.xy);
}
