//! Equirectangular panoramas (what HDRI libraries publish: one `.hdr`, `.exr`, `.png` or `.jpg`
//! twice as wide as it is high), resampled into the six faces of a [`Skybox`] as they load.
//!
//! Orientation: the top row looks along +Y and the bottom row along -Y. The centre column looks
//! along -Z (where the orbit camera at yaw 0 and the fly camera at its start look), the column a
//! quarter of the way from the left along -X, three quarters along +X, and the left and right
//! edges along +Z. Seen from inside, the panorama is not mirrored: +X is to the right of -Z.

use std::path::{Path, PathBuf};

use glam::Vec3;
use rayon::prelude::*;

use super::skybox::{
    conversion_bytes, face_direction, linear_texels, stored_bytes, Skybox, EXTENSIONS, FACE_NAMES, MAX_FACE_SIDE,
    STORED_FACE_SIDE,
};
use super::texture::read_image_checked;
use crate::budget::{self, Share};
use crate::{Error, Result};

/// Largest panorama height accepted (twice that wide): the faces' largest side, so a panorama
/// decodes to at most twice the texels of the largest face.
pub const MAX_PANORAMA_HEIGHT: u32 = MAX_FACE_SIDE;

/// The unit direction through panorama coordinates `u` (0 at the left edge, 1 at the right) and
/// `v` (0 at the top, 1 at the bottom).
pub fn direction(u: f32, v: f32) -> Vec3 {
    let phi = std::f32::consts::TAU * (u - 0.5);
    let theta = std::f32::consts::PI * v;
    Vec3::new(theta.sin() * phi.sin(), theta.cos(), -theta.sin() * phi.cos())
}

/// The panorama coordinates (u, v in [0, 1]) that direction `d` looks through; the inverse of
/// [`direction`]. A zero or non-finite direction gives the top row's centre.
pub fn coordinates(d: Vec3) -> (f32, f32) {
    if !d.is_finite() || d == Vec3::ZERO {
        return (0.5, 0.0);
    }
    let d = d.normalize();
    let u = 0.5 + d.x.atan2(-d.z) / std::f32::consts::TAU;
    (u.rem_euclid(1.0), d.y.clamp(-1.0, 1.0).acos() / std::f32::consts::PI)
}

/// Linear RGB texels of a panorama, rows top to bottom.
pub struct Panorama {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<[f32; 3]>,
}

impl Panorama {
    /// A panorama computed from a function of the (unit) direction through each texel's centre.
    pub fn from_fn(width: u32, height: u32, radiance: impl Fn(Vec3) -> Vec3 + Sync) -> Self {
        let texels = (0..width * height)
            .into_par_iter()
            .map(|i| {
                let (x, y) = (i % width, i / width);
                let d = direction((x as f32 + 0.5) / width as f32, (y as f32 + 0.5) / height as f32);
                radiance(d).max(Vec3::ZERO).into()
            })
            .collect();
        Self { width, height, texels }
    }

    /// Bilinear radiance at (u, v): wrapping around the horizon, clamped at the poles.
    pub fn sample(&self, u: f32, v: f32) -> Vec3 {
        let x = u * self.width as f32 - 0.5;
        let y = (v * self.height as f32 - 0.5).clamp(0.0, (self.height - 1) as f32);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let column = |c: f32| (c as i64).rem_euclid(self.width as i64) as u32;
        let (xa, xb) = (column(x0), column(x0 + 1.0));
        let (ya, yb) = (y0 as u32, (y0 as u32 + 1).min(self.height - 1));
        let at = |x: u32, y: u32| Vec3::from(self.texels[(y * self.width + x) as usize]);
        let top = at(xa, ya).lerp(at(xb, ya), fx);
        let bottom = at(xa, yb).lerp(at(xb, yb), fx);
        top.lerp(bottom, fy)
    }

    /// Six cube faces of `size`² texels. Each texel averages four bilinear samples of the
    /// panorama spread over its footprint, so detail finer than a texel is filtered, not aliased.
    pub fn to_faces(&self, size: u32) -> Vec<Vec<[f32; 3]>> {
        const OFFSETS: [(f32, f32); 4] = [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)];
        (0..6)
            .map(|face| {
                (0..size * size)
                    .into_par_iter()
                    .map(|i| {
                        let sum: Vec3 = OFFSETS
                            .iter()
                            .map(|(ox, oy)| {
                                let s = 2.0 * ((i % size) as f32 + ox) / size as f32 - 1.0;
                                let t = 2.0 * ((i / size) as f32 + oy) / size as f32 - 1.0;
                                let (u, v) = coordinates(face_direction(face, s, t));
                                self.sample(u, v)
                            })
                            .sum();
                        (sum / OFFSETS.len() as f32).into()
                    })
                    .collect()
            })
            .collect()
    }

    /// The face side this panorama resamples to (see [`face_side`]).
    pub fn face_side(&self) -> u32 {
        face_side(self.width)
    }
}

/// The face side a panorama `width` wide resamples to: its width over four (the texel density at
/// the horizon), at most [`STORED_FACE_SIDE`].
pub fn face_side(width: u32) -> u32 {
    (width / 4).clamp(1, STORED_FACE_SIDE)
}

/// Whether `path` names a file with one of the sky image extensions.
pub fn is_image(path: &Path) -> bool {
    path.extension().is_some_and(|e| EXTENSIONS.iter().any(|x| e.eq_ignore_ascii_case(x)))
}

/// The one panorama in a folder that holds no cube face: `Some` when the folder has exactly one
/// image and none of them is named as a face.
pub fn in_folder(dir: &Path) -> Option<PathBuf> {
    let images: Vec<PathBuf> =
        std::fs::read_dir(dir).ok()?.flatten().map(|e| e.path()).filter(|p| p.is_file() && is_image(p)).collect();
    let is_face = |p: &PathBuf| {
        let stem = p.file_stem().map(|s| s.to_string_lossy().to_lowercase()).unwrap_or_default();
        FACE_NAMES.iter().any(|(long, short)| stem == *long || stem == *short)
    };
    match images.as_slice() {
        [one] if !is_face(one) => Some(one.clone()),
        _ => None,
    }
}

/// Whether a panorama of `width` x `height` can be read: at least 2x1, twice as wide as high
/// (within a texel), at most [`MAX_PANORAMA_HEIGHT`] high; the problem when it cannot.
fn check_shape(width: u32, height: u32) -> std::result::Result<(), String> {
    if height == 0 || width < 2 {
        return Err(format!("panorama is {width}x{height}; at least 2x1 is needed"));
    }
    if width.abs_diff(2 * height) > 1 {
        return Err(format!(
            "panorama is {width}x{height}; an equirectangular panorama is twice as wide as it is high"
        ));
    }
    if height > MAX_PANORAMA_HEIGHT {
        return Err(format!(
            "panorama is {width}x{height}; at most {}x{MAX_PANORAMA_HEIGHT} is accepted",
            2 * MAX_PANORAMA_HEIGHT
        ));
    }
    Ok(())
}

/// Why a folder that holds no cube face is no sky, when it holds several panoramas: which one
/// is meant is the user's to say.
pub fn several_in_folder(dir: &Path) -> Option<String> {
    let entries = std::fs::read_dir(dir).ok()?;
    let mut images: Vec<String> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_file() && is_image(p))
        .map(|p| p.file_name().unwrap_or_default().to_string_lossy().into_owned())
        .collect();
    let is_face = |name: &String| {
        let stem = Path::new(name).file_stem().map(|s| s.to_string_lossy().to_lowercase()).unwrap_or_default();
        FACE_NAMES.iter().any(|(long, short)| stem == *long || stem == *short)
    };
    if images.len() < 2 || images.iter().any(is_face) {
        return None;
    }
    images.sort();
    Some(format!(
        "holds {} images and no cube face ({}): give one of them as the sky, or name six faces right left top \
         bottom front back",
        images.len(),
        images.join(", ")
    ))
}

/// Loads an equirectangular panorama file as a sky named after the file. Its size, its shape
/// and what decoding and resampling it would hold are checked from its header, against the
/// sky's share of the memory budget, before any texel is decoded; the resampling runs under the
/// panic guard.
pub fn load(path: &Path) -> Result<Skybox> {
    if !is_image(path) {
        return Err(Error::input(
            path,
            format!("not a sky: a skybox is a folder of six faces or one panorama image (.{})", EXTENSIONS.join(" .")),
        ));
    }
    let image = read_image_checked(path, 2 * MAX_PANORAMA_HEIGHT, |(width, height), decode| {
        check_shape(width, height).map_err(|problem| Error::input(path, problem))?;
        let needed = decode + conversion_bytes((width, height), decode) + stored_bytes(face_side(width));
        budget::check_transient(Share::Sky, needed, || format!("a panorama of {width}x{height}"))
            .map_err(|problem| Error::input(path, problem))
    })?;
    let (width, height) = (image.width(), image.height());
    let (texels, repaired) = linear_texels(image);
    let mut warnings = repaired.warnings(path);
    let panorama = Panorama { width, height, texels };
    let size = panorama.face_side();
    if width / 4 > size {
        warnings.push(format!(
            "{}: panorama of {width}x{height} resampled to faces of {size}x{size} (the sky's memory budget)",
            path.display()
        ));
    }
    for w in &warnings {
        log::warn!("{w}");
    }
    let name = path.file_stem().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| "panorama".into());
    let faces = crate::guard::catch(|| panorama.to_faces(size))
        .map_err(|panic| Error::input(path, format!("resampling the panorama failed: {panic}")))?;
    Ok(Skybox::from_faces(name, size, faces, warnings))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::skybox::direction_to_face;

    #[test]
    fn directions_and_coordinates_are_inverse_and_oriented_as_documented() {
        let close = |a: Vec3, b: Vec3| (a - b).length() < 1e-5;
        assert!(close(direction(0.5, 0.5), Vec3::NEG_Z), "centre column looks along -Z");
        assert!(close(direction(0.75, 0.5), Vec3::X), "three quarters along +X");
        assert!(close(direction(0.25, 0.5), Vec3::NEG_X), "a quarter along -X");
        assert!(close(direction(0.0, 0.5), Vec3::Z) && close(direction(1.0, 0.5), Vec3::Z), "edges along +Z");
        assert!(close(direction(0.3, 0.0), Vec3::Y) && close(direction(0.3, 1.0), Vec3::NEG_Y));
        for (u, v) in [(0.1, 0.2), (0.5, 0.5), (0.9, 0.7), (0.62, 0.95)] {
            let (u2, v2) = coordinates(direction(u, v));
            assert!((u - u2).abs() < 1e-5 && (v - v2).abs() < 1e-5, "({u}, {v}) came back as ({u2}, {v2})");
        }
    }

    #[test]
    fn a_panorama_coloured_by_direction_lands_on_the_matching_cube_faces() {
        // Each direction coloured by the cube face it looks through; every face's texels,
        // resampled from the panorama, must come back with that face's colour (the seams blend).
        let colour = |face: usize| Vec3::new(face as f32, 10.0 - face as f32, 1.0 + (face % 2) as f32);
        let panorama = Panorama::from_fn(256, 128, |d| colour(direction_to_face(d).0));
        let size = panorama.face_side();
        assert_eq!(size, 64);
        for (face, texels) in panorama.to_faces(size).iter().enumerate() {
            let inner = texels.iter().enumerate().filter(|(i, _)| {
                let (x, y) = (i % size as usize, i / size as usize);
                (4..size as usize - 4).contains(&x) && (4..size as usize - 4).contains(&y)
            });
            for (i, t) in inner {
                assert!(
                    (Vec3::from(*t) - colour(face)).abs().max_element() < 1e-4,
                    "face {face} ({}) texel {i}: {t:?}",
                    FACE_NAMES[face].0
                );
            }
        }
    }

    #[test]
    fn sampling_is_bilinear_and_wraps_around_the_horizon() {
        let panorama = Panorama {
            width: 4,
            height: 2,
            texels: vec![[0.0; 3], [1.0; 3], [2.0; 3], [3.0; 3], [0.0; 3], [1.0; 3], [2.0; 3], [3.0; 3]],
        };
        // Half-way between texel columns 1 and 2, and between the last column and the first.
        assert!((panorama.sample(0.5, 0.25).x - 1.5).abs() < 1e-6);
        assert!((panorama.sample(1.0, 0.25).x - 1.5).abs() < 1e-6, "wraps: {}", panorama.sample(1.0, 0.25).x);
        assert!((panorama.sample(0.0, 0.25).x - 1.5).abs() < 1e-6);
    }
}
