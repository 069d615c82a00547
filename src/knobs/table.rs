//! The table of knobs: what a knob is (its value, kind, rungs, cost and scope) and [`KNOBS`],
//! every knob's declaration, and [`Knobs`], the values they set.

use crate::render::sampling::{REACH_RADII, THICKNESS_RADII};
use crate::render::variant::Count;
use crate::render::{SenderSky, Variant, ACCUMULATE, SAMPLES, SLICES, STEPS};

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
    /// The march's reach (how far its far steps go), as a multiple of the scene's default.
    pub reach_scale: f32,
    pub depth_pyramid: bool,
    /// 0: no bounce.
    pub indirect_strength: f32,
    pub sender_sky: SenderSky,
    /// The far side layer: the surfaces turned from the eye send their point lights' light.
    pub far_side: bool,
    /// ... and the sky each sees, from a march of its own.
    pub far_sky: bool,
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
    /// The modes with DO, with a bounce and the far side layer (what lights its senders).
    FarSide,
}

/// One knob's declaration.
pub struct Knob {
    /// Its key in a preset's settings, and its column in tune's CSV.
    pub key: &'static str,
    /// Its command-line flag, without the dashes.
    pub flag: &'static str,
    /// Its name in the panel.
    pub label: &'static str,
    /// What it does, as `--help` and the panel say it (a count's range and defaults are added
    /// from its declaration, a switch's default and what its flag does).
    pub help: &'static str,
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

/// The largest radiance-like setting (ambient, strengths, exposure, sky scale) taken: beyond it
/// a frame's light no longer fits even pre-exposed half floats, and the sky and the light cubes
/// would turn black instead of white.
pub const MAX_GAIN: f32 = 1e6;

/// The multiples of the scene's lengths a knob may hold.
pub const RADIUS_SCALE: (f32, f32) = (0.125, 8.0);
pub const THICKNESS_SCALE: (f32, f32) = (0.0625, 16.0);
pub const REACH_SCALE: (f32, f32) = (0.0625, 16.0);

pub(super) fn count(v: Value) -> usize {
    match v {
        Value::Count(n) => n,
        other => unreachable!("a count knob given {other:?}"),
    }
}

pub(super) fn switch(v: Value) -> bool {
    match v {
        Value::Switch(b) => b,
        other => unreachable!("a switch knob given {other:?}"),
    }
}

pub(super) fn number(v: Value) -> f32 {
    match v {
        Value::Number(x) => x,
        other => unreachable!("a number knob given {other:?}"),
    }
}

pub(super) fn choice<T: std::str::FromStr>(v: Value) -> T {
    match v {
        Value::Choice(name) => name.parse().ok().expect("a name the knob lists"),
        other => unreachable!("a choice knob given {other:?}"),
    }
}

/// Every knob, in the order tune steps them and a preset writes them (the variant first: the
/// others' defaults are its own).
pub const KNOBS: [Knob; 15] = [
    Knob {
        key: "variant",
        flag: "variant",
        label: "variant",
        help: "Algorithm family: march, points (the paper's point sampling) or classic",
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
        help: "Samples per pixel of the points and classic variants",
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
        help: "The march: slices (directions around the view vector) per pixel",
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
        help: "The march: steps along each side of a slice (half within the radius)",
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
        help: "Frames averaged with the camera still (1: none; headless commands render this many frames of the still camera and keep the last)",
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
        help: "Denoise the sampling pass's output",
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
        help: "Sample at half width and height, then upsample by depth and normal",
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
        help: "The sampling radius, a multiple of the scene's default",
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
        help: "The thickness a depth sample is taken to have, a multiple of the scene's default",
        kind: Kind::Multiple { base: THICKNESS_RADII, range: THICKNESS_SCALE },
        rungs: Rungs::Fixed,
        cost: Cost::Same,
        scope: Scope::March,
        get: |k| Value::Number(k.thickness_scale),
        set: |k, v| k.thickness_scale = number(v),
    },
    Knob {
        key: "reach_scale",
        flag: "reach",
        label: "reach",
        help: "How far the march's far steps go for what blocks the sky and sends the bounce, a multiple of the scene's default",
        kind: Kind::Multiple { base: REACH_RADII, range: REACH_SCALE },
        rungs: Rungs::Fixed,
        cost: Cost::Same,
        scope: Scope::MarchDirectional,
        get: |k| Value::Number(k.reach_scale),
        set: |k, v| k.reach_scale = number(v),
    },
    Knob {
        key: "depth_pyramid",
        flag: "depth-pyramid",
        label: "depth pyramid for far steps",
        help: "The march's far steps read a closest-depth pyramid (it over-occludes: docs/accuracy.md)",
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
        help: "What lights the bounce's senders besides the point lights",
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
        key: "far_side",
        flag: "far-side",
        label: "far sides send bounce",
        help: "A second geometry pass draws the surfaces turned from the eye (a fin's far face, an \
               underside), lit by the point lights, and the bounce takes their light where the surface the \
               screen shows faces away (scenes with point lights; docs/accuracy.md)",
        kind: Kind::Switch,
        rungs: Rungs::Toggle,
        cost: Cost::Rises,
        scope: Scope::Bounce,
        get: |k| Value::Switch(k.far_side),
        set: |k, v| k.far_side = switch(v),
    },
    Knob {
        key: "far_sky",
        flag: "far-sky",
        label: "far sides see the sky",
        help: "With --far-side: a quarter-resolution march from each far side surface measures the sky it \
               sees, which it sends beside its point lights' light (so the far side is drawn under a sky \
               alone too; docs/accuracy.md)",
        kind: Kind::Switch,
        rungs: Rungs::Toggle,
        cost: Cost::Rises,
        scope: Scope::FarSide,
        get: |k| Value::Switch(k.far_sky),
        set: |k, v| k.far_sky = switch(v),
    },
    Knob {
        key: "indirect_strength",
        flag: "indirect-strength",
        label: "indirect strength",
        help: "Multiplies SSDO's one bounce (0: none)",
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
