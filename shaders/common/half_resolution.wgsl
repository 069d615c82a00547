// Half resolution: the sampling pass, its blur and the temporal pass run at half width and
// height, each pixel (x, y) standing for the full-resolution pixel (2x, 2y) (an upsample
// follows); the composite then reads half-size samples, and the lighting pass the last frame's
// half-size sky. One override for all of them, set from the plan.
override HALF_RESOLUTION: bool = false;

// The full-resolution pixel (its G-buffer) that pixel `t` of a half-size target holds; `t` itself
// at full resolution.
fn surface_pixel(t: vec2<i32>) -> vec2<i32> {
    if HALF_RESOLUTION {
        return min(2 * t, vec2<i32>(frame.viewport.xy) - 1);
    }
    return t;
}
