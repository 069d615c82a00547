// Lighting pass (SSDO modes with point lights only): evaluates the point lights once per pixel
// and writes two things:
//   hdr:    direct lighting as displayed (diffuse + specular), the composite adds to it;
//   bounce: diffuse outgoing radiance (albedo/π · irradiance), what a surface sends to its
//           neighbours in SSDO's one-bounce indirect light.

#include "common/uniforms.wgsl"
#include "common/gbuffer_read.wgsl"
#include "common/point_lights.wgsl"
#include "common/fullscreen.wgsl"

struct LightingOut {
    @location(0) hdr: vec4<f32>,
    @location(1) bounce: vec4<f32>,
}

@fragment
fn fs_main(in: FullscreenOut) -> LightingOut {
    var out: LightingOut;
    let pixel = vec2<i32>(in.position.xy);
    let depth = load_depth(pixel);
    if depth <= 0.0 {
        return out;
    }
    let albedo = textureLoad(g_albedo, pixel, 0);
    let normal = load_surface(pixel);
    let p = view_position(in.position.xy, depth);
    let light = point_lighting(p, normal.xyz, albedo.rgb, albedo.a, normal.w);
    out.hdr = vec4<f32>(light.diffuse + light.specular, 1.0);
    out.bounce = vec4<f32>(light.diffuse, 1.0);
    return out;
}
