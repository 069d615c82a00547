//! Denoise of the sampling pass's output (`shaders/blur.wgsl`): a 4x4 window, bilateral (plane
//! distance and normal agreement) in the default variant, the classic box blur otherwise.

use super::sampling::Outputs;
use crate::render::graph::io::{PassIo, Read};
use crate::render::graph::state::{flag, PassState, PipelineSpec};
use crate::render::graph::{no_history, Entry, Pass, PassContext, Preparation, Recording};
use crate::render::modes::{Plan, Step};
use crate::render::targets::{Stage, ALBEDO, DEPTH, NORMAL};
use crate::render::variant::Blur;
use crate::Result;

impl Step {
    pub const BLUR: Step = Step::new("blur");
}

pub const ENTRY: Entry = Entry {
    step: Step::BLUR,
    runs: |f| f.samples() && f.options.blur,
    io: BlurPass::io,
    histories: no_history,
    group_shaders: &["blur.wgsl"],
    build: |cx| Ok(Box::new(BlurPass::new(cx)?)),
};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Key {
    outputs: Outputs,
    bilateral: bool,
}

pub struct BlurPass {
    state: PassState<Key>,
}

impl BlurPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        Ok(Self { state: PassState::new(cx, "blur", "blur.wgsl", false)? })
    }

    /// The G-buffer, the parameters and the sampling output; the output blurred.
    pub fn io(plan: &Plan) -> PassIo {
        let d = plan.decl.directional_occlusion;
        let raw = Read::Target(Stage::Raw.target(d));
        let reads = vec![Read::Target(ALBEDO), Read::Target(NORMAL), Read::Target(DEPTH), Read::Filter, raw];
        PassIo { reads, attached: vec![], writes: vec![Stage::Blurred.target(d)] }
    }
}

impl Pass for BlurPass {
    /// Builds what the plan needs (nothing when it does not blur).
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        if !self.state.runs(p.plan.has(Step::BLUR)) {
            return;
        }
        self.state.bind(device, &Self::io(p.plan), &p.inputs);
        let key = Key { outputs: Outputs::of(p.plan), bilateral: p.variant.decl().blur == Blur::Bilateral };
        self.state.ensure_fullscreen(device, key, |key| PipelineSpec {
            entry: "fs_main",
            targets: vec![Some(key.outputs.format().into())],
            constants: vec![("BILATERAL", flag(key.bilateral)), ("HAS_DO", flag(key.outputs.directional))],
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
