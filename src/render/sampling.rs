//! The sampling pass's lengths: those given in model units, their defaults as multiples of the
//! scene's default radius, and the lengths a frame resolves them to. The variant and the counts
//! are knobs (`crate::knobs`), their ranges and each variant's defaults declared in `variant.rs`.

/// The march's default reach and thickness, in default sampling radii (a tenth of the scene's
/// bounding radius each): far enough to see the walls of a room from its middle; thin enough that
/// a pole does not shadow the floor behind it (walls need no more: consecutive samples on one
/// surface are bridged). Chosen with the report on cornell, open and stairs (see docs/accuracy.md):
/// 3 radii lowered cornell's error at 2×8 a little but made it rise again with more steps.
pub const REACH_RADII: f32 = 24.0;
pub const THICKNESS_RADII: f32 = 1.0;

/// The occlusion test's default depth bias, as a fraction of the radius.
pub const DEFAULT_BIAS: f32 = 0.03;

/// The lengths given in model units (`--radius`, `--reach`, `--thickness`, the panel's sliders),
/// `None` for the scene's default times the knobs' multiple: the sampling `radius` (a tenth of the
/// scene's bounding radius); the march's `reach` for what blocks the sky and sends the bounce
/// ([`REACH_RADII`] default radii) and the `thickness` a surface in the depth buffer is taken to
/// have ([`THICKNESS_RADII`]); and the depth `bias` as a fraction of the radius. What the
/// sampling pass counts and which variant it runs are knobs (`crate::knobs::Knobs`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GivenLengths {
    pub radius: Option<f32>,
    pub reach: Option<f32>,
    pub thickness: Option<f32>,
    /// Depth bias of the occlusion test, as a fraction of the radius.
    pub bias: f32,
}

/// The lengths a frame samples with, in model units (the view transform does not scale them):
/// the radius, the reach (never below the radius), the thickness, and the depth bias as a length
/// (the bias fraction times the radius).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lengths {
    pub radius: f32,
    pub reach: f32,
    pub thickness: f32,
    /// The depth bias as a length (`GivenLengths::bias` is its fraction of the radius).
    pub bias_length: f32,
    /// The scene's default thickness at scale 1, what a material's thickness code is a share of
    /// (`scene/thickness.rs`).
    pub default_thickness: f32,
}

impl Default for GivenLengths {
    fn default() -> Self {
        Self { radius: None, reach: None, thickness: None, bias: DEFAULT_BIAS }
    }
}

impl GivenLengths {
    /// The lengths in use for a scene whose default radius is `default_radius`, those not given
    /// being the defaults times their `scales` (the knobs' radius, reach and thickness multiples).
    pub fn lengths(&self, scales: [f32; 3], default_radius: f32) -> Lengths {
        let [radius_scale, reach_scale, thickness_scale] = scales;
        let radius = self.radius.unwrap_or(default_radius * radius_scale);
        Lengths {
            radius,
            reach: self.reach.unwrap_or(REACH_RADII * default_radius * reach_scale).max(radius),
            thickness: self.thickness.unwrap_or(THICKNESS_RADII * default_radius * thickness_scale),
            bias_length: self.bias * radius,
            default_thickness: THICKNESS_RADII * default_radius,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_follow_the_default_radius_and_reach_never_falls_below_the_radius() {
        let s = GivenLengths::default();
        let l = s.lengths([1.0; 3], 0.5);
        assert_eq!((l.radius, l.reach, l.thickness), (0.5, 0.5 * REACH_RADII, 0.5 * THICKNESS_RADII));
        assert!((l.bias_length - 0.03 * 0.5).abs() < 1e-7);
        let wide = GivenLengths { radius: Some(100.0), reach: Some(1.0), ..s }.lengths([1.0; 3], 0.5);
        assert_eq!((wide.radius, wide.reach), (100.0, 100.0));
        assert!((wide.bias_length - 3.0).abs() < 1e-5);
        let scaled = s.lengths([2.0, 0.25, 0.5], 0.5);
        assert_eq!((scaled.radius, scaled.thickness, scaled.default_thickness), (1.0, 0.25, 0.5));
        assert_eq!(scaled.reach, 0.25 * 0.5 * REACH_RADII);
    }
}
