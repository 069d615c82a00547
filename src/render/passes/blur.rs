//! Denoise of the sampling pass's output (`shaders/blur.wgsl`): a 4x4 window, bilateral (plane
//! distance and normal agreement) in the default variant, the classic box blur otherwise. Where
//! the samples were taken at half resolution it runs there, on a quarter of the pixels, before
//! the upsample: its window is that of the rotation tile the samples were taken with.
//! A still view's frames after its first few skip it (`BLURRED_FRAMES`): the temporal pass then
//! reads the raw samples. A half-resolution plan that averages over frames has no blur pass: its
//! temporal pass blurs as it reads the samples (`PlanFacts::temporal_blurs`).

use super::sampling::{filter_io, Outputs};
use crate::render::graph::io::PassIo;
use crate::render::graph::state::{flag, PassState, PipelineSpec};
use crate::render::graph::{Entry, FrameState, Pass, PassContext, Preparation, Recording, Role};
use crate::render::modes::{Plan, Step};
use crate::render::variant::Blur;
use crate::Result;

impl Step {
    pub const BLUR: Step = Step::new("blur");
}

pub const ENTRY: Entry = Entry::new(
    Step::BLUR,
    |f| f.samples() && f.options.blur && !f.temporal_blurs(),
    BlurPass::io,
    |cx| Ok(Box::new(BlurPass::new(cx)?)),
)
.binding(&["blur.wgsl"])
.role(Role::Denoise);

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Key {
    outputs: Outputs,
    bilateral: bool,
}

pub struct BlurPass {
    state: PassState<Key>,
    /// This frame skips the blur (set in `begin_frame`).
    skip: bool,
}

impl BlurPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        Ok(Self { state: PassState::new(cx, "blur", "blur.wgsl", false)?, skip: false })
    }

    /// The G-buffer, the parameters and the sampling output; the output blurred (at half size
    /// where the samples are, for the upsample).
    pub fn io(plan: &Plan) -> PassIo {
        filter_io(plan, plan.sampled(false, false), plan.sampled(false, true))
    }
}

impl Pass for BlurPass {
    /// Builds what the plan needs (nothing when it does not blur).
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let key = || Key { outputs: Outputs::of(p.plan), bilateral: p.variant.decl().blur == Blur::Bilateral };
        self.state.prepare_fullscreen(device, p, (Step::BLUR, Self::io), key, |key| PipelineSpec {
            entry: "fs_main",
            targets: vec![Some(key.outputs.format().into())],
            constants: vec![("BILATERAL", flag(key.bilateral)), ("HAS_DO", flag(key.outputs.directional))],
        });
    }

    fn begin_frame(&mut self, frame: &FrameState<'_>) {
        self.skip = !frame.blur;
    }

    fn record(&self, rec: Recording<'_>) {
        if self.skip {
            rec.skip(self.state.writes());
        } else {
            self.state.record(rec);
        }
    }
}
