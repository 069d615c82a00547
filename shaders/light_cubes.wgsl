// The point lights drawn as small emissive cubes in their own colours, one instance per light,
// depth-tested against the G-buffer depth (reverse-Z: nearer is greater).

#include "common/uniforms.wgsl"

// Cube radiance relative to the light's colour: bright enough to read as a light source.
const CUBE_EMISSION: f32 = 1.5;

struct CubeOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) color: vec3<f32>,
}

@vertex
fn vs_main(@location(0) corner: vec3<f32>, @builtin(instance_index) index: u32) -> CubeOut {
    let light = lights[index];
    let world = light.world_position.xyz + corner * light.color.w;
    var out: CubeOut;
    out.clip = frame.view_to_clip * (frame.world_to_view * vec4<f32>(world, 1.0));
    out.color = light.color.rgb * (CUBE_EMISSION * frame.sky.z);
    return out;
}

@fragment
fn fs_main(in: CubeOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.color, 1.0);
}
