//! Material maps: texture paths resolved as exporters write them (Windows backslashes, options
//! before the name, wrong letter case), images decoded within size limits, each file decoded once
//! per model within a byte budget, and a visible checker in place of what cannot be read.

use std::path::{Path, PathBuf};

use super::model::read_bounded;
use crate::{Error, Result};

/// An 8-bit RGBA texture in sRGB encoding, as decoded from a file. The pixels are shared: every
/// material that names the same file (by canonical path or by content) holds the same ones, and
/// the G-buffer uploads them once.
#[derive(Clone, Debug)]
pub struct TextureImage {
    pub width: u32,
    pub height: u32,
    pub rgba: std::sync::Arc<Vec<u8>>,
}

impl TextureImage {
    /// The fallback for a texture that is missing or unreadable: a magenta/grey checker, so the
    /// problem is visible on screen as well as in the log.
    pub fn checker() -> Self {
        let size = 8u32;
        let rgba = (0..size * size)
            .flat_map(
                |i| if ((i % size) / 2 + (i / size) / 2) % 2 == 0 { [200, 40, 200, 255] } else { [90, 90, 90, 255] },
            )
            .collect();
        Self { width: size, height: size, rgba: std::sync::Arc::new(rgba) }
    }
}

/// The decoded RGBA8 bytes all of one model's textures may take together; a texture that would
/// go beyond is halved until it fits, with a warning. A small file can decode to a huge image
/// (a 128 KB PNG of 4096² 16-bit texels), and a material file can name it many times.
pub const TEXTURE_BUDGET_BYTES: u64 = 1 << 30;

/// The textures of one model load: each file decoded once, whichever names it.
#[derive(Default)]
pub(super) struct TextureCache {
    by_path: std::collections::HashMap<PathBuf, TextureImage>,
    /// (length, hash) of the file's bytes: the same picture under another name.
    by_content: std::collections::HashMap<(usize, u64), TextureImage>,
    bytes: u64,
    budget: u64,
}

impl TextureCache {
    pub(super) fn with_budget(budget: u64) -> Self {
        Self { budget, ..Self::default() }
    }
}

/// Splits a texture statement's argument into the file name, dropping the options exporters put
/// before it (`-bm 0.5 -s 1 1 1 bricks.png`) and turning Windows separators into `/`.
pub fn texture_file_name(argument: &str) -> Option<String> {
    let words: Vec<&str> = argument.split_whitespace().collect();
    let mut i = 0;
    while i < words.len() && words[i].starts_with('-') && words[i].len() > 1 {
        let max_args = match words[i] {
            "-o" | "-s" | "-t" => 3,
            "-mm" => 2,
            _ => 1,
        };
        i += 1;
        let mut taken = 0;
        while taken < max_args && i < words.len() && (taken == 0 || words[i].parse::<f32>().is_ok()) {
            i += 1;
            taken += 1;
        }
    }
    let name = words[i.min(words.len())..].join(" ").replace('\\', "/");
    let name = name.trim_start_matches("./").to_string();
    (!name.is_empty()).then_some(name)
}

/// Finds a texture file next to the MTL: as written, then by its file name alone, then ignoring
/// letter case (files made on Windows often disagree with their MTL about case).
fn find_texture(dir: &Path, name: &str) -> Option<PathBuf> {
    let direct = dir.join(name);
    if direct.is_file() {
        return Some(direct);
    }
    let file_name = Path::new(name).file_name()?.to_string_lossy().to_lowercase();
    let base = dir.join(Path::new(name).parent().unwrap_or(Path::new("")));
    for folder in [base, dir.to_path_buf()] {
        let Ok(entries) = std::fs::read_dir(&folder) else { continue };
        for entry in entries.flatten() {
            if entry.file_name().to_string_lossy().to_lowercase() == file_name && entry.path().is_file() {
                return Some(entry.path());
            }
        }
    }
    None
}

/// Decodes an image file whatever its extension says, within a size limit.
pub fn read_image(path: &Path, max_side: u32) -> Result<image::DynamicImage> {
    // A face of 16384² RGBA32F is 4 GiB decoded; compressed files are far smaller than that.
    let bytes = read_bounded(path, 1 << 30).map_err(|problem| Error::input(path, problem))?;
    decode_image(path, &bytes, max_side)
}

/// Decodes an image file's bytes (named `path` in errors), with the same limits.
pub fn decode_image(path: &Path, bytes: &[u8], max_side: u32) -> Result<image::DynamicImage> {
    let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| Error::input(path, format!("cannot read: {e}")))?;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(max_side);
    limits.max_image_height = Some(max_side);
    limits.max_alloc = Some(4 * 1024 * 1024 * 1024);
    reader.limits(limits);
    reader.decode().map_err(|e| Error::input(path, format!("not a readable image: {e}")))
}

/// Largest texture side accepted when loading (textures are also checked against the device).
pub const MAX_TEXTURE_SIDE: u32 = 16384;

pub(super) fn load_texture(
    dir: &Path,
    argument: &str,
    cache: &mut TextureCache,
    warnings: &mut Vec<String>,
) -> TextureImage {
    use std::hash::{Hash, Hasher};
    let Some(name) = texture_file_name(argument) else {
        warnings.push(format!("texture statement '{argument}' names no file; using a checker"));
        return TextureImage::checker();
    };
    let Some(path) = find_texture(dir, &name) else {
        warnings.push(format!("{}: texture not found; using a checker", dir.join(&name).display()));
        return TextureImage::checker();
    };
    let canonical = std::fs::canonicalize(&path).unwrap_or_else(|_| path.clone());
    if let Some(image) = cache.by_path.get(&canonical) {
        return image.clone();
    }
    let bytes = match read_bounded(&path, 1 << 30) {
        Ok(bytes) => bytes,
        Err(problem) => {
            warnings.push(format!("{}: {problem}; using a checker", path.display()));
            return TextureImage::checker();
        }
    };
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    bytes.hash(&mut hasher);
    let key = (bytes.len(), hasher.finish());
    if let Some(image) = cache.by_content.get(&key) {
        let image = image.clone();
        cache.by_path.insert(canonical, image.clone());
        return image;
    }
    let image = match decode_image(&path, &bytes, MAX_TEXTURE_SIDE) {
        Ok(image) => image,
        Err(e) => {
            warnings.push(format!("{e}; using a checker"));
            return TextureImage::checker();
        }
    };
    let mut rgba = image.to_rgba8();
    drop(image);
    let room = cache.budget.saturating_sub(cache.bytes);
    let (w0, h0) = rgba.dimensions();
    let (mut w, mut h) = (w0, h0);
    while (w as u64) * (h as u64) * 4 > room && (w > 1 || h > 1) {
        (w, h) = ((w / 2).max(1), (h / 2).max(1));
    }
    if (w, h) != (w0, h0) {
        warnings.push(format!(
            "{}: downscaled from {w0}x{h0} to {w}x{h}: the model's textures would exceed the {} KiB texture budget",
            path.display(),
            cache.budget >> 10
        ));
        rgba = image::imageops::resize(&rgba, w, h, image::imageops::FilterType::Triangle);
    }
    cache.bytes += (w as u64) * (h as u64) * 4;
    let texture = TextureImage { width: w, height: h, rgba: std::sync::Arc::new(rgba.into_raw()) };
    cache.by_path.insert(canonical, texture.clone());
    cache.by_content.insert(key, texture.clone());
    texture
}
