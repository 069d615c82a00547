// The marched sampling pass: AO, SSDO's sky light and its one bounce from one march of the depth
// buffer per direction, after GTAO (Jimenez et al. 2016, "Practical Real-Time Strategies for
// Accurate Indirect Occlusion") and the visibility bitmask (Therrien, Levesque & Gilet 2023,
// "Screen Space Indirect Lighting with Visibility Bitmask").
//
// The hemisphere above a pixel is cut into `slices` planes that contain the view vector v; a
// direction ω in slice φ at angle θ from v has solid angle dω = |sin θ| dθ dφ, and its cosine at
// the receiver is n·ω = |n_p| cos(θ − γ), with n_p the normal projected into the slice and γ its
// angle. So every cosine-weighted integral (1/π)∫ f(ω) n·ω dω becomes a sum over slices of
// |n_p| ∫ f cos(θ − γ) |sin θ| dθ, which each slice evaluates over 32 sectors of θ, in closed form.
//
// Each slice is marched both ways across the screen. Every depth sample is a surface of a given
// thickness (its front at the depth buffer, its back `thickness` further along its view ray: the
// scene's one thickness, or, with the thickness layer, its material's where that is thinner); the
// sectors between the angles of its front and back are occluded, and the sectors it occludes
// first take their bounce from it (its diffuse radiance from the lighting pass, if it faces the
// receiver). Sectors never occluded see the sky, read from the cube map at the mip level of a
// sector group's solid angle. Steps are dense within the AO radius R (AO counts occluders within
// R only) and then spread geometrically out to `reach`, so walls far beyond R still block the sky.
//
//   AO       = 1 − Σ|n_p| w(occluded within R) / Σ|n_p| w(all)
// ("all": the sectors above the surface's own plane; with normal maps n is the mapped normal and
// the plane the depth buffer's, see NORMAL_MAPPED in common/sampling_params.wgsl)
//   direct   = Σ|n_p| Σ_g w_g · visible_g · L_sky(ω_g) / Σ|n_p| w(all)     (white furnace exact)
//   indirect = Σ|n_p| Σ_k w_k · occluded_first_by(s) · L_bounce(s) / Σ|n_p| w(all)
// with w = ∫ cos(θ − γ)|sin θ| dθ over the sectors named. Albedo is applied in the composite.

#include "common/uniforms.wgsl"
#include "common/gbuffer_read.wgsl"
#include "common/sampling_params.wgsl"
#include "common/fullscreen.wgsl"

#include "common/occlusion_inputs.wgsl"
// The closest depth per 2^(k+1)-pixel block at level k, as f32 bits (shaders/depth_pyramid.wgsl),
// read by the far steps when the plan built it (USE_PYRAMID); a 1x1 stand-in otherwise.
@group(1) @binding(5) var depth_pyramid: texture_2d<u32>;
// The far steps read the depth pyramid (the plan built one) rather than the depth buffer.
override USE_PYRAMID: bool = false;
// The depth with each surface's thickness code in its low 6 bits (gbuffer.wgsl `fs_thickness`),
// read in place of the depth where the plan has it (THICKNESS_LAYER); a 1x1 stand-in otherwise.
@group(1) @binding(6) var thickness_layer: texture_2d<u32>;
override THICKNESS_LAYER: bool = false;
// The layer is the lighting pass's depth with each surface's extent (common/thickness.wgsl
// EXTENT_CODE_MASK: there is a far side), which the thickness layer's codes stand in where a
// surface has no face behind it.
override EXTENT_CODES: bool = false;
// The bounce target's second pair holds the far side layer's senders (lighting.wgsl).
override FAR_SIDE: bool = false;

#include "common/sectors.wgsl"
#include "common/thickness.wgsl"

struct Occlusion {
    ao: f32,
    direct: vec3<f32>,
    indirect: vec3<f32>,
    // The cosine-weighted share of the hemisphere no sample occludes (what the sky is seen
    // through; the constant ambient's visibility at a sender).
    open: f32,
}

// The receiver: what every slice of a pixel's march shares.
struct Receiver {
    position: vec2<f32>,
    // The shading normal (the cosines are its) and the surface's own plane's normal (the
    // hemisphere is cut there; the same as `n` unless the G-buffer's normals are mapped).
    n: vec3<f32>,
    n_g: vec3<f32>,
    // The receiver, lifted off its surface by the depth bias so its own plane does not occlude
    // it, and the view vector from it.
    p: vec3<f32>,
    v: vec3<f32>,
    v_world: vec3<f32>,
    radius: f32,
    // log2(reach / R): the far steps grow geometrically from R to the reach, R·(reach/R)^x, as
    // exp2 of this log taken once rather than a pow (a log and an exp) on every step.
    log2_span: f32,
    thickness: f32,
    // Pixels per view unit at the receiver's depth.
    pixels_per_unit: f32,
    near_steps: u32,
    far_steps: u32,
    // AO alone counts occluders within R only: the far steps would change nothing.
    last_step: u32,
    // The tile's slice and step offsets, moved on by this frame's entry of the schedule.
    noise: vec4<f32>,
}

// The receiver at pixel centre `position` (of `pixel`, whose depth is `depth`), with the
// rotation and jitter of the 4x4 tile at `tile`.
fn receiver_at(position: vec2<f32>, pixel: vec2<i32>, depth: f32, tile: vec2<i32>) -> Receiver {
    let n = load_normal(pixel);
    let surface = view_position(position, depth);
    var n_g = n;
    if NORMAL_MAPPED {
        n_g = depth_normal(pixel, surface, n);
    }
    return receiver_of(position, surface, n, n_g, tile, false);
}

// The receiver at view point `surface` (pixel centre `position`) with shading normal `n` and
// plane normal `n_g`; `away`: a surface turned from the eye, whose hemisphere is measured about
// the view ray's continuation (the slices' angles from the direction away from the eye).
fn receiver_of(position: vec2<f32>, surface: vec3<f32>, n: vec3<f32>, n_g: vec3<f32>, tile: vec2<i32>, away: bool) -> Receiver {
    var r: Receiver;
    r.position = position;
    r.n = n;
    r.n_g = n_g;
    r.radius = occ.radius;
    r.p = surface + r.n_g * occ.bias_length;
    r.v = safe_normalize(-r.p, vec3<f32>(0.0, 0.0, 1.0));
    if away {
        r.v = -r.v;
    }
    r.v_world = (frame.view_to_world * vec4<f32>(r.v, 0.0)).xyz;
    let steps = max(occ.steps, 1u);
    let reach = max(occ.reach, r.radius);
    r.log2_span = log2(reach / r.radius);
    r.thickness = max(occ.thickness, 0.0);
    r.pixels_per_unit = 0.5 * frame.viewport.y * frame.view_to_clip[1][1] / max(-r.p.z, 1e-30);
    r.near_steps = max(steps / 2u, 1u);
    r.far_steps = steps - r.near_steps;
    r.last_step = select(r.near_steps, steps, HAS_DO);
    let tile_noise = occ.rotations[u32(tile.x & 3) + 4u * u32(tile.y & 3)];
    r.noise = vec4<f32>(tile_noise.xy, fract(tile_noise.zw + occ.schedule.xy));
    return r;
}

// What a pixel's march sums over its slices, and what one slice has taken so far.
struct Sums {
    total: f32,
    occluded_near: f32,
    direct: vec3<f32>,
    indirect: vec3<f32>,
    open: f32,
}

struct Taken {
    // Sectors occluded (or below the surface's plane), and those occluded within R.
    mask: u32,
    near_mask: u32,
}

// How far along the slice step `i` lies: dense within R, then geometric out to the reach;
// jittered per pixel. (AO alone takes the near steps only: its pipeline has no far branch.)
fn step_distance(r: Receiver, i: u32) -> f32 {
    let j = f32(i) + r.noise.w;
    if !HAS_DO || i < r.near_steps {
        let x = j / f32(r.near_steps);
        return r.radius * x * x;
    }
    let x = (j - f32(r.near_steps)) / f32(max(r.far_steps, 1u));
    return r.radius * exp2(x * r.log2_span);
}

// A depth sample: its depth and its thickness code (common/thickness.wgsl; the default class
// without the thickness layer).
struct DepthSample {
    depth: f32,
    code: u32,
}

// How deep along its view ray the depth sample at `p` (a step standing for `spacing` pixels) is
// taken to be: the scene's one thickness (or the one given), or where the thickness layer says
// its surface is thinner, the depth its own thickness and tilt span over the step's footprint
// (common/thickness.wgsl), never more than the scene's. Arithmetic only: no branch, no load.
fn sample_thickness(r: Receiver, sample: DepthSample, p: vec3<f32>, spacing: f32) -> f32 {
    if !THICKNESS_LAYER {
        return r.thickness;
    }
    if EXTENT_CODES && (sample.code & EXTENT_FLAG) != 0u {
        return extent_of(sample.code, length(p));
    }
    let extent = depth_extent(sample.code, pixel_footprint(spacing, p.z), frame.default_thickness);
    return min(r.thickness, extent);
}

// The depth step `i` reads at `texel`, `spacing` pixels past the last step. A far step stands for
// the pixels since the last one: it reads the closest depth of a block about that wide, so what
// lies between steps is not skipped (and takes the receiver's thickness: a block has no one
// material).
fn step_depth(r: Receiver, i: u32, texel: vec2<i32>, spacing: f32) -> DepthSample {
    let level = i32(floor(log2(max(spacing, 1.0)))) - 1;
    if !USE_PYRAMID || i < r.near_steps || level < 0 {
        if THICKNESS_LAYER {
            let bits = textureLoad(thickness_layer, texel, 0).r;
            return DepthSample(bitcast<f32>(bits), bits & select(THICKNESS_CODE_MASK, EXTENT_CODE_MASK, EXTENT_CODES));
        }
        return DepthSample(load_depth(texel), DEFAULT_THICKNESS_CLASS);
    }
    let top = i32(textureNumLevels(depth_pyramid)) - 1;
    let k = min(level, top);
    let last = vec2<i32>(textureDimensions(depth_pyramid, k)) - vec2<i32>(1);
    let block = min(texel >> vec2<u32>(u32(k + 1)), last);
    return DepthSample(bitcast<f32>(textureLoad(depth_pyramid, block, k).r), DEFAULT_THICKNESS_CLASS);
}

// The bounce the sender at `texel` (at `front` from the receiver) sends into the sectors
// `fresh` it is the first to occlude: a sender facing the receiver sends its light. Where the
// one the screen shows faces away, the far side layer's sender behind it (FAR_SIDE: a fin's or
// box's far face, an underside) sends its own if it faces the receiver; else a sheet (a cut-out
// or thin class) sends its near side's light from its far side, as the two sides of a fence see
// much the same light (the candidates measured for both: docs/accuracy.md).
fn bounce_from(texel: vec2<i32>, front: vec3<f32>, fresh: u32, weights: vec4<f32>, sheet: bool) -> vec3<f32> {
    let senders = textureLoad(bounce_map, texel, 0);
    var sender = senders.xy;
    var sends = dot(sender_normal(sender), -front) > 0.0;
    if FAR_SIDE {
        // Faces tested from the near point (no far depth is kept); a select, as below.
        let far = !sends && any(senders.zw != vec2<u32>(0u)) && dot(sender_normal(senders.zw), -front) > 0.0;
        sender = select(sender, senders.zw, far);
        sends = sends || far;
    }
    sends = sends || sheet;
    // The measure of the sectors it occludes first, group by group. (A select, not an early
    // return: a CPU rasteriser runs both sides of a branch its lanes disagree on, and the
    // branch's bookkeeping cost the sampling pass 5%.)
    let w = dot(weights, group_counts(fresh));
    return select(vec3<f32>(0.0), (w / f32(PER_GROUP)) * sender_radiance(sender), sends);
}

// Marches one side (`sign`) of slice `s`, marking the sectors each depth sample occludes in
// `taken` and adding the bounce of the first occluder of each to `sums`.
fn march_side(r: Receiver, s: Slice, sign: f32, taken: ptr<function, Taken>, sums: ptr<function, Sums>) {
    // The last sample's surface point and front angle, while samples are on one surface.
    var connected = false;
    var previous = vec3<f32>(0.0);
    var previous_angle = 0.0;
    var previous_distance = 0.0;
    var previous_offset = 0.0;
    for (var i = 0u; i < r.last_step; i += 1u) {
        let distance = step_distance(r, i);
        let offset = max(distance * r.pixels_per_unit, f32(i + 1u));
        let spacing = offset - previous_offset;
        previous_offset = offset;
        let sample_f = r.position + sign * s.screen_dir * offset;
        if any(sample_f < vec2<f32>(0.0)) || any(sample_f >= frame.viewport.xy) {
            break;
        }
        let texel = vec2<i32>(sample_f);
        let sample = step_depth(r, i, texel, spacing);
        if sample.depth <= 0.0 {
            connected = false;
            continue;
        }
        let p = view_position(vec2<f32>(texel) + 0.5, sample.depth);
        let front = p - r.p;
        let thickness = far_extent(texel, sample, p, sample_thickness(r, sample, p, spacing));
        let back = front - safe_normalize(-p, r.v) * thickness;
        let a_front = slice_angle(front, r.v, s.t);
        let a_back = slice_angle(back, r.v, s.t);
        var a_min = min(a_front, a_back);
        var a_max = max(a_front, a_back);
        // One surface between this sample and the last (closer than the thickness plus twice the
        // step between them): the angles between them are that surface too, not a gap the sky
        // shows through. Sparse far steps would otherwise leak sky through every wall.
        // Only to a sample above the receiver's tangent plane. From one below it (the receiver's
        // own ground before the foot of a wall) the surface rises through the horizon, so the
        // sectors from the horizon up to this sample are that surface too: the previous angle
        // lies below the hemisphere and clamps to its edge sector. Without this the sectors
        // between the horizon and a wall's first sample showed the sky, and sent no bounce.
        let above = dot(front, r.n_g) > 0.0;
        // (Squared: the bound is never negative, the distances growing step by step.)
        let gap = p - previous;
        let bound = thickness + 2.0 * (distance - previous_distance);
        if connected && above && dot(gap, gap) < bound * bound {
            a_min = min(a_min, previous_angle);
            a_max = max(a_max, previous_angle);
        }
        connected = true;
        previous = p;
        previous_distance = distance;
        previous_angle = a_front;
        // Wholly below the receiver's tangent plane: it blocks nothing of the hemisphere.
        // (Tested on the positions, exactly, not on the approximate angles.)
        if !above && dot(back, r.n_g) <= 0.0 {
            continue;
        }
        let bits = bit_range(sector_of(a_min, s.gamma), sector_of(a_max, s.gamma));
        let fresh = bits & ~(*taken).mask;
        (*taken).mask |= bits;
        // AO counts the near steps only (within R of the receiver), so AO alone (which skips the
        // far steps) and AO beside DO are the same.
        if HAS_AO && i < r.near_steps && dot(front, front) < r.radius * r.radius {
            (*taken).near_mask |= bits;
        }
        if HAS_DO && INDIRECT && fresh != 0u {
            let sheet = THICKNESS_LAYER && (sample.code & EXTENT_FLAG) == 0u && is_thin(sample.code);
            (*sums).indirect += bounce_from(texel, front, fresh, s.weights, sheet);
        }
    }
}

// Adds slice `s` to `sums` over its sector groups: its measure, what is occluded within R, and
// the sky through what nothing occludes. Group g's middle direction is at θ = γ + δ_g,
// δ_g = (2g − 3)π/8: its cosine and sine from cos γ and sin γ by the angle sum (no cosine or sine
// of its own), and in world space from v and t turned there once a slice (no transform of its own).
fn integrate_slice(r: Receiver, s: Slice, taken: Taken, sums: ptr<function, Sums>) {
    let t_world = (frame.view_to_world * vec4<f32>(s.t, 0.0)).xyz;
    let turns = array<vec2<f32>, 4>(
        vec2<f32>(0.38268343, -0.92387953),
        vec2<f32>(0.92387953, -0.38268343),
        vec2<f32>(0.92387953, 0.38268343),
        vec2<f32>(0.38268343, 0.92387953),
    );
    for (var g = 0u; g < GROUPS; g += 1u) {
        let w = s.weights[g];
        let group_bits = bit_range(g * PER_GROUP, g * PER_GROUP + PER_GROUP - 1u);
        (*sums).total += w * f32(countOneBits(s.inside & group_bits)) / f32(PER_GROUP);
        if HAS_AO {
            (*sums).occluded_near += w * f32(countOneBits(taken.near_mask & s.inside & group_bits)) / f32(PER_GROUP);
        }
        if HAS_DO {
            let visible = f32(countOneBits(~taken.mask & group_bits)) / f32(PER_GROUP);
            (*sums).open += w * visible;
            if visible > 0.0 {
                let turn = read_turn(s, g, turns[g]);
                let cos_theta = s.turned.x * turn.x - s.turned.y * turn.y;
                let sin_theta = s.turned.y * turn.x + s.turned.x * turn.y;
                let world = r.v_world * cos_theta + t_world * sin_theta;
                (*sums).direct += w * visible * textureSampleLevel(sky_map, sky_sampler, world, occ.sky_mip).rgb;
            }
        }
    }
}

// The march at pixel centre `position` with `slices` slices, its rotation and jitter from the
// 4x4 tile at `tile` (the pixel itself, or the sender-sky pass's own half-resolution pixel).
fn evaluate(position: vec2<f32>, slice_count: u32, tile: vec2<i32>) -> Occlusion {
    var out: Occlusion;
    out.ao = 1.0;
    out.open = 1.0;
    let pixel = vec2<i32>(position);
    let depth = load_depth(pixel);
    if depth <= 0.0 {
        return out;
    }
    return march_receiver(receiver_at(position, pixel, depth, tile), slice_count);
}

// The march about receiver `r` with `slice_count` slices.
fn march_receiver(r: Receiver, slice_count: u32) -> Occlusion {
    var out: Occlusion;
    out.ao = 1.0;
    out.open = 1.0;
    let slices = max(slice_count, 1u);
    var sums: Sums;
    for (var slice = 0u; slice < slices; slice += 1u) {
        let s = slice_at(r.n, r.n_g, r.v, PI * (f32(slice) + r.noise.z) / f32(slices));
        if s.n_len < 1e-6 {
            continue;
        }
        // Sectors below the surface's plane count as taken: no sky, no bounce, and they leave
        // the slice's measure (`total`) out.
        var taken = Taken(~s.inside, 0u);
        march_side(r, s, 1.0, &taken, &sums);
        march_side(r, s, -1.0, &taken, &sums);
        integrate_slice(r, s, taken, &sums);
    }
    if sums.total > 0.0 {
        out.ao = 1.0 - sums.occluded_near / sums.total;
        out.direct = sums.direct / sums.total * frame.sky_scale;
        out.indirect = sums.indirect / sums.total;
        out.open = sums.open / sums.total;
    }
    return out;
}

// The pass's fragment at `frag`: its full-resolution pixel, with its own tile entry.
fn evaluate_pixel(frag: vec2<f32>) -> Occlusion {
    return evaluate(sampled_position(frag), occ.slices, vec2<i32>(frag));
}

// The far side layer's surfaces (far_side.rs FAR_SURFACE: x the packed normal, z the depth's
// bits, 0 where there is none), read by the far-sky pass alone.
@group(1) @binding(7) var far_surface: texture_2d<u32>;
// The far-sky pass: each depth sample spans to the far side's face behind it, read here (the
// lighting pass, which writes that extent for the sampling pass, runs after this one).
override FAR_EXTENT: bool = false;

// `thickness`, or with FAR_EXTENT the distance from the sample at `p` to the far side's face
// behind it, where there is one and the sample is no sheet (as lighting.wgsl `extent_layer`).
fn far_extent(texel: vec2<i32>, sample: DepthSample, p: vec3<f32>, thickness: f32) -> f32 {
    if !FAR_EXTENT || (THICKNESS_LAYER && (sample.code & 7u) == 0u) {
        return thickness;
    }
    let far = textureLoad(far_surface, texel, 0).z;
    if far == 0u || bitcast<f32>(far) >= sample.depth {
        return thickness;
    }
    return length(view_position(vec2<f32>(texel) + 0.5, bitcast<f32>(far))) - length(p);
}

// The sky a surface sends in the bounce, before its albedo: rgb the visible sky light (E/π,
// pre-exposed, at the senders' sky strength, which the sky's unoccluded irradiance carries too),
// a the open share (the constant ambient's visibility).
fn sender_value(o: Occlusion) -> vec4<f32> {
    return vec4<f32>(o.direct * occ.sender_sky_strength, o.open);
}
