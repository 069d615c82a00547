//! One triangle of a loaded model, built the same way for every file format, the vertex it is
//! made of (which `model.rs` hands on as `model::Vertex`), and whether it is smooth-shaded.

use glam::Vec3;

/// One vertex as the G-buffer pass reads it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub uv: [f32; 2],
}

/// What became of a triangle handed to [`push_triangle`].
pub(super) enum Triangle {
    Kept,
    /// Kept with its winding reversed to agree with its normals.
    Flipped,
    /// Left out: a position non-finite or beyond 1e12.
    Dropped,
}

/// The unit normal of the triangle at `pos` by its winding, and whether that winding can be
/// trusted: a sliver (a sphere's pole) has none. In f64: the cross product of edges 1e-20 long
/// underflows f32 (to a zero normal); a model that small is scaled up later, and keeps the
/// normals computed here.
fn face(pos: [Vec3; 3]) -> (Vec3, bool) {
    let (e1, e2) = ((pos[1] - pos[0]).as_dvec3(), (pos[2] - pos[0]).as_dvec3());
    let cross = e1.cross(e2);
    let normal = cross.try_normalize().map_or(Vec3::Y, |n| n.as_vec3());
    (normal, cross.length() > 1e-4 * e1.length_squared().max(e2.length_squared()))
}

/// How far (degrees) a vertex normal may turn from its triangle's face for the triangle to count
/// as flat-shaded ([`smooth_shaded`]).
pub const SMOOTH_NORMAL_DEG: f32 = 2.0;

/// Whether the triangle of vertices `v` is smooth-shaded: a vertex normal turns more than
/// `SMOOTH_NORMAL_DEG` from its face, so the normal turns from pixel to pixel across it, not
/// only at its edges. A sliver says nothing, as for its winding.
pub(super) fn smooth_shaded(v: [Vertex; 3]) -> bool {
    let (normal, well_shaped) = face(v.map(|v| Vec3::from(v.position)));
    let cos = SMOOTH_NORMAL_DEG.to_radians().cos();
    well_shaped && v.iter().any(|v| normal.dot(Vec3::from(v.normal)) < cos)
}

/// Whether the triangle at `pos` is wound against `normals` (their sum, the side they say is
/// out): the rule every model's triangles are held to ([`super::Model::from_groups`]), which the
/// G-buffer relies on to tell from the rasteriser's facing which side of a surface the camera
/// sees. A sliver, or normals that say nothing, leave the winding as it is.
pub(super) fn wound_against(pos: [Vec3; 3], normals: Vec3) -> bool {
    let (normal, well_shaped) = face(pos);
    well_shaped && normals.is_finite() && normal.dot(normals) < 0.0
}

/// Appends one triangle's three vertices to `out`, the same way for every file format. The
/// supplied normals, where there are any, say which side is out; the winding is often an
/// accident (left-handed exporters, mirrored objects), so where they disagree, the winding yields
/// ([`wound_against`], over the normals as the vertices keep them, so the model built from them
/// finds nothing more to turn). A vertex without a usable normal takes the face's.
pub(super) fn push_triangle(
    pos: [Vec3; 3],
    normals: Option<[Vec3; 3]>,
    uvs: [[f32; 2]; 3],
    out: &mut Vec<Vertex>,
) -> Triangle {
    // Beyond 1e12 from the origin, f32 keeps no precision the depth buffer could use.
    if !pos.iter().all(|p| p.is_finite() && p.abs().max_element() <= 1e12) {
        return Triangle::Dropped;
    }
    let (mut face_normal, _) = face(pos);
    let usable = normals.map(|n| n.map(Vec3::try_normalize)).unwrap_or([None; 3]);
    let mut order = [0, 1, 2];
    let mut outcome = Triangle::Kept;
    if wound_against(pos, usable.iter().flatten().sum()) {
        order = [0, 2, 1];
        face_normal = -face_normal;
        outcome = Triangle::Flipped;
    }
    for k in order {
        let normal = usable[k].unwrap_or(face_normal);
        let uv = if uvs[k].iter().all(|x| x.is_finite()) { uvs[k] } else { [0.0, 0.0] };
        out.push(Vertex { position: pos[k].into(), normal: normal.into(), uv });
    }
    outcome
}
