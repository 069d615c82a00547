//! The modes: one row each in [`MODES`], read by everything that names, selects or plans a mode.
//! Adding a mode is a variant of [`Mode`] and its row here; `Plan::new` then gives it the steps
//! its two flags ask for.

use crate::error::named_choice;

/// The four render modes of the SSDO course project, in key order (1-4). Everything about a mode
/// is its row of [`MODES`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    Off,
    Ssao,
    Ssdo,
    Both,
}

/// Everything a mode is, in one row: what selects it, what it is called where, and what it
/// computes. The viewer's keys, the command line, file names, captions, the plan's step names
/// and the messages all read this table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModeDecl {
    pub mode: Mode,
    /// The viewer's key (and the caption's `[key]`).
    pub key: u32,
    /// On the command line and in file names.
    pub name: &'static str,
    /// For people: labels, captions, the window.
    pub title: &'static str,
    /// The sampling step's name in this mode's plan (`--print-plan`, timings).
    pub sampling_step: &'static str,
    /// Ambient occlusion: darkens the ambient term.
    pub ambient_occlusion: bool,
    /// Directional occlusion: sky light from the open directions and one indirect bounce.
    pub directional_occlusion: bool,
}

/// The modes, in key order.
pub const MODES: [ModeDecl; 4] = [
    // Off: the sky's irradiance, the ambient term and the point lights, unoccluded.
    ModeDecl {
        mode: Mode::Off,
        key: 1,
        name: "off",
        title: "Off",
        sampling_step: "sampling",
        ambient_occlusion: false,
        directional_occlusion: false,
    },
    // SSAO: the sky and ambient terms darkened by screen-space ambient occlusion (the classic
    // hemisphere-kernel technique, or the march's near steps).
    ModeDecl {
        mode: Mode::Ssao,
        key: 2,
        name: "ssao",
        title: "SSAO",
        sampling_step: "ssao",
        ambient_occlusion: true,
        directional_occlusion: false,
    },
    // SSDO: directional occlusion (Ritschel, Grosch & Seidel 2009) — the sky from the open
    // directions plus one bounce from nearby surfaces — instead of the unoccluded sky.
    ModeDecl {
        mode: Mode::Ssdo,
        key: 3,
        name: "ssdo",
        title: "SSDO",
        sampling_step: "ssdo",
        ambient_occlusion: false,
        directional_occlusion: true,
    },
    // SSAO+SSDO: SSDO with AO on the constant ambient term, both from one set of samples.
    ModeDecl {
        mode: Mode::Both,
        key: 4,
        name: "both",
        title: "SSAO+SSDO",
        sampling_step: "ssao_ssdo",
        ambient_occlusion: true,
        directional_occlusion: true,
    },
];

impl Mode {
    pub const ALL: [Mode; 4] = [MODES[0].mode, MODES[1].mode, MODES[2].mode, MODES[3].mode];

    /// This mode's row of [`MODES`].
    pub fn declaration(self) -> &'static ModeDecl {
        MODES.iter().find(|d| d.mode == self).expect("every mode has a row")
    }

    /// Name used on the command line and in file names.
    pub fn name(self) -> &'static str {
        self.declaration().name
    }

    /// Name shown to people (labels, window title).
    pub fn title(self) -> &'static str {
        self.declaration().title
    }

    /// The viewer's key for this mode.
    pub fn key(self) -> u32 {
        self.declaration().key
    }

    /// The mode of a viewer key.
    pub fn from_key(key: u32) -> Option<Mode> {
        MODES.iter().find(|d| d.key == key).map(|d| d.mode)
    }

    /// The modes that run the sampling pass (every one but Off).
    pub fn sampled() -> impl Iterator<Item = Mode> {
        MODES.iter().filter(|d| d.runs_sampling()).map(|d| d.mode)
    }
}

named_choice!(Mode, "mode", MODES.iter().map(|d| (d.name, d.mode)));

impl ModeDecl {
    /// Whether the mode runs the sampling pass at all.
    pub fn runs_sampling(&self) -> bool {
        self.ambient_occlusion || self.directional_occlusion
    }
}
