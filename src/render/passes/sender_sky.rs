//! The sender-sky march (`--sender-sky march`): before the lighting pass, at half resolution, the
//! sky each surface sees through one slice of the march (`fs_sender` in `shaders/march.wgsl`,
//! built with DO on and AO and the bounce off). The lighting pass turns it into the sky light each
//! sender bounces, so the bounce carries the sky with the sender's own visibility.

use super::super::modes::Step;
use super::super::targets::DO_FORMAT;
use super::color_attachment;
use super::occlusion::{sampling_entries, sampling_layout};
use super::state::{flag, state_pass, PassState, PipelineSpec};
use super::{Pass, PassContext, Preparation, Recording};
use crate::Result;

// Keyed by whether the far steps read the depth pyramid.
state_pass!(SenderSkyPass, bool, "sender_sky", "march.wgsl", sky: true, sampling_layout);

impl Pass for SenderSkyPass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        if !self.state.runs(p.plan.has(Step::SenderSky)) {
            return;
        }
        self.state.ensure_fullscreen(device, p.plan.has(Step::DepthPyramid), |pyramid| PipelineSpec {
            entry: "fs_sender",
            targets: vec![Some(DO_FORMAT.into())],
            constants: vec![("HAS_AO", 0.0), ("HAS_DO", 1.0), ("INDIRECT", 0.0), ("USE_PYRAMID", flag(pyramid))],
        });
        // The bounce source is what this pass feeds; it reads none.
        self.state.bind(device, &sampling_entries(p, p.unused));
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, sky, .. } = rec;
        let output = targets.sender_sky.as_ref().expect("a plan with the sender-sky march has its target");
        let attachments = [color_attachment(&output.view, true)];
        self.state.draw((encoder, timestamps), &attachments, (frame, Some(&sky.bind_group)), None);
    }
}
