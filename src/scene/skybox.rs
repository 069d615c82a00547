//! Skyboxes: six square faces of linear RGB texels, with their mips and SH irradiance. They are
//! read from six images in a folder or one equirectangular panorama (`sky_files.rs`,
//! [`super::panorama`]).
//!
//! Faces are named `right left top bottom front back` (or `px nx py ny pz nz`) for +X, -X, +Y,
//! -Y, +Z, -Z, with the orientation of the GL/Vulkan cube-map convention (the one most skybox
//! images on the web are made for). `.png` and `.jpg` are sRGB and converted to linear; `.hdr`
//! and `.exr` are linear already. Non-finite and negative texels are replaced by 0, with a
//! warning, so the renderer never sees them.

use glam::{Mat3, Vec3};

/// Face names in cube-layer order (+X, -X, +Y, -Y, +Z, -Z): the long name and the short one.
pub const FACE_NAMES: [(&str, &str); 6] =
    [("right", "px"), ("left", "nx"), ("top", "py"), ("bottom", "ny"), ("front", "pz"), ("back", "nz")];

/// File extensions tried for each face, in this order.
pub const EXTENSIONS: [&str; 5] = ["png", "jpg", "jpeg", "hdr", "exr"];

/// Largest face side accepted when loading (a larger one is refused with one line).
pub const MAX_FACE_SIDE: u32 = 8192;
/// Largest face side kept: larger faces are downscaled to it as they load, with a warning. The
/// sky is the background and, at coarse mips, SSDO's light; 2048² per face is more than either
/// shows, and six of them take 0.3 GB as f32 texels and 0.27 GB on the GPU with mips.
pub const STORED_FACE_SIDE: u32 = 2048;

#[derive(Clone, Debug)]
pub struct Skybox {
    pub name: String,
    /// Side of each square face in texels.
    pub size: u32,
    /// Six faces of `size * size` linear RGB texels, rows top to bottom.
    pub faces: Vec<Vec<[f32; 3]>>,
    pub warnings: Vec<String>,
    /// E(n)/π as 9 spherical-harmonic coefficients ([`Skybox::irradiance_sh`]), computed once
    /// when the sky is made — on the viewer's loading thread, not its render thread.
    pub irradiance: [Vec3; 9],
}

/// The world direction through face `face` at cube coordinates `s`, `t` in [-1, 1]
/// (s grows along a row, t down the rows). Not normalised.
pub fn face_direction(face: usize, s: f32, t: f32) -> Vec3 {
    match face {
        0 => Vec3::new(1.0, -t, -s),
        1 => Vec3::new(-1.0, -t, s),
        2 => Vec3::new(s, 1.0, t),
        3 => Vec3::new(s, -1.0, -t),
        4 => Vec3::new(s, -t, 1.0),
        _ => Vec3::new(-s, -t, -1.0),
    }
}

/// The face and cube coordinates (s, t in [-1, 1]) that direction `d` looks through;
/// the inverse of [`face_direction`]. A zero or non-finite direction gives face +Y's centre.
pub fn direction_to_face(d: Vec3) -> (usize, f32, f32) {
    if !d.is_finite() || d == Vec3::ZERO {
        return (2, 0.0, 0.0);
    }
    let a = d.abs();
    if a.x >= a.y && a.x >= a.z {
        if d.x > 0.0 {
            (0, -d.z / a.x, -d.y / a.x)
        } else {
            (1, d.z / a.x, -d.y / a.x)
        }
    } else if a.y >= a.z {
        if d.y > 0.0 {
            (2, d.x / a.y, d.z / a.y)
        } else {
            (3, d.x / a.y, -d.z / a.y)
        }
    } else if d.z > 0.0 {
        (4, d.x / a.z, -d.y / a.z)
    } else {
        (5, -d.x / a.z, -d.y / a.z)
    }
}

fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Whether a decoded image holds linear HDR values (`.hdr`, `.exr`) rather than sRGB ones.
pub(super) fn is_hdr(image: &image::DynamicImage) -> bool {
    matches!(image, image::DynamicImage::ImageRgb32F(_) | image::DynamicImage::ImageRgba32F(_))
}

/// The brightest radiance a sky keeps: texels above it are clamped as they load, with a warning.
/// A sky's irradiance sums millions of texels in f32, and so do its mips, its resampling from a
/// panorama and the truth's estimates; the gains (`--sky-scale`, `--sky-strength`, up to 1e6
/// each) multiply it again. A few texels of 3e38 overflowed them all and the frame came out
/// black; 1e20 leaves every one of those sums and products finite (and is fifteen orders above
/// the sun's disc in a real HDR capture).
pub const MAX_SKY_RADIANCE: f32 = 1e20;

/// What [`linear_texels`] replaced: non-finite or negative values (now 0), and values above
/// [`MAX_SKY_RADIANCE`] (now that).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Repaired {
    pub invalid: usize,
    pub clamped: usize,
}

impl Repaired {
    /// The warnings for `path`'s texels, one line each kind.
    pub fn warnings(&self, path: &std::path::Path) -> Vec<String> {
        let mut out = Vec::new();
        if self.invalid > 0 {
            out.push(format!("{}: {} non-finite or negative value(s) replaced by 0", path.display(), self.invalid));
        }
        if self.clamped > 0 {
            out.push(format!(
                "{}: {} value(s) above {MAX_SKY_RADIANCE:e} clamped to it (brighter would overflow the sky's sums)",
                path.display(),
                self.clamped
            ));
        }
        out
    }
}

/// An image's texels as linear RGB, rows top to bottom, with non-finite and negative values
/// replaced by 0 and values above [`MAX_SKY_RADIANCE`] clamped; and how many were. A float
/// RGB image is converted in place (a 16384x8192 panorama is 1.5 GiB as one copy).
pub(super) fn linear_texels(image: image::DynamicImage) -> (Vec<[f32; 3]>, Repaired) {
    let hdr = is_hdr(&image);
    let mut repaired = Repaired::default();
    let mut values = image.into_rgb32f().into_raw();
    for c in &mut values {
        let linear = if hdr { *c } else { srgb_to_linear(*c) };
        *c = if !(linear.is_finite() && linear >= 0.0) {
            repaired.invalid += 1;
            0.0
        } else if linear > MAX_SKY_RADIANCE {
            repaired.clamped += 1;
            MAX_SKY_RADIANCE
        } else {
            linear
        };
    }
    let texels = bytemuck::allocation::try_cast_vec(values)
        .unwrap_or_else(|(_, values)| values.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect());
    (texels, repaired)
}

/// The bytes a sky of faces of `side`² holds once loaded: the f32 faces, their mip chain (a
/// third more) and the half-float copy with mips that the GPU keeps (in the same RAM on a
/// software adapter).
pub fn stored_bytes(side: u32) -> u64 {
    let texels = 6 * side as u64 * side as u64;
    texels * 12 + texels * 4 + texels * 8 * 4 / 3
}

/// The bytes a decode of `size` takes beyond `decode` (what the decoder allocates) while it
/// becomes linear f32 RGB: nothing when it is f32 RGB already (converted in place), else a copy.
pub fn conversion_bytes(size: (u32, u32), decode: u64) -> u64 {
    let rgb_f32 = size.0 as u64 * size.1 as u64 * 12;
    if decode == rgb_f32 {
        0
    } else {
        rgb_f32
    }
}

impl Skybox {
    /// A sky of six faces of `size`² linear texels, in cube-layer order.
    pub fn from_faces(name: String, size: u32, faces: Vec<Vec<[f32; 3]>>, warnings: Vec<String>) -> Self {
        Self { name, size, faces, warnings, irradiance: [Vec3::ZERO; 9] }.with_irradiance()
    }

    /// A sky computed from a function of the (unit) world direction.
    pub fn from_fn(name: &str, size: u32, radiance: impl Fn(Vec3) -> Vec3) -> Self {
        let faces = (0..6)
            .map(|face| {
                (0..size * size)
                    .map(|i| {
                        let s = 2.0 * ((i % size) as f32 + 0.5) / size as f32 - 1.0;
                        let t = 2.0 * ((i / size) as f32 + 0.5) / size as f32 - 1.0;
                        radiance(face_direction(face, s, t).normalize()).max(Vec3::ZERO).into()
                    })
                    .collect()
            })
            .collect();
        Self::from_faces(name.into(), size, faces, Vec::new())
    }

    /// A sky of the same radiance in every direction (the white-furnace test's sky).
    pub fn constant(radiance: Vec3) -> Self {
        Self::from_fn("constant", 4, |_| radiance)
    }

    /// Radiance in direction `d` (nearest texel).
    pub fn sample(&self, d: Vec3) -> Vec3 {
        let (face, s, t) = direction_to_face(d);
        let texel = |c: f32| ((0.5 * (c + 1.0) * self.size as f32) as u32).min(self.size - 1);
        Vec3::from(self.faces[face][(texel(t) * self.size + texel(s)) as usize])
    }

    /// Largest channel value anywhere on the sky.
    pub fn max_value(&self) -> f32 {
        self.faces.iter().flatten().flat_map(|t| t.iter().copied()).fold(0.0, f32::max)
    }

    /// Every texel as (unit direction, radiance, weight ∝ its solid angle: (1 + s² + t²)^-3/2).
    fn texels(&self) -> impl Iterator<Item = (Vec3, Vec3, f32)> + '_ {
        let n = self.size;
        self.faces.iter().enumerate().flat_map(move |(face, texels)| {
            texels.iter().enumerate().map(move |(i, t)| {
                let s = 2.0 * ((i as u32 % n) as f32 + 0.5) / n as f32 - 1.0;
                let tt = 2.0 * ((i as u32 / n) as f32 + 0.5) / n as f32 - 1.0;
                let d = face_direction(face, s, tt);
                (d.normalize(), Vec3::from(*t), d.length().powi(-3))
            })
        })
    }

    /// Mean radiance over the sphere, weighting each texel by its solid angle.
    pub fn mean(&self) -> Vec3 {
        let (sum, weight) = self.texels().fold((Vec3::ZERO, 0.0), |(s, w), (_, l, dw)| (s + l * dw, w + dw));
        sum / weight.max(f32::MIN_POSITIVE)
    }

    /// Fills in [`Skybox::irradiance`].
    fn with_irradiance(mut self) -> Self {
        self.irradiance = self.irradiance_sh();
        self
    }

    /// The sky's irradiance over π for every normal, E(n)/π, as 9 spherical-harmonic coefficients
    /// (bands 0-2, rgb): the sky's radiance projected on the basis, each band convolved with the
    /// clamped cosine (Ramamoorthi & Hanrahan 2001, "An Efficient Representation for Irradiance
    /// Environment Maps"). Evaluate with [`sh_basis`]: E(n)/π = Σ cᵢ·Yᵢ(n). Texels are weighted
    /// by their solid angle, normalised to 4π, so a constant sky L gives exactly L. Three bands
    /// hold irradiance to within a few percent for smooth skies; a small bright sun rings a little,
    /// which the shader clamps at 0.
    pub fn irradiance_sh(&self) -> [Vec3; 9] {
        // The clamped cosine's band factors Â_l = π, 2π/3, π/4, divided by π.
        const BAND: [f32; 9] = [1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25, 0.25, 0.25];
        let mut sum = [Vec3::ZERO; 9];
        let mut weight = 0.0f64;
        for (d, radiance, w) in self.texels() {
            let y = sh_basis(d);
            for k in 0..9 {
                sum[k] += radiance * (w * y[k]);
            }
            weight += w as f64;
        }
        let solid_angle = (4.0 * std::f64::consts::PI / weight.max(f64::MIN_POSITIVE)) as f32;
        std::array::from_fn(|k| sum[k] * solid_angle * BAND[k])
    }

    /// Mip chain of every face, level 0 first: each level averages 2x2 texels of the one above.
    pub fn mip_chain(&self) -> Vec<Vec<Vec<[f32; 3]>>> {
        let mut levels = vec![self.faces.clone()];
        let mut size = self.size;
        while size > 1 {
            let next = size / 2;
            let above = levels.last().expect("level 0 exists");
            let level = above
                .iter()
                .map(|face| {
                    (0..next * next)
                        .map(|i| {
                            let (x, y) = (2 * (i % next), 2 * (i / next));
                            let mut acc = [0.0f32; 3];
                            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                                let t = face[((y + dy).min(size - 1) * size + (x + dx).min(size - 1)) as usize];
                                for c in 0..3 {
                                    acc[c] += 0.25 * t[c];
                                }
                            }
                            acc
                        })
                        .collect()
                })
                .collect();
            levels.push(level);
            size = next;
        }
        levels
    }
}

/// The real spherical harmonics of bands 0-2 at unit direction `d`, in the order of
/// [`Skybox::irradiance_sh`].
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

/// E(n)/π from the coefficients of [`Skybox::irradiance_sh`], clamped at 0.
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
