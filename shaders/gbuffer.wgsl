// G-buffer pass: rasterises the model once and stores what every mode shares.
//   albedo target (Rgba8UnormSrgb): rgb diffuse albedo, a specular strength
//   normal target (R32Uint):        view-space unit shading normal (the normal map's, where the
//                                   material has one) and Blinn-Phong shininess, packed
//                                   (common/surface_pack.wgsl)
//   depth (Depth32Float, reverse-Z): position is reconstructed from it, not stored.
// Faces are two-sided: the normal that reaches the G-buffer is turned to the side of the surface
// the camera sees, so single-sided walls and leaves seen from behind are lit from the visible
// side. Every model's triangles are wound to agree with their vertex normals (a mesh wound
// against them is turned when it is built: `Model::from_groups`), so the rasteriser's facing says
// which side that is: a back face's normal is flipped. A normal-mapped surface turns its whole
// tangent frame with it. A material that reads maps draws the faces seen from the front first and
// those seen from behind in a second round (`Sides` in src/render/passes/gbuffer.rs), so a closed
// surface's far side is rejected by the depth test before it is shaded.
// (Taking the side from the plane of the view-space position's derivatives
// instead, which needs no rule on the winding, cost the pass about 5% on a CPU rasteriser, for
// three more varyings and their derivatives: docs/performance.md.)
// In a scene with a thin material (src/scene/thickness.rs) a plan whose march reads thickness
// draws with `fs_thickness`, which also writes the thickness layer (R32Uint): the fragment's
// depth bits with the material's thickness class and the surface's tilt in the low 8
// (common/thickness.wgsl). The march reads it in place of the depth, so a sample's depth and how
// deep it spans come in one load.
// Cut-out materials discard the texels whose coverage is below their cutoff: this pass is the
// only one that writes depth (the depth pyramid is built from its depth), so every screen-space
// pass sees the holes.

#include "common/uniforms.wgsl"
#include "common/surface_pack.wgsl"
#include "common/thickness.wgsl"
#include "common/unproject.wgsl"

// Mirrors `MaterialParams` in src/render/uniforms.rs.
struct MaterialParams {
    // diffuse albedo (linear)
    albedo: vec3<f32>,
    // specular strength
    specular: f32,
    // Blinn-Phong exponent, as the G-buffer's bits 24-31 hold it (common/surface_pack.wgsl)
    shininess_bits: u32,
    // multiplies the normal map's x and y
    normal_scale: f32,
    // coverage below this is a hole
    alpha_cutoff: f32,
    // multiplies the mask's coverage
    alpha_factor: f32,
    // the material's thickness class (src/scene/thickness.rs; 7 the scene's default)
    thickness_code: u32,
}

@group(1) @binding(0) var<uniform> material: MaterialParams;
@group(1) @binding(1) var diffuse_map: texture_2d<f32>;
@group(1) @binding(2) var specular_map: texture_2d<f32>;
@group(1) @binding(3) var material_sampler: sampler;
// Tangent-space normals, linear (x along u, y up the image, z out).
@group(1) @binding(4) var normal_map: texture_2d<f32>;
// Coverage in alpha (sRGB view: alpha is linear; often the colour map itself).
@group(1) @binding(5) var coverage_map: texture_2d<f32>;

// Each is false where a material does not need it: its pipeline never touches that map, and an
// opaque untextured material draws with none of them (no texture read, no discard).
override TEXTURED: bool = false;
// Where the specular strength's map is: 0 none, 1 its own texture, 2 the diffuse map's alpha
// (packed at upload where the two maps are one size: one sample for both).
override SPECULAR_MAP: u32 = 0u;
override NORMAL_MAPPED: bool = false;
override CUT_OUT: bool = false;
// The material is thinner than the scene's default (fs_thickness writes its tilt).
override THIN: bool = false;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) uv: vec2<f32>,
    // View-space tangent and bitangent sign (0 where there is none); vs_main leaves it 0.
    @location(2) tangent: vec4<f32>,
}

fn transform(v: VertexIn) -> VertexOut {
    let view = frame.world_to_view * vec4<f32>(v.position, 1.0);
    var out: VertexOut;
    out.clip = frame.view_to_clip * view;
    out.normal = (frame.world_to_view * vec4<f32>(v.normal, 0.0)).xyz;
    out.uv = v.uv;
    out.tangent = vec4<f32>(0.0);
    return out;
}

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    return transform(v);
}

// The vertex stage of normal-mapped materials: the tangents come in a second buffer, which only
// a model with normal maps has.
@vertex
fn vs_mapped(v: VertexIn, @location(3) tangent: vec4<f32>) -> VertexOut {
    var out = transform(v);
    out.tangent = vec4<f32>((frame.world_to_view * vec4<f32>(tangent.xyz, 0.0)).xyz, tangent.w);
    return out;
}

// The normal map's normal at `uv` in the frame of the unit vertex normal `n` and the
// interpolated tangent `t` (w the bitangent's sign); `n` itself where there is no frame.
fn mapped_normal(n: vec3<f32>, t: vec4<f32>, uv: vec2<f32>) -> vec3<f32> {
    // Gram-Schmidt: the interpolated tangent is no longer quite perpendicular to the normal.
    let tangent = t.xyz - n * dot(n, t.xyz);
    if t.w == 0.0 || dot(tangent, tangent) < 1e-12 {
        return n;
    }
    let tu = normalize(tangent);
    let bv = cross(n, tu) * sign(t.w);
    var m = textureSample(normal_map, material_sampler, uv).xyz * 2.0 - 1.0;
    m = vec3<f32>(m.xy * material.normal_scale, max(m.z, 0.0));
    return safe_normalize(tu * m.x + bv * m.y + n * m.z, n);
}

struct GBufferOut {
    @location(0) albedo: vec4<f32>,
    @location(1) normal: u32,
}

// The G-buffer of the fragment `in` (seen from the front where `front`).
fn surface(in: VertexOut, front: bool) -> GBufferOut {
    // Every implicit-derivative sample first, in uniform control flow.
    var albedo = material.albedo;
    var specular = material.specular;
    if TEXTURED {
        // Trilinear: the maps carry mip chains (src/render/passes/gbuffer.rs, `mip_chain`).
        let colour = textureSample(diffuse_map, material_sampler, in.uv);
        albedo *= colour.rgb;
        if SPECULAR_MAP == 2u {
            specular *= colour.a;
        } else if SPECULAR_MAP == 1u {
            specular *= textureSample(specular_map, material_sampler, in.uv).r;
        }
    }
    let vertex_normal = safe_normalize(in.normal, vec3<f32>(0.0, 0.0, 1.0));
    var n = vertex_normal;
    if NORMAL_MAPPED {
        n = mapped_normal(vertex_normal, in.tangent, in.uv);
    }
    if CUT_OUT {
        let coverage = textureSample(coverage_map, material_sampler, in.uv).a * material.alpha_factor;
        if coverage < material.alpha_cutoff {
            discard;
        }
    }
    // A back face shows the surface's other side: the normal, mapped or not, turns with it.
    n *= select(-1.0, 1.0, front);
    var out: GBufferOut;
    out.albedo = vec4<f32>(albedo, specular);
    out.normal = pack_normal(n) | material.shininess_bits;
    return out;
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> GBufferOut {
    return surface(in, front);
}

struct ThicknessOut {
    @location(0) albedo: vec4<f32>,
    @location(1) normal: u32,
    @location(2) depth_and_code: u32,
}

// The G-buffer and the thickness layer: the depth's bits with the material's thickness class and
// the surface's tilt from the view ray in the low 8 (common/thickness.wgsl). The tilt is the
// vertex normal's, the surface's own, not a normal map's.
@fragment
fn fs_thickness(in: VertexOut, @builtin(front_facing) front: bool) -> ThicknessOut {
    let g = surface(in, front);
    // (A material of the default thickness has no tilt to compute: its pipeline's THIN is off.)
    var code = DEFAULT_THICKNESS_CLASS;
    if THIN {
        let to_eye = safe_normalize(-view_position(in.clip.xy, in.clip.z), vec3<f32>(0.0, 0.0, 1.0));
        let n = safe_normalize(in.normal, to_eye);
        code = thickness_code_of(material.thickness_code, abs(dot(n, to_eye)));
    }
    let depth = (bitcast<u32>(in.clip.z) & ~THICKNESS_CODE_MASK) | code;
    return ThicknessOut(g.albedo, g.normal, depth);
}

// The far side layer (drawn by src/render/passes/far_side.rs with the faces towards the camera
// culled, so each pixel holds the nearest surface turned away from the eye: a closed fin's or
// box's far face, an underside, the other side of a sheet seen from behind): its normal as the
// mesh has it (away from the eye) with its shininess bits, its albedo, and its depth's bits. The
// lighting pass lights it as a sender (lighting.wgsl, `far_sender`).
@fragment
fn fs_far_side(in: VertexOut) -> @location(0) vec4<u32> {
    let g = surface(in, true);
    return vec4<u32>(g.normal, pack4x8unorm(vec4<f32>(g.albedo.rgb, 0.0)), bitcast<u32>(in.clip.z), 0u);
}
