//! The sender-sky march (`--sender-sky march`, or `march-quarter` at a quarter of the width and
//! height): before the lighting pass, at half resolution, the
//! sky each surface sees through one slice of the march (`fs_sender` in `shaders/sender_sky.wgsl`,
//! built with DO on and AO and the bounce off). The lighting pass turns it into the sky light each
//! sender bounces, so the bounce carries the sky with the sender's own visibility.
//!
//! With `--sender-sky last-frame` the march of the sampling pass writes that sky for the next
//! frame (`sampling::LAST_SKY`), and this pass runs only on a frame with no last frame to read
//! (the first after a reset).

use super::sampling::{last_sky_held, SamplingPass};
use crate::render::graph::io::PassIo;
use crate::render::graph::state::{flag, PassState, PipelineSpec};
use crate::render::graph::{Entry, FrameState, Pass, PassContext, Preparation, Recording, Role};
use crate::render::modes::{Plan, Step};
use crate::render::targets::{Place, TargetId, DO_FORMAT};
use crate::render::SenderSky;
use crate::Result;

impl Step {
    pub const SENDER_SKY: Step = Step::new("sender_sky");
}

pub const ENTRY: Entry = Entry::new(
    Step::SENDER_SKY,
    |f| f.sender_sky().marches(),
    SenderSkyPass::io,
    |cx| Ok(Box::new(SenderSkyPass::new(cx)?)),
)
.binding(&["sender_sky.wgsl"])
.role(Role::Sampling);

/// The sky each sender of the bounce sees (rgb, E/π before albedo) and its open share (a), at
/// half resolution: read by the lighting pass.
pub const SENDER_SKY: TargetId = TargetId::new("sender_sky", DO_FORMAT, Place::HalfScreen);
/// The same at a quarter of the width and height (`--sender-sky march-quarter`).
pub const SENDER_SKY_QUARTER: TargetId = TargetId::new("sender_sky_quarter", DO_FORMAT, Place::QuarterScreen);

/// The senders' sky target of a plan: at half or at quarter resolution.
pub fn target(plan: &Plan) -> TargetId {
    match plan.sender_sky {
        SenderSky::MarchQuarter => SENDER_SKY_QUARTER,
        _ => SENDER_SKY,
    }
}

pub struct SenderSkyPass {
    /// Keyed by whether the far steps read the depth pyramid, whether the G-buffer's normals
    /// are mapped, whether it runs at quarter resolution and whether it reads the thickness
    /// layer.
    state: PassState<(bool, bool, bool, bool)>,
    /// The last frame's march left the senders' sky: this frame skips the pass.
    skipped: bool,
}

impl SenderSkyPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        Ok(Self { state: PassState::new(cx, "sender_sky", "sender_sky.wgsl", true)?, skipped: false })
    }

    /// The sampling pass's reads but the bounce, which this pass feeds; the senders' sky.
    pub fn io(plan: &Plan) -> PassIo {
        PassIo { reads: SamplingPass::reads(plan, false), attached: vec![], writes: vec![target(plan)] }
    }
}

/// A sky pass's pipeline (this one's, and the far sky's): the march with DO alone (no AO, no
/// bounce), its pyramid, normal maps and thickness layer as `inputs` say, at `1 / 2^shift` of the
/// screen's width and height.
pub fn sky_march(entry: &'static str, (pyramid, mapped, thickness): (bool, bool, bool), shift: u32) -> PipelineSpec {
    PipelineSpec {
        entry,
        targets: vec![Some(DO_FORMAT.into())],
        constants: vec![
            ("HAS_AO", 0.0),
            ("HAS_DO", 1.0),
            ("INDIRECT", 0.0),
            ("USE_PYRAMID", flag(pyramid)),
            ("NORMAL_MAPPED", flag(mapped)),
            ("SENDER_SHIFT", shift as f64),
            ("THICKNESS_LAYER", flag(thickness)),
        ],
    }
}

impl Pass for SenderSkyPass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let quarter = p.plan.sender_sky == SenderSky::MarchQuarter;
        let key = || (p.plan.pyramid, p.plan.features.normal_mapped, quarter, p.plan.thickness_layer);
        let spec = |(pyramid, mapped, quarter, thickness)| {
            sky_march("fs_sender", (pyramid, mapped, thickness), if quarter { 2 } else { 1 })
        };
        self.state.prepare_fullscreen(device, p, (Step::SENDER_SKY, Self::io), key, spec);
    }

    fn begin_frame(&mut self, frame: &FrameState<'_>) {
        self.skipped = last_sky_held(frame.plan, frame.history);
    }

    fn record(&self, rec: Recording<'_>) {
        if self.skipped {
            rec.skip(self.state.writes());
        } else {
            self.state.record(rec);
        }
    }
}
