//! Skyboxes: six square faces of linear RGB texels, with their mips and SH irradiance. They are
//! read from six images in a folder or one equirectangular panorama (`sky_files.rs`,
//! [`super::panorama`]).
//!
//! Faces are named `right left top bottom front back` (or `px nx py ny pz nz`) for +X, -X, +Y,
//! -Y, +Z, -Z, with the orientation of the GL/Vulkan cube-map convention (the one most skybox
//! images on the web are made for). `.png` and `.jpg` are sRGB and converted to linear; `.hdr`
//! and `.exr` are linear already. Non-finite and negative texels are replaced by 0, with a
//! warning, so the renderer never sees them.

use glam::Vec3;

use super::irradiance::sh_basis;

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
    /// Environment Maps"). Evaluate with `irradiance::sh_basis`: E(n)/π = Σ cᵢ·Yᵢ(n). Texels are weighted
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
