//! What the user can change without reloading anything — the mode, the knobs, the lengths given,
//! the shading settings, what is shown — with their defaults.

use super::modes::table::Mode;
use super::sampling::{GivenLengths, Lengths};
use super::variant::Variant;
use crate::error::named_choice;
use crate::knobs::Knobs;

/// What the window shows: the final image or one of the intermediate buffers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum View {
    #[default]
    Final,
    Albedo,
    Normals,
    Depth,
    Ao,
    /// SSDO's sky light alone (the bounce's strength set to 0).
    DoDirect,
    /// SSDO's one-bounce indirect light alone (the sky's strength set to 0).
    DoIndirect,
    /// The final image with every albedo white: light and occlusion without surface colour.
    LightingOnly,
    /// The thickness the march takes each surface to have, against the scene's default: white
    /// the default slab, red a sheet (a cut-out), between them a thin solid.
    Thickness,
}

impl View {
    pub const ALL: [View; 9] = [
        View::Final,
        View::Albedo,
        View::Normals,
        View::Depth,
        View::Ao,
        View::DoDirect,
        View::DoIndirect,
        View::LightingOnly,
        View::Thickness,
    ];

    /// Name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            View::Final => "final",
            View::Albedo => "albedo",
            View::Normals => "normals",
            View::Depth => "depth",
            View::Ao => "ao",
            View::DoDirect => "do-direct",
            View::DoIndirect => "do-indirect",
            View::LightingOnly => "lighting",
            View::Thickness => "thickness",
        }
    }

    pub fn title(self) -> &'static str {
        match self {
            View::Final => "final image",
            View::Albedo => "albedo",
            View::Normals => "normals",
            View::Depth => "depth",
            View::Ao => "AO",
            View::DoDirect => "DO direct (sky)",
            View::DoIndirect => "DO indirect (bounce)",
            View::LightingOnly => "lighting only",
            View::Thickness => "thickness",
        }
    }
}

named_choice!(View, "view", View::ALL.map(|v| (v.name(), v)));

/// What the user can change without reloading anything. The renderer follows changes on the
/// next frame, rebuilding only what the change affects (a mode or blur switch re-plans).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    pub mode: Mode,
    /// What trades error for time: the variant, its counts, the filters, the resolution, the
    /// radius, reach and thickness as multiples of the scene's, the bounce's senders (each declared in
    /// `crate::knobs::KNOBS`).
    pub knobs: Knobs,
    /// The lengths given in model units, which win over the knobs' multiples, and the bias.
    pub given: GivenLengths,
    /// 0 leaves the ambient term unoccluded, 1 applies AO fully.
    pub ao_strength: f32,
    /// AO is raised to this power before it is applied.
    pub ao_power: f32,
    /// Multiplies SSDO's sky light.
    pub sky_strength: f32,
    /// Multiplies HDR radiance before tone mapping.
    pub exposure: f32,
    /// Constant ambient radiance (grey), multiplied by albedo and AO.
    pub ambient: f32,
    /// Multiplies the sky's radiance (the background and, in SSDO, the sky light).
    pub sky_scale: f32,
    /// What is shown.
    pub view: View,
}

impl Default for Settings {
    fn default() -> Self {
        Self::for_variant(Variant::default())
    }
}

impl Settings {
    /// The defaults of `variant`: the shared ones, with the variant's own samples and ambient.
    pub fn for_variant(variant: Variant) -> Self {
        Self {
            mode: Mode::Off,
            knobs: Knobs::for_variant(variant),
            given: GivenLengths::default(),
            ao_strength: 1.0,
            ao_power: 1.0,
            sky_strength: 1.0,
            exposure: 1.0,
            ambient: variant.decl().default_ambient,
            sky_scale: 1.0,
            view: View::Final,
        }
    }

    /// The classic variant's defaults: 64 samples and the SSDO course report's `albedo·0.5·AO` ambient.
    pub fn classic() -> Self {
        Self::for_variant(Variant::Classic)
    }

    /// These settings with `knobs` (a preset's): the radius, reach and thickness go back to the scene's
    /// defaults times the knobs' multiples; a variant other than the settings' brings its own
    /// ambient.
    pub fn with_knobs(self, knobs: Knobs) -> Self {
        let ambient =
            if knobs.variant == self.knobs.variant { self.ambient } else { knobs.variant.decl().default_ambient };
        let given = GivenLengths { radius: None, reach: None, thickness: None, ..self.given };
        Self { knobs, given, ambient, ..self }
    }

    /// Whether the temporal pass runs: more than one frame is averaged and something is sampled.
    pub fn accumulates(&self) -> bool {
        self.knobs.accumulate > 1
    }

    /// Whether `other` gives the temporal pass's history the same meaning: every setting but the
    /// exposure (applied after it) and the number of frames averaged is the same.
    pub fn same_history(&self, other: &Settings) -> bool {
        let plain = |s: &Settings| Settings { exposure: 1.0, knobs: Knobs { accumulate: 1, ..s.knobs }, ..*s };
        plain(self) == plain(other)
    }

    /// The lengths in use for a scene whose default radius is `default_radius`.
    pub fn lengths(&self, default_radius: f32) -> Lengths {
        let k = &self.knobs;
        self.given.lengths([k.radius_scale, k.reach_scale, k.thickness_scale], default_radius)
    }

    /// Whether each depth sample may take its material's thickness: the march (whose lengths
    /// these are) with no thickness given: a given one, as a length or as a preset's multiple of
    /// the default, is every sample's (so `resolved` states the same frame).
    pub fn material_thickness(&self) -> bool {
        self.knobs.variant.decl().marched_lengths && self.given.thickness.is_none() && self.knobs.thickness_scale == 1.0
    }

    /// The same settings with the radius, reach and thickness scales made given lengths for a
    /// scene whose default radius is `default_radius` (what the reproduce line states).
    pub fn resolved(&self, default_radius: f32) -> Self {
        let (k, lengths) = (self.knobs, self.lengths(default_radius));
        let radius = self.given.radius.or((k.radius_scale != 1.0).then_some(lengths.radius));
        let reach = self.given.reach.or((k.reach_scale != 1.0).then_some(lengths.reach));
        let thickness = self.given.thickness.or((k.thickness_scale != 1.0).then_some(lengths.thickness));
        Self {
            knobs: Knobs { radius_scale: 1.0, reach_scale: 1.0, thickness_scale: 1.0, ..k },
            given: GivenLengths { radius, reach, thickness, ..self.given },
            ..*self
        }
    }
}

/// The most frames the temporal pass averages where the view moves (`shaders/temporal.wgsl`):
/// screen-space occlusion changes with what the view shows, so a moving pixel keeps at most this
/// many frames' worth of its past: 8 (a blend of at least 1/8, as kajiya's) where the mode
/// computes DO, 4 for AO alone. Turning 1° a frame (320x240, 16 frames), AO, sharper than DO,
/// loses more to the half-size history's resampling each frame than more frames gain it: SSAO's
/// AO within R at 8, 6, 4 and 3 frames 0.0355, 0.0349, 0.0342, 0.0339 on cornell (still 0.0324),
/// 0.0349, -, 0.0337, 0.0338 on stairs; SSDO's DO 0.0319, 0.0321, 0.0326, 0.0333 on cornell.
pub const fn motion_accumulate(mode: Mode) -> u32 {
    match mode {
        Mode::Ssao => 4,
        _ => 8,
    }
}

/// How far (degrees) the viewpoints of a moving view's kept frames may spread
/// (`MAX_HISTORY_TURN` in `shaders/temporal.wgsl`): a surface keeps this over its turn since the
/// last frame, so at 1° a frame the motion cap binds and at 12° and more nothing is kept.
pub const MAX_HISTORY_TURN_DEG: f32 = 12.0;
