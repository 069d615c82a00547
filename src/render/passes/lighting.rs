//! Lighting pass (SSDO modes with light to bounce): each surface's direct light once per pixel.
//! It writes the diffuse radiance SSDO bounces into `bounce` — the point lights and, unless the
//! senders are lit by the point lights alone, the sky and the ambient they receive (from the
//! sender-sky march, the last frame's march, or the sky's unoccluded irradiance) — and, where
//! there are point lights, their displayed light into HDR. The pipeline is specialised to the
//! plan: without lights it has one target and runs no light loop.
//!
//! With the senders' sky from the last frame (`--sender-sky last-frame`) it reads one side of a
//! history, so it keeps a bind group for each, and two more pipelines: for a frame whose camera
//! moved (reprojecting) and for a still one. A frame with no last frame (the first after a
//! reset) reads this frame's sender-sky march, as `--sender-sky march` does.

use super::far_side::{EXTENT_LAYER, FAR_SURFACE};
use super::sampling::{last_sky_held, LAST_SKY};
use super::sender_sky;
use crate::render::graph::io::{PassIo, Read};
use crate::render::graph::state::{flag, ParityGroups, PassState, PipelineSpec};
use crate::render::graph::{Entry, FrameState, Pass, PassContext, Preparation, Recording};
use crate::render::modes::{LightReads, Plan, Step};
use crate::render::targets::{bounce_target, ALBEDO, DEPTH, HDR, HDR_FORMAT, NORMAL, THICKNESS};
use crate::render::SenderSky;
use crate::Result;

impl Step {
    pub const LIGHTING: Step = Step::new("lighting");
}

// Where a DO mode bounces light and there is light to bounce: point lights, or the sky when
// the senders take it.
pub const ENTRY: Entry = Entry::new(
    Step::LIGHTING,
    |f| f.bounces() && (f.lights() || f.sender_sky() != SenderSky::Off),
    LightingPass::io,
    |cx| Ok(Box::new(LightingPass::new(cx)?)),
)
.binding(&["lighting.wgsl"]);

/// The shader variant a plan needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Key {
    /// Point lights: their loop runs and their displayed light goes to HDR.
    lights: bool,
    light_reads: LightReads,
    sender_sky: SenderSky,
    /// The camera moved since the last frame (only with the sky from the last frame).
    reproject: bool,
    /// The model has normal maps: a sender's facing comes from the depth buffer's plane.
    normal_mapped: bool,
    /// The far side layer's surfaces are lit too, into the bounce target's second pair.
    far_side: bool,
    /// The march's depth with each surface's extent behind it is written.
    extent_layer: bool,
    /// ... from the G-buffer's thickness layer where it holds a sheet.
    thickness_layer: bool,
    /// The far side's surfaces take the sky their own march saw.
    far_sky: bool,
}

impl Key {
    /// The plan's key; with the sky from the last frame, a frame's that has none (reading this
    /// frame's sender-sky march).
    fn of(plan: &Plan) -> Self {
        Self {
            lights: plan.lighting_writes_direct(),
            light_reads: plan.light_reads(),
            sender_sky: plan.sender_sky.without_march(),
            reproject: false,
            normal_mapped: plan.features.normal_mapped,
            far_side: plan.far_side,
            extent_layer: plan.extent_layer,
            thickness_layer: plan.thickness_layer,
            far_sky: plan.has(Step::FAR_SKY),
        }
    }

    fn spec(self) -> PipelineSpec {
        let hdr = self.lights.then(|| HDR_FORMAT.into());
        let constants = [
            ("LIGHTS", flag(self.lights)),
            ("SENDER_SKY", self.sender_sky.shader_code()),
            ("REPROJECT", flag(self.reproject)),
            ("NORMAL_MAPPED", flag(self.normal_mapped)),
            ("FAR_SIDE", flag(self.far_side)),
            ("THICKNESS_LAYER", flag(self.extent_layer && self.thickness_layer)),
            ("FAR_SKY", flag(self.far_sky)),
        ];
        let extent = self.extent_layer.then(|| EXTENT_LAYER.format.into());
        PipelineSpec {
            entry: match (self.lights, self.extent_layer) {
                (true, false) => "fs_main",
                (false, false) => "fs_bounce",
                (true, true) => "fs_main_far",
                (false, true) => "fs_bounce_far",
            },
            targets: hdr
                .into_iter()
                .chain([bounce_target(self.far_side).format.into()])
                .chain(extent)
                .map(Some)
                .collect(),
            constants: constants.into_iter().chain(self.light_reads.constants()).collect(),
        }
    }
}

pub struct LightingPass {
    state: PassState<Key>,
    /// With the sky from the last frame: the pipelines reading it, for a still camera and for
    /// a moving one, and group 1 for each side of its history.
    still: PassState<Key>,
    moved: PassState<Key>,
    groups: Option<ParityGroups>,
    /// What this frame reads (set in `begin_frame`): the last frame's sky, and whether the
    /// camera moved since.
    last_sky: bool,
    camera_moved: bool,
}

impl LightingPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        // The sky's pixels send nothing: the depth test leaves them cleared.
        let state = PassState::new(cx, "lighting", "lighting.wgsl", false)?.surfaces_only(cx);
        let (still, moved) = (state.sibling("lighting_last_sky"), state.sibling("lighting_reprojected"));
        Ok(Self { state, still, moved, groups: None, last_sky: false, camera_moved: false })
    }

    /// The G-buffer and, after their march, the senders' sky (this frame's, and with the sky
    /// from the last frame, the last frame's); the point lights' displayed light (with lights)
    /// and the bounce.
    pub fn io(plan: &Plan) -> PassIo {
        let reads = vec![
            Read::Target(ALBEDO),
            Read::Target(NORMAL),
            Read::Target(DEPTH),
            Read::target_if(plan.sender_march, sender_sky::target(plan)),
            Read::target_if(plan.sender_sky == SenderSky::LastFrame, LAST_SKY),
            Read::target_if(plan.far_side, FAR_SURFACE),
            Read::target_if(plan.extent_layer && plan.thickness_layer, THICKNESS),
            Read::target_if(plan.has(Step::FAR_SKY), super::far_sky::FAR_SKY),
        ];
        let direct = plan.lighting_writes_direct().then_some(HDR);
        let extent = plan.extent_layer.then_some(EXTENT_LAYER);
        PassIo {
            reads,
            attached: vec![],
            writes: direct.into_iter().chain([plan.bounce_target()]).chain(extent).collect(),
        }
    }
}

impl Pass for LightingPass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let plan = p.plan;
        let key = Key::of(plan);
        self.state.prepare_fullscreen(device, p, (Step::LIGHTING, Self::io), || key, Key::spec);
        if !plan.has(Step::LIGHTING) || plan.sender_sky != SenderSky::LastFrame {
            self.still.clear();
            self.moved.clear();
            self.groups = None;
            return;
        }
        let io = Self::io(plan);
        self.groups = Some(self.state.parity_groups(device, &io, &p.inputs));
        for (state, reproject) in [(&mut self.still, false), (&mut self.moved, true)] {
            state.layout_for(device, &io);
            let key = Key { sender_sky: SenderSky::LastFrame, reproject, ..key };
            state.ensure_fullscreen(device, plan, key, Key::spec);
        }
    }

    fn begin_frame(&mut self, frame: &FrameState<'_>) {
        self.last_sky = last_sky_held(frame.plan, frame.history);
        self.camera_moved = frame.camera_moved;
    }

    fn record(&self, rec: Recording<'_>) {
        let last = rec.history.get(LAST_SKY).zip(self.groups.as_ref());
        match last {
            Some((history, groups)) if self.last_sky => {
                let state = if self.camera_moved { &self.moved } else { &self.still };
                state.record_with(rec, self.state.writes(), groups.of(history));
            }
            _ => self.state.record(rec),
        }
    }
}
