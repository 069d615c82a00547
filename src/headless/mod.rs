//! The headless layer above the renderer: offscreen frames read back as images
//! ([`capture`]), textures read back to the CPU ([`readback`]), buffer statistics ([`stats`]) and
//! the bench's measurement ([`bench`]). It uses `render/`; nothing in `render/` uses it.

pub mod bench;
pub mod capture;
pub mod readback;
pub mod stats;
