//! SSAO: the ambient term darkened by screen-space ambient occlusion (seed 001's technique).
//! AO targets only; no DO targets, no lighting pass (the composite lights the scene itself).

use super::{Mode, ModeDecl};

pub const DECL: ModeDecl = ModeDecl { mode: Mode::Ssao, ambient_occlusion: true, directional_occlusion: false };
