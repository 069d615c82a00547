//! Uniform and storage structs, mirrored field for field — names included — in
//! `shaders/common/uniforms.wgsl`, `shaders/common/sampling_params.wgsl` and
//! `shaders/gbuffer.wgsl`. Fields are 4-byte scalars, vec3s followed by a scalar, and 16-byte
//! arrays, padded by hand where WGSL would align, so there is no hidden padding on either side;
//! `tests/it/cpu/shaders.rs` checks every member's offset against naga's layout of the WGSL.

use glam::Mat4;

/// Per-frame data (bind group 0, binding 0). The meaning of each field is written once, beside
/// the WGSL struct `Frame` in `shaders/common/uniforms.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameUniforms {
    pub world_to_view: [[f32; 4]; 4],
    pub view_to_clip: [[f32; 4]; 4],
    pub view_to_world: [[f32; 4]; 4],
    pub viewport: [f32; 4],
    pub near: f32,
    pub far: f32,
    pub display_scale: f32,
    pub min_light_distance2: f32,
    pub ambient: [f32; 3],
    pub orbit_distance: f32,
    pub sky_scale: f32,
    pub sky_mips: f32,
    pub pre_exposure: f32,
    pub ao_strength: f32,
    pub ao_power: f32,
    pub light_count: u32,
    pub frame_index: u32,
    /// The scene's default march thickness (a thickness code's unit; the thickness view's scale).
    pub default_thickness: f32,
    pub output_origin: [f32; 2],
    pub _pad1: [f32; 2],
    pub sky_irradiance: [[f32; 4]; 9],
    pub previous_world_to_clip: [[f32; 4]; 4],
    /// The previous frame's projection: 1 / its [0][0] and [1][1] terms, and a, b of its depth
    /// (depth = -a - b / z), to take a pixel of the previous frame and its depth to that frame's
    /// view space.
    pub previous_projection: [f32; 4],
    pub view_to_previous_view: [[f32; 4]; 4],
    /// The previous frame's eye in this frame's view space (this eye on a first frame or after a
    /// reset): how far a surface's view turned since then, once a frame rather than each pixel.
    pub previous_eye: [f32; 3],
    pub _pad2: f32,
    /// The first [`UNIFORM_LIGHTS`] lights (the rest zero), which the light loops read where the
    /// scene has no more.
    pub first_lights: [GpuLight; UNIFORM_LIGHTS],
}

/// The most point lights a light loop is built for (`Plan::unrolled_lights`): the default
/// scene's eight. Such a loop has a known length, which the shader compiler unrolls: on lavapipe
/// at 800x600 a loop over the frame's count cost the one-light composite 1.7 ms of 12
/// (docs/performance.md).
pub const UNROLLED_LIGHTS: usize = 8;

/// The most point lights the frame uniforms carry (`FrameUniforms::first_lights`,
/// `Plan::uniform_lights`; `UNIFORM_LIGHTS` in `uniforms.wgsl`): 12 KiB, within the 16 KiB a
/// uniform binding may hold on every backend. Lights read from uniform memory instead of the
/// storage array made the eight-light Off composite 3.8 times as fast on lavapipe
/// (docs/performance.md); a scene with more lights reads the storage array.
pub const UNIFORM_LIGHTS: usize = 256;

/// One point light (bind group 0, binding 1, an array); `Light` in `uniforms.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuLight {
    pub world_position: [f32; 3],
    pub intensity: f32,
    pub view_position: [f32; 3],
    pub _pad0: f32,
    pub color: [f32; 3],
    pub cube_half_size: f32,
}

/// One material (G-buffer pass, bind group 1, binding 0); `MaterialParams` in `gbuffer.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct MaterialParams {
    pub albedo: [f32; 3],
    pub specular: f32,
    /// The Blinn-Phong exponent as the G-buffer packs it (`surface_pack::shininess_bits`).
    pub shininess_bits: u32,
    /// Multiplies the normal map's x and y.
    pub normal_scale: f32,
    /// Coverage below this is a hole (cut-out materials).
    pub alpha_cutoff: f32,
    /// Multiplies the mask's coverage.
    pub alpha_factor: f32,
    /// The material's thickness class for the thickness layer (`scene/thickness.rs`).
    pub thickness_code: u32,
    pub _pad: [u32; 3],
}

/// Sampling parameters of the occlusion pass; `SamplingParams` in
/// `shaders/common/sampling_params.wgsl`, where each field is explained.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SamplingParams {
    /// Tangent-space offsets (z along the normal) for a unit radius; w unused.
    pub kernel: [[f32; 4]; MAX_SAMPLES],
    /// The 4x4 tile of per-pixel rotations: (cos, sin) or a random tangent-plane vector.
    pub rotations: [[f32; 4]; 16],
    pub radius: f32,
    pub bias_length: f32,
    pub sample_count: u32,
    pub sky_mip: f32,
    pub sky_strength: f32,
    pub indirect_strength: f32,
    pub sender_sky_strength: f32,
    pub _pad0: f32,
    pub slices: u32,
    pub steps: u32,
    pub reach: f32,
    pub thickness: f32,
    pub schedule: [f32; 4],
}

/// What the passes that filter the samples read (the upsample, the blur, the temporal pass);
/// `FilterParams` in `shaders/common/filter_params.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FilterParams {
    pub radius: f32,
    pub accumulate: u32,
    pub motion_accumulate: u32,
    pub history_frames: u32,
}

/// Largest kernel the occlusion pass takes.
pub const MAX_SAMPLES: usize = super::variant::SAMPLES.max;

pub fn mat(m: Mat4) -> [[f32; 4]; 4] {
    m.to_cols_array_2d()
}
