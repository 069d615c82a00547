// The thickness layer's codes (src/scene/thickness.rs) and the depth a surface spans, shared by
// the G-buffer, which writes them, the march, which takes the depth, and the thickness view.
//
// The layer is the depth's f32 bits with its low 8 replaced: bits 0-2 the material's thickness
// class (7 the scene's default slab, 0 a sheet, k in 1-6 the default times 2^(k − 7)), bits 3-7
// the tilt of the surface from the view ray, as an index j of tan θ (0: face-on; else
// 2^((j − 16) / 3), from 1/32 to 32). A surface of thickness t tilted by θ spans, over a step
// w wide across the screen, (t + w/2 · sin θ) / cos θ = t · sec θ + w/2 · tan θ along the view ray
// behind its sample: a sheet seen face-on next to nothing (its holes stay open), one seen
// edge-on its footprint. The march reads it all in the one load that gives the depth.

// The low bits of the layer that hold the class and the tilt.
const THICKNESS_CODE_MASK: u32 = 255u;
// The class of the scene's default slab.
const DEFAULT_THICKNESS_CLASS: u32 = 7u;

// The code of a surface of class `thickness_class` whose normal makes cosine `c` with the view
// ray (its tilt index: the nearest step of tan θ on the scale above).
fn thickness_code_of(thickness_class: u32, c: f32) -> u32 {
    let cos_theta = clamp(c, 1e-4, 1.0);
    let tan_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0)) / cos_theta;
    var tilt = 0u;
    if tan_theta >= exp2(-15.5 / 3.0) {
        tilt = u32(clamp(round(16.0 + 3.0 * log2(tan_theta)), 1.0, 31.0));
    }
    return thickness_class | (tilt << 3u);
}

// Whether `code` is a thin class (a sheet, or below the default): the march takes such a sample's
// own span, and its far side sends bounce.
fn is_thin(code: u32) -> bool {
    return (code & 7u) < DEFAULT_THICKNESS_CLASS;
}

// The share of the scene's default thickness the class in `code` stands for: 2^(k − 7) from the
// exponent bits (the march decodes every depth sample's code: a float built from integers, not
// exp2's polynomial).
fn thickness_ratio(code: u32) -> f32 {
    let thickness_class = code & 7u;
    return select(bitcast<f32>((thickness_class + 120u) << 23u), 0.0, thickness_class == 0u);
}

// tan θ of the tilt in `code`, 2^((j − 16) / 3), as 2^(q − 16) · 2^(r / 3) with j + 32 = 3q + r:
// the power of two from the exponent bits, the third from one of three constants.
fn code_tan(code: u32) -> f32 {
    let tilt = (code >> 3u) & 31u;
    let q = (tilt + 32u) / 3u;
    let r = tilt + 32u - 3u * q;
    let third = select(select(1.0, 1.2599210, r == 1u), 1.5874011, r == 2u);
    return select(bitcast<f32>((q + 111u) << 23u) * third, 0.0, tilt == 0u);
}

// How deep along its view ray the surface of `code` spans over a footprint `footprint` wide
// (view units), with `default_thickness` the scene's (a class's unit); the default itself for
// the default class.
fn depth_extent(code: u32, footprint: f32, default_thickness: f32) -> f32 {
    let t = code_tan(code);
    let own = thickness_ratio(code) * default_thickness * sqrt(1.0 + t * t) + 0.5 * footprint * t;
    return select(default_thickness, own, is_thin(code));
}

// The width in view units of `pixels` pixels at view depth `z` (< 0).
fn pixel_footprint(pixels: f32, z: f32) -> f32 {
    return pixels * -z / (0.5 * frame.viewport.y * frame.view_to_clip[1][1]);
}

// The depth with each surface's extent behind it (far_side.rs EXTENT_LAYER, written by the
// lighting pass where there is a far side): the depth's bits with their low nine replaced. Bit 8
// set: bits 0-7 code the distance along the view ray to the far side's face behind the surface
// as a share of the surface's own distance from the eye, 2^((c − 192) / 16) (1/4096 to 15, in
// steps of 4.4%: relative, so the lighting pass needs no scene length); clear: bits 0-7 are the
// thickness layer's code (a sheet, a surface with nothing behind it).
const EXTENT_CODE_MASK: u32 = 511u;
const EXTENT_FLAG: u32 = 256u;

// The extent code of a distance `t` behind a surface `distance` from the eye.
fn extent_code(t: f32, distance: f32) -> u32 {
    let octaves = log2(max(t, 1e-30) / max(distance, 1e-30));
    return EXTENT_FLAG | u32(clamp(round(16.0 * octaves) + 192.0, 0.0, 255.0));
}

// The distance an extent code (EXTENT_FLAG set) stands for behind a surface `distance` from the eye.
fn extent_of(code: u32, distance: f32) -> f32 {
    return distance * exp2((f32(code & 255u) - 192.0) / 16.0);
}
