// Per-frame data shared by every pass (bind group 0). Mirrors `FrameUniforms` and `GpuLight`
// in src/render/uniforms.rs field for field, names included (tests/it/cpu/shaders.rs checks every
// member's offset against naga's layout of this file).

struct Frame {
    world_to_view: mat4x4<f32>,
    view_to_clip: mat4x4<f32>,
    view_to_world: mat4x4<f32>,
    // width, height, 1/width, 1/height of the image (not of the output it may be drawn into)
    viewport: vec4<f32>,
    near: f32,
    // 0: an infinite far plane
    far: f32,
    // exposure / pre-exposure: turns what a half-float buffer holds into displayed radiance
    display_scale: f32,
    // the point lights' irradiance is clamped at this distance, squared
    min_light_distance2: f32,
    // constant ambient radiance
    ambient: vec3<f32>,
    // the orbit camera's distance (the depth view's range)
    orbit_distance: f32,
    // multiplies the sky cube map's values into pre-exposed radiance
    sky_scale: f32,
    sky_mips: f32,
    // see below
    pre_exposure: f32,
    ao_strength: f32,
    ao_power: f32,
    light_count: u32,
    frame_index: u32,
    // the scene's default march thickness (a thickness code's unit; the thickness view's scale)
    default_thickness: f32,
    // the pixel of the output where this image starts (the viewer's 3D view beside its panel);
    // passes that draw straight into the output subtract it
    output_origin: vec2<f32>,
    _pad1: vec2<f32>,
    // The sky's irradiance E(n)/π for a view-space unit normal (x, y, z), as the rgb weights of
    // x², y², xy, xz, yz, x, y, z and 1: its 9 spherical-harmonic coefficients
    // (Skybox::irradiance_sh) turned into this frame's view space (irradiance_quadratic in
    // src/scene/irradiance.rs), scaled by the sky scale and strength and pre-exposed.
    sky_irradiance: array<vec4<f32>, 9>,
    // World space to the previous frame's clip space (this frame's own on a first frame or
    // after a reset): where a static surface was on screen a frame ago, for reprojection.
    previous_world_to_clip: mat4x4<f32>,
    // The previous frame's projection: 1 / its x and y scales, and a, b of its reverse-Z depth
    // (depth = -a - b / z): a pixel of the previous frame and its depth to that frame's view space.
    previous_projection: vec4<f32>,
    // This frame's view space to the previous frame's: a direction (a normal) as the previous
    // frame's view saw it.
    view_to_previous_view: mat4x4<f32>,
    // The previous frame's eye in this frame's view space (this eye on a first frame or after a
    // reset): how far a surface's view turned since then.
    previous_eye: vec3<f32>,
    _pad2: f32,
    // The first UNIFORM_LIGHTS lights of `lights` again (the rest zero): a light loop over at most
    // that many reads them here, in uniform memory. On lavapipe each pixel's read of the storage
    // array is a load of its own: one light read there took the composite 12 ms of 25 at
    // 800x600, eight lights 85 ms of 113 (docs/performance.md).
    first_lights: array<Light, UNIFORM_LIGHTS>,
}

// The most lights the frame uniforms carry (`UNIFORM_LIGHTS` in src/render/uniforms.rs).
const UNIFORM_LIGHTS: u32 = 256u;

struct Light {
    world_position: vec3<f32>,
    // radiant intensity
    intensity: f32,
    view_position: vec3<f32>,
    _pad0: f32,
    // linear rgb colour, largest channel 1
    color: vec3<f32>,
    // half the edge of the emissive cube drawn at the light
    cube_half_size: f32,
}

// Pre-exposure: every radiance written to a half-float buffer (HDR, bounce, DO) is radiance ×
// frame.pre_exposure, chosen on the CPU so the brightest radiance of the frame stays far below
// 65504; what displays it multiplies by frame.display_scale (exposure / pre-exposure).
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
