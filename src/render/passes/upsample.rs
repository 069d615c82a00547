//! The upsample after a half-resolution sampling chain (`shaders/upsample.wgsl`): the half-size
//! AO or DO + AO brought to full resolution, each pixel taking only the samples on its own
//! surface, so silhouettes keep no halo. The composite upsamples the chain's last half-size
//! stage itself as it reads it (the same function, `shaders/common/upsample.wgsl`), so this pass
//! runs only in an HDR plan, where the full-size copy has readers of its own: the debug views,
//! `--stats` and the report's AO and DO errors. It reads the average over frames, or without
//! accumulation the samples blurred where the plan blurs, and writes the full-size target of the
//! same stage.

use super::sampling::{filter_io, Outputs};
use crate::render::graph::io::PassIo;
use crate::render::graph::state::{flag, PassState, PipelineSpec};
use crate::render::graph::{Entry, Pass, PassContext, Preparation, Recording, Role};
use crate::render::modes::{Plan, Step};
use crate::Result;

impl Step {
    pub const UPSAMPLE: Step = Step::new("upsample");
}

pub const ENTRY: Entry = Entry::new(
    Step::UPSAMPLE,
    // A display plan's composite upsamples as it reads, and nothing else reads a full-size copy.
    |f| f.half_resolution() && !f.options.display,
    UpsamplePass::io,
    |cx| Ok(Box::new(UpsamplePass::new(cx)?)),
)
.binding(&["upsample.wgsl"])
.role(Role::Denoise);

pub struct UpsamplePass {
    /// Keyed by the outputs and whether the DO is held over the samples' irradiance.
    state: PassState<(Outputs, bool)>,
}

impl UpsamplePass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        Ok(Self { state: PassState::new(cx, "upsample", "upsample.wgsl", false)? })
    }

    /// The G-buffer, the parameters and the chain's last half-size stage; its full-size copy.
    pub fn io(plan: &Plan) -> PassIo {
        filter_io(plan, plan.chain_end(true), plan.chain_end(false))
    }
}

impl Pass for UpsamplePass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let key = || (Outputs::of(p.plan), p.plan.do_over_irradiance());
        self.state.prepare_fullscreen(device, p, (Step::UPSAMPLE, Self::io), key, |(outputs, over_irradiance)| {
            PipelineSpec {
                entry: "fs_main",
                targets: vec![Some(outputs.format().into())],
                constants: vec![("HAS_DO", flag(outputs.directional)), ("DO_OVER_IRRADIANCE", flag(over_irradiance))],
            }
        });
    }

    fn record(&self, rec: Recording<'_>) {
        self.state.record(rec);
    }
}
