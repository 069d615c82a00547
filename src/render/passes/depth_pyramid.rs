//! The depth pyramid (`shaders/depth_pyramid.wgsl`): level 0 from the depth buffer, each next
//! level from the one before, one small full-screen pass per level. Built only by plans whose
//! sampling pass marches far (the march variant in SSDO and SSAO+SSDO).

use crate::render::graph::io::color_attachment;
use crate::render::graph::io::{Kind, PassIo, Read};
use crate::render::graph::{fullscreen_pipeline, Entry, FullscreenDesc, FullscreenPass, Role};
use crate::render::graph::{Pass, PassContext, Preparation, Recording};
use crate::render::modes::{Plan, Step};
use crate::render::targets::{Place, TargetId, DEPTH};
use crate::{shaders, Result};

impl Step {
    pub const DEPTH_PYRAMID: Step = Step::new("depth_pyramid");
}

// The march's far steps read it, and only where DO is computed.
pub const ENTRY: Entry = Entry::new(
    Step::DEPTH_PYRAMID,
    |f| f.options.pyramid && f.decl.directional_occlusion,
    DepthPyramidPass::io,
    |cx| Ok(Box::new(DepthPyramidPass::new(cx)?)),
)
.role(Role::Sampling);

/// The closest depth per block, as f32 bits, half the screen at level 0 and halving down: read
/// by the march's far steps (the sampling pass and the sender-sky march).
pub const PYRAMID: TargetId = TargetId::new("depth_pyramid", PYRAMID_FORMAT, Place::Pyramid);
pub const PYRAMID_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

pub struct DepthPyramidPass {
    layout: wgpu::BindGroupLayout,
    first: wgpu::RenderPipeline,
    next: wgpu::RenderPipeline,
    /// One bind group per level: its source (the depth buffer, or the level before).
    groups: Vec<wgpu::BindGroup>,
}

impl DepthPyramidPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        let device = cx.device;
        let module = shaders::module(device, "depth_pyramid.wgsl")?;
        let layout = cx.layout("depth_pyramid_layout", &Self::level_reads().layout_entries());
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
        Ok(Self { first: pipeline("fs_first"), next: pipeline("fs_next"), layout, groups: Vec::new() })
    }

    /// What each level's group binds: the depth buffer (level 0) and the level before (the
    /// others), each level binding the fallback for the one it does not read.
    fn level_reads() -> PassIo {
        PassIo { reads: vec![Read::Target(DEPTH), Read::Target(PYRAMID)], ..PassIo::default() }
    }

    /// The depth (through its levels' own groups); the pyramid.
    pub fn io(_plan: &Plan) -> PassIo {
        PassIo { reads: vec![], attached: vec![DEPTH], writes: vec![PYRAMID] }
    }
}

impl Pass for DepthPyramidPass {
    /// Bind groups for the targets' pyramid (none when the plan has no pyramid).
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let (targets, fallbacks) = (p.inputs.targets, p.inputs.fallbacks);
        self.groups.clear();
        let Some(pyramid) = targets.get(PYRAMID) else { return };
        for level in 0..pyramid.levels.len() {
            let (depth, above) = if level == 0 {
                (&targets.depth().view, fallbacks.of(Kind::Uint))
            } else {
                (fallbacks.of(Kind::Float), &pyramid.levels[level - 1])
            };
            let view = wgpu::BindingResource::TextureView;
            self.groups.push(device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("depth_pyramid_bind_group"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: view(depth) },
                    wgpu::BindGroupEntry { binding: 1, resource: view(above) },
                ],
            }));
        }
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, .. } = rec;
        let pyramid = targets.expect(PYRAMID);
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
