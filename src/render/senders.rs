//! What lights the bounce's senders besides the point lights: a knob's named choice (`--sender-sky`).

use super::variant::Variant;
use crate::error::named_choice;

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
    pub fn for_variant(self, variant: Variant) -> Self {
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
