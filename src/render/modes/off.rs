//! Off: plain deferred shading — constant ambient and the point lights, no occlusion. It has no
//! AO or DO targets and no sampling pass.

use super::{Mode, ModeDecl};

pub const DECL: ModeDecl = ModeDecl { mode: Mode::Off, ambient_occlusion: false, directional_occlusion: false };
