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
// thickness (its front at the depth buffer, its back `thickness` further along its view ray); the
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

@group(1) @binding(3) var<uniform> occ: SamplingParams;
// The senders: radiance and facing, packed (pack_sender in common/surface_pack.wgsl).
@group(1) @binding(4) var bounce_map: texture_2d<u32>;
// The closest depth per 2^(k+1)-pixel block at level k, as f32 bits (shaders/depth_pyramid.wgsl),
// read by the far steps when the plan built it (USE_PYRAMID); a 1x1 stand-in otherwise.
@group(1) @binding(5) var depth_pyramid: texture_2d<u32>;
#include "common/sky.wgsl"

// What the mode computes: AO, DO, or both (the composite and the tone mapper have the same two).
override HAS_AO: bool = true;
override HAS_DO: bool = true;
// The scene has point lights, so there is a bounce buffer to read.
override INDIRECT: bool = true;
// The far steps read the depth pyramid (the plan built one) rather than the depth buffer.
override USE_PYRAMID: bool = false;

// Sectors per slice (one bit each: what occludes is resolved to π/32) and the groups the sky is
// read and the weights are integrated for (a sky read per group, not per sector: 4 reads per
// slice instead of 32; a group's partial visibility scales its read). Fewer groups cost fewer
// cube-map reads and blur the sky's directions within a slice more.
const SECTORS: u32 = 32u;
// (group_counts counts the groups as the mask's bytes: 4 groups of 8.)
const GROUPS: u32 = 4u;
const PER_GROUP: u32 = 8u;
const HALF_PI: f32 = 1.5707963;

struct Occlusion {
    ao: f32,
    direct: vec3<f32>,
    indirect: vec3<f32>,
    // The cosine-weighted share of the hemisphere no sample occludes (what the sky is seen
    // through; the constant ambient's visibility at a sender).
    open: f32,
}

// F(θ) = ∫ cos(θ − γ) sin θ dθ = (θ sin γ − cos(2θ − γ)/2) / 2. F falls where sin θ < 0 and rises
// where sin θ > 0 (cos(θ − γ) ≥ 0 inside the hemisphere), so ∫_a^b cos(θ − γ)|sin θ| dθ is
// |F(b) − F(a)| for an interval on one side of θ = 0, and F(a) + F(b) − 2F(0) across it.
// At the group boundaries θ_g = γ − π/2 + g·π/4, 2θ_g − γ = γ − π + g·π/2, so cos(2θ_g − γ) is
// −cos γ, sin γ, cos γ, −sin γ, −cos γ for g = 0..4 (`cos_term`): one cosine and one sine a
// slice instead of five cosines; and F(0) = −cos γ / 4.
fn antiderivative(theta: f32, cos_term: f32, sin_gamma: f32) -> f32 {
    return 0.5 * (theta * sin_gamma - 0.5 * cos_term);
}

// atan2 to within 0.004 rad (a sector is 0.098 rad wide), without the library call's cost.
fn fast_atan2(y: f32, x: f32) -> f32 {
    let ax = abs(x);
    let ay = abs(y);
    let q = min(ax, ay) / max(max(ax, ay), 1e-30);
    var a = q * (0.7853982 + 0.273 * (1.0 - q));
    if ay > ax {
        a = HALF_PI - a;
    }
    if x < 0.0 {
        a = PI - a;
    }
    return select(a, -a, y < 0.0);
}

// How many of the sectors in `bits` fall in each of the four groups (the mask's four bytes),
// counted at once by the parallel bit count run only to the bytes. Exactly what a
// countOneBits per group gives; the gather does it on every step that occludes something new,
// and a CPU rasteriser on every step: four separate counts were an eighth of the SSDO pass.
fn group_counts(bits: u32) -> vec4<f32> {
    var x = bits - ((bits >> 1u) & 0x55555555u);
    x = (x & 0x33333333u) + ((x >> 2u) & 0x33333333u);
    x = (x + (x >> 4u)) & 0x0f0f0f0fu;
    return vec4<f32>(vec4<u32>(x & 0xffu, (x >> 8u) & 0xffu, (x >> 16u) & 0xffu, x >> 24u));
}

// The bits of sectors [first, last] (inclusive, 0..31).
fn bit_range(first: u32, last: u32) -> u32 {
    let count = last - first + 1u;
    let ones = select((1u << count) - 1u, 0xffffffffu, count >= 32u);
    return ones << first;
}

// The sector holding angle θ (clamped into the hemisphere [γ − π/2, γ + π/2]).
fn sector_of(theta: f32, gamma: f32) -> u32 {
    let t = clamp((theta - (gamma - HALF_PI)) / PI, 0.0, 0.99999);
    return u32(t * f32(SECTORS));
}

// Signed angle of `d` from the view vector `v` towards `t`, in the slice plane.
fn slice_angle(d: vec3<f32>, v: vec3<f32>, t: vec3<f32>) -> f32 {
    return fast_atan2(dot(d, t), dot(d, v));
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
    // The cosines are the shading normal's; the hemisphere is cut at the surface's own plane
    // (its normal `n_g`, the same as `n` unless the G-buffer's normals are mapped).
    let n = load_normal(pixel);
    let surface = view_position(position, depth);
    var n_g = n;
    if NORMAL_MAPPED {
        n_g = depth_normal(pixel, surface, n);
    }
    let radius = occ.radius;
    // The receiver, lifted off its surface by the depth bias so its own plane does not occlude it.
    let p = surface + n_g * occ.bias_length;
    let v = safe_normalize(-p, vec3<f32>(0.0, 0.0, 1.0));
    let v_world = (frame.view_to_world * vec4<f32>(v, 0.0)).xyz;
    let slices = max(slice_count, 1u);
    let steps = max(occ.steps, 1u);
    let reach = max(occ.reach, radius);
    // The far steps grow geometrically from R to the reach: R·(reach/R)^x, as exp2 of a log
    // taken once here rather than a pow (a log and an exp) on every step.
    let log2_span = log2(reach / radius);
    let thickness = max(occ.thickness, 0.0);
    let size = frame.viewport.xy;
    // Pixels per view unit at the receiver's depth.
    let pixels_per_unit = 0.5 * size.y * frame.view_to_clip[1][1] / max(-p.z, 1e-30);
    let near_steps = max(steps / 2u, 1u);
    let far_steps = steps - near_steps;
    // AO alone counts occluders within R only: the far steps would change nothing.
    let last_step = select(near_steps, steps, HAS_DO);
    // The tile's slice and step offsets, moved on by this frame's entry of the schedule.
    let tile_noise = occ.rotations[u32(tile.x & 3) + 4u * u32(tile.y & 3)];
    let noise = vec4<f32>(tile_noise.xy, fract(tile_noise.zw + occ.schedule.xy));

    var total = 0.0;
    var occluded_near = 0.0;
    var direct = vec3<f32>(0.0);
    var indirect = vec3<f32>(0.0);
    var open = 0.0;
    for (var slice = 0u; slice < slices; slice += 1u) {
        let phi = PI * (f32(slice) + noise.z) / f32(slices);
        // Screen direction (x right, y down) and the view-space direction it moves along.
        let screen_dir = vec2<f32>(cos(phi), sin(phi));
        let axis = vec3<f32>(screen_dir.x, -screen_dir.y, 0.0);
        let t = safe_normalize(axis - v * dot(axis, v), vec3<f32>(1.0, 0.0, 0.0));
        let plane_normal = cross(v, t);
        let n_p = n - plane_normal * dot(n, plane_normal);
        let n_len = length(n_p);
        if n_len < 1e-6 {
            continue;
        }
        let gamma = slice_angle(n_p, v, t);
        let lo = gamma - HALF_PI;
        let sin_gamma = dot(n_p, t) / n_len;
        // The cosine and sine of γ as the sectors place it (fast_atan2's angle, within 0.004 rad
        // of the normal's own): every group boundary's and group middle's follow from them.
        let turned = vec2<f32>(cos(gamma), sin(gamma));
        // The sectors above the surface's own plane: all of them unless the normals are mapped.
        var inside = 0xffffffffu;
        if NORMAL_MAPPED {
            let ng_p = n_g - plane_normal * dot(n_g, plane_normal);
            if dot(ng_p, ng_p) > 1e-12 {
                let gamma_g = slice_angle(ng_p, v, t);
                let first = sector_of(gamma_g - HALF_PI, gamma);
                let last = sector_of(gamma_g + HALF_PI, gamma);
                inside = select(0u, bit_range(first, last), first <= last);
            }
        }
        // The cosine-weighted measure of each sector group, times |n_p| (four groups: the
        // boundaries' cosines below are those of quarter turns).
        let width = PI / f32(GROUPS);
        let f_zero = -0.25 * turned.x;
        let cos_terms = array<f32, 5>(-turned.x, turned.y, turned.x, -turned.y, -turned.x);
        var weights: array<f32, GROUPS>;
        var f_a = antiderivative(lo, cos_terms[0], sin_gamma);
        for (var g = 0u; g < GROUPS; g += 1u) {
            let a = lo + f32(g) * width;
            let b = a + width;
            let f_b = antiderivative(b, cos_terms[g + 1u], sin_gamma);
            var w = abs(f_b - f_a);
            if a < 0.0 && b > 0.0 {
                w = f_a + f_b - 2.0 * f_zero;
            }
            weights[g] = n_len * w;
            f_a = f_b;
        }

        let group_weights = vec4<f32>(weights[0], weights[1], weights[2], weights[3]);

        // Sectors below the surface's plane count as taken: no sky, no bounce, and they leave
        // the slice's measure (`total`) below.
        var mask = ~inside;
        var near_mask = 0u;
        for (var side = 0u; side < 2u; side += 1u) {
            let sign = select(-1.0, 1.0, side == 0u);
            // The last sample's surface point and front angle, while samples are on one surface.
            var connected = false;
            var previous = vec3<f32>(0.0);
            var previous_angle = 0.0;
            var previous_distance = 0.0;
            var previous_offset = 0.0;
            for (var i = 0u; i < last_step; i += 1u) {
                // Dense within R, then geometric out to the reach; jittered per pixel.
                let j = f32(i) + noise.w;
                var distance: f32;
                // (AO alone takes the near steps only: its pipeline has no far branch to run.)
                if !HAS_DO || i < near_steps {
                    let x = j / f32(near_steps);
                    distance = radius * x * x;
                } else {
                    let x = (j - f32(near_steps)) / f32(max(far_steps, 1u));
                    distance = radius * exp2(x * log2_span);
                }
                let offset = max(distance * pixels_per_unit, f32(i + 1u));
                let spacing = offset - previous_offset;
                previous_offset = offset;
                let sample_f = position + sign * screen_dir * offset;
                if any(sample_f < vec2<f32>(0.0)) || any(sample_f >= size) {
                    break;
                }
                let texel = vec2<i32>(sample_f);
                // A far step stands for the pixels since the last one: it reads the closest depth
                // of a block about that wide, so what lies between steps is not skipped.
                var sample_depth: f32;
                let level = i32(floor(log2(max(spacing, 1.0)))) - 1;
                if !USE_PYRAMID || i < near_steps || level < 0 {
                    sample_depth = load_depth(texel);
                } else {
                    let top = i32(textureNumLevels(depth_pyramid)) - 1;
                    let k = min(level, top);
                    let last = vec2<i32>(textureDimensions(depth_pyramid, k)) - vec2<i32>(1);
                    let block = min(texel >> vec2<u32>(u32(k + 1)), last);
                    sample_depth = bitcast<f32>(textureLoad(depth_pyramid, block, k).r);
                }
                if sample_depth <= 0.0 {
                    connected = false;
                    continue;
                }
                let s = view_position(vec2<f32>(texel) + 0.5, sample_depth);
                let front = s - p;
                let back = front - safe_normalize(-s, v) * thickness;
                let a_front = slice_angle(front, v, t);
                let a_back = slice_angle(back, v, t);
                var a_min = min(a_front, a_back);
                var a_max = max(a_front, a_back);
                // One surface between this sample and the last (closer than the thickness plus
                // twice the step between them): the angles between them are that surface too, not
                // a gap the sky shows through. Sparse far steps would otherwise leak sky through
                // every wall.
                // Only to a sample above the receiver's tangent plane. From one below it (the
                // receiver's own ground before the foot of a wall) the surface rises through the
                // horizon, so the sectors from the horizon up to this sample are that surface too:
                // the previous angle lies below the hemisphere and clamps to its edge sector.
                // Without this the sectors between the horizon and a wall's first sample showed
                // the sky, and sent no bounce.
                let above = dot(front, n_g) > 0.0;
                // (Squared: the bound is never negative, the distances growing step by step.)
                let gap = s - previous;
                let bound = thickness + 2.0 * (distance - previous_distance);
                if connected && above && dot(gap, gap) < bound * bound {
                    a_min = min(a_min, previous_angle);
                    a_max = max(a_max, previous_angle);
                }
                connected = true;
                previous = s;
                previous_distance = distance;
                previous_angle = a_front;
                // Wholly below the receiver's tangent plane: it blocks nothing of the hemisphere.
                // (Tested on the positions, exactly, not on the approximate angles.)
                if !above && dot(back, n_g) <= 0.0 {
                    continue;
                }
                let first = sector_of(a_min, gamma);
                let last = sector_of(a_max, gamma);
                let bits = bit_range(first, last);
                let fresh = bits & ~mask;
                mask |= bits;
                // AO counts the near steps only (within R of the receiver), so AO alone (which
                // skips the far steps) and AO beside DO are the same.
                if HAS_AO && i < near_steps && dot(front, front) < radius * radius {
                    near_mask |= bits;
                }
                if HAS_DO && INDIRECT && fresh != 0u {
                    let sender = textureLoad(bounce_map, texel, 0).xy;
                    // Only a sender facing the receiver sends its light this way.
                    if dot(sender_normal(sender), -front) > 0.0 {
                        // The measure of the sectors it occludes first, group by group.
                        let w = dot(group_weights, group_counts(fresh));
                        indirect += (w / f32(PER_GROUP)) * sender_radiance(sender);
                    }
                }
            }
        }

        // Integrate the slice over the sector groups. Group g's middle direction is at
        // θ = γ + δ_g, δ_g = (2g − 3)π/8: its cosine and sine from cos γ and sin γ by the angle
        // sum (no cosine or sine of its own), and in world space from v and t turned there once
        // a slice (no transform of its own).
        let t_world = (frame.view_to_world * vec4<f32>(t, 0.0)).xyz;
        let turns = array<vec2<f32>, 4>(
            vec2<f32>(0.38268343, -0.92387953),
            vec2<f32>(0.92387953, -0.38268343),
            vec2<f32>(0.92387953, 0.38268343),
            vec2<f32>(0.38268343, 0.92387953),
        );
        for (var g = 0u; g < GROUPS; g += 1u) {
            let w = weights[g];
            let group_bits = bit_range(g * PER_GROUP, g * PER_GROUP + PER_GROUP - 1u);
            total += w * f32(countOneBits(inside & group_bits)) / f32(PER_GROUP);
            if HAS_AO {
                occluded_near += w * f32(countOneBits(near_mask & inside & group_bits)) / f32(PER_GROUP);
            }
            if HAS_DO {
                let visible = f32(countOneBits(~mask & group_bits)) / f32(PER_GROUP);
                open += w * visible;
                if visible > 0.0 {
                    let turn = turns[g];
                    let cos_theta = turned.x * turn.x - turned.y * turn.y;
                    let sin_theta = turned.y * turn.x + turned.x * turn.y;
                    let world = v_world * cos_theta + t_world * sin_theta;
                    direct += w * visible * textureSampleLevel(sky_map, sky_sampler, world, occ.sky_mip).rgb;
                }
            }
        }
    }
    if total > 0.0 {
        out.ao = 1.0 - occluded_near / total;
        out.direct = direct / total * frame.sky_scale;
        out.indirect = indirect / total;
        out.open = open / total;
    }
    return out;
}

// The pass's fragment at `frag`: its full-resolution pixel, with its own tile entry.
fn evaluate_pixel(frag: vec2<f32>) -> Occlusion {
    return evaluate(sampled_position(frag), occ.slices, vec2<i32>(frag));
}

// SSAO: AO alone, into a one-channel target.
@fragment
fn fs_ao(in: FullscreenOut) -> @location(0) vec4<f32> {
    return vec4<f32>(evaluate_pixel(in.position.xy).ao, 0.0, 0.0, 1.0);
}

// SSDO and SSAO+SSDO: DO in rgb; in a, AO (SSAO+SSDO) or, in SSDO, the open share: the constant
// ambient is a uniform sky, and SSDO sees it through the same open sectors as the sky.
fn do_value(o: Occlusion) -> vec4<f32> {
    return vec4<f32>(o.direct * occ.sky_strength + o.indirect * occ.indirect_strength, select(o.open, o.ao, HAS_AO));
}

@fragment
fn fs_do(in: FullscreenOut) -> @location(0) vec4<f32> {
    return do_value(evaluate_pixel(in.position.xy));
}

// The sky a surface sends in the bounce, before its albedo: rgb the visible sky light (E/π,
// pre-exposed, at the senders' sky strength, which the sky's unoccluded irradiance carries too),
// a the open share (the constant ambient's visibility).
fn sender_value(o: Occlusion) -> vec4<f32> {
    return vec4<f32>(o.direct * occ.sender_sky_strength, o.open);
}

struct DoAndSky {
    @location(0) occlusion: vec4<f32>,
    // `sender_value` of this pixel's surface, as `fs_sender` writes it: the next frame's lighting
    // pass reads it as the sky this surface sends in the bounce (`--sender-sky last-frame`).
    @location(1) sky: vec4<f32>,
}

// fs_do, and the sky this pixel sees for the next frame's senders: the same march's visible sky
// and open share (all its slices, where the sender-sky pass marches one).
@fragment
fn fs_do_senders(in: FullscreenOut) -> DoAndSky {
    let o = evaluate_pixel(in.position.xy);
    return DoAndSky(do_value(o), sender_value(o));
}

// The sender-sky pass's resolution: half (1) or a quarter (2) of the screen's width and height.
override SENDER_SHIFT: u32 = 1u;

// The sender-sky pass (built with HAS_DO on, HAS_AO and INDIRECT off): at half (quarter)
// resolution, the sky the full-resolution pixel (2x, 2y) ((4x + 1, 4y + 1), about the middle of
// its block) sees through one slice — rgb the visible
// sky light (E/π, pre-exposed), a the open share — which the lighting pass turns into the light
// that surface sends in the bounce. One slice is noisy per sender; the gather averages many.
@fragment
fn fs_sender(in: FullscreenOut) -> @location(0) vec4<f32> {
    let cell = vec2<i32>(in.position.xy);
    let scale = 1 << SENDER_SHIFT;
    return sender_value(evaluate(vec2<f32>(scale * cell + (scale / 2 - 1)) + 0.5, 1u, cell));
}
