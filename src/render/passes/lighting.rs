//! Lighting pass (SSDO modes with point lights): the light loop once per pixel, writing the
//! displayed direct light into HDR and the diffuse radiance SSDO bounces into `bounce`.

use super::super::targets::{Targets, BOUNCE_FORMAT, HDR_FORMAT};
use super::{cleared_attachments, fullscreen_pipeline, gbuffer_entries, view_entries, FullscreenDesc, FullscreenPass};
use super::{Pass, Preparation, Recording};
use crate::{shaders, Result};

pub struct LightingPass {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
    bind_group: wgpu::BindGroup,
}

impl LightingPass {
    pub fn new(device: &wgpu::Device, frame_layout: &wgpu::BindGroupLayout, targets: &Targets) -> Result<Self> {
        let module = shaders::module(device, "lighting.wgsl")?;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("lighting_layout"),
            entries: &gbuffer_entries(),
        });
        let pipeline = fullscreen_pipeline(
            device,
            &FullscreenDesc {
                label: "lighting_pipeline",
                module: &module,
                entry: "fs_main",
                bind_group_layouts: &[Some(frame_layout), Some(&layout)],
                targets: &[Some(HDR_FORMAT.into()), Some(BOUNCE_FORMAT.into())],
                depth: None,
                constants: &[],
            },
        );
        let bind_group = Self::bind_group(device, &layout, targets);
        Ok(Self { layout, pipeline, bind_group })
    }

    fn bind_group(device: &wgpu::Device, layout: &wgpu::BindGroupLayout, targets: &Targets) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("lighting_bind_group"),
            layout,
            entries: &view_entries(&[&targets.albedo.view, &targets.normal.view, &targets.depth.view]),
        })
    }
}

impl Pass for LightingPass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { targets, .. } = *p;
        self.bind_group = Self::bind_group(device, &self.layout, targets);
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, .. } = rec;
        let bounce = targets.bounce.as_ref().map(|t| &t.view);
        FullscreenPass {
            label: "lighting_pass",
            attachments: &cleared_attachments(&[super::super::targets::view_of(&targets.hdr), bounce]),
            depth: None,
            timestamps,
            pipeline: &self.pipeline,
            bind_groups: &[(0, frame), (1, &self.bind_group)],
            viewport: None,
        }
        .record(encoder);
    }
}
