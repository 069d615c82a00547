//! The sender-sky march (`--sender-sky march`): before the lighting pass, at half resolution, the
//! sky each surface sees through one slice of the march (`fs_sender` in `shaders/march.wgsl`,
//! built with DO on and AO and the bounce off). The lighting pass turns it into the sky light each
//! sender bounces, so the bounce carries the sky with the sender's own visibility.

use super::super::modes::Step;
use super::super::targets::DO_FORMAT;
use super::occlusion::{sampling_bind_group, sampling_layout};
use super::{color_attachment, fullscreen_pipeline, FullscreenDesc, FullscreenPass, KeyedPipeline};
use super::{Pass, Preparation, Recording};
use crate::{shaders, Result};

pub struct SenderSkyPass {
    module: wgpu::ShaderModule,
    layout: wgpu::BindGroupLayout,
    pipeline_layouts: [wgpu::BindGroupLayout; 2],
    /// Keyed by whether the far steps read the depth pyramid.
    pipeline: KeyedPipeline<bool>,
    bind_group: Option<wgpu::BindGroup>,
}

impl SenderSkyPass {
    pub fn new(
        device: &wgpu::Device,
        frame_layout: &wgpu::BindGroupLayout,
        sky_layout: &wgpu::BindGroupLayout,
    ) -> Result<Self> {
        Ok(Self {
            module: shaders::module(device, "march.wgsl")?,
            layout: sampling_layout(device, "sender_sky_layout"),
            pipeline_layouts: [frame_layout.clone(), sky_layout.clone()],
            pipeline: KeyedPipeline::new(),
            bind_group: None,
        })
    }
}

impl Pass for SenderSkyPass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        if !p.plan.has(Step::SenderSky) {
            self.pipeline.clear();
            self.bind_group = None;
            return;
        }
        let [frame, sky] = &self.pipeline_layouts;
        let (module, layout) = (&self.module, &self.layout);
        self.pipeline.ensure(p.plan.has(Step::DepthPyramid), |pyramid| {
            let f = |b: bool| b as u8 as f64;
            fullscreen_pipeline(
                device,
                &FullscreenDesc {
                    label: "sender_sky_pipeline",
                    module,
                    entry: "fs_sender",
                    bind_group_layouts: &[Some(frame), Some(layout), Some(sky)],
                    targets: &[Some(DO_FORMAT.into())],
                    depth: None,
                    constants: &[
                        ("COMPUTE_AO", 0.0),
                        ("COMPUTE_DO", 1.0),
                        ("INDIRECT", 0.0),
                        ("USE_PYRAMID", f(pyramid)),
                    ],
                },
            )
        });
        // The bounce source is what this pass feeds; it reads none.
        self.bind_group = Some(sampling_bind_group(device, &self.layout, p, p.unused));
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, sky, .. } = rec;
        let (Some((_, pipeline)), Some(bind_group), Some(output)) =
            (self.pipeline.get(), &self.bind_group, targets.sender_sky.as_ref())
        else {
            unreachable!("the sender-sky march recorded before `prepare` or in a plan without it")
        };
        FullscreenPass {
            label: "sender_sky_pass",
            attachments: &[color_attachment(&output.view, true)],
            depth: None,
            timestamps,
            pipeline,
            bind_groups: &[(0, frame), (1, bind_group), (2, &sky.bind_group)],
            viewport: None,
        }
        .record(encoder);
    }
}
