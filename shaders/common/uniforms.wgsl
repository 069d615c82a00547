// Per-frame data shared by every pass (bind group 0). Mirrors `FrameUniforms` and `GpuLight`
// in src/render/uniforms.rs field for field.

struct Frame {
    world_to_view: mat4x4<f32>,
    view_to_clip: mat4x4<f32>,
    clip_to_view: mat4x4<f32>,
    view_to_world: mat4x4<f32>,
    // width, height, 1/width, 1/height
    viewport: vec4<f32>,
    // near, far (0 = infinite), exposure / pre-exposure, smallest light distance squared
    camera: vec4<f32>,
    // ambient radiance (rgb), orbit distance of the camera (for the depth view)
    ambient: vec4<f32>,
    // sky radiance scale (pre-exposed), sky mip count, pre-exposure, unused
    sky: vec4<f32>,
    // AO strength, AO power, unused, unused
    shading: vec4<f32>,
    // light count, frame index, unused, unused
    counts: vec4<u32>,
    // xy: the pixel of the output where this image starts (the viewer's 3D view beside its
    // panel), zw unused. Passes that draw straight into the output subtract it.
    output_origin: vec4<f32>,
    // The sky's irradiance E(n)/π for a world-space normal: 9 spherical-harmonic coefficients
    // (rgb), scaled by the sky scale and strength and pre-exposed (Skybox::irradiance_sh).
    sky_sh: array<vec4<f32>, 9>,
}

struct Light {
    // xyz world position, w radiant intensity
    world_position: vec4<f32>,
    // xyz view-space position, w unused
    view_position: vec4<f32>,
    // linear rgb colour, w half edge of the emissive cube
    color: vec4<f32>,
}

// Pre-exposure: every radiance written to a half-float buffer (HDR, bounce, DO) is radiance ×
// frame.sky.z, chosen on the CPU so the brightest radiance of the frame stays far below 65504;
// the tone-map pass divides it back out (camera.z is exposure / pre-exposure).
@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<storage, read> lights: array<Light>;

const PI: f32 = 3.14159265358979;

// Normalises `v`, or returns `fallback` when `v` is zero or too small to normalise.
fn safe_normalize(v: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let len2 = dot(v, v);
    if len2 > 1e-30 && len2 < 1e30 {
        return v * inverseSqrt(len2);
    }
    return fallback;
}
