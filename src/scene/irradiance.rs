//! A sky's irradiance in spherical harmonics (bands 0-2): the basis, E(n)/π at a normal, and the
//! same as a quadratic form in another frame's normal, as the composite evaluates it.

use glam::{Mat3, Vec3};

/// The real spherical harmonics of bands 0-2 at unit direction `d`, in the order of
/// `Skybox::irradiance_sh`.
pub fn sh_basis(d: Vec3) -> [f32; 9] {
    let (x, y, z) = (d.x, d.y, d.z);
    [
        0.282_095,
        0.488_603 * y,
        0.488_603 * z,
        0.488_603 * x,
        1.092_548 * x * y,
        1.092_548 * y * z,
        0.315_392 * (3.0 * z * z - 1.0),
        1.092_548 * x * z,
        0.546_274 * (x * x - y * y),
    ]
}

/// E(n)/π from the coefficients of `Skybox::irradiance_sh`, clamped at 0.
pub fn sh_irradiance(coefficients: &[Vec3; 9], n: Vec3) -> Vec3 {
    let y = sh_basis(n);
    coefficients.iter().zip(y).map(|(c, y)| *c * y).sum::<Vec3>().max(Vec3::ZERO)
}

/// The irradiance of [`sh_irradiance`] as a quadratic form in the normal of another frame: with
/// `to_sky` turning that frame's directions into the sky's (a rotation, such as view to world),
/// returns `q` with E(n)/π = q0·x² + q1·y² + q2·xy + q3·xz + q4·yz + q5·x + q6·y + q7·z + q8 for
/// a unit normal n = (x, y, z) in that frame: bands 0-2 are a quadratic polynomial of the
/// direction, which a rotation keeps quadratic, and z² = 1 − x² − y² folds the ninth term away.
/// The shaders evaluate this (`sky_irradiance`): nine terms of the view-space normal, no
/// transform of the normal to world space and no basis to evaluate.
pub fn irradiance_quadratic(coefficients: &[Vec3; 9], to_sky: Mat3) -> [Vec3; 9] {
    let c = coefficients;
    let (k_xy, k_yz, k_xz) = (c[4] * 1.092_548, c[5] * 1.092_548, c[7] * 1.092_548);
    let (k_zz, k_xxyy) = (c[6] * 0.315_392, c[8] * 0.546_274);
    // E = wᵀ A w + b·w + k, per colour channel, w the sky-frame direction; A symmetric.
    let a = [[k_xxyy, k_xy * 0.5, k_xz * 0.5], [k_xy * 0.5, -k_xxyy, k_yz * 0.5], [k_xz * 0.5, k_yz * 0.5, k_zz * 3.0]];
    let b = [c[3] * 0.488_603, c[1] * 0.488_603, c[2] * 0.488_603];
    let k = c[0] * 0.282_095 - k_zz;
    // w = R n: E = nᵀ (Rᵀ A R) n + (Rᵀ b)·n + k.
    let r = [to_sky.x_axis, to_sky.y_axis, to_sky.z_axis];
    let quad = |i: usize, j: usize| -> Vec3 {
        let mut sum = Vec3::ZERO;
        for (p, row) in a.iter().enumerate() {
            for (q, entry) in row.iter().enumerate() {
                sum += *entry * (r[i][p] * r[j][q]);
            }
        }
        sum
    };
    let linear = |i: usize| b[0] * r[i].x + b[1] * r[i].y + b[2] * r[i].z;
    let zz = quad(2, 2);
    [
        quad(0, 0) - zz,
        quad(1, 1) - zz,
        quad(0, 1) * 2.0,
        quad(0, 2) * 2.0,
        quad(1, 2) * 2.0,
        linear(0),
        linear(1),
        linear(2),
        k + zz,
    ]
}

/// E(n)/π from [`irradiance_quadratic`]'s terms, clamped at 0 (what `sky_irradiance` computes).
pub fn quadratic_irradiance(q: &[Vec3; 9], n: Vec3) -> Vec3 {
    let (x, y, z) = (n.x, n.y, n.z);
    let terms = [x * x, y * y, x * y, x * z, y * z, x, y, z, 1.0];
    q.iter().zip(terms).map(|(q, t)| *q * t).sum::<Vec3>().max(Vec3::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Skybox;

    #[test]
    fn the_quadratic_form_in_a_rotated_frame_is_the_sh_irradiance() {
        // A sky with structure in every band: a warm sun, a blue zenith, a dark ground.
        let sky = Skybox::from_fn("lopsided", 32, |d| {
            let sun = Vec3::new(0.6, 0.5, -0.62).normalize();
            Vec3::new(1.0, 0.8, 0.5) * d.dot(sun).max(0.0).powi(8) * 6.0
                + Vec3::new(0.2, 0.3, 0.6) * d.y.max(0.0)
                + Vec3::splat(0.05) * (d.x * d.z).abs()
        });
        let sh = sky.irradiance_sh();
        let rotations = [
            Mat3::IDENTITY,
            Mat3::from_rotation_y(0.7) * Mat3::from_rotation_x(-0.4),
            Mat3::from_euler(glam::EulerRot::ZXY, 2.1, -1.3, 0.35),
        ];
        for r in rotations {
            let q = irradiance_quadratic(&sh, r);
            for n in [Vec3::X, Vec3::NEG_Y, Vec3::Z, Vec3::new(0.3, 0.5, -0.8), Vec3::new(-0.9, 0.1, 0.2)] {
                let n = n.normalize();
                let want = sh_irradiance(&sh, r * n);
                let got = quadratic_irradiance(&q, n);
                assert!((got - want).abs().max_element() < 1e-5, "{r:?} {n}: {got} vs {want}");
            }
        }
    }

    #[test]
    fn constant_sky_has_irradiance_equal_to_its_radiance() {
        let sh = Skybox::constant(Vec3::new(0.3, 0.6, 0.9)).irradiance_sh();
        for n in [Vec3::X, Vec3::NEG_Y, Vec3::new(0.3, 0.5, -0.8).normalize()] {
            let e = sh_irradiance(&sh, n);
            assert!((e - Vec3::new(0.3, 0.6, 0.9)).abs().max_element() < 1e-4, "{n}: {e}");
        }
    }

    #[test]
    fn half_sky_matches_the_closed_form() {
        // Radiance 1 above the horizon, 0 below. E/π at a normal tilted θ from up is
        // (1 + cos θ)/2 exactly; three bands reproduce it within a few percent of 1.
        let sky = Skybox::from_fn("half", 64, |d| if d.y > 0.0 { Vec3::ONE } else { Vec3::ZERO });
        let sh = sky.irradiance_sh();
        for theta in [0.0f32, 45.0, 90.0, 135.0, 180.0] {
            let t = theta.to_radians();
            let n = Vec3::new(t.sin(), t.cos(), 0.0);
            let want = 0.5 * (1.0 + t.cos());
            let got = sh_irradiance(&sh, n).x;
            assert!((got - want).abs() < 0.05, "θ {theta}: {got} vs {want}");
        }
    }
}
