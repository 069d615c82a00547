//! A glTF file's meshes as triangles: every instance's primitives read (each accessor checked
//! before the crate's reader trusts it), placed in the world, and grouped by material.

use std::rc::Rc;

use glam::{Mat3, Mat4, Vec3};

use super::gltf_data::{accessor_fits, Kind, INDEX_KINDS, UV_KINDS, VEC3_KINDS, VEC4_KINDS};
use super::model::Vertex;
use super::triangle::{push_triangle, Triangle};

/// The triangles of every instance's primitives, grouped by material, and beside each group's
/// vertices their tangents from the file (w = 0 where it gives none).
pub(super) type Groups = (Vec<Vec<Vertex>>, Vec<Vec<[f32; 4]>>);

pub(super) fn build_groups(
    instances: &[(::gltf::Mesh, Mat4)],
    buffers: &[Rc<Vec<u8>>],
    default_material: usize,
    material_count: usize,
    warnings: &mut Vec<String>,
) -> std::result::Result<Groups, String> {
    let mut groups: Vec<Vec<Vertex>> = vec![Vec::new(); material_count];
    let mut tangents: Vec<Vec<[f32; 4]>> = vec![Vec::new(); material_count];
    let mut tally = Tally::default();
    for (mesh, world) in instances {
        if !world.is_finite() {
            tally.unreadable += mesh.primitives().len();
            continue;
        }
        let place = Placement {
            world: *world,
            tangents: Mat3::from_mat4(*world),
            normals: normal_matrix(world),
            // A mirroring transform turns the winding around (glTF's rule for negative determinants).
            mirrored: world.determinant() < 0.0,
        };
        for primitive in mesh.primitives() {
            let material = primitive.material().index().filter(|&i| i < default_material).unwrap_or(default_material);
            match read_primitive(&primitive, &place, buffers) {
                Read::Triangles(primitive) => {
                    primitive.push_into(&mut groups[material], &mut tangents[material], &mut tally)
                }
                Read::Empty => {}
                Read::NotTriangles => tally.skipped += 1,
                Read::Unreadable => tally.unreadable += 1,
            }
        }
    }
    if groups.iter().all(Vec::is_empty) && tally.unreadable > 0 {
        return Err(format!(
            "none of its primitives could be read ({} with positions or indices of the wrong type, or outside their buffers)",
            tally.unreadable
        ));
    }
    for (n, what) in [
        (tally.dropped, "triangle(s) with out-of-range indices, or positions non-finite or beyond 1e12 dropped"),
        (tally.flipped, "triangle(s) reversed in winding to agree with their normals"),
        (tally.skipped, "primitive(s) of points or lines left out"),
        (tally.unreadable, "primitive(s) whose positions or indices could not be read left out"),
    ] {
        if n > 0 {
            warnings.push(format!("{n} {what}"));
        }
    }
    Ok((groups, tangents))
}

/// What became of the triangles and primitives read, for the warnings.
#[derive(Default)]
struct Tally {
    dropped: usize,
    flipped: usize,
    skipped: usize,
    unreadable: usize,
}

/// Where an instance's primitives go: its world transform, the matrix for its normals, and
/// whether it mirrors.
struct Placement {
    world: Mat4,
    /// Carries tangents (directions on the surface).
    tangents: Mat3,
    normals: Mat3,
    mirrored: bool,
}

/// One primitive's vertices in world space, and its triangles as index triples.
struct Primitive {
    positions: Vec<Vec3>,
    normals: Option<Vec<Vec3>>,
    uvs: Option<Vec<[f32; 2]>>,
    /// `TANGENT`, in world space (w = 0 for one that is not finite).
    tangents: Option<Vec<[f32; 4]>>,
    triangles: Vec<[u32; 3]>,
    mirrored: bool,
}

enum Read {
    Triangles(Primitive),
    /// No positions or no indices: nothing to draw, nothing to say.
    Empty,
    /// Points or lines.
    NotTriangles,
    /// Positions or indices of the wrong type, or outside their buffers.
    Unreadable,
}

/// A primitive's vertices and triangles, each accessor checked before the crate's reader trusts
/// it (it asserts on a mismatch).
fn read_primitive(primitive: &::gltf::Primitive, place: &Placement, buffers: &[Rc<Vec<u8>>]) -> Read {
    use ::gltf::mesh::Mode;
    if !matches!(primitive.mode(), Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
        return Read::NotTriangles;
    }
    let uv_set = primitive.material().pbr_metallic_roughness().base_color_texture().map_or(0, |t| t.tex_coord());
    let fits = |accessor: Option<::gltf::Accessor>, kinds: &[Kind]| {
        accessor.is_some_and(|a| accessor_fits(&a, kinds, buffers))
    };
    let positions = primitive.get(&::gltf::Semantic::Positions);
    if positions.as_ref().is_some_and(|p| p.count() == 0) || primitive.indices().is_some_and(|i| i.count() == 0) {
        return Read::Empty;
    }
    let indices_fit = primitive.indices().is_none_or(|a| accessor_fits(&a, INDEX_KINDS, buffers));
    if !fits(positions, VEC3_KINDS) || !indices_fit {
        return Read::Unreadable;
    }
    let has_normals = fits(primitive.get(&::gltf::Semantic::Normals), VEC3_KINDS);
    let has_uvs = fits(primitive.get(&::gltf::Semantic::TexCoords(uv_set)), UV_KINDS);
    let has_tangents = fits(primitive.get(&::gltf::Semantic::Tangents), VEC4_KINDS);
    let reader = primitive.reader(|b| buffers.get(b.index()).map(|data| data.as_slice()));
    let Some(positions) = reader.read_positions() else { return Read::Unreadable };
    let positions: Vec<Vec3> = positions.map(|p| place.world.transform_point3(Vec3::from(p))).collect();
    let count = positions.len();
    let normals: Option<Vec<Vec3>> = has_normals
        .then(|| reader.read_normals())
        .flatten()
        .map(|n| n.map(|n| place.normals * Vec3::from(n)).collect::<Vec<_>>())
        .filter(|n| n.len() == count);
    let uvs: Option<Vec<[f32; 2]>> = has_uvs
        .then(|| reader.read_tex_coords(uv_set))
        .flatten()
        .map(|t| t.into_f32().collect::<Vec<_>>())
        .filter(|t| t.len() == count);
    // A mirroring transform turns the bitangent's handedness around with the winding.
    let handedness = if place.mirrored { -1.0 } else { 1.0 };
    let tangents: Option<Vec<[f32; 4]>> = has_tangents
        .then(|| reader.read_tangents())
        .flatten()
        .map(|t| {
            t.map(|[x, y, z, w]| {
                let t = place.tangents * Vec3::new(x, y, z);
                match t.try_normalize() {
                    Some(t) if w.is_finite() && w != 0.0 => [t.x, t.y, t.z, w.signum() * handedness],
                    _ => [0.0; 4],
                }
            })
            .collect::<Vec<_>>()
        })
        .filter(|t| t.len() == count);
    let indices: Vec<u32> = match reader.read_indices() {
        Some(indices) => indices.into_u32().collect(),
        None if primitive.indices().is_some() => return Read::Unreadable,
        None => (0..count as u32).collect(),
    };
    let triangles = triangle_list(primitive.mode(), &indices);
    Read::Triangles(Primitive { positions, normals, uvs, tangents, triangles, mirrored: place.mirrored })
}

impl Primitive {
    /// Appends its triangles to `group`, and their tangents to `tangents` (those with an index out
    /// of range dropped).
    fn push_into(&self, group: &mut Vec<Vertex>, tangents: &mut Vec<[f32; 4]>, tally: &mut Tally) {
        let count = self.positions.len();
        for tri in &self.triangles {
            let mut idx = tri.map(|i| i as usize);
            if idx.iter().any(|&i| i >= count) {
                tally.dropped += 1;
                continue;
            }
            if self.mirrored {
                idx.swap(1, 2);
            }
            let normals = self.normals.as_ref().map(|n| idx.map(|i| n[i]));
            let uv = idx.map(|i| self.uvs.as_ref().map_or([0.0; 2], |t| t[i]));
            let given = idx.map(|i| self.tangents.as_ref().map_or([0.0; 4], |t| t[i]));
            match push_triangle(idx.map(|i| self.positions[i]), normals, uv, group) {
                Triangle::Kept => tangents.extend(given),
                Triangle::Flipped => {
                    tally.flipped += 1;
                    tangents.extend([given[0], given[2], given[1]]);
                }
                Triangle::Dropped => tally.dropped += 1,
            }
        }
    }
}

/// The matrix that carries normals through `world`: its cofactor matrix (the inverse transpose
/// times the determinant, with the determinant's sign kept so normals stay outward), computed in
/// f64 from the matrix scaled to a largest element of 1. It survives scales of 1e-20 and 1e20,
/// where the inverse underflows or overflows in f32, and flattening ones, which have none.
fn normal_matrix(world: &Mat4) -> Mat3 {
    let m = glam::DMat3::from_mat4(world.as_dmat4());
    let largest = m.to_cols_array().iter().fold(0.0f64, |a, x| a.max(x.abs()));
    if !(largest > 0.0 && largest.is_finite()) {
        return Mat3::IDENTITY;
    }
    let m = m * (1.0 / largest);
    let cofactor = glam::DMat3::from_cols(m.y_axis.cross(m.z_axis), m.z_axis.cross(m.x_axis), m.x_axis.cross(m.y_axis));
    let sign = if m.determinant() < 0.0 { -1.0 } else { 1.0 };
    let biggest = cofactor.to_cols_array().iter().fold(0.0f64, |a, x| a.max(x.abs()));
    if biggest > 0.0 {
        (cofactor * (sign / biggest)).as_mat3()
    } else {
        Mat3::IDENTITY
    }
}

/// A primitive's triangles as index triples: a list as it is, a strip with every other triangle
/// turned to keep the winding, a fan about its first vertex.
fn triangle_list(mode: ::gltf::mesh::Mode, indices: &[u32]) -> Vec<[u32; 3]> {
    use ::gltf::mesh::Mode;
    let n = indices.len();
    match mode {
        Mode::TriangleStrip => (0..n.saturating_sub(2))
            .map(|i| {
                if i % 2 == 0 {
                    [indices[i], indices[i + 1], indices[i + 2]]
                } else {
                    [indices[i + 1], indices[i], indices[i + 2]]
                }
            })
            .collect(),
        Mode::TriangleFan => (1..n.saturating_sub(1)).map(|i| [indices[0], indices[i], indices[i + 1]]).collect(),
        _ => indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
    }
}
