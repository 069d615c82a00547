//! The sampling passes' parameters on the GPU: the kernel and the 4x4 rotations (regenerated only
//! when the variant or the sample count changes), the radius, bias, strengths and the march's
//! slices, steps, reach and thickness. Read by the sampling pass and the blur.

use super::super::kernel;
use super::super::sampling::{Lengths, Sampling};
use super::super::uniforms::OcclusionParams;
use super::super::variant::Variant;

/// Sampling parameters for one frame: the settings' [`Sampling`] with its counts clamped, the
/// lengths it resolves to, and what the sky and the temporal pass add.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SamplingParams {
    pub sampling: Sampling,
    pub lengths: Lengths,
    pub sky_mip: f32,
    pub sky_strength: f32,
    pub indirect_strength: f32,
    /// The user's sky strength, for the bounce's senders (not zeroed by the debug views).
    pub sender_sky_strength: f32,
    /// This frame's entry of the sample schedule (`kernel::schedule`).
    pub schedule: [f32; 4],
    /// The temporal pass: the most frames averaged still and moving, and the frames its
    /// history holds.
    pub accumulate: u32,
    pub motion_accumulate: u32,
    pub history_frames: u32,
}

/// The kernel and parameters uniform, shared by the sampling and blur passes.
pub struct OcclusionData {
    pub buffer: wgpu::Buffer,
    uniforms: Box<OcclusionParams>,
    kernel_key: Option<(Variant, usize)>,
}

impl OcclusionData {
    pub fn new(device: &wgpu::Device) -> Self {
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("occlusion_params"),
            size: std::mem::size_of::<OcclusionParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self { buffer, uniforms: Box::new(bytemuck::Zeroable::zeroed()), kernel_key: None }
    }

    /// Writes the parameters (their counts already clamped); the kernel is regenerated only when
    /// the variant or the sample count changes.
    pub fn update(&mut self, queue: &wgpu::Queue, params: &SamplingParams) {
        let (sampling, lengths) = (&params.sampling, &params.lengths);
        let (variant, samples) = (sampling.variant, sampling.samples);
        if self.kernel_key != Some((variant, samples)) {
            for (slot, k) in self.uniforms.kernel.iter_mut().zip(kernel::kernel(variant.decl().kernel, samples)) {
                *slot = k.extend(0.0).into();
            }
            self.uniforms.rotations = kernel::rotations(variant.decl().kernel);
            self.kernel_key = Some((variant, samples));
        }
        let u = self.uniforms.as_mut();
        (u.radius, u.bias, u.sample_count, u.sky_mip) = (lengths.radius, lengths.bias, samples as u32, params.sky_mip);
        (u.sky_strength, u.indirect_strength) = (params.sky_strength, params.indirect_strength);
        u.sender_sky_strength = params.sender_sky_strength;
        u.schedule = params.schedule;
        (u.accumulate, u.motion_accumulate, u.history_frames) =
            (params.accumulate, params.motion_accumulate, params.history_frames);
        (u.slices, u.steps, u.reach, u.thickness) =
            (sampling.slices as u32, sampling.steps as u32, lengths.reach, lengths.thickness);
        queue.write_buffer(&self.buffer, 0, bytemuck::bytes_of(self.uniforms.as_ref()));
    }
}
