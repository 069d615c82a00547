//! Tone mapping: linear HDR → exposure → ACES filmic curve → sRGB into the output (the capture
//! texture or the window's surface). For an sRGB output format the hardware encodes; for a
//! linear one the shader does (`OUTPUT_SRGB = false`). The debug views (G-buffer channels, AO, DO)
//! are variants of this pass, so showing one costs no extra pass.

use crate::render::graph::io::{PassIo, Read};
use crate::render::graph::state::{flag, PassState, PipelineSpec};
use crate::render::graph::Entry;
use crate::render::graph::{Pass, PassContext, Preparation, Recording};
use crate::render::modes::{Plan, Step};
use crate::render::settings::View;
use crate::render::targets::{ALBEDO, DEPTH, HDR, NORMAL, OUTPUT, THICKNESS};
use crate::Result;

impl Step {
    pub const TONEMAP: Step = Step::new("tonemap");
}

// A display plan's composite tone-maps itself.
pub const ENTRY: Entry =
    Entry::new(Step::TONEMAP, |f| !f.options.display, TonemapPass::io, |cx| Ok(Box::new(TonemapPass::new(cx)?)))
        .binding(&["tonemap.wgsl"]);

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Key {
    view: u32,
    ao: bool,
    directional: bool,
    thickness_layer: bool,
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
            View::Thickness => 6,
        };
        let (ao, directional) = (plan.decl.ambient_occlusion, plan.decl.directional_occlusion);
        Self { view: code, ao, directional, thickness_layer: plan.thickness_layer }
    }
}

pub struct TonemapPass {
    state: PassState<Key>,
    output: wgpu::TextureFormat,
}

impl TonemapPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        Ok(Self { state: PassState::new(cx, "tonemap", "tonemap.wgsl", false)?, output: cx.output })
    }

    /// HDR, and for the debug views the G-buffer and what the composite reads of the sampling
    /// chain, and the thickness layer; the output.
    pub fn io(plan: &Plan) -> PassIo {
        let mut reads = vec![Read::Target(HDR), Read::Target(ALBEDO), Read::Target(NORMAL), Read::Target(DEPTH)];
        reads.extend(occlusion_reads(plan));
        reads.push(Read::target_if(plan.thickness_layer, THICKNESS));
        PassIo { reads, attached: vec![], writes: vec![OUTPUT] }
    }
}

/// What the debug views read of the sampling chain: its last stage at full size (after a
/// half-size chain, the upsample pass's copy), AO alone or DO + AO, the other absent.
fn occlusion_reads(plan: &Plan) -> [Read; 2] {
    let stage = plan.chain_end(false);
    let (sampled, d) = (plan.decl.runs_sampling(), plan.decl.directional_occlusion);
    [Read::target_if(sampled && !d, stage.target(false)), Read::target_if(sampled && d, stage.target(true))]
}

impl Pass for TonemapPass {
    /// Builds the pipeline for the plan and view (if it changed) and the bind group for `targets`.
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { plan, view, .. } = *p;
        let output = self.output;
        self.state.prepare_fullscreen(
            device,
            p,
            (Step::TONEMAP, Self::io),
            || Key::of(plan, view),
            |key| PipelineSpec {
                entry: "fs_main",
                targets: vec![Some(output.into())],
                constants: vec![
                    ("OUTPUT_SRGB", flag(output.is_srgb())),
                    ("VIEW", key.view as f64),
                    ("HAS_AO", flag(key.ao)),
                    ("HAS_DO", flag(key.directional)),
                    ("THICKNESS_LAYER", flag(key.thickness_layer)),
                ],
            },
        );
    }

    fn record(&self, rec: Recording<'_>) {
        let attachments = rec.attachments(self.state.writes(), true);
        let viewport = Some(rec.viewport());
        self.state.draw((rec.encoder, rec.timestamps), &attachments, (rec.frame, None), viewport);
    }
}
