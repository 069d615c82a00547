// The thickness layer's codes (src/scene/thickness.rs) and the depth a thin surface spans, shared
// by the march, which takes it, and the thickness view, which shows it.

// The low bits of the thickness layer that hold a material's code (the rest are its depth's).
const THICKNESS_CODE_MASK: u32 = 63u;
// The code of the scene's default slab.
const DEFAULT_THICKNESS_CODE: u32 = 63u;

// The share of the scene's default thickness code `code` stands for: 0 a sheet (a cut-out),
// 2^((code − 62) / 4) a thin solid, 1 the default (src/scene/thickness.rs `thickness_ratio`).
fn thickness_ratio(code: u32) -> f32 {
    if code >= DEFAULT_THICKNESS_CODE {
        return 1.0;
    }
    return select(exp2((f32(code) - 62.0) * 0.25), 0.0, code == 0u);
}

// How deep along the view ray `v` (unit, towards the eye) a surface of thickness `thickness` with
// normal `n` lies over a footprint `footprint` wide across the screen: a slab crossed at angle θ
// to its normal is thickness / cos θ deep, and a surface tilted by θ recedes by tan θ per unit
// across, half the footprint of it behind the sample at its middle. So a sheet seen face-on
// spans next to nothing (its holes stay open) and one seen edge-on its footprint.
fn depth_extent(thickness: f32, footprint: f32, n: vec3<f32>, v: vec3<f32>) -> f32 {
    let c = max(abs(dot(n, v)), 0.05);
    return (thickness + 0.5 * footprint * sqrt(1.0 - c * c)) / c;
}

// The width in view units of `pixels` pixels at view depth `z` (< 0).
fn pixel_footprint(pixels: f32, z: f32) -> f32 {
    return pixels * -z / (0.5 * frame.viewport.y * frame.view_to_clip[1][1]);
}
