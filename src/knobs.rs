//! The knobs: the settings a person chooses that trade error for time, each declared once in
//! [`KNOBS`] with its preset key, its flag, its label, its kind (a count, a switch, a multiple of
//! a scene length, a gain, a named choice) and range, the rungs tune steps it along, which way it
//! moves a frame's cost, and the variants and modes it means anything in. A preset's JSON (read
//! and written), its range checks, its flags, tune's search space (its neighbours and which of
//! two is dearer) and tune's CSV columns are all read from the table, so a new knob is its
//! declaration here, its field in [`Knobs`] and [`crate::render::Settings`], and its way to the
//! shader.
//!
//! Lengths are kept as multiples of the scene's lengths (the radius as a multiple of the scene's
//! default radius, the thickness of its default thickness): a preset travels between models, and
//! the renderer makes them lengths for the scene it draws.

use serde_json::{json, Map, Value as Json};

use crate::render::sampling::THICKNESS_RADII;
use crate::render::settings::MAX_GAIN;
use crate::render::variant::{Count, Sampler};
use crate::render::{Mode, SenderSky, Settings, Variant, ACCUMULATE, SAMPLES, SLICES, STEPS};
use crate::text::num;

/// The settings the knobs set; everything else (exposure, ambient, the strengths of AO and sky,
/// explicit lengths, the view) stays the user's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Knobs {
    pub variant: Variant,
    /// Samples of the points and classic variants.
    pub samples: usize,
    /// The march's slices and steps.
    pub slices: usize,
    pub steps: usize,
    pub accumulate: usize,
    pub blur: bool,
    pub half_resolution: bool,
    /// The sampling radius as a multiple of the scene's default.
    pub radius_scale: f32,
    /// The thickness a depth sample is taken to have, as a multiple of the scene's default.
    pub thickness_scale: f32,
    pub depth_pyramid: bool,
    /// 0: no bounce.
    pub indirect_strength: f32,
    pub sender_sky: SenderSky,
}

/// One knob's value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    Count(usize),
    Switch(bool),
    Number(f32),
    /// A named choice, by its name.
    Choice(&'static str),
}

/// What a knob holds and what it accepts.
#[derive(Clone, Copy, Debug)]
pub enum Kind {
    /// A whole number in the count's range.
    Count(Count),
    /// On or off; the flag turns it from its default.
    Switch,
    /// A multiple of one of the scene's lengths (`base` default radii), within `range`; its flag
    /// takes the length.
    Multiple { base: f32, range: (f32, f32) },
    /// A factor within `range`.
    Gain { range: (f32, f32) },
    /// One of the names `names` lists; `parse` gives the name a text means, or the error.
    Choice { names: fn() -> Vec<&'static str>, parse: fn(&str) -> crate::Result<&'static str> },
}

/// The values tune steps a knob along: to the rung either side of the value.
#[derive(Clone, Copy, Debug)]
pub enum Rungs {
    /// Tune leaves the knob where it starts.
    Fixed,
    Counts(&'static [usize]),
    Numbers(&'static [f32]),
    /// A switch: the other side.
    Toggle,
    /// A choice: every other name.
    Every,
}

/// How a knob moves a frame's cost as its value rises (for a switch: as it turns on).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cost {
    Rises,
    Falls,
    /// Every count above one costs the same (one temporal pass), one costs less.
    AboveOne,
    /// The names from cheapest to dearest.
    Ranked(&'static [&'static str]),
    /// About the same whatever the value.
    Same,
}

/// Where a knob means anything.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scope {
    /// Every variant.
    All,
    /// The variants that sample points (points, classic).
    Points,
    /// The variants that march.
    March,
    /// The marching variants, in the modes with DO (the pyramid).
    MarchDirectional,
    /// The modes with DO (the bounce's strength).
    Directional,
    /// The modes with DO, with a bounce (what lights the senders).
    Bounce,
}

/// One knob's declaration.
pub struct Knob {
    /// Its key in a preset's settings, and its column in tune's CSV.
    pub key: &'static str,
    /// Its command-line flag, without the dashes.
    pub flag: &'static str,
    /// Its name in the panel.
    pub label: &'static str,
    pub kind: Kind,
    pub rungs: Rungs,
    pub cost: Cost,
    pub scope: Scope,
    pub get: fn(&Knobs) -> Value,
    pub set: fn(&mut Knobs, Value),
}

/// The rungs of each count tune steps: what a step up or down on that knob reaches.
pub const SAMPLE_RUNGS: [usize; 8] = [4, 8, 12, 16, 24, 32, 48, 64];
pub const SLICE_RUNGS: [usize; 6] = [1, 2, 3, 4, 6, 8];
pub const STEP_RUNGS: [usize; 7] = [4, 6, 8, 12, 16, 24, 32];
/// Frames averaged: none, a few, the default. Every count above 1 costs the same a frame (one
/// temporal pass) and the error is taken after that many still frames, so a longer average always
/// looks better still; 16 is where the report stopped it (a moving view keeps 8 at most).
pub const ACCUMULATE_RUNGS: [usize; 3] = [1, 4, 16];
/// The radius in half-octave steps about the scene's default.
pub const RADIUS_RUNGS: [f32; 5] = [0.5, std::f32::consts::FRAC_1_SQRT_2, 1.0, std::f32::consts::SQRT_2, 2.0];
/// A bounce or none.
pub const BOUNCE_RUNGS: [f32; 2] = [0.0, 1.0];

/// The multiples of the scene's lengths a knob may hold.
pub const RADIUS_SCALE: (f32, f32) = (0.125, 8.0);
pub const THICKNESS_SCALE: (f32, f32) = (0.0625, 16.0);

fn count(v: Value) -> usize {
    match v {
        Value::Count(n) => n,
        other => unreachable!("a count knob given {other:?}"),
    }
}

fn switch(v: Value) -> bool {
    match v {
        Value::Switch(b) => b,
        other => unreachable!("a switch knob given {other:?}"),
    }
}

fn number(v: Value) -> f32 {
    match v {
        Value::Number(x) => x,
        other => unreachable!("a number knob given {other:?}"),
    }
}

fn choice<T: std::str::FromStr>(v: Value) -> T {
    match v {
        Value::Choice(name) => name.parse().ok().expect("a name the knob lists"),
        other => unreachable!("a choice knob given {other:?}"),
    }
}

/// Every knob, in the order tune steps them and a preset writes them (the variant first: the
/// others' defaults are its own).
pub const KNOBS: [Knob; 12] = [
    Knob {
        key: "variant",
        flag: "variant",
        label: "variant",
        kind: Kind::Choice {
            names: || Variant::ALL.map(Variant::name).to_vec(),
            parse: |s| s.parse::<Variant>().map(Variant::name),
        },
        rungs: Rungs::Fixed,
        cost: Cost::Same,
        scope: Scope::All,
        get: |k| Value::Choice(k.variant.name()),
        set: |k, v| k.variant = choice(v),
    },
    Knob {
        key: "samples",
        flag: SAMPLES.flag,
        label: SAMPLES.label,
        kind: Kind::Count(SAMPLES),
        rungs: Rungs::Counts(&SAMPLE_RUNGS),
        cost: Cost::Rises,
        scope: Scope::Points,
        get: |k| Value::Count(k.samples),
        set: |k, v| k.samples = count(v),
    },
    Knob {
        key: "slices",
        flag: SLICES.flag,
        label: SLICES.label,
        kind: Kind::Count(SLICES),
        rungs: Rungs::Counts(&SLICE_RUNGS),
        cost: Cost::Rises,
        scope: Scope::March,
        get: |k| Value::Count(k.slices),
        set: |k, v| k.slices = count(v),
    },
    Knob {
        key: "steps",
        flag: STEPS.flag,
        label: STEPS.label,
        kind: Kind::Count(STEPS),
        rungs: Rungs::Counts(&STEP_RUNGS),
        cost: Cost::Rises,
        scope: Scope::March,
        get: |k| Value::Count(k.steps),
        set: |k, v| k.steps = count(v),
    },
    Knob {
        key: "accumulate",
        flag: ACCUMULATE.flag,
        label: ACCUMULATE.label,
        kind: Kind::Count(ACCUMULATE),
        rungs: Rungs::Counts(&ACCUMULATE_RUNGS),
        cost: Cost::AboveOne,
        scope: Scope::All,
        get: |k| Value::Count(k.accumulate),
        set: |k, v| k.accumulate = count(v),
    },
    Knob {
        key: "blur",
        flag: "no-blur",
        label: "blur",
        kind: Kind::Switch,
        rungs: Rungs::Toggle,
        cost: Cost::Rises,
        scope: Scope::All,
        get: |k| Value::Switch(k.blur),
        set: |k, v| k.blur = switch(v),
    },
    Knob {
        key: "half_resolution",
        flag: "full-res",
        label: "half resolution",
        kind: Kind::Switch,
        rungs: Rungs::Toggle,
        cost: Cost::Falls,
        scope: Scope::All,
        get: |k| Value::Switch(k.half_resolution),
        set: |k, v| k.half_resolution = switch(v),
    },
    Knob {
        key: "radius_scale",
        flag: "radius",
        label: "radius",
        kind: Kind::Multiple { base: 1.0, range: RADIUS_SCALE },
        rungs: Rungs::Numbers(&RADIUS_RUNGS),
        cost: Cost::Same,
        scope: Scope::All,
        get: |k| Value::Number(k.radius_scale),
        set: |k, v| k.radius_scale = number(v),
    },
    Knob {
        key: "thickness_scale",
        flag: "thickness",
        label: "thickness",
        kind: Kind::Multiple { base: THICKNESS_RADII, range: THICKNESS_SCALE },
        rungs: Rungs::Fixed,
        cost: Cost::Same,
        scope: Scope::March,
        get: |k| Value::Number(k.thickness_scale),
        set: |k, v| k.thickness_scale = number(v),
    },
    Knob {
        key: "depth_pyramid",
        flag: "depth-pyramid",
        label: "depth pyramid for far steps",
        kind: Kind::Switch,
        rungs: Rungs::Toggle,
        cost: Cost::Same,
        scope: Scope::MarchDirectional,
        get: |k| Value::Switch(k.depth_pyramid),
        set: |k, v| k.depth_pyramid = switch(v),
    },
    Knob {
        key: "sender_sky",
        flag: "sender-sky",
        label: "bounce senders lit by",
        kind: Kind::Choice {
            names: || SenderSky::ALL.map(SenderSky::name).to_vec(),
            parse: |s| s.parse::<SenderSky>().map(SenderSky::name),
        },
        rungs: Rungs::Every,
        cost: Cost::Ranked(&["off", "irradiance", "last-frame", "march-quarter", "march"]),
        scope: Scope::Bounce,
        get: |k| Value::Choice(k.sender_sky.name()),
        set: |k, v| k.sender_sky = choice(v),
    },
    Knob {
        key: "indirect_strength",
        flag: "indirect-strength",
        label: "indirect strength",
        kind: Kind::Gain { range: (0.0, MAX_GAIN) },
        rungs: Rungs::Numbers(&BOUNCE_RUNGS),
        cost: Cost::Rises,
        scope: Scope::Directional,
        get: |k| Value::Number(k.indirect_strength),
        set: |k, v| k.indirect_strength = number(v),
    },
];

/// The keys of a preset's `settings`, in the order it writes them.
pub fn keys() -> Vec<&'static str> {
    KNOBS.iter().map(|k| k.key).collect()
}

impl Knob {
    /// Whether the knob means anything for `knobs` in `mode` (`None`: in any mode).
    pub fn applies(&self, knobs: &Knobs, mode: Option<Mode>) -> bool {
        let marches = knobs.variant.decl().sampler == Sampler::March;
        let directional = mode.is_none_or(|m| m.declaration().directional_occlusion);
        match self.scope {
            Scope::All => true,
            Scope::Points => !marches,
            Scope::March => marches,
            Scope::MarchDirectional => marches && directional,
            Scope::Directional => directional,
            Scope::Bounce => directional && knobs.indirect_strength > 0.0,
        }
    }

    /// The value as a preset's JSON holds it.
    fn json(&self, knobs: &Knobs) -> Json {
        match (self.get)(knobs) {
            Value::Count(n) => json!(n),
            Value::Switch(b) => json!(b),
            Value::Number(x) => json!(x),
            Value::Choice(name) => json!(name),
        }
    }

    /// The value as text (tune's CSV, a flag's value).
    pub fn text(&self, knobs: &Knobs) -> String {
        match (self.get)(knobs) {
            Value::Count(n) => n.to_string(),
            Value::Switch(b) => b.to_string(),
            Value::Number(x) => x.to_string(),
            Value::Choice(name) => name.to_string(),
        }
    }

    /// The value of `json` for this knob, or what was expected instead.
    fn read(&self, json: &Json) -> std::result::Result<Value, String> {
        match self.kind {
            Kind::Count(_) => json.as_u64().map(|n| Value::Count(n as usize)).ok_or_else(|| "a whole number".into()),
            Kind::Switch => json.as_bool().map(Value::Switch).ok_or_else(|| "true or false".into()),
            Kind::Multiple { .. } | Kind::Gain { .. } => json
                .as_f64()
                .filter(|x| x.is_finite())
                .map(|x| Value::Number(x as f32))
                .ok_or_else(|| "a number".into()),
            Kind::Choice { parse, .. } => {
                let text = json.as_str().ok_or_else(|| "a name".to_string())?;
                parse(text).map(Value::Choice).map_err(|e| format!("!{e}"))
            }
        }
    }

    /// The value within range, or the problem naming the key and what is accepted.
    fn check(&self, knobs: &Knobs) -> std::result::Result<(), String> {
        let key = self.key;
        match (self.kind, (self.get)(knobs)) {
            (Kind::Count(c), Value::Count(n)) if !c.range().contains(&n) => {
                Err(format!("settings.{key}: {n} is out of range; expected a whole number from {} to {}", c.min, c.max))
            }
            (Kind::Multiple { range: (lo, hi), .. } | Kind::Gain { range: (lo, hi) }, Value::Number(v))
                if !(v.is_finite() && (lo..=hi).contains(&v)) =>
            {
                Err(format!(
                    "settings.{key}: {} is out of range; expected a finite number from {} to {}",
                    num(v),
                    num(lo),
                    num(hi)
                ))
            }
            _ => Ok(()),
        }
    }

    /// Whether `a` and `b` differ in this knob where it means something in both, and if so
    /// whether `b` costs more a frame (the senders of a bounce against none are no difference:
    /// the bounce's strength is).
    fn dearer(&self, a: &Knobs, b: &Knobs) -> Option<bool> {
        use std::cmp::Ordering;
        if !(self.applies(a, None) && self.applies(b, None)) {
            return None;
        }
        let rank = |v: Value| -> f64 {
            match (self.cost, v) {
                (Cost::AboveOne, Value::Count(n)) => f64::from(n > 1),
                (Cost::Ranked(names), Value::Choice(name)) => names.iter().position(|n| *n == name).unwrap_or(0) as f64,
                (_, Value::Count(n)) => n as f64,
                (_, Value::Switch(on)) => f64::from(on),
                (_, Value::Number(x)) => x as f64,
                (_, Value::Choice(_)) => 0.0,
            }
        };
        let order = rank((self.get)(a)).total_cmp(&rank((self.get)(b)));
        let order = match self.cost {
            Cost::Same => Ordering::Equal,
            Cost::Falls => order.reverse(),
            _ => order,
        };
        match order {
            Ordering::Less => Some(true),
            Ordering::Greater => Some(false),
            Ordering::Equal => None,
        }
    }

    /// The settings one rung away on this knob, before they are made canonical.
    fn steps_from(&self, knobs: &Knobs) -> Vec<Knobs> {
        let with = |v: Value| {
            let mut k = *knobs;
            (self.set)(&mut k, v);
            k
        };
        let current = (self.get)(knobs);
        let ladder: Vec<(f64, Value)> = match self.rungs {
            Rungs::Fixed => return Vec::new(),
            Rungs::Toggle => return vec![with(Value::Switch(!switch(current)))],
            Rungs::Every => {
                let Kind::Choice { names, .. } = self.kind else { return Vec::new() };
                return names()
                    .into_iter()
                    .filter(|&n| Value::Choice(n) != current)
                    .map(|n| with(Value::Choice(n)))
                    .collect();
            }
            Rungs::Counts(rungs) => rungs.iter().map(|&n| (n as f64, Value::Count(n))).collect(),
            Rungs::Numbers(rungs) => rungs.iter().map(|&x| (x as f64, Value::Number(x))).collect(),
        };
        let value = match current {
            Value::Count(n) => n as f64,
            Value::Number(x) => x as f64,
            _ => return Vec::new(),
        };
        // The rung at or below the value, and the ones either side of it.
        let at = ladder.iter().rposition(|&(r, _)| r <= value).unwrap_or(0);
        let below = if ladder[at].0 < value { Some(at) } else { at.checked_sub(1) };
        below.into_iter().chain([at + 1]).filter_map(|i| ladder.get(i)).map(|&(_, v)| with(v)).collect()
    }
}

impl Default for Knobs {
    fn default() -> Self {
        Self::from_settings(&Settings::default())
    }
}

impl Knobs {
    /// The defaults of `variant`.
    pub fn for_variant(variant: Variant) -> Self {
        Self::from_settings(&Settings::for_variant(variant))
    }

    /// The knobs of `settings` (an explicit length is not a multiple: it stays the settings').
    pub fn from_settings(s: &Settings) -> Self {
        Self {
            variant: s.sampling.variant,
            samples: s.sampling.samples,
            slices: s.sampling.slices,
            steps: s.sampling.steps,
            accumulate: s.accumulate,
            blur: s.blur,
            half_resolution: s.half_resolution,
            radius_scale: s.sampling.radius_scale,
            thickness_scale: s.sampling.thickness_scale,
            depth_pyramid: s.sampling.depth_pyramid,
            indirect_strength: s.indirect_strength,
            sender_sky: s.sender_sky,
        }
    }

    /// Sets these knobs in `s`. The radius and thickness go back to the scene's defaults times
    /// the knobs' multiples; a variant other than the settings' brings its own ambient.
    pub fn apply(&self, s: &mut Settings) {
        if s.sampling.variant != self.variant {
            s.ambient = self.variant.decl().default_ambient;
        }
        s.sampling.variant = self.variant;
        s.sampling.samples = self.samples;
        s.sampling.slices = self.slices;
        s.sampling.steps = self.steps;
        s.sampling.depth_pyramid = self.depth_pyramid;
        s.sampling.radius = None;
        s.sampling.radius_scale = self.radius_scale;
        s.sampling.thickness = None;
        s.sampling.thickness_scale = self.thickness_scale;
        s.blur = self.blur;
        s.half_resolution = self.half_resolution;
        s.accumulate = self.accumulate;
        s.sender_sky = self.sender_sky;
        s.indirect_strength = self.indirect_strength;
    }

    /// The settings: `base` with these knobs.
    pub fn settings(&self, base: Settings) -> Settings {
        let mut s = base;
        self.apply(&mut s);
        s
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
        let read = |knob: &Knob, json: &Json| {
            knob.read(json).map_err(|expected| match expected.strip_prefix('!') {
                Some(error) => format!("settings.{}: {error}", knob.key),
                None => format!("settings.{}: expected {expected}", knob.key),
            })
        };
        let variant = match object.get("variant") {
            Some(json) => choice(read(&KNOBS[0], json)?),
            None => Variant::default(),
        };
        let mut k = Knobs::for_variant(variant);
        for knob in &KNOBS[1..] {
            if let Some(json) = object.get(knob.key) {
                (knob.set)(&mut k, read(knob, json)?);
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
        let counts = self.variant.decl().count_label(self.samples, self.slices, self.steps);
        let bounce = if self.indirect_strength == 0.0 {
            "no bounce".to_string()
        } else {
            format!("senders {}", self.sender_sky)
        };
        let marches = self.variant.decl().marched_lengths;
        format!(
            "{} {counts}{}, radius {:.2}x{}, blur {}, {} res, {} frames, {bounce}",
            self.variant,
            if self.depth_pyramid && marches { " pyramid" } else { "" },
            self.radius_scale,
            if self.thickness_scale != 1.0 && marches {
                format!(", thickness {:.2}x", self.thickness_scale)
            } else {
                String::new()
            },
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
        let s = k.settings(Settings::default());
        assert_eq!(Knobs::from_settings(&s), k);
        // A length the knobs make follows the scene it is used on.
        let lengths = s.sampling.lengths(2.0);
        assert_eq!((lengths.radius, lengths.thickness), (1.5, 0.5 * THICKNESS_RADII));
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
        // bounce and four other senders.
        assert_eq!(n.len(), 2 + 2 + 1 + 1 + 1 + 2 + 1 + 1 + 4);
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
