// G-buffer pass: rasterises the model once and stores what every mode shares.
//   albedo target (Rgba8UnormSrgb): rgb diffuse albedo, a specular strength
//   normal target (Rgba16Float):    xyz view-space unit normal, w Blinn-Phong shininess
//   depth (Depth32Float, reverse-Z): position is reconstructed from it, not stored.
// Faces are two-sided: a back face gets the flipped normal, so single-sided walls in real OBJ
// files are lit from the side the camera sees.

#include "common/uniforms.wgsl"

struct MaterialParams {
    // rgb diffuse albedo, a specular strength
    diffuse: vec4<f32>,
    // shininess, unused x3
    params: vec4<f32>,
}

@group(1) @binding(0) var<uniform> material: MaterialParams;
@group(1) @binding(1) var diffuse_map: texture_2d<f32>;
@group(1) @binding(2) var specular_map: texture_2d<f32>;
@group(1) @binding(3) var material_sampler: sampler;

// False for untextured materials: their pipeline never touches the maps.
override TEXTURED: bool = false;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) uv: vec2<f32>,
}

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    let view = frame.world_to_view * vec4<f32>(v.position, 1.0);
    var out: VertexOut;
    out.clip = frame.view_to_clip * view;
    out.normal = (frame.world_to_view * vec4<f32>(v.normal, 0.0)).xyz;
    out.uv = v.uv;
    return out;
}

struct GBufferOut {
    @location(0) albedo: vec4<f32>,
    @location(1) normal: vec4<f32>,
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> GBufferOut {
    var albedo = material.diffuse.rgb;
    var specular = material.diffuse.a;
    if TEXTURED {
        albedo *= textureSampleLevel(diffuse_map, material_sampler, in.uv, 0.0).rgb;
        specular *= textureSampleLevel(specular_map, material_sampler, in.uv, 0.0).r;
    }
    var n = safe_normalize(in.normal, vec3<f32>(0.0, 0.0, 1.0));
    if !front {
        n = -n;
    }
    var out: GBufferOut;
    out.albedo = vec4<f32>(albedo, specular);
    out.normal = vec4<f32>(n, material.params.x);
    return out;
}
