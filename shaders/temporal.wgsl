// The temporal pass: this frame's (blurred) AO / DO averaged with what the last frames left for
// the same surface. The scene and its lights are static, so where a surface was on screen a
// frame ago follows from the camera alone: each pixel's world position through the previous
// frame's world-to-clip transform. The 4x4 history texels around that point (but its corners)
// are each kept only if they hold the same surface — their own position (from the depth they
// stored and the previous camera) within a tenth of the sampling radius of this pixel's tangent
// plane, and their normal within 25° of this one — and are weighted by Catmull-Rom's cubic. Where the kept
// texels carry less than half the weight (disoccluded, off screen, or the first frame after a
// reset) the pixel starts anew from this frame.
//
// Each pixel counts the frames it holds, n. It blends 1/n of this frame in, n rising by one a
// frame: while the pixel stays put, up to `accumulate`, where it then holds the exact mean of
// those frames and stops blending (still frames add nothing new once the schedule's frames are
// in); while it moves, up to `motion_accumulate`, with the history clamped to the range of this
// frame's 3x3 neighbourhood: screen-space occlusion depends on what the view shows, so a moving
// view keeps less of the past.
//
// Where the plan has no blur pass (BLUR: half resolution, the bilateral blur, accumulation) it
// blurs this frame's samples as it reads that neighbourhood, in the frames that blur.
//
// After a half-resolution sampling pass it runs where the samples are: each texel is the sample
// of the full-resolution pixel (2x, 2y), its surface that pixel's, and the histories are half
// size too; the composite upsamples the average as it reads it. A full-screen pass here
// would upsample every frame's samples first, at four times the pixels.

#include "common/uniforms.wgsl"
#include "common/gbuffer_read.wgsl"
#include "common/filter_params.wgsl"
#include "common/fullscreen.wgsl"
#include "common/bilateral.wgsl"

@group(1) @binding(3) var<uniform> params: FilterParams;
// This frame's output of the blur (or of the sampling pass without blur), at this pass's size.
@group(1) @binding(4) var current: texture_2d<f32>;
// The last frame's average, and the surface each of its pixels holds: x the reverse-Z depth
// (f32 bits), y its view-space normal as that frame's G-buffer packed it (bits 0-23) and the
// frames averaged (bits 24-31; 0 where nothing is held). The normal is the G-buffer's code as
// it is, so a still frame stores it without decoding; a moving one compares it in the previous
// frame's view space.
@group(1) @binding(5) var history: texture_2d<f32>;
@group(1) @binding(6) var history_surface: texture_2d<u32>;

// How far (in sampling radii) a history texel's position may lie off this pixel's tangent plane,
// and how closely the normals must agree, for it to count as the same surface.
const PLANE_RADII: f32 = 0.1;
const MIN_NORMAL_COS: f32 = 0.9;
// Reprojected movement below this (in pixels) is a still pixel.
const STILL_PIXELS: f32 = 0.01;

// The camera moved since the last frame (a pipeline of its own): reproject. Without it every
// pixel is still and reads its own texel alone, which on a CPU rasteriser (where a branch not
// taken still costs its work) keeps the pass to a fifth of its moving cost.
override CAMERA_MOVED: bool = true;
// In a half-resolution plan the pass runs at half size, over half-size samples, into half-size
// histories.
#include "common/sample_grid.wgsl"

struct TemporalOut {
    // what the composite reads this frame
    @location(0) shown: vec4<f32>,
    // the same, kept for the next frame
    @location(1) history: vec4<f32>,
    @location(2) surface: vec4<u32>,
}

fn finite4(v: vec4<f32>) -> bool {
    return all(abs(v) < vec4<f32>(1e30)) && all(v == v);
}

// The samples are blurred here, not by a pass of their own (BLUR): the bilateral 3x3 tent of
// shaders/blur.wgsl at half resolution, over the texels whose range the moving view's history is
// clamped to, so the blur's reads are this pass's.
override BLUR: bool = false;

// This frame's samples over the 3x3 texels around `texel` (its own sample `centre`, its surface
// at view point `p` with normal `n` and octahedral code `oct`): with BLUR their bilateral tent
// average, else `centre`; and their range over the texels on a surface.
struct Around {
    value: vec4<f32>,
    lo: vec4<f32>,
    hi: vec4<f32>,
}

fn around(texel: vec2<i32>, centre: vec4<f32>, p: vec3<f32>, n: vec3<f32>, oct: vec2<f32>) -> Around {
    let last = vec2<i32>(textureDimensions(current)) - 1;
    var out = Around(centre, centre, centre);
    let tolerance = bilateral_tolerance(params.radius);
    var sum = vec4<f32>(0.0);
    var total = 0.0;
    for (var y = -1; y <= 1; y += 1) {
        for (var x = -1; x <= 1; x += 1) {
            let t = clamp(texel + vec2<i32>(x, y), vec2<i32>(0), last);
            let at = surface_pixel(t);
            let d = load_depth(at);
            let v = textureLoad(current, t, 0);
            // (Selects, not a `continue`: a CPU rasteriser pays for a branch its lanes disagree on.)
            let on_surface = d > 0.0 && finite4(v);
            out.lo = select(out.lo, min(out.lo, v), on_surface);
            out.hi = select(out.hi, max(out.hi, v), on_surface);
            if BLUR {
                let q = view_position(vec2<f32>(at) + 0.5, d);
                let oct_q = octahedral_code(textureLoad(g_normal, at, 0).r);
                let w = f32((2 - abs(x)) * (2 - abs(y))) * bilateral_weight(p, n, oct, q, oct_q, tolerance);
                sum += select(vec4<f32>(0.0), w * v, on_surface);
                total += select(0.0, w, on_surface);
            }
        }
    }
    if BLUR && total > 0.0 {
        out.value = sum / total;
    }
    return out;
}

// What the history holds of a pixel's surface: its average, the frames that average holds (0:
// nothing), and how far (in pixels) the surface moved on screen since the last frame.
struct Past {
    value: vec4<f32>,
    held: f32,
    moved: f32,
}

// The camera has not moved: texel `texel` holds the same surface exactly when it holds the same
// depth (the scene is static).
fn past_in_place(texel: vec2<i32>, depth: f32) -> Past {
    var past = Past(vec4<f32>(0.0), 0.0, 0.0);
    let s = textureLoad(history_surface, texel, 0);
    let value = textureLoad(history, texel, 0);
    if bitcast<f32>(s.x) == depth && finite4(value) {
        past.value = value;
        past.held = f32(s.y >> 24u);
    }
    return past;
}

// The camera moved: the surface at view point `p` (pixel centre `position`, `clip` where the last
// frame's camera put it, `n_then` its normal in the last frame's view) seen there again,
// from the history texels there that hold it. Catmull-Rom weights over the 4x4 texels around the
// point but its corners, from the taps that hold this surface (renormalised; below half the weight, the history
// is dropped): a history resampled every frame on a grid two pixels wide loses its detail under
// bilinear weights (turning 1° a frame, SSAO's AO near contacts came out 5-13% further from the
// truth). The frames held are the bilinear average of the 2x2 around the point.
fn past_reprojected(clip: vec4<f32>, position: vec2<f32>, p: vec3<f32>, n_then: vec3<f32>) -> Past {
    var past = Past(vec4<f32>(0.0), 0.0, 0.0);
    let ndc = clip.xy / clip.w;
    let was = vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - 0.5 * ndc.y) * frame.viewport.xy;
    past.moved = length(was - position);
    // In the history's texels, texel t at t.
    let at = texel_coordinate(was);
    let base = floor(at);
    let f = at - base;
    // This pixel's surface (point and unit normal) in the previous view, where the taps are.
    let then = Then(
        (frame.view_to_previous_view * vec4<f32>(p, 1.0)).xyz,
        n_then,
        safe_normalize(n_then, n_then),
        max(PLANE_RADII * params.radius, 1e-6 * -p.z),
        vec2<i32>(textureDimensions(history_surface)),
    );
    let c0 = f * (-0.5 + f * (1.0 - 0.5 * f));
    let c1 = 1.0 + f * f * (-2.5 + 1.5 * f);
    let c2 = f * (0.5 + f * (2.0 - 1.5 * f));
    let c3 = f * f * (-0.5 + 0.5 * f);
    let g = 1.0 - f;
    // The 4x4 taps but its corners (their weight is at most 0.006 of the sum), row by row, each
    // written out with its weights (no tap chooses its place and weights by selects); the middle
    // four also carry their bilinear weights.
    let b = vec2<i32>(base) - 1;
    var taken = Taken(vec4<f32>(0.0), 0.0, 0.0, 0.0);
    take(&taken, then, b + vec2<i32>(1, 0), c1.x * c0.y, 0.0);
    take(&taken, then, b + vec2<i32>(2, 0), c2.x * c0.y, 0.0);
    take(&taken, then, b + vec2<i32>(0, 1), c0.x * c1.y, 0.0);
    take(&taken, then, b + vec2<i32>(1, 1), c1.x * c1.y, g.x * g.y);
    take(&taken, then, b + vec2<i32>(2, 1), c2.x * c1.y, f.x * g.y);
    take(&taken, then, b + vec2<i32>(3, 1), c3.x * c1.y, 0.0);
    take(&taken, then, b + vec2<i32>(0, 2), c0.x * c2.y, 0.0);
    take(&taken, then, b + vec2<i32>(1, 2), c1.x * c2.y, g.x * f.y);
    take(&taken, then, b + vec2<i32>(2, 2), c2.x * c2.y, f.x * f.y);
    take(&taken, then, b + vec2<i32>(3, 2), c3.x * c2.y, 0.0);
    take(&taken, then, b + vec2<i32>(1, 3), c1.x * c3.y, 0.0);
    take(&taken, then, b + vec2<i32>(2, 3), c2.x * c3.y, 0.0);
    if taken.weight > 0.5 && taken.held_weight > 1e-3 {
        past.value = taken.value / taken.weight;
        past.held = taken.held / taken.held_weight;
    }
    return past;
}

// A pixel's surface in the last frame's view: its point, its normal (and that normalised: its
// plane), and how far off that plane a history texel may lie and still hold it.
struct Then {
    p: vec3<f32>,
    n: vec3<f32>,
    plane_normal: vec3<f32>,
    tolerance: f32,
    // The history's size in texels (the taps outside it are dropped).
    texels: vec2<i32>,
}

// The history taps that hold the surface, summed: their values and weights, and their frames
// held under the bilinear weights.
struct Taken {
    value: vec4<f32>,
    weight: f32,
    held: f32,
    held_weight: f32,
}

// Adds history texel `tap` to `taken` with weight `w` (and `bilinear` for its frames held), if it
// holds the surface `then`: its own surface point in the previous view, from its pixel and depth
// through the previous projection (a rigid turn from world space keeps the plane's distances),
// lies on that surface's plane and its normal agrees.
fn take(taken: ptr<function, Taken>, then: Then, tap: vec2<i32>, w: f32, bilinear: f32) {
    let inside = all(tap >= vec2<i32>(0)) && all(tap < then.texels);
    let at = clamp(tap, vec2<i32>(0), then.texels - 1);
    let s = textureLoad(history_surface, at, 0);
    let frames = f32(s.y >> 24u);
    let pp = frame.previous_projection;
    let uv = (vec2<f32>(surface_pixel(at)) + 0.5) / frame.viewport.xy;
    let z = -pp.w / (bitcast<f32>(s.x) + pp.z);
    let q = vec3<f32>((uv.x * 2.0 - 1.0) * -z * pp.x, (1.0 - uv.y * 2.0) * -z * pp.y, z);
    let value = textureLoad(history, at, 0);
    let same = abs(dot(then.plane_normal, q - then.p)) <= then.tolerance && dot(unpack_normal(s.y), then.n) >= MIN_NORMAL_COS;
    // (Selects, not early returns: a CPU rasteriser pays for a branch its lanes disagree on.)
    let kept = inside && frames > 0.0 && same && finite4(value);
    (*taken).value += select(vec4<f32>(0.0), w * value, kept);
    (*taken).weight += select(0.0, w, kept);
    (*taken).held += select(0.0, bilinear * frames, kept);
    (*taken).held_weight += select(0.0, bilinear, kept);
}

// How far (degrees) a moving view's kept frames may have looked at a surface from: screen-space
// occlusion depends on the viewpoint (what the screen shows beside a surface, and its horizon),
// so a history of frames seen from elsewhere is an error of its own, not an average. At 1° a frame
// the motion cap binds (8 frames, SSAO's 4); at 10° a frame nothing is kept (but on a few texels
// far from both eyes, which see them 6-8° apart: two frames).
// Set from MAX_HISTORY_TURN_DEG (src/render/settings.rs), whose blur rule depends on it.
override MAX_HISTORY_TURN: f32;

// The frames a surface at view point `p` may keep: MAX_HISTORY_TURN over the angle between the
// directions to this frame's and the last frame's eye (at least one: this frame).
fn frames_within_turn(p: vec3<f32>) -> f32 {
    let now = safe_normalize(-p, vec3<f32>(0.0, 0.0, 1.0));
    let then = safe_normalize(frame.previous_eye - p, now);
    let turn = degrees(acos(clamp(dot(now, then), -1.0, 1.0)));
    return max(floor(MAX_HISTORY_TURN / max(turn, 1e-3)), 1.0);
}

@fragment
fn fs_main(in: FullscreenOut) -> TemporalOut {
    // This texel of the pass's targets, and the full-resolution pixel (centre `position`) whose
    // surface it holds.
    let texel = vec2<i32>(in.position.xy);
    let pixel = surface_pixel(texel);
    let position = vec2<f32>(pixel) + 0.5;
    var out: TemporalOut;
    out.shown = textureLoad(current, texel, 0);
    out.history = out.shown;
    out.surface = vec4<u32>(0u);
    let depth = load_depth(pixel);
    // The sky keeps nothing.
    if depth <= 0.0 {
        return out;
    }
    let p = view_position(position, depth);
    let normal_bits = textureLoad(g_normal, pixel, 0).r;
    let view_normal = unpack_normal(normal_bits);
    let samples = around(texel, out.shown, p, view_normal, octahedral_code(normal_bits));
    let now = samples.value;
    // A non-finite value is passed on as it is, and never kept.
    if !finite4(now) {
        out.shown = now;
        out.history = now;
        return out;
    }
    let world = (frame.view_to_world * vec4<f32>(p, 1.0)).xyz;
    // The normal as the last frame's view saw it (the taps' surfaces are compared there).
    let n_then = (frame.view_to_previous_view * vec4<f32>(view_normal, 0.0)).xyz;

    var past = Past(vec4<f32>(0.0), 0.0, 0.0);
    if !CAMERA_MOVED && params.history_frames > 0u {
        past = past_in_place(texel, depth);
    }
    let clip = frame.previous_world_to_clip * vec4<f32>(world, 1.0);
    if CAMERA_MOVED && params.history_frames > 0u && clip.w > 0.0 {
        past = past_reprojected(clip, position, p, n_then);
    }

    let still = past.moved < STILL_PIXELS;
    var most = max(f32(select(params.motion_accumulate, params.accumulate, still)), 1.0);
    if CAMERA_MOVED && !still {
        most = min(most, frames_within_turn(p));
    }
    var frames = min(past.held + 1.0, most);
    var result = now;
    if past.held > 0.0 {
        if still && past.held >= most {
            // A still pixel that holds its `accumulate` frames keeps their mean as it is: the
            // converged image is the exact mean of those frames, as a headless capture makes it.
            result = past.value;
            frames = most;
        } else {
            var kept = past.value;
            if CAMERA_MOVED && !still {
                kept = clamp(kept, samples.lo, samples.hi);
            }
            result = mix(kept, now, 1.0 / frames);
        }
    }
    out.shown = result;
    out.history = result;
    out.surface = vec4<u32>(bitcast<u32>(depth), (normal_bits & 0xffffffu) | (u32(round(frames)) << 24u), 0u, 0u);
    return out;
}
