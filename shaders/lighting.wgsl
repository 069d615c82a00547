// Lighting pass (SSDO modes with light to bounce): each surface's direct light once per pixel.
//   bounce: the diffuse radiance a surface sends to its neighbours in SSDO's one bounce — its
//           direct light times albedo/π: the point lights and, by SENDER_SKY, the sky and the
//           constant ambient A it receives:
//             1 (irradiance): the sky's unoccluded E(n)/π for its normal, plus A;
//             2 (march):      the sky it sees through the open sectors of its own march and A
//                             times their share (the sender-sky pass, half resolution);
//             3 (march-quarter): the same from the sender-sky pass at quarter resolution;
//   hdr:    (fs_main, with point lights) the point lights' light as displayed (diffuse +
//           specular), which the composite adds to.

#include "common/uniforms.wgsl"
#include "common/gbuffer_read.wgsl"
#include "common/point_lights.wgsl"
#include "common/sky_irradiance.wgsl"
#include "common/fullscreen.wgsl"

// rgb: visible sky light (E/π, pre-exposed), a: open share, at half (SENDER_SKY 2) or quarter
// (3) resolution.
@group(1) @binding(3) var sender_sky: texture_2d<f32>;

// What lights the senders besides the point lights: 0 nothing, 1 irradiance, 2 march, 3 march at
// quarter resolution.
override SENDER_SKY: u32 = 2u;
// There are point lights to evaluate (fs_main); fs_bounce is the entry point without them.
override LIGHTS: bool = true;

struct LightingOut {
    @location(0) hdr: vec4<f32>,
    // pack_sender (common/surface_pack.wgsl): the bounce radiance and the sender's normal.
    @location(1) bounce: vec4<u32>,
}

fn direct(pixel: vec2<i32>, position: vec2<f32>) -> LightingOut {
    var out: LightingOut;
    let depth = load_depth(pixel);
    if depth <= 0.0 {
        return out;
    }
    let albedo = textureLoad(g_albedo, pixel, 0);
    let normal_bits = textureLoad(g_normal, pixel, 0).r;
    let normal = surface_of(normal_bits);
    var bounce = vec3<f32>(0.0);
    if LIGHTS {
        let p = view_position(position, depth);
        let light = point_lighting(p, normal.xyz, albedo.rgb, albedo.a, normal.w);
        out.hdr = vec4<f32>(light.diffuse + light.specular, 1.0);
        bounce = light.diffuse;
    }
    let ambient = frame.pre_exposure * frame.ambient;
    if SENDER_SKY == 1u {
        bounce += albedo.rgb * (sky_irradiance(normal.xyz) + ambient);
    } else if SENDER_SKY >= 2u {
        let last = vec2<i32>(textureDimensions(sender_sky)) - vec2<i32>(1);
        let shift = vec2<u32>(select(1u, 2u, SENDER_SKY == 3u));
        let seen = textureLoad(sender_sky, min(pixel >> shift, last), 0);
        bounce += albedo.rgb * (seen.rgb + ambient * seen.a);
    }
    out.bounce = vec4<u32>(pack_sender(bounce, normal_bits), 0u, 0u);
    return out;
}

@fragment
fn fs_main(in: FullscreenOut) -> LightingOut {
    return direct(vec2<i32>(in.position.xy), in.position.xy);
}

// No point lights: the bounce alone (no HDR target is written).
@fragment
fn fs_bounce(in: FullscreenOut) -> @location(0) vec4<u32> {
    return direct(vec2<i32>(in.position.xy), in.position.xy).bounce;
}
