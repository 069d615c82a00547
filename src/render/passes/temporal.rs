//! The temporal pass (`shaders/temporal.wgsl`): the blurred (or raw) sampling output averaged
//! with the last frames' where the same surface was, reprojected through the previous camera.
//! It writes three targets at once: what the composite reads this frame (`ao_accumulated` /
//! `do_accumulated`), and the two histories the next frame reads (`history.rs`). Its bind group
//! reads one side of each history pair, so it keeps one group a parity and binds the frame's.

use super::super::history::History;
use super::super::modes::{OCCLUSION_HISTORY, SURFACE_HISTORY, SURFACE_HISTORY_FORMAT};
use super::occlusion::Outputs;
use super::state::{flag, PassState, PipelineSpec};
use super::{color_attachment, gbuffer_entries, texture_entry, uint_entry, uniform_entry};
use super::{FrameState, Pass, PassContext, Preparation, Recording};
use crate::Result;
use wgpu::TextureViewDimension::D2;

pub struct TemporalPass {
    /// Keyed by what the sampling pass produces (AO alone, or DO + AO): the pipeline for a frame
    /// whose camera moved (reprojecting), and the one for a still camera (each pixel its own).
    state: PassState<Outputs>,
    still: PassState<Outputs>,
    /// This frame's camera moved (set in `begin_frame`).
    camera_moved: bool,
    /// Group 1 for a frame that writes side 0 of the histories, and for one that writes side 1.
    groups: Option<[wgpu::BindGroup; 2]>,
}

impl TemporalPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        let [a, n, d] = gbuffer_entries();
        let input = |b| texture_entry(b, false, D2);
        let layout = cx.layout("temporal_layout", &[a, n, d, uniform_entry(3), input(4), input(5), uint_entry(6)]);
        let state = PassState::new(cx, "temporal", "temporal.wgsl", false, layout)?;
        let still = state.sibling("temporal_still");
        Ok(Self { state, still, camera_moved: false, groups: None })
    }
}

/// The histories of a plan that accumulates.
fn pairs(history: &History) -> (&super::super::history::PingPong, &super::super::history::PingPong) {
    match (history.get(OCCLUSION_HISTORY), history.get(SURFACE_HISTORY)) {
        (Some(o), Some(s)) => (o, s),
        _ => unreachable!("a plan that accumulates has its histories"),
    }
}

impl Pass for TemporalPass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { targets, plan, data, history, .. } = *p;
        if !plan.accumulates() {
            self.state.clear();
            self.still.clear();
            self.groups = None;
            return;
        }
        for (state, moved) in [(&mut self.state, true), (&mut self.still, false)] {
            state.ensure_fullscreen(device, Outputs::of(plan), |outputs| PipelineSpec {
                entry: "fs_main",
                targets: vec![
                    Some(outputs.format().into()),
                    Some(outputs.format().into()),
                    Some(SURFACE_HISTORY_FORMAT.into()),
                ],
                constants: vec![("CAMERA_MOVED", flag(moved))],
            });
        }
        let input = targets.filtered().output().expect("a plan that accumulates samples");
        let (occlusion, surface) = pairs(history);
        let group = |parity: usize| {
            let views = [&targets.albedo.view, &targets.normal.view, &targets.depth.view];
            let mut entries = super::view_entries(&views);
            let view = |b, v| wgpu::BindGroupEntry { binding: b, resource: wgpu::BindingResource::TextureView(v) };
            entries.extend([
                wgpu::BindGroupEntry { binding: 3, resource: data.buffer.as_entire_binding() },
                view(4, &input.view),
                view(5, &occlusion.read_side(parity).view),
                view(6, &surface.read_side(parity).view),
            ]);
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("temporal_bind_group"),
                layout: &self.state.layout,
                entries: &entries,
            })
        };
        self.groups = Some([group(0), group(1)]);
    }

    fn begin_frame(&mut self, frame: &FrameState<'_>) {
        self.camera_moved = frame.camera_moved;
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, history, .. } = rec;
        let (occlusion, surface) = pairs(history);
        let parity = occlusion.parity();
        debug_assert_eq!(parity, surface.parity(), "the two histories advance together");
        let shown =
            targets.accumulated.as_ref().and_then(|a| a.output()).expect("a plan that accumulates has its target");
        let groups = self.groups.as_ref().expect("the temporal pass recorded before `prepare`");
        let attachments = [
            color_attachment(&shown.view, true),
            color_attachment(&occlusion.write().view, true),
            color_attachment(&surface.write().view, true),
        ];
        let state = if self.camera_moved { &self.state } else { &self.still };
        state.draw_with((encoder, timestamps), &attachments, (frame, &groups[parity], None), None);
    }
}
