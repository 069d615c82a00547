// The samples' grid: the targets the sampling pass, its blur and the temporal pass write. At
// half resolution they are half the width and height, each texel (x, y) standing for the
// full-resolution pixel (2x, 2y) (an upsample follows); the composite then reads half-size
// samples, and the lighting pass the last frame's half-size sky. One override for all of them,
// set from the plan; the passes map between their texels and the full-resolution pixels with
// the functions below.
override HALF_RESOLUTION: bool = false;

// Full-resolution pixels across one texel of the targets where the samples are: 2, or 1.
fn sample_step() -> i32 {
    return select(1, 2, HALF_RESOLUTION);
}

// The full-resolution pixel (its G-buffer) that texel `t` of those targets holds.
fn surface_pixel(t: vec2<i32>) -> vec2<i32> {
    return min(sample_step() * t, vec2<i32>(frame.viewport.xy) - 1);
}

// The texel of those targets that holds the full-resolution pixel `pixel` (or the pixel that
// shares its texel).
fn sample_texel(pixel: vec2<i32>) -> vec2<i32> {
    return pixel / sample_step();
}

// A full-resolution position (pixel centres at i + 0.5) in the texels of those targets, texel t
// at t: where a filter over them is centred.
fn texel_coordinate(position: vec2<f32>) -> vec2<f32> {
    return (position - 0.5) / f32(sample_step());
}
