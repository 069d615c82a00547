// The march's slices and sectors (shaders/common/march.wgsl): the hemisphere is cut into slices about the
// view vector, and a slice into 32 sectors of angle, one bit each, integrated in four groups of
// eight; a slice's plane, its angles and its groups' measures.

// Sectors per slice (one bit each: what occludes is resolved to π/32) and the groups the sky is
// read and the weights are integrated for (a sky read per group, not per sector: 4 reads per
// slice instead of 32; a group's partial visibility scales its read). Fewer groups cost fewer
// cube-map reads and blur the sky's directions within a slice more.
const SECTORS: u32 = 32u;
// (group_counts counts the groups as the mask's bytes: 4 groups of 8.)
const GROUPS: u32 = 4u;
const PER_GROUP: u32 = 8u;
const HALF_PI: f32 = 1.5707963;

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

// The cosine-weighted measure of each of the four sector groups from `lo` (γ − π/2), times |n_p|
// (the boundaries' cosines are those of quarter turns).
fn group_measures(lo: f32, turned: vec2<f32>, sin_gamma: f32, n_len: f32) -> vec4<f32> {
    let width = PI / f32(GROUPS);
    let f_zero = -0.25 * turned.x;
    let cos_terms = array<f32, 5>(-turned.x, turned.y, turned.x, -turned.y, -turned.x);
    var weights: vec4<f32>;
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
    return weights;
}

// One slice of the hemisphere: its plane, the normal's angle in it, the sectors above the
// surface's own plane, and the cosine-weighted measure of each sector group.
struct Slice {
    // Screen direction (x right, y down) and the view-space direction it moves along.
    screen_dir: vec2<f32>,
    t: vec3<f32>,
    // |n_p|: the slice is skipped where the normal is (almost) perpendicular to its plane.
    n_len: f32,
    gamma: f32,
    // The cosine and sine of γ as the sectors place it (fast_atan2's angle, within 0.004 rad of
    // the normal's own): every group boundary's and group middle's follow from them.
    turned: vec2<f32>,
    // The sectors above the surface's own plane: all of them unless the normals are mapped.
    inside: u32,
    // Each group's measure, times |n_p|.
    weights: vec4<f32>,
    // NORMAL_MAPPED: the groups the surface's plane cuts (bit g), and for each the cosine and
    // sine of the turn from the group's middle to the middle of its sectors inside, where its sky
    // is read.
    cut: u32,
    cut_turns: array<vec2<f32>, 4>,
}

// The slice at screen angle `phi` of the hemisphere about the view vector `v`, for shading normal
// `n` and the surface's own plane's normal `n_g`.
fn slice_at(n: vec3<f32>, n_g: vec3<f32>, v: vec3<f32>, phi: f32) -> Slice {
    var s: Slice;
    s.screen_dir = vec2<f32>(cos(phi), sin(phi));
    let axis = vec3<f32>(s.screen_dir.x, -s.screen_dir.y, 0.0);
    s.t = safe_normalize(axis - v * dot(axis, v), vec3<f32>(1.0, 0.0, 0.0));
    let plane_normal = cross(v, s.t);
    let n_p = n - plane_normal * dot(n, plane_normal);
    s.n_len = length(n_p);
    if s.n_len < 1e-6 {
        return s;
    }
    s.gamma = slice_angle(n_p, v, s.t);
    let sin_gamma = dot(n_p, s.t) / s.n_len;
    s.turned = vec2<f32>(cos(s.gamma), sin(s.gamma));
    s.inside = 0xffffffffu;
    if NORMAL_MAPPED {
        let ng_p = n_g - plane_normal * dot(n_g, plane_normal);
        if dot(ng_p, ng_p) > 1e-12 {
            let gamma_g = slice_angle(ng_p, v, s.t);
            let first = sector_of(gamma_g - HALF_PI, s.gamma);
            let last = sector_of(gamma_g + HALF_PI, s.gamma);
            s.inside = select(0u, bit_range(first, last), first <= last);
        }
    }
    s.weights = group_measures(s.gamma - HALF_PI, s.turned, sin_gamma, s.n_len);
    // (SSAO alone keeps the groups' shares: its AO moves by 1-2% for 8% of its pass.)
    if NORMAL_MAPPED && HAS_DO && s.inside != 0xffffffffu {
        inside_measures(&s, sin_gamma);
    }
    return s;
}

// The measure of the angles [a, b] about the shading normal at γ (`turned` its cosine and
// sine), times |n_p| (`n_len`), as `group_measures` gives it for a group's.
fn measure_between(a: f32, b: f32, gamma: f32, turned: vec2<f32>, sin_gamma: f32, n_len: f32) -> f32 {
    let f_a = antiderivative(a, cos(2.0 * a - gamma), sin_gamma);
    let f_b = antiderivative(b, cos(2.0 * b - gamma), sin_gamma);
    var w = abs(f_b - f_a);
    if a < 0.0 && b > 0.0 {
        w = f_a + f_b + 0.5 * turned.x;
    }
    return n_len * w;
}

// Where the surface's own plane cuts the shading normal's hemisphere: a group the plane cuts
// keeps the measure of its sectors above the plane (those nearest the normal, which weigh more
// than the ones cut off), spread over them so that a sum's count of its inside sectors times the
// group's weight over PER_GROUP is that measure, and reads its sky in the middle of those
// sectors, not its own (which may lie below the plane). Taking the group's whole measure by the
// share of its sectors inside, and its sky from its middle, underweighed the directions just
// above the plane and read the sky from below it: on a floor whose map leans its normals 40-75°
// under a sky bright only in a band above the horizon, SSDO gave 0.60-0.99 of the truth's light,
// 0.87-1.08 now (docs/accuracy.md).
fn inside_measures(s: ptr<function, Slice>, sin_gamma: f32) {
    let counts = group_counts((*s).inside);
    let lo = (*s).gamma - HALF_PI;
    let sector = PI / f32(SECTORS);
    var weights = (*s).weights;
    for (var g = 0u; g < GROUPS; g += 1u) {
        let count = counts[g];
        if count > 0.0 && count < f32(PER_GROUP) {
            let first = firstTrailingBit(((*s).inside >> (g * PER_GROUP)) & 0xffu);
            let a = lo + f32(g * PER_GROUP + first) * sector;
            let w = measure_between(a, a + count * sector, (*s).gamma, (*s).turned, sin_gamma, (*s).n_len);
            weights[g] = w * f32(PER_GROUP) / count;
            // The turn from the group's middle to theirs, |Δ| ≤ 3.5 sectors: by its series (to 1e-5).
            let d = (f32(first) + 0.5 * count - 0.5 * f32(PER_GROUP)) * sector;
            let d2 = d * d;
            (*s).cut |= 1u << g;
            (*s).cut_turns[g] = vec2<f32>(1.0 - d2 * (0.5 - d2 / 24.0), d * (1.0 - d2 * (1.0 / 6.0 - d2 / 120.0)));
        }
    }
    (*s).weights = weights;
}

// Where group `g` of slice `s` reads its sky, turned from γ (`turn`: the cosine and sine of its
// middle's angle from γ): its middle, or under NORMAL_MAPPED the middle of its sectors above the
// surface's plane where the plane cuts it.
fn read_turn(s: Slice, g: u32, turn: vec2<f32>) -> vec2<f32> {
    if NORMAL_MAPPED && ((s.cut >> g) & 1u) != 0u {
        let d = s.cut_turns[g];
        return vec2<f32>(turn.x * d.x - turn.y * d.y, turn.y * d.x + turn.x * d.y);
    }
    return turn;
}
