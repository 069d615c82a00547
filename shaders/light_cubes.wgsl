// The point lights drawn as small emissive cubes in their own colours, one instance per light,
// depth-tested against the G-buffer depth (reverse-Z: nearer is greater): by the depth attachment
// when they are drawn into HDR, by `fs_display` itself when they are drawn straight into the
// output (which may be larger than the G-buffer, so the depth buffer cannot be attached).

#include "common/uniforms.wgsl"
#include "common/tone_curve.wgsl"

// The G-buffer depth (fs_display only).
@group(1) @binding(0) var g_depth: texture_2d<f32>;
// True when the output format does the sRGB encoding itself (fs_display only).
override OUTPUT_SRGB: bool = true;

// Cube radiance relative to the light's colour: bright enough to read as a light source.
const CUBE_EMISSION: f32 = 1.5;

struct CubeOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) color: vec3<f32>,
}

@vertex
fn vs_main(@location(0) corner: vec3<f32>, @location(1) index: u32) -> CubeOut {
    let light = lights[index];
    let world = light.world_position + corner * light.cube_half_size;
    var out: CubeOut;
    out.clip = frame.view_to_clip * (frame.world_to_view * vec4<f32>(world, 1.0));
    out.color = light.color * (CUBE_EMISSION * frame.pre_exposure);
    return out;
}

@fragment
fn fs_main(in: CubeOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.color, 1.0);
}

// Straight into the output: the depth test against the G-buffer, then the tone map. There is no
// depth buffer between cubes here: they are drawn farthest first (the instance order), so a nearer
// cube covers a farther one.
@fragment
fn fs_display(in: CubeOut) -> @location(0) vec4<f32> {
    let pixel = vec2<i32>(in.clip.xy - frame.output_origin);
    if in.clip.z < textureLoad(g_depth, pixel, 0).r {
        discard;
    }
    var color = tone_map(in.color * frame.display_scale);
    if !OUTPUT_SRGB {
        color = linear_to_srgb(color);
    }
    return vec4<f32>(color, 1.0);
}
