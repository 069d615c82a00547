//! The sampling pass: SSAO, SSDO, or both from one set of samples (`shaders/points.wgsl`,
//! or the march's `shaders/march.wgsl`). One shader, two entry points (`fs_ao` writes AO; `fs_do`
//! writes DO + AO); the variant (default or classic) and whether there is a bounce buffer are
//! override constants. The pipeline is built for what the plan needs and rebuilt only when that
//! changes. With `--sender-sky last-frame` the march also writes the sky each pixel sees, for the
//! next frame's senders ([`LAST_SKY`], which this pass writes and the lighting pass reads).

use super::depth_pyramid::PYRAMID;
use crate::render::graph::io::{PassIo, Read};
use crate::render::graph::state::PassState;
use crate::render::graph::{fullscreen_pipeline, Entry, FullscreenDesc, Role};
use crate::render::graph::{Pass, PassContext, Preparation, Recording};
use crate::render::history::HistorySpec;
use crate::render::modes::{Plan, PlanFacts, Step};
use crate::render::targets::{Place, Stage, TargetId, ALBEDO, AO_FORMAT, DEPTH, DO_FORMAT, NORMAL, THICKNESS};
use crate::render::variant::{Estimator, Sampler};
use crate::render::SenderSky;
use crate::{shaders, Result};

impl Step {
    /// Named after what the mode computes: `ssao`, `ssdo` or `ssao_ssdo`.
    pub const SAMPLING: Step = Step::named_by_mode("sampling");
}

pub const ENTRY: Entry =
    Entry::new(Step::SAMPLING, |f| f.samples(), SamplingPass::io, |cx| Ok(Box::new(SamplingPass::new(cx)?)))
        .binding(&["points.wgsl", "march.wgsl"])
        .keeping(last_sky_history)
        .role(Role::Sampling);

/// The sky each pixel's march saw (as `sender_sky::SENDER_SKY`), at the sampling pass's size, kept for
/// the next frame's lighting pass (`--sender-sky last-frame`): written by the sampling pass.
pub const LAST_SKY: TargetId = TargetId::new("history_sender_sky", DO_FORMAT, Place::History);

/// The history of [`LAST_SKY`] where the plan takes the senders' sky from the last frame: at
/// the samples' size, meaning one thing in every DO mode (the key is the format's alone).
pub fn last_sky_history(facts: &PlanFacts) -> Vec<HistorySpec> {
    let wanted = facts.sender_sky() == SenderSky::LastFrame;
    let spec = HistorySpec { name: LAST_SKY.name, format: DO_FORMAT, key: 0 };
    wanted.then_some(spec).into_iter().collect()
}

/// Whether the last frame left its senders' sky for this one: the plan keeps it and it holds a
/// frame.
pub fn last_sky_held(plan: &Plan, history: &crate::render::history::History) -> bool {
    plan.sender_sky == SenderSky::LastFrame && history.get(LAST_SKY).is_some_and(|h| h.frames > 0)
}

/// What a plan's sampling (and blur) pass produces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Outputs {
    pub ao: bool,
    pub directional: bool,
    pub indirect: bool,
}

impl Outputs {
    pub fn of(plan: &Plan) -> Self {
        Self { ao: plan.decl.ambient_occlusion, directional: plan.decl.directional_occlusion, indirect: plan.lighting }
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

/// What a filter of the sampling chain (the upsample, the blur) reads and writes: the G-buffer,
/// the filter's parameters and the chain's stage `from`; the stage `to`.
pub fn filter_io(plan: &Plan, from: Stage, to: Stage) -> PassIo {
    let d = plan.decl.directional_occlusion;
    let reads = vec![
        Read::Target(ALBEDO),
        Read::Target(NORMAL),
        Read::Target(DEPTH),
        Read::Filter,
        Read::Target(from.target(d)),
    ];
    PassIo { reads, attached: vec![], writes: vec![to.target(d)] }
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
    /// The G-buffer holds mapped normals: the geometry's come from the depth.
    normal_mapped: bool,
    /// The DO is written over the sky's irradiance at the sample's normal
    /// (`Plan::do_over_irradiance`).
    over_irradiance: bool,
    /// The march writes the sky each pixel sees for the next frame's senders.
    last_sky: bool,
    /// The march reads each sample's thickness from the thickness layer.
    thickness_layer: bool,
    /// The march takes the far side layer's sender (the bounce target's second pair) where the
    /// near one faces away.
    far_side: bool,
    /// The march reads the lighting pass's depth with each surface's extent.
    extent_layer: bool,
}

impl Key {
    fn constants(self) -> Vec<(&'static str, f64)> {
        let f = |b: bool| b as u8 as f64;
        let o = self.outputs;
        let mut list = vec![
            ("HAS_AO", f(o.ao)),
            ("HAS_DO", f(o.directional)),
            ("INDIRECT", f(o.indirect)),
            ("NORMAL_MAPPED", f(self.normal_mapped)),
            ("DO_OVER_IRRADIANCE", f(self.over_irradiance)),
        ];
        if self.march {
            list.push(("USE_PYRAMID", f(self.pyramid)));
            list.push(("THICKNESS_LAYER", f(self.thickness_layer || self.extent_layer)));
            list.push(("EXTENT_CODES", f(self.extent_layer)));
            list.push(("FAR_SIDE", f(self.far_side)));
        } else {
            list.push(("CLASSIC", f(self.classic)));
        }
        list
    }
}

pub struct SamplingPass {
    /// The points' shader (`points.wgsl`) and its state; the march's shader beside it.
    state: PassState<Key>,
    march_module: wgpu::ShaderModule,
}

impl SamplingPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        let state = PassState::new(cx, "sampling", "points.wgsl", true)?;
        Ok(Self { state, march_module: shaders::module(cx.device, "march.wgsl")? })
    }

    /// The sampling passes' reads (this one's and the sender-sky march's): the G-buffer, the
    /// parameters, the bounce source where `bounce` says it is read (and then, with the far side,
    /// the depth with each surface's extent that the lighting pass writes beside it, in place of
    /// the thickness layer), the depth pyramid, the thickness layer and the far side's surfaces
    /// (which only the far-sky pass reads).
    pub fn reads(plan: &Plan, bounce: bool) -> Vec<Read> {
        let layer = match bounce && plan.extent_layer {
            true => Read::Target(super::far_side::EXTENT_LAYER),
            false => Read::target_if(plan.thickness_layer, THICKNESS),
        };
        vec![
            Read::Target(ALBEDO),
            Read::Target(NORMAL),
            Read::Target(DEPTH),
            Read::Sampling,
            Read::target_if(bounce, plan.bounce_target()),
            Read::target_if(plan.pyramid, PYRAMID),
            layer,
            // The far side's surfaces: the far-sky pass's alone (`far_sky.rs`).
            Read::Absent(super::far_side::FAR_SURFACE),
        ]
    }

    /// The sampling reads with the bounce where a lighting pass writes it; AO or DO + AO, at
    /// half size when an upsample follows, and the sky for the next frame's senders.
    pub fn io(plan: &Plan) -> PassIo {
        let stage = plan.sampled(false, false);
        let last_sky = (plan.sender_sky == SenderSky::LastFrame).then_some(LAST_SKY);
        let writes = [stage.target(plan.decl.directional_occlusion)].into_iter().chain(last_sky).collect();
        PassIo { reads: Self::reads(plan, plan.lighting), attached: vec![], writes }
    }
}

impl Pass for SamplingPass {
    /// Builds what the plan needs (nothing when it has no sampling step).
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { plan, variant, .. } = *p;
        if !self.state.runs(plan.has(Step::SAMPLING)) {
            return;
        }
        self.state.bind(device, &Self::io(plan), &p.inputs);
        let key = Key {
            outputs: Outputs::of(plan),
            classic: variant.decl().estimator == Estimator::Classic,
            march: variant.decl().sampler == Sampler::March,
            pyramid: plan.pyramid,
            normal_mapped: plan.features.normal_mapped,
            over_irradiance: plan.do_over_irradiance(),
            last_sky: plan.sender_sky == SenderSky::LastFrame,
            thickness_layer: plan.thickness_layer,
            far_side: plan.far_side,
            extent_layer: plan.extent_layer,
        };

        let march_module = &self.march_module;
        self.state.ensure(plan, key, |key, points_module, layouts, shared| {
            let entry = match (key.outputs.directional, key.last_sky) {
                (false, _) => "fs_ao",
                (true, false) => "fs_do",
                (true, true) => "fs_do_senders",
            };
            let format = Some(key.outputs.format().into());
            let sky = key.last_sky.then(|| Some(LAST_SKY.format.into()));
            fullscreen_pipeline(
                device,
                &FullscreenDesc {
                    label: "sampling_pipeline",
                    module: if key.march { march_module } else { points_module },
                    entry,
                    bind_group_layouts: layouts,
                    targets: &[format].into_iter().chain(sky).collect::<Vec<_>>(),
                    depth: None,
                    constants: &[key.constants(), shared].concat(),
                },
            )
        });
    }

    fn record(&self, rec: Recording<'_>) {
        self.state.record(rec);
    }
}
