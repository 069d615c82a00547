// G-buffer pass: rasterises the model once and stores what every mode shares.
//   albedo target (Rgba8UnormSrgb): rgb diffuse albedo, a specular strength
//   normal target (R32Uint):        view-space unit normal and Blinn-Phong shininess, packed
//                                   (common/surface_pack.wgsl)
//   depth (Depth32Float, reverse-Z): position is reconstructed from it, not stored.
// Faces are two-sided: the normal that reaches the G-buffer is turned to the side of the surface
// the camera sees, whatever the triangle's winding (see `camera_side`), so single-sided walls,
// leaves seen from behind and meshes wound against their normals are lit from the visible side.

#include "common/uniforms.wgsl"
#include "common/surface_pack.wgsl"

// Mirrors `MaterialParams` in src/render/uniforms.rs.
struct MaterialParams {
    // diffuse albedo (linear)
    albedo: vec3<f32>,
    // specular strength
    specular: f32,
    // Blinn-Phong exponent
    shininess: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
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
    @location(2) view_position: vec3<f32>,
}

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    let view = frame.world_to_view * vec4<f32>(v.position, 1.0);
    var out: VertexOut;
    out.clip = frame.view_to_clip * view;
    out.normal = (frame.world_to_view * vec4<f32>(v.normal, 0.0)).xyz;
    out.uv = v.uv;
    out.view_position = view.xyz;
    return out;
}

// Turns the shading normal `n` to the camera's side of the triangle at view-space position `p`.
// The triangle's plane comes from the screen-space derivatives of `p` (exact for a flat triangle,
// independent of its winding), oriented towards the camera; `n` is flipped when it lies on the
// other side of that plane. At a silhouette a smooth normal may point slightly away from the
// camera while still on the visible side: it is kept. Only a degenerate plane (no derivatives)
// falls back to the rasteriser's facing.
fn camera_side(n: vec3<f32>, p: vec3<f32>, plane: vec3<f32>, front: bool) -> vec3<f32> {
    var facing = select(-1.0, 1.0, front);
    let towards_camera = dot(plane, -p);
    if towards_camera != 0.0 && dot(plane, plane) > 0.0 {
        // Signs apart: their product could underflow on a tiny model.
        facing = sign(dot(n, plane)) * sign(towards_camera);
    }
    return select(n, -n, facing < 0.0);
}

struct GBufferOut {
    @location(0) albedo: vec4<f32>,
    @location(1) normal: u32,
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> GBufferOut {
    // Derivatives first, in uniform control flow.
    let plane = cross(dpdx(in.view_position), dpdy(in.view_position));
    var albedo = material.albedo;
    var specular = material.specular;
    if TEXTURED {
        // Trilinear: the maps carry mip chains (src/render/passes/gbuffer.rs, `mip_chain`).
        albedo *= textureSample(diffuse_map, material_sampler, in.uv).rgb;
        specular *= textureSample(specular_map, material_sampler, in.uv).r;
    }
    let n = camera_side(safe_normalize(in.normal, vec3<f32>(0.0, 0.0, 1.0)), in.view_position, plane, front);
    var out: GBufferOut;
    out.albedo = vec4<f32>(albedo, specular);
    out.normal = pack_surface(n, material.shininess);
    return out;
}
