// The full-screen triangle's vertex stage for the passes that light every pixel (the composite and
// the lighting pass): it reads the frame's constants those pixels use once and hands them down as
// flat varyings, so the fragment stage reads no frame uniform for them.
//
// Why: on a CPU rasteriser (lavapipe, llvmpipe) every read of a uniform is a bounds-checked load
// of each scalar, repeated for every eight pixels; a flat varying is set up once for the
// triangle. The 27 weights of the sky's irradiance alone were a quarter of the composite (3.5 of
// 14 ms at 800x600); with these constants handed down the Off composite takes 0.71 of its time
// (docs/performance.md). A GPU reads either from a constant cache.

#include "common/uniforms.wgsl"
#include "common/fullscreen_triangle.wgsl"

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
    // frame.ao_strength, frame.ao_power
    @location(4) @interpolate(flat) ao: vec2<f32>,
    // What the point lights need besides their own entries: frame.pre_exposure,
    // frame.min_light_distance2
    @location(14) @interpolate(flat) lights: vec2<f32>,
    // frame.sky_irradiance's nine rgb weights (see `sky_irradiance`).
    @location(5) @interpolate(flat) sky0: vec3<f32>,
    @location(6) @interpolate(flat) sky1: vec3<f32>,
    @location(7) @interpolate(flat) sky2: vec3<f32>,
    @location(8) @interpolate(flat) sky3: vec3<f32>,
    @location(9) @interpolate(flat) sky4: vec3<f32>,
    @location(10) @interpolate(flat) sky5: vec3<f32>,
    @location(11) @interpolate(flat) sky6: vec3<f32>,
    @location(12) @interpolate(flat) sky7: vec3<f32>,
    @location(13) @interpolate(flat) sky8: vec3<f32>,
}

@vertex
fn fullscreen_vs(@builtin(vertex_index) index: u32) -> FrameVaryings {
    var out: FrameVaryings;
    out.position = fullscreen_clip(fullscreen_uv(index));
    out.viewport = frame.viewport;
    out.projection = projection_terms();
    out.output = vec4<f32>(frame.output_origin, frame.display_scale, 0.0);
    out.ambient = vec4<f32>(frame.pre_exposure * frame.ambient, 0.0);
    out.ao = vec2<f32>(frame.ao_strength, frame.ao_power);
    out.lights = vec2<f32>(frame.pre_exposure, frame.min_light_distance2);
    let q = frame.sky_irradiance;
    out.sky0 = q[0].rgb;
    out.sky1 = q[1].rgb;
    out.sky2 = q[2].rgb;
    out.sky3 = q[3].rgb;
    out.sky4 = q[4].rgb;
    out.sky5 = q[5].rgb;
    out.sky6 = q[6].rgb;
    out.sky7 = q[7].rgb;
    out.sky8 = q[8].rgb;
    return out;
}

// The view-space position of the surface at `pixel` with depth `depth` (> 0), as
// `view_position` (common/gbuffer_read.wgsl) finds it, from the handed-down constants.
fn view_position_of(c: FrameVaryings, pixel: vec2<f32>, depth: f32) -> vec3<f32> {
    return unproject(pixel, depth, c.projection, c.viewport.zw);
}

// The sky's unoccluded irradiance E(n)/π for view-space unit normal `n` (pre-exposed): the
// composite's sky light in Off and SSAO, and the sky light the lighting pass gives the bounce's
// senders. The three SH bands are a quadratic polynomial of the direction; the CPU turns them
// into view space each frame (`irradiance_quadratic` in src/scene/skybox.rs), so a pixel pays nine
// multiply-adds and no transform of its normal. Three bands can ring below 0 opposite a bright
// sun: clamped.
fn sky_irradiance(c: FrameVaryings, n: vec3<f32>) -> vec3<f32> {
    let e = c.sky0 * (n.x * n.x) + c.sky1 * (n.y * n.y) + c.sky2 * (n.x * n.y) + c.sky3 * (n.x * n.z)
        + c.sky4 * (n.y * n.z) + c.sky5 * n.x + c.sky6 * n.y + c.sky7 * n.z + c.sky8;
    return max(e, vec3<f32>(0.0));
}
