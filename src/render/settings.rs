//! What the user can change without reloading anything — the mode, the variant, the sampling
//! and shading settings, what is shown — with their defaults.

use super::modes::table::Mode;
use super::sampling::Sampling;
use super::variant::{CountId, Variant, ACCUMULATE};
use crate::error::named_choice;

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

/// What lights the senders of SSDO's one bounce besides the point lights: the light a surface
/// sends to its neighbours is its direct light, and under a sky most of that is sky light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SenderSky {
    /// The sky each sender sees, with its own visibility: a half-resolution march of one slice
    /// per pixel before the lighting pass (the sky from the open sectors, and the constant
    /// ambient by the open share), read by the lighting pass at each sender.
    March,
    /// The same march at a quarter of the width and height: a sixteenth of the pixels, each
    /// standing for its 4x4 block. A sender's sky is smooth across a surface and the gather
    /// averages many senders, so it loses little (the report measures it) for a quarter of the
    /// cost.
    MarchQuarter,
    /// The sky each sender saw in the last frame's march (the march variant): the sampling pass
    /// writes every pixel's visible sky and open share beside DO, into a history the next
    /// frame's lighting pass reads where that surface was (reprojected through the last
    /// camera; where it was off screen, the unoccluded irradiance). No march of the senders'
    /// own but on a frame with no last frame (the first after a reset), which runs `March`'s.
    /// The default: the same error as `March` on every scene, without its pass.
    #[default]
    LastFrame,
    /// The sender's unoccluded sky irradiance for its normal (the spherical harmonics the
    /// composite already has) plus the constant ambient: no extra pass, but blind to what
    /// occludes the sender, so too bright wherever a sender stands on a floor or in a crevice.
    Irradiance,
    /// The point lights only (no bounce at all under a sky alone): what the renderer did before
    /// the senders took the sky, kept for comparison in the report.
    Off,
}

impl SenderSky {
    pub const ALL: [SenderSky; 5] =
        [SenderSky::March, SenderSky::MarchQuarter, SenderSky::LastFrame, SenderSky::Irradiance, SenderSky::Off];

    /// Whether the plan has the senders' own march (the sender-sky pass): every frame, or (for
    /// `LastFrame`) on a frame with no last frame to read.
    pub fn marches(self) -> bool {
        matches!(self, SenderSky::March | SenderSky::MarchQuarter | SenderSky::LastFrame)
    }

    /// What a sampling pass that does not march (the points and classic variants) takes
    /// instead: it writes no sky for the next frame, so `LastFrame` becomes `March`.
    pub fn without_march(self) -> Self {
        match self {
            SenderSky::LastFrame => SenderSky::March,
            other => other,
        }
    }

    /// What the senders take with `variant`'s sampling pass: this, or [`SenderSky::without_march`]
    /// where it does not march.
    pub fn for_variant(self, variant: crate::render::Variant) -> Self {
        if variant.decl().marched_lengths {
            self
        } else {
            self.without_march()
        }
    }

    /// The value of the lighting shader's `SENDER_SKY` constant.
    pub fn shader_code(self) -> f64 {
        match self {
            SenderSky::Off => 0.0,
            SenderSky::Irradiance => 1.0,
            SenderSky::March => 2.0,
            SenderSky::MarchQuarter => 3.0,
            SenderSky::LastFrame => 4.0,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            SenderSky::March => "march",
            SenderSky::MarchQuarter => "march-quarter",
            SenderSky::LastFrame => "last-frame",
            SenderSky::Irradiance => "irradiance",
            SenderSky::Off => "off",
        }
    }
}

named_choice!(SenderSky, "sender sky", SenderSky::ALL.map(|v| (v.name(), v)));

/// What the user can change without reloading anything. The renderer follows changes on the
/// next frame, rebuilding only what the change affects (a mode or blur switch re-plans).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    pub mode: Mode,
    /// The sampling pass: the variant, its counts, lengths and bias.
    pub sampling: Sampling,
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
    /// The far side layer: a second geometry pass draws the surfaces turned from the eye, lit by
    /// the point lights, and the bounce takes their light where the surface the screen shows
    /// faces away from the receiver (off by default: docs/accuracy.md).
    pub far_side: bool,
    /// With the far side: a quarter-resolution march from each far side surface measures the sky
    /// it sees, which it sends beside its point lights' light (off by default: docs/accuracy.md).
    pub far_sky: bool,
    /// Denoise the sampling output.
    pub blur: bool,
    /// The sampling pass runs at half width and height, and so do the blur and the average over
    /// frames; the composite upsamples by depth and normal as it reads (the default: the report
    /// measured the same error as full resolution at 0.7× the frame, see docs/accuracy.md).
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
            sampling: Sampling::default(),
            ao_strength: 1.0,
            ao_power: 1.0,
            sky_strength: 1.0,
            indirect_strength: 1.0,
            sender_sky: SenderSky::LastFrame,
            far_side: false,
            far_sky: false,
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
        Self { sampling: Sampling::for_variant(variant), ambient: variant.decl().default_ambient, ..Self::default() }
    }

    /// The classic variant's defaults: 64 samples and the SSDO course report's `albedo·0.5·AO` ambient.
    pub fn classic() -> Self {
        Self::for_variant(Variant::Classic)
    }

    /// The value of a count: a sampling count or the frames averaged.
    pub fn count(&self, id: CountId) -> usize {
        self.sampling.count(id).unwrap_or(self.accumulate)
    }

    /// A count to change (the panel's sliders).
    pub fn count_mut(&mut self, id: CountId) -> &mut usize {
        match self.sampling.count_mut(id) {
            Some(n) => n,
            None => &mut self.accumulate,
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
}

/// The largest radiance-like setting (ambient, strengths, exposure, sky scale) taken: beyond it
/// a frame's light no longer fits even pre-exposed half floats, and the sky and the light cubes
/// would turn black instead of white.
pub const MAX_GAIN: f32 = 1e6;

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
