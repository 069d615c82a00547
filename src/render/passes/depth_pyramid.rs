//! The depth pyramid (`shaders/depth_pyramid.wgsl`): level 0 from the depth buffer, each next
//! level from the one before, one small full-screen pass per level. Built only by plans whose
//! sampling pass marches far (the march variant in SSDO and SSAO+SSDO).

use super::super::targets::PYRAMID_FORMAT;
use super::{color_attachment, fullscreen_pipeline, texture_entry, FullscreenDesc, FullscreenPass};
use super::{Pass, PassContext, Preparation, Recording};
use crate::{shaders, Result};

pub struct DepthPyramidPass {
    layout: wgpu::BindGroupLayout,
    first: wgpu::RenderPipeline,
    next: wgpu::RenderPipeline,
    /// One bind group per level: its source (the depth buffer, or the level before).
    groups: Vec<wgpu::BindGroup>,
    /// Bound where an entry point does not read its slot.
    unused_depth: wgpu::TextureView,
    unused_level: wgpu::TextureView,
}

fn unused(device: &wgpu::Device, format: wgpu::TextureFormat) -> wgpu::TextureView {
    device
        .create_texture(&wgpu::TextureDescriptor {
            label: Some("depth_pyramid_unused"),
            size: wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        })
        .create_view(&wgpu::TextureViewDescriptor::default())
}

impl DepthPyramidPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        let device = cx.device;
        let module = shaders::module(device, "depth_pyramid.wgsl")?;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("depth_pyramid_layout"),
            entries: &[texture_entry(0, false, wgpu::TextureViewDimension::D2), super::uint_entry(1)],
        });
        let pipeline = |entry: &str| {
            fullscreen_pipeline(
                device,
                &FullscreenDesc {
                    label: "depth_pyramid_pipeline",
                    module: &module,
                    entry,
                    bind_group_layouts: &[Some(&layout)],
                    targets: &[Some(PYRAMID_FORMAT.into())],
                    depth: None,
                    constants: &[],
                },
            )
        };
        Ok(Self {
            first: pipeline("fs_first"),
            next: pipeline("fs_next"),
            layout,
            groups: Vec::new(),
            unused_depth: unused(device, wgpu::TextureFormat::R32Float),
            unused_level: unused(device, PYRAMID_FORMAT),
        })
    }
}

impl Pass for DepthPyramidPass {
    /// Bind groups for the targets' pyramid (none when the plan has no pyramid).
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { targets, .. } = *p;
        self.groups.clear();
        let Some(pyramid) = &targets.pyramid else { return };
        for level in 0..pyramid.levels.len() {
            let (depth, above) = if level == 0 {
                (&targets.depth.view, &self.unused_level)
            } else {
                (&self.unused_depth, &pyramid.levels[level - 1])
            };
            self.groups.push(device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("depth_pyramid_bind_group"),
                layout: &self.layout,
                entries: &super::view_entries(&[depth, above]),
            }));
        }
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, .. } = rec;
        let Some(pyramid) = &targets.pyramid else { unreachable!("the depth pyramid recorded in a plan without one") };
        // The step's timestamps frame the whole chain: the first level's pass begins it and
        // the last one's ends it.
        let last = self.groups.len().saturating_sub(1);
        for (level, group) in self.groups.iter().enumerate() {
            // A pass in the middle writes none (wgpu refuses writes with neither index).
            let timestamps =
                timestamps.as_ref().filter(|_| level == 0 || level == last).map(|t| wgpu::RenderPassTimestampWrites {
                    query_set: t.query_set,
                    beginning_of_pass_write_index: if level == 0 { t.beginning_of_pass_write_index } else { None },
                    end_of_pass_write_index: if level == last { t.end_of_pass_write_index } else { None },
                });
            FullscreenPass {
                label: "depth_pyramid_pass",
                attachments: &[color_attachment(&pyramid.levels[level], true)],
                depth: None,
                timestamps,
                pipeline: if level == 0 { &self.first } else { &self.next },
                bind_groups: &[(0, group)],
                viewport: None,
            }
            .record(encoder);
        }
    }
}
