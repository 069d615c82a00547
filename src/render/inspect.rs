//! What the renderer tells of itself: its GPU time per step, its plan as `--print-plan` lists it,
//! and the bytes it holds on the GPU.

use super::targets::TargetId;
use super::timer::GpuTimer;
use super::{Renderer, Step};
use crate::gpu::Gpu;
use crate::Result;

impl Renderer {
    /// Starts recording per-step GPU times (needs timestamp queries on the device).
    pub fn enable_timing(&mut self, gpu: &Gpu) -> bool {
        if gpu.timestamps && self.timer.is_none() {
            self.timer = Some(GpuTimer::new(gpu, &self.plan));
        }
        self.timer.is_some()
    }

    /// Starts reading back the timestamps of the frame just submitted (call after
    /// `queue.submit` of an encoder given to [`Renderer::encode`]; without it no timings arrive).
    pub fn timings_submitted(&mut self) {
        if let Some(timer) = &mut self.timer {
            timer.submitted();
        }
    }

    /// Per-step GPU milliseconds of the newest submitted frame, waiting for the GPU.
    pub fn read_timings(&mut self, gpu: &Gpu) -> Result<Option<Vec<(Step, f64)>>> {
        let plan = &self.plan;
        self.timer.as_mut().map(|t| t.wait(gpu, plan)).transpose().map(Option::flatten)
    }

    /// Per-step GPU milliseconds of the newest frame whose timestamps have arrived since the last
    /// call, without waiting (the viewer's readback, a frame or two behind).
    pub fn poll_timings(&mut self, gpu: &Gpu) -> Result<Option<Vec<(Step, f64)>>> {
        let plan = &self.plan;
        self.timer.as_mut().map(|t| t.poll(gpu, plan)).transpose().map(Option::flatten)
    }

    /// The plan as `--print-plan` prints it: each step with what it reads and writes, then the
    /// bytes of each allocation and their total.
    pub fn plan_listing(&self) -> String {
        let plan = &self.plan;
        let mut text = format!("plan {}:", plan.mode);
        let names = |ids: &[TargetId]| ids.iter().map(|t| t.name()).collect::<Vec<_>>().join(" ");
        for (step, io) in plan.io() {
            let (name, reads, writes) = (step.name_in(plan.mode), names(&io.reads), names(&io.writes));
            text += &format!("\n  pass {name} reads [{reads}] writes [{writes}]");
        }
        let allocations = self.allocations();
        for (name, bytes) in &allocations {
            text += &format!("\n  bytes {name} {bytes}");
        }
        text + &format!("\n  bytes total {}", allocations.iter().map(|(_, b)| b).sum::<u64>())
    }

    /// Bytes allocated on the GPU, by name: screen targets first, then scene, sky and frame data.
    pub fn allocations(&self) -> Vec<(String, u64)> {
        let mut list: Vec<(String, u64)> =
            self.targets.allocations().into_iter().map(|(n, b)| (n.to_string(), b)).collect();
        list.extend(self.history.all().map(|h| (h.spec.name.to_string(), h.bytes())));
        list.push(("scene_geometry_and_materials".into(), self.scene.bytes));
        list.push(("sky_cubemap".into(), self.sky.bytes));
        list.push(("frame_uniforms_and_lights".into(), self.frame.bytes()));
        if self.plan.decl.runs_sampling() {
            list.push(("sampling_and_filter_params".into(), self.sampling_data.bytes()));
        }
        list
    }
}
