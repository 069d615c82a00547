//! Wavefront OBJ + MTL loading through `tobj`, hardened for the files people actually have.
//!
//! tobj does the parsing; around it we decode Latin-1 and UTF-16 text, pad single-value colour
//! lines in MTL files (tobj 4.0.5 panics on `Kd 0.5`, which the format allows), check every
//! attribute array against the vertex count (tobj reports success with arrays of the wrong length
//! for some malformed faces), drop triangles with out-of-range indices or non-finite positions,
//! compute normals where they are missing, and resolve texture paths as exporters write them
//! (Windows backslashes, options before the name, wrong letter case). Anything recoverable is a
//! warning with a fallback; anything else is one error naming the file and the problem.

use std::cell::RefCell;
use std::path::{Path, PathBuf};

use glam::Vec3;

use super::Bounds;
use crate::{Error, Result};

/// One vertex as the G-buffer pass reads it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub uv: [f32; 2],
}

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
struct TextureCache {
    by_path: std::collections::HashMap<PathBuf, TextureImage>,
    /// (length, hash) of the file's bytes: the same picture under another name.
    by_content: std::collections::HashMap<(usize, u64), TextureImage>,
    bytes: u64,
    budget: u64,
}

/// Surface description: Blinn-Phong with optional diffuse and specular maps.
#[derive(Clone, Debug)]
pub struct Material {
    pub name: String,
    /// Linear diffuse albedo (multiplies the diffuse map).
    pub diffuse: [f32; 3],
    /// Linear specular colour; the G-buffer keeps its mean as the specular strength.
    pub specular: [f32; 3],
    pub shininess: f32,
    pub diffuse_map: Option<TextureImage>,
    pub specular_map: Option<TextureImage>,
}

impl Material {
    pub fn plain(name: &str, diffuse: [f32; 3]) -> Self {
        Self { name: name.into(), diffuse, specular: [0.0; 3], shininess: 32.0, diffuse_map: None, specular_map: None }
    }

    pub fn is_textured(&self) -> bool {
        self.diffuse_map.is_some() || self.specular_map.is_some()
    }
}

/// A run of indices drawn with one material.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Part {
    pub first_index: u32,
    pub index_count: u32,
    pub material: usize,
}

/// Triangles ready for upload: one vertex and one index buffer, parts sorted by material.
#[derive(Clone, Debug)]
pub struct Model {
    pub name: String,
    pub vertices: Vec<Vertex>,
    pub indices: Vec<u32>,
    pub parts: Vec<Part>,
    pub materials: Vec<Material>,
    pub bounds: Bounds,
    /// What was repaired or replaced while loading, one line each.
    pub warnings: Vec<String>,
}

impl Model {
    /// Builds a model from triangles grouped by material (`groups[i]` are the triangles, as
    /// vertex triples, of `materials[i]`). Fails when there is nothing to draw.
    pub fn from_groups(name: &str, materials: Vec<Material>, groups: Vec<Vec<Vertex>>) -> Result<Self> {
        let mut vertices = Vec::new();
        let mut indices = Vec::new();
        let mut parts = Vec::new();
        for (material, triangles) in groups.into_iter().enumerate() {
            if triangles.is_empty() {
                continue;
            }
            let first_index = indices.len() as u32;
            for v in triangles {
                indices.push(vertices.len() as u32);
                vertices.push(v);
            }
            parts.push(Part { first_index, index_count: indices.len() as u32 - first_index, material });
        }
        let bounds = Bounds::from_points(vertices.iter().map(|v| Vec3::from(v.position)))
            .ok_or_else(|| Error::input(name, "no triangles with finite vertices"))?;
        Ok(Self { name: name.into(), vertices, indices, parts, materials, bounds, warnings: Vec::new() })
    }

    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    pub fn is_textured(&self) -> bool {
        self.materials.iter().any(Material::is_textured)
    }

    /// World-space triangle `i` as three positions.
    pub fn triangle(&self, i: usize) -> [Vec3; 3] {
        let p = |k: usize| Vec3::from(self.vertices[self.indices[3 * i + k] as usize].position);
        [p(0), p(1), p(2)]
    }

    /// Uniformly scales the model about the origin (the stability suite's scale cases).
    pub fn scaled(mut self, factor: f32) -> Self {
        for v in &mut self.vertices {
            v.position = (Vec3::from(v.position) * factor).into();
        }
        self.bounds = Bounds { min: self.bounds.min * factor, max: self.bounds.max * factor };
        self
    }
}

/// Reads text that may be UTF-8, UTF-16 (with a byte-order mark) or Latin-1.
pub fn decode_text(bytes: &[u8]) -> String {
    let utf16 = |le: bool| {
        let units: Vec<u16> = bytes[2..]
            .chunks_exact(2)
            .map(|c| if le { u16::from_le_bytes([c[0], c[1]]) } else { u16::from_be_bytes([c[0], c[1]]) })
            .collect();
        String::from_utf16_lossy(&units)
    };
    match bytes {
        [0xFF, 0xFE, ..] => utf16(true),
        [0xFE, 0xFF, ..] => utf16(false),
        [0xEF, 0xBB, 0xBF, rest @ ..] => String::from_utf8_lossy(rest).into_owned(),
        _ => match std::str::from_utf8(bytes) {
            Ok(text) => text.to_owned(),
            Err(_) => bytes.iter().map(|&b| b as char).collect(),
        },
    }
}

/// Pads colour statements that give one value (`Kd 0.5`, allowed by the format) to three, which
/// is what they mean, and drops colour statements tobj 4.0.5 would panic on (no value, two
/// values, or words that are not numbers). Returns the text and the number of lines dropped.
fn sanitize_mtl(text: &str) -> (String, usize) {
    let mut out = String::with_capacity(text.len() + 64);
    let mut dropped = 0;
    for line in text.lines() {
        let mut words = line.split_whitespace();
        let keyword = words.next().unwrap_or("");
        let values: Vec<&str> = words.collect();
        if matches!(keyword, "Ka" | "Kd" | "Ks" | "Ke" | "Tf") {
            let numeric = values.iter().take(3).all(|v| v.parse::<f32>().is_ok());
            match values.len() {
                1 if numeric => out.push_str(&format!("{keyword} {0} {0} {0}\n", values[0])),
                n if n >= 3 && numeric => {
                    out.push_str(line);
                    out.push('\n');
                }
                _ => dropped += 1,
            }
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    (out, dropped)
}

/// Drops face statements tobj would mishandle: a vertex reference of 0, one beyond the elements
/// defined so far (negative references count back from the last one), or a face whose vertices
/// disagree on which attributes they carry (`1/1 2//1`). tobj 4.0.5 overflows on some of these
/// and silently misreads others. Returns the text to parse and how many faces were dropped.
fn sanitize_obj(text: &str) -> (String, usize) {
    let mut counts = [0i64; 3];
    let mut dropped = 0;
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        let mut words = line.split_whitespace();
        let keyword = words.next().unwrap_or("");
        match keyword {
            "v" => counts[0] += 1,
            "vt" => counts[1] += 1,
            "vn" => counts[2] += 1,
            "f" => {
                let mut shape = None;
                let valid = words.all(|vertex| {
                    let parts: Vec<&str> = vertex.split('/').collect();
                    let form: Vec<bool> = parts.iter().map(|p| !p.is_empty()).collect();
                    let consistent = *shape.get_or_insert_with(|| form.clone()) == form;
                    let in_range = parts.iter().zip(counts).all(|(p, count)| {
                        p.is_empty()
                            || p.parse::<i64>().is_ok_and(|i| i != 0 && (if i > 0 { i <= count } else { -i <= count }))
                    });
                    consistent && parts.len() <= 3 && !parts[0].is_empty() && in_range
                });
                if !valid {
                    dropped += 1;
                    continue;
                }
            }
            _ => {}
        }
        out.push_str(line);
        out.push('\n');
    }
    (out, dropped)
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

fn load_texture(dir: &Path, argument: &str, cache: &mut TextureCache, warnings: &mut Vec<String>) -> TextureImage {
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

fn finite3(v: Option<[f32; 3]>, default: [f32; 3]) -> [f32; 3] {
    match v {
        Some(c) if c.iter().all(|x| x.is_finite()) => c.map(|x| x.clamp(0.0, 1.0)),
        _ => default,
    }
}

fn convert_material(m: &tobj::Material, dir: &Path, cache: &mut TextureCache, warnings: &mut Vec<String>) -> Material {
    Material {
        name: m.name.clone(),
        diffuse: finite3(m.diffuse, [0.8; 3]),
        specular: finite3(m.specular, [0.0; 3]),
        shininess: m.shininess.filter(|s| s.is_finite()).unwrap_or(32.0).clamp(1.0, 1024.0),
        diffuse_map: m.diffuse_texture.as_deref().map(|t| load_texture(dir, t, cache, warnings)),
        specular_map: m.specular_texture.as_deref().map(|t| load_texture(dir, t, cache, warnings)),
    }
}

/// Loads an OBJ file (and its MTL files and textures).
/// The largest OBJ read (a 5M-triangle model is about 400 MB) and the largest MTL.
pub const MAX_OBJ_BYTES: u64 = 1 << 30;
pub const MAX_MTL_BYTES: u64 = 64 << 20;

/// Checks that `path` is a regular file of at most `limit` bytes before anything opens it (a
/// FIFO would block the open, `/dev/zero` would never end, a sparse file of gigabytes would fill
/// memory), then reads at most that much. The error is the problem alone, for the caller to name
/// the file.
pub fn check_file(path: &Path, limit: u64) -> std::result::Result<(), String> {
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot read: {e}"))?;
    if meta.is_dir() {
        return Err("is a folder, not a file".into());
    }
    if !meta.is_file() {
        return Err("is not a regular file (a device, a FIFO or a socket)".into());
    }
    if meta.len() > limit {
        return Err(format!("is {} MiB; files over {} MiB are refused", meta.len() >> 20, limit >> 20));
    }
    Ok(())
}

fn read_bounded(path: &Path, limit: u64) -> std::result::Result<Vec<u8>, String> {
    use std::io::Read;
    check_file(path, limit)?;
    let mut bytes = Vec::new();
    let file = std::fs::File::open(path).map_err(|e| format!("cannot read: {e}"))?;
    file.take(limit + 1).read_to_end(&mut bytes).map_err(|e| format!("cannot read: {e}"))?;
    if bytes.len() as u64 > limit {
        return Err(format!("grew past {} MiB while being read", limit >> 20));
    }
    Ok(bytes)
}

pub fn load_obj(path: &Path) -> Result<Model> {
    load_obj_with_budget(path, TEXTURE_BUDGET_BYTES)
}

/// [`load_obj`] with another texture budget (decoded RGBA8 bytes for all textures together).
pub fn load_obj_with_budget(path: &Path, texture_budget: u64) -> Result<Model> {
    let bytes = read_bounded(path, MAX_OBJ_BYTES).map_err(|problem| Error::input(path, problem))?;
    if bytes.iter().all(|b| b.is_ascii_whitespace()) {
        return Err(Error::input(path, "the file is empty"));
    }
    let (text, bad_faces) = sanitize_obj(&decode_text(&bytes));
    let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let warnings = RefCell::new(Vec::new());

    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let material_loader = |mtl: &Path| {
        let mtl_path = dir.join(mtl.to_string_lossy().replace('\\', "/"));
        match read_bounded(&mtl_path, MAX_MTL_BYTES) {
            Ok(bytes) => {
                let (text, dropped) = sanitize_mtl(&decode_text(&bytes));
                if dropped > 0 {
                    warnings.borrow_mut().push(format!(
                        "{}: ignored {dropped} colour line(s) without one or three numbers",
                        mtl_path.display()
                    ));
                }
                tobj::load_mtl_buf(&mut text.as_bytes())
            }
            Err(e) => {
                warnings
                    .borrow_mut()
                    .push(format!("{}: cannot read material file ({e}); using a default material", mtl_path.display()));
                Err(tobj::LoadError::OpenFileFailed)
            }
        }
    };
    // A panic inside the parser is still a bad file, not a crash (the known ones are avoided by
    // `sanitize_obj`; this is the net under it).
    let parsed = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        tobj::load_obj_buf(&mut text.as_bytes(), &options, material_loader)
    }))
    .map_err(|_| Error::input(path, "malformed OBJ (the parser gave up on it)"))?;
    let (models, materials) = parsed.map_err(|e| Error::input(path, format!("malformed OBJ: {e}")))?;

    let mut warnings = warnings.into_inner();
    if bad_faces > 0 {
        warnings.push(format!(
            "dropped {bad_faces} face(s) with a vertex reference of 0, out of range, or in mixed formats"
        ));
    }
    let tobj_materials = materials.unwrap_or_else(|e| {
        if e != tobj::LoadError::OpenFileFailed {
            warnings.push(format!("{}: material file is malformed ({e}); using a default material", path.display()));
        }
        Vec::new()
    });
    let mut cache = TextureCache { budget: texture_budget, ..Default::default() };
    let mut materials: Vec<Material> =
        tobj_materials.iter().map(|m| convert_material(m, &dir, &mut cache, &mut warnings)).collect();
    let default_material = materials.len();
    materials.push(Material::plain("default", [0.8; 3]));

    let mut groups: Vec<Vec<Vertex>> = vec![Vec::new(); materials.len()];
    let mut dropped = 0usize;
    let mut flipped = 0usize;
    for model in &models {
        let mesh = &model.mesh;
        let count = mesh.positions.len() / 3;
        let has_normals = mesh.normals.len() == 3 * count;
        let has_uvs = mesh.texcoords.len() == 2 * count;
        if !mesh.normals.is_empty() && !has_normals {
            warnings.push(format!("object '{}': normal count does not match vertices; computing normals", model.name));
        }
        if !mesh.texcoords.is_empty() && !has_uvs {
            warnings.push(format!(
                "object '{}': texture coordinate count does not match vertices; ignoring them",
                model.name
            ));
        }
        let material = match mesh.material_id {
            Some(id) if id < default_material => id,
            Some(id) => {
                warnings
                    .push(format!("object '{}': material #{id} is not defined; using a default material", model.name));
                default_material
            }
            None => default_material,
        };
        for tri in mesh.indices.chunks_exact(3) {
            let idx = [tri[0] as usize, tri[1] as usize, tri[2] as usize];
            if idx.iter().any(|&i| i >= count) {
                dropped += 1;
                continue;
            }
            let pos = idx.map(|i| Vec3::from_slice(&mesh.positions[3 * i..3 * i + 3]));
            // Beyond 1e12 from the origin, f32 keeps no precision the depth buffer could use.
            if !pos.iter().all(|p| p.is_finite() && p.abs().max_element() <= 1e12) {
                dropped += 1;
                continue;
            }
            let (e1, e2) = (pos[1] - pos[0], pos[2] - pos[0]);
            let cross = e1.cross(e2);
            let mut face_normal = cross.try_normalize().unwrap_or(Vec3::Y);
            // A sliver (a sphere's pole) has no trustworthy winding: it is left as it is.
            let well_shaped = cross.length() > 1e-4 * e1.length_squared().max(e2.length_squared());
            // The supplied normals say which side is out; the winding is often an accident
            // (left-handed exporters, mirrored objects). Where they disagree, the winding yields.
            let mut order = [0, 1, 2];
            if has_normals {
                let supplied: Vec3 = idx.iter().map(|&i| Vec3::from_slice(&mesh.normals[3 * i..3 * i + 3])).sum();
                if well_shaped && supplied.is_finite() && face_normal.dot(supplied) < 0.0 {
                    order = [0, 2, 1];
                    face_normal = -face_normal;
                    flipped += 1;
                }
            }
            for k in order {
                let i = idx[k];
                let normal = if has_normals {
                    Vec3::from_slice(&mesh.normals[3 * i..3 * i + 3]).try_normalize().unwrap_or(face_normal)
                } else {
                    face_normal
                };
                // OBJ puts v = 0 at the bottom of the image; textures start at the top row.
                let uv = if has_uvs { [mesh.texcoords[2 * i], 1.0 - mesh.texcoords[2 * i + 1]] } else { [0.0, 0.0] };
                let uv = if uv.iter().all(|x| x.is_finite()) { uv } else { [0.0, 0.0] };
                groups[material].push(Vertex { position: pos[k].into(), normal: normal.into(), uv });
            }
        }
    }
    if dropped > 0 {
        warnings.push(format!(
            "dropped {dropped} triangle(s) with out-of-range indices, or positions non-finite or beyond 1e12"
        ));
    }
    if flipped > 0 {
        warnings.push(format!("reversed the winding of {flipped} triangle(s) to agree with their normals"));
    }
    if groups.iter().all(Vec::is_empty) {
        return Err(Error::input(path, "no triangles to draw (no faces, or only points and lines)"));
    }
    let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "model".into());
    let mut out = Model::from_groups(&name, materials, groups)
        .map_err(|_| Error::input(path, "no triangles with finite vertices"))?;
    for w in &warnings {
        log::warn!("{}: {w}", path.display());
    }
    out.warnings = warnings;
    Ok(out)
}
