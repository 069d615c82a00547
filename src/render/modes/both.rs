//! SSAO+SSDO: AO on the ambient term and DO added, both from one set of samples in one pass.

use super::{Mode, ModeDecl};

pub const DECL: ModeDecl = ModeDecl { mode: Mode::Both, ambient_occlusion: true, directional_occlusion: true };
