//! The sampling pass: SSAO, SSDO, or both from one set of samples (`shaders/occlusion.wgsl`).
//! One shader, two entry points (`fs_ao` writes AO; `fs_do` writes DO + AO); the variant (default or
//! classic) and whether there is a bounce buffer are override constants. The pipeline is built
//! for what the plan needs and rebuilt only when that changes.

use super::super::variant::{Estimator, Sampler};
use super::super::modes::{Plan, Step};
use super::super::targets::{AO_FORMAT, DO_FORMAT};
use super::{
    color_attachment, fullscreen_pipeline, gbuffer_entries, texture_entry, uniform_entry, FullscreenDesc,
    FullscreenPass, KeyedPipeline,
};
use super::{Pass, Preparation, Recording};
use crate::{shaders, Result};

/// What a plan's sampling (and blur) pass produces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Outputs {
    pub ao: bool,
    pub directional: bool,
    pub indirect: bool,
}

impl Outputs {
    pub fn of(plan: &Plan) -> Self {
        Self {
            ao: plan.decl.ambient_occlusion,
            directional: plan.decl.directional_occlusion,
            indirect: plan.has(Step::Lighting),
        }
    }

    /// The format of the one target written: AO alone, or DO + AO.
    pub fn format(self) -> wgpu::TextureFormat {
        if self.directional {
            DO_FORMAT
        } else {
            AO_FORMAT
        }
    }
}

/// What distinguishes one sampling pipeline from another.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Key {
    outputs: Outputs,
    classic: bool,
    /// The march shader rather than the point-sampling one.
    march: bool,
    /// The march's far steps read the depth pyramid.
    pyramid: bool,
}

impl Key {
    fn constants(self) -> Vec<(&'static str, f64)> {
        let f = |b: bool| b as u8 as f64;
        let o = self.outputs;
        let mut list = vec![("COMPUTE_AO", f(o.ao)), ("COMPUTE_DO", f(o.directional)), ("INDIRECT", f(o.indirect))];
        if self.march {
            list.push(("USE_PYRAMID", f(self.pyramid)));
        } else {
            list.push(("CLASSIC", f(self.classic)));
        }
        list
    }
}

pub struct OcclusionPass {
    module: wgpu::ShaderModule,
    march_module: wgpu::ShaderModule,
    layout: wgpu::BindGroupLayout,
    pipeline_layouts: [wgpu::BindGroupLayout; 2],
    pipeline: KeyedPipeline<Key>,
    bind_group: Option<wgpu::BindGroup>,
}

impl OcclusionPass {
    pub fn new(
        device: &wgpu::Device,
        frame_layout: &wgpu::BindGroupLayout,
        sky_layout: &wgpu::BindGroupLayout,
    ) -> Result<Self> {
        let module = shaders::module(device, "occlusion.wgsl")?;
        let march_module = shaders::module(device, "march.wgsl")?;
        let layout = sampling_layout(device, "occlusion_layout");
        Ok(Self {
            module,
            march_module,
            layout,
            pipeline_layouts: [frame_layout.clone(), sky_layout.clone()],
            pipeline: KeyedPipeline::new(),
            bind_group: None,
        })
    }
}

impl Pass for OcclusionPass {
    /// Builds what the plan needs (nothing when it has no sampling step).
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { targets, plan, variant, unused, .. } = *p;
        if !plan.decl.runs_sampling() {
            self.pipeline.clear();
            self.bind_group = None;
            return;
        }
        let key = Key {
            outputs: Outputs::of(plan),
            classic: variant.decl().estimator == Estimator::Classic,
            march: variant.decl().sampler == Sampler::March,
            pyramid: plan.has(Step::DepthPyramid),
        };
        self.pipeline.ensure(key, |key| {
            let entry = if key.outputs.directional { "fs_do" } else { "fs_ao" };
            let [frame, sky] = &self.pipeline_layouts;
            fullscreen_pipeline(
                device,
                &FullscreenDesc {
                    label: "occlusion_pipeline",
                    module: if key.march { &self.march_module } else { &self.module },
                    entry,
                    bind_group_layouts: &[Some(frame), Some(&self.layout), Some(sky)],
                    targets: &[Some(key.outputs.format().into())],
                    depth: None,
                    constants: &key.constants(),
                },
            )
        });
        let bounce = targets.bounce.as_ref().map_or(unused, |t| &t.view);
        self.bind_group = Some(sampling_bind_group(device, &self.layout, p, bounce));
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, sky, .. } = rec;
        let sky = &sky.bind_group;
        let (Some((_, pipeline)), Some(bind_group), Some(output)) =
            (self.pipeline.get(), &self.bind_group, targets.raw.output())
        else {
            unreachable!("the sampling pass recorded before `prepare` or in a plan without it")
        };
        FullscreenPass {
            label: "occlusion_pass",
            attachments: &[color_attachment(&output.view, true)],
            depth: None,
            timestamps,
            pipeline,
            bind_groups: &[(0, frame), (1, bind_group), (2, sky)],
            viewport: None,
        }
        .record(encoder);
    }
}

/// The layout of a sampling pass's bind group 1 (the sampling pass and the sender-sky march):
/// the G-buffer, the parameters, the bounce source and the depth pyramid.
pub fn sampling_layout(device: &wgpu::Device, label: &'static str) -> wgpu::BindGroupLayout {
    let [a, n, d] = gbuffer_entries();
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &[
            a,
            n,
            d,
            uniform_entry(3),
            texture_entry(4, false, wgpu::TextureViewDimension::D2),
            super::uint_entry(5),
        ],
    })
}

/// Bind group 1 of a sampling pass for the prepared targets, with `bounce` as its bounce source.
pub fn sampling_bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    p: &Preparation<'_>,
    bounce: &wgpu::TextureView,
) -> wgpu::BindGroup {
    let Preparation { targets, data, unused_pyramid, .. } = *p;
    let pyramid = targets.pyramid.as_ref().map_or(unused_pyramid, |p| &p.view);
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("sampling_bind_group"),
        layout,
        entries: &[
            wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&targets.albedo.view) },
            wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(&targets.normal.view) },
            wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::TextureView(&targets.depth.view) },
            wgpu::BindGroupEntry { binding: 3, resource: data.buffer.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 4, resource: wgpu::BindingResource::TextureView(bounce) },
            wgpu::BindGroupEntry { binding: 5, resource: wgpu::BindingResource::TextureView(pyramid) },
        ],
    })
}
