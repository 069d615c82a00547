// Skybox: drawn where the depth buffer still holds the far plane (0 in reverse-Z), by a
// full-screen triangle at depth 0 with a `GreaterEqual` test (0 >= stored passes only where
// stored is 0), so covered pixels cost nothing.

#include "common/uniforms.wgsl"
#include "common/fullscreen.wgsl"
#include "common/sky.wgsl"
#include "common/tone_curve.wgsl"

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4<f32> {
    return vec4<f32>(background(in.uv), 1.0);
}

// A display plan's sky, drawn by the G-buffer pass into the albedo of the pixels nothing covers:
// the colour the composite shows there as it is (exposure and tone curve applied; the target's
// sRGB encoding, like the output's, done by the format).
@fragment
fn fs_display(in: FullscreenOut) -> @location(0) vec4<f32> {
    return vec4<f32>(tone_map(background(in.uv) * frame.display_scale), 0.0);
}
