//! Render modes. Each mode is a small module that *declares* what it needs; [`Plan::new`] turns
//! that declaration and the scene's features into the list of steps the frame runs. Nothing a
//! mode or scene does not need is in the plan, and so nothing for it is allocated or run.

mod both;
mod off;
mod ssao;
mod ssdo;

use std::fmt;
use std::str::FromStr;

use crate::{Error, Result};

/// The four render modes of the source project, in key order (1-4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    Off,
    Ssao,
    Ssdo,
    Both,
}

impl Mode {
    pub const ALL: [Mode; 4] = [Mode::Off, Mode::Ssao, Mode::Ssdo, Mode::Both];

    /// Name used on the command line and in file names.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Off => "off",
            Mode::Ssao => "ssao",
            Mode::Ssdo => "ssdo",
            Mode::Both => "both",
        }
    }

    /// Name shown to people (labels, window title).
    pub fn title(self) -> &'static str {
        match self {
            Mode::Off => "Off",
            Mode::Ssao => "SSAO",
            Mode::Ssdo => "SSDO",
            Mode::Both => "SSAO+SSDO",
        }
    }

    /// What this mode needs.
    pub fn declaration(self) -> &'static ModeDecl {
        match self {
            Mode::Off => &off::DECL,
            Mode::Ssao => &ssao::DECL,
            Mode::Ssdo => &ssdo::DECL,
            Mode::Both => &both::DECL,
        }
    }

    /// The mode for keys 1-4.
    pub fn from_key(key: u32) -> Option<Mode> {
        Mode::ALL.get(key.checked_sub(1)? as usize).copied()
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
        Mode::ALL
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| Error::Setting(format!("unknown mode '{s}' (expected off, ssao, ssdo or both)")))
    }
}

/// What a mode asks of the frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModeDecl {
    pub mode: Mode,
    /// Ambient occlusion: darkens the ambient term.
    pub ambient_occlusion: bool,
    /// Directional occlusion: sky light from the open directions and one indirect bounce.
    pub directional_occlusion: bool,
}

impl ModeDecl {
    /// Whether the mode runs the sampling pass at all.
    pub fn samples(&self) -> bool {
        self.ambient_occlusion || self.directional_occlusion
    }
}

/// What the scene brings that changes the plan.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SceneFeatures {
    pub lights: usize,
}

/// One step of a frame, in the order the frame runs them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Step {
    /// Rasterise the model into albedo, normal and depth.
    GBuffer,
    /// The closest-depth pyramid the march's far steps read (march variant, DO modes).
    DepthPyramid,
    /// Point lights once per pixel: the displayed direct light and the radiance SSDO bounces.
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
        match (self, mode) {
            (Step::Occlusion, Mode::Ssao) => "ssao",
            (Step::Occlusion, Mode::Ssdo) => "ssdo",
            (Step::Occlusion, _) => "ssao_ssdo",
            _ => self.name(),
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Step::GBuffer => "gbuffer",
            Step::DepthPyramid => "depth_pyramid",
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
    pub steps: Vec<Step>,
}

impl Plan {
    /// The steps of `mode` for a scene with `features`; `blur` denoises the sampling output.
    /// `pyramid`: the sampling pass marches the depth buffer and its far steps, taken only where
    /// DO is computed, read a depth pyramid (the march variant with `depth_pyramid` on).
    /// `display`: see [`Plan::display`].
    pub fn new(mode: Mode, features: SceneFeatures, blur: bool, pyramid: bool, display: bool) -> Self {
        let decl = *mode.declaration();
        let lights = features.lights > 0;
        let mut steps = vec![Step::GBuffer];
        if pyramid && decl.directional_occlusion {
            steps.push(Step::DepthPyramid);
        }
        if decl.directional_occlusion && lights {
            steps.push(Step::Lighting);
        }
        if decl.samples() {
            steps.push(Step::Occlusion);
            if blur {
                steps.push(Step::Blur);
            }
        }
        steps.push(Step::Composite);
        if !display {
            steps.push(Step::Skybox);
        }
        if lights {
            steps.push(Step::LightCubes);
        }
        if !display {
            steps.push(Step::Tonemap);
        }
        Self { mode, decl, features, blur: blur && decl.samples(), display, steps }
    }

    /// The names of the steps, in order.
    pub fn step_names(&self) -> Vec<&'static str> {
        self.steps.iter().map(|s| s.name_in(self.mode)).collect()
    }

    /// Whether SSDO's indirect bounce has a radiance buffer to read (a lighting pass ran).
    pub fn indirect(&self) -> bool {
        self.has(Step::Lighting)
    }

    /// Whether the HDR target exists: an HDR plan, or a lighting pass writing its direct light.
    pub fn keeps_hdr(&self) -> bool {
        !self.display || self.has(Step::Lighting)
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
    fn a_display_plan_has_no_skybox_or_tonemap_pass_and_keeps_hdr_only_for_the_lighting_pass() {
        let lit = SceneFeatures { lights: 8 };
        for mode in Mode::ALL {
            let hdr = Plan::new(mode, lit, true, false, false);
            let display = Plan::new(mode, lit, true, false, true);
            assert!(hdr.has(Step::Skybox) && hdr.has(Step::Tonemap) && hdr.keeps_hdr());
            assert!(!display.has(Step::Skybox) && !display.has(Step::Tonemap));
            assert_eq!(display.keeps_hdr(), display.has(Step::Lighting), "{mode}");
            let without = |p: &Plan| p.steps.iter().filter(|s| !matches!(s, Step::Skybox | Step::Tonemap)).count();
            assert_eq!(without(&hdr), display.steps.len(), "{mode}: the same passes otherwise");
        }
        let dark = Plan::new(Mode::Ssdo, SceneFeatures { lights: 0 }, true, false, true);
        assert!(!dark.keeps_hdr(), "no lights, no lighting pass, no HDR target");
    }
}
