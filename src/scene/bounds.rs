//! Axis-aligned bounds, which the camera, the lights and the scene defaults scale with.

use glam::Vec3;

/// Axis-aligned bounds of finite points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub min: Vec3,
    pub max: Vec3,
}

impl Bounds {
    /// Bounds of the finite points; `None` when there are none.
    pub fn from_points(points: impl IntoIterator<Item = Vec3>) -> Option<Self> {
        let mut it = points.into_iter().filter(|p| p.is_finite());
        let first = it.next()?;
        Some(it.fold(Self { min: first, max: first }, |b, p| Self { min: b.min.min(p), max: b.max.max(p) }))
    }

    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// Half the diagonal (in f64: squaring the sides of a model 1e-30 across underflows f32);
    /// never zero, so a single point still has a scale.
    pub fn radius(&self) -> f32 {
        let r = (0.5 * (self.max - self.min).as_dvec3().length()) as f32;
        if r > 0.0 && r.is_finite() {
            r
        } else {
            1.0_f32.max(self.center().abs().max_element() * 1e-3)
        }
    }
}
