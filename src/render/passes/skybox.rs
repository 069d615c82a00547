//! Skybox: the cube map drawn into HDR behind everything, in HDR plans (a display plan's
//! G-buffer pass draws the displayed sky behind the geometry and the composite shows it). The sky's GPU resources are `resources/sky.rs`.

use crate::render::graph::io::PassIo;
use crate::render::graph::{fullscreen_depth_test, fullscreen_pipeline, Entry, FullscreenDesc, FullscreenPass};
use crate::render::graph::{Pass, PassContext, Recording};
use crate::render::modes::{Plan, Step};
use crate::render::targets::{DEPTH, HDR, HDR_FORMAT};
use crate::{shaders, Result};

impl Step {
    pub const SKYBOX: Step = Step::new("skybox");
}

// A display plan's G-buffer pass draws the displayed sky itself.
pub const ENTRY: Entry =
    Entry::new(Step::SKYBOX, |f| !f.options.display, SkyboxPass::io, |cx| Ok(Box::new(SkyboxPass::new(cx)?)));

pub struct SkyboxPass {
    pipeline: wgpu::RenderPipeline,
}

impl SkyboxPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        Ok(Self { pipeline: behind_geometry(cx, "skybox_pipeline", "fs_main", &[Some(HDR_FORMAT.into())])? })
    }

    /// The depth (through the depth attachment, tested read-only); HDR where nothing was drawn.
    pub fn io(_plan: &Plan) -> PassIo {
        PassIo { reads: vec![], attached: vec![DEPTH], writes: vec![HDR] }
    }
}

/// A pipeline of `shaders/skybox.wgsl`'s `entry` drawing the sky where nothing was drawn: the
/// full-screen triangle at the far plane (0) behind a `GreaterEqual` test, which passes only
/// where the depth is still 0, so a covered pixel costs its test alone. The skybox pass draws
/// HDR with it; a display plan's G-buffer pass the displayed sky into the albedo.
pub fn behind_geometry(
    cx: &PassContext<'_>,
    label: &str,
    entry: &str,
    targets: &[Option<wgpu::ColorTargetState>],
) -> Result<wgpu::RenderPipeline> {
    let module = shaders::module(cx.device, "skybox.wgsl")?;
    let desc = FullscreenDesc {
        label,
        module: &module,
        bind_group_layouts: &[Some(cx.frame_layout), None, Some(cx.sky_layout)],
        entry,
        targets,
        depth: Some(fullscreen_depth_test(wgpu::CompareFunction::GreaterEqual)),
        constants: &[],
    };
    Ok(fullscreen_pipeline(cx.device, &desc))
}

impl Pass for SkyboxPass {
    fn record(&self, rec: Recording<'_>) {
        let attachments = rec.attachments(&Self::io(rec.plan).writes, false);
        FullscreenPass {
            label: "skybox_pass",
            attachments: &attachments,
            depth: Some(&rec.targets.depth().view),
            timestamps: rec.timestamps,
            pipeline: &self.pipeline,
            bind_groups: &[(0, rec.frame), (2, &rec.sky.bind_group)],
            viewport: None,
        }
        .record(rec.encoder);
    }
}
