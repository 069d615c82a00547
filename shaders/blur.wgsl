// Denoise of the AO / DO buffers over a 4x4 window: the window of the 4x4 rotation tile, so on a
// flat surface every one of the 16 rotations is averaged and the tile pattern cancels.
//
//  * BILATERAL (default): each neighbour is weighted by how close it lies to the centre pixel's
//    tangent plane (relative to the sampling radius) and how well the normals agree, so the blur
//    does not cross silhouettes or creases (no halos).
//  * otherwise the classic 4x4 box blur of the classic SSAO chapter.
// Neighbours on the sky or holding non-finite values are left out.
// In a half-resolution plan the blur runs on the half-size samples, before the upsample: its pixel
// (x, y) is the sample taken at the full-resolution pixel (2x, 2y), whose G-buffer it reads, and
// its 4x4 window is the rotation tile the samples were taken with (sampling_params.wgsl).

#include "common/uniforms.wgsl"
#include "common/gbuffer_read.wgsl"
#include "common/filter_params.wgsl"
#include "common/fullscreen.wgsl"
#include "common/bilateral.wgsl"

@group(1) @binding(3) var<uniform> params: FilterParams;
// The sampling pass's output: AO (SSAO, r) or DO + AO (SSDO and both, rgb + a).
@group(1) @binding(4) var input: texture_2d<f32>;

override BILATERAL: bool = true;
// On the half-size samples, in a half-resolution plan.
#include "common/sample_grid.wgsl"
// The input is DO + AO (SSDO, SSAO+SSDO) rather than the one-channel AO target (SSAO).
override HAS_DO: bool = true;

fn finite4(v: vec4<f32>) -> bool {
    return all(abs(v) < vec4<f32>(1e30)) && all(v == v);
}


// The classic 4x4 box: the sampling pass wrote every pixel (the sky as unoccluded), so no depth
// is read per neighbour; only non-finite values are left out.
fn box_blur(pixel: vec2<i32>) -> vec4<f32> {
    let last = vec2<i32>(textureDimensions(input)) - 1;
    var sum = vec4<f32>(0.0);
    var total = 0.0;
    for (var y = -2; y < 2; y += 1) {
        for (var x = -2; x < 2; x += 1) {
            let value = textureLoad(input, clamp(pixel + vec2<i32>(x, y), vec2<i32>(0), last), 0);
            let ok = finite4(value);
            sum += select(vec4<f32>(0.0), value, ok);
            total += select(0.0, 1.0, ok);
        }
    }
    if total > 0.0 {
        return sum / total;
    }
    return textureLoad(input, pixel, 0);
}

fn blur(position: vec2<f32>) -> vec4<f32> {
    let pixel = vec2<i32>(position);
    let centre = surface_pixel(pixel);
    let depth = load_depth(centre);
    if depth <= 0.0 {
        // A sky pixel: no occlusion, no DO.
        return select(vec4<f32>(1.0, 0.0, 0.0, 1.0), vec4<f32>(0.0, 0.0, 0.0, 1.0), HAS_DO);
    }
    if !BILATERAL {
        return box_blur(pixel);
    }
    let bits_p = textureLoad(g_normal, centre, 0).r;
    let n = unpack_normal(bits_p);
    let oct_p = octahedral_code(bits_p);
    let p = view_position(vec2<f32>(centre) + 0.5, depth);
    let size = vec2<i32>(textureDimensions(input));
    let tolerance = bilateral_tolerance(params.radius);

    var sum = vec4<f32>(0.0);
    var total = 0.0;
    // At half resolution a 3x3 tent (1 2 1 × 1 2 1) over the half-size samples: about the
    // footprint the 4x4 window has at full resolution (6 full-resolution pixels across).
    // (Either way the window ends at +1: -2..1 at full resolution, -1..1 at half.)
    let lo = select(-2, -1, HALF_RESOLUTION);
    for (var y = lo; y < 2; y += 1) {
        for (var x = lo; x < 2; x += 1) {
            let t = clamp(pixel + vec2<i32>(x, y), vec2<i32>(0), size - 1);
            let at = surface_pixel(t);
            let d = load_depth(at);
            if d <= 0.0 {
                continue;
            }
            var w = 1.0;
            if HALF_RESOLUTION {
                w = f32((2 - abs(x)) * (2 - abs(y)));
            }
            if BILATERAL {
                let q = view_position(vec2<f32>(at) + 0.5, d);
                w *= bilateral_weight(p, n, oct_p, q, octahedral_code(textureLoad(g_normal, at, 0).r), tolerance);
            }
            let value = textureLoad(input, t, 0);
            if w <= 0.0 || !finite4(value) {
                continue;
            }
            sum += w * value;
            total += w;
        }
    }
    if total > 0.0 {
        return sum / total;
    }
    return textureLoad(input, pixel, 0);
}

// The AO target has one channel and the DO target four; one entry point serves both.
@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4<f32> {
    return blur(in.position.xy);
}
