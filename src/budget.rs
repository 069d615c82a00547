//! One memory budget for the whole run, checked before the work it pays for: image dimensions
//! before decoding, triangle counts before building, the plan's targets before allocating.
//!
//! The budget is a share of the machine (half of its physical memory, or of the container's
//! limit where that is lower) unless `--memory-budget` sets it. It is split into fixed shares so
//! that one greedy input cannot take what the others need: geometry (the parsed model and its
//! GPU copy), the screen targets, and the material maps. A software adapter (lavapipe, llvmpipe)
//! keeps its "GPU" memory in the same RAM, which is why the GPU copies count too.

use std::sync::atomic::{AtomicU64, Ordering};

use crate::{Error, Result};

/// The process's budget in bytes; 0 = not set, use the machine's share.
static BUDGET: AtomicU64 = AtomicU64::new(0);

/// Assumed physical memory where the system does not say (not Linux, no /proc).
const UNKNOWN_MACHINE_BYTES: u64 = 8 << 30;
/// The smallest budget accepted: below it even the default scene does not fit.
pub const MIN_BUDGET: u64 = 64 << 20;

/// Bytes one triangle costs from file to screen, as measured on lavapipe: the parser's indexed
/// mesh, the loader's three 32-byte vertices, the GPU buffers and their upload copies (one
/// polygon of 15.7M fan triangles peaked at 474 B a triangle, 6.6M separate faces at 662 B).
pub const BYTES_PER_TRIANGLE: u64 = 640;
/// What a normal-mapped model's tangents add a triangle: three 16-byte tangents on the CPU, in
/// their GPU buffer and in its upload copy.
pub const TANGENT_BYTES_PER_TRIANGLE: u64 = 3 * 3 * 16;

/// What a material costs besides its maps' texels, as measured on lavapipe (10,000 plain
/// materials, one triangle each: 9.4 KiB a material with the Off frame, 16 KiB with all four
/// modes' frames recorded): its parameters' buffer and bind group on the GPU, its draw calls in
/// every recorded frame, its loader's structures.
pub const BYTES_PER_MATERIAL: u64 = 16 << 10;
/// What a distinct map costs besides its texels (the same 10,000 materials each with its own
/// 4x4 normal map: 1.3-2.1 KiB more a material): its texture, view and mip chain's objects.
pub const BYTES_PER_MAP: u64 = 4 << 10;

/// The parts of the budget, each a fraction of the whole.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Share {
    /// The model: parsed text, triangles and vertex buffers (three eighths).
    Geometry,
    /// Screen-sized render targets and readback buffers (five sixteenths).
    Targets,
    /// Material maps, decoded and on the GPU (an eighth; see [`texture_room`]).
    Textures,
    /// The sky: its files decoded, its faces and their mips (three sixteenths: one 16384x8192
    /// HDR panorama is 2.1 GiB while it loads).
    Sky,
}

impl Share {
    fn fraction(self) -> (u64, u64) {
        match self {
            Share::Geometry => (3, 8),
            Share::Targets => (5, 16),
            Share::Textures => (1, 8),
            Share::Sky => (3, 16),
        }
    }

    fn name(self) -> &'static str {
        match self {
            Share::Geometry => "geometry",
            Share::Targets => "render targets",
            Share::Textures => "textures",
            Share::Sky => "the sky",
        }
    }
}

/// Sets the process's budget (`--memory-budget`); refused below [`MIN_BUDGET`].
pub fn set(bytes: u64) -> Result<()> {
    if bytes < MIN_BUDGET {
        return Err(Error::Setting(format!(
            "--memory-budget {}: at least {} is needed",
            format_bytes(bytes),
            format_bytes(MIN_BUDGET)
        )));
    }
    BUDGET.store(bytes, Ordering::Relaxed);
    Ok(())
}

/// The whole budget in bytes: the set one, or half of the machine's memory.
pub fn total() -> u64 {
    match BUDGET.load(Ordering::Relaxed) {
        0 => (machine_bytes() / 2).max(MIN_BUDGET),
        set => set,
    }
}

/// The bytes of one share of the budget.
pub fn share(share: Share) -> u64 {
    let (num, den) = share.fraction();
    total() / den * num
}

/// The level-0 RGBA8 bytes the textures' share pays for: each map is held by the model (the
/// reference tracer reads it) and by the GPU with its mip chain (4/3 as much), 7/3 in all.
pub fn texture_room() -> u64 {
    share(Share::Textures) / 7 * 3
}

/// The smallest room a transient decode is allowed whatever the shares (a 4096² RGBA8 picture):
/// a small budget still loads an ordinary texture or sky, then keeps less of it.
pub const MIN_TRANSIENT: u64 = 64 << 20;

/// The bytes a share may hold for a moment while its files are read and decoded: the share,
/// or [`MIN_TRANSIENT`] where that is more.
pub fn transient_room(share_of: Share) -> u64 {
    share(share_of).max(MIN_TRANSIENT)
}

/// The problem, in one line, when `bytes` of `what` would not fit in its share (the caller
/// names the file or setting it comes from).
pub fn check(share_of: Share, bytes: u64, what: impl FnOnce() -> String) -> std::result::Result<(), String> {
    check_within(share(share_of), share_of, bytes, what)
}

/// [`check`] against the share's [`transient_room`]: for what is held only while it is decoded.
pub fn check_transient(share_of: Share, bytes: u64, what: impl FnOnce() -> String) -> std::result::Result<(), String> {
    check_within(transient_room(share_of), share_of, bytes, what)
}

fn check_within(
    room: u64,
    share_of: Share,
    bytes: u64,
    what: impl FnOnce() -> String,
) -> std::result::Result<(), String> {
    if bytes <= room {
        return Ok(());
    }
    Err(format!(
        "{} would need {}, over the {} of the memory budget for {} ({} in all; set it with --memory-budget)",
        what(),
        format_bytes(bytes),
        format_bytes(room),
        share_of.name(),
        format_bytes(total())
    ))
}

/// Physical memory, or the container's memory limit where that is lower.
pub fn machine_bytes() -> u64 {
    let physical = std::fs::read_to_string("/proc/meminfo").ok().and_then(|text| {
        let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
        let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
        Some(kib * 1024)
    });
    let cgroup = ["/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"]
        .iter()
        .find_map(|p| std::fs::read_to_string(p).ok()?.trim().parse::<u64>().ok());
    match (physical, cgroup) {
        (Some(p), Some(c)) => p.min(c),
        (Some(p), None) => p,
        (None, Some(c)) => c,
        (None, None) => UNKNOWN_MACHINE_BYTES,
    }
}

/// Reads a size such as `512M`, `2G`, `1.5GiB` or `1000000` (bytes); K, M, G, T are powers of
/// 1024 with or without `iB`/`B`.
pub fn parse_size(text: &str) -> std::result::Result<u64, String> {
    let t = text.trim();
    let split = t.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let value: f64 = number.parse().map_err(|_| format!("'{text}' is not a size such as 512M or 2G"))?;
    let shift = match unit.trim().to_ascii_uppercase().trim_end_matches('B').trim_end_matches('I') {
        "" => 0,
        "K" => 10,
        "M" => 20,
        "G" => 30,
        "T" => 40,
        _ => return Err(format!("'{text}': the unit must be K, M, G or T (powers of 1024)")),
    };
    let bytes = value * (1u64 << shift) as f64;
    if !(bytes.is_finite() && bytes < 1e18) {
        return Err(format!("'{text}' is beyond any machine"));
    }
    Ok(bytes as u64)
}

/// A byte count for people: `768 MiB`, `5.4 GiB`.
pub fn format_bytes(bytes: u64) -> String {
    const GIB: f64 = (1u64 << 30) as f64;
    if bytes >= 10 << 30 {
        format!("{:.0} GiB", bytes as f64 / GIB)
    } else if bytes >= 1 << 30 {
        format!("{:.1} GiB", bytes as f64 / GIB)
    } else if bytes >= 1 << 20 {
        format!("{} MiB", bytes >> 20)
    } else {
        format!("{} KiB", bytes.div_ceil(1024))
    }
}

/// Sizes a set of images to fit `room` bytes of RGBA8 level 0: the largest is halved (both
/// sides, at least 1) until the sum fits, so every image keeps as much as the others allow and
/// equal images end within one halving of each other. Returns the new sizes in input order.
pub fn fit_images(sizes: &[(u32, u32)], room: u64) -> Vec<(u32, u32)> {
    let bytes = |(w, h): (u32, u32)| w as u64 * h as u64 * 4;
    let mut out = sizes.to_vec();
    let mut total: u64 = out.iter().map(|&s| bytes(s)).sum();
    // The images by size, largest first and on a tie the last named (so the first keep most):
    // each halving is one step of the heap, not a scan of every image (a hundred thousand maps
    // took minutes).
    let mut largest: std::collections::BinaryHeap<(u64, usize)> =
        (0..out.len()).filter(|&i| out[i] != (1, 1)).map(|i| (bytes(out[i]), i)).collect();
    while total > room {
        let Some((_, i)) = largest.pop() else { break };
        let (w, h) = out[i];
        let smaller = ((w / 2).max(1), (h / 2).max(1));
        total = total - bytes(out[i]) + bytes(smaller);
        out[i] = smaller;
        if smaller != (1, 1) {
            largest.push((bytes(smaller), i));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_as_people_write_them() {
        assert_eq!(parse_size("512M"), Ok(512 << 20));
        assert_eq!(parse_size("2G"), Ok(2 << 30));
        assert_eq!(parse_size("1.5GiB"), Ok(3 << 29));
        assert_eq!(parse_size("64 MB"), Ok(64 << 20));
        assert_eq!(parse_size("1000"), Ok(1000));
        assert!(parse_size("lots").is_err());
        assert!(parse_size("2X").is_err());
        assert!(parse_size("1e30").is_err());
        assert!(parse_size("99999999999T").is_err());
    }

    #[test]
    fn the_machine_has_some_memory_and_shares_add_up_to_at_most_the_whole() {
        assert!(machine_bytes() >= MIN_BUDGET);
        let parts = [Share::Geometry, Share::Targets, Share::Textures, Share::Sky].map(share);
        assert!(parts.iter().sum::<u64>() <= total());
    }

    #[test]
    fn images_are_halved_largest_first_until_they_fit() {
        // 32 textures of 4096² (2 GiB) in 768 MiB: none ends below half size.
        let sizes = vec![(4096, 4096); 32];
        let fitted = fit_images(&sizes, 768 << 20);
        assert!(fitted.iter().all(|&s| s == (4096, 4096) || s == (2048, 2048)), "{fitted:?}");
        assert!(fitted.iter().map(|&(w, h)| w as u64 * h as u64 * 4).sum::<u64>() <= 768 << 20);
        // One huge image beside small ones: only the huge one shrinks.
        let fitted = fit_images(&[(16384, 16384), (512, 512)], 768 << 20);
        assert_eq!(fitted, vec![(8192, 8192), (512, 512)]);
        // What fits is left alone; what cannot fit ends at 1x1 without looping.
        assert_eq!(fit_images(&[(64, 32)], 1 << 20), vec![(64, 32)]);
        assert_eq!(fit_images(&[(64, 32), (8, 8)], 0), vec![(1, 1), (1, 1)]);
    }
}
