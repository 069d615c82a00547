//! The upsample after a half-resolution sampling pass (`shaders/upsample.wgsl`): the half-size
//! AO or DO + AO brought to full resolution, each pixel taking only the samples on its own
//! surface, so silhouettes keep no halo. It writes the full-resolution raw target, which the blur
//! and the temporal pass read as they would the sampling pass's own.

use super::super::modes::Step;
use super::occlusion::Outputs;
use super::state::{flag, state_pass, PassState, PipelineSpec};
use super::{color_attachment, filter_entries, filter_layout};
use super::{Pass, PassContext, Preparation, Recording};
use crate::Result;

state_pass!(UpsamplePass, Outputs, "upsample", "upsample.wgsl", sky: false, filter_layout);

impl Pass for UpsamplePass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { targets, plan, data, .. } = *p;
        let input = targets.half.as_ref().and_then(|h| h.output()).filter(|_| plan.has(Step::Upsample));
        let Some(input) = self.state.input(input) else { return };
        self.state.ensure_fullscreen(device, Outputs::of(plan), |outputs| PipelineSpec {
            entry: "fs_main",
            targets: vec![Some(outputs.format().into())],
            constants: vec![("HAS_DO", flag(outputs.directional))],
        });
        self.state.bind(device, &filter_entries(targets, data, &input.view));
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, .. } = rec;
        let output = targets.raw.output().expect("a plan that upsamples has its full-resolution target");
        self.state.draw((encoder, timestamps), &[color_attachment(&output.view, true)], (frame, None), None);
    }
}
