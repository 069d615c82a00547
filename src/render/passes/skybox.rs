//! Skybox: the cube map drawn into HDR behind everything, in HDR plans (a display plan's
//! composite draws the sky itself). The sky's GPU resources are `resources/sky.rs`.

use super::super::targets::{DEPTH_FORMAT, HDR_FORMAT};
use super::{color_attachment, fullscreen_pipeline, FullscreenDesc, FullscreenPass};
use super::{Pass, PassContext, Recording};
use crate::{shaders, Result};

pub struct SkyboxPass {
    pipeline: wgpu::RenderPipeline,
}

impl SkyboxPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        let module = shaders::module(cx.device, "skybox.wgsl")?;
        let pipeline = fullscreen_pipeline(
            cx.device,
            &FullscreenDesc {
                label: "skybox_pipeline",
                module: &module,
                bind_group_layouts: &[Some(cx.frame_layout), None, Some(cx.sky_layout)],
                entry: "fs_main",
                targets: &[Some(HDR_FORMAT.into())],
                depth: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(false),
                    depth_compare: Some(wgpu::CompareFunction::GreaterEqual),
                    stencil: wgpu::StencilState::default(),
                    bias: wgpu::DepthBiasState::default(),
                }),
                constants: &[],
            },
        );
        Ok(Self { pipeline })
    }
}

impl Pass for SkyboxPass {
    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, sky, .. } = rec;
        let hdr = targets.hdr.as_ref().expect("the skybox pass runs only in plans with an HDR target");
        FullscreenPass {
            label: "skybox_pass",
            attachments: &[color_attachment(&hdr.view, false)],
            depth: Some(&targets.depth.view),
            timestamps,
            pipeline: &self.pipeline,
            bind_groups: &[(0, frame), (2, &sky.bind_group)],
            viewport: None,
        }
        .record(encoder);
    }
}
