//! What the sampling pass is asked for, as one value: the variant, its counts, its lengths and the
//! depth bias. The flags (`spec::RenderArgs::sampling`), the panel's sliders, the report's sweep,
//! the captions, the reproduce line and the uniforms (`resources/sampling.rs`) all read a
//! [`Sampling`]; the counts' ranges and defaults, and each variant's own defaults, are declared in
//! `variant.rs`.

use super::variant::{CountId, Variant, SAMPLES, SLICES, STEPS};

/// The march's default reach and thickness, in default sampling radii (a tenth of the scene's
/// bounding radius each): far enough to see the walls of a room from its middle; thin enough that
/// a pole does not shadow the floor behind it (walls need no more: consecutive samples on one
/// surface are bridged). Chosen with the report on cornell, open and stairs (see docs/accuracy.md):
/// 3 radii lowered cornell's error at 2×8 a little but made it rise again with more steps.
pub const REACH_RADII: f32 = 24.0;
pub const THICKNESS_RADII: f32 = 1.0;

/// The occlusion test's default depth bias, as a fraction of the radius.
pub const DEFAULT_BIAS: f32 = 0.03;

/// The sampling pass's variant and parameters.
///
/// The counts: `samples` per pixel for the points and classic variants ([`SAMPLES`]); for the
/// march, `slices` (directions around the view vector) per pixel ([`SLICES`]) and `steps` along
/// each side of a slice ([`STEPS`]), half within the radius and half beyond. The lengths, in model
/// units, `None` for the scene's default: the sampling `radius` (a tenth of the scene's bounding
/// radius); the march's `reach` for what blocks the sky and sends the bounce ([`REACH_RADII`]
/// default radii) and the `thickness` a surface in the depth buffer is taken to have
/// ([`THICKNESS_RADII`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampling {
    pub variant: Variant,
    pub samples: usize,
    pub slices: usize,
    pub steps: usize,
    pub radius: Option<f32>,
    /// The default radius is the scene's times this (a preset's radius, which travels between
    /// scenes); an explicit `radius` wins over it.
    pub radius_scale: f32,
    pub reach: Option<f32>,
    pub thickness: Option<f32>,
    /// The default thickness is the scene's times this (a preset's, which travels between
    /// scenes); an explicit `thickness` wins over it.
    pub thickness_scale: f32,
    /// Depth bias of the occlusion test, as a fraction of the radius.
    pub bias: f32,
    /// The march's far steps read a closest-depth pyramid instead of the depth buffer (off by
    /// default: the report measured it over-occluding on three scenes of four).
    pub depth_pyramid: bool,
}

/// The lengths a frame samples with, in model units (the view transform does not scale them):
/// the radius, the reach (never below the radius), the thickness, and the depth bias as a length
/// (the bias fraction times the radius).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lengths {
    pub radius: f32,
    pub reach: f32,
    pub thickness: f32,
    /// The depth bias as a length (`Sampling::bias` is its fraction of the radius).
    pub bias_length: f32,
    /// The scene's default thickness at scale 1, what a material's thickness code is a share of
    /// (`scene/thickness.rs`).
    pub default_thickness: f32,
}

impl Default for Sampling {
    fn default() -> Self {
        Self::for_variant(Variant::default())
    }
}

impl Sampling {
    /// The defaults of `variant`: the shared ones, with the variant's own sample count.
    pub fn for_variant(variant: Variant) -> Self {
        Self {
            variant,
            samples: variant.decl().default_samples,
            slices: SLICES.default,
            steps: STEPS.default,
            radius: None,
            radius_scale: 1.0,
            reach: None,
            thickness: None,
            thickness_scale: 1.0,
            bias: DEFAULT_BIAS,
            depth_pyramid: false,
        }
    }

    /// The value of a sampling count (`Accumulate` is not one: see `Settings::count`).
    pub fn count(&self, id: CountId) -> Option<usize> {
        match id {
            CountId::Samples => Some(self.samples),
            CountId::Slices => Some(self.slices),
            CountId::Steps => Some(self.steps),
            CountId::Accumulate => None,
        }
    }

    /// A sampling count to change (the panel's sliders).
    pub fn count_mut(&mut self, id: CountId) -> Option<&mut usize> {
        match id {
            CountId::Samples => Some(&mut self.samples),
            CountId::Slices => Some(&mut self.slices),
            CountId::Steps => Some(&mut self.steps),
            CountId::Accumulate => None,
        }
    }

    /// The counts within their ranges: what the passes sample with, whatever was set.
    pub fn clamped(&self) -> Self {
        Self {
            samples: SAMPLES.clamp(self.samples),
            slices: SLICES.clamp(self.slices),
            steps: STEPS.clamp(self.steps),
            ..*self
        }
    }

    /// Whether the march's far steps read the depth pyramid: asked for, and the variant marches.
    pub fn reads_pyramid(&self) -> bool {
        self.variant.decl().marched_lengths && self.depth_pyramid
    }

    /// Whether each depth sample may take its material's thickness: the march (whose lengths
    /// these are) with no thickness given: a given one, as a length or as a preset's multiple of
    /// the default, is every sample's (so `resolved` states the same frame).
    pub fn material_thickness(&self) -> bool {
        self.variant.decl().marched_lengths && self.thickness.is_none() && self.thickness_scale == 1.0
    }

    /// The same sampling with the radius and thickness scales made explicit lengths for a scene
    /// whose default radius is `default_radius` (what the reproduce line states).
    pub fn resolved(&self, default_radius: f32) -> Self {
        let lengths = self.lengths(default_radius);
        let radius = self.radius.or((self.radius_scale != 1.0).then_some(lengths.radius));
        let thickness = self.thickness.or((self.thickness_scale != 1.0).then_some(lengths.thickness));
        Self { radius, thickness, radius_scale: 1.0, thickness_scale: 1.0, ..*self }
    }

    /// The lengths in use for a scene whose default radius is `default_radius`.
    pub fn lengths(&self, default_radius: f32) -> Lengths {
        let radius = self.radius.unwrap_or(default_radius * self.radius_scale);
        Lengths {
            radius,
            reach: self.reach.unwrap_or(REACH_RADII * default_radius).max(radius),
            thickness: self.thickness.unwrap_or(THICKNESS_RADII * default_radius * self.thickness_scale),
            bias_length: self.bias * radius,
            default_thickness: THICKNESS_RADII * default_radius,
        }
    }

    /// "2 slices × 12 steps" or "16 samples": the counts this variant takes.
    pub fn count_label(&self) -> String {
        self.variant.decl().count_label(self.samples, self.slices, self.steps)
    }

    /// How many directions share the sky's radiance in one frame (see `VariantDecl::sky_directions`).
    pub fn sky_directions(&self) -> usize {
        self.variant.decl().sky_directions(self.samples, self.slices)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_variant_takes_its_own_sample_count_and_the_shared_rest() {
        for v in Variant::ALL {
            let s = Sampling::for_variant(v);
            assert_eq!(s.samples, v.decl().default_samples, "{v}");
            assert_eq!(
                (s.slices, s.steps, s.radius, s.bias),
                (SLICES.default, STEPS.default, None, DEFAULT_BIAS),
                "{v}"
            );
        }
        assert_eq!(Sampling::for_variant(Variant::Classic).samples, 64);
    }

    #[test]
    fn lengths_follow_the_default_radius_and_reach_never_falls_below_the_radius() {
        let s = Sampling::default();
        let l = s.lengths(0.5);
        assert_eq!((l.radius, l.reach, l.thickness), (0.5, 0.5 * REACH_RADII, 0.5 * THICKNESS_RADII));
        assert!((l.bias_length - 0.03 * 0.5).abs() < 1e-7);
        let wide = Sampling { radius: Some(100.0), reach: Some(1.0), ..s }.lengths(0.5);
        assert_eq!((wide.radius, wide.reach), (100.0, 100.0));
        assert!((wide.bias_length - 3.0).abs() < 1e-5);
    }

    #[test]
    fn counts_are_clamped_into_their_declared_ranges() {
        let s = Sampling { samples: 0, slices: 1000, steps: 7, ..Sampling::default() }.clamped();
        assert_eq!((s.samples, s.slices, s.steps), (SAMPLES.min, SLICES.max, 7));
        let mut s = Sampling::default();
        *s.count_mut(CountId::Slices).unwrap() = 5;
        assert_eq!((s.count(CountId::Slices), s.count(CountId::Accumulate)), (Some(5), None));
    }
}
