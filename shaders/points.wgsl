// The sampling pass: SSAO, SSDO, or both from one set of samples.
//
// Every pixel takes N samples in the hemisphere above its surface (a kernel in tangent space,
// scaled towards the centre, rotated per pixel by one of 16 rotations tiled 4x4), projects each
// to the screen and compares it with the surface the depth buffer holds there.
//
//  * SSAO: a sample behind that surface, within range, is occluded. AO = 1 - occluded share.
//  * SSDO (Ritschel, Grosch & Seidel 2009): an unoccluded sample brings the sky's radiance from
//    its direction (the cube map read at the mip level of the sample's solid angle); an occluded
//    one brings one bounce from the surface in front of it, a small patch whose diffuse radiance
//    the lighting pass wrote.
//
// Default variant (normalised so that the white-furnace test holds exactly):
//   direct   = Σ v_i L_sky(ω_i) cosθ_i / Σ cosθ_i            (E/π of the visible sky)
//   indirect = 1/N Σ o_i L_s cosθ_r min(R² cosθ_s / d², 2)   (patch area πR²/N; each patch's
//              solid angle is capped at its share 2π/N, so d → 0 cannot blow it up)
//   AO       = 1 - Σ o_i cosθ_i / Σ cosθ_i                    (cosine-weighted, like the reference)
// Albedo is applied in the composite, so the blur never mixes textures. DO leaves this pass as one
// buffer, rgb = sky·strength + indirect·strength and a = AO, so SSDO and SSAO+SSDO write (and
// blur) exactly the same target; a debug view of one term sets the other's strength to 0.
//
// Classic variant (the classic SSAO chapter and the SSDO course project): random kernel and 4x4 random
// rotation vectors, occlusion += (behind ? 1 : 0)·rangeCheck, AO = 1 - occlusion/N;
// indirect += rangeCheck·max(dot(n_s, normalize(p - s)), 0)·albedo_s, sky += rangeCheck·sky·cosθ,
// both divided by N and added without the receiver's albedo.
//
// Samples that project off-screen or behind the camera are skipped: not counted in the default
// variant, counted as contributing nothing in the classic one (which divides by N regardless).

#include "common/uniforms.wgsl"
#include "common/gbuffer_read.wgsl"
#include "common/sampling_params.wgsl"
#include "common/fullscreen.wgsl"

// The sky's mip chain is read at one whole level per pass (the sampler's mip filter is nearest):
// the level already matches a sample's solid angle, and bilinear costs half of trilinear.
#include "common/occlusion_inputs.wgsl"

override CLASSIC: bool = false;

struct Occlusion {
    ao: f32,
    direct: vec3<f32>,
    indirect: vec3<f32>,
}

// An orthonormal basis around unit `n` without a singularity (Duff et al. 2017).
fn basis(n: vec3<f32>) -> mat3x3<f32> {
    let s = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    return mat3x3<f32>(vec3<f32>(1.0 + s * n.x * n.x * a, s * b, -s * n.x), vec3<f32>(b, s + n.y * n.y * a, -n.y), n);
}

// Tangent frame at `pixel`, rotated by the pixel's entry of the 4x4 rotation tile, turned by
// this frame's angle of the schedule.
fn tangent_frame(n: vec3<f32>, pixel: vec2<i32>) -> mat3x3<f32> {
    let tile = occ.rotations[u32(pixel.x & 3) + 4u * u32(pixel.y & 3)].xy;
    let turn = occ.schedule.zw;
    let r = vec2<f32>(tile.x * turn.x - tile.y * turn.y, tile.x * turn.y + tile.y * turn.x);
    let b = basis(n);
    if CLASSIC {
        // Gram-Schmidt of the tile's random view-space vector, as the source does.
        let v = vec3<f32>(r.xy, 0.0);
        let t = safe_normalize(v - n * dot(v, n), b[0]);
        return mat3x3<f32>(t, cross(n, t), n);
    }
    let t = b[0] * r.x + b[1] * r.y;
    return mat3x3<f32>(t, cross(n, t), n);
}

// What a pixel's samples sum: the occlusion and its weight, the sky and the bounce.
struct Sums {
    occluded: f32,
    weight: f32,
    direct: vec3<f32>,
    indirect: vec3<f32>,
}

// One sample about the receiver `p` (normal `n`): its point `q`, the surface `s` seen at its
// pixel `texel` (none where the sky is), its direction and cosine at the receiver, and the range
// check's weight.
struct Sample {
    q: vec3<f32>,
    s: vec3<f32>,
    texel: vec2<i32>,
    has_surface: bool,
    dir: vec3<f32>,
    cos_r: f32,
    range: f32,
}

// The classic chapter's estimator: a sample behind the depth buffer occludes (by the range
// check's weight); one in front sees the sky, one behind a surface takes its albedo's bounce.
fn add_classic(sums: ptr<function, Sums>, p: vec3<f32>, n: vec3<f32>, x: Sample) {
    let behind_ao = select(0.0, 1.0, x.has_surface && x.s.z >= x.q.z + occ.bias_length);
    (*sums).occluded += behind_ao * x.range;
    if !HAS_DO {
        return;
    }
    if x.has_surface && x.s.z >= x.q.z {
        if INDIRECT {
            let n_s = load_normal(x.texel);
            let albedo_s = textureLoad(g_albedo, x.texel, 0).rgb;
            (*sums).indirect += x.range * max(dot(n_s, safe_normalize(p - x.s, n)), 0.0) * albedo_s * frame.pre_exposure;
        }
    } else {
        let world = (frame.view_to_world * vec4<f32>(x.dir, 0.0)).xyz;
        (*sums).direct += x.range * textureSampleLevel(sky_map, sky_sampler, world, 0.0).rgb * x.cos_r;
    }
}

// The paper's estimator: cosine-weighted occlusion; the sky through what is not occluded; the
// bounce of an occluding sender as a small patch of the radius's area, facing the receiver.
fn add_paper(sums: ptr<function, Sums>, p: vec3<f32>, n: vec3<f32>, x: Sample) {
    let o = select(0.0, x.range, x.has_surface && x.s.z > x.q.z + occ.bias_length);
    (*sums).occluded += o * x.cos_r;
    (*sums).weight += x.cos_r;
    if !HAS_DO {
        return;
    }
    let world = (frame.view_to_world * vec4<f32>(x.dir, 0.0)).xyz;
    (*sums).direct += (1.0 - o) * x.cos_r * textureSampleLevel(sky_map, sky_sampler, world, occ.sky_mip).rgb;
    if INDIRECT && o > 0.0 {
        let n_s = load_normal(x.texel);
        let to_receiver = p - x.s;
        let d2 = max(dot(to_receiver, to_receiver), 1e-30);
        let w = to_receiver * inverseSqrt(d2);
        let cos_s = max(dot(n_s, w), 0.0);
        let cos_rs = max(dot(n, -w), 0.0);
        let solid = min(occ.radius * occ.radius * cos_s / d2, 2.0);
        (*sums).indirect += o * sender_radiance(textureLoad(bounce_map, x.texel, 0).xy) * cos_rs * solid;
    }
}

// The samples at pixel centre `position`, rotated by the tile entry of `tile` (the pass's own
// pixel: the same pixel at full resolution).
fn evaluate(position: vec2<f32>, tile: vec2<i32>) -> Occlusion {
    var out: Occlusion;
    out.ao = 1.0;
    let pixel = vec2<i32>(position);
    let depth = load_depth(pixel);
    if depth <= 0.0 {
        return out;
    }
    let n = load_normal(pixel);
    let p = view_position(position, depth);
    // With mapped normals, a sample below the surface's own plane is mirrored above it: the
    // plane itself never occludes (see NORMAL_MAPPED in common/sampling_params.wgsl).
    var n_g = n;
    if NORMAL_MAPPED {
        n_g = depth_normal(pixel, p, n);
    }
    let radius = occ.radius;
    let count = min(occ.sample_count, MAX_SAMPLES);
    let tbn = tangent_frame(n, tile);

    var sums: Sums;
    var valid = 0u;
    for (var i = 0u; i < count; i += 1u) {
        var offset = tbn * occ.kernel[i].xyz;
        if NORMAL_MAPPED {
            offset -= 2.0 * min(dot(offset, n_g), 0.0) * n_g;
        }
        var x: Sample;
        x.q = p + offset * radius;
        let clip = frame.view_to_clip * vec4<f32>(x.q, 1.0);
        if clip.w <= 0.0 {
            continue;
        }
        let ndc = clip.xy / clip.w;
        let texel_f = floor(vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * frame.viewport.xy);
        if any(texel_f < vec2<f32>(0.0)) || any(texel_f >= frame.viewport.xy) {
            continue;
        }
        x.texel = vec2<i32>(texel_f);
        valid += 1u;
        let sample_depth = load_depth(x.texel);
        x.has_surface = sample_depth > 0.0;
        x.s = view_position(texel_f + 0.5, max(sample_depth, 1e-30));
        x.dir = safe_normalize(offset, n);
        x.cos_r = max(dot(n, x.dir), 0.0);
        // Range check: a surface far in front of the receiver does not occlude it. The divisor
        // never reaches 0, also with a radius of 0 (where every sample is at the receiver).
        x.range = smoothstep(0.0, 1.0, radius / max(abs(p.z - x.s.z), max(radius * 1e-4, 1e-30)));
        if CLASSIC {
            add_classic(&sums, p, n, x);
        } else {
            add_paper(&sums, p, n, x);
        }
    }

    if CLASSIC {
        let inv_n = 1.0 / f32(max(count, 1u));
        out.ao = 1.0 - sums.occluded * inv_n;
        out.direct = sums.direct * inv_n * frame.sky_scale;
        out.indirect = sums.indirect * inv_n;
    } else if sums.weight > 0.0 {
        out.ao = 1.0 - sums.occluded / sums.weight;
        out.direct = sums.direct / sums.weight * frame.sky_scale;
        out.indirect = sums.indirect / f32(valid);
    }
    return out;
}

// SSAO: AO alone, into a one-channel target.
@fragment
fn fs_ao(in: FullscreenOut) -> @location(0) vec4<f32> {
    return vec4<f32>(evaluate(sampled_position(in.position.xy), vec2<i32>(in.position.xy)).ao, 0.0, 0.0, 1.0);
}

// SSDO and SSAO+SSDO: DO in rgb, AO in a (1 when HAS_AO is off).
@fragment
fn fs_do(in: FullscreenOut) -> @location(0) vec4<f32> {
    let o = evaluate(sampled_position(in.position.xy), vec2<i32>(in.position.xy));
    let value = vec4<f32>(o.direct * occ.sky_strength + o.indirect * occ.indirect_strength, select(1.0, o.ao, HAS_AO));
    return stored_do(value, surface_pixel(vec2<i32>(in.position.xy)));
}
