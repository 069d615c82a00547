// Composite: the sky and ambient light each mode sees, plus direct point lighting, in linear HDR.
// Every mode is lit by the same sky, so switching modes shows occlusion, not a different light.
// With ρ the albedo, A the constant ambient radiance, E(n)/π the sky's unoccluded irradiance
// (spherical harmonics, precomputed per sky), AO and DO the sampling pass's outputs:
//   Off        ρ·(E(n)/π + A)
//   SSAO       ρ·(E(n)/π + A)·AO
//   SSDO       ρ·(DO + A·V)        DO = the visible sky per direction + one bounce, V the share
//                                  of the hemisphere the march finds open (1 for points)
//   SSAO+SSDO  ρ·(DO + A·AO)       AO darkens only the constant ambient SSDO does not see
// The classic variant keeps the SSDO course project's composite: A·ρ·AO + DO (DO without ρ), no
// sky irradiance. Which terms exist is decided when the pipeline is built (override constants),
// so a mode or a scene that lacks a term pays nothing for it. After a lighting pass the composite
// adds the direct light that pass wrote; otherwise it runs the light loop. After a half-size
// sampling chain it upsamples AO / DO as it reads them (common/upsample.wgsl): the chain's last
// stage stays where the samples are, and no full-screen pass stands between them and this one.
//
// Two outputs. Into the HDR target (pre-exposed radiance; the skybox and tone-map passes follow)
// when something reads HDR afterwards: the report, `--raw`, `--stats`, the debug views. Otherwise
// (DISPLAY) straight into the output: exposure, tone curve and sRGB here, in the output's
// viewport — no HDR write, no skybox or tone-map pass; where nothing was drawn, the sky as the
// G-buffer pass drew it for display into the albedo (src/render/passes/gbuffer.rs).

#include "common/uniforms.wgsl"
#include "common/gbuffer_read.wgsl"
#include "common/point_lights.wgsl"
#include "common/frame_varyings.wgsl"
#include "common/tone_curve.wgsl"
#include "common/filter_params.wgsl"

// The upsample's tolerances (in a half-resolution plan).
@group(1) @binding(3) var<uniform> params: FilterParams;
// The sampling chain's last stage: AO alone in r (SSAO), or DO in rgb and AO in a (SSDO,
// SSAO+SSDO); at half size in a half-resolution plan.
@group(1) @binding(4) var current: texture_2d<f32>;
// The lighting pass's direct light (DISPLAY after a lighting pass; blended onto otherwise).
@group(1) @binding(5) var direct_map: texture_2d<f32>;
// GUIDE_INPUT: the surface each half-size sample holds, as the temporal pass wrote it this frame
// (its surface history: x the depth as f32 bits, y the packed normal in bits 0-23; 0 where it
// kept nothing).
@group(1) @binding(6) var surface_guide: texture_2d<u32>;

// Run the point-light loop here (there are lights and no lighting pass ran).
override LIGHT_LOOP: bool = true;
override HAS_AO: bool = false;
// DO in the DO target's rgb; AO, when the mode has it, then travels in its alpha.
override HAS_DO: bool = false;
// The classic variant adds DO without the receiver's albedo, as the source does, and has no
// sky irradiance.
override CLASSIC: bool = false;
// The "lighting only" view: every surface white.
override WHITE_ALBEDO: bool = false;
// Draw tone-mapped colour straight into the output (see the top of the file).
override DISPLAY: bool = false;
// DISPLAY: the output format does the sRGB encoding itself.
override OUTPUT_SRGB: bool = true;
// DISPLAY after a lighting pass: read its direct light from `direct_map`.
override DIRECT_INPUT: bool = false;
// In a half-resolution plan `current` holds half-size samples, upsampled here as they are read.
#include "common/sample_grid.wgsl"
// ... the temporal pass's average: the samples' surfaces are read from `surface_guide`, one load
// a tap instead of the G-buffer's depth and normal.
override GUIDE_INPUT: bool = false;

// The surface of the sample at half-size `texel`, the full-resolution pixel `pixel`: its depth
// (f32 bits) and packed normal.
fn sample_surface(texel: vec2<i32>, pixel: vec2<i32>) -> vec2<u32> {
    if GUIDE_INPUT {
        return textureLoad(surface_guide, texel, 0).xy;
    }
    return vec2<u32>(bitcast<u32>(load_depth(pixel)), textureLoad(g_normal, pixel, 0).r);
}

#include "common/upsample.wgsl"

@fragment
fn fs_main(in: FrameVaryings) -> @location(0) vec4<f32> {
    if DISPLAY {
        // The fragment's position is in the output; the targets are addressed from the image's
        // own top-left corner.
        let size = in.viewport.xy;
        let pixel = vec2<i32>(min(in.position.xy - in.output.xy, size - 1.0));
        let depth = load_depth(pixel);
        let albedo = textureLoad(g_albedo, pixel, 0);
        // The sky, displayed as the G-buffer pass drew it.
        var color = albedo.rgb;
        if depth > 0.0 {
            color = tone_map(radiance(in, pixel, vec2<f32>(pixel) + 0.5, depth, albedo) * in.output.z);
        }
        if !OUTPUT_SRGB {
            color = linear_to_srgb(color);
        }
        return vec4<f32>(color, 1.0);
    }
    let pixel = vec2<i32>(in.position.xy);
    let depth = load_depth(pixel);
    if depth <= 0.0 {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    return vec4<f32>(radiance(in, pixel, in.position.xy, depth, textureLoad(g_albedo, pixel, 0)), 1.0);
}

// Pre-exposed radiance leaving `pixel` (centre `position`) towards the camera, from its depth
// (> 0 where there is a surface) and its G-buffer albedo, which the caller has read: each is
// read once a pixel (in a display plan the sky's pixels show that albedo as it is). `c`: the
// frame's constants as the triangle handed them down.
fn radiance(c: FrameVaryings, pixel: vec2<i32>, position: vec2<f32>, depth: f32, surface_albedo: vec4<f32>) -> vec3<f32> {
    var albedo = surface_albedo;
    if WHITE_ALBEDO {
        albedo = vec4<f32>(1.0, 1.0, 1.0, albedo.a);
    }
    // The surface, where a term needs it: its packed normal and its view-space position.
    var bits = 0u;
    if LIGHT_LOOP || (!CLASSIC && !HAS_DO) || HALF_RESOLUTION {
        bits = textureLoad(g_normal, pixel, 0).r;
    }
    var p = vec3<f32>(0.0);
    if LIGHT_LOOP || HALF_RESOLUTION {
        p = view_position_of(c, position, depth);
    }
    // The sampling chain's value here: AO in r, or DO + AO.
    var occlusion = unoccluded_value();
    if HAS_AO || HAS_DO {
        if HALF_RESOLUTION {
            occlusion = upsample_surface(pixel, p, bits, c.projection, c.viewport, sky_quadratic(c));
        } else {
            occlusion = textureLoad(current, pixel, 0);
        }
    }
    var directional = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    if HAS_DO {
        directional = occlusion;
    }
    var ao = 1.0;
    if HAS_AO {
        let raw = clamp(select(occlusion.r, occlusion.a, HAS_DO), 0.0, 1.0);
        ao = mix(1.0, pow(raw, c.shading.y), c.shading.x);
    } else if HAS_DO && !CLASSIC {
        // SSDO: the ambient's visibility, from the sampling pass (the march's open share; 1 for
        // the point estimator, which has none).
        ao = clamp(directional.a, 0.0, 1.0);
    }
    let ambient = c.ambient.rgb;
    var color: vec3<f32>;
    let normal = surface_of(bits);
    if CLASSIC {
        color = ambient * albedo.rgb * ao;
        if HAS_DO {
            color += directional.rgb;
        }
    } else if HAS_DO {
        color = albedo.rgb * (directional.rgb + ambient * ao);
    } else {
        color = albedo.rgb * (sky_irradiance(c, normal.xyz) + ambient) * ao;
    }
    if LIGHT_LOOP {
        let direct = point_lighting(c, p, normal.xyz, albedo.rgb, albedo.a, normal.w);
        color += direct.diffuse + direct.specular;
    }
    if DIRECT_INPUT {
        color += textureLoad(direct_map, pixel, 0).rgb;
    }
    return color;
}
