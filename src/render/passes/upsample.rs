//! The upsample after a half-resolution sampling pass (`shaders/upsample.wgsl`): the half-size
//! AO or DO + AO brought to full resolution, each pixel taking only the samples on its own
//! surface, so silhouettes keep no halo. It reads the half-size samples blurred where the plan
//! blurs (the blur runs before it, at half size) and writes the full-resolution target the
//! composite reads: the blurred one, or the raw one without a blur. It runs only where nothing
//! is accumulated: the temporal pass upsamples as it reads (the same function,
//! `shaders/common/upsample.wgsl`), one full-screen pass fewer.

use super::sampling::{filter_io, Outputs};
use crate::render::graph::io::PassIo;
use crate::render::graph::state::{flag, PassState, PipelineSpec};
use crate::render::graph::{Entry, Pass, PassContext, Preparation, Recording, Role};
use crate::render::modes::{Plan, Step};
use crate::render::targets::Stage;
use crate::Result;

impl Step {
    pub const UPSAMPLE: Step = Step::new("upsample");
}

pub const ENTRY: Entry = Entry::new(
    Step::UPSAMPLE,
    // With accumulation the temporal pass upsamples as it reads: one full-screen pass fewer.
    |f| f.samples() && f.options.half_resolution && !f.options.accumulate,
    UpsamplePass::io,
    |cx| Ok(Box::new(UpsamplePass::new(cx)?)),
)
.binding(&["upsample.wgsl"])
.role(Role::Denoise);

pub struct UpsamplePass {
    state: PassState<Outputs>,
}

impl UpsamplePass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        Ok(Self { state: PassState::new(cx, "upsample", "upsample.wgsl", false)? })
    }

    /// The G-buffer, the parameters and the half-size samples (blurred, where the plan blurs);
    /// the full-size ones.
    pub fn io(plan: &Plan) -> PassIo {
        match plan.blur {
            true => filter_io(plan, Stage::HalfBlurred, Stage::Blurred),
            false => filter_io(plan, Stage::Half, Stage::Raw),
        }
    }
}

impl Pass for UpsamplePass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let key = || Outputs::of(p.plan);
        self.state.prepare_fullscreen(device, p, (Step::UPSAMPLE, Self::io), key, |outputs| PipelineSpec {
            entry: "fs_main",
            targets: vec![Some(outputs.format().into())],
            constants: vec![("HAS_DO", flag(outputs.directional))],
        });
    }

    fn record(&self, rec: Recording<'_>) {
        self.state.record(rec);
    }
}
