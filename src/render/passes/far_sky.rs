//! The far side's sky (`--far-sky`, with `--far-side`): before the lighting pass, at a quarter of
//! the width and height, the sky each far side surface sees through one slice of the march
//! (`fs_far_sender` in `shaders/sender_sky.wgsl`), its angles measured about the continuation of its
//! eye ray (it faces away from the eye), over the depth buffer: what lies behind it on the screen
//! occludes it (an underside sees the floor beneath), what the screen does not show does not. The
//! lighting pass lights the far senders with it and the ambient, as it lights the near ones with
//! theirs.

use super::far_side::FAR_SURFACE;
use super::sampling::SamplingPass;
use super::sender_sky::sky_march;
use crate::render::graph::io::{PassIo, Read};
use crate::render::graph::state::PassState;
use crate::render::graph::{Entry, Pass, PassContext, Preparation, Recording, Role};
use crate::render::modes::{Plan, Step};
use crate::render::targets::{Place, TargetId, DO_FORMAT};
use crate::Result;

impl Step {
    pub const FAR_SKY: Step = Step::new("far_sky");
}

pub const ENTRY: Entry = Entry::new(
    Step::FAR_SKY,
    |f| super::far_side::runs(f) && super::far_side::sky(f),
    FarSkyPass::io,
    |cx| Ok(Box::new(FarSkyPass::new(cx)?)),
)
.binding(&["sender_sky.wgsl"])
.role(Role::Sampling);

/// The sky each far side surface sees (rgb, E/π before albedo, at the senders' sky strength) and
/// its open share (a), at a quarter of the width and height (a half cost the far side's frame
/// 1.22×, for the same errors).
pub const FAR_SKY: TargetId = TargetId::new("far_sky", DO_FORMAT, Place::QuarterScreen);

pub struct FarSkyPass {
    state: PassState<(bool, bool, bool)>,
}

impl FarSkyPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        Ok(Self { state: PassState::new(cx, "far_sky", "sender_sky.wgsl", true)? })
    }

    /// The sampling pass's reads but the bounce, and the far side's surfaces; the far sky.
    pub fn io(plan: &Plan) -> PassIo {
        let mut reads = SamplingPass::reads(plan, false);
        reads[7] = Read::Target(FAR_SURFACE);
        PassIo { reads, attached: vec![], writes: vec![FAR_SKY] }
    }
}

impl Pass for FarSkyPass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let key = || (p.plan.pyramid, p.plan.features.normal_mapped, p.plan.thickness_layer);
        let spec = |inputs| {
            let mut spec = sky_march("fs_far_sender", inputs, 2);
            spec.constants.push(("FAR_EXTENT", 1.0));
            spec
        };
        self.state.prepare_fullscreen(device, p, (Step::FAR_SKY, Self::io), key, spec);
    }

    fn record(&self, rec: Recording<'_>) {
        self.state.record(rec);
    }
}
