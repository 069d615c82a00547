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
use std::path::Path;

use glam::Vec3;

use super::files::{check_file, other_model_kind, read_bounded, ModelFolder};
use super::finish::{finish, NO_TRIANGLES};
use super::model::{Cutout, Material, Model, NormalMap, Vertex};
use super::obj_text::{count_obj, decode_text, sanitize_mtl, sanitize_obj};
use super::texture::{load_texture, room_for_maps, texture_option, try_load_texture, TextureCache, TextureImage};
use super::triangle::{push_triangle, Triangle};
use crate::budget::{self, Share};
use crate::{Error, Result};

fn finite3(v: Option<[f32; 3]>, default: [f32; 3]) -> [f32; 3] {
    match v {
        Some(c) if c.iter().all(|x| x.is_finite()) => c.map(|x| x.clamp(0.0, 1.0)),
        _ => default,
    }
}

/// The material `m` describes; `warnings` gets what was wrong, `read` what each normal map was
/// read from.
fn convert_material(
    m: &tobj::Material,
    folder: &ModelFolder,
    cache: &mut TextureCache,
    (warnings, read): (&mut Vec<String>, &mut Vec<String>),
) -> Material {
    Material {
        name: m.name.clone(),
        diffuse: finite3(m.diffuse, [0.8; 3]),
        specular: finite3(m.specular, [0.0; 3]),
        shininess: m.shininess.filter(|s| s.is_finite()).unwrap_or(32.0).clamp(1.0, 1024.0),
        diffuse_map: m.diffuse_texture.as_deref().map(|t| load_texture(folder, t, cache, warnings)),
        specular_map: m.specular_texture.as_deref().map(|t| load_texture(folder, t, cache, warnings)),
        normal_map: normal_map(m, folder, cache, warnings, read),
        cutout: cutout(m, folder, cache, warnings),
    }
}

/// The statements that may name a normal map, the explicit one first: `norm`, then `map_Bump`
/// or `bump` (which tobj keeps as one), which exporters use for normal and height maps alike.
fn normal_statements(m: &tobj::Material) -> Vec<(&'static str, &str)> {
    let norm = m.unknown_param.get("norm").map(|a| ("norm", a.as_str()));
    let bump = m.normal_texture.as_deref().map(|a| ("map_Bump", a));
    norm.into_iter().chain(bump).collect()
}

/// The material's tangent-space normal map: the first statement that names a readable picture
/// in colour. A grey picture is a height map (Sponza ships both kinds under `map_Bump`), which
/// is not read; it is said which statement was taken and what was left out. `-bm` is the scale.
fn normal_map(
    m: &tobj::Material,
    folder: &ModelFolder,
    cache: &mut TextureCache,
    warnings: &mut Vec<String>,
    read: &mut Vec<String>,
) -> Option<NormalMap> {
    let statements = normal_statements(m);
    let mut taken: Option<(&str, &str, NormalMap)> = None;
    for (key, argument) in statements {
        if let Some((taken_key, taken_argument, _)) = &taken {
            warnings.push(format!(
                "material '{}': {key} {argument} left out: the normal map is {taken_key} {taken_argument}",
                m.name
            ));
            continue;
        }
        let fallback = "the surface keeps its vertex normals";
        let Some(image) = try_load_texture(folder, argument, cache, fallback, warnings) else { continue };
        if image.is_greyscale() {
            warnings.push(format!(
                "material '{}': {key} {argument} is a height map (a grey picture), not a normal map: height maps \
                 are not read",
                m.name
            ));
            continue;
        }
        let scale = match texture_option(argument, "-bm") {
            None => 1.0,
            Some(word) => {
                let what = format!("material '{}': -bm {word}", m.name);
                match word.parse::<f32>() {
                    Ok(scale) => NormalMap::checked_scale(scale, &what, warnings),
                    Err(_) => {
                        warnings.push(format!("{what} is not a number; the normal map is read at scale 1"));
                        1.0
                    }
                }
            }
        };
        read.push(format!("material '{}': normal map from {key} {argument} (scale {scale})", m.name));
        taken = Some((key, argument, NormalMap { image, scale }));
    }
    taken.map(|(_, _, map)| map)
}

/// The material's alpha cutout from `map_d`: coverage from the picture's alpha where it has one
/// (often the colour map's own RGBA file, then shared with it), else from its luminance (a grey
/// mask). Coverage below one half is a hole. A mask that cannot be read leaves the surface opaque.
fn cutout(
    m: &tobj::Material,
    folder: &ModelFolder,
    cache: &mut TextureCache,
    warnings: &mut Vec<String>,
) -> Option<Cutout> {
    let argument = m.dissolve_texture.as_deref()?;
    let image = try_load_texture(folder, argument, cache, "the surface stays opaque", warnings)?;
    let mask = if image.has_alpha() { image } else { TextureImage::luminance_as_alpha(&image) };
    Some(Cutout { mask: Some(mask), factor: 1.0, cutoff: 0.5 })
}

/// The largest OBJ read (a 5M-triangle model is about 400 MB) and the largest MTL.
pub const MAX_OBJ_BYTES: u64 = 1 << 30;
pub const MAX_MTL_BYTES: u64 = 64 << 20;

/// Loads an OBJ file, its materials and textures within the run's memory budget.
pub fn load_obj(path: &Path) -> Result<Model> {
    load_obj_with_budget(path, budget::texture_room())
}

/// [`load_obj`] with another room for textures (decoded RGBA8 bytes for all of them together).
pub fn load_obj_with_budget(path: &Path, texture_room: u64) -> Result<Model> {
    let input = |problem: String| Error::input(path, problem);
    if let Some(kind) = other_model_kind(path) {
        return Err(input(format!("a {kind} file; models load from {}", super::files::model_formats())));
    }
    check_size(path).map_err(input)?;
    let bytes = read_bounded(path, MAX_OBJ_BYTES).map_err(input)?;
    let (text, bad_faces) = sanitize_obj(&decode_text(&bytes));
    let folder = ModelFolder::of(path);
    let (models, tobj_materials, mut warnings) = parse(&text, &folder).map_err(input)?;
    if bad_faces > 0 {
        warnings.push(format!(
            "dropped {bad_faces} face(s) with a vertex reference of 0, out of range, or in mixed formats"
        ));
    }
    let mut tobj_materials = tobj_materials.unwrap_or_else(|e| {
        if e != tobj::LoadError::OpenFileFailed {
            warnings.push(format!("{}: material file is malformed ({e}); using a default material", path.display()));
        }
        Vec::new()
    });
    // A name is shown in messages and the panel: one line of bounded length.
    for m in &mut tobj_materials {
        m.name = crate::text::bounded_name(&m.name);
    }
    let maps = tobj_materials.iter().flat_map(|m| {
        let colour = [m.diffuse_texture.as_deref(), m.specular_texture.as_deref(), m.dissolve_texture.as_deref()];
        colour.into_iter().flatten().chain(normal_statements(m).into_iter().map(|(_, argument)| argument))
    });
    let distinct = maps.clone().collect::<std::collections::HashSet<&str>>().len();
    let room = room_for_maps(tobj_materials.len() + 1, distinct, texture_room).map_err(input)?;
    let mut cache = TextureCache::plan(&folder, maps, room);
    // What each normal map was read from: logged once for the load, capped.
    let mut read = Vec::new();
    let mut materials: Vec<Material> =
        tobj_materials.iter().map(|m| convert_material(m, &folder, &mut cache, (&mut warnings, &mut read))).collect();
    super::finish::log_capped(log::Level::Info, path, &read);
    let default_material = materials.len();
    materials.push(Material::plain("default", [0.8; 3]));
    let groups = build_groups(&models, default_material, &mut warnings);
    finish(path, materials, groups, None, warnings)
}

/// Sizes the file before it is read: the triangles its faces make, counted from a stream of
/// it, against the geometry's share of the budget; the problem when it is refused.
fn check_size(path: &Path) -> std::result::Result<(), String> {
    check_file(path, MAX_OBJ_BYTES)?;
    let counts = count_obj(path).map_err(|e| format!("cannot read: {e}"))?;
    if !counts.has_content {
        let nothing = if counts.zero_bytes > 0 { "holds only zero bytes, no text" } else { "the file is empty" };
        return Err(nothing.into());
    }
    if counts.triangles == 0 {
        return Err(NO_TRIANGLES.into());
    }
    let file_bytes = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
    // The file is held three times while it is parsed: as read, as text, and cleaned.
    let needed = counts.triangles.saturating_mul(budget::BYTES_PER_TRIANGLE).saturating_add(3 * file_bytes);
    budget::check(Share::Geometry, needed, || format!("{} triangles", counts.triangles))
}

type Parsed = (Vec<tobj::Model>, std::result::Result<Vec<tobj::Material>, tobj::LoadError>, Vec<String>);

/// The OBJ's objects and its materials (from the model's folder), by tobj, with the warnings of
/// the MTL's reading; a panic inside the parser is still a bad file, not a crash (the known ones
/// are avoided by `sanitize_obj`; the guard is the net under it).
fn parse(text: &str, folder: &ModelFolder) -> std::result::Result<Parsed, String> {
    let warnings = RefCell::new(Vec::new());
    let options = tobj::LoadOptions { triangulate: true, single_index: true, ignore_points: true, ignore_lines: true };
    let material_loader = |mtl: &Path| match folder.read(&mtl.to_string_lossy(), MAX_MTL_BYTES) {
        Ok((mtl_path, bytes)) => {
            let (text, dropped) = sanitize_mtl(&decode_text(&bytes));
            if dropped > 0 {
                warnings.borrow_mut().push(format!(
                    "{}: ignored {dropped} colour line(s) without one or three numbers",
                    mtl_path.display()
                ));
            }
            tobj::load_mtl_buf(&mut text.as_bytes())
        }
        Err(problem) => {
            warnings.borrow_mut().push(format!("material file {problem}; using a default material"));
            Err(tobj::LoadError::OpenFileFailed)
        }
    };
    let parsed = crate::guard::catch(|| tobj::load_obj_buf(&mut text.as_bytes(), &options, material_loader))
        .map_err(|_| "malformed OBJ (the parser gave up on it)".to_string())?;
    let (models, materials) = parsed.map_err(|e| format!("malformed OBJ: {e}"))?;
    Ok((models, materials, warnings.into_inner()))
}

/// Every object's triangles, grouped by material (`default_material` where an object names
/// none, or one that is not defined), with what was repaired on the way as warnings.
fn build_groups(models: &[tobj::Model], default_material: usize, warnings: &mut Vec<String>) -> Vec<Vec<Vertex>> {
    let mut groups: Vec<Vec<Vertex>> = vec![Vec::new(); default_material + 1];
    let (mut dropped, mut flipped) = (0usize, 0usize);
    for model in models {
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
            let normals = has_normals.then(|| idx.map(|i| Vec3::from_slice(&mesh.normals[3 * i..3 * i + 3])));
            // OBJ puts v = 0 at the bottom of the image; textures start at the top row.
            let uvs =
                idx.map(|i| if has_uvs { [mesh.texcoords[2 * i], 1.0 - mesh.texcoords[2 * i + 1]] } else { [0.0; 2] });
            match push_triangle(pos, normals, uvs, &mut groups[material]) {
                Triangle::Kept => {}
                Triangle::Flipped => flipped += 1,
                Triangle::Dropped => dropped += 1,
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
    groups
}
