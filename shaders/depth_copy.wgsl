// Depth's bits into an R32Uint colour target (integer targets are renderable everywhere; R32Float
// is not on GL), bit for bit, for reading depth back where the device cannot copy a depth
// texture to a buffer (wgpu's GL backend lacks DEPTH_TEXTURE_AND_BUFFER_COPIES).

#include "common/fullscreen.wgsl"

@group(0) @binding(0) var depth: texture_2d<f32>;

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4<u32> {
    return vec4<u32>(bitcast<u32>(textureLoad(depth, vec2<i32>(in.position.xy), 0).r), 0u, 0u, 1u);
}
