// The G-buffer as the screen-space passes read it (bind group 1, bindings 0-2), and the
// surface's own normal from the depth buffer (view-space positions: common/unproject.wgsl).

// Each include declares what it uses: `frame` (bind group 0) comes from uniforms.wgsl. Bindings
// 0-2 of group 1 are fixed here; each pass that includes this file declares the G-buffer as its
// first three reads (src/render/passes/<pass>.rs, checked against this file by a test).
#include "common/uniforms.wgsl"
#include "common/surface_pack.wgsl"
#include "common/unproject.wgsl"

@group(1) @binding(0) var g_albedo: texture_2d<f32>;
// Normal and shininess packed in one u32 (see surface_pack.wgsl).
@group(1) @binding(1) var g_normal: texture_2d<u32>;
// Depth is bound as an unfilterable float texture rather than `texture_depth_2d`: WebGPU allows it
// for depth32float, and wgpu's GL backend cannot translate `textureLoad` from a depth texture.
@group(1) @binding(2) var g_depth: texture_2d<f32>;

// Reverse-Z depth at `pixel`: 0 where nothing was drawn (the sky), larger nearer the camera.
fn load_depth(pixel: vec2<i32>) -> f32 {
    return textureLoad(g_depth, pixel, 0).r;
}

// Unit view-space normal at `pixel`.
fn load_normal(pixel: vec2<i32>) -> vec3<f32> {
    return unpack_normal(textureLoad(g_normal, pixel, 0).r);
}

// Normal in xyz and shininess in w at `pixel`.
fn load_surface(pixel: vec2<i32>) -> vec4<f32> {
    return surface_of(textureLoad(g_normal, pixel, 0).r);
}

// Normal in xyz and shininess in w of the G-buffer's packed `bits` (for a pass that also keeps
// the bits themselves).
fn surface_of(bits: u32) -> vec4<f32> {
    return vec4<f32>(unpack_normal(bits), unpack_shininess(bits));
}

// The surface's own unit normal at `pixel` (view space, towards the camera) from the depth
// buffer: the cross product of the position's steps to a horizontal and a vertical neighbour,
// each on the side whose depth continues the surface best (the nearer in view z), so an edge of
// the surface does not bend it. `p` is the pixel's position; `fallback` is returned where no
// neighbour has a surface.
fn depth_normal(pixel: vec2<i32>, p: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    return depth_normal_in(pixel, p, fallback, projection_terms(), frame.viewport);
}

// `depth_normal` with the frame's projection terms and viewport (width, height, 1/width,
// 1/height) given, for a pass that has them as varyings.
fn depth_normal_in(pixel: vec2<i32>, p: vec3<f32>, fallback: vec3<f32>, k: vec4<f32>, viewport: vec4<f32>) -> vec3<f32> {
    let last = vec2<i32>(viewport.xy) - vec2<i32>(1);
    var steps: array<vec3<f32>, 2>;
    for (var axis = 0; axis < 2; axis += 1) {
        var best = vec3<f32>(0.0);
        var best_gap = 3.4e38;
        for (var side = -1; side <= 1; side += 2) {
            var q = pixel;
            q[axis] += side;
            if any(q < vec2<i32>(0)) || any(q > last) {
                continue;
            }
            let d = load_depth(q);
            if d <= 0.0 {
                continue;
            }
            let s = unproject(vec2<f32>(q) + 0.5, d, k, viewport.zw);
            let gap = abs(s.z - p.z);
            if gap < best_gap {
                best_gap = gap;
                best = (s - p) * f32(side);
            }
        }
        steps[axis] = best;
    }
    let n = cross(steps[0], steps[1]);
    if dot(n, n) <= 0.0 || !(dot(n, n) < 3.4e38) {
        return fallback;
    }
    let unit = normalize(n);
    return select(-unit, unit, dot(unit, -p) >= 0.0);
}
