//! The sampling passes' parameters on the GPU: the kernel and the 4x4 rotations (regenerated only
//! when the variant or the sample count changes), the radius, bias, strengths and the march's
//! slices, steps, reach and thickness, read by the sampling pass and the sender-sky march; and
//! beside them the little the filters read (the radius and the temporal pass's frame counts).

use super::super::kernel;
use super::super::sampling::Lengths;
use super::super::uniforms::{FilterParams, SamplingParams};
use super::super::variant::Variant;
use crate::knobs::Knobs;

/// Sampling parameters for one frame: the settings' [`Knobs`] with their counts clamped, the
/// lengths it resolves to, and what the sky and the temporal pass add.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SamplingFrame {
    pub knobs: Knobs,
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

/// The sampling passes' uniform and the filters' one, written every frame that samples (the
/// schedule and the history move).
pub struct SamplingData {
    /// `SamplingParams`: the sampling pass and the sender-sky march.
    pub buffer: wgpu::Buffer,
    /// `FilterParams`: the upsample, the blur and the temporal pass.
    pub filter_buffer: wgpu::Buffer,
    uniforms: Box<SamplingParams>,
    kernel_key: Option<(Variant, usize)>,
}

impl SamplingData {
    pub fn new(device: &wgpu::Device) -> Self {
        let uniform = |label, size| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        Self {
            buffer: uniform("sampling_params", std::mem::size_of::<SamplingParams>() as u64),
            filter_buffer: uniform("filter_params", std::mem::size_of::<FilterParams>() as u64),
            uniforms: Box::new(bytemuck::Zeroable::zeroed()),
            kernel_key: None,
        }
    }

    /// Writes the parameters (their counts already clamped); the kernel is regenerated only when
    /// the variant or the sample count changes.
    pub fn update(&mut self, queue: &wgpu::Queue, params: &SamplingFrame) {
        let (knobs, lengths) = (&params.knobs, &params.lengths);
        let (variant, samples) = (knobs.variant, knobs.samples);
        if self.kernel_key != Some((variant, samples)) {
            for (slot, k) in self.uniforms.kernel.iter_mut().zip(kernel::kernel(variant.decl().kernel, samples)) {
                *slot = k.extend(0.0).into();
            }
            self.uniforms.rotations = kernel::rotations(variant.decl().kernel);
            self.kernel_key = Some((variant, samples));
        }
        let u = self.uniforms.as_mut();
        (u.radius, u.bias_length, u.sample_count, u.sky_mip) =
            (lengths.radius, lengths.bias_length, samples as u32, params.sky_mip);
        (u.sky_strength, u.indirect_strength) = (params.sky_strength, params.indirect_strength);
        u.sender_sky_strength = params.sender_sky_strength;
        u.schedule = params.schedule;
        (u.slices, u.steps, u.reach, u.thickness) =
            (knobs.slices as u32, knobs.steps as u32, lengths.reach, lengths.thickness);
        queue.write_buffer(&self.buffer, 0, bytemuck::bytes_of(self.uniforms.as_ref()));
        let filter = FilterParams {
            radius: lengths.radius,
            accumulate: params.accumulate,
            motion_accumulate: params.motion_accumulate,
            history_frames: params.history_frames,
        };
        queue.write_buffer(&self.filter_buffer, 0, bytemuck::bytes_of(&filter));
    }

    /// The bytes of both uniforms.
    pub fn bytes(&self) -> u64 {
        self.buffer.size() + self.filter_buffer.size()
    }
}
