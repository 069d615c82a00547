//! What each step reads and writes, as its pass binds them: the one declaration of a pass's
//! inputs and outputs. The plan's target set is derived from it (`Plan::target_set`: a target
//! exists when a step of the plan writes it), a test checks that every read of a plan is written
//! by an earlier step, and `--print-plan` prints it.

use super::{Plan, Step};

/// A screen texture a step reads or writes (names as `targets.rs` gives them).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TargetId {
    Albedo,
    Normal,
    Depth,
    Pyramid,
    SenderSky,
    Bounce,
    Hdr,
    AoRaw,
    DoRaw,
    AoBlurred,
    DoBlurred,
    AoAccumulated,
    DoAccumulated,
    /// The sampling pass's output at half resolution (before the upsample).
    AoHalf,
    DoHalf,
    /// The temporal pass's histories (`history.rs`): read as the last frame left them, written
    /// for the next.
    OcclusionHistory,
    SurfaceHistory,
    /// What the frame is drawn into (the window or the capture).
    Output,
}

impl TargetId {
    pub fn name(self) -> &'static str {
        match self {
            TargetId::Albedo => "gbuffer_albedo",
            TargetId::Normal => "gbuffer_normal",
            TargetId::Depth => "gbuffer_depth",
            TargetId::Pyramid => "depth_pyramid",
            TargetId::SenderSky => "sender_sky",
            TargetId::Bounce => "bounce_radiance",
            TargetId::Hdr => "hdr_color",
            TargetId::AoRaw => "ao_raw",
            TargetId::DoRaw => "do_raw",
            TargetId::AoBlurred => "ao_blurred",
            TargetId::DoBlurred => "do_blurred",
            TargetId::AoAccumulated => "ao_accumulated",
            TargetId::AoHalf => "ao_half",
            TargetId::DoHalf => "do_half",
            TargetId::DoAccumulated => "do_accumulated",
            TargetId::OcclusionHistory => "history_occlusion",
            TargetId::SurfaceHistory => "history_surface",
            TargetId::Output => "output",
        }
    }

    /// Whether the target is a history: it outlives the frame, and a step may read it before any
    /// step of this frame writes it.
    pub fn persistent(self) -> bool {
        matches!(self, TargetId::OcclusionHistory | TargetId::SurfaceHistory)
    }

    /// Whether the target is one of the G-buffer's three, which every plan has.
    pub fn in_gbuffer(self) -> bool {
        matches!(self, TargetId::Albedo | TargetId::Normal | TargetId::Depth)
    }
}

/// A step's inputs and outputs in one plan.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StepIo {
    pub reads: Vec<TargetId>,
    pub writes: Vec<TargetId>,
}

impl Step {
    /// What this step reads and writes in `plan`.
    pub fn io(self, plan: &Plan) -> StepIo {
        use TargetId::*;
        let gbuffer = [Albedo, Normal, Depth];
        let when = |wanted: bool, id: TargetId| wanted.then_some(id);
        let pyramid = when(plan.has(Step::DepthPyramid), Pyramid);
        let directional = plan.decl.directional_occlusion;
        let (raw, blurred, accumulated) =
            if directional { (DoRaw, DoBlurred, DoAccumulated) } else { (AoRaw, AoBlurred, AoAccumulated) };
        let filtered = if plan.blur { blurred } else { raw };
        let half = if directional { DoHalf } else { AoHalf };
        // In a display plan what is shown is drawn straight into the output.
        let shown = if plan.display { Output } else { Hdr };
        let (reads, writes): (Vec<Option<TargetId>>, Vec<Option<TargetId>>) = match self {
            // The model into albedo, normal and depth.
            Step::GBuffer => (vec![], gbuffer.map(Some).to_vec()),
            // The closest depth per block.
            Step::DepthPyramid => (vec![Some(Depth)], vec![Some(Pyramid)]),
            // The sky each sender sees, from a one-slice march.
            Step::SenderSky => ([Some(Albedo), Some(Normal), Some(Depth), pyramid].to_vec(), vec![Some(SenderSky)]),
            // The senders' direct light; with lights, their displayed light too.
            Step::Lighting => (
                [Some(Albedo), Some(Normal), Some(Depth), when(plan.has(Step::SenderSky), SenderSky)].to_vec(),
                vec![Some(Bounce), when(plan.features.lights > 0, Hdr)],
            ),
            // AO or DO (+ AO) from one set of samples.
            Step::Occlusion => (
                [Some(Albedo), Some(Normal), Some(Depth), when(plan.has(Step::Lighting), Bounce), pyramid].to_vec(),
                vec![Some(if plan.half() { half } else { raw })],
            ),
            // The half-resolution samples on this pixel's surface, to full resolution.
            Step::Upsample => (vec![Some(Albedo), Some(Normal), Some(Depth), Some(half)], vec![Some(raw)]),
            Step::Blur => (vec![Some(Albedo), Some(Normal), Some(Depth), Some(raw)], vec![Some(blurred)]),
            // This frame's output and the last frames' average where the same surface was.
            Step::Temporal => (
                [Normal, Depth, filtered, OcclusionHistory, SurfaceHistory].map(Some).to_vec(),
                [accumulated, OcclusionHistory, SurfaceHistory].map(Some).to_vec(),
            ),
            // Every mode's terms; in a display plan, the lighting pass's light as well.
            Step::Composite => {
                let averaged = if plan.accumulates() { accumulated } else { filtered };
                let sampled = plan.decl.runs_sampling().then_some(averaged);
                let direct = when(plan.display && plan.lighting_writes_direct(), Hdr);
                ([Some(Albedo), Some(Normal), Some(Depth), sampled, direct].to_vec(), vec![Some(shown)])
            }
            Step::Skybox => (vec![Some(Depth)], vec![Some(Hdr)]),
            Step::LightCubes => (vec![Some(Depth)], vec![Some(shown)]),
            Step::Tonemap => (vec![Some(Hdr)], vec![Some(Output)]),
        };
        StepIo { reads: reads.into_iter().flatten().collect(), writes: writes.into_iter().flatten().collect() }
    }
}

impl Plan {
    /// Every step's inputs and outputs, in order.
    pub fn io(&self) -> Vec<(Step, StepIo)> {
        self.steps.iter().map(|&s| (s, s.io(self))).collect()
    }

    /// Whether a step of this plan writes `target`.
    pub fn writes(&self, target: TargetId) -> bool {
        self.steps.iter().any(|s| s.io(self).writes.contains(&target))
    }
}
