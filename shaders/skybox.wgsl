// Skybox: drawn where the depth buffer still holds the far plane (0 in reverse-Z), by a
// full-screen triangle at depth 0 with a `GreaterEqual` test (0 >= stored passes only where
// stored is 0), so covered pixels cost nothing.

#include "common/uniforms.wgsl"
#include "common/fullscreen.wgsl"
#include "common/sky.wgsl"

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4<f32> {
    return vec4<f32>(background(in.uv), 1.0);
}
