//! glTF 2.0 models (`.gltf` with external or embedded buffers, and `.glb`) through the `gltf`
//! crate, with the same rules as OBJ: repairs are warnings, a missing texture is a checker, a
//! broken file is one error naming it, and the budgets hold.
//!
//! The default scene's node hierarchy is walked with its transforms, and every primitive of
//! triangle mode is drawn. Materials are metallic-roughness, mapped to the G-buffer's
//! Blinn-Phong terms:
//!
//! * diffuse albedo = base colour × (1 − metallic) (a metal has no diffuse), times the base
//!   colour texture (sRGB);
//! * specular strength = 0.04 (a dielectric's reflectance at normal incidence) blended towards
//!   the base colour's mean by metallic;
//! * shininess = 2/α² − 2 with α = roughness² (the Blinn-Phong exponent of the same highlight
//!   width as a Beckmann lobe of that roughness), clamped to 1-1024.
//!
//! The normal texture (tangent space, with its `scale`) is read in the frame of the `TANGENT`
//! attribute, or of MikkTSpace tangents where a primitive has none, as glTF asks. `alphaMode`
//! `MASK` cuts texels whose base colour alpha (texture × factor) is below `alphaCutoff` (0.5 by
//! default); `BLEND` is drawn as a mask at 0.5, with a warning (a deferred G-buffer holds one
//! surface a pixel). Every face is drawn two-sided, lit on the side the camera sees, whatever
//! `doubleSided` says.
//!
//! Metallic-roughness, occlusion and emissive textures are not read; a model that has them says
//! so once.

use std::path::Path;

use glam::{Mat4, Vec3};

use super::files::{read_bounded, ModelFolder};
use super::finish::finish;
use super::gltf_data::{check_references, read_images, BufferPlan, Picture, MAX_GLTF_BYTES};
use super::gltf_mesh::build_groups;
use super::model::{Cutout, Material, Model, NormalMap};
use super::texture::{room_for_maps, TextureCache, TextureImage};
use crate::budget::{self, Share};
use crate::{Error, Result};

/// Nodes deeper than this below a root are not walked (the hierarchy of a real scene is a few
/// levels; a file whose nodes form a cycle would recurse for ever).
const MAX_DEPTH: usize = 64;

/// Whether `path` names a glTF file by its extension.
pub fn is_gltf(path: &Path) -> bool {
    super::files::has_extension(path, super::files::MODEL_FORMATS[1].1)
}

/// Loads a glTF 2.0 file with its buffers and base colour textures. Everything it names is read
/// from its own folder, within the memory budget; a panic in the reading (the `gltf` crate's, or
/// ours) is a bad file, not a crash.
pub fn load(path: &Path, texture_room: u64) -> Result<Model> {
    crate::guard::catch(|| load_unguarded(path, texture_room))
        .unwrap_or_else(|panic| Err(Error::input(path, format!("malformed glTF (reading it failed: {panic})"))))
}

fn load_unguarded(path: &Path, texture_room: u64) -> Result<Model> {
    let input = |problem: String| Error::input(path, problem);
    let size = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
    budget::check(Share::Geometry, size, || "the file".into()).map_err(input)?;
    let bytes = read_bounded(path, MAX_GLTF_BYTES).map_err(input)?;
    let (document, blob) = parse(&bytes).map_err(input)?;
    drop(bytes);
    let folder = ModelFolder::of(path);
    let mut warnings = Vec::new();

    // Sized before anything is read: the triangles every instance draws, and the buffers.
    let instances = mesh_instances(&document, &mut warnings);
    let triangles: u64 =
        instances.iter().flat_map(|(mesh, _)| mesh.primitives()).map(|p| primitive_triangles(&p)).sum();
    let plan = BufferPlan::new(&document, &folder, blob.as_ref()).map_err(input)?;
    let needed = triangles.saturating_mul(budget::BYTES_PER_TRIANGLE).saturating_add(plan.bytes);
    budget::check(Share::Geometry, needed, || {
        format!(
            "{triangles} triangles ({} instances) and {} of buffers",
            instances.len(),
            budget::format_bytes(plan.bytes)
        )
    })
    .map_err(|problem| with_notes(input(problem), &warnings))?;
    let lengths: Vec<usize> = document.buffers().map(|b| b.length()).collect();
    let buffers = plan.read(&folder, blob, &lengths).map_err(input)?;

    // The base colour and normal pictures, read once each and planned together within the
    // texture room.
    let used: std::collections::BTreeSet<usize> = document
        .materials()
        .flat_map(|m| {
            let base = m.pbr_metallic_roughness().base_color_texture().map(|info| info.texture().source().index());
            base.into_iter().chain(m.normal_texture().map(|info| info.texture().source().index()))
        })
        .collect();
    let room = room_for_maps(document.materials().len() + 1, used.len(), texture_room).map_err(input)?;
    let pictures = read_images(&document, &used, &folder, &buffers);
    let mut cache = TextureCache::plan_pictures(
        pictures.iter().flatten().filter_map(|(_, bytes)| bytes.as_deref().ok().map(Vec::as_slice)),
        room,
    );
    let materials = document.materials().map(|m| convert_material(&m, &pictures, &mut cache, &mut warnings));
    let mut materials: Vec<Material> = materials.collect();
    let default_material = materials.len();
    materials.push(Material::plain("default", [0.8; 3]));

    let (groups, tangents) = build_groups(&instances, &buffers, default_material, materials.len(), &mut warnings)
        .map_err(|problem| with_notes(input(problem), &warnings))?;
    finish(path, materials, groups, Some(tangents.concat()), warnings)
}

/// The document, its references checked before the crate validates it (its validation indexes
/// a primitive's position accessor unchecked), and the `.glb`'s binary chunk.
fn parse(bytes: &[u8]) -> std::result::Result<(::gltf::Document, Option<Vec<u8>>), String> {
    let ::gltf::Gltf { document, blob } =
        ::gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| refusal(bytes, &e))?;
    let json = document.into_json();
    check_references(&json)?;
    let document = ::gltf::Document::from_json(json).map_err(|e| refusal(bytes, &e))?;
    Ok((document, blob))
}

/// The triangles a primitive draws, from its accessor counts.
fn primitive_triangles(p: &::gltf::Primitive) -> u64 {
    let count = p.indices().or_else(|| p.get(&::gltf::Semantic::Positions)).map_or(0, |a| a.count() as u64);
    if p.mode() == ::gltf::mesh::Mode::Triangles {
        count / 3
    } else {
        count
    }
}

/// An input error with what the walk noted before it (a node graph cut short, say), which is
/// often its cause.
fn with_notes(error: Error, notes: &[String]) -> Error {
    match error {
        Error::Input { path, problem } if !notes.is_empty() => {
            Error::Input { path, problem: format!("{problem} (also: {})", notes.join("; ")) }
        }
        other => other,
    }
}

/// Blinn-Phong shininess for a metallic-roughness roughness (see the module's notes).
pub fn shininess(roughness: f32) -> f32 {
    let alpha = roughness.clamp(0.0, 1.0).powi(2).max(1e-3);
    (2.0 / (alpha * alpha) - 2.0).clamp(1.0, 1024.0)
}

fn convert_material(
    m: &::gltf::Material,
    pictures: &[Option<Picture>],
    cache: &mut TextureCache,
    warnings: &mut Vec<String>,
) -> Material {
    // A name is shown in messages and the panel: one line of bounded length.
    let name = m.name().map_or_else(|| format!("material {}", m.index().unwrap_or(0)), crate::text::bounded_name);
    let pbr = m.pbr_metallic_roughness();
    let finite = |x: f32, default: f32| if x.is_finite() { x.clamp(0.0, 1.0) } else { default };
    let [r, g, b, alpha] = pbr.base_color_factor().map(|c| finite(c, 1.0));
    let base = Vec3::new(r, g, b);
    let metallic = finite(pbr.metallic_factor(), 1.0);
    let roughness = finite(pbr.roughness_factor(), 1.0);
    let specular = 0.04 + (base.element_sum() / 3.0 - 0.04) * metallic;
    let mut picture = |index: usize, what_for: &str, fallback: &str| match &pictures[index] {
        Some((what, Ok(bytes))) => cache.decode_or(what, bytes, fallback, warnings),
        Some((_, Err(problem))) => {
            warnings.push(format!("material '{name}': {what_for}: {problem}; {fallback}"));
            None
        }
        None => unreachable!("every picture a material names was read"),
    };
    let diffuse_map = pbr.base_color_texture().map(|info| {
        picture(info.texture().source().index(), "base colour texture", "using a checker")
            .unwrap_or_else(TextureImage::checker)
    });
    let normal_map = m.normal_texture().and_then(|info| {
        let image = picture(info.texture().source().index(), "normal texture", "the surface keeps its vertex normals")?;
        Some((image, info.scale()))
    });
    let normal_map = normal_map.map(|(image, scale)| {
        let what = format!("material '{name}': normalTexture.scale {}", crate::text::num(scale));
        NormalMap { image, scale: NormalMap::checked_scale(scale, &what, warnings) }
    });
    let cutoff = m.alpha_cutoff().filter(|c| c.is_finite()).unwrap_or(0.5);
    let cutout = match m.alpha_mode() {
        ::gltf::material::AlphaMode::Opaque => None,
        ::gltf::material::AlphaMode::Mask => Some(Cutout { mask: diffuse_map.clone(), factor: alpha, cutoff }),
        ::gltf::material::AlphaMode::Blend => {
            warnings.push(format!(
                "material '{name}': alphaMode BLEND is drawn as a mask at 0.5 (the G-buffer holds one surface a pixel)"
            ));
            Some(Cutout { mask: diffuse_map.clone(), factor: alpha, cutoff: 0.5 })
        }
    };
    let unread: Vec<&str> = [
        (pbr.metallic_roughness_texture().is_some(), "metallic-roughness texture"),
        (m.occlusion_texture().is_some(), "occlusion texture"),
        (m.emissive_texture().is_some() || m.emissive_factor() != [0.0; 3], "emission"),
    ]
    .into_iter()
    .filter_map(|(present, what)| present.then_some(what))
    .collect();
    if !unread.is_empty() {
        warnings.push(format!("material '{name}': not rendered: {}", unread.join(", ")));
    }
    Material {
        name,
        diffuse: (base * (1.0 - metallic)).into(),
        specular: [specular; 3],
        shininess: shininess(roughness),
        diffuse_map,
        specular_map: None,
        normal_map,
        cutout,
    }
}

/// Every mesh the default scene (or else the first) draws, with its node's world transform.
/// glTF's nodes form trees: a node reached a second time (a repeated child, a cycle, a node under
/// two parents) is placed once, so a file of a few nodes cannot multiply into millions of
/// instances; the walk visits each node at most once.
fn mesh_instances<'a>(document: &'a ::gltf::Document, warnings: &mut Vec<String>) -> Vec<(::gltf::Mesh<'a>, Mat4)> {
    let roots: Vec<::gltf::Node> = match document.default_scene().or_else(|| document.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        // No scene: every node that is no other's child.
        None => {
            let children: std::collections::HashSet<usize> =
                document.nodes().flat_map(|n| n.children().map(|c| c.index())).collect();
            document.nodes().filter(|n| !children.contains(&n.index())).collect()
        }
    };
    let mut out = Vec::new();
    let (mut too_deep, mut repeated) = (false, 0usize);
    let mut placed = std::collections::HashSet::new();
    let mut stack: Vec<(::gltf::Node, Mat4, usize)> = roots.into_iter().map(|n| (n, Mat4::IDENTITY, 0)).collect();
    while let Some((node, parent, depth)) = stack.pop() {
        if depth > MAX_DEPTH {
            too_deep = true;
            continue;
        }
        if !placed.insert(node.index()) {
            repeated += 1;
            continue;
        }
        let local = Mat4::from_cols_array_2d(&node.transform().matrix());
        let world = parent * local;
        if let Some(mesh) = node.mesh() {
            out.push((mesh, world));
        }
        stack.extend(node.children().map(|c| (c, world, depth + 1)));
    }
    if too_deep {
        warnings.push(format!("nodes nested deeper than {MAX_DEPTH} levels were left out"));
    }
    if repeated > 0 {
        warnings.push(format!(
            "{repeated} reference(s) to a node already placed (a repeated child, a cycle, or a node under two \
             parents) left out: glTF's nodes form trees, and each is drawn once"
        ));
    }
    out
}

/// The line for a file the crate refuses: the extensions it needs when it names some this
/// program does not read (a Draco-compressed mesh fails validation for want of its accessors'
/// views, which says little), else the crate's own words.
fn refusal(bytes: &[u8], error: &::gltf::Error) -> String {
    let required: Vec<String> = ::gltf::Gltf::from_slice_without_validation(bytes)
        .map(|g| g.document.extensions_required().map(str::to_string).collect())
        .unwrap_or_default();
    if required.is_empty() {
        format!("malformed glTF: {error}")
    } else {
        format!("needs the glTF extension(s) {}, which this program does not read", required.join(", "))
    }
}
