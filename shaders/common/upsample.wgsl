// The edge-aware upsample of half-resolution samples, shared by the composite, which upsamples
// the chain's last half-size stage as it reads it (shaders/composite.wgsl), and the upsample
// pass, which makes a full-size copy for the readers of one (shaders/upsample.wgsl).
//
// Each full-resolution pixel takes the 2x2 half-resolution samples at and after it (each sample
// is the full-resolution pixel (2x, 2y), so these are the nearest ones on either side of an odd
// pixel, and an even pixel's own with the next), weighted by a tent over their distance and by whether they lie on this pixel's
// surface — within a quarter of the sampling radius of its tangent plane, with normals that
// agree (compared by their octahedral codes, as the blur compares its neighbours'). So a silhouette takes nothing from the surface
// behind it, and a far wall nothing from the object before it: no halo. Where no sample is on
// the same surface (a feature thinner than two pixels), the one nearest its plane stands in.
//
// Under a normal map, or on a smooth-shaded model, the normal turns from pixel to pixel faster
// than the samples are spaced, and a sample's DO was measured with its own pixel's normal. With
// DO_OVER_IRRADIANCE the samples hold their DO over the sky's unoccluded irradiance at their own
// normal (`stored_do` in common/occlusion_inputs.wgsl), which the blur and the temporal pass
// average as they are, and the upsample multiplies by that at this pixel's: Ê(n)/Ê(n_s) in
// effect (`irradiance_floored`), so each pixel's shading survives half resolution where the
// occlusion is shared (what it buys: docs/accuracy.md, normal maps).
//
// The including shader declares `current` (the half-size samples: AO in r, or DO + AO),
// `params` (FilterParams), the override HAS_DO and `sample_surface` (a sample's depth and packed
// normal: the G-buffer's at its pixel, or what the temporal pass stored for it), and includes
// gbuffer_read.wgsl first.

#include "common/sky_quadratic.wgsl"

// The samples hold their DO over the sky's irradiance at their normals (the including shader
// declares HAS_DO; this is only set with it).
override DO_OVER_IRRADIANCE: bool = false;

// What a pixel with no surface holds: no occlusion, no DO.
fn unoccluded_value() -> vec4<f32> {
    return select(vec4<f32>(1.0, 0.0, 0.0, 1.0), vec4<f32>(0.0, 0.0, 0.0, 1.0), HAS_DO);
}

// The upsampled value at full-resolution `pixel` (its centre `position`), from the half-size
// samples in `current`.
fn upsample(pixel: vec2<i32>, position: vec2<f32>) -> vec4<f32> {
    let depth = load_depth(pixel);
    if depth <= 0.0 {
        return unoccluded_value();
    }
    let bits = textureLoad(g_normal, pixel, 0).r;
    var sky: SkyQuadratic;
    if DO_OVER_IRRADIANCE {
        sky = frame_sky_quadratic();
    }
    return upsample_surface(pixel, view_position(position, depth), bits, projection_terms(), frame.viewport, sky);
}

// The same for a `pixel` that shows a surface, given its view-space position `p` and its packed
// normal `bits` (for a caller that has read them already), the frame's `projection_terms` and
// viewport (for a caller that has them at hand: common/frame_varyings.wgsl) and, under
// DO_OVER_IRRADIANCE, the sky's irradiance weights.
fn upsample_surface(pixel: vec2<i32>, p: vec3<f32>, bits: u32, projection: vec4<f32>, viewport: vec4<f32>, sky: SkyQuadratic) -> vec4<f32> {
    let unoccluded = unoccluded_value();
    let n = unpack_normal(bits);
    let code = octahedral_code(bits);
    let tolerance = max(0.25 * params.radius, 1e-30);
    let full = vec2<i32>(viewport.xy);
    let half_last = vec2<i32>(textureDimensions(current)) - 1;
    let base = pixel >> vec2<u32>(1u);

    var sum = vec4<f32>(0.0);
    var total = 0.0;
    var nearest = unoccluded;
    var nearest_plane = 3.4e38;
    for (var y = 0; y <= 1; y += 1) {
        for (var x = 0; x <= 1; x += 1) {
            let h = clamp(base + vec2<i32>(x, y), vec2<i32>(0), half_last);
            let at = min(2 * h, full - 1);
            let surface = sample_surface(h, at);
            let d = bitcast<f32>(surface.x);
            // (Selects, not a `continue` where the sample has no surface: a CPU rasteriser runs
            // both sides of a branch its lanes disagree on.)
            let on_surface = d > 0.0;
            let value = textureLoad(current, h, 0);
            let q = unproject(vec2<f32>(at) + 0.5, d, projection, viewport.zw);
            let plane = abs(dot(n, q - p));
            let nearer = on_surface && plane < nearest_plane;
            nearest_plane = select(nearest_plane, plane, nearer);
            nearest = select(nearest, value, nearer);
            // A tent over the distance in full-resolution pixels: 1 at the pixel itself, 0 at 3.
            let gap = abs(vec2<f32>(at - pixel));
            let tent = max(1.0 - gap / 3.0, vec2<f32>(0.0));
            // 1 − 2.5δ² ≈ (cos θ − 0.8)·5 for normals θ apart: 1 when equal, 0 from about 37°.
            let spread = octahedral_distance(code, octahedral_code(surface.y));
            let agree = max(1.0 - 2.5 * spread * spread, 0.0);
            let w = tent.x * tent.y * max(1.0 - plane / tolerance, 0.0) * agree;
            sum += select(vec4<f32>(0.0), w * value, on_surface);
            total += select(0.0, w, on_surface);
        }
    }
    var result = nearest;
    if total > 1e-4 {
        result = sum / total;
    }
    if DO_OVER_IRRADIANCE {
        result = vec4<f32>(result.rgb * irradiance_floored(sky, n), result.a);
    }
    return result;
}
