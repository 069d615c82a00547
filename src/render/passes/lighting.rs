//! Lighting pass (SSDO modes with light to bounce): each surface's direct light once per pixel.
//! It writes the diffuse radiance SSDO bounces into `bounce` — the point lights and, unless the
//! senders are lit by the point lights alone, the sky and the ambient they receive (from the
//! sender-sky march, or the sky's unoccluded irradiance) — and, where there are point lights,
//! their displayed light into HDR. The pipeline is specialised to the plan: without lights it
//! has one target and runs no light loop.

use super::sender_sky;
use crate::render::graph::io::{PassIo, Read};
use crate::render::graph::state::{flag, PassState, PipelineSpec};
use crate::render::graph::{Entry, Pass, PassContext, Preparation, Recording};
use crate::render::modes::{LightReads, Plan, Step};
use crate::render::settings::SenderSky;
use crate::render::targets::{ALBEDO, BOUNCE, BOUNCE_FORMAT, DEPTH, HDR, HDR_FORMAT, NORMAL};
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
}

impl Key {
    fn of(plan: &Plan) -> Self {
        Self { lights: plan.lighting_writes_direct(), light_reads: plan.light_reads(), sender_sky: plan.sender_sky }
    }
}

pub struct LightingPass {
    state: PassState<Key>,
}

impl LightingPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        // The sky's pixels send nothing: the depth test leaves them cleared.
        Ok(Self { state: PassState::new(cx, "lighting", "lighting.wgsl", false)?.surfaces_only(cx) })
    }

    /// The G-buffer and, after their march, the senders' sky; the point lights' displayed light
    /// (with lights) and the bounce.
    pub fn io(plan: &Plan) -> PassIo {
        let reads = vec![
            Read::Target(ALBEDO),
            Read::Target(NORMAL),
            Read::Target(DEPTH),
            Read::target_if(plan.sender_march, sender_sky::target(plan)),
        ];
        let direct = plan.lighting_writes_direct().then_some(HDR);
        PassIo { reads, attached: vec![], writes: direct.into_iter().chain([BOUNCE]).collect() }
    }
}

impl Pass for LightingPass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let key = || Key::of(p.plan);
        self.state.prepare_fullscreen(device, p, (Step::LIGHTING, Self::io), key, |key| {
            let hdr = key.lights.then(|| HDR_FORMAT.into());
            PipelineSpec {
                entry: if key.lights { "fs_main" } else { "fs_bounce" },
                targets: hdr.into_iter().map(Some).chain([Some(BOUNCE_FORMAT.into())]).collect(),
                constants: [("LIGHTS", flag(key.lights)), ("SENDER_SKY", key.sender_sky.shader_code())]
                    .into_iter()
                    .chain(key.light_reads.constants())
                    .collect(),
            }
        });
    }

    fn record(&self, rec: Recording<'_>) {
        self.state.record(rec);
    }
}
