//! Lighting pass (SSDO modes with light to bounce): each surface's direct light once per pixel.
//! It writes the diffuse radiance SSDO bounces into `bounce` — the point lights and, unless the
//! senders are lit by the point lights alone, the sky and the ambient they receive (from the
//! sender-sky march, or the sky's unoccluded irradiance) — and, where there are point lights,
//! their displayed light into HDR. The pipeline is specialised
//! to the plan: without lights it has one target and runs no light loop.

use super::super::modes::{Plan, Step};
use super::super::settings::SenderSky;
use super::super::targets::{view_of, view_or, Targets, BOUNCE_FORMAT, HDR_FORMAT};
use super::{
    cleared_attachments, fullscreen_pipeline, gbuffer_entries, texture_entry, view_entries, FullscreenDesc,
    FullscreenPass,
};
use super::{KeyedPipeline, Pass, Preparation, Recording};
use crate::{shaders, Result};

/// The shader variant a plan needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Key {
    /// Point lights: their loop runs and their displayed light goes to HDR.
    lights: bool,
    sender_sky: SenderSky,
}

impl Key {
    fn of(plan: &Plan) -> Self {
        Self { lights: plan.lighting_writes_direct(), sender_sky: plan.sender_sky }
    }
}

pub struct LightingPass {
    module: wgpu::ShaderModule,
    frame_layout: wgpu::BindGroupLayout,
    layout: wgpu::BindGroupLayout,
    pipeline: KeyedPipeline<Key>,
    bind_group: Option<wgpu::BindGroup>,
}

impl LightingPass {
    pub fn new(device: &wgpu::Device, frame_layout: &wgpu::BindGroupLayout) -> Result<Self> {
        let module = shaders::module(device, "lighting.wgsl")?;
        let [a, n, d] = gbuffer_entries();
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("lighting_layout"),
            entries: &[a, n, d, texture_entry(3, false, wgpu::TextureViewDimension::D2)],
        });
        Ok(Self {
            module,
            frame_layout: frame_layout.clone(),
            layout,
            pipeline: KeyedPipeline::new(),
            bind_group: None,
        })
    }

    fn bind_group(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        targets: &Targets,
        unused: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        let views =
            [&targets.albedo.view, &targets.normal.view, &targets.depth.view, view_or(&targets.sender_sky, unused)];
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("lighting_bind_group"),
            layout,
            entries: &view_entries(&views),
        })
    }
}

impl Pass for LightingPass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { targets, plan, unused, .. } = *p;
        if !plan.has(Step::Lighting) {
            self.pipeline.clear();
            self.bind_group = None;
            return;
        }
        self.bind_group = Some(Self::bind_group(device, &self.layout, targets, unused));
        let (module, frame_layout, layout) = (&self.module, &self.frame_layout, &self.layout);
        self.pipeline.ensure(Key::of(plan), |key| {
            let f = |b: bool| b as u8 as f64;
            let both = [Some(HDR_FORMAT.into()), Some(BOUNCE_FORMAT.into())];
            let bounce = [Some(BOUNCE_FORMAT.into())];
            fullscreen_pipeline(
                device,
                &FullscreenDesc {
                    label: "lighting_pipeline",
                    module,
                    entry: if key.lights { "fs_main" } else { "fs_bounce" },
                    bind_group_layouts: &[Some(frame_layout), Some(layout)],
                    targets: if key.lights { &both } else { &bounce },
                    depth: None,
                    constants: &[("LIGHTS", f(key.lights)), ("SENDER_SKY", key.sender_sky.shader_code())],
                },
            )
        });
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, .. } = rec;
        let (Some((key, pipeline)), Some(bind_group)) = (self.pipeline.get(), &self.bind_group) else {
            unreachable!("the lighting pass recorded before `prepare`")
        };
        let bounce = view_of(&targets.bounce);
        let attachments = if key.lights {
            cleared_attachments(&[view_of(&targets.hdr), bounce])
        } else {
            cleared_attachments(&[bounce])
        };
        FullscreenPass {
            label: "lighting_pass",
            attachments: &attachments,
            depth: None,
            timestamps,
            pipeline,
            bind_groups: &[(0, frame), (1, bind_group)],
            viewport: None,
        }
        .record(encoder);
    }
}
