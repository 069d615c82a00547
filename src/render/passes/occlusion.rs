//! The sampling pass: SSAO, SSDO, or both from one set of samples (`shaders/occlusion.wgsl`).
//! One shader, two entry points (`fs_ao` writes AO; `fs_do` writes DO + AO); the variant (default or
//! classic) and whether there is a bounce buffer are override constants. The pipeline is built
//! for what the plan needs and rebuilt only when that changes.

use super::super::modes::{Plan, Step};
use super::super::targets::{AO_FORMAT, DO_FORMAT};
use super::super::variant::{Estimator, Sampler};
use super::state::PassState;
use super::{color_attachment, fullscreen_pipeline, gbuffer_entries, texture_entry, uniform_entry, FullscreenDesc};
use super::{Pass, PassContext, Preparation, Recording};
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
    /// Half width and height (an upsample follows).
    half: bool,
}

impl Key {
    fn constants(self) -> Vec<(&'static str, f64)> {
        let f = |b: bool| b as u8 as f64;
        let o = self.outputs;
        let mut list = vec![
            ("HAS_AO", f(o.ao)),
            ("HAS_DO", f(o.directional)),
            ("INDIRECT", f(o.indirect)),
            ("HALF_RES", f(self.half)),
        ];
        if self.march {
            list.push(("USE_PYRAMID", f(self.pyramid)));
        } else {
            list.push(("CLASSIC", f(self.classic)));
        }
        list
    }
}

pub struct OcclusionPass {
    /// The points' shader (`occlusion.wgsl`) and its state; the march's shader beside it.
    state: PassState<Key>,
    march_module: wgpu::ShaderModule,
}

impl OcclusionPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        let state = PassState::new(cx, "occlusion", "occlusion.wgsl", true, sampling_layout(cx, "occlusion_layout"))?;
        Ok(Self { state, march_module: shaders::module(cx.device, "march.wgsl")? })
    }
}

impl Pass for OcclusionPass {
    /// Builds what the plan needs (nothing when it has no sampling step).
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { targets, plan, variant, unused, .. } = *p;
        if !self.state.runs(plan.decl.runs_sampling()) {
            return;
        }
        let key = Key {
            outputs: Outputs::of(plan),
            classic: variant.decl().estimator == Estimator::Classic,
            march: variant.decl().sampler == Sampler::March,
            pyramid: plan.has(Step::DepthPyramid),
            half: plan.half(),
        };
        let march_module = &self.march_module;
        self.state.ensure(key, |key, points_module, layouts| {
            let entry = if key.outputs.directional { "fs_do" } else { "fs_ao" };
            fullscreen_pipeline(
                device,
                &FullscreenDesc {
                    label: "occlusion_pipeline",
                    module: if key.march { march_module } else { points_module },
                    entry,
                    bind_group_layouts: layouts,
                    targets: &[Some(key.outputs.format().into())],
                    depth: None,
                    constants: &key.constants(),
                },
            )
        });
        let bounce = targets.bounce.as_ref().map_or(unused, |t| &t.view);
        self.state.bind(device, &sampling_entries(p, bounce));
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, sky, .. } = rec;
        let set = targets.half.as_ref().unwrap_or(&targets.raw);
        let output = set.output().expect("a plan with a sampling step has its target");
        let attachments = [color_attachment(&output.view, true)];
        self.state.draw((encoder, timestamps), &attachments, (frame, Some(&sky.bind_group)), None);
    }
}

/// The layout of a sampling pass's bind group 1 (the sampling pass and the sender-sky march):
/// the G-buffer, the parameters, the bounce source and the depth pyramid.
pub fn sampling_layout(cx: &PassContext<'_>, label: &'static str) -> wgpu::BindGroupLayout {
    let [a, n, d] = gbuffer_entries();
    let bounce = texture_entry(4, false, wgpu::TextureViewDimension::D2);
    cx.layout(label, &[a, n, d, uniform_entry(3), bounce, super::uint_entry(5)])
}

/// Bind group 1 of a sampling pass for the prepared targets, with `bounce` as its bounce source.
pub fn sampling_entries<'a>(p: &Preparation<'a>, bounce: &'a wgpu::TextureView) -> Vec<wgpu::BindGroupEntry<'a>> {
    let Preparation { targets, data, unused_pyramid, .. } = *p;
    let pyramid = targets.pyramid.as_ref().map_or(unused_pyramid, |p| &p.view);
    let mut entries = super::view_entries(&[&targets.albedo.view, &targets.normal.view, &targets.depth.view]);
    entries.extend([
        wgpu::BindGroupEntry { binding: 3, resource: data.buffer.as_entire_binding() },
        wgpu::BindGroupEntry { binding: 4, resource: wgpu::BindingResource::TextureView(bounce) },
        wgpu::BindGroupEntry { binding: 5, resource: wgpu::BindingResource::TextureView(pyramid) },
    ]);
    entries
}
