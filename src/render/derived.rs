//! What the renderer derives each frame from its settings and the scene: the lengths in model
//! units (radius, reach, thickness), the pre-exposure that keeps half floats in range, and the
//! frame uniforms and sampling parameters computed from them.

use glam::Vec3;

use super::frame::{pre_exposure_for, FrameInputs};
use super::kernel;
use super::modes::OCCLUSION_HISTORY;
use super::resources::sampling::SamplingFrame;
use super::sampling::Lengths;
use super::settings::{motion_accumulate, View};
use super::Renderer;
use crate::scene::OrbitCamera;

/// What the frame's uniforms and the sampling parameters are computed from: the settings, the
/// scene's scale, the sky and the lights.
impl Renderer {
    /// The factor between radiance and what the half-float buffers (HDR, bounce, DO) hold.
    ///
    /// Half floats end at 65504; a sky of 1e5 or a thousand lights would overflow them. Each
    /// frame scales radiance by `min(1, 4096 / peak)`, where `peak` bounds the frame's brightest
    /// radiance (the sky's peak, the ambient, and every light's irradiance at its clamp
    /// distance), and the tone mapper divides it back out. Readers of those buffers divide too.
    pub fn pre_exposure(&self) -> f32 {
        let s = &self.settings;
        let sky = self.sky.peak * s.sky_scale * s.sky_strength.max(1.0);
        let min_d2 = (self.rig.min_distance * self.rig.min_distance).max(f32::MIN_POSITIVE);
        let lights: f32 = self.lights.iter().map(|l| l.intensity * l.color.max_element() / min_d2).sum();
        pre_exposure_for(sky.max(s.ambient).max(lights * s.knobs.indirect_strength.max(1.0)))
    }

    /// The sampling radius in use, in model units.
    pub fn radius(&self) -> f32 {
        self.lengths().radius
    }

    /// The radius, reach, thickness and bias in use, in model units.
    pub fn lengths(&self) -> Lengths {
        self.settings.lengths(self.scene_radius)
    }

    /// Writes this frame's uniforms and, when the plan samples, the sampling parameters.
    pub(super) fn upload_frame(&mut self, gpu: &crate::gpu::Gpu, camera: &OrbitCamera, origin: (u32, u32)) {
        let s = self.settings;
        let inputs = FrameInputs {
            size: self.targets.size,
            exposure: s.exposure,
            ambient: Vec3::splat(s.ambient),
            sky_scale: s.sky_scale * self.sky.encode_scale,
            sky_mips: self.sky.mip_levels,
            pre_exposure: self.pre_exposure(),
            ao_strength: s.ao_strength,
            ao_power: s.ao_power,
            sky_sh: self.sky_sh.map(|c| c * (s.sky_scale * s.sky_strength)),
            output_origin: origin,
            default_thickness: self.lengths().default_thickness,
        };
        self.frame.update(&gpu.device, &gpu.queue, camera, &self.lights, &self.rig, &inputs);
        if self.plan.decl.runs_sampling() {
            let knobs = s.knobs.clamped();
            // The frames the temporal pass's history holds: this frame's place in the schedule.
            let held = self.history.get(OCCLUSION_HISTORY).map_or(0, |h| h.frames);
            let accumulate = if self.plan.accumulates() { knobs.accumulate as u32 } else { 1 };
            // The sky's mip is the solid angle of one direction of the converged average: the
            // frames' directions differ (the schedule), so together they resolve finer detail.
            let directions = knobs.sky_directions() * accumulate as usize;
            let params = SamplingFrame {
                knobs,
                lengths: self.lengths(),
                sky_mip: kernel::sky_mip_level(self.sky.size, directions),
                sky_strength: if s.view == View::DoIndirect { 0.0 } else { s.sky_strength },
                indirect_strength: if s.view == View::DoDirect { 0.0 } else { knobs.indirect_strength },
                sender_sky_strength: s.sky_strength,
                schedule: kernel::schedule(held.wrapping_add(self.schedule_start)),
                accumulate,
                motion_accumulate: accumulate.min(motion_accumulate(s.mode)),
                history_frames: held,
            };
            self.sampling_data.update(&gpu.queue, &params);
        }
    }
}
