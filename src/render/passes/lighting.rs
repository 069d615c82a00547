//! Lighting pass (SSDO modes with light to bounce): each surface's direct light once per pixel.
//! It writes the diffuse radiance SSDO bounces into `bounce` — the point lights and, unless the
//! senders are lit by the point lights alone, the sky and the ambient they receive (from the
//! sender-sky march, or the sky's unoccluded irradiance) — and, where there are point lights,
//! their displayed light into HDR. The pipeline is specialised
//! to the plan: without lights it has one target and runs no light loop.

use super::super::modes::{Plan, Step};
use super::super::settings::SenderSky;
use super::super::targets::{view_of, view_or, BOUNCE_FORMAT, HDR_FORMAT};
use super::state::{flag, PassState, PipelineSpec};
use super::{cleared_attachments, gbuffer_entries, texture_entry, view_entries};
use super::{Pass, PassContext, Preparation, Recording};
use crate::Result;

/// The shader variant a plan needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Key {
    /// Point lights: their loop runs and their displayed light goes to HDR.
    lights: bool,
    sender_sky: SenderSky,
}

impl Key {
    fn of(plan: &Plan) -> Self {
        Self { lights: plan.lighting_writes_direct(), sender_sky: plan.sender_sky }
    }
}

pub struct LightingPass {
    state: PassState<Key>,
}

impl LightingPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        let [a, n, d] = gbuffer_entries();
        let layout = cx.layout("lighting_layout", &[a, n, d, texture_entry(3, false, wgpu::TextureViewDimension::D2)]);
        Ok(Self { state: PassState::new(cx, "lighting", "lighting.wgsl", false, layout)? })
    }
}

impl Pass for LightingPass {
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { targets, plan, unused, .. } = *p;
        if !self.state.runs(plan.has(Step::Lighting)) {
            return;
        }
        let views =
            [&targets.albedo.view, &targets.normal.view, &targets.depth.view, view_or(&targets.sender_sky, unused)];
        self.state.bind(device, &view_entries(&views));
        self.state.ensure_fullscreen(device, Key::of(plan), |key| {
            let hdr = key.lights.then(|| HDR_FORMAT.into());
            PipelineSpec {
                entry: if key.lights { "fs_main" } else { "fs_bounce" },
                targets: hdr.into_iter().map(Some).chain([Some(BOUNCE_FORMAT.into())]).collect(),
                constants: vec![("LIGHTS", flag(key.lights)), ("SENDER_SKY", key.sender_sky.shader_code())],
            }
        });
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, .. } = rec;
        let (key, _, _) = self.state.ready();
        let bounce = view_of(&targets.bounce);
        let attachments = if key.lights {
            cleared_attachments(&[view_of(&targets.hdr), bounce])
        } else {
            cleared_attachments(&[bounce])
        };
        self.state.draw((encoder, timestamps), &attachments, (frame, None), None);
    }
}
