//! What the report sweeps: one [`Config`] a measured row, listed by [`configurations`] for each
//! radius. The count is known before anything renders, so the report can say its planned work.

use super::options::ReportOptions;
use crate::knobs::Knobs;
use crate::render::variant::{Sampler, VARIANTS};
use crate::render::{Mode, SenderSky, Settings, Variant};

/// One configuration the report renders and measures at a radius: the knobs in a mode (the
/// radius given apart), and the camera's turn a frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Config {
    pub mode: Mode,
    pub knobs: Knobs,
    /// The degrees the camera turns about the model each of the frames averaged (0: still); the
    /// error is taken at the last frame, in the view of the truth.
    pub orbit: f32,
    /// A camera cut: as many frames as the row averages are first rendered from [`CUT_DEG`]
    /// around the model, then as many in the truth's view, the last one measured. What the
    /// history of another view leaves in the average after a cut.
    pub cut: bool,
}

/// Where a cut row's camera was before the cut: this far around the model from the truth's view.
pub const CUT_DEG: f32 = 90.0;

/// The configurations measured at one radius. Off has no sampling pass and no radius, so only
/// the first radius measures it: once with the sky-lit composite (under the default variant's
/// name; points gives the same image) and once for classic. Every sampled mode is measured at
/// each count with blur on and off; the DO modes also with the march's depth pyramid, and at the
/// default count with the bounce's other senders, with no bounce and with the far side layer's
/// senders (`--far-side`, and with their sky, `--far-sky`). The rows with blur on and
/// off and the default bounce are measured at every `--accumulate` count, and the accumulated
/// ones also orbiting where `--orbit` is given (and at the default setting, after a cut: a cut
/// starts anew, so one row a mode and count checks it stays so); the rows with blur on at full and at half
/// resolution; the pyramid, the other bounces and the far side at one frame, at the default
/// resolution.
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
            for &(samples, steps) in &counts {
                let counted = match decl.sampler {
                    Sampler::March => Knobs { slices: samples, steps, ..Knobs::for_variant(variant) },
                    Sampler::Points => Knobs { samples, ..Knobs::for_variant(variant) },
                };
                // The pyramid's and the other bounces' rows: one frame at the default resolution.
                let at = |knobs: Knobs| Config::new(mode, Knobs { accumulate: 1, ..knobs });
                for (blur, half) in [(true, false), (true, true), (false, false)] {
                    for &accumulate in &options.accumulate {
                        let config = Config::new(mode, Knobs { blur, half_resolution: half, accumulate, ..counted });
                        configs.push(config);
                        if accumulate > 1 && options.orbit != 0.0 {
                            configs.push(Config { orbit: options.orbit, ..config });
                            if config.knobs == (Knobs { accumulate, ..Knobs::default() }).canonical(mode) {
                                configs.push(Config { cut: true, ..config });
                            }
                        }
                    }
                }
                if decl.marched_lengths && directional {
                    configs.push(at(Knobs { depth_pyramid: true, ..counted }));
                }
                if variant == Variant::default()
                    && directional
                    && (samples, steps) == (base.knobs.slices, base.knobs.steps)
                {
                    for sender_sky in SenderSky::ALL.into_iter().filter(|&s| s != base.knobs.sender_sky) {
                        configs.push(at(Knobs { sender_sky, ..counted }));
                    }
                    configs.push(at(Knobs { indirect_strength: 0.0, ..counted }));
                    configs.push(at(Knobs { far_side: true, ..counted }));
                    configs.push(at(Knobs { far_side: true, far_sky: true, ..counted }));
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
    /// `knobs` in `mode`, in their canonical form, still.
    pub fn new(mode: Mode, knobs: Knobs) -> Self {
        Self { mode, knobs: knobs.canonical(mode), orbit: 0.0, cut: false }
    }

    /// The configuration a preset's knobs give in `mode`, and its radius scale.
    pub fn of_knobs(mode: Mode, knobs: &Knobs) -> (Self, f32) {
        (Self::new(mode, Knobs { radius_scale: 1.0, ..*knobs }), knobs.radius_scale)
    }

    /// Off under `variant`'s composite: no sampling pass, one still frame.
    pub(crate) fn off(variant: Variant) -> Self {
        let knobs = Knobs { blur: false, half_resolution: false, accumulate: 1, ..Knobs::for_variant(variant) };
        Self::new(Mode::Off, knobs)
    }

    fn marches(&self) -> bool {
        self.knobs.variant.decl().sampler == Sampler::March
    }

    /// The row's count: samples of the points and classic variants, slices of the march, 0 for
    /// Off (which samples nothing).
    pub fn samples(&self) -> usize {
        match (self.mode, self.marches()) {
            (Mode::Off, _) => 0,
            (_, true) => self.knobs.slices,
            (_, false) => self.knobs.samples,
        }
    }

    /// Steps a side of the march's slices (0 otherwise).
    pub fn steps(&self) -> usize {
        if self.mode != Mode::Off && self.marches() {
            self.knobs.steps
        } else {
            0
        }
    }

    /// The march's far steps read the depth pyramid.
    pub fn pyramid(&self) -> bool {
        self.knobs.depth_pyramid && self.marches()
    }

    /// The far side layer's senders send too: asked for, with a bounce (the renderer draws the
    /// layer only where the scene has point lights).
    pub fn far_side(&self) -> bool {
        self.knobs.far_side && self.bounce().is_some()
    }

    /// ... with the sky its surfaces see (`--far-sky`).
    pub fn far_sky(&self) -> bool {
        self.far_side() && self.knobs.far_sky
    }

    /// What lights the bounce's senders (the variants that do not march take `march` for
    /// `last-frame`); `None`: no bounce (`--indirect-strength 0`), or no DO.
    pub fn bounce(&self) -> Option<SenderSky> {
        let directional = self.mode.declaration().directional_occlusion;
        let senders = self.knobs.sender_sky.for_variant(self.knobs.variant);
        (directional && self.knobs.indirect_strength > 0.0).then_some(senders)
    }

    /// The renderer's settings for this configuration at `radius`. Every configuration renders
    /// the same lighting (the classic variant keeps its own composite, not its own ambient), so
    /// all meet one truth.
    pub fn settings(&self, radius: f32) -> Settings {
        let base = Settings { mode: self.mode, ..Settings::default() };
        let mut s = base.with_knobs(self.knobs);
        s.ambient = base.ambient;
        s.given.radius = Some(radius);
        s
    }

    /// The configuration whose error maps the report writes: the default SSAO+SSDO, still.
    pub fn is_the_default_both(&self) -> bool {
        *self == Config::new(Mode::Both, Knobs::default())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::{SLICES, STEPS};

    fn options(samples: usize, march: usize, radii: usize) -> ReportOptions {
        ReportOptions {
            on: super::super::options::TruthScene {
                lights: 0,
                ..super::super::options::TruthScene::named("cornell", (16, 12))
            },
            samples: vec![8; samples],
            march: vec![(2, 16); march],
            radii: vec![super::super::options::RadiusChoice::Times(1.0); radii],
            samples_per_pixel: 2,
            frames: 1,
            accumulate: vec![1],
            orbit: 0.0,
            out: "report".into(),
            preset: None,
        }
    }

    #[test]
    fn the_sweep_is_counted_as_it_is_listed() {
        // Per radius and count: 3 sampled modes × blur on/off, the two DO modes again with the
        // pyramid (march only), and at the default march 5 other bounces and the far side (with
        // and without its sky) in each DO mode.
        for (samples, march, radii) in [(1, 1, 1), (5, 4, 1), (2, 3, 2)] {
            let o = options(samples, march, radii);
            // ...and the 3 sampled modes with blur on again at half resolution.
            let per_radius = 2 * (9 * samples) + (9 + 2) * march + 2 * 7 * march;
            assert_eq!(planned_configurations(&o), 2 + radii * per_radius, "{samples} {march} {radii}");
        }
        let mut o = options(1, 1, 1);
        o.accumulate = vec![1, Settings::default().knobs.accumulate];
        let configs = configurations(&o, true);
        assert_eq!(configs.iter().filter(|c| c.mode == Mode::Off).count(), 2);
        assert_eq!(configs.iter().filter(|c| c.is_the_default_both()).count(), 1);
        // Accumulation doubles the rows of blur on (full and half resolution) and off (3 variants
        // × 3 modes × 3) at one count each; orbiting adds the accumulated ones again, and each
        // mode's default setting after a cut.
        let single = configurations(&options(1, 1, 1), true).len();
        assert_eq!(configs.len(), single + 3 * 3 * 3);
        o.orbit = 1.0;
        let orbiting = configurations(&o, true);
        assert_eq!(orbiting.len(), single + 2 * 3 * 3 * 3 + 3);
        assert_eq!(orbiting.iter().filter(|c| c.cut).count(), 3);
        assert!(orbiting.iter().all(|c| (c.orbit == 0.0 && !c.cut) || c.knobs.accumulate > 1));
        assert!(orbiting.iter().all(|c| !(c.cut && c.orbit != 0.0)));
        assert!(configs.iter().filter(|c| c.mode == Mode::Ssao).all(|c| c.bounce().is_none() && !c.pyramid()));
        // No two configurations of one radius are the same setting.
        let distinct: Vec<String> = orbiting.iter().map(|c| format!("{c:?}")).collect();
        assert_eq!(distinct.iter().collect::<std::collections::HashSet<_>>().len(), orbiting.len());
    }

    #[test]
    fn no_bounce_is_a_bounce_of_strength_zero_and_counts_reach_the_variant_they_belong_to() {
        let knobs = Knobs { slices: 4, accumulate: 4, indirect_strength: 0.0, ..Knobs::default() };
        let none = Config::new(Mode::Ssdo, knobs);
        assert_eq!((none.samples(), none.steps(), none.bounce()), (4, 16, None));
        let s = none.settings(0.5);
        assert_eq!((s.knobs.accumulate, s.knobs.half_resolution), (4, true));
        assert_eq!((s.knobs.indirect_strength, s.knobs.slices, s.knobs.steps, s.given.radius), (0.0, 4, 16, Some(0.5)));
        let knobs = Knobs { samples: 32, sender_sky: SenderSky::March, ..Knobs::for_variant(Variant::Points) };
        let points = Config::new(Mode::Ssdo, knobs);
        assert_eq!((points.samples(), points.steps(), points.bounce()), (32, 0, Some(SenderSky::March)));
        let s = points.settings(0.5);
        assert_eq!((s.knobs.samples, s.knobs.indirect_strength), (32, 1.0));
        assert_eq!((s.knobs.slices, s.knobs.steps), (SLICES.default, STEPS.default));
    }
}
