//! Composite: ambient·albedo·AO + DO + direct point lighting into the linear HDR target.
//! The pipeline is specialised to the plan (override constants): without lights there is no
//! light loop in the shader at all.

use super::super::modes::Plan;
use super::super::targets::{Targets, HDR_FORMAT};
use super::{color_attachment, depth_entry, fullscreen_pipeline, texture_entry, view_entries, FullscreenDesc};
use crate::{shaders, Result};

/// The shader variant a plan needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Variant {
    light_loop: bool,
}

impl Variant {
    fn of(plan: &Plan) -> Self {
        Self { light_loop: plan.light_loop() }
    }
}

pub struct CompositePass {
    module: wgpu::ShaderModule,
    layout: wgpu::BindGroupLayout,
    frame_layout: wgpu::BindGroupLayout,
    variant: Variant,
    pipeline: wgpu::RenderPipeline,
    bind_group: wgpu::BindGroup,
}

impl CompositePass {
    pub fn new(
        device: &wgpu::Device,
        frame_layout: &wgpu::BindGroupLayout,
        targets: &Targets,
        plan: &Plan,
    ) -> Result<Self> {
        let module = shaders::module(device, "composite.wgsl")?;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("composite_layout"),
            entries: &[
                texture_entry(0, false, wgpu::TextureViewDimension::D2),
                texture_entry(1, false, wgpu::TextureViewDimension::D2),
                depth_entry(2),
            ],
        });
        let variant = Variant::of(plan);
        let pipeline = Self::pipeline(device, &module, frame_layout, &layout, variant);
        let bind_group = Self::bind_group(device, &layout, targets);
        Ok(Self { module, layout, frame_layout: frame_layout.clone(), variant, pipeline, bind_group })
    }

    fn pipeline(
        device: &wgpu::Device,
        module: &wgpu::ShaderModule,
        frame_layout: &wgpu::BindGroupLayout,
        layout: &wgpu::BindGroupLayout,
        variant: Variant,
    ) -> wgpu::RenderPipeline {
        fullscreen_pipeline(
            device,
            &FullscreenDesc {
                label: "composite_pipeline",
                module,
                bind_group_layouts: &[Some(frame_layout), Some(layout)],
                format: HDR_FORMAT,
                depth: None,
                constants: &[("LIGHT_LOOP", variant.light_loop as u8 as f64)],
            },
        )
    }

    fn bind_group(device: &wgpu::Device, layout: &wgpu::BindGroupLayout, targets: &Targets) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("composite_bind_group"),
            layout,
            entries: &view_entries(&[&targets.albedo.view, &targets.normal.view, &targets.depth.view]),
        })
    }

    /// Rebuilds the bind group for new targets and the pipeline if the plan changed variant.
    pub fn resize(&mut self, device: &wgpu::Device, targets: &Targets, plan: &Plan) {
        let variant = Variant::of(plan);
        if variant != self.variant {
            self.pipeline = Self::pipeline(device, &self.module, &self.frame_layout, &self.layout, variant);
            self.variant = variant;
        }
        self.bind_group = Self::bind_group(device, &self.layout, targets);
    }

    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
        targets: &Targets,
        frame: &wgpu::BindGroup,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("composite_pass"),
            color_attachments: &[color_attachment(&targets.hdr.view, true)],
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
