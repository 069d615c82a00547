//! SSDO: directional occlusion (Ritschel, Grosch & Seidel 2009) — sky light from the open
//! directions plus one bounce from nearby surfaces — added to the unoccluded ambient term.
//! DO targets only; the lighting pass runs when there are lights, to give the bounce a source.

use super::{Mode, ModeDecl};

pub const DECL: ModeDecl = ModeDecl { mode: Mode::Ssdo, ambient_occlusion: false, directional_occlusion: true };
