//! One triangle of a loaded model, built the same way for every file format.

use glam::Vec3;

use super::model::Vertex;

/// What became of a triangle handed to [`push_triangle`].
pub(super) enum Triangle {
    Kept,
    /// Kept with its winding reversed to agree with its normals.
    Flipped,
    /// Left out: a position non-finite or beyond 1e12.
    Dropped,
}

/// Appends one triangle's three vertices to `out`, the same way for every file format. The
/// supplied normals, where there are any, say which side is out; the winding is often an
/// accident (left-handed exporters, mirrored objects), so where they disagree, the winding yields.
/// A vertex without a usable normal takes the face's.
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
    // In f64: the cross product of edges 1e-20 long underflows f32 (to a zero normal); a model
    // that small is scaled up later, and keeps the normals computed here.
    let (e1, e2) = ((pos[1] - pos[0]).as_dvec3(), (pos[2] - pos[0]).as_dvec3());
    let cross = e1.cross(e2);
    let mut face_normal = cross.try_normalize().map_or(Vec3::Y, |n| n.as_vec3());
    // A sliver (a sphere's pole) has no trustworthy winding: it is left as it is.
    let well_shaped = cross.length() > 1e-4 * e1.length_squared().max(e2.length_squared());
    let mut order = [0, 1, 2];
    let mut outcome = Triangle::Kept;
    if let Some(normals) = normals {
        let supplied: Vec3 = normals.iter().sum();
        if well_shaped && supplied.is_finite() && face_normal.dot(supplied) < 0.0 {
            order = [0, 2, 1];
            face_normal = -face_normal;
            outcome = Triangle::Flipped;
        }
    }
    for k in order {
        let normal = normals.and_then(|n| n[k].try_normalize()).unwrap_or(face_normal);
        let uv = if uvs[k].iter().all(|x| x.is_finite()) { uvs[k] } else { [0.0, 0.0] };
        out.push(Vertex { position: pos[k].into(), normal: normal.into(), uv });
    }
    outcome
}
