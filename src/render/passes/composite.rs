//! Composite: ambient·albedo·AO + DO + direct point lighting into the linear HDR target, or, in a
//! display plan, with the tone curve straight into the output (no HDR write, no skybox or
//! tone-map pass; the sky's pixels as the G-buffer pass drew them for display). The pipeline is specialised to the plan (override constants):
//! without lights there is no light loop in the shader, without AO no AO read, and so on. After a
//! lighting pass it blends additively onto the direct light that pass wrote (HDR), or reads it
//! (display). After a half-size sampling chain it upsamples the chain's last stage as it reads it;
//! after the temporal pass, with the surface each sample holds taken from the surface history
//! that pass has just written (one load a tap instead of the G-buffer's depth and normal), so it
//! keeps a bind group for each side of that history.

use crate::render::graph::io::{PassIo, Read};
use crate::render::graph::state::{ParityGroups, PassState};
use crate::render::graph::{fullscreen_pipeline, Entry, FullscreenDesc};
use crate::render::graph::{Pass, PassContext, Preparation, Recording};
use crate::render::modes::{LightReads, Plan, Step, SURFACE_HISTORY};
use crate::render::settings::View;
use crate::render::targets::{ALBEDO, DEPTH, HDR, HDR_FORMAT, NORMAL, OUTPUT};
use crate::render::variant::{Composite, Variant};
use crate::Result;

impl Step {
    pub const COMPOSITE: Step = Step::new("composite");
}

pub const ENTRY: Entry =
    Entry::new(Step::COMPOSITE, |_| true, CompositePass::io, |cx| Ok(Box::new(CompositePass::new(cx)?)))
        .binding(&["composite.wgsl"]);

/// The shader variant a plan needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Key {
    light_loop: bool,
    lights: LightReads,
    additive: bool,
    ao: bool,
    directional: bool,
    classic: bool,
    white_albedo: bool,
    display: bool,
    /// ... and is the temporal pass's average, whose surfaces its surface history holds.
    guide: bool,
    /// ... and holds its DO over the sky's irradiance at each sample's normal
    /// (`Plan::do_over_irradiance`).
    over_irradiance: bool,
}

impl Key {
    fn of(plan: &Plan, variant: Variant, white_albedo: bool) -> Self {
        Self {
            light_loop: plan.light_loop(),
            lights: plan.light_reads(),
            additive: plan.lighting_writes_direct(),
            ao: plan.decl.ambient_occlusion,
            directional: plan.decl.directional_occlusion,
            classic: variant.decl().composite == Composite::ClassicAmbient,
            white_albedo,
            display: plan.display,
            guide: guided(plan),
            over_irradiance: plan.do_over_irradiance(),
        }
    }
}

/// Whether the composite upsamples the temporal pass's half-size average, reading the surface
/// of each sample from the surface history that pass wrote this frame.
fn guided(plan: &Plan) -> bool {
    plan.half_resolution && plan.accumulates()
}

pub struct CompositePass {
    state: PassState<Key>,
    /// The output's format (display plans draw into it).
    output: wgpu::TextureFormat,
    /// Group 1 for each side of the surface history, where the plan reads it (`Key::guide`).
    guided_groups: Option<ParityGroups>,
}

impl CompositePass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        let state = PassState::new(cx, "composite", "composite.wgsl", false)?;
        Ok(Self { state, output: cx.output, guided_groups: None })
    }

    /// The G-buffer, the filters' parameters (the upsample's), the sampling chain's last stage
    /// (AO alone or DO + AO, at half size where the samples are) and in a display plan the
    /// lighting pass's direct light (blended onto otherwise, where it is the attachment and
    /// cannot also be bound), and after the temporal pass at half size the surface history it
    /// wrote this frame; HDR, or in a display plan the output.
    pub fn io(plan: &Plan) -> PassIo {
        let mut reads = vec![Read::Target(ALBEDO), Read::Target(NORMAL), Read::Target(DEPTH), Read::Filter];
        let stage = plan.sampled(plan.accumulates, plan.blur);
        reads.push(Read::target_if(plan.decl.runs_sampling(), stage.target(plan.decl.directional_occlusion)));
        reads.push(Read::target_if(plan.display && plan.lighting_writes_direct(), HDR));
        reads.push(if guided(plan) { Read::Written(SURFACE_HISTORY) } else { Read::Absent(SURFACE_HISTORY) });
        PassIo { reads, attached: vec![], writes: vec![if plan.display { OUTPUT } else { HDR }] }
    }
}

impl Pass for CompositePass {
    /// Builds the pipeline the plan needs (if it changed) and the bind group for `targets`.
    /// `white_albedo` is the "lighting only" view: every surface white.
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { plan, variant, view, .. } = *p;
        let io = Self::io(plan);
        self.state.bind(device, &io, &p.inputs);
        self.guided_groups = guided(plan).then(|| self.state.parity_groups(device, &io, &p.inputs));
        let white_albedo = view == View::LightingOnly;
        let key = Key::of(plan, variant, white_albedo);
        let output = self.output;
        self.state.ensure(plan, key, |key, module, layouts, shared| {
            let f = |b: bool| b as u8 as f64;
            let blend = (key.additive && !key.display).then_some(wgpu::BlendState {
                color: wgpu::BlendComponent {
                    src_factor: wgpu::BlendFactor::One,
                    dst_factor: wgpu::BlendFactor::One,
                    operation: wgpu::BlendOperation::Add,
                },
                alpha: wgpu::BlendComponent::REPLACE,
            });
            let constants: Vec<_> = [
                ("LIGHT_LOOP", f(key.light_loop)),
                ("HAS_AO", f(key.ao)),
                ("HAS_DO", f(key.directional)),
                ("CLASSIC", f(key.classic)),
                ("WHITE_ALBEDO", f(key.white_albedo)),
                ("DISPLAY", f(key.display)),
                ("OUTPUT_SRGB", f(output.is_srgb())),
                ("DIRECT_INPUT", f(key.display && key.additive)),
                ("GUIDE_INPUT", f(key.guide)),
                ("DO_OVER_IRRADIANCE", f(key.over_irradiance)),
            ]
            .into_iter()
            .chain(key.lights.constants())
            .chain(shared)
            .collect();
            fullscreen_pipeline(
                device,
                &FullscreenDesc {
                    label: "composite_pipeline",
                    module,
                    entry: "fs_main",
                    bind_group_layouts: layouts,
                    targets: &[Some(wgpu::ColorTargetState {
                        format: if key.display { output } else { HDR_FORMAT },
                        blend,
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                    depth: None,
                    constants: &constants,
                },
            )
        });
    }

    fn record(&self, rec: Recording<'_>) {
        let (key, _, own) = self.state.ready();
        // Onto the lighting pass's direct light (kept), or cleared; a display plan at its origin.
        let keep = key.additive && !key.display;
        let attachments = rec.attachments(self.state.writes(), !keep);
        let viewport = key.display.then(|| rec.viewport());
        // The side of the surface history the temporal pass wrote this frame.
        let written = rec.history.get(SURFACE_HISTORY).zip(self.guided_groups.as_ref());
        let own = written.map_or(own, |(history, groups)| groups.of(history));
        self.state.draw_with((rec.encoder, rec.timestamps), &attachments, (rec.frame, own, None), viewport);
    }
}
