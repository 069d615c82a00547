//! Tone mapping: linear HDR → exposure → ACES filmic curve → sRGB into the output (the capture
//! texture or the window's surface). For an sRGB output format the hardware encodes; for a
//! linear one the shader does (`OUTPUT_SRGB = false`).

use super::super::targets::Targets;
use super::{color_attachment, fullscreen_pipeline, texture_entry, view_entries, FullscreenDesc};
use crate::{shaders, Result};

pub struct TonemapPass {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
    bind_group: wgpu::BindGroup,
}

impl TonemapPass {
    pub fn new(
        device: &wgpu::Device,
        frame_layout: &wgpu::BindGroupLayout,
        targets: &Targets,
        output: wgpu::TextureFormat,
    ) -> Result<Self> {
        let module = shaders::module(device, "tonemap.wgsl")?;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("tonemap_layout"),
            entries: &[texture_entry(0, false, wgpu::TextureViewDimension::D2)],
        });
        let pipeline = fullscreen_pipeline(
            device,
            &FullscreenDesc {
                label: "tonemap_pipeline",
                module: &module,
                bind_group_layouts: &[Some(frame_layout), Some(&layout)],
                entry: "fs_main",
                targets: &[Some(output.into())],
                depth: None,
                constants: &[("OUTPUT_SRGB", output.is_srgb() as u8 as f64)],
            },
        );
        let bind_group = Self::bind_group(device, &layout, targets);
        Ok(Self { layout, pipeline, bind_group })
    }

    fn bind_group(device: &wgpu::Device, layout: &wgpu::BindGroupLayout, targets: &Targets) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("tonemap_bind_group"),
            layout,
            entries: &view_entries(&[&targets.hdr.view]),
        })
    }

    pub fn resize(&mut self, device: &wgpu::Device, targets: &Targets) {
        self.bind_group = Self::bind_group(device, &self.layout, targets);
    }

    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
        frame: &wgpu::BindGroup,
        output: &wgpu::TextureView,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("tonemap_pass"),
            color_attachments: &[color_attachment(output, true)],
            depth_stencil_attachment: None,
            timestamp_writes: timestamps,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, frame, &[]);
        pass.set_bind_group(1, &self.bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}
