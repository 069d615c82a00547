//! Uniform and storage structs, mirrored field for field in `shaders/common/uniforms.wgsl`
//! (and `MaterialParams` in `shaders/gbuffer.wgsl`). Only 16-byte fields, so the Rust and WGSL
//! layouts agree without hidden padding; the sizes are checked at compile time.

use glam::Mat4;

/// Per-frame data (bind group 0, binding 0).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameUniforms {
    pub world_to_view: [[f32; 4]; 4],
    pub view_to_clip: [[f32; 4]; 4],
    pub clip_to_view: [[f32; 4]; 4],
    pub view_to_world: [[f32; 4]; 4],
    /// width, height, 1/width, 1/height
    pub viewport: [f32; 4],
    /// near, far (0 = infinite), exposure / pre-exposure, smallest light distance squared
    pub camera: [f32; 4],
    /// ambient radiance rgb, orbit distance of the camera (for the depth view)
    pub ambient: [f32; 4],
    /// sky radiance scale (pre-exposed), sky mip count, pre-exposure, unused
    pub sky: [f32; 4],
    /// AO strength, AO power, unused, unused
    pub shading: [f32; 4],
    /// light count, frame index, unused, unused
    pub counts: [u32; 4],
    /// xy: where the image starts in the output target; zw unused.
    pub output_origin: [f32; 4],
    /// The sky's irradiance E(n)/π for a world-space normal: 9 spherical-harmonic coefficients
    /// (rgb; w unused), scaled by the sky scale and strength and pre-exposed.
    pub sky_sh: [[f32; 4]; 9],
}

/// One point light (bind group 0, binding 1, an array).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuLight {
    /// xyz world position, w radiant intensity
    pub world_position: [f32; 4],
    /// xyz view-space position, w unused
    pub view_position: [f32; 4],
    /// linear rgb colour, w half edge of the emissive cube
    pub color: [f32; 4],
}

/// One material (G-buffer pass, bind group 1, binding 0).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct MaterialParams {
    /// rgb diffuse albedo, a specular strength
    pub diffuse: [f32; 4],
    /// shininess, unused x3
    pub params: [f32; 4],
}

/// Sampling parameters of the occlusion pass (mirrors `OcclusionParams` in
/// `shaders/common/occlusion_params.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct OcclusionUniforms {
    /// Tangent-space offsets (z along the normal) for a unit radius; w unused.
    pub kernel: [[f32; 4]; MAX_SAMPLES],
    /// The 4x4 tile of per-pixel rotations: (cos, sin) or a random tangent-plane vector.
    pub rotations: [[f32; 4]; 16],
    /// radius, bias (view units), sample count, sky mip level
    pub params: [f32; 4],
    /// sky-light strength, indirect strength, unused, unused
    pub strengths: [f32; 4],
    /// The march: slices, steps per side, reach and thickness (view units).
    pub march: [f32; 4],
}

/// Largest kernel the occlusion pass takes.
pub const MAX_SAMPLES: usize = 256;

const _: () = assert!(std::mem::size_of::<FrameUniforms>() == 4 * 64 + 7 * 16 + 9 * 16);
const _: () = assert!(std::mem::size_of::<OcclusionUniforms>() == (MAX_SAMPLES + 16 + 3) * 16);
const _: () = assert!(std::mem::size_of::<GpuLight>() == 48);
const _: () = assert!(std::mem::size_of::<MaterialParams>() == 32);

pub fn mat(m: Mat4) -> [[f32; 4]; 4] {
    m.to_cols_array_2d()
}
