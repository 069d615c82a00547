//! Composite: ambient·albedo·AO + DO + direct point lighting into the linear HDR target, or, in a
//! display plan, with the sky and the tone curve straight into the output (no HDR write, no
//! skybox or tone-map pass). The pipeline is specialised to the plan (override constants):
//! without lights there is no light loop in the shader, without AO no AO read, and so on. After a
//! lighting pass it blends additively onto the direct light that pass wrote (HDR), or reads it
//! (display).

use super::super::variant::{Composite, Variant};
use super::super::modes::Plan;
use super::super::targets::{view_or, HDR_FORMAT};
use super::super::View;
use super::{
    color_attachment, fullscreen_pipeline, gbuffer_entries, texture_entry, FullscreenDesc, FullscreenPass,
    KeyedPipeline,
};
use super::{Pass, Preparation, Recording};
use crate::{shaders, Result};

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
    module: wgpu::ShaderModule,
    layout: wgpu::BindGroupLayout,
    frame_layout: wgpu::BindGroupLayout,
    sky_layout: wgpu::BindGroupLayout,
    /// The output's format (display plans draw into it).
    output: wgpu::TextureFormat,
    pipeline: KeyedPipeline<Key>,
    bind_group: Option<wgpu::BindGroup>,
}

impl CompositePass {
    pub fn new(
        device: &wgpu::Device,
        frame_layout: &wgpu::BindGroupLayout,
        sky_layout: &wgpu::BindGroupLayout,
        output: wgpu::TextureFormat,
    ) -> Result<Self> {
        let module = shaders::module(device, "composite.wgsl")?;
        let [a, n, d] = gbuffer_entries();
        let input = |b| texture_entry(b, false, wgpu::TextureViewDimension::D2);
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("composite_layout"),
            entries: &[a, n, d, input(3), input(4), input(5)],
        });
        Ok(Self {
            module,
            layout,
            frame_layout: frame_layout.clone(),
            sky_layout: sky_layout.clone(),
            output,
            pipeline: KeyedPipeline::new(),
            bind_group: None,
        })
    }
}

impl Pass for CompositePass {
    /// Builds the pipeline the plan needs (if it changed) and the bind group for `targets`.
    /// `white_albedo` is the "lighting only" view: every surface white.
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { targets, plan, variant, unused, view, .. } = *p;
        let white_albedo = view == View::LightingOnly;
        let key = Key::of(plan, variant, white_albedo);
        let (module, frame_layout, layout, sky_layout) =
            (&self.module, &self.frame_layout, &self.layout, &self.sky_layout);
        let output = self.output;
        self.pipeline.ensure(key, |key| {
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
                    bind_group_layouts: &[Some(frame_layout), Some(layout), Some(sky_layout)],
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
        self.bind_group = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("composite_bind_group"),
            layout: &self.layout,
            entries: &super::view_entries(&views),
        }));
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, sky, output, origin, .. } = rec;
        let sky = &sky.bind_group;
        let (Some((key, pipeline)), Some(bind_group)) = (self.pipeline.get(), &self.bind_group) else {
            unreachable!("the composite recorded before `prepare`")
        };
        let (w, h) = targets.size;
        let (attachment, viewport) = match (key.display, &targets.hdr) {
            (false, Some(hdr)) => (color_attachment(&hdr.view, !key.additive), None),
            (true, _) => (color_attachment(output, true), Some([origin.0 as f32, origin.1 as f32, w as f32, h as f32])),
            (false, None) => unreachable!("an HDR plan always has its HDR target"),
        };
        FullscreenPass {
            label: "composite_pass",
            attachments: &[attachment],
            depth: None,
            timestamps,
            pipeline,
            bind_groups: &[(0, frame), (1, bind_group), (2, sky)],
            viewport,
        }
        .record(encoder);
    }
}
