//! Render modes, and what each allocates and runs: this file answers it. A mode *declares* what
//! it needs ([`ModeDecl`], the table in [`Mode::declaration`]); [`Plan::new`] turns that and the
//! scene's features into the steps the frame runs, and [`Plan::target_set`] into the screen
//! targets it allocates (`targets.rs` allocates exactly that set). Nothing a mode or a scene does
//! not need is in the plan, and so nothing for it is allocated or run. `--print-plan` prints both.
//!
//! | mode | steps (the defaults: lights, half resolution, blur, accumulation, display plan) | targets besides the G-buffer and histories |
//! |---|---|---|
//! | Off | gbuffer, composite, light_cubes | — |
//! | SSAO | gbuffer, ssao, upsample, blur, temporal, composite, light_cubes | `ao_half`, `ao_raw`, `ao_blurred`, `ao_accumulated` |
//! | SSDO | gbuffer, sender_sky, lighting, ssdo, upsample, blur, temporal, composite, light_cubes | `hdr_color`, `bounce_radiance`, `sender_sky`, `do_half`, `do_raw`, `do_blurred`, `do_accumulated` |
//! | SSAO+SSDO | gbuffer, sender_sky, lighting, ssao_ssdo, upsample, blur, temporal, composite, light_cubes | as SSDO (AO travels in the DO target's alpha) |
//!
//! Without lights there are no light cubes and the lighting pass writes the bounce alone (the
//! senders' sky and ambient light; no HDR target in a display plan); with `--sender-sky off` and
//! no lights, or with `--indirect-strength 0`, there is no lighting pass and no bounce target at
//! all (the composite then runs the light loop). An HDR plan (the report, `--raw`, `--stats`, a debug view) adds `hdr_color`, the skybox
//! and the tone map; `--no-blur` drops the blur and its targets; `--accumulate 1` drops the
//! temporal pass, its target and its two histories; `--full-res` the upsample and the half-size
//! target; the march with `--depth-pyramid`
//! adds the pyramid in the DO modes.

mod io;
pub mod table;

pub use io::{StepIo, TargetId};

pub use table::{Mode, ModeDecl, MODES};

use super::history::HistorySpec;
use super::settings::SenderSky;
pub use super::targets::TargetSet;

/// What the scene brings that changes the plan.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SceneFeatures {
    pub lights: usize,
}

/// The settings that shape a plan besides the mode, by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlanOptions {
    /// Denoise the sampling output.
    pub blur: bool,
    /// The sampling pass marches the depth buffer and its far steps, taken only where DO is
    /// computed, read a depth pyramid (the march variant with `depth_pyramid` on).
    pub pyramid: bool,
    /// See [`Plan::display`].
    pub display: bool,
    /// SSDO's one bounce is on (its strength is above 0).
    pub indirect: bool,
    /// What lights the bounce's senders besides the point lights (`Settings::sender_sky`).
    pub sender_sky: SenderSky,
    /// The sampling pass runs at half resolution, an upsample after it.
    pub half: bool,
    /// The sampling output is averaged over frames (`Settings::accumulates`): a temporal pass
    /// and its history.
    pub accumulate: bool,
}

impl Default for PlanOptions {
    /// The defaults' plan: a display plan with half-resolution sampling, blur and accumulation,
    /// no pyramid, and the bounce lit by the sky and the lights.
    fn default() -> Self {
        let (blur, pyramid, display, indirect, half, accumulate) = (true, false, true, true, true, true);
        Self { blur, pyramid, display, indirect, sender_sky: SenderSky::default(), half, accumulate }
    }
}

/// One step of a frame, in the order the frame runs them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Step {
    /// Rasterise the model into albedo, normal and depth.
    GBuffer,
    /// The closest-depth pyramid the march's far steps read (march variant, DO modes).
    DepthPyramid,
    /// The sky each sender of the bounce sees: a half-resolution march of one slice per pixel
    /// (`--sender-sky march`), read by the lighting pass.
    SenderSky,
    /// Each surface's direct light once per pixel: the radiance SSDO bounces (point lights, and
    /// the sky and ambient when the senders take them), and the point lights' displayed light.
    Lighting,
    /// The sampling pass: AO, DO, or both from one set of samples.
    Occlusion,
    /// A half-resolution sampling output brought to full resolution, by depth and normal.
    Upsample,
    /// Depth- and normal-aware (or classic box) blur of the sampling pass's output.
    Blur,
    /// The (blurred) sampling output averaged with the last frames', reprojected where the same
    /// surface was (`shaders/temporal.wgsl`).
    Temporal,
    /// Ambient, occlusion and point lighting into the HDR target; in a display plan also the
    /// sky, exposure and tone curve, straight into the output.
    Composite,
    /// Sky where nothing was drawn (HDR plans).
    Skybox,
    /// The point lights as emissive cubes.
    LightCubes,
    /// HDR to the display format (HDR plans).
    Tonemap,
}

impl Step {
    /// The step's name in a plan of `mode` (the sampling pass is named after what it computes).
    pub fn name_in(self, mode: Mode) -> &'static str {
        match self {
            Step::Occlusion => mode.declaration().sampling_step,
            _ => self.name(),
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Step::GBuffer => "gbuffer",
            Step::DepthPyramid => "depth_pyramid",
            Step::SenderSky => "sender_sky",
            Step::Lighting => "lighting",
            Step::Occlusion => "occlusion",
            Step::Upsample => "upsample",
            Step::Blur => "blur",
            Step::Temporal => "temporal",
            Step::Composite => "composite",
            Step::Skybox => "skybox",
            Step::LightCubes => "light_cubes",
            Step::Tonemap => "tonemap",
        }
    }
}

/// The steps of one frame for a mode and a scene.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plan {
    pub mode: Mode,
    pub decl: ModeDecl,
    pub features: SceneFeatures,
    pub blur: bool,
    /// Nothing reads HDR after the frame (the final image is shown or saved as it is): the
    /// composite draws the sky and tone-maps straight into the output, and there is no skybox or
    /// tone-map pass, and no HDR target unless a lighting pass writes its direct light there.
    pub display: bool,
    /// What lights the bounce's senders besides the point lights; `Off` wherever the plan has no
    /// bounce.
    pub sender_sky: SenderSky,
    pub steps: Vec<Step>,
    /// The targets kept across frames (see `history.rs`): the temporal pass's, where it runs.
    pub history: Vec<HistorySpec>,
}

impl Plan {
    /// The steps of `mode` for a scene with `features` and the options `o`.
    ///
    /// The lighting pass runs where a DO mode bounces light and there is light to bounce: point
    /// lights, or the sky when the senders take it. Off, SSAO and a bounce of strength 0 never
    /// run it.
    pub fn new(mode: Mode, features: SceneFeatures, o: PlanOptions) -> Self {
        let decl = *mode.declaration();
        let lights = features.lights > 0;
        let bounces = decl.directional_occlusion && o.indirect;
        let sender_sky = if bounces { o.sender_sky } else { SenderSky::Off };
        let mut steps = vec![Step::GBuffer];
        if o.pyramid && decl.directional_occlusion {
            steps.push(Step::DepthPyramid);
        }
        if sender_sky == SenderSky::March {
            steps.push(Step::SenderSky);
        }
        if bounces && (lights || sender_sky != SenderSky::Off) {
            steps.push(Step::Lighting);
        }
        if decl.runs_sampling() {
            steps.push(Step::Occlusion);
            if o.half {
                steps.push(Step::Upsample);
            }
            if o.blur {
                steps.push(Step::Blur);
            }
            if o.accumulate {
                steps.push(Step::Temporal);
            }
        }
        steps.push(Step::Composite);
        if !o.display {
            steps.push(Step::Skybox);
        }
        if lights {
            steps.push(Step::LightCubes);
        }
        if !o.display {
            steps.push(Step::Tonemap);
        }
        let blur = o.blur && decl.runs_sampling();
        let history = if steps.contains(&Step::Temporal) { temporal_history(&decl) } else { Vec::new() };
        Self { mode, decl, features, blur, display: o.display, sender_sky, steps, history }
    }

    /// Whether the sampling pass runs at half resolution.
    pub fn half(&self) -> bool {
        self.has(Step::Upsample)
    }

    /// Whether the plan averages the sampling output over frames.
    pub fn accumulates(&self) -> bool {
        self.has(Step::Temporal)
    }

    /// The names of the steps, in order.
    pub fn step_names(&self) -> Vec<&'static str> {
        self.steps.iter().map(|s| s.name_in(self.mode)).collect()
    }

    /// Whether the HDR target exists: an HDR plan, or a lighting pass writing its direct light.
    pub fn keeps_hdr(&self) -> bool {
        !self.display || self.lighting_writes_direct()
    }

    /// Whether the lighting pass writes the point lights' displayed light (it runs and there are
    /// lights), which the composite then adds instead of running the light loop.
    pub fn lighting_writes_direct(&self) -> bool {
        self.has(Step::Lighting) && self.features.lights > 0
    }

    /// The screen targets this plan allocates besides the G-buffer (albedo, normal, depth):
    /// those its steps write (see `io.rs`).
    pub fn target_set(&self) -> TargetSet {
        let written: Vec<TargetId> = self.steps.iter().flat_map(|s| s.io(self).writes).collect();
        let writes = |id| written.contains(&id);
        TargetSet {
            hdr: writes(TargetId::Hdr),
            bounce: writes(TargetId::Bounce),
            ao: writes(TargetId::AoRaw),
            directional: writes(TargetId::DoRaw),
            blurred: writes(TargetId::AoBlurred) || writes(TargetId::DoBlurred),
            accumulated: writes(TargetId::AoAccumulated) || writes(TargetId::DoAccumulated),
            half: writes(TargetId::AoHalf) || writes(TargetId::DoHalf),
            pyramid: writes(TargetId::Pyramid),
            sender_sky: writes(TargetId::SenderSky),
        }
    }

    pub fn has(&self, step: Step) -> bool {
        self.steps.contains(&step)
    }

    /// Whether the composite runs the point-light loop itself (lights, but no lighting pass).
    pub fn light_loop(&self) -> bool {
        self.features.lights > 0 && !self.has(Step::Lighting)
    }
}

/// The temporal pass's two histories: the averaged sampling output (in its own format) and the
/// surface each pixel of it belongs to (`SURFACE_HISTORY_FORMAT`). What a channel means depends
/// on what the mode computes, so the mode is the key: another mode starts anew.
fn temporal_history(decl: &ModeDecl) -> Vec<HistorySpec> {
    let format = if decl.directional_occlusion { super::targets::DO_FORMAT } else { super::targets::AO_FORMAT };
    let key = decl.mode as u64;
    vec![
        HistorySpec { name: OCCLUSION_HISTORY, format, key },
        HistorySpec { name: SURFACE_HISTORY, format: SURFACE_HISTORY_FORMAT, key },
    ]
}

/// The temporal pass's history of the averaged AO or DO + AO.
pub const OCCLUSION_HISTORY: &str = "occlusion";
/// The temporal pass's history of each pixel's surface: its depth (f32 bits), and its world
/// normal (two 12-bit octahedral codes) with the frames it holds (8 bits).
pub const SURFACE_HISTORY: &str = "surface";
pub const SURFACE_HISTORY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rg32Uint;

#[cfg(test)]
mod tests;
