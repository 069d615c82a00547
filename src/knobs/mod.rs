//! The knobs: the settings a person chooses that trade error for time, each declared once in
//! [`KNOBS`] with its preset key, its flag, its label, its kind (a count, a switch, a multiple of
//! a scene length, a gain, a named choice) and range, the rungs tune steps it along, which way it
//! moves a frame's cost, and the variants and modes it means anything in. A preset's JSON (read
//! and written), its range checks, its flags, tune's search space (its neighbours and which of
//! two is dearer), tune's CSV columns, the render flags' checks and the counts' help are all read
//! from the table, and so are a switch's flag, panel checkbox and reproducing flag
//! (`switches.rs`). The renderer's settings hold the knobs as they are ([`crate::render::Settings`]'s
//! `knobs`): a new knob is its row and its field in [`Knobs`] (`table.rs`), its default in
//! [`Knobs::for_variant`], and its way to the shader.
//!
//! Lengths are kept as multiples of the scene's lengths (the radius as a multiple of the scene's
//! default radius, the thickness of its default thickness): a preset travels between models, and
//! the renderer makes them lengths for the scene it draws.

mod knob;
mod switches;
mod table;

use serde_json::{Map, Value as Json};

use crate::render::variant::CountId;
use crate::render::{Mode, SenderSky, Variant, ACCUMULATE, SAMPLES, SLICES, STEPS};
pub use switches::{switches, SwitchFlags};
use table::choice;
pub use table::{
    keys, Cost, Kind, Knob, Knobs, Rungs, Scope, Value, ACCUMULATE_RUNGS, BOUNCE_RUNGS, KNOBS, MAX_GAIN, RADIUS_RUNGS,
    RADIUS_SCALE, REACH_SCALE, SAMPLE_RUNGS, SLICE_RUNGS, STEP_RUNGS, THICKNESS_SCALE,
};

impl Default for Knobs {
    fn default() -> Self {
        Self::for_variant(Variant::default())
    }
}

impl Knobs {
    /// The defaults of `variant`: the shared ones, with the variant's own sample count.
    pub fn for_variant(variant: Variant) -> Self {
        Self {
            variant,
            samples: variant.decl().default_samples,
            slices: SLICES.default,
            steps: STEPS.default,
            accumulate: ACCUMULATE.default,
            blur: true,
            half_resolution: true,
            radius_scale: 1.0,
            thickness_scale: 1.0,
            reach_scale: 1.0,
            depth_pyramid: false,
            indirect_strength: 1.0,
            sender_sky: SenderSky::LastFrame,
            far_side: false,
            far_sky: false,
        }
    }

    /// The value of a count: a sampling count or the frames averaged.
    pub fn count(&self, id: CountId) -> usize {
        match id {
            CountId::Samples => self.samples,
            CountId::Slices => self.slices,
            CountId::Steps => self.steps,
            CountId::Accumulate => self.accumulate,
        }
    }

    /// A count to change (the panel's sliders).
    pub fn count_mut(&mut self, id: CountId) -> &mut usize {
        match id {
            CountId::Samples => &mut self.samples,
            CountId::Slices => &mut self.slices,
            CountId::Steps => &mut self.steps,
            CountId::Accumulate => &mut self.accumulate,
        }
    }

    /// The sampling counts within their ranges: what the passes sample with, whatever was set.
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

    /// "2 slices × 12 steps" or "16 samples": the counts this variant takes.
    pub fn count_label(&self) -> String {
        self.variant.decl().count_label(self.samples, self.slices, self.steps)
    }

    /// How many directions share the sky's radiance in one frame (see `VariantDecl::sky_directions`).
    pub fn sky_directions(&self) -> usize {
        self.variant.decl().sky_directions(self.samples, self.slices)
    }

    /// Every value within its range, or the problem naming its key in a preset and what is
    /// accepted.
    pub fn check(&self) -> std::result::Result<(), String> {
        KNOBS.iter().try_for_each(|knob| knob.check(self))
    }

    /// The knobs as a preset's `settings` object.
    pub fn json(&self) -> Json {
        Json::Object(KNOBS.iter().map(|knob| (knob.key.to_string(), knob.json(self))).collect())
    }

    /// The knobs a preset's `settings` object gives: the variant's defaults where a key is
    /// missing. An unknown key, a value of the wrong kind or out of range is the problem, naming
    /// the key (`settings.KEY: …`).
    pub fn from_json(object: &Map<String, Json>) -> std::result::Result<Self, String> {
        if let Some(key) = object.keys().find(|k| KNOBS.iter().all(|knob| knob.key != k.as_str())) {
            return Err(format!("settings: unknown key '{key}' (known: {})", keys().join(", ")));
        }
        let variant = match object.get("variant") {
            Some(json) => choice(KNOBS[0].read(json)?),
            None => Variant::default(),
        };
        let mut k = Knobs::for_variant(variant);
        for knob in &KNOBS[1..] {
            if let Some(json) = object.get(knob.key) {
                (knob.set)(&mut k, knob.read(json)?);
            }
        }
        k.check()?;
        Ok(k)
    }

    /// The flags that give these knobs on the command line, those at their variant's defaults
    /// (and those the variant does not take) left out; multiples as the lengths they make on a
    /// scene whose default radius is `default_radius`.
    pub fn flags(&self, default_radius: f32) -> Vec<String> {
        let base = Knobs { variant: Variant::default(), ..Knobs::for_variant(self.variant) };
        let mut out = Vec::new();
        for knob in KNOBS.iter().filter(|knob| knob.applies(self, None)) {
            let value = (knob.get)(self);
            if value == (knob.get)(&base) {
                continue;
            }
            out.push(format!("--{}", knob.flag));
            match (knob.kind, value) {
                (Kind::Switch, _) => {}
                (Kind::Multiple { base, .. }, Value::Number(x)) => out.push(format!("{}", default_radius * base * x)),
                _ => out.push(knob.text(self)),
            }
        }
        out
    }

    /// "march 2×16, radius 1.00x, blur on, half res, 16 frames, senders last-frame": the knobs
    /// in a line.
    pub fn label(&self) -> String {
        let counts = self.count_label();
        let bounce = if self.indirect_strength == 0.0 {
            "no bounce".to_string()
        } else {
            let far = if self.far_side { " + far side" } else { "" };
            format!("senders {}{far}", self.sender_sky)
        };
        let marches = self.variant.decl().marched_lengths;
        format!(
            "{} {counts}{}, radius {:.2}x{}, blur {}, {} res, {} frames, {bounce}",
            self.variant,
            if self.depth_pyramid && marches { " pyramid" } else { "" },
            self.radius_scale,
            [("reach", self.reach_scale), ("thickness", self.thickness_scale)]
                .iter()
                .filter(|(_, x)| *x != 1.0 && marches)
                .map(|(name, x)| format!(", {name} {x:.2}x"))
                .collect::<String>(),
            if self.blur { "on" } else { "off" },
            if self.half_resolution { "half" } else { "full" },
            self.accumulate,
        )
    }

    /// The same setting in its one form for `mode`: the knobs that mean nothing there (a count
    /// the variant does not take, the pyramid or the bounce outside DO, the senders of no
    /// bounce) at their variant's defaults, so two settings that render alike compare equal.
    pub fn canonical(&self, mode: Mode) -> Self {
        let base = Knobs::for_variant(self.variant);
        let mut k = *self;
        for knob in &KNOBS {
            if !knob.applies(&k, Some(mode)) {
                (knob.set)(&mut k, (knob.get)(&base));
            }
        }
        k
    }

    /// The cheapest corner of `variant`: every knob tune steps at its cheapest rung (the lowest
    /// counts, no blur, half resolution, one frame, no bounce), the others at their defaults.
    pub fn cheapest(variant: Variant) -> Self {
        let mut k = Knobs::for_variant(variant);
        for knob in &KNOBS {
            if let Some(value) = knob.cheapest() {
                (knob.set)(&mut k, value);
            }
        }
        k
    }

    /// The settings one rung away on one knob that means something in `mode`, each canonical.
    /// A step that gives a choice its meaning (the bounce turned on gives the senders theirs)
    /// reaches each of its values.
    pub fn neighbours(&self, mode: Mode) -> Vec<Self> {
        KNOBS
            .iter()
            .filter(|knob| knob.applies(self, Some(mode)))
            .flat_map(|knob| knob.steps_from(self))
            .flat_map(|next| self.widened(next, mode))
            .map(|k| k.canonical(mode))
            .collect()
    }

    /// `next` (a step from these knobs), with every value of each choice that means nothing
    /// here and something there.
    fn widened(&self, next: Knobs, mode: Mode) -> Vec<Knobs> {
        let woken = KNOBS.iter().find(|knob| {
            matches!(knob.rungs, Rungs::Every) && !knob.applies(self, Some(mode)) && knob.applies(&next, Some(mode))
        });
        match woken.map(|knob| (knob, knob.kind)) {
            Some((knob, Kind::Choice { names, .. })) => names()
                .into_iter()
                .map(|name| {
                    let mut k = next;
                    (knob.set)(&mut k, Value::Choice(name));
                    k
                })
                .collect(),
            _ => vec![next],
        }
    }

    /// Whether `other` (a neighbour: one knob apart) costs more a frame (`Some(true)`), less
    /// (`Some(false)`) or about the same (`None`: the radius, the pyramid, 4 against 16 frames).
    pub fn dearer(&self, other: &Knobs) -> Option<bool> {
        KNOBS.iter().find_map(|knob| knob.dearer(self, other))
    }

    /// A key that is equal exactly when the knobs are (every float by its bits), for hashing.
    pub fn key(&self) -> Vec<u64> {
        KNOBS
            .iter()
            .map(|knob| match (knob.get)(self) {
                Value::Count(n) => n as u64,
                Value::Switch(b) => u64::from(b),
                Value::Number(x) => u64::from(x.to_bits()),
                Value::Choice(name) => {
                    let Kind::Choice { names, .. } = knob.kind else { return 0 };
                    names().iter().position(|n| *n == name).unwrap_or(0) as u64
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::SenderSky;

    #[test]
    fn every_knob_reads_back_what_it_writes_and_its_defaults_are_the_settings() {
        let k = Knobs {
            variant: Variant::Points,
            samples: 24,
            accumulate: 4,
            blur: false,
            radius_scale: 0.75,
            thickness_scale: 0.25,
            indirect_strength: 0.5,
            sender_sky: SenderSky::Irradiance,
            ..Knobs::default()
        };
        let Json::Object(object) = k.json() else { panic!("an object") };
        let mut known = keys();
        known.sort_unstable();
        assert_eq!(object.keys().map(String::as_str).collect::<Vec<_>>(), known);
        assert_eq!(Knobs::from_json(&object), Ok(k));
        assert_eq!(Knobs::from_json(&Map::new()), Ok(Knobs::default()));
        assert_eq!(Knobs::default(), crate::render::Settings::default().knobs);
        // A length the knobs make follows the scene it is used on.
        let lengths = crate::render::Settings::default().with_knobs(k).lengths(2.0);
        assert_eq!((lengths.radius, lengths.thickness), (1.5, 0.5 * crate::render::THICKNESS_RADII));
    }

    #[test]
    fn each_variant_takes_its_own_sample_count_and_the_shared_rest() {
        for v in Variant::ALL {
            let k = Knobs::for_variant(v);
            assert_eq!(k.samples, v.decl().default_samples, "{v}");
            assert_eq!(
                Knobs { variant: Variant::default(), samples: 0, ..k },
                Knobs { samples: 0, ..Knobs::default() },
                "{v}"
            );
        }
        assert_eq!(Knobs::for_variant(Variant::Classic).samples, 64);
    }

    #[test]
    fn counts_are_clamped_into_their_declared_ranges() {
        let k = Knobs { samples: 0, slices: 1000, steps: 7, ..Knobs::default() }.clamped();
        assert_eq!((k.samples, k.slices, k.steps), (SAMPLES.min, SLICES.max, 7));
        let mut k = Knobs::default();
        *k.count_mut(CountId::Slices) = 5;
        *k.count_mut(CountId::Accumulate) = 4;
        assert_eq!((k.count(CountId::Slices), k.count(CountId::Accumulate)), (5, 4));
    }

    #[test]
    fn each_flag_is_one_the_command_line_takes() {
        let command = <crate::spec::RenderArgs as clap::Args>::augment_args(clap::Command::new("ssdo"));
        let flags: Vec<&str> = command.get_arguments().filter_map(|a| a.get_long()).collect();
        for knob in &KNOBS {
            assert!(flags.contains(&knob.flag), "--{} is no flag of the command line", knob.flag);
        }
    }

    #[test]
    fn neighbours_are_one_rung_away_on_one_knob_that_means_something() {
        let k = Knobs::default();
        let n = k.neighbours(Mode::Ssdo);
        let differs = |a: &Knobs, b: &Knobs| KNOBS.iter().filter(|x| (x.get)(a) != (x.get)(b)).count();
        assert!(n.iter().all(|m| differs(&k, m) == 1), "{n:?}");
        // Slices 1 and 3, steps 12 and 24, 4 frames, blur, resolution, 2 radii, pyramid, no
        // bounce, four other senders and the far side.
        assert_eq!(n.len(), 2 + 2 + 1 + 1 + 1 + 2 + 1 + 1 + 4 + 1);
        // A count off the ladder steps onto it; the ends of a ladder have one neighbour there.
        let odd = Knobs { slices: 5, steps: 4, radius_scale: 2.0, ..k };
        let n = odd.neighbours(Mode::Ssdo);
        assert!(n.iter().any(|m| m.slices == 4) && n.iter().any(|m| m.slices == 6));
        assert!(n.iter().all(|m| m.steps >= 4 && m.accumulate <= 16 && m.radius_scale <= 2.0));
        // SSAO has no bounce and no pyramid to turn; no bounce has no senders to change.
        let ao = Knobs::for_variant(Variant::Points);
        assert!(ao.neighbours(Mode::Ssao).iter().all(|m| m.indirect_strength == 1.0 && !m.depth_pyramid));
        // No bounce: its senders are no knob, and the bounce turned on reaches every sender.
        let none = Knobs { indirect_strength: 0.0, ..k };
        let n = none.neighbours(Mode::Ssdo);
        let on: Vec<SenderSky> = n.iter().filter(|m| m.indirect_strength > 0.0).map(|m| m.sender_sky).collect();
        assert_eq!(on, SenderSky::ALL);
        assert!(n.iter().all(|m| m.indirect_strength > 0.0 || m.sender_sky == k.sender_sky));
        // Which is dearer: more steps, blur on, full resolution, a bounce; not the radius.
        assert_eq!(k.dearer(&Knobs { steps: 24, ..k }), Some(true));
        assert_eq!(k.dearer(&Knobs { half_resolution: false, ..k }), Some(true));
        assert_eq!(k.dearer(&Knobs { indirect_strength: 0.0, ..k }), Some(false));
        assert_eq!(k.dearer(&Knobs { sender_sky: SenderSky::March, ..k }), Some(true));
        assert_eq!(k.dearer(&Knobs { accumulate: 4, ..k }), None);
        assert_eq!(k.dearer(&Knobs { radius_scale: 2.0, ..k }), None);
    }
}
