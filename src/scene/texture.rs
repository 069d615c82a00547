//! Material maps: texture paths resolved as exporters write them (Windows backslashes, options
//! before the name, wrong letter case), images decoded within size limits, each file decoded once
//! per model within a byte budget, and a visible checker in place of what cannot be read.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use super::files::{check_file, open_regular, ModelFolder};
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
    /// The texel under `uv` (nearest, wrapping; v down the image, as the vertices store it).
    pub fn texel(&self, uv: [f32; 2]) -> [u8; 4] {
        let wrap = |t: f32, n: u32| {
            let t = if t.is_finite() { t.rem_euclid(1.0) } else { 0.0 };
            ((t * n as f32) as u32).min(n - 1)
        };
        let i = 4 * (wrap(uv[1], self.height) * self.width + wrap(uv[0], self.width)) as usize;
        [self.rgba[i], self.rgba[i + 1], self.rgba[i + 2], self.rgba[i + 3]]
    }

    /// Whether every texel is grey (red, green and blue within a few steps of each other, as a
    /// compressed grey picture keeps them): a height map, not a normal map, whose flat texels
    /// are (128, 128, 255).
    pub fn is_greyscale(&self) -> bool {
        let grey = self.rgba.chunks_exact(4).filter(|t| t[0].abs_diff(t[1]) <= 8 && t[1].abs_diff(t[2]) <= 8).count();
        grey * 100 >= 99 * (self.rgba.len() / 4)
    }

    /// Whether some texel is less than opaque.
    pub fn has_alpha(&self) -> bool {
        self.rgba.chunks_exact(4).any(|t| t[3] < 255)
    }

    /// The same picture with its luminance as coverage in alpha (a mask drawn in grey).
    pub fn luminance_as_alpha(&self) -> Self {
        let luminance = |t: &[u8]| (0.2126 * t[0] as f32 + 0.7152 * t[1] as f32 + 0.0722 * t[2] as f32).round() as u8;
        let rgba = self.rgba.chunks_exact(4).flat_map(|t| [255, 255, 255, luminance(t)]).collect();
        Self { width: self.width, height: self.height, rgba: std::sync::Arc::new(rgba) }
    }

    /// The fallback for a texture that is missing or unreadable: a magenta/grey checker, so the
    /// problem is visible on screen as well as in the log.
    pub fn checker() -> Self {
        let size = 8u32;
        let rgba = (0..size * size)
            .flat_map(|i| {
                if ((i % size) / 2 + (i / size) / 2).is_multiple_of(2) {
                    [200, 40, 200, 255]
                } else {
                    [90, 90, 90, 255]
                }
            })
            .collect();
        Self { width: size, height: size, rgba: std::sync::Arc::new(rgba) }
    }
}

/// The textures of one model load: each file decoded once, whichever names it, at a size
/// planned from all the model's image headers before any is decoded.
#[derive(Default)]
pub(super) struct TextureCache {
    by_path: HashMap<PathBuf, TextureImage>,
    /// (length, hash) of the file's bytes: the same picture under another name.
    by_content: HashMap<ContentKey, TextureImage>,
    /// The size each picture decodes to, so that all of them fit `room` together.
    planned: HashMap<ContentKey, (u32, u32)>,
    /// Decoded RGBA8 level-0 bytes the model's textures may take together.
    room: u64,
}

type ContentKey = (usize, u64);

fn content_key(bytes: &[u8]) -> ContentKey {
    use std::hash::{Hash, Hasher};
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    bytes.hash(&mut hasher);
    (bytes.len(), hasher.finish())
}

impl TextureCache {
    /// Reads every distinct picture the texture statements name (its bytes, for the content
    /// key, and its header; the pixels are not decoded) and plans each one's size: all of them together within `room` bytes of RGBA8, the
    /// largest halved first (see [`crate::budget::fit_images`]). A file that cannot be read is
    /// left to [`load_texture`] to report.
    pub(super) fn plan<'a>(folder: &ModelFolder, arguments: impl IntoIterator<Item = &'a str>, room: u64) -> Self {
        let mut seen_paths = HashSet::new();
        let mut pictures = Vec::new();
        for argument in arguments {
            let Some(Ok((path, _))) = texture_file_name(argument).map(|name| folder.find(&name)) else { continue };
            if !seen_paths.insert(std::fs::canonicalize(&path).unwrap_or(path.clone())) {
                continue;
            }
            let Ok(bytes) = folder.read_found(&path, file_limit()) else { continue };
            note_picture(&mut pictures, &bytes);
        }
        Self::fitted(pictures, room)
    }

    /// [`TextureCache::plan`] for pictures already in memory (a glTF's images).
    pub(super) fn plan_pictures<'a>(pictures: impl IntoIterator<Item = &'a [u8]>, room: u64) -> Self {
        let mut noted = Vec::new();
        for bytes in pictures {
            note_picture(&mut noted, bytes);
        }
        Self::fitted(noted, room)
    }

    fn fitted(pictures: Vec<(ContentKey, (u32, u32))>, room: u64) -> Self {
        let sizes: Vec<(u32, u32)> = pictures.iter().map(|&(_, size)| size).collect();
        let fitted = crate::budget::fit_images(&sizes, room);
        let planned = pictures.iter().map(|&(key, _)| key).zip(fitted).collect();
        Self { planned, room, ..Self::default() }
    }

    /// The texture for the picture in `bytes` (called `path` in warnings): decoded once per
    /// content at its planned size; `None`, with a warning ending in `fallback` (what the surface
    /// does instead), when it cannot be.
    pub(super) fn decode_or(
        &mut self,
        path: &Path,
        bytes: &[u8],
        fallback: &str,
        warnings: &mut Vec<String>,
    ) -> Option<TextureImage> {
        let key = content_key(bytes);
        if let Some(image) = self.by_content.get(&key) {
            return Some(image.clone());
        }
        let planned = self.planned.get(&key).copied();
        let texture = match decode_texture(path, bytes, planned, self.room) {
            Ok((texture, original)) => {
                if (texture.width, texture.height) != original {
                    warnings.push(format!(
                        "{}: downscaled from {}x{} to {}x{}: the model's textures would exceed the {} of the memory budget for textures",
                        path.display(),
                        original.0,
                        original.1,
                        texture.width,
                        texture.height,
                        crate::budget::format_bytes(self.room)
                    ));
                }
                texture
            }
            Err(e) => {
                warnings.push(format!("{e}; {fallback}"));
                return None;
            }
        };
        self.by_content.insert(key, texture.clone());
        Some(texture)
    }
}

/// Adds a picture's content key and header size to `pictures`, once per content; a picture
/// whose header cannot be read is left to the decode to report.
fn note_picture(pictures: &mut Vec<(ContentKey, (u32, u32))>, bytes: &[u8]) {
    let key = content_key(bytes);
    if pictures.iter().any(|(k, _)| *k == key) {
        return;
    }
    let header = image::ImageReader::new(std::io::Cursor::new(bytes)).with_guessed_format();
    if let Ok(size) = header.map_err(image::ImageError::IoError).and_then(|r| r.into_dimensions()) {
        pictures.push((key, size));
    }
}

/// The room for the maps' texels (at most `room`) once a model's `materials` and its `maps`
/// distinct maps are paid for ([`crate::budget::BYTES_PER_MATERIAL`],
/// [`crate::budget::BYTES_PER_MAP`]): materials and texels together within the textures' share,
/// checked before any map is read, so that a hundred thousand materials of a few texels each
/// are refused in one line instead of outgrowing the budget.
pub(super) fn room_for_maps(materials: usize, maps: usize, room: u64) -> std::result::Result<u64, String> {
    use crate::budget::{self, Share, BYTES_PER_MAP, BYTES_PER_MATERIAL};
    let overhead = (materials as u64)
        .saturating_mul(BYTES_PER_MATERIAL)
        .saturating_add((maps as u64).saturating_mul(BYTES_PER_MAP));
    budget::check(Share::Textures, overhead, || format!("{materials} materials with {maps} distinct maps"))?;
    // The room counts level-0 texels, 3/7 of what they cost (see `texture_room`).
    Ok(room.min(budget::share(Share::Textures).saturating_sub(overhead) / 7 * 3))
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

/// The largest map file read: what the textures' share may hold while it decodes.
fn file_limit() -> u64 {
    crate::budget::transient_room(crate::budget::Share::Textures)
}

/// Decodes an image file whatever its extension says, within a size limit, after `check` has
/// seen its size and the bytes its decode allocates, both read from the header: nothing is
/// decoded that the caller would refuse.
pub fn read_image_checked(
    path: &Path,
    max_side: u32,
    check: impl FnOnce((u32, u32), u64) -> Result<()>,
) -> Result<image::DynamicImage> {
    use image::ImageDecoder;
    // Decoded from the file as it is read (a 16384x8192 HDR panorama can be 512 MiB on disk),
    // once it is known to be a regular file of a bounded size.
    check_file(path, 1 << 30).map_err(|problem| Error::input(path, problem))?;
    let file = open_regular(path, 1 << 30).map_err(|problem| Error::input(path, problem))?;
    let mut reader = image::ImageReader::new(std::io::BufReader::new(file))
        .with_guessed_format()
        .map_err(|e| Error::input(path, format!("cannot read: {e}")))?;
    reader.limits(decode_limits(max_side));
    let decoder = reader.into_decoder().map_err(|e| Error::input(path, format!("not a readable image: {e}")))?;
    check(decoder.dimensions(), decoder.total_bytes())?;
    image::DynamicImage::from_decoder(decoder).map_err(|e| Error::input(path, format!("not a readable image: {e}")))
}

/// The decoder's limits: sides up to `max_side`, and no allocation past 4 GiB.
fn decode_limits(max_side: u32) -> image::Limits {
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(max_side);
    limits.max_image_height = Some(max_side);
    limits.max_alloc = Some(4 * 1024 * 1024 * 1024);
    limits
}

/// Largest texture side accepted when loading (textures are also checked against the device).
pub const MAX_TEXTURE_SIDE: u32 = 16384;

/// What a colour map that cannot be read becomes.
const CHECKER: &str = "using a checker";

pub(super) fn load_texture(
    folder: &ModelFolder,
    argument: &str,
    cache: &mut TextureCache,
    warnings: &mut Vec<String>,
) -> TextureImage {
    try_load_texture(folder, argument, cache, CHECKER, warnings).unwrap_or_else(TextureImage::checker)
}

/// The picture a texture statement names, or `None` with a warning that ends with `fallback`
/// (what the surface does instead: a normal map that cannot be read leaves it flat, not
/// checkered).
pub(super) fn try_load_texture(
    folder: &ModelFolder,
    argument: &str,
    cache: &mut TextureCache,
    fallback: &str,
    warnings: &mut Vec<String>,
) -> Option<TextureImage> {
    let Some(name) = texture_file_name(argument) else {
        warnings.push(format!("texture statement '{argument}' names no file; {fallback}"));
        return None;
    };
    let path = match folder.find(&name) {
        Ok((path, note)) => {
            warnings.extend(note);
            path
        }
        Err(problem) => {
            warnings.push(format!("texture {problem}; {fallback}"));
            return None;
        }
    };
    let canonical = std::fs::canonicalize(&path).unwrap_or_else(|_| path.clone());
    if let Some(image) = cache.by_path.get(&canonical) {
        return Some(image.clone());
    }
    let bytes = match folder.read_found(&path, file_limit()) {
        Ok(bytes) => bytes,
        Err(problem) => {
            warnings.push(format!("{problem}; {fallback}"));
            return None;
        }
    };
    let texture = cache.decode_or(&path, &bytes, fallback, warnings)?;
    cache.by_path.insert(canonical, texture.clone());
    Some(texture)
}

/// The word after option `name` in a texture statement (`-bm 0.5 bricks.png`: "0.5"), if the
/// option is there; the caller reads the number and says what is wrong with it.
pub fn texture_option<'a>(argument: &'a str, name: &str) -> Option<&'a str> {
    let mut words = argument.split_whitespace();
    words.by_ref().find(|w| *w == name)?;
    words.next()
}

/// Decodes a picture at its own size, then resizes it to `planned` (filtered) and turns it into
/// RGBA8. The decode's own allocation is checked from the header first: it may take the
/// texture share for a moment (a 1-bit PNG of 16384² decodes to 256 MiB of grey), not more.
/// Returns the texture and the picture's original size.
fn decode_texture(
    path: &Path,
    bytes: &[u8],
    planned: Option<(u32, u32)>,
    room: u64,
) -> Result<(TextureImage, (u32, u32))> {
    use image::ImageDecoder;
    let cannot = |e: image::ImageError| Error::input(path, format!("not a readable image: {e}"));
    let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| Error::input(path, format!("cannot read: {e}")))?;
    reader.limits(decode_limits(MAX_TEXTURE_SIDE));
    let decoder = reader.into_decoder().map_err(cannot)?;
    let original = decoder.dimensions();
    let (decode_bytes, allowed) = (decoder.total_bytes(), room.max(crate::budget::MIN_TRANSIENT));
    if decode_bytes > allowed {
        let size = crate::budget::format_bytes;
        return Err(Error::input(
            path,
            format!(
                "{}x{} decodes to {}, over the {} of the memory budget for textures",
                original.0,
                original.1,
                size(decode_bytes),
                size(allowed)
            ),
        ));
    }
    let image = image::DynamicImage::from_decoder(decoder).map_err(cannot)?;
    let (w, h) = planned.unwrap_or(original);
    let rgba = if (w, h) == original { image.into_rgba8() } else { image.thumbnail_exact(w, h).into_rgba8() };
    Ok((TextureImage { width: w, height: h, rgba: std::sync::Arc::new(rgba.into_raw()) }, original))
}
