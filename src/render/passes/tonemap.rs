//! Tone mapping: linear HDR → exposure → ACES filmic curve → sRGB into the output (the capture
//! texture or the window's surface). For an sRGB output format the hardware encodes; for a
//! linear one the shader does (`OUTPUT_SRGB = false`). The debug views (G-buffer channels, AO, DO)
//! are variants of this pass, so showing one costs no extra pass.

use super::super::modes::Plan;
use super::super::targets::view_or;
use super::super::View;
use super::{
    color_attachment, depth_entry, fullscreen_pipeline, texture_entry, view_entries, FullscreenDesc, FullscreenPass,
    KeyedPipeline,
};
use super::{Pass, Preparation, Recording};
use crate::{shaders, Result};

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
    module: wgpu::ShaderModule,
    layout: wgpu::BindGroupLayout,
    frame_layout: wgpu::BindGroupLayout,
    output: wgpu::TextureFormat,
    pipeline: KeyedPipeline<Key>,
    bind_group: Option<wgpu::BindGroup>,
}

impl TonemapPass {
    pub fn new(
        device: &wgpu::Device,
        frame_layout: &wgpu::BindGroupLayout,
        output: wgpu::TextureFormat,
    ) -> Result<Self> {
        let module = shaders::module(device, "tonemap.wgsl")?;
        let float = |b| texture_entry(b, false, wgpu::TextureViewDimension::D2);
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("tonemap_layout"),
            entries: &[float(0), float(1), super::normal_entry(2), depth_entry(3), float(4), float(5)],
        });
        Ok(Self {
            module,
            layout,
            frame_layout: frame_layout.clone(),
            output,
            pipeline: KeyedPipeline::new(),
            bind_group: None,
        })
    }
}

impl Pass for TonemapPass {
    /// Builds the pipeline for the plan and view (if it changed) and the bind group for `targets`.
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { targets, plan, view, unused, .. } = *p;
        let key = Key::of(plan, view);
        let (module, frame_layout, layout) = (&self.module, &self.frame_layout, &self.layout);
        self.pipeline.ensure(key, |key| {
            let f = |b: bool| b as u8 as f64;
            fullscreen_pipeline(
                device,
                &FullscreenDesc {
                    label: "tonemap_pipeline",
                    module,
                    entry: "fs_main",
                    bind_group_layouts: &[Some(frame_layout), Some(layout)],
                    targets: &[Some(self.output.into())],
                    depth: None,
                    constants: &[
                        ("OUTPUT_SRGB", f(self.output.is_srgb())),
                        ("VIEW", key.view as f64),
                        ("HAS_AO", f(key.ao)),
                        ("HAS_DO", f(key.directional)),
                    ],
                },
            )
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
        self.bind_group = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("tonemap_bind_group"),
            layout: &self.layout,
            entries: &view_entries(&views),
        }));
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, output, origin, .. } = rec;
        let (Some((_, pipeline)), Some(bind_group)) = (self.pipeline.get(), &self.bind_group) else {
            unreachable!("the tone map recorded before `prepare`")
        };
        let (w, h) = targets.size;
        FullscreenPass {
            label: "tonemap_pass",
            attachments: &[color_attachment(output, true)],
            depth: None,
            timestamps,
            pipeline,
            bind_groups: &[(0, frame), (1, bind_group)],
            viewport: Some([origin.0 as f32, origin.1 as f32, w as f32, h as f32]),
        }
        .record(encoder);
    }
}
