// The sky passes' entry points: the march (common/march.wgsl) from a surface that sends bounce
// rather than from a receiver, one slice each, at a fraction of the screen's resolution.

#include "common/march.wgsl"

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

// The far-sky pass (far_sky.rs, at a quarter of the width and height, as fs_sender with
// SENDER_SHIFT 2): the sky the far side layer's surface at this cell's pixel sees through one
// slice, and its open share. It faces away from the eye, so its hemisphere's angles are measured
// about its eye ray's continuation: the depth samples behind it on the screen occlude it, those
// in front (its own solid's near side) lie below its plane.
@fragment
fn fs_far_sender(in: FullscreenOut) -> @location(0) vec4<f32> {
    let cell = vec2<i32>(in.position.xy);
    let scale = 1 << SENDER_SHIFT;
    // The first pixel of the cell's block that holds a far surface, from its middle out: a cell
    // at a far surface's edge still measures it for the pixels of its block that hold it.
    let block = vec2<i32>(scale * cell);
    let last = vec2<i32>(frame.viewport.xy) - 1;
    var pixel = vec2<i32>(-1);
    var far = vec4<u32>(0u);
    // From the middle out: offsets 1, 2, 0, 3 on each axis (a 2-wide block's 1, 0 among them).
    var middle_out = array<i32, 4>(1, 2, 0, 3);
    if scale == 2 {
        middle_out = array<i32, 4>(1, 0, 1, 0);
    }
    for (var k = 0; k < scale * scale && pixel.x < 0; k += 1) {
        let order = vec2<i32>(middle_out[k % scale], middle_out[k / scale]);
        let at = min(block + order, last);
        let f = textureLoad(far_surface, at, 0);
        if f.z != 0u {
            pixel = at;
            far = f;
        }
    }
    if pixel.x < 0 {
        return vec4<f32>(0.0);
    }
    let position = vec2<f32>(pixel) + 0.5;
    let surface = view_position(position, bitcast<f32>(far.z));
    let n = unpack_normal(far.x);
    return sender_value(march_receiver(receiver_of(position, surface, n, n, cell, true), 1u));
}
