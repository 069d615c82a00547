//! What the user can change without reloading anything — the mode, the variant, the sampling
//! and shading settings, what is shown — with their defaults.

use super::modes::table::Mode;
use super::variant::{Variant, ACCUMULATE, SAMPLES, SLICES, STEPS};
use crate::Result;

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
}

impl View {
    pub const ALL: [View; 8] = [
        View::Final,
        View::Albedo,
        View::Normals,
        View::Depth,
        View::Ao,
        View::DoDirect,
        View::DoIndirect,
        View::LightingOnly,
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
        }
    }
}

impl std::str::FromStr for View {
    type Err = crate::Error;
    fn from_str(s: &str) -> Result<Self> {
        crate::error::by_name("view", s, View::ALL.map(|v| (v.name(), v)))
    }
}

/// What lights the senders of SSDO's one bounce besides the point lights: the light a surface
/// sends to its neighbours is its direct light, and under a sky most of that is sky light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SenderSky {
    /// The sky each sender sees, with its own visibility: a half-resolution march of one slice
    /// per pixel before the lighting pass (the sky from the open sectors, and the constant
    /// ambient by the open share), read by the lighting pass at each sender.
    #[default]
    March,
    /// The sender's unoccluded sky irradiance for its normal (the spherical harmonics the
    /// composite already has) plus the constant ambient: no extra pass, but blind to what
    /// occludes the sender, so too bright wherever a sender stands on a floor or in a crevice.
    Irradiance,
    /// The point lights only (no bounce at all under a sky alone): what the renderer did before
    /// the senders took the sky, kept for comparison in the report.
    Off,
}

impl SenderSky {
    pub const ALL: [SenderSky; 3] = [SenderSky::March, SenderSky::Irradiance, SenderSky::Off];

    /// The value of the lighting shader's `SENDER_SKY` constant.
    pub fn shader_code(self) -> f64 {
        match self {
            SenderSky::Off => 0.0,
            SenderSky::Irradiance => 1.0,
            SenderSky::March => 2.0,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            SenderSky::March => "march",
            SenderSky::Irradiance => "irradiance",
            SenderSky::Off => "off",
        }
    }
}

impl std::str::FromStr for SenderSky {
    type Err = crate::Error;
    fn from_str(s: &str) -> Result<Self> {
        crate::error::by_name("sender sky", s, SenderSky::ALL.map(|v| (v.name(), v)))
    }
}

/// What the user can change without reloading anything. The renderer follows changes on the
/// next frame, rebuilding only what the change affects (a mode or blur switch re-plans).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    pub mode: Mode,
    pub variant: Variant,
    /// Samples per pixel of the sampling pass, points and classic variants (1 to 256).
    pub samples: usize,
    /// The march: slices (directions around the view vector) per pixel (1 to 32)...
    pub slices: usize,
    /// ...and steps along each side of a slice (1 to 64); half within the radius, half beyond.
    pub steps: usize,
    /// How far the march looks for what blocks the sky and sends the bounce, in model units;
    /// `None` is the scene's bounding radius × 2.4 (24 sampling radii).
    pub reach: Option<f32>,
    /// How deep a surface in the depth buffer is taken to be, in model units; `None` is the
    /// bounding radius × 0.1 (1 sampling radius).
    pub thickness: Option<f32>,
    /// The march's far steps read a closest-depth pyramid instead of the depth buffer (off by
    /// default: the report measured it over-occluding on three scenes of four).
    pub depth_pyramid: bool,
    /// Sampling radius in model units; `None` is a tenth of the scene's bounding radius.
    pub radius: Option<f32>,
    /// Depth bias of the occlusion test, as a fraction of the radius.
    pub bias: f32,
    /// 0 leaves the ambient term unoccluded, 1 applies AO fully.
    pub ao_strength: f32,
    /// AO is raised to this power before it is applied.
    pub ao_power: f32,
    /// Multiplies SSDO's sky light.
    pub sky_strength: f32,
    /// Multiplies SSDO's indirect bounce.
    pub indirect_strength: f32,
    /// What lights the bounce's senders besides the point lights.
    pub sender_sky: SenderSky,
    /// Denoise the sampling output.
    pub blur: bool,
    /// The sampling pass runs at half width and height, followed by a depth- and normal-aware
    /// upsample (the default: the report measured the same error as full resolution at 0.7× the
    /// frame, see docs/accuracy.md).
    pub half_resolution: bool,
    /// Frames the temporal pass averages at most with the camera still (1 to 64; 1 turns the
    /// pass and its history off). Each frame's samples follow the schedule, so N still frames
    /// are N independent sample sets.
    pub accumulate: usize,
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
        Self {
            mode: Mode::Off,
            variant: Variant::default(),
            samples: SAMPLES.default,
            slices: SLICES.default,
            steps: STEPS.default,
            reach: None,
            thickness: None,
            depth_pyramid: false,
            radius: None,
            bias: 0.03,
            ao_strength: 1.0,
            ao_power: 1.0,
            sky_strength: 1.0,
            indirect_strength: 1.0,
            sender_sky: SenderSky::March,
            blur: true,
            half_resolution: true,
            accumulate: ACCUMULATE.default,
            exposure: 1.0,
            ambient: Variant::default().decl().default_ambient,
            sky_scale: 1.0,
            view: View::Final,
        }
    }
}

impl Settings {
    /// The defaults of `variant`: the shared ones, with the variant's own samples and ambient.
    pub fn for_variant(variant: Variant) -> Self {
        let d = variant.decl();
        Self { variant, samples: d.default_samples, ambient: d.default_ambient, ..Self::default() }
    }

    /// The classic variant's defaults: 64 samples and the SSDO course report's `albedo·0.5·AO` ambient.
    pub fn classic() -> Self {
        Self::for_variant(Variant::Classic)
    }

    /// The value of a sampling count.
    pub fn count(&self, id: super::variant::CountId) -> usize {
        use super::variant::CountId;
        match id {
            CountId::Samples => self.samples,
            CountId::Slices => self.slices,
            CountId::Steps => self.steps,
            CountId::Accumulate => self.accumulate,
        }
    }

    /// A sampling count to change (the panel's sliders).
    pub fn count_mut(&mut self, id: super::variant::CountId) -> &mut usize {
        use super::variant::CountId;
        match id {
            CountId::Samples => &mut self.samples,
            CountId::Slices => &mut self.slices,
            CountId::Steps => &mut self.steps,
            CountId::Accumulate => &mut self.accumulate,
        }
    }

    /// Whether the temporal pass runs: more than one frame is averaged and something is sampled.
    pub fn accumulates(&self) -> bool {
        self.accumulate > 1
    }

    /// Whether `other` gives the temporal pass's history the same meaning: every setting but the
    /// exposure (applied after it) and the number of frames averaged is the same.
    pub fn same_history(&self, other: &Settings) -> bool {
        let plain = |s: &Settings| Settings { exposure: 1.0, accumulate: 1, ..*s };
        plain(self) == plain(other)
    }

    /// "2 slices × 12 steps" or "16 samples": the counts this variant takes.
    pub fn count_label(&self) -> String {
        self.variant.decl().count_label(self.samples, self.slices, self.steps)
    }
}

/// The most frames the temporal pass averages where the view moves (`shaders/temporal.wgsl`):
/// screen-space occlusion changes with what the view shows, so a moving pixel keeps at most this
/// many frames' worth of its past (a blend of at least 1/8, as kajiya's).
pub const MOTION_ACCUMULATE: u32 = 8;

/// The march's default reach and thickness, in default sampling radii (a tenth of the scene's
/// bounding radius each): far enough to see the walls of a room from its middle; thin enough that
/// a pole does not shadow the floor behind it (walls need no more: consecutive samples on one
/// surface are bridged). Chosen with the report on cornell, open and stairs (see docs/accuracy.md):
/// 3 radii lowered cornell's error at 2×8 a little but made it rise again with more steps.
pub const REACH_RADII: f32 = 24.0;
pub const THICKNESS_RADII: f32 = 1.0;
