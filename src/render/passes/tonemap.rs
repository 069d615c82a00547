//! Tone mapping: linear HDR → exposure → ACES filmic curve → sRGB into the output (the capture
//! texture or the window's surface). For an sRGB output format the hardware encodes; for a
//! linear one the shader does (`OUTPUT_SRGB = false`). The debug views (G-buffer channels, AO, DO)
//! are variants of this pass, so showing one costs no extra pass.

use super::super::modes::Plan;
use super::super::targets::view_or;
use super::super::View;
use super::state::{flag, PassState, PipelineSpec};
use super::{color_attachment, depth_entry, texture_entry, view_entries};
use super::{Pass, PassContext, Preparation, Recording};
use crate::Result;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Key {
    view: u32,
    ao: bool,
    directional: bool,
}

impl Key {
    fn of(plan: &Plan, view: View) -> Self {
        let code = match view {
            View::Final | View::LightingOnly => 0,
            View::Albedo => 1,
            View::Normals => 2,
            View::Depth => 3,
            View::Ao => 4,
            View::DoDirect | View::DoIndirect => 5,
        };
        Self { view: code, ao: plan.decl.ambient_occlusion, directional: plan.decl.directional_occlusion }
    }
}

pub struct TonemapPass {
    state: PassState<Key>,
    output: wgpu::TextureFormat,
}

impl TonemapPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        let float = |b| texture_entry(b, false, wgpu::TextureViewDimension::D2);
        let entries = [float(0), float(1), super::normal_entry(2), depth_entry(3), float(4), float(5)];
        let layout = cx.layout("tonemap_layout", &entries);
        Ok(Self { state: PassState::new(cx, "tonemap", "tonemap.wgsl", false, layout)?, output: cx.output })
    }
}

impl Pass for TonemapPass {
    /// Builds the pipeline for the plan and view (if it changed) and the bind group for `targets`.
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { targets, plan, view, unused, .. } = *p;
        let key = Key::of(plan, view);
        let output = self.output;
        self.state.ensure_fullscreen(device, key, |key| PipelineSpec {
            entry: "fs_main",
            targets: vec![Some(output.into())],
            constants: vec![
                ("OUTPUT_SRGB", flag(output.is_srgb())),
                ("VIEW", key.view as f64),
                ("HAS_AO", flag(key.ao)),
                ("HAS_DO", flag(key.directional)),
            ],
        });
        let occlusion = targets.occlusion();
        let views = [
            view_or(&targets.hdr, unused),
            &targets.albedo.view,
            &targets.normal.view,
            &targets.depth.view,
            view_or(&occlusion.ao, unused),
            view_or(&occlusion.directional, unused),
        ];
        self.state.bind(device, &view_entries(&views));
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, output, origin, .. } = rec;
        let (w, h) = targets.size;
        let viewport = Some([origin.0 as f32, origin.1 as f32, w as f32, h as f32]);
        self.state.draw((encoder, timestamps), &[color_attachment(output, true)], (frame, None), viewport);
    }
}
