//! An orbit camera (which the viewer's fly camera steers too) and reverse-Z projections.
//!
//! Reverse-Z maps the near plane to depth 1 and the far plane (or infinity) to 0; with a float
//! depth buffer this keeps depth precision roughly uniform in log scale, so a near plane of 1e-6
//! still resolves a floor far away. The background is exactly depth 0.

use glam::{Mat4, Vec3, Vec4};

use super::bounds::Bounds;

/// The camera's distance from its target, in the model's bounding radii: from inside the model
/// out to where it is a speck.
pub const DISTANCE_RADII: (f32, f32) = (1e-5, 1e5);
/// How far from the model's centre a camera point (target, eye, look-at) may lie, in its
/// bounding radii. The view's 32-bit maths subtracts the eye from every position: at a million
/// radii the model is a speck and still drawn right; at a hundred million (`--target 3e8` on the
/// default scene) the sky's horizon bends and the picture is one colour.
pub const REACH_RADII: f32 = 1e6;

/// Orbits `target` at `distance`; yaw 0 looks down -Z from +Z, pitch is elevation in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrbitCamera {
    pub target: Vec3,
    pub yaw_deg: f32,
    pub pitch_deg: f32,
    pub distance: f32,
    pub fov_y_deg: f32,
    pub near: f32,
    /// `None` is an infinite far plane.
    pub far: Option<f32>,
}

impl OrbitCamera {
    /// Frames `bounds`: the whole bounding sphere fits the vertical field of view.
    pub fn framing(bounds: &Bounds) -> Self {
        let fov_y_deg: f32 = 45.0;
        let radius = bounds.radius();
        let distance = radius / (0.5 * fov_y_deg.to_radians()).sin() * 0.92;
        Self {
            target: bounds.center(),
            yaw_deg: 35.0,
            pitch_deg: 22.0,
            distance,
            fov_y_deg,
            near: distance * 1e-3,
            far: None,
        }
    }

    pub fn eye(&self) -> Vec3 {
        let (yaw, pitch) = (self.yaw_deg.to_radians(), self.pitch_deg.clamp(-89.9, 89.9).to_radians());
        self.target
            + self.distance.max(f32::MIN_POSITIVE)
                * Vec3::new(pitch.cos() * yaw.sin(), pitch.sin(), pitch.cos() * yaw.cos())
    }

    /// The camera at `eye` looking at `look_at`, as an orbit about `look_at` (so every view the
    /// fly camera reaches is an orbit camera too), with this camera's lens. `None` when the two
    /// points are the same or not finite, or the view looks straight up or down.
    pub fn looking(&self, eye: Vec3, look_at: Vec3) -> Option<Self> {
        let offset = eye - look_at;
        let distance = offset.length();
        if !(distance.is_finite() && distance > 0.0) {
            return None;
        }
        let d = offset / distance;
        let pitch_deg = d.y.clamp(-1.0, 1.0).asin().to_degrees();
        if pitch_deg.abs() > 89.9 {
            return None;
        }
        let yaw_deg = d.x.atan2(d.z).to_degrees();
        Some(Self { target: look_at, yaw_deg, pitch_deg, distance, ..*self })
    }

    /// The unit direction the camera looks in.
    pub fn forward(&self) -> Vec3 {
        (self.target - self.eye()).normalize_or(Vec3::NEG_Z)
    }

    /// Brings the camera back within the ranges the command line takes for a model of `bounds`
    /// ([`DISTANCE_RADII`], [`REACH_RADII`] for both the target and the eye), so that any view
    /// the viewer reaches by flying, panning or zooming can be captured again from its command.
    pub fn keep_in_range(&mut self, bounds: &Bounds) {
        let r = bounds.radius();
        let (lo, hi) = (DISTANCE_RADII.0 * r, DISTANCE_RADII.1 * r);
        if !(self.distance >= lo && self.distance <= hi) {
            let distance = if self.distance.is_finite() { self.distance.clamp(lo, hi) } else { hi };
            self.near *= distance / self.distance;
            self.distance = distance;
        }
        // The target within the reach less the distance keeps the eye within the reach too.
        let (center, reach) = (bounds.center(), REACH_RADII * r - self.distance);
        let offset = self.target - center;
        if !(offset.length() <= reach) {
            self.target = center + offset.normalize_or_zero() * reach;
        }
    }

    /// The fly camera's step: the eye and what it looks at move together by `by`.
    pub fn translate(&mut self, by: Vec3) {
        self.target += by;
    }

    /// The fly camera's look: turns the view about the eye (the orbit camera turns about its
    /// target), by degrees of yaw and pitch.
    pub fn turn(&mut self, yaw_deg: f32, pitch_deg: f32) {
        let eye = self.eye();
        self.yaw_deg += yaw_deg;
        self.pitch_deg = (self.pitch_deg + pitch_deg).clamp(-89.0, 89.0);
        self.target = eye - (self.eye() - self.target);
    }

    pub fn world_to_view(&self) -> Mat4 {
        glam::camera::rh::view::look_at_mat4(self.eye(), self.target, Vec3::Y)
    }

    pub fn view_to_clip(&self, aspect: f32) -> Mat4 {
        reverse_z_perspective(self.fov_y_deg.to_radians(), aspect, self.near, self.far)
    }
}

/// Right-handed perspective (camera looks down -Z) with depth 1 at `near` and 0 at `far`, or at
/// infinity when `far` is `None`. In clip space `z = a·z_view + b`, `w = -z_view`, so depth is
/// `-a - b / z_view` with `a = n / (f - n)`, `b = n·f / (f - n)`; for `f → ∞`, `a = 0`, `b = n`.
pub fn reverse_z_perspective(fov_y: f32, aspect: f32, near: f32, far: Option<f32>) -> Mat4 {
    let f = 1.0 / (0.5 * fov_y).tan();
    let (a, b) = match far {
        Some(far) if far.is_finite() && far > near => (near / (far - near), near * far / (far - near)),
        _ => (0.0, near),
    };
    Mat4::from_cols(
        Vec4::new(f / aspect.max(f32::MIN_POSITIVE), 0.0, 0.0, 0.0),
        Vec4::new(0.0, f, 0.0, 0.0),
        Vec4::new(0.0, 0.0, a, -1.0),
        Vec4::new(0.0, 0.0, b, 0.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_view_from_an_eye_to_a_point_and_the_fly_moves_keep_what_they_should() {
        let base = OrbitCamera::framing(&Bounds { min: Vec3::splat(-1.0), max: Vec3::ONE });
        let (eye, look_at) = (Vec3::new(3.0, 2.0, -4.0), Vec3::new(0.5, 0.0, 0.25));
        let c = base.looking(eye, look_at).unwrap();
        assert!((c.eye() - eye).length() < 1e-5 && c.target == look_at, "{} {}", c.eye(), c.target);
        assert!((c.forward() - (look_at - eye).normalize()).length() < 1e-6);
        assert!(base.looking(eye, eye).is_none() && base.looking(Vec3::Y * 5.0, Vec3::ZERO).is_none());
        // Turning keeps the eye; moving keeps the direction.
        let mut turned = c;
        turned.turn(30.0, -10.0);
        assert!((turned.eye() - eye).length() < 1e-4 && (turned.forward() - c.forward()).length() > 0.1);
        let mut moved = c;
        moved.translate(Vec3::X);
        assert!((moved.eye() - eye - Vec3::X).length() < 1e-5 && (moved.forward() - c.forward()).length() < 1e-6);
    }
}
