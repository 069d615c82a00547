// Direct lighting by the point lights: Lambert diffuse plus normalised Blinn-Phong specular,
// inverse-square falloff with the distance clamped from below (a light on a surface stays
// finite). Returns outgoing radiance towards the camera at view-space `p`, split into the
// diffuse part (which SSDO bounces) and the specular part.

#include "common/frame_varyings.wgsl"

// The number of lights where the pipeline was built for it (the loop has a known length, and the
// compiler unrolls it); 0: the frame's count, read as the loop runs (src/render/modes/mod.rs,
// `Plan::unrolled_lights`).
override LIGHT_COUNT: u32 = 0u;
// The lights are read from the frame uniforms' copy (`frame.first_lights`: the scene has at most
// UNIFORM_LIGHTS), not from the storage array (`Plan::uniform_lights`).
override UNIFORM_LIGHT_READS: bool = false;
// A loop built for one light takes it from the triangle (common/frame_varyings.wgsl): its pixels
// read no uniform at all. (Flat varyings are too few for more: WebGPU's downlevel limits allow 15.)
override HANDED_DOWN: bool = LIGHT_COUNT == 1u && UNIFORM_LIGHT_READS;

struct PointLighting {
    diffuse: vec3<f32>,
    specular: vec3<f32>,
}

// `c`: the frame's constants as the full-screen triangle handed them down.
fn point_lighting(c: FrameVaryings, p: vec3<f32>, n: vec3<f32>, albedo: vec3<f32>, specular: f32, shininess: f32) -> PointLighting {
    let to_eye = safe_normalize(-p, vec3<f32>(0.0, 0.0, 1.0));
    let pre_exposure = c.shading.z;
    let min_d2 = c.shading.w;
    let spec_norm = (shininess + 8.0) / (8.0 * PI);
    var count = frame.light_count;
    if LIGHT_COUNT > 0u {
        count = LIGHT_COUNT;
    }
    var out: PointLighting;
    for (var i = 0u; i < count; i += 1u) {
        // The light's position and its colour × intensity, pre-exposed.
        var position: vec3<f32>;
        var power: vec3<f32>;
        if HANDED_DOWN {
            position = c.light_position.xyz;
            power = c.light_power.rgb;
        } else {
            var light: Light;
            if UNIFORM_LIGHT_READS {
                light = frame.first_lights[i];
            } else {
                light = lights[i];
            }
            position = light.view_position;
            power = light.color * (pre_exposure * light.intensity);
        }
        let to_light = position - p;
        let d2 = dot(to_light, to_light);
        let l = safe_normalize(to_light, n);
        let n_dot_l = max(dot(n, l), 0.0);
        let irradiance = power * (n_dot_l / max(d2, min_d2));
        let h = safe_normalize(l + to_eye, n);
        out.diffuse += irradiance * albedo / PI;
        out.specular += irradiance * (specular * spec_norm * pow(max(dot(n, h), 0.0), shininess));
    }
    return out;
}
