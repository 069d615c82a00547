//! What `ssdo tune` is asked: the scene, the budget or the target error, the views and the
//! search's limits, checked.

use std::path::PathBuf;

use crate::render::Mode;
use crate::report::{RadiusChoice, ReportOptions, TruthScene};
use crate::{Error, Result};

/// The most views and the most measured settings a run takes.
pub const MAX_VIEWS: usize = 8;
pub const MAX_SETTINGS: usize = 400;

/// The budget: milliseconds, or a multiple of the Off frame's time measured in the same run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Budget {
    Ms(f64),
    OffTimes(f64),
}

/// What to tune, on what.
#[derive(Clone, Debug)]
pub struct TuneOptions {
    /// The scene, its sky, size and lights, and the truth's seed.
    pub on: TruthScene,
    /// The mode whose settings are searched (not Off).
    pub mode: Mode,
    /// The cheapest-first goal: the most accurate setting within this frame time.
    pub budget: Option<Budget>,
    /// The cheapest setting whose HDR RMSE is at most this (within the budget, if one is given).
    pub target_error: Option<f64>,
    /// Views of the scene: the report's view, and `views - 1` others turned about the model by
    /// up to `spread` degrees either side.
    pub views: usize,
    /// Degrees.
    pub spread: f32,
    /// Frames timed per setting (on the report's view; a frame costs the same from the others).
    pub frames: usize,
    /// Reference rays per pixel in each of the two traces of each view.
    pub samples_per_pixel: u32,
    /// The most settings the search measures (0: no search, only `also` and Off).
    pub max_settings: usize,
    /// Presets measured beside the search's settings (`--also`): their figures on this scene and
    /// device, and picked if they are the best.
    pub also: Vec<crate::preset::Preset>,
    /// Folder for front.csv, tune.md and (with a pick) preset.json.
    pub out: PathBuf,
}

impl TuneOptions {
    /// A goal given, every number within its range; the first that is not, as the setting error.
    pub fn check(&self) -> Result<()> {
        if self.budget.is_none() && self.target_error.is_none() && self.max_settings > 0 {
            return Err(Error::Setting(
                "give --budget-ms, --budget-off or --target-error (or --max-settings 0 to measure --also presets only)"
                    .into(),
            ));
        }
        let positive = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(Error::Setting(format!("--{name} {v}: must be a positive number")))
            }
        };
        match self.budget {
            Some(Budget::Ms(ms)) => positive("budget-ms", ms)?,
            Some(Budget::OffTimes(k)) => positive("budget-off", k)?,
            None => {}
        }
        if let Some(e) = self.target_error {
            positive("target-error", e)?;
        }
        if self.mode == Mode::Off {
            return Err(Error::Setting("--mode off: Off samples nothing, so it has no setting to tune".into()));
        }
        if !(1..=MAX_VIEWS).contains(&self.views) {
            return Err(Error::Setting(format!("--views {}: must be from 1 to {MAX_VIEWS}", self.views)));
        }
        crate::spec::in_range("spread", self.spread, 0.0, 90.0)?;
        if self.max_settings > MAX_SETTINGS {
            return Err(Error::Setting(format!(
                "--max-settings {}: must be from 0 to {MAX_SETTINGS}",
                self.max_settings
            )));
        }
        if self.max_settings == 0 && self.also.is_empty() {
            return Err(Error::Setting("--max-settings 0: give --also presets to measure".into()));
        }
        if self.samples_per_pixel < 2 {
            return Err(Error::Setting(format!(
                "--spp {}: the reference needs at least 2 rays per pixel for an error estimate",
                self.samples_per_pixel
            )));
        }
        Ok(())
    }

    /// The report's options for the same scene (what its loaders and measurements read).
    pub(super) fn report_options(&self) -> ReportOptions {
        ReportOptions {
            on: self.on.clone(),
            samples: vec![16],
            march: vec![(2, 16)],
            radii: vec![RadiusChoice::Times(1.0)],
            samples_per_pixel: self.samples_per_pixel,
            frames: self.frames,
            accumulate: vec![1],
            orbit: 0.0,
            out: self.out.clone(),
            preset: None,
        }
    }

    /// The views' yaw offsets from the report's view: 0 first, then ± the spread, evenly between.
    pub fn yaw_offsets(&self) -> Vec<f32> {
        let mut offsets = vec![0.0];
        let pairs = (self.views - 1).div_ceil(2);
        for k in 1..=pairs {
            let angle = self.spread * k as f32 / pairs as f32;
            offsets.push(-angle);
            if offsets.len() < self.views {
                offsets.push(angle);
            }
        }
        offsets
    }

    /// The work planned, in a line.
    pub fn planned(&self) -> String {
        format!(
            "planned: {} views at {}x{} (a truth of 2 × {} rays a pixel each), up to {} settings × {} timed frames a view",
            self.views, self.on.size.0, self.on.size.1, self.samples_per_pixel, self.max_settings, self.frames
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn views_start_at_the_reports_and_spread_evenly_both_ways() {
        let mut o = TuneOptions {
            on: TruthScene::named("cornell", (16, 12)),
            mode: Mode::Ssdo,
            budget: Some(Budget::Ms(10.0)),
            target_error: None,
            views: 1,
            spread: 20.0,
            frames: 1,
            samples_per_pixel: 2,
            max_settings: 10,
            also: Vec::new(),
            out: "tune".into(),
        };
        assert_eq!(o.yaw_offsets(), [0.0]);
        o.views = 3;
        assert_eq!(o.yaw_offsets(), [0.0, -20.0, 20.0]);
        o.views = 4;
        assert_eq!(o.yaw_offsets(), [0.0, -10.0, 10.0, -20.0]);
        assert!(o.check().is_ok());
        o.budget = None;
        assert!(o.check().unwrap_err().to_string().contains("--budget-ms"));
        o.budget = Some(Budget::OffTimes(-1.0));
        assert!(o.check().unwrap_err().to_string().contains("--budget-off -1"));
        o.budget = Some(Budget::Ms(1.0));
        o.mode = Mode::Off;
        assert!(o.check().unwrap_err().to_string().contains("--mode off"));
    }
}
