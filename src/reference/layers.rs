//! The surfaces along an eye ray: whether a point is among the first two, the depth buffer's
//! and the one behind it, which is what a second depth layer would hold (the report's split of
//! the bounce the screen cannot send, `place.rs`).

use glam::Vec3;

use super::scene::ReferenceScene;

/// Whether `point` is the first or the second surface the ray from `eye` towards it meets (cut-out
/// texels let the ray through, as the G-buffer discards them): within a thousandth of its
/// distance.
pub fn within_two_surfaces(scene: &ReferenceScene, eye: Vec3, point: Vec3) -> bool {
    let to = point - eye;
    let distance = to.length();
    let Some(direction) = to.try_normalize() else { return false };
    let tolerance = 1e-3 * distance + 1e-6;
    let mut travelled = 0.0;
    for _ in 0..2 {
        let origin = eye + direction * travelled;
        let Some(hit) = scene.trace(origin, direction, f32::INFINITY) else { return false };
        let at = travelled + hit.distance;
        if (at - distance).abs() <= tolerance {
            return true;
        }
        if at > distance {
            return false;
        }
        travelled = at + tolerance;
    }
    false
}
