//! The upsample after a half-resolution sampling pass (`shaders/upsample.wgsl`): the half-size
//! AO or DO + AO brought to full resolution, each pixel taking only the samples on its own
//! surface, so silhouettes keep no halo. It writes the full-resolution raw target, which the blur
//! and the temporal pass read as they would the sampling pass's own.

use super::sampling::Outputs;
use crate::render::graph::io::{PassIo, Read};
use crate::render::graph::state::{flag, PassState, PipelineSpec};
use crate::render::graph::{no_history, Entry, Pass, PassContext, Preparation, Recording};
use crate::render::modes::{Plan, Step};
use crate::render::targets::{Stage, ALBEDO, DEPTH, NORMAL};
use crate::Result;

impl Step {
    pub const UPSAMPLE: Step = Step::new("upsample");
}

pub const ENTRY: Entry = Entry {
    step: Step::UPSAMPLE,
    runs: |f| f.samples() && f.options.half_resolution,
    io: UpsamplePass::io,
    histories: no_history,
    group_shaders: &["upsample.wgsl"],
    build: |cx| Ok(Box::new(UpsamplePass::new(cx)?)),
};

pub struct UpsamplePass {
    state: PassState<Outputs>,
}

impl UpsamplePass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        Ok(Self { state: PassState::new(cx, "upsample", "upsample.wgsl", false)? })
    }

    /// The G-buffer, the parameters and the half-size samples; the full-size ones.
    pub fn io(plan: &Plan) -> PassIo {
        let d = plan.decl.directional_occlusion;
        let half = Read::Target(Stage::Half.target(d));
        let reads = vec![Read::Target(ALBEDO), Read::Target(NORMAL), Read::Target(DEPTH), Read::Filter, half];
        PassIo { reads, attached: vec![], writes: vec![Stage::Raw.target(d)] }
    }
}

impl Pass for UpsamplePass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        if !self.state.runs(p.plan.has(Step::UPSAMPLE)) {
            return;
        }
        self.state.bind(device, &Self::io(p.plan), &p.inputs);
        self.state.ensure_fullscreen(device, Outputs::of(p.plan), |outputs| PipelineSpec {
            entry: "fs_main",
            targets: vec![Some(outputs.format().into())],
            constants: vec![("HAS_DO", flag(outputs.directional))],
        });
    }

    fn record(&self, rec: Recording<'_>) {
        let attachments = crate::render::graph::io::attachments(
            &Self::io(rec.plan).writes,
            rec.targets,
            rec.history,
            rec.output,
            true,
        );
        self.state.draw((rec.encoder, rec.timestamps), &attachments, (rec.frame, None), None);
    }
}
