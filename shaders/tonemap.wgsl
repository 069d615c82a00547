// HDR to display: exposure, the ACES filmic curve (Narkowicz's fit), then sRGB. When the target
// format is an sRGB format the hardware encodes; otherwise the shader does. The same pass shows
// the debug views (a G-buffer channel, AO or DO instead of the final image).
// Pixels are addressed through uv, so the pass can draw into a viewport of a larger target.

#include "common/uniforms.wgsl"
#include "common/fullscreen.wgsl"
#include "common/surface_pack.wgsl"
#include "common/tone_curve.wgsl"
#include "common/thickness.wgsl"
#include "common/unproject.wgsl"

@group(1) @binding(0) var hdr: texture_2d<f32>;
@group(1) @binding(1) var g_albedo: texture_2d<f32>;
@group(1) @binding(2) var g_normal: texture_2d<u32>;  // packed (surface_pack.wgsl)
@group(1) @binding(3) var g_depth: texture_2d<f32>;  // depth32float as unfilterable float (GL-safe)
@group(1) @binding(4) var ao_map: texture_2d<f32>;
@group(1) @binding(5) var do_map: texture_2d<f32>;
// The thickness layer (gbuffer.wgsl `fs_thickness`) where the plan has it; a stand-in otherwise.
@group(1) @binding(6) var thickness_layer: texture_2d<u32>;

// True when the output format does the sRGB encoding itself.
override OUTPUT_SRGB: bool = true;
// 0 final image, 1 albedo, 2 view-space normals, 3 depth, 4 AO, 5 DO (tone mapped), 6 the
// march's thickness.
override VIEW: u32 = 0u;
// The plan has the thickness layer (a thin material in the scene, and the march reads it).
override THICKNESS_LAYER: bool = false;
override HAS_AO: bool = false;
// DO in the DO target's rgb; AO, when the mode has it, then travels in its alpha.
override HAS_DO: bool = false;

// The displayed colour (linear, before sRGB encoding) of `pixel`.
fn shade(pixel: vec2<i32>) -> vec3<f32> {
    switch VIEW {
        case 1u: {
            return textureLoad(g_albedo, pixel, 0).rgb;
        }
        case 2u: {
            // Normals as colours, n · 0.5 + 0.5, shown as written (no sRGB curve); the sky, which
            // has no normal, mid-grey.
            var n = vec3<f32>(0.0);
            if textureLoad(g_depth, pixel, 0).r > 0.0 {
                n = unpack_normal(textureLoad(g_normal, pixel, 0).r);
            }
            return pow(n * 0.5 + 0.5, vec3<f32>(2.2));
        }
        case 3u: {
            // Distance from the camera, linear: bright at the camera, black at twice the orbit
            // distance and on the sky. Reverse-Z depth d maps back to view z = -b / (d + a).
            let d = textureLoad(g_depth, pixel, 0).r;
            if d <= 0.0 {
                return vec3<f32>(0.0);
            }
            let z = frame.view_to_clip[3][2] / max(d + frame.view_to_clip[2][2], 1e-30);
            return vec3<f32>(pow(clamp(1.0 - z / (2.0 * frame.orbit_distance), 0.0, 1.0), 2.2));
        }
        case 4u: {
            var ao = 1.0;
            if HAS_AO {
                ao = select(textureLoad(ao_map, pixel, 0).r, textureLoad(do_map, pixel, 0).a, HAS_DO);
            }
            return vec3<f32>(clamp(ao, 0.0, 1.0));
        }
        case 5u: {
            var light = vec3<f32>(0.0);
            if HAS_DO {
                light = textureLoad(do_map, pixel, 0).rgb;
            }
            return tone_map(light * frame.display_scale);
        }
        case 6u: {
            // The thickness the march takes a depth sample here to have at its nearest step (one
            // pixel's footprint), against the scene's default: white the default slab (everywhere
            // without the thickness layer), red none (a cut-out seen face-on), pink between them
            // by the square root of the share; the sky black. With the layer, its own depth: what
            // the march reads (the light cubes, drawn later into the depth, are not in it).
            var depth = textureLoad(g_depth, pixel, 0).r;
            var code = DEFAULT_THICKNESS_CLASS;
            if THICKNESS_LAYER {
                let bits = textureLoad(thickness_layer, pixel, 0).r;
                depth = bitcast<f32>(bits & ~THICKNESS_CODE_MASK);
                code = bits & THICKNESS_CODE_MASK;
            }
            if depth <= 0.0 {
                return vec3<f32>(0.0);
            }
            let z = view_position(vec2<f32>(pixel) + 0.5, depth).z;
            let unit = max(frame.default_thickness, 1e-30);
            let share = min(depth_extent(code, pixel_footprint(1.0, z), unit) / unit, 1.0);
            return mix(vec3<f32>(0.8, 0.05, 0.02), vec3<f32>(1.0), sqrt(share));
        }
        default: {
            return tone_map(textureLoad(hdr, pixel, 0).rgb * frame.display_scale);
        }
    }
}

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4<f32> {
    let size = vec2<f32>(textureDimensions(hdr));
    let pixel = vec2<i32>(min(in.uv * size, size - 1.0));
    var color = shade(pixel);
    if !OUTPUT_SRGB {
        color = linear_to_srgb(color);
    }
    return vec4<f32>(color, 1.0);
}
