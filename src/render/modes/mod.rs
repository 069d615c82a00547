//! Render modes, and what each allocates and runs: this file answers it. A mode *declares* what
//! it needs ([`ModeDecl`], the table in [`Mode::declaration`]); [`Plan::new`] turns that and the
//! scene's features into the steps the frame runs, and [`Plan::target_set`] into the screen
//! targets it allocates (`targets.rs` allocates exactly that set). Nothing a mode or a scene does
//! not need is in the plan, and so nothing for it is allocated or run. `--print-plan` prints both.
//!
//! | mode | steps (with lights, blur and accumulation on, display plan) | targets besides the G-buffer and histories |
//! |---|---|---|
//! | Off | gbuffer, composite, light_cubes | — |
//! | SSAO | gbuffer, ssao, blur, temporal, composite, light_cubes | `ao_raw`, `ao_blurred`, `ao_accumulated` |
//! | SSDO | gbuffer, sender_sky, lighting, ssdo, blur, temporal, composite, light_cubes | `hdr_color`, `bounce_radiance`, `sender_sky`, `do_raw`, `do_blurred`, `do_accumulated` |
//! | SSAO+SSDO | gbuffer, sender_sky, lighting, ssao_ssdo, blur, temporal, composite, light_cubes | as SSDO (AO travels in the DO target's alpha) |
//!
//! Without lights there are no light cubes and the lighting pass writes the bounce alone (the
//! senders' sky and ambient light; no HDR target in a display plan); with `--sender-sky off` and
//! no lights, or with `--indirect-strength 0`, there is no lighting pass and no bounce target at
//! all (the composite then runs the light loop). An HDR plan (the report, `--raw`, `--stats`, a debug view) adds `hdr_color`, the skybox
//! and the tone map; `--no-blur` drops the blur and its targets; `--accumulate 1` drops the
//! temporal pass, its target and its two histories; the march with `--depth-pyramid`
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
    /// A display plan with blur and accumulation, no pyramid, and the bounce lit by the sky and
    /// the lights.
    fn default() -> Self {
        let (blur, pyramid, display, indirect, half, accumulate) = (true, false, true, true, false, true);
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
mod tests {
    use super::*;

    /// Every plan the options can make.
    fn all_plans() -> Vec<Plan> {
        let mut plans = Vec::new();
        for mode in Mode::ALL {
            for lights in [0, 8] {
                for bits in 0..64u32 {
                    for sender_sky in SenderSky::ALL {
                        let [blur, pyramid, display, indirect, accumulate, half] =
                            [0, 1, 2, 3, 4, 5].map(|b| bits & (1 << b) != 0);
                        let o = PlanOptions { blur, pyramid, display, indirect, sender_sky, half, accumulate };
                        plans.push(Plan::new(mode, SceneFeatures { lights }, o));
                    }
                }
            }
        }
        plans
    }

    #[test]
    fn every_read_is_written_by_an_earlier_step_and_the_targets_are_what_the_steps_write() {
        for plan in all_plans() {
            let io = plan.io();
            for (i, (step, step_io)) in io.iter().enumerate() {
                // A history is read before it is written: what it holds is the last frame's.
                for read in step_io.reads.iter().filter(|t| !t.persistent()) {
                    let earlier = io[..i].iter().any(|(_, e)| e.writes.contains(read));
                    assert!(earlier, "{:?}: {step:?} reads {} before any step writes it", plan.steps, read.name());
                }
            }
            assert!(plan.writes(TargetId::Output), "{:?}: nothing reaches the output", plan.steps);
            // The set by hand, as the plan's rules say it.
            let sampled = plan.decl.runs_sampling();
            let t = plan.target_set();
            assert_eq!(t.hdr, plan.keeps_hdr(), "{:?}", plan.steps);
            assert_eq!(t.bounce, plan.has(Step::Lighting));
            assert_eq!(
                (t.ao, t.directional),
                (sampled && !plan.decl.directional_occlusion, plan.decl.directional_occlusion)
            );
            assert_eq!(t.blurred, plan.blur);
            assert_eq!(t.accumulated, plan.accumulates());
            assert_eq!(t.half, plan.half());
            assert_eq!(plan.half(), sampled && plan.has(Step::Upsample));
            assert_eq!(plan.accumulates(), sampled && plan.has(Step::Temporal));
            assert_eq!(plan.history.len(), if plan.accumulates() { 2 } else { 0 }, "{:?}", plan.steps);
            assert_eq!((t.pyramid, t.sender_sky), (plan.has(Step::DepthPyramid), plan.has(Step::SenderSky)));
        }
    }

    #[test]
    fn the_architecture_pages_mode_table_is_what_the_plans_are() {
        let page = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/ARCHITECTURE.md")).unwrap();
        let lit = SceneFeatures { lights: 8 };
        let mut previous: Option<Vec<String>> = None;
        let mut rows = 0;
        for line in page.lines().filter(|l| l.starts_with("| ")) {
            let cells: Vec<&str> = line.split('|').map(str::trim).collect();
            let Some(mode) = MODES.iter().find(|d| d.title == cells[1]).map(|d| d.mode) else { continue };
            let plan = Plan::new(mode, lit, PlanOptions::default());
            assert_eq!(cells[2].replace(" → ", ", "), plan.step_names().join(", "), "{mode}: steps");
            let mut named: Vec<String> = cells[3].split('`').skip(1).step_by(2).map(String::from).collect();
            if cells[3].starts_with("as ") {
                named = previous.clone().expect("'as' names an earlier row");
            }
            let mut written: Vec<String> = plan
                .io()
                .iter()
                .flat_map(|(_, io)| io.writes.clone())
                .filter(|t| !t.in_gbuffer() && !t.persistent() && *t != TargetId::Output)
                .map(|t| t.name().to_string())
                .collect();
            written.sort();
            written.dedup();
            let mut sorted = named.clone();
            sorted.sort();
            assert_eq!(sorted, written, "{mode}: targets besides the G-buffer");
            previous = Some(named);
            rows += 1;
        }
        assert_eq!(rows, MODES.len(), "one row a mode in ARCHITECTURE.md");
    }

    #[test]
    fn every_mode_has_one_row_with_its_own_key_and_names() {
        for (i, d) in MODES.iter().enumerate() {
            assert_eq!(Mode::ALL[i], d.mode);
            assert_eq!(Mode::from_key(d.key), Some(d.mode));
            assert_eq!(d.name.parse::<Mode>().unwrap(), d.mode);
            assert_eq!(d.mode.declaration(), d);
        }
        let err = "ssdo2".parse::<Mode>().unwrap_err().to_string();
        assert!(err.contains("expected off, ssao, ssdo, both"), "{err}");
        assert_eq!(Mode::sampled().collect::<Vec<_>>(), [Mode::Ssao, Mode::Ssdo, Mode::Both]);
        assert_eq!(Mode::from_key(0), None);
    }

    #[test]
    fn the_table_at_the_top_of_this_file_is_what_the_plans_are() {
        let lit = SceneFeatures { lights: 8 };
        // (mode, steps, (hdr, bounce, ao, directional))
        let rows = [
            (Mode::Off, "gbuffer, composite, light_cubes", (false, false, false, false)),
            (Mode::Ssao, "gbuffer, ssao, blur, temporal, composite, light_cubes", (false, false, true, false)),
            (
                Mode::Ssdo,
                "gbuffer, sender_sky, lighting, ssdo, blur, temporal, composite, light_cubes",
                (true, true, false, true),
            ),
            (
                Mode::Both,
                "gbuffer, sender_sky, lighting, ssao_ssdo, blur, temporal, composite, light_cubes",
                (true, true, false, true),
            ),
        ];
        for (mode, steps, targets) in rows {
            let plan = Plan::new(mode, lit, PlanOptions::default());
            assert_eq!(plan.step_names().join(", "), steps, "{mode}");
            let t = plan.target_set();
            assert_eq!((t.hdr, t.bounce, t.ao, t.directional), targets, "{mode}");
            assert_eq!((t.blurred, t.pyramid), (plan.decl.runs_sampling(), false), "{mode}");
        }
    }

    #[test]
    fn a_display_plan_has_no_skybox_or_tonemap_pass_and_keeps_hdr_only_for_the_lighting_pass() {
        let lit = SceneFeatures { lights: 8 };
        for mode in Mode::ALL {
            let hdr = Plan::new(mode, lit, PlanOptions { display: false, ..PlanOptions::default() });
            let display = Plan::new(mode, lit, PlanOptions::default());
            assert!(hdr.has(Step::Skybox) && hdr.has(Step::Tonemap) && hdr.keeps_hdr());
            assert!(!display.has(Step::Skybox) && !display.has(Step::Tonemap));
            assert_eq!(display.keeps_hdr(), display.has(Step::Lighting), "{mode}");
            let without = |p: &Plan| p.steps.iter().filter(|s| !matches!(s, Step::Skybox | Step::Tonemap)).count();
            assert_eq!(without(&hdr), display.steps.len(), "{mode}: the same passes otherwise");
        }
        let dark = Plan::new(Mode::Ssdo, SceneFeatures { lights: 0 }, PlanOptions::default());
        assert!(dark.has(Step::Lighting), "under a sky alone the senders' sky light is bounced");
        assert!(!dark.keeps_hdr(), "no lights: the lighting pass writes the bounce alone, no HDR target");
    }

    #[test]
    fn the_lighting_pass_runs_where_there_is_light_to_bounce_and_nowhere_else() {
        // (mode, lights, indirect, sender sky) -> lighting pass, bounce target, light cubes
        let (march, irradiance, off) = (SenderSky::March, SenderSky::Irradiance, SenderSky::Off);
        let rows = [
            (Mode::Ssdo, 0, true, march, (true, true, false)),
            (Mode::Both, 0, true, irradiance, (true, true, false)),
            (Mode::Ssdo, 0, true, off, (false, false, false)),
            (Mode::Ssdo, 8, true, off, (true, true, true)),
            (Mode::Ssdo, 8, false, march, (false, false, true)),
            (Mode::Ssdo, 0, false, irradiance, (false, false, false)),
            (Mode::Off, 8, true, march, (false, false, true)),
            (Mode::Ssao, 0, true, march, (false, false, false)),
        ];
        for (mode, lights, indirect, sender_sky, want) in rows {
            let o = PlanOptions { indirect, sender_sky, ..PlanOptions::default() };
            let plan = Plan::new(mode, SceneFeatures { lights }, o);
            let got = (plan.has(Step::Lighting), plan.target_set().bounce, plan.has(Step::LightCubes));
            assert_eq!(got, want, "{mode}, {lights} lights, indirect {indirect}, sender sky {sender_sky:?}");
            // Without a lighting pass that writes it, the composite runs the light loop itself.
            assert_eq!(plan.light_loop(), lights > 0 && !plan.has(Step::Lighting));
            assert_eq!(plan.lighting_writes_direct(), plan.has(Step::Lighting) && lights > 0);
            // The senders' own march runs exactly where a lighting pass reads it.
            let marched = plan.has(Step::Lighting) && sender_sky == march;
            assert_eq!((plan.has(Step::SenderSky), plan.target_set().sender_sky), (marched, marched));
        }
    }
}
