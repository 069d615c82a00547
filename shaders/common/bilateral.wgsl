// The blur's bilateral weight (shaders/blur.wgsl, and the temporal pass where it blurs the samples
// as it reads them): a neighbour counts as much as its surface lies on the centre's.

// How well two normals agree, from their octahedral codes rather than decoded vectors (decoding
// 16 neighbours was a third of the blur's time on a CPU rasteriser). With δ their L1 distance in
// octahedral units (about the angle in radians between facing normals), 1 - 3δ², clamped: 1 for
// equal normals, 0.6 at 30°, 0.25 at 45°, 0 from about 55° — close to the cos⁴ it replaces
// (0.56, 0.25, 0.06 at 60°).
fn normal_agreement(a: vec2<f32>, b: vec2<f32>) -> f32 {
    let spread = octahedral_distance(a, b);
    return max(1.0 - 3.0 * spread * spread, 0.0);
}

// The plane distance a neighbour may lie off the centre's tangent plane before it counts for
// nothing: a quarter of the sampling radius (never 0: a radius of 0 still blurs flat surfaces).
fn bilateral_tolerance(radius: f32) -> f32 {
    return max(0.25 * radius, 1e-30);
}

// The weight of the neighbour at view point `q` with normal code `oct_q` for the centre at `p`
// with unit normal `n` and code `oct_p`: falling linearly with its distance from the centre's
// tangent plane, times how well the normals agree.
fn bilateral_weight(p: vec3<f32>, n: vec3<f32>, oct_p: vec2<f32>, q: vec3<f32>, oct_q: vec2<f32>, tolerance: f32) -> f32 {
    let plane = abs(dot(n, q - p));
    return max(1.0 - plane / tolerance, 0.0) * normal_agreement(oct_p, oct_q);
}
