//! Render modes, and what each allocates and runs: this file answers it. A mode *declares* what
//! it needs ([`ModeDecl`], the table in [`Mode::declaration`]); [`Plan::new`] turns that and the
//! scene's features into the steps the frame runs, and [`Plan::target_set`] into the screen
//! targets it allocates (`targets.rs` allocates exactly that set). Nothing a mode or a scene does
//! not need is in the plan, and so nothing for it is allocated or run. `--print-plan` prints both.
//!
//! | mode | steps (with lights, blur on, display plan) | targets besides the G-buffer |
//! |---|---|---|
//! | Off | gbuffer, composite, light_cubes | — |
//! | SSAO | gbuffer, ssao, blur, composite, light_cubes | `ao_raw`, `ao_blurred` |
//! | SSDO | gbuffer, sender_sky, lighting, ssdo, blur, composite, light_cubes | `hdr_color`, `bounce_radiance`, `sender_sky`, `do_raw`, `do_blurred` |
//! | SSAO+SSDO | gbuffer, sender_sky, lighting, ssao_ssdo, blur, composite, light_cubes | as SSDO (AO travels in the DO target's alpha) |
//!
//! Without lights there are no light cubes and the lighting pass writes the bounce alone (the
//! senders' sky and ambient light; no HDR target in a display plan); with `--sender-sky off` and
//! no lights, or with `--indirect-strength 0`, there is no lighting pass and no bounce target at
//! all (the composite then runs the light loop). An HDR plan (the report, `--raw`, `--stats`, a debug view) adds `hdr_color`, the skybox
//! and the tone map; `--no-blur` drops the blur and its targets; the march with `--depth-pyramid`
//! adds the pyramid in the DO modes.

use std::fmt;
use std::str::FromStr;

use super::history::HistorySpec;
use super::settings::SenderSky;
use crate::{Error, Result};

/// The four render modes of the SSDO course project, in key order (1-4). Everything about a mode
/// is its row of [`MODES`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    Off,
    Ssao,
    Ssdo,
    Both,
}

/// Everything a mode is, in one row: what selects it, what it is called where, and what it
/// computes. The viewer's keys, the command line, file names, captions, the plan's step names
/// and the messages all read this table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModeDecl {
    pub mode: Mode,
    /// The viewer's key (and the caption's `[key]`).
    pub key: u32,
    /// On the command line and in file names.
    pub name: &'static str,
    /// For people: labels, captions, the window.
    pub title: &'static str,
    /// The sampling step's name in this mode's plan (`--print-plan`, timings).
    pub sampling_step: &'static str,
    /// Ambient occlusion: darkens the ambient term.
    pub ambient_occlusion: bool,
    /// Directional occlusion: sky light from the open directions and one indirect bounce.
    pub directional_occlusion: bool,
}

/// The modes, in key order.
pub const MODES: [ModeDecl; 4] = [
    // Off: the sky's irradiance, the ambient term and the point lights, unoccluded.
    ModeDecl {
        mode: Mode::Off,
        key: 1,
        name: "off",
        title: "Off",
        sampling_step: "occlusion",
        ambient_occlusion: false,
        directional_occlusion: false,
    },
    // SSAO: the sky and ambient terms darkened by screen-space ambient occlusion (the classic
    // hemisphere-kernel technique, or the march's near steps).
    ModeDecl {
        mode: Mode::Ssao,
        key: 2,
        name: "ssao",
        title: "SSAO",
        sampling_step: "ssao",
        ambient_occlusion: true,
        directional_occlusion: false,
    },
    // SSDO: directional occlusion (Ritschel, Grosch & Seidel 2009) — the sky from the open
    // directions plus one bounce from nearby surfaces — instead of the unoccluded sky.
    ModeDecl {
        mode: Mode::Ssdo,
        key: 3,
        name: "ssdo",
        title: "SSDO",
        sampling_step: "ssdo",
        ambient_occlusion: false,
        directional_occlusion: true,
    },
    // SSAO+SSDO: SSDO with AO on the constant ambient term, both from one set of samples.
    ModeDecl {
        mode: Mode::Both,
        key: 4,
        name: "both",
        title: "SSAO+SSDO",
        sampling_step: "ssao_ssdo",
        ambient_occlusion: true,
        directional_occlusion: true,
    },
];

impl Mode {
    pub const ALL: [Mode; 4] = [MODES[0].mode, MODES[1].mode, MODES[2].mode, MODES[3].mode];

    /// This mode's row of [`MODES`].
    pub fn declaration(self) -> &'static ModeDecl {
        MODES.iter().find(|d| d.mode == self).expect("every mode has a row")
    }

    /// Name used on the command line and in file names.
    pub fn name(self) -> &'static str {
        self.declaration().name
    }

    /// Name shown to people (labels, window title).
    pub fn title(self) -> &'static str {
        self.declaration().title
    }

    /// The viewer's key for this mode.
    pub fn key(self) -> u32 {
        self.declaration().key
    }

    /// The mode of a viewer key.
    pub fn from_key(key: u32) -> Option<Mode> {
        MODES.iter().find(|d| d.key == key).map(|d| d.mode)
    }

    /// The modes that run the sampling pass (every one but Off).
    pub fn sampled() -> impl Iterator<Item = Mode> {
        MODES.iter().filter(|d| d.runs_sampling()).map(|d| d.mode)
    }
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Mode {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        MODES.iter().find(|d| d.name.eq_ignore_ascii_case(s)).map(|d| d.mode).ok_or_else(|| {
            let names: Vec<&str> = MODES.iter().map(|d| d.name).collect();
            Error::Setting(format!("unknown mode '{s}' (expected {})", names.join(", ")))
        })
    }
}

impl ModeDecl {
    /// Whether the mode runs the sampling pass at all.
    pub fn runs_sampling(&self) -> bool {
        self.ambient_occlusion || self.directional_occlusion
    }
}

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
}

impl Default for PlanOptions {
    /// A display plan with blur, no pyramid, and the bounce lit by the sky and the lights.
    fn default() -> Self {
        Self { blur: true, pyramid: false, display: true, indirect: true, sender_sky: SenderSky::default() }
    }
}

/// Which screen targets a plan allocates besides the G-buffer (see `targets.rs` for formats).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TargetSet {
    /// Linear HDR radiance (`hdr_color`).
    pub hdr: bool,
    /// The diffuse radiance SSDO bounces (`bounce_radiance`): the senders' direct light.
    pub bounce: bool,
    /// AO alone (`ao_raw`): SSAO.
    pub ao: bool,
    /// DO + AO (`do_raw`): SSDO and SSAO+SSDO.
    pub directional: bool,
    /// A blurred copy of whichever of the two the plan has.
    pub blurred: bool,
    /// The closest-depth pyramid of the march's far steps.
    pub pyramid: bool,
    /// The sky each sender sees, at half resolution (`sender_sky`).
    pub sender_sky: bool,
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
    /// Depth- and normal-aware (or classic box) blur of the sampling pass's output.
    Blur,
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
            Step::Blur => "blur",
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
    /// The targets kept across frames (see `history.rs`); no step accumulates yet, so none.
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
            if o.blur {
                steps.push(Step::Blur);
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
        Self { mode, decl, features, blur, display: o.display, sender_sky, steps, history: Vec::new() }
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

    /// The screen targets this plan allocates besides the G-buffer (albedo, normal, depth).
    pub fn target_set(&self) -> TargetSet {
        let samples = self.decl.runs_sampling();
        TargetSet {
            hdr: self.keeps_hdr(),
            bounce: self.has(Step::Lighting),
            ao: samples && !self.decl.directional_occlusion,
            directional: self.decl.directional_occlusion,
            blurred: self.blur,
            pyramid: self.has(Step::DepthPyramid),
            sender_sky: self.has(Step::SenderSky),
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

#[cfg(test)]
mod tests {
    use super::*;

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
            (Mode::Ssao, "gbuffer, ssao, blur, composite, light_cubes", (false, false, true, false)),
            (
                Mode::Ssdo,
                "gbuffer, sender_sky, lighting, ssdo, blur, composite, light_cubes",
                (true, true, false, true),
            ),
            (
                Mode::Both,
                "gbuffer, sender_sky, lighting, ssao_ssdo, blur, composite, light_cubes",
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
