//! The headless layer above the renderer: offscreen frames read back as images
//! ([`capture`]), textures read back to the CPU ([`readback`]), buffer statistics ([`stats`]) and
//! the bench's measurement ([`bench`]) and the truth of a captured view with each mode's error
//! against it ([`truth`]). It uses `render/`; nothing in `render/` uses it.

pub mod bench;
pub mod capture;
pub mod readback;
pub mod stats;
pub mod truth;
