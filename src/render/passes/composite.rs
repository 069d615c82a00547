//! Composite: ambient·albedo·AO + DO + direct point lighting into the linear HDR target, or, in a
//! display plan, with the sky and the tone curve straight into the output (no HDR write, no
//! skybox or tone-map pass). The pipeline is specialised to the plan (override constants):
//! without lights there is no light loop in the shader, without AO no AO read, and so on. After a
//! lighting pass it blends additively onto the direct light that pass wrote (HDR), or reads it
//! (display).

use super::super::modes::Plan;
use super::super::targets::{view_or, HDR_FORMAT};
use super::super::variant::{Composite, Variant};
use super::super::View;
use super::state::PassState;
use super::{color_attachment, fullscreen_pipeline, gbuffer_entries, texture_entry, FullscreenDesc};
use super::{Pass, PassContext, Preparation, Recording};
use crate::Result;

/// The shader variant a plan needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Key {
    light_loop: bool,
    additive: bool,
    ao: bool,
    directional: bool,
    classic: bool,
    white_albedo: bool,
    display: bool,
}

impl Key {
    fn of(plan: &Plan, variant: Variant, white_albedo: bool) -> Self {
        Self {
            light_loop: plan.light_loop(),
            additive: plan.lighting_writes_direct(),
            ao: plan.decl.ambient_occlusion,
            directional: plan.decl.directional_occlusion,
            classic: variant.decl().composite == Composite::ClassicAmbient,
            white_albedo,
            display: plan.display,
        }
    }
}

pub struct CompositePass {
    state: PassState<Key>,
    /// The output's format (display plans draw into it).
    output: wgpu::TextureFormat,
}

impl CompositePass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        let [a, n, d] = gbuffer_entries();
        let input = |b| texture_entry(b, false, wgpu::TextureViewDimension::D2);
        let layout = cx.layout("composite_layout", &[a, n, d, input(3), input(4), input(5)]);
        Ok(Self { state: PassState::new(cx, "composite", "composite.wgsl", true, layout)?, output: cx.output })
    }
}

impl Pass for CompositePass {
    /// Builds the pipeline the plan needs (if it changed) and the bind group for `targets`.
    /// `white_albedo` is the "lighting only" view: every surface white.
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { targets, plan, variant, unused, view, .. } = *p;
        let white_albedo = view == View::LightingOnly;
        let key = Key::of(plan, variant, white_albedo);
        let output = self.output;
        self.state.ensure(key, |key, module, layouts| {
            let f = |b: bool| b as u8 as f64;
            let blend = (key.additive && !key.display).then_some(wgpu::BlendState {
                color: wgpu::BlendComponent {
                    src_factor: wgpu::BlendFactor::One,
                    dst_factor: wgpu::BlendFactor::One,
                    operation: wgpu::BlendOperation::Add,
                },
                alpha: wgpu::BlendComponent::REPLACE,
            });
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
                    constants: &[
                        ("LIGHT_LOOP", f(key.light_loop)),
                        ("HAS_AO", f(key.ao)),
                        ("HAS_DO", f(key.directional)),
                        ("CLASSIC", f(key.classic)),
                        ("WHITE_ALBEDO", f(key.white_albedo)),
                        ("DISPLAY", f(key.display)),
                        ("OUTPUT_SRGB", f(output.is_srgb())),
                        ("DIRECT_INPUT", f(key.display && key.additive)),
                    ],
                },
            )
        });
        let occlusion = targets.occlusion();
        let views = [
            &targets.albedo.view,
            &targets.normal.view,
            &targets.depth.view,
            view_or(&occlusion.ao, unused),
            view_or(&occlusion.directional, unused),
            // The lighting pass's direct light, read in a display plan (blended onto otherwise,
            // where it is the attachment and cannot also be bound).
            if plan.display { view_or(&targets.hdr, unused) } else { unused },
        ];
        self.state.bind(device, &super::view_entries(&views));
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, sky, output, origin, .. } = rec;
        let (key, _, _) = self.state.ready();
        let (w, h) = targets.size;
        let (attachment, viewport) = match (key.display, &targets.hdr) {
            (false, Some(hdr)) => (color_attachment(&hdr.view, !key.additive), None),
            (true, _) => (color_attachment(output, true), Some([origin.0 as f32, origin.1 as f32, w as f32, h as f32])),
            (false, None) => unreachable!("an HDR plan always has its HDR target"),
        };
        self.state.draw((encoder, timestamps), &[attachment], (frame, Some(&sky.bind_group)), viewport);
    }
}
