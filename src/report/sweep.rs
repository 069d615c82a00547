//! What the report sweeps: one [`Config`] a measured row, listed by [`configurations`] for each
//! radius. The count is known before anything renders, so the report can say its planned work.

use super::options::ReportOptions;
use crate::render::variant::{Sampler, VARIANTS};
use crate::render::{Mode, Sampling, SenderSky, Settings, Variant};

/// One configuration the report renders and measures at a radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Config {
    pub mode: Mode,
    pub variant: Variant,
    /// Samples of the points and classic variants; slices of the march (0 for Off).
    pub samples: usize,
    /// Steps a side of the march's slices (0 otherwise).
    pub steps: usize,
    pub blur: bool,
    /// The march's far steps read the depth pyramid.
    pub pyramid: bool,
    /// What lights the bounce's senders; `None`: no bounce (`--indirect-strength 0`), or no DO.
    pub bounce: Option<SenderSky>,
    /// Frames averaged (1: a single frame), and the degrees the camera turns about the model
    /// each of them (0: still); the error is taken at the last frame, in the view of the truth.
    pub accumulate: usize,
    pub orbit: f32,
    /// The sampling pass at half resolution, upsampled.
    pub half_resolution: bool,
}

/// The configurations measured at one radius. Off has no sampling pass and no radius, so only
/// the first radius measures it: once with the sky-lit composite (under the default variant's
/// name; points gives the same image) and once for classic. Every sampled mode is measured at
/// each count with blur on and off; the DO modes also with the march's depth pyramid, and at the
/// default count with the bounce's other senders and with no bounce. The rows with blur on and
/// off and the default bounce are measured at every `--accumulate` count, and the accumulated
/// ones also orbiting where `--orbit` is given; the rows with blur on at full and at half
/// resolution; the pyramid and the other bounces at one frame, at the default resolution.
pub fn configurations(options: &ReportOptions, first_radius: bool) -> Vec<Config> {
    let base = Settings::default();
    let mut configs = Vec::new();
    let default = Variant::default().decl();
    // The default variant last, so the table's slowest rows are measured warm.
    for decl in VARIANTS.iter().rev() {
        let variant = decl.variant;
        // Off has no sampling: measured once for each composite, under the default variant's name
        // for the sky-lit one.
        if first_radius && (variant == default.variant || decl.composite != default.composite) {
            configs.push(Config::off(variant));
        }
        let counts: Vec<(usize, usize)> = match decl.sampler {
            Sampler::March => options.march.clone(),
            Sampler::Points => options.samples.iter().map(|&n| (n, 0)).collect(),
        };
        for mode in Mode::sampled() {
            let directional = mode.declaration().directional_occlusion;
            let bounce = directional.then_some(base.sender_sky);
            for &(samples, steps) in &counts {
                // The pyramid's and the other bounces' rows: one frame at the default resolution.
                let at = |blur, pyramid, bounce| Config {
                    mode,
                    samples,
                    steps,
                    blur,
                    pyramid,
                    bounce,
                    half_resolution: base.half_resolution,
                    ..Config::off(variant)
                };
                for (blur, half_resolution) in [(true, false), (true, true), (false, false)] {
                    for &accumulate in &options.accumulate {
                        let config = Config { accumulate, half_resolution, ..at(blur, false, bounce) };
                        configs.push(config);
                        if accumulate > 1 && options.orbit != 0.0 {
                            configs.push(Config { orbit: options.orbit, ..config });
                        }
                    }
                }
                if decl.marched_lengths && directional {
                    configs.push(at(true, true, bounce));
                }
                if variant == Variant::default()
                    && directional
                    && (samples, steps) == (base.sampling.slices, base.sampling.steps)
                {
                    for other in SenderSky::ALL.map(Some).into_iter().chain([None]) {
                        if other != bounce {
                            configs.push(at(true, false, other));
                        }
                    }
                }
            }
        }
    }
    configs
}

/// Every configuration of the whole report, over all its radii (and the preset's row).
pub fn planned_configurations(options: &ReportOptions) -> usize {
    (0..options.radii.len()).map(|i| configurations(options, i == 0).len()).sum::<usize>()
        + usize::from(options.preset.is_some())
}

impl Config {
    /// The configuration a preset's knobs give in `mode`, and its radius scale. A bounce's
    /// strength is 1 or none (0), as tune writes it.
    pub fn of_knobs(mode: Mode, k: &crate::preset::Knobs) -> (Self, f32) {
        let marches = k.variant.decl().sampler == Sampler::March;
        let directional = mode.declaration().directional_occlusion;
        let config = Config {
            mode,
            variant: k.variant,
            samples: if marches { k.slices } else { k.samples },
            steps: if marches { k.steps } else { 0 },
            blur: k.blur,
            pyramid: k.depth_pyramid && marches,
            bounce: (directional && k.indirect_strength > 0.0).then_some(k.sender_sky),
            accumulate: k.accumulate,
            orbit: 0.0,
            half_resolution: k.half_resolution,
        };
        (config, k.radius_scale)
    }

    /// Off under `variant`'s composite: no sampling pass, one still frame.
    pub(crate) fn off(variant: Variant) -> Self {
        Config {
            mode: Mode::Off,
            variant,
            samples: 0,
            steps: 0,
            blur: false,
            pyramid: false,
            bounce: None,
            accumulate: 1,
            orbit: 0.0,
            half_resolution: false,
        }
    }

    /// The renderer's settings for this configuration at `radius`. Every configuration renders
    /// the same lighting (the classic variant keeps its own composite, not its own ambient), so
    /// all meet one truth.
    pub fn settings(&self, radius: f32) -> Settings {
        let base = Settings::default();
        let marches = self.variant.decl().sampler == Sampler::March;
        let defaults = base.sampling;
        let (slices, steps) = if marches { (self.samples, self.steps) } else { (defaults.slices, defaults.steps) };
        // No bounce (`none`) is the bounce's strength at 0.
        let no_bounce = self.bounce.is_none() && self.mode.declaration().directional_occlusion;
        Settings {
            mode: self.mode,
            sampling: Sampling {
                variant: self.variant,
                samples: if marches { defaults.samples } else { self.samples.max(1) },
                slices,
                steps,
                depth_pyramid: self.pyramid,
                radius: Some(radius),
                ..defaults
            },
            blur: self.blur,
            sender_sky: self.bounce.unwrap_or(base.sender_sky),
            indirect_strength: if no_bounce { 0.0 } else { base.indirect_strength },
            accumulate: self.accumulate,
            half_resolution: self.half_resolution,
            ..base
        }
    }

    /// The configuration whose error maps the report writes: the default SSAO+SSDO.
    pub fn is_the_default_both(&self) -> bool {
        let base = Settings::default();
        self.variant == Variant::default()
            && (self.samples, self.steps) == (base.sampling.slices, base.sampling.steps)
            && !self.pyramid
            && self.blur
            && self.bounce == Some(base.sender_sky)
            && self.mode == Mode::Both
            && self.accumulate == base.accumulate
            && self.orbit == 0.0
            && self.half_resolution == base.half_resolution
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::{SLICES, STEPS};

    fn options(samples: usize, march: usize, radii: usize) -> ReportOptions {
        ReportOptions {
            scene: "cornell".into(),
            model: None,
            no_surface_maps: false,
            skybox: None,
            size: (16, 12),
            samples: vec![8; samples],
            march: vec![(2, 16); march],
            radii: vec![super::super::options::RadiusChoice::Times(1.0); radii],
            samples_per_pixel: 2,
            frames: 1,
            accumulate: vec![1],
            orbit: 0.0,
            lights: 0,
            seed: 1,
            out: "report".into(),
            preset: None,
        }
    }

    #[test]
    fn the_sweep_is_counted_as_it_is_listed() {
        // Per radius and count: 3 sampled modes × blur on/off, the two DO modes again with the
        // pyramid (march only), and at the default march 5 other bounces in each DO mode.
        for (samples, march, radii) in [(1, 1, 1), (5, 4, 1), (2, 3, 2)] {
            let o = options(samples, march, radii);
            // ...and the 3 sampled modes with blur on again at half resolution.
            let per_radius = 2 * (9 * samples) + (9 + 2) * march + 2 * 5 * march;
            assert_eq!(planned_configurations(&o), 2 + radii * per_radius, "{samples} {march} {radii}");
        }
        let mut o = options(1, 1, 1);
        o.accumulate = vec![1, Settings::default().accumulate];
        let configs = configurations(&o, true);
        assert_eq!(configs.iter().filter(|c| c.mode == Mode::Off).count(), 2);
        assert_eq!(configs.iter().filter(|c| c.is_the_default_both()).count(), 1);
        // Accumulation doubles the rows of blur on (full and half resolution) and off (3 variants
        // × 3 modes × 3) at one count each; orbiting adds the accumulated ones again.
        let single = configurations(&options(1, 1, 1), true).len();
        assert_eq!(configs.len(), single + 3 * 3 * 3);
        o.orbit = 1.0;
        let orbiting = configurations(&o, true);
        assert_eq!(orbiting.len(), single + 2 * 3 * 3 * 3);
        assert!(orbiting.iter().all(|c| c.orbit == 0.0 || c.accumulate > 1));
        assert!(configs.iter().filter(|c| c.mode == Mode::Ssao).all(|c| c.bounce.is_none() && !c.pyramid));
    }

    #[test]
    fn no_bounce_is_a_bounce_of_strength_zero_and_counts_reach_the_variant_they_belong_to() {
        let none = Config {
            mode: Mode::Ssdo,
            variant: Variant::March,
            samples: 4,
            steps: 16,
            blur: true,
            pyramid: false,
            bounce: None,
            accumulate: 4,
            orbit: 0.0,
            half_resolution: true,
        };
        let s = none.settings(0.5);
        assert_eq!((s.accumulate, s.half_resolution), (4, true));
        assert_eq!(
            (s.indirect_strength, s.sampling.slices, s.sampling.steps, s.sampling.radius),
            (0.0, 4, 16, Some(0.5))
        );
        let points = Config { variant: Variant::Points, samples: 32, steps: 0, bounce: Some(SenderSky::March), ..none };
        let s = points.settings(0.5);
        assert_eq!((s.sampling.samples, s.indirect_strength), (32, 1.0));
        assert_eq!((s.sampling.slices, s.sampling.steps), (SLICES.default, STEPS.default));
    }
}
