//! Denoise of the sampling pass's output (`shaders/blur.wgsl`): a 4x4 window, bilateral (plane
//! distance and normal agreement) in the default variant, the classic box blur otherwise.

use super::super::variant::Blur;
use super::occlusion::Outputs;
use super::state::{flag, state_pass, PassState, PipelineSpec};
use super::{color_attachment, filter_entries, filter_layout};
use super::{Pass, PassContext, Preparation, Recording};
use crate::Result;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Key {
    outputs: Outputs,
    bilateral: bool,
}

state_pass!(BlurPass, Key, "blur", "blur.wgsl", sky: false, filter_layout);

impl Pass for BlurPass {
    /// Builds what the plan needs (nothing when it does not blur).
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { targets, plan, variant, data, .. } = *p;
        let Some(input) = self.state.input(targets.raw.output().filter(|_| plan.blur)) else { return };
        let key = Key { outputs: Outputs::of(plan), bilateral: variant.decl().blur == Blur::Bilateral };
        self.state.ensure_fullscreen(device, key, |key| PipelineSpec {
            entry: "fs_main",
            targets: vec![Some(key.outputs.format().into())],
            constants: vec![("BILATERAL", flag(key.bilateral)), ("HAS_DO", flag(key.outputs.directional))],
        });
        self.state.bind(device, &filter_entries(targets, data, &input.view));
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, .. } = rec;
        let output = targets.blurred.as_ref().and_then(|b| b.output()).expect("a plan that blurs has blurred targets");
        self.state.draw((encoder, timestamps), &[color_attachment(&output.view, true)], (frame, None), None);
    }
}
