// The full-screen triangle's vertex stage for the passes that light every pixel (the composite and
// the lighting pass): it reads the frame's constants those pixels use once and hands them down as
// flat varyings, so the fragment stage reads no frame uniform for them.
//
// Why: on a CPU rasteriser (lavapipe, llvmpipe) every read of a uniform is a bounds-checked load
// of each scalar, repeated for every eight pixels; a flat varying is set up once for the
// triangle. The 27 weights of the sky's irradiance alone were a quarter of the composite (3.5 of
// 14 ms at 800x600); with these constants handed down the Off composite takes 0.71 of its time
// (docs/performance.md). A GPU reads either from a constant cache. The first light comes down
// too, for a loop built for one light (common/point_lights.wgsl): 14 of the 15 varyings
// WebGPU's downlevel limits allow, the sky's weights packed four to a varying to make room.

#include "common/uniforms.wgsl"
#include "common/fullscreen_triangle.wgsl"
#include "common/sky_quadratic.wgsl"

struct FrameVaryings {
    @builtin(position) position: vec4<f32>,
    // frame.viewport: width, height, 1/width, 1/height
    @location(0) @interpolate(flat) viewport: vec4<f32>,
    // What `unproject` needs of view_to_clip: [2][2], [3][2], [0][0], [1][1].
    @location(1) @interpolate(flat) projection: vec4<f32>,
    // frame.output_origin (xy), frame.display_scale (z), 0
    @location(2) @interpolate(flat) output: vec4<f32>,
    // The constant ambient, pre-exposed (rgb); 0
    @location(3) @interpolate(flat) ambient: vec4<f32>,
    // frame.ao_strength, frame.ao_power; what the point lights need besides their own entries:
    // frame.pre_exposure, frame.min_light_distance2
    @location(4) @interpolate(flat) shading: vec4<f32>,
    // frame.sky_irradiance's nine rgb weights as `SkyQuadratic` packs them (red: sky_r0,
    // sky_r1; the constant term: sky_k).
    @location(5) @interpolate(flat) sky_r0: vec4<f32>,
    @location(6) @interpolate(flat) sky_r1: vec4<f32>,
    @location(7) @interpolate(flat) sky_g0: vec4<f32>,
    @location(8) @interpolate(flat) sky_g1: vec4<f32>,
    @location(9) @interpolate(flat) sky_b0: vec4<f32>,
    @location(10) @interpolate(flat) sky_b1: vec4<f32>,
    @location(11) @interpolate(flat) sky_k: vec4<f32>,
    // The first light (common/point_lights.wgsl reads it here where the pipeline is built for
    // one light): its view-space position (xyz), and its colour times its intensity and the
    // pre-exposure (rgb).
    @location(12) @interpolate(flat) light_position: vec4<f32>,
    @location(13) @interpolate(flat) light_power: vec4<f32>,
}

@vertex
fn fullscreen_vs(@builtin(vertex_index) index: u32) -> FrameVaryings {
    var out: FrameVaryings;
    out.position = fullscreen_clip(fullscreen_uv(index));
    out.viewport = frame.viewport;
    out.projection = projection_terms();
    out.output = vec4<f32>(frame.output_origin, frame.display_scale, 0.0);
    out.ambient = vec4<f32>(frame.pre_exposure * frame.ambient, 0.0);
    out.shading = vec4<f32>(frame.ao_strength, frame.ao_power, frame.pre_exposure, frame.min_light_distance2);
    let sky = frame_sky_quadratic();
    out.sky_r0 = sky.r0;
    out.sky_r1 = sky.r1;
    out.sky_g0 = sky.g0;
    out.sky_g1 = sky.g1;
    out.sky_b0 = sky.b0;
    out.sky_b1 = sky.b1;
    out.sky_k = sky.k;
    // (The uniforms' copy of the lights is zero past the scene's count.)
    let light = frame.first_lights[0];
    out.light_position = vec4<f32>(light.view_position, 0.0);
    out.light_power = vec4<f32>(light.color * (frame.pre_exposure * light.intensity), 0.0);
    return out;
}

// The view-space position of the surface at `pixel` with depth `depth` (> 0), as
// `view_position` (common/gbuffer_read.wgsl) finds it, from the handed-down constants.
fn view_position_of(c: FrameVaryings, pixel: vec2<f32>, depth: f32) -> vec3<f32> {
    return unproject(pixel, depth, c.projection, c.viewport.zw);
}

// The sky's weights as the triangle handed them down.
fn sky_quadratic(c: FrameVaryings) -> SkyQuadratic {
    return SkyQuadratic(c.sky_r0, c.sky_r1, c.sky_g0, c.sky_g1, c.sky_b0, c.sky_b1, c.sky_k);
}

// The sky's unoccluded irradiance E(n)/π for view-space unit normal `n` (pre-exposed,
// common/sky_quadratic.wgsl): the composite's sky light in Off and SSAO, and the sky light the
// lighting pass gives the bounce's senders. A pixel pays nine multiply-adds a colour and no
// transform of its normal.
fn sky_irradiance(c: FrameVaryings, n: vec3<f32>) -> vec3<f32> {
    return irradiance_at(sky_quadratic(c), n);
}
