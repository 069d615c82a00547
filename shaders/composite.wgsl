// Composite: ambient·albedo·AO + DO + direct point lighting, in linear HDR.
// Which terms exist is decided when the pipeline is built (override constants), so a mode or a
// scene that lacks a term pays nothing for it.

#include "common/uniforms.wgsl"
#include "common/gbuffer_read.wgsl"
#include "common/lighting.wgsl"
#include "common/fullscreen.wgsl"

// The scene has point lights: run the light loop here.
override LIGHT_LOOP: bool = true;

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4<f32> {
    let pixel = vec2<i32>(in.position.xy);
    let depth = textureLoad(g_depth, pixel, 0);
    if depth <= 0.0 {
        return vec4<f32>(0.0);
    }
    let albedo = textureLoad(g_albedo, pixel, 0);
    let normal = textureLoad(g_normal, pixel, 0);
    var color = frame.ambient.rgb * albedo.rgb;
    if LIGHT_LOOP {
        let p = view_position(in.position.xy, depth);
        color += point_lighting(p, normal.xyz, albedo.rgb, albedo.a, normal.w);
    }
    return vec4<f32>(color, 1.0);
}
