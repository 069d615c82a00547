//! What the passes read that is not a screen target: the scene's buffers and maps, the sky, the
//! sampling parameters. (The per-frame uniforms are `frame.rs`; the screen targets `targets.rs`.)

pub mod maps;
pub mod sampling;
pub mod scene;
pub mod sky;
