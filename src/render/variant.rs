//! The sampling variants, one row each in [`VARIANTS`]: what the sampling pass runs, which kernel,
//! estimator, blur and composite go with it, which counts it takes, and its defaults. With each
//! count's range, default and label ([`SAMPLES`], [`SLICES`], [`STEPS`]) this is the one place a
//! variant is defined: the flags, the panel, the report's sweep, the captions, the passes' keys
//! and the uniforms read it. Adding a variant is a `Variant` and its row here (and, for a new
//! sampler or estimator, its shader).

use crate::error::named_choice;
use crate::{Error, Result};

/// Which algorithm family the occlusion, blur and composite passes follow.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Variant {
    /// The depth buffer marched per direction (slices × steps) for AO, sky and bounce, out to a
    /// reach beyond the AO radius (`shaders/common/march.wgsl`); bilateral blur. The default: the
    /// report's lowest error at the default time budget.
    #[default]
    March,
    /// The paper's point sampling (Ritschel et al. 2009) with normalised estimators, a stratified
    /// kernel and bilateral blur: each direction tested at one point within the radius.
    Points,
    /// The classic SSAO chapter's SSAO (LearnOpenGL) and the SSDO course project's SSDO,
    /// reproduced as written.
    Classic,
}

/// Which count a [`Count`] is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CountId {
    Samples,
    Slices,
    Steps,
    Accumulate,
}

/// A whole-number sampling setting: its flag, its label, its range and its default.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Count {
    pub id: CountId,
    pub flag: &'static str,
    pub label: &'static str,
    pub min: usize,
    pub max: usize,
    pub default: usize,
}

/// Point samples per pixel (points and classic; the kernel's size limits it).
pub const SAMPLES: Count =
    Count { id: CountId::Samples, flag: "samples", label: "samples", min: 1, max: 256, default: 16 };
/// The march's directions around the view vector per pixel.
pub const SLICES: Count = Count { id: CountId::Slices, flag: "slices", label: "slices", min: 1, max: 32, default: 2 };
/// The march's samples along each side of a slice (half within the radius).
pub const STEPS: Count = Count { id: CountId::Steps, flag: "steps", label: "steps", min: 1, max: 64, default: 16 };
/// Frames the temporal pass averages at most while the camera is still (1: no accumulation, no
/// history); every variant takes it.
pub const ACCUMULATE: Count =
    Count { id: CountId::Accumulate, flag: "accumulate", label: "frames", min: 1, max: 64, default: 16 };

impl Count {
    pub fn range(&self) -> std::ops::RangeInclusive<usize> {
        self.min..=self.max
    }

    pub fn clamp(&self, n: usize) -> usize {
        n.clamp(self.min, self.max)
    }

    /// `n` if it is in range; otherwise an error naming the flag and the range.
    pub fn check(&self, n: usize) -> Result<usize> {
        self.range().contains(&n).then_some(n).ok_or_else(|| {
            Error::Setting(format!("--{} {n}: must be a whole number between {} and {}", self.flag, self.min, self.max))
        })
    }
}

/// What the sampling pass runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sampler {
    /// Slices × steps through the depth buffer (`march.wgsl`).
    March,
    /// A kernel of points in the hemisphere (`points.wgsl`).
    Points,
}

/// The points' kernel and the per-pixel rotations (`kernel.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kernel {
    /// Directions even in solid angle, distances over [0.1 R, R], rotations in Bayer order.
    Stratified,
    /// The chapter's random kernel scaled towards the centre and random rotation vectors.
    Classic,
}

/// How the point samples become AO and DO.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Estimator {
    /// Normalised, cosine-weighted estimators with a smooth range check.
    Normalised,
    /// The chapter's `smoothstep` range check and the course project's sums over N.
    Classic,
}

/// The denoise of the sampling output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Blur {
    /// Depth- and normal-aware 4x4.
    Bilateral,
    /// The chapter's 4x4 box.
    Box,
}

/// The composite's sky and ambient terms.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Composite {
    /// The sky's irradiance and the ambient, occluded by the mode's AO or DO.
    SkyLit,
    /// The course project's `albedo·A·AO + DO`, with no sky irradiance in Off and SSAO.
    ClassicAmbient,
}

impl Composite {
    /// What lights an unoccluded surface, for captions.
    pub fn label(self) -> &'static str {
        match self {
            Composite::SkyLit => "sky + ambient",
            Composite::ClassicAmbient => "ambient",
        }
    }
}

/// Everything a variant is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VariantDecl {
    pub variant: Variant,
    pub name: &'static str,
    pub sampler: Sampler,
    pub kernel: Kernel,
    pub estimator: Estimator,
    pub blur: Blur,
    pub composite: Composite,
    /// The counts the sampling pass takes, in the order captions give them.
    pub counts: &'static [Count],
    /// It looks out to a reach, through surfaces of a thickness, and its far steps may read the
    /// depth pyramid.
    pub marched_lengths: bool,
    /// Its defaults for the settings that differ by variant.
    pub default_samples: usize,
    pub default_ambient: f32,
    /// The report's plot: line width and opacity.
    pub plot_width: u32,
    pub plot_opacity: f64,
}

/// The variants, the default first.
pub const VARIANTS: [VariantDecl; 3] = [
    VariantDecl {
        variant: Variant::March,
        name: "march",
        sampler: Sampler::March,
        kernel: Kernel::Stratified,
        estimator: Estimator::Normalised,
        blur: Blur::Bilateral,
        composite: Composite::SkyLit,
        counts: &[SLICES, STEPS],
        marched_lengths: true,
        default_samples: SAMPLES.default,
        default_ambient: 0.1,
        plot_width: 3,
        plot_opacity: 1.0,
    },
    VariantDecl {
        variant: Variant::Points,
        name: "points",
        sampler: Sampler::Points,
        kernel: Kernel::Stratified,
        estimator: Estimator::Normalised,
        blur: Blur::Bilateral,
        composite: Composite::SkyLit,
        counts: &[SAMPLES],
        marched_lengths: false,
        default_samples: SAMPLES.default,
        default_ambient: 0.1,
        plot_width: 2,
        plot_opacity: 0.8,
    },
    VariantDecl {
        variant: Variant::Classic,
        name: "classic",
        sampler: Sampler::Points,
        kernel: Kernel::Classic,
        estimator: Estimator::Classic,
        blur: Blur::Box,
        composite: Composite::ClassicAmbient,
        counts: &[SAMPLES],
        marched_lengths: false,
        // The chapter's 64-sample kernel and the course report's `albedo·0.5·AO` ambient.
        default_samples: 64,
        default_ambient: 0.5,
        plot_width: 1,
        plot_opacity: 0.5,
    },
];

impl Variant {
    pub const ALL: [Variant; 3] = [VARIANTS[0].variant, VARIANTS[1].variant, VARIANTS[2].variant];

    /// This variant's row of [`VARIANTS`].
    pub fn decl(self) -> &'static VariantDecl {
        VARIANTS.iter().find(|d| d.variant == self).expect("every variant has a row")
    }

    pub fn name(self) -> &'static str {
        self.decl().name
    }
}

impl VariantDecl {
    /// Each count this variant takes with its value, from the three settings.
    pub fn count_values(&self, samples: usize, slices: usize, steps: usize) -> Vec<(Count, usize)> {
        let value = |c: &Count| match c.id {
            CountId::Samples => samples,
            CountId::Slices => slices,
            CountId::Steps => steps,
            // Not a variant's count: no variant lists it.
            CountId::Accumulate => 1,
        };
        self.counts.iter().map(|c| (*c, value(c))).collect()
    }

    /// "2 slices × 12 steps" or "16 samples".
    pub fn count_label(&self, samples: usize, slices: usize, steps: usize) -> String {
        let values = self.count_values(samples, slices, steps);
        values.iter().map(|(c, v)| format!("{v} {}", c.label)).collect::<Vec<_>>().join(" × ")
    }

    /// "2×12" or "16": the same, short, for tables.
    pub fn count_short(&self, samples: usize, slices: usize, steps: usize) -> String {
        let values = self.count_values(samples, slices, steps);
        values.iter().map(|(_, v)| v.to_string()).collect::<Vec<_>>().join("×")
    }

    /// How many directions share the sky's radiance, which sets the mip level it is read at:
    /// the march reads it once per group of sectors (4 a slice), the points once a sample.
    pub fn sky_directions(&self, samples: usize, slices: usize) -> usize {
        match self.sampler {
            Sampler::March => SLICES.clamp(slices) * 4,
            Sampler::Points => samples,
        }
    }
}

named_choice!(
    Variant,
    "variant",
    VARIANTS.iter().map(|d| (d.name, d.variant)).chain([("default", Variant::default())])
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_variant_has_one_row_and_its_counts_label_themselves() {
        for (i, d) in VARIANTS.iter().enumerate() {
            assert_eq!(Variant::ALL[i], d.variant);
            assert_eq!(d.name.parse::<Variant>().unwrap(), d.variant);
            assert!(!d.counts.is_empty());
        }
        assert_eq!(VARIANTS[0].variant, Variant::default(), "the default first");
        assert_eq!(Variant::March.decl().count_label(16, 2, 12), "2 slices × 12 steps");
        assert_eq!(Variant::Points.decl().count_label(16, 2, 12), "16 samples");
        assert_eq!(Variant::March.decl().count_short(16, 4, 16), "4×16");
        assert_eq!(SLICES.check(33).unwrap_err().to_string(), "--slices 33: must be a whole number between 1 and 32");
        assert_eq!(STEPS.clamp(0), 1);
        let err = "ssao".parse::<Variant>().unwrap_err().to_string();
        assert!(err.contains("expected march, points, classic, default"), "{err}");
    }
}
