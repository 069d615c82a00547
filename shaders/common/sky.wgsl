// The sky cube map with its mip chain (bind group 2, `src/render/resources/sky.rs`), and the
// background seen through a point of the image — drawn by the skybox pass in HDR plans and by the
// composite in display plans.

#include "common/uniforms.wgsl"

@group(2) @binding(0) var sky_map: texture_cube<f32>;
@group(2) @binding(1) var sky_sampler: sampler;

// The sky's pre-exposed radiance seen through `uv` of the image ((0, 0) its top-left corner).
fn background(uv: vec2<f32>) -> vec3<f32> {
    let ndc = vec2<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0);
    let view_dir = vec3<f32>(ndc.x / frame.view_to_clip[0][0], ndc.y / frame.view_to_clip[1][1], -1.0);
    let world_dir = (frame.view_to_world * vec4<f32>(view_dir, 0.0)).xyz;
    return textureSampleLevel(sky_map, sky_sampler, world_dir, 0.0).rgb * frame.sky_scale;
}
