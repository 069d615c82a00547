//! The temporal pass (`shaders/temporal.wgsl`): the blurred (or raw) sampling output averaged
//! with the last frames' where the same surface was, reprojected through the previous camera.
//! It runs where the samples are: after a half-resolution sampling pass at half size, over the
//! half-size samples, into half-size histories; the composite upsamples the average as it reads
//! it (`shaders/common/upsample.wgsl`), so the chain after the samples has no full-screen pass.
//! It writes three targets at once: what the composite reads this frame (`ao_half_accumulated`
//! / `do_half_accumulated`, or the full-size `ao_accumulated` / `do_accumulated`), and the two
//! histories the next frame reads (`history.rs`). Its bind group
//! reads one side of each history pair, so it keeps one group a parity and binds the frame's;
//! and where a blur pass runs, one set reading the blurred samples and one the raw, for the frames
//! that skip the blur (`FrameState::blur`). Where the plan has no blur pass but blurs
//! (`Plan::temporal_blurs`), it reads the raw samples and blurs them itself in the frames that
//! blur (a pipeline built with `BLUR`).

use super::sampling::Outputs;
use crate::render::graph::io::{PassIo, Read};
use crate::render::graph::state::{flag, ParityGroups, PassState, PipelineSpec};
use crate::render::graph::{Entry, FrameState, Pass, PassContext, Preparation, Recording, Role};
use crate::render::history::HistorySpec;
use crate::render::modes::{Plan, PlanFacts, Step, OCCLUSION_HISTORY, SURFACE_HISTORY, SURFACE_HISTORY_FORMAT};
use crate::render::settings::MAX_HISTORY_TURN_DEG;
use crate::render::targets::{Stage, ALBEDO, DEPTH, NORMAL};
use crate::Result;

impl Step {
    pub const TEMPORAL: Step = Step::new("temporal");
}

pub const ENTRY: Entry = Entry::new(
    Step::TEMPORAL,
    |f| f.samples() && f.options.accumulate,
    TemporalPass::io,
    |cx| Ok(Box::new(TemporalPass::new(cx)?)),
)
.binding(&["temporal.wgsl"])
.keeping(TemporalPass::histories)
.role(Role::Denoise);

/// What distinguishes one temporal pipeline from another: what the sampling pass produces and
/// whether it blurs them (the framework keys it by the samples' size too).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Key {
    outputs: Outputs,
    blur: bool,
}

pub struct TemporalPass {
    /// Keyed by what the sampling pass produces (AO alone, or DO + AO): the pipeline for a frame
    /// whose camera moved (reprojecting) and the one for a still camera (each pixel its own),
    /// and where the plan has no blur pass, each of them blurring the samples first.
    state: PassState<Key>,
    still: PassState<Key>,
    moving_blurring: PassState<Key>,
    still_blurring: PassState<Key>,
    /// This frame's camera moved, and its samples were blurred (set in `begin_frame`).
    camera_moved: bool,
    blurred: bool,
    /// Group 1 for a frame that writes side 0 of the histories, and for one that writes side 1:
    /// reading the raw samples, then (where the plan blurs) the blurred ones.
    groups: Vec<ParityGroups>,
}

impl TemporalPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        let state = PassState::new(cx, "temporal", "temporal.wgsl", false)?;
        let still = state.sibling("temporal_still");
        let moving_blurring = state.sibling("temporal_blurring");
        let still_blurring = state.sibling("temporal_still_blurring");
        let (camera_moved, blurred, groups) = (false, false, Vec::new());
        Ok(Self { state, still, moving_blurring, still_blurring, camera_moved, blurred, groups })
    }

    /// The G-buffer, the parameters, the (blurred) sampling output and the last frame's
    /// histories; the average and this frame's histories, all at the samples' size.
    pub fn io(plan: &Plan) -> PassIo {
        Self::io_reading(plan, plan.has(Step::BLUR))
    }

    /// [`TemporalPass::io`] reading the blurred samples or, in a frame that skips the blur, the
    /// raw ones.
    fn io_reading(plan: &Plan, blurred: bool) -> PassIo {
        let d = plan.decl.directional_occlusion;
        let filtered = plan.sampled(false, blurred).target(d);
        let reads = [ALBEDO, NORMAL, DEPTH].map(Read::Target).into_iter().chain([Read::Filter]);
        let reads = reads.chain([filtered, OCCLUSION_HISTORY, SURFACE_HISTORY].map(Read::Target)).collect();
        let average = plan.sampled(true, blurred).target(d);
        PassIo { reads, attached: vec![], writes: vec![average, OCCLUSION_HISTORY, SURFACE_HISTORY] }
    }

    /// Its two histories, at the samples' size: the averaged sampling output (in its own
    /// format) and the surface each texel of it belongs to. What a channel means depends on what
    /// the mode computes, so the mode is the key: another mode starts anew.
    pub fn histories(facts: &PlanFacts) -> Vec<HistorySpec> {
        let format = Stage::Raw.target(facts.decl.directional_occlusion).format;
        let key = facts.decl.mode as u64;
        vec![
            HistorySpec { name: OCCLUSION_HISTORY.name, format, key },
            HistorySpec { name: SURFACE_HISTORY.name, format: SURFACE_HISTORY_FORMAT, key },
        ]
    }
}

impl Pass for TemporalPass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let plan = p.plan;
        if !plan.accumulates() {
            for state in [&mut self.state, &mut self.still, &mut self.moving_blurring, &mut self.still_blurring] {
                state.clear();
            }
            self.groups.clear();
            return;
        }
        let io = Self::io(plan);
        let blur_pass = plan.has(Step::BLUR);
        let inputs = if blur_pass { vec![Self::io_reading(plan, false), io.clone()] } else { vec![io.clone()] };
        self.groups = inputs.iter().map(|io| self.state.parity_groups(device, io, &p.inputs)).collect();
        self.still.layout_for(device, &io);
        let mut states = vec![(&mut self.state, true, false), (&mut self.still, false, false)];
        if plan.temporal_blurs {
            self.moving_blurring.layout_for(device, &io);
            self.still_blurring.layout_for(device, &io);
            states.extend([(&mut self.moving_blurring, true, true), (&mut self.still_blurring, false, true)]);
        } else {
            self.moving_blurring.clear();
            self.still_blurring.clear();
        }
        for (state, moved, blur) in states {
            let key = Key { outputs: Outputs::of(plan), blur };
            state.ensure_fullscreen(device, plan, key, |key| PipelineSpec {
                entry: "fs_main",
                targets: vec![
                    Some(key.outputs.format().into()),
                    Some(key.outputs.format().into()),
                    Some(SURFACE_HISTORY_FORMAT.into()),
                ],
                constants: vec![
                    ("CAMERA_MOVED", flag(moved)),
                    ("BLUR", flag(key.blur)),
                    ("MAX_HISTORY_TURN", f64::from(MAX_HISTORY_TURN_DEG)),
                ],
            });
        }
    }

    fn begin_frame(&mut self, frame: &FrameState<'_>) {
        self.camera_moved = frame.camera_moved;
        self.blurred = frame.blur;
    }

    fn record(&self, rec: Recording<'_>) {
        let (occlusion, surface) = match (rec.history.get(OCCLUSION_HISTORY), rec.history.get(SURFACE_HISTORY)) {
            (Some(o), Some(s)) => (o, s),
            _ => unreachable!("a plan that accumulates has its histories"),
        };
        debug_assert_eq!(occlusion.parity(), surface.parity(), "the two histories advance together");
        let set = if self.blurred { self.groups.last() } else { self.groups.first() };
        let groups = set.expect("the temporal pass recorded before `prepare`");
        let attachments = rec.attachments(self.state.writes(), true);
        let state = match (self.camera_moved, self.blurred && rec.plan.temporal_blurs) {
            (true, true) => &self.moving_blurring,
            (true, false) => &self.state,
            (false, true) => &self.still_blurring,
            (false, false) => &self.still,
        };
        state.draw_with((rec.encoder, rec.timestamps), &attachments, (rec.frame, groups.of(occlusion), None), None);
    }
}
