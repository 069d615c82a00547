// View-space position reconstructed from reverse-Z depth, from the frame's projection alone (no
// binding beyond the frame uniforms, so the G-buffer pass and the tone map use it as the
// screen-space passes do).

#include "common/uniforms.wgsl"

// View-space position of the surface at `pixel` with depth `depth` (> 0).
fn view_position(pixel: vec2<f32>, depth: f32) -> vec3<f32> {
    return unproject(pixel, depth, projection_terms(), frame.viewport.zw);
}

// What `unproject` needs of view_to_clip: a = [2][2], b = [3][2], and the x and y scales [0][0],
// [1][1].
fn projection_terms() -> vec4<f32> {
    let m = frame.view_to_clip;
    return vec4<f32>(m[2][2], m[3][2], m[0][0], m[1][1]);
}

// The view-space position at `pixel` (in pixels; `inv_size` the image's 1/width, 1/height) with
// depth `depth` > 0, from `projection_terms`. With z_clip = a·z + b and w = -z,
// depth = -a - b / z, so z = -b / (depth + a).
fn unproject(pixel: vec2<f32>, depth: f32, k: vec4<f32>, inv_size: vec2<f32>) -> vec3<f32> {
    let z = -k.y / max(depth + k.x, 1e-30);
    let uv = pixel * inv_size;
    let ndc = vec2<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0);
    return vec3<f32>(ndc.x * -z / k.z, ndc.y * -z / k.w, z);
}
