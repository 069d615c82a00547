//! What tune searches: a [`Candidate`] is one setting of the knobs in a mode, in its canonical
//! form; its neighbours are the settings one rung away on one knob (the rungs and which way each
//! knob moves the cost are the knobs' declarations, `crate::knobs::KNOBS`).

use crate::knobs::Knobs;
use crate::render::{Mode, Variant};
use crate::report::Config;

/// One setting of the knobs, in a mode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate {
    pub mode: Mode,
    pub knobs: Knobs,
}

// Canonical knobs compare equal exactly when their floats' bits do: none is NaN.
impl Eq for Candidate {}

impl std::hash::Hash for Candidate {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.mode.hash(state);
        self.knobs.key().hash(state);
    }
}

impl Candidate {
    /// `knobs` in `mode`, in their canonical form.
    pub fn new(mode: Mode, knobs: Knobs) -> Self {
        Self { mode, knobs: knobs.canonical(mode) }
    }

    /// The defaults of `variant` in `mode`.
    pub fn default_of(mode: Mode, variant: Variant) -> Self {
        Self::new(mode, Knobs::for_variant(variant))
    }

    /// The cheapest corner of `variant` ([`Knobs::cheapest`]).
    pub fn cheapest_of(mode: Mode, variant: Variant) -> Self {
        Self::new(mode, Knobs::cheapest(variant))
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

    /// The settings one rung away on one knob.
    pub fn neighbours(&self) -> Vec<Self> {
        self.knobs.neighbours(self.mode).into_iter().map(|knobs| Self { mode: self.mode, knobs }).collect()
    }

    /// Whether `other` (a neighbour: one knob apart) costs more a frame (`Some(true)`), less
    /// (`Some(false)`) or about the same (`None`).
    pub fn dearer(&self, other: &Candidate) -> Option<bool> {
        self.knobs.dearer(&other.knobs)
    }

    /// The report's configuration of this candidate, and its radius scale.
    pub fn config(&self) -> (Config, f32) {
        Config::of_knobs(self.mode, &self.knobs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::Settings;

    #[test]
    fn a_candidate_is_the_same_setting_as_a_config_and_as_knobs() {
        let c = Candidate::new(
            Mode::Ssdo,
            Knobs { radius_scale: 0.5, indirect_strength: 0.0, ..Knobs::for_variant(Variant::March) },
        );
        let (config, scale) = c.config();
        assert_eq!((scale, c.knobs.indirect_strength), (0.5, 0.0));
        let from_config = config.settings(0.25);
        let from_knobs = Settings { mode: Mode::Ssdo, ..Settings::default() }.with_knobs(c.knobs);
        // The same settings, every knob and length, once the lengths are resolved.
        assert_eq!(from_config.resolved(0.5), from_knobs.resolved(0.5));
        let p = Candidate::new(Mode::Ssao, Knobs { samples: 32, ..Knobs::for_variant(Variant::Points) });
        assert_eq!((p.config().0.samples(), p.knobs.samples, p.knobs.indirect_strength), (32, 32, 1.0));
        // The starts are five distinct settings, and the cheapest has no bounce in SSDO only.
        let starts = Candidate::starts(Mode::Ssdo);
        assert_eq!(starts.iter().collect::<std::collections::HashSet<_>>().len(), 5);
        assert_eq!(Candidate::cheapest_of(Mode::Ssdo, Variant::March).knobs.indirect_strength, 0.0);
        assert_eq!(Candidate::cheapest_of(Mode::Ssao, Variant::March).knobs.indirect_strength, 1.0);
    }

    #[test]
    fn no_neighbour_of_the_cheapest_corner_costs_less() {
        for mode in Mode::sampled() {
            for variant in [Variant::March, Variant::Points] {
                let c = Candidate::cheapest_of(mode, variant);
                assert_eq!(c.knobs.accumulate, 1);
                assert!(!c.knobs.blur);
                for n in c.neighbours() {
                    assert_ne!(c.knobs.dearer(&n.knobs), Some(false), "{mode} {variant}: {:?} is cheaper", n.knobs);
                }
            }
        }
    }
}
