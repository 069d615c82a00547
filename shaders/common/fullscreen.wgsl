// The full-screen triangle's vertex stage for the passes that need nothing but their pixel
// (common/fullscreen_triangle.wgsl). uv is (0,0) at the top-left of the target.

#include "common/fullscreen_triangle.wgsl"

struct FullscreenOut {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

@vertex
fn fullscreen_vs(@builtin(vertex_index) index: u32) -> FullscreenOut {
    var out: FullscreenOut;
    out.uv = fullscreen_uv(index);
    out.position = fullscreen_clip(out.uv);
    return out;
}
