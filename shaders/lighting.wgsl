// Lighting pass (SSDO modes with light to bounce): each surface's direct light once per pixel.
//   bounce: the diffuse radiance a surface sends to its neighbours in SSDO's one bounce — its
//           direct light times albedo/π: the point lights and, by SENDER_SKY, the sky and the
//           constant ambient A it receives:
//             1 (irradiance): the sky's unoccluded E(n)/π for its normal, plus A;
//             2 (march):      the sky it sees through the open sectors of its own march and A
//                             times their share (the sender-sky pass, half resolution);
//             3 (march-quarter): the same from the sender-sky pass at quarter resolution;
//             4 (last-frame): the same from the last frame's sampling pass (its march writes
//                             the sky each pixel sees), where the surface was then;
//   hdr:    (fs_main, with point lights) the point lights' light as displayed (diffuse +
//           specular), which the composite adds to.

#include "common/uniforms.wgsl"
#include "common/gbuffer_read.wgsl"
#include "common/point_lights.wgsl"
#include "common/frame_varyings.wgsl"

// rgb: visible sky light (E/π, pre-exposed), a: open share, at half (SENDER_SKY 2) or quarter
// (3) resolution.
@group(1) @binding(3) var sender_sky: texture_2d<f32>;
// The same as the last frame's sampling pass saw it (SENDER_SKY 4), at that pass's size.
@group(1) @binding(4) var last_sky: texture_2d<f32>;
// The far side layer (FAR_SIDE; gbuffer.wgsl `fs_far_side`): the nearest surface behind each
// pixel turned from the eye, its packed normal, albedo and depth bits; a 1x1 stand-in otherwise.
@group(1) @binding(5) var far_surface: texture_2d<u32>;

// What lights the senders besides the point lights: 0 nothing, 1 irradiance, 2 march, 3 march at
// quarter resolution, 4 the last frame's march.
override SENDER_SKY: u32 = 2u;
// SENDER_SKY 4: the last frame's sampling pass ran where the samples are, so its sky is half
// size in a half-resolution plan.
#include "common/sample_grid.wgsl"
// SENDER_SKY 4: the camera moved since the last frame, so a surface is looked for where the last
// camera saw it. Without it each pixel reads its own texel.
override REPROJECT: bool = false;
// There are point lights to evaluate (fs_main); fs_bounce is the entry point without them.
override LIGHTS: bool = true;
// A material has a normal map: the sender's normal the bounce's facing test reads is its
// surface's own, from the depth buffer (`depth_normal`), not the map's, which leans away where
// the surface faces the receiver. The light it sends keeps the mapped normal's.
override NORMAL_MAPPED: bool = false;
// The far side layer's surface is lit too (with the point lights: it is drawn only where there
// are some), into the bounce's second pair.
override FAR_SIDE: bool = false;
// FAR_SIDE: the G-buffer's thickness layer, whose codes say which surfaces are sheets.
@group(1) @binding(6) var thickness_layer: texture_2d<u32>;
override THICKNESS_LAYER: bool = false;
// FAR_SKY: the sky the far side's surfaces see and their open share (far_sky.rs), at a quarter
// of the width and height.
@group(1) @binding(7) var far_sky: texture_2d<f32>;
override FAR_SKY: bool = false;
#include "common/thickness.wgsl"

struct LightingOut {
    @location(0) hdr: vec4<f32>,
    // pack_sender (common/surface_pack.wgsl): the bounce radiance and the sender's normal (xy),
    // and with FAR_SIDE the far side layer's sender (zw; zero where it holds none).
    @location(1) bounce: vec4<u32>,
}

// `c`: the frame's constants as the triangle handed them down.
fn direct(c: FrameVaryings, pixel: vec2<i32>, position: vec2<f32>) -> LightingOut {
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
        let p = view_position_of(c, position, depth);
        let light = point_lighting(c, p, normal.xyz, albedo.rgb, albedo.a, normal.w);
        out.hdr = vec4<f32>(light.diffuse + light.specular, 1.0);
        bounce = light.diffuse;
    }
    let ambient = c.ambient.rgb;
    if SENDER_SKY == 1u {
        bounce += albedo.rgb * (sky_irradiance(c, normal.xyz) + ambient);
    } else if SENDER_SKY == 4u {
        let seen = last_frame_sky(c, pixel, position, depth, normal.xyz);
        bounce += albedo.rgb * (seen.rgb + ambient * seen.a);
    } else if SENDER_SKY >= 2u {
        let last = vec2<i32>(textureDimensions(sender_sky)) - vec2<i32>(1);
        let shift = vec2<u32>(select(1u, 2u, SENDER_SKY == 3u));
        let seen = textureLoad(sender_sky, min(pixel >> shift, last), 0);
        bounce += albedo.rgb * (seen.rgb + ambient * seen.a);
    }
    var facing_bits = normal_bits;
    if NORMAL_MAPPED {
        let p = view_position_of(c, position, depth);
        facing_bits = pack_normal(depth_normal_in(pixel, p, normal.xyz, c.projection, c.viewport));
    }
    out.bounce = vec4<u32>(pack_sender(bounce, facing_bits), 0u, 0u);
    if FAR_SIDE {
        out.bounce = vec4<u32>(out.bounce.xy, far_sender(c, pixel, position));
    }
    return out;
}

// The far side layer's surface at `pixel` as a sender: the diffuse light the point lights give
// it and, with FAR_SKY, the sky and ambient its own march saw (the sky's unoccluded irradiance
// overstates it: an underside facing the floor took the ground's half of the sky, cornell's SSDO
// error 0.0197 → 0.0264; docs/accuracy.md), and its normal (away from the eye).
fn far_sender(c: FrameVaryings, pixel: vec2<i32>, position: vec2<f32>) -> vec2<u32> {
    let far = textureLoad(far_surface, pixel, 0);
    if far.z == 0u {
        return vec2<u32>(0u);
    }
    let p = view_position_of(c, position, bitcast<f32>(far.z));
    let albedo = unpack4x8unorm(far.y).rgb;
    var light = vec3<f32>(0.0);
    if LIGHTS {
        light = point_lighting(c, p, unpack_normal(far.x), albedo, 0.0, 1.0).diffuse;
    }
    if FAR_SKY {
        let last = vec2<i32>(textureDimensions(far_sky)) - vec2<i32>(1);
        let seen = textureLoad(far_sky, min(pixel >> vec2<u32>(2u), last), 0);
        light += albedo * (seen.rgb + c.ambient.rgb * seen.a);
    }
    return pack_sender(light, far.x);
}

// The sky the surface at `pixel` saw in the last frame's march (rgb, with its open share in a):
// the texel of the last frame's samples that held the pixel the surface was at, through the
// last camera where this one moved. Where the last frame did not see it (off screen, or behind
// the camera), its unoccluded irradiance, all open. (A surface the last frame saw behind
// another takes that one's sky for a frame: the march's next frame has its own.)
fn last_frame_sky(c: FrameVaryings, pixel: vec2<i32>, position: vec2<f32>, depth: f32, n: vec3<f32>) -> vec4<f32> {
    var was = pixel;
    if REPROJECT {
        // This point in the last frame's view, and through its projection (one transform and
        // four floats a pixel, not two transforms).
        let then = (frame.view_to_previous_view * vec4<f32>(view_position_of(c, position, depth), 1.0)).xyz;
        let w = max(-then.z, 1e-30);
        let ndc = then.xy / (frame.previous_projection.xy * w);
        let at = vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - 0.5 * ndc.y) * c.viewport.xy;
        if then.z >= 0.0 || any(at < vec2<f32>(0.0)) || any(at >= c.viewport.xy) {
            return vec4<f32>(sky_irradiance(c, n), 1.0);
        }
        was = vec2<i32>(at);
    }
    let last = vec2<i32>(textureDimensions(last_sky)) - vec2<i32>(1);
    let texel = sample_texel(was);
    return textureLoad(last_sky, min(texel, last), 0);
}

// FAR_SIDE: the depth at `pixel` with the extent of its surface for the march (EXTENT_CODE_MASK in
// common/thickness.wgsl): where the far side layer holds a face behind a surface that is no sheet,
// the distance to it along the view ray (a closed solid's own thickness there); elsewhere the
// thickness layer's code, or the scene's default slab.
fn extent_layer(c: FrameVaryings, pixel: vec2<i32>, position: vec2<f32>) -> u32 {
    let depth = load_depth(pixel);
    var code = DEFAULT_THICKNESS_CLASS;
    if THICKNESS_LAYER {
        code = textureLoad(thickness_layer, pixel, 0).r & THICKNESS_CODE_MASK;
    }
    let far = textureLoad(far_surface, pixel, 0).z;
    let sheet = (code & 7u) == 0u;
    if far != 0u && bitcast<f32>(far) < depth && !sheet {
        let near = length(view_position_of(c, position, depth));
        code = extent_code(length(view_position_of(c, position, bitcast<f32>(far))) - near, near);
    }
    return (bitcast<u32>(depth) & ~EXTENT_CODE_MASK) | code;
}

struct LightingFarOut {
    @location(0) hdr: vec4<f32>,
    @location(1) bounce: vec4<u32>,
    @location(2) extent: u32,
}

struct BounceFarOut {
    @location(0) bounce: vec4<u32>,
    @location(1) extent: u32,
}

// FAR_SIDE: fs_main and fs_bounce with the depth and extents the march reads.
@fragment
fn fs_main_far(in: FrameVaryings) -> LightingFarOut {
    let pixel = vec2<i32>(in.position.xy);
    let lit = direct(in, pixel, in.position.xy);
    return LightingFarOut(lit.hdr, lit.bounce, extent_layer(in, pixel, in.position.xy));
}

@fragment
fn fs_bounce_far(in: FrameVaryings) -> BounceFarOut {
    let pixel = vec2<i32>(in.position.xy);
    return BounceFarOut(direct(in, pixel, in.position.xy).bounce, extent_layer(in, pixel, in.position.xy));
}

@fragment
fn fs_main(in: FrameVaryings) -> LightingOut {
    return direct(in, vec2<i32>(in.position.xy), in.position.xy);
}

// No point lights: the bounce alone (no HDR target is written).
@fragment
fn fs_bounce(in: FrameVaryings) -> @location(0) vec4<u32> {
    return direct(in, vec2<i32>(in.position.xy), in.position.xy).bounce;
}
