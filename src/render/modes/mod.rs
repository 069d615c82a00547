//! Render modes. Each mode is a small module that *declares* what it needs; [`Plan::new`] turns
//! that declaration and the scene's features into the list of steps the frame runs. Nothing a
//! mode or scene does not need is in the plan, and so nothing for it is allocated or run.

mod off;

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

    /// What this mode needs; `None` for a mode this build does not implement yet.
    pub fn declaration(self) -> Option<&'static ModeDecl> {
        match self {
            Mode::Off => Some(&off::DECL),
            Mode::Ssao | Mode::Ssdo | Mode::Both => None,
        }
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
    /// Ambient, occlusion and point lighting into the HDR target.
    Composite,
    /// Sky where nothing was drawn.
    Skybox,
    /// The point lights as emissive cubes.
    LightCubes,
    /// HDR to the display format.
    Tonemap,
}

impl Step {
    pub fn name(self) -> &'static str {
        match self {
            Step::GBuffer => "gbuffer",
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
    pub features: SceneFeatures,
    pub steps: Vec<Step>,
}

impl Plan {
    pub fn new(mode: Mode, features: SceneFeatures) -> Result<Self> {
        let decl = mode.declaration().ok_or_else(|| {
            Error::Setting(format!("mode '{mode}' is not implemented in this build (available: off)"))
        })?;
        let mut steps = vec![Step::GBuffer, Step::Composite, Step::Skybox];
        if features.lights > 0 {
            steps.push(Step::LightCubes);
        }
        steps.push(Step::Tonemap);
        Ok(Self { mode: decl.mode, features, steps })
    }

    pub fn has(&self, step: Step) -> bool {
        self.steps.contains(&step)
    }

    /// Whether the composite runs the point-light loop itself.
    pub fn light_loop(&self) -> bool {
        self.features.lights > 0
    }
}
