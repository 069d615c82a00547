// Skybox: drawn where the depth buffer still holds the far plane (0 in reverse-Z), by a
// full-screen triangle at depth 0 with a `GreaterEqual` test (0 >= stored passes only where
// stored is 0), so covered pixels cost nothing.

#include "common/uniforms.wgsl"
#include "common/fullscreen.wgsl"

@group(2) @binding(0) var sky_map: texture_cube<f32>;
@group(2) @binding(1) var sky_sampler: sampler;

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4<f32> {
    let ndc = vec2<f32>(in.uv.x * 2.0 - 1.0, 1.0 - in.uv.y * 2.0);
    let view_dir = vec3<f32>(ndc.x / frame.view_to_clip[0][0], ndc.y / frame.view_to_clip[1][1], -1.0);
    let world_dir = (frame.view_to_world * vec4<f32>(view_dir, 0.0)).xyz;
    let radiance = textureSampleLevel(sky_map, sky_sampler, world_dir, 0.0).rgb * frame.sky_scale;
    return vec4<f32>(radiance, 1.0);
}
