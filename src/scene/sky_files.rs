//! Reading a sky from files: the panorama file a path names, the one panorama in a folder
//! ([`super::panorama`]), or a folder's six cube faces, each found under either of its names and
//! checked against the others (square, one size, one kind: HDR or LDR).

use std::path::{Path, PathBuf};

use super::skybox::{
    conversion_bytes, is_hdr, linear_texels, stored_bytes, Skybox, EXTENSIONS, FACE_NAMES, MAX_FACE_SIDE,
    STORED_FACE_SIDE,
};
use super::texture::read_image_checked;
use crate::budget::{self, Share};
use crate::{Error, Result};

impl Skybox {
    /// Loads a sky: the six faces of folder `path`, the panorama file `path`, or the one panorama in
    /// folder `path`. An incomplete or inconsistent folder, or a panorama that is not 2:1, is an
    /// error naming the folder or the file.
    pub fn load(path: &Path) -> Result<Self> {
        let dir = path;
        if dir.is_file() {
            return super::panorama::load(dir);
        }
        if !dir.is_dir() {
            return Err(Error::input(dir, "skybox not found (a folder of six faces or a panorama image)"));
        }
        if let Some(panorama) = super::panorama::in_folder(dir) {
            return super::panorama::load(&panorama);
        }
        if let Some(problem) = super::panorama::several_in_folder(dir) {
            return Err(Error::input(dir, problem));
        }
        let mut faces = Vec::with_capacity(6);
        let mut warnings = Vec::new();
        let mut size = 0;
        let mut kinds = Vec::new();
        let mut first_face = String::new();
        for (index, names) in FACE_NAMES.iter().enumerate() {
            let path = find_face(dir, *names)?;
            // Shape, size and memory from the header, before the face is decoded.
            let mut image = read_image_checked(&path, MAX_FACE_SIDE, |(w, h), decode| {
                let problem = if w == 0 || h == 0 {
                    Some(format!("skybox face is {w}x{h}; a face needs at least one texel"))
                } else if w != h {
                    Some(format!("skybox face is {w}x{h}; faces must be square"))
                } else if index > 0 && w != size {
                    Some(format!(
                        "skybox face is {w}x{w} but {first_face} is {size}x{size}; all faces must be the same size"
                    ))
                } else {
                    let needed = decode + conversion_bytes((w, h), decode) + stored_bytes(w.min(STORED_FACE_SIDE));
                    budget::check_transient(Share::Sky, needed, || format!("skybox faces of {w}x{w}")).err()
                };
                problem.map_or(Ok(()), |problem| Err(Error::input(&path, problem)))
            })?;
            let w = image.width();
            if index == 0 {
                size = w;
                first_face = path.display().to_string();
            }
            // Kept at most STORED_FACE_SIDE² per face, one face at a time, so an 8192² sky takes
            // what a 2048² one does once loaded (0.3 GB, not 4.8 GB) and fits any adapter.
            if w > STORED_FACE_SIDE {
                image = image.resize_exact(STORED_FACE_SIDE, STORED_FACE_SIDE, image::imageops::FilterType::Triangle);
                if index == 0 {
                    warnings.push(format!(
                        "{}: faces of {w}x{w} downscaled to {STORED_FACE_SIDE}x{STORED_FACE_SIDE} (the sky's memory budget)",
                        dir.display()
                    ));
                }
            }
            kinds.push(is_hdr(&image));
            let (texels, repaired) = linear_texels(image);
            warnings.extend(repaired.warnings(&path));
            faces.push(texels);
        }
        if kinds.iter().any(|&k| k != kinds[0]) {
            let hdr: Vec<&str> = FACE_NAMES.iter().zip(&kinds).filter(|(_, &k)| k).map(|(n, _)| n.0).collect();
            return Err(Error::input(
                dir,
                format!("faces mix HDR ({}) and LDR images; use one kind for all six", hdr.join(", ")),
            ));
        }
        for w in &warnings {
            log::warn!("{w}");
        }
        let name =
            dir.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| dir.display().to_string());
        Ok(Self::from_faces(name, size.min(STORED_FACE_SIDE), faces, warnings))
    }
}

/// The one file for a face, under either of its names and any image extension. Two candidates
/// (`right.png` and `px.png`, or `right.png` and `right.jpg`) are an error, not a silent choice;
/// so is a candidate that is not a readable regular file (a folder, a FIFO, a broken link).
fn find_face(dir: &Path, names: (&str, &str)) -> Result<PathBuf> {
    let entries =
        std::fs::read_dir(dir).map_err(|e| Error::input(dir, format!("cannot read the skybox folder: {e}")))?;
    let candidates: Vec<PathBuf> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            let stem = p.file_stem().map(|s| s.to_string_lossy().to_lowercase());
            let ext = p.extension().map(|s| s.to_string_lossy().to_lowercase());
            [names.0, names.1].contains(&stem.as_deref().unwrap_or(""))
                && EXTENSIONS.contains(&ext.as_deref().unwrap_or(""))
        })
        .collect();
    match candidates.as_slice() {
        [] => Err(Error::input(
            dir,
            format!(
                "skybox face '{}' is missing (looked for {}.* and {}.* with .png .jpg .hdr .exr)",
                names.0, names.0, names.1
            ),
        )),
        [one] => match std::fs::metadata(one) {
            Ok(m) if m.is_file() => Ok(one.clone()),
            Ok(_) => Err(Error::input(one, format!("skybox face '{}' is not a regular file", names.0))),
            Err(e) => Err(Error::input(one, format!("skybox face '{}' cannot be read: {e}", names.0))),
        },
        several => {
            let mut list: Vec<String> =
                several.iter().map(|p| p.file_name().unwrap_or_default().to_string_lossy().into_owned()).collect();
            list.sort();
            Err(Error::input(dir, format!("skybox face '{}' is given twice: {}", names.0, list.join(" and "))))
        }
    }
}
