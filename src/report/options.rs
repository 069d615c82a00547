//! What a report sweeps: the flags' values, each checked against its range.

use std::path::PathBuf;

use crate::{Error, Result};

/// A sampling radius to sweep: a multiple of the scene's default, or a length in model units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RadiusChoice {
    Times(f32),
    Units(f32),
}

impl std::str::FromStr for RadiusChoice {
    type Err = Error;
    /// `2x` (twice the default radius) or `0.3` (model units).
    fn from_str(s: &str) -> Result<Self> {
        let bad = || Error::Setting(format!("--radius {s}: expected a length or a multiple of the default like 2x"));
        let (text, times) = match s.trim().strip_suffix(['x', 'X']) {
            Some(t) => (t, true),
            None => (s.trim(), false),
        };
        let value: f32 = text.parse().map_err(|_| bad())?;
        if !value.is_finite() || value <= 0.0 {
            return Err(bad());
        }
        Ok(if times { Self::Times(value) } else { Self::Units(value) })
    }
}

impl RadiusChoice {
    pub fn resolve(self, default: f32) -> f32 {
        match self {
            Self::Times(k) => k * default,
            Self::Units(r) => r,
        }
    }
}

/// The scene a report or tune measures against its truth: a named scene or a model, its sky,
/// the image size, the point lights and the seed of the lights and the truth's rays.
#[derive(Clone, Debug, PartialEq)]
pub struct TruthScene {
    /// A named scene (`report::scenes`), used where no model is given.
    pub scene: String,
    /// Overrides the scene's model with an OBJ or glTF file.
    pub model: Option<PathBuf>,
    /// Leave out the model's normal maps and alpha cutouts, on both sides.
    pub no_surface_maps: bool,
    /// `None`: the scene's own sky.
    pub skybox: Option<PathBuf>,
    pub size: (u32, u32),
    pub lights: usize,
    pub seed: u64,
}

impl TruthScene {
    /// A named scene at `size` under its own sky, with the command line's lights and seed.
    pub fn named(scene: &str, size: (u32, u32)) -> Self {
        Self {
            scene: scene.into(),
            model: None,
            no_surface_maps: false,
            skybox: None,
            size,
            lights: crate::scene::DEFAULT_LIGHTS,
            seed: 1,
        }
    }

    /// The model's file, or the named scene.
    pub fn model_name(&self) -> String {
        self.model.as_ref().map_or_else(|| self.scene.clone(), |p| p.display().to_string())
    }

    /// The scene in words: the model's name, and the sky where one is given.
    pub fn name(&self) -> String {
        match &self.skybox {
            Some(sky) => format!("{} under {}", self.model_name(), sky.display()),
            None => self.model_name(),
        }
    }
}

/// What to sweep.
pub struct ReportOptions {
    pub on: TruthScene,
    /// Sample counts of the points and classic variants.
    pub samples: Vec<usize>,
    /// Slices × steps of the march variant.
    pub march: Vec<(usize, usize)>,
    pub radii: Vec<RadiusChoice>,
    /// Reference rays per pixel in each of the two traces (at least 2).
    pub samples_per_pixel: u32,
    pub frames: usize,
    /// Frames averaged, each count a row (1: a single frame).
    pub accumulate: Vec<usize>,
    /// Degrees the camera turns about the model each accumulated frame (0: still rows only).
    pub orbit: f32,
    pub out: PathBuf,
    /// A preset (`--preset`, `--quality`) measured as one more row, marked in the table.
    pub preset: Option<crate::preset::Preset>,
}

/// The most values one list of a sweep takes (`--samples`, `--march`, `--radius`, `--accumulate`).
pub const MAX_SWEEP: usize = 16;

impl ReportOptions {
    /// Every value of the sweep within its range, every list given and within [`MAX_SWEEP`]; the
    /// first that is not, as the setting error naming its flag.
    pub fn check(&self) -> Result<()> {
        use crate::render::{ACCUMULATE, SAMPLES, SLICES, STEPS};
        for &n in &self.samples {
            SAMPLES.check(n)?;
        }
        for &n in &self.accumulate {
            ACCUMULATE.check(n)?;
        }
        crate::spec::in_range("orbit", self.orbit, -90.0, 90.0)?;
        for &(slices, steps) in &self.march {
            SLICES.check(slices)?;
            STEPS.check(steps)?;
        }
        let lists = [
            ("samples", self.samples.len()),
            ("march", self.march.len()),
            ("radius", self.radii.len()),
            ("accumulate", self.accumulate.len()),
        ];
        if lists.iter().any(|&(_, count)| count == 0) {
            return Err(Error::Setting(
                "--samples, --march, --radius and --accumulate must each give at least one".into(),
            ));
        }
        match lists.iter().find(|&&(_, count)| count > MAX_SWEEP) {
            Some((name, count)) => {
                Err(Error::Setting(format!("--{name}: {count} values; a sweep takes at most {MAX_SWEEP}")))
            }
            None => Ok(()),
        }
    }
}
