//! What tune searches: a [`Candidate`] is one setting of the knobs that trade error for time, each
//! on a ladder of values; its neighbours are the settings one rung away on one knob.

use crate::preset::Knobs;
use crate::render::variant::Sampler;
use crate::render::{Mode, SenderSky, Settings, Variant};
use crate::report::Config;

/// The rungs of each count: what a step up or down on that knob reaches.
pub const SAMPLES: [usize; 8] = [4, 8, 12, 16, 24, 32, 48, 64];
pub const SLICES: [usize; 6] = [1, 2, 3, 4, 6, 8];
pub const STEPS: [usize; 7] = [4, 6, 8, 12, 16, 24, 32];
/// Frames averaged: none, a few, the default. Every count above 1 costs the same a frame (one
/// temporal pass) and the error is taken after that many still frames, so a longer average always
/// looks better still; 16 is where the report stopped it (a moving view keeps 8 at most).
pub const ACCUMULATE: [usize; 3] = [1, 4, 16];
/// The radius in half-octave steps about the scene's default: 2^(step/2) times it.
pub const RADIUS_STEPS: std::ops::RangeInclusive<i8> = -2..=2;

/// One setting of the knobs, in a mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Candidate {
    pub mode: Mode,
    pub variant: Variant,
    /// Points and classic: samples per pixel.
    pub samples: usize,
    /// The march: slices and steps.
    pub slices: usize,
    pub steps: usize,
    pub pyramid: bool,
    pub radius_step: i8,
    pub blur: bool,
    pub half_resolution: bool,
    pub accumulate: usize,
    /// What lights the bounce's senders; `None`: no bounce (also every mode without DO).
    pub bounce: Option<SenderSky>,
}

impl Candidate {
    /// The defaults of `variant` in `mode`.
    pub fn default_of(mode: Mode, variant: Variant) -> Self {
        let s = Settings::for_variant(variant);
        Self {
            mode,
            variant,
            samples: s.sampling.samples,
            slices: s.sampling.slices,
            steps: s.sampling.steps,
            pyramid: false,
            radius_step: 0,
            blur: s.blur,
            half_resolution: s.half_resolution,
            accumulate: s.accumulate,
            bounce: mode.declaration().directional_occlusion.then_some(s.sender_sky),
        }
    }

    /// The cheapest corner of `variant`: the lowest counts, half resolution, no blur, no history,
    /// no bounce.
    pub fn cheapest_of(mode: Mode, variant: Variant) -> Self {
        Self {
            samples: SAMPLES[0],
            slices: SLICES[0],
            steps: STEPS[0],
            blur: false,
            half_resolution: true,
            accumulate: 1,
            bounce: None,
            ..Self::default_of(mode, variant)
        }
    }

    /// Where the search starts: each variant's defaults, and the cheapest corner of the two that
    /// are not the classic one (whose composite differs and is never close to the truth).
    pub fn starts(mode: Mode) -> Vec<Self> {
        let mut starts: Vec<Self> = [Variant::March, Variant::Points, Variant::Classic]
            .into_iter()
            .map(|v| Self::default_of(mode, v))
            .collect();
        starts.extend([Variant::March, Variant::Points].map(|v| Self::cheapest_of(mode, v)));
        starts
    }

    fn marches(&self) -> bool {
        self.variant.decl().sampler == Sampler::March
    }

    fn directional(&self) -> bool {
        self.mode.declaration().directional_occlusion
    }

    pub fn radius_scale(&self) -> f32 {
        2f32.powf(self.radius_step as f32 / 2.0)
    }

    /// The settings one rung away on one knob.
    pub fn neighbours(&self) -> Vec<Self> {
        let mut out = Vec::new();
        let mut ladder = |ladder: &[usize], value: usize, set: &dyn Fn(usize) -> Self| {
            // The rung at or below the value, and the ones either side of it.
            let at = ladder.iter().rposition(|&r| r <= value).unwrap_or(0);
            let below = if ladder[at] < value { Some(at) } else { at.checked_sub(1) };
            for i in below.into_iter().chain([at + 1]) {
                if let Some(&v) = ladder.get(i) {
                    out.push(set(v));
                }
            }
        };
        if self.marches() {
            ladder(&SLICES, self.slices, &|v| Self { slices: v, ..*self });
            ladder(&STEPS, self.steps, &|v| Self { steps: v, ..*self });
        } else {
            ladder(&SAMPLES, self.samples, &|v| Self { samples: v, ..*self });
        }
        ladder(&ACCUMULATE, self.accumulate, &|v| Self { accumulate: v, ..*self });
        out.push(Self { blur: !self.blur, ..*self });
        out.push(Self { half_resolution: !self.half_resolution, ..*self });
        for step in [self.radius_step - 1, self.radius_step + 1] {
            if RADIUS_STEPS.contains(&step) {
                out.push(Self { radius_step: step, ..*self });
            }
        }
        if self.directional() {
            if self.marches() {
                out.push(Self { pyramid: !self.pyramid, ..*self });
            }
            for bounce in SenderSky::ALL.map(Some).into_iter().chain([None]) {
                if bounce != self.bounce {
                    out.push(Self { bounce, ..*self });
                }
            }
        }
        out
    }

    /// Whether `other` (a neighbour: one knob apart) costs more a frame (`Some(true)`), less
    /// (`Some(false)`) or about the same (`None`: the radius, the pyramid, 4 against 16 frames).
    pub fn dearer(&self, other: &Candidate) -> Option<bool> {
        use std::cmp::Ordering;
        let bounce = |b: Option<SenderSky>| match b {
            None => 0,
            Some(SenderSky::Off) => 1,
            Some(SenderSky::Irradiance) => 2,
            Some(SenderSky::LastFrame) => 3,
            Some(SenderSky::MarchQuarter) => 4,
            Some(SenderSky::March) => 5,
        };
        let order = [
            self.samples.cmp(&other.samples),
            self.slices.cmp(&other.slices),
            self.steps.cmp(&other.steps),
            self.blur.cmp(&other.blur),
            // Full resolution costs more.
            other.half_resolution.cmp(&self.half_resolution),
            (self.accumulate > 1).cmp(&(other.accumulate > 1)),
            bounce(self.bounce).cmp(&bounce(other.bounce)),
        ];
        match order.into_iter().find(|o| *o != Ordering::Equal) {
            Some(Ordering::Less) => Some(true),
            Some(_) => Some(false),
            None => None,
        }
    }

    /// The report's configuration of this candidate (its radius is given apart, as
    /// [`Candidate::radius_scale`]): the one its knobs give, as for any preset.
    pub fn config(&self) -> Config {
        Config::of_knobs(self.mode, &self.knobs()).0
    }

    /// The preset's knobs of this candidate.
    pub fn knobs(&self) -> Knobs {
        let base = Knobs::from_settings(&Settings::for_variant(self.variant));
        Knobs {
            variant: self.variant,
            samples: if self.marches() { base.samples } else { self.samples },
            slices: if self.marches() { self.slices } else { base.slices },
            steps: if self.marches() { self.steps } else { base.steps },
            depth_pyramid: self.pyramid && self.marches(),
            radius_scale: self.radius_scale(),
            blur: self.blur,
            half_resolution: self.half_resolution,
            accumulate: self.accumulate,
            sender_sky: self.bounce.unwrap_or(base.sender_sky),
            indirect_strength: if self.bounce.is_none() && self.directional() { 0.0 } else { base.indirect_strength },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neighbours_are_one_rung_away_on_one_knob_and_stay_on_the_ladders() {
        let c = Candidate::default_of(Mode::Ssdo, Variant::March);
        let n = c.neighbours();
        let differs = |a: &Candidate, b: &Candidate| {
            [
                a.variant != b.variant,
                a.samples != b.samples,
                a.slices != b.slices,
                a.steps != b.steps,
                a.pyramid != b.pyramid,
                a.radius_step != b.radius_step,
                a.blur != b.blur,
                a.half_resolution != b.half_resolution,
                a.accumulate != b.accumulate,
                a.bounce != b.bounce,
            ]
            .iter()
            .filter(|&&d| d)
            .count()
        };
        assert!(n.iter().all(|m| differs(&c, m) == 1), "{n:?}");
        // Slices 1 and 3, steps 12 and 24, 4 frames, blur, resolution, 2 radii, pyramid, and
        // five other bounces.
        assert_eq!(n.len(), 2 + 2 + 1 + 1 + 1 + 2 + 1 + 5);
        assert!(n.iter().any(|m| m.slices == 1) && n.iter().any(|m| m.steps == 24));
        // A count off the ladder steps onto it; the ends of a ladder have one neighbour there.
        let odd = Candidate { slices: 5, steps: 4, accumulate: 16, radius_step: 2, ..c };
        let n = odd.neighbours();
        assert!(n.iter().any(|m| m.slices == 4) && n.iter().any(|m| m.slices == 6));
        assert!(n.iter().all(|m| m.steps >= 4 && m.accumulate <= 16 && m.radius_step <= 2));
        // SSAO has no bounce and no pyramid to turn.
        let ao = Candidate::default_of(Mode::Ssao, Variant::Points);
        assert!(ao.neighbours().iter().all(|m| m.bounce.is_none() && !m.pyramid));
    }

    #[test]
    fn a_candidate_is_the_same_setting_as_a_config_and_as_knobs() {
        let c = Candidate { radius_step: -2, bounce: None, ..Candidate::default_of(Mode::Ssdo, Variant::March) };
        let k = c.knobs();
        assert_eq!((k.radius_scale, k.indirect_strength), (0.5, 0.0));
        let from_config = c.config().settings(0.25);
        let from_knobs = k.settings(Settings { mode: Mode::Ssdo, ..Settings::default() });
        assert_eq!(from_config.sampling.resolved(0.5), from_knobs.sampling.resolved(0.5));
        assert_eq!(
            (from_config.blur, from_config.half_resolution, from_config.accumulate, from_config.indirect_strength),
            (from_knobs.blur, from_knobs.half_resolution, from_knobs.accumulate, from_knobs.indirect_strength)
        );
        let p = Candidate { samples: 32, ..Candidate::default_of(Mode::Ssao, Variant::Points) };
        assert_eq!((p.config().samples, p.knobs().samples, p.knobs().indirect_strength), (32, 32, 1.0));
    }
}
