// Composite: ambient·albedo·AO + DO + direct point lighting, in linear HDR.
// Which terms exist is decided when the pipeline is built (override constants), so a mode or a
// scene that lacks a term pays nothing for it. After a lighting pass the composite is blended
// additively onto the direct light that pass wrote; otherwise it runs the light loop itself.

#include "common/uniforms.wgsl"
#include "common/gbuffer_read.wgsl"
#include "common/point_lights.wgsl"
#include "common/fullscreen.wgsl"

// AO alone (SSAO, r channel).
@group(1) @binding(3) var ao_map: texture_2d<f32>;
// DO in rgb, AO in a (SSDO, SSAO+SSDO).
@group(1) @binding(4) var do_map: texture_2d<f32>;

// Run the point-light loop here (there are lights and no lighting pass ran).
override LIGHT_LOOP: bool = true;
override HAS_AO: bool = false;
override HAS_DO: bool = false;
// AO travels in the DO buffer's alpha (SSAO+SSDO) rather than in its own buffer.
override AO_IN_DO: bool = false;
// The classic variant adds DO without the receiver's albedo, as the source does.
override CLASSIC: bool = false;
// The "lighting only" view: every surface white.
override WHITE_ALBEDO: bool = false;

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4<f32> {
    let pixel = vec2<i32>(in.position.xy);
    let depth = load_depth(pixel);
    if depth <= 0.0 {
        return vec4<f32>(0.0);
    }
    var albedo = textureLoad(g_albedo, pixel, 0);
    if WHITE_ALBEDO {
        albedo = vec4<f32>(1.0, 1.0, 1.0, albedo.a);
    }
    var directional = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    if HAS_DO {
        directional = textureLoad(do_map, pixel, 0);
    }
    var ao = 1.0;
    if HAS_AO {
        let raw = clamp(select(textureLoad(ao_map, pixel, 0).r, directional.a, AO_IN_DO), 0.0, 1.0);
        ao = mix(1.0, pow(raw, frame.shading.y), frame.shading.x);
    }
    var color = frame.sky.z * frame.ambient.rgb * albedo.rgb * ao;
    if HAS_DO {
        color += select(albedo.rgb * directional.rgb, directional.rgb, CLASSIC);
    }
    if LIGHT_LOOP {
        let normal = textureLoad(g_normal, pixel, 0);
        let p = view_position(in.position.xy, depth);
        let direct = point_lighting(p, normal.xyz, albedo.rgb, albedo.a, normal.w);
        color += direct.diffuse + direct.specular;
    }
    return vec4<f32>(color, 1.0);
}
