//! The end every loader shares: the model from its triangles, brought into f32's range, its
//! tangents made and its vertices shared, and the loader's warnings logged (a few lines of a kind).

use std::path::Path;

use super::model::{Material, Model, Vertex};
use crate::budget::{self, Share};
use crate::{Error, Result};

/// The end of every loader: the model named after its file from triangles grouped by material
/// (an error when there are none), brought into f32's range, with the loader's warnings logged
/// and kept on it.
pub(super) fn finish(
    path: &Path,
    materials: Vec<Material>,
    groups: Vec<Vec<Vertex>>,
    given_tangents: Option<Vec<[f32; 4]>>,
    mut warnings: Vec<String>,
) -> Result<Model> {
    if groups.iter().all(Vec::is_empty) {
        // What the loader noted (nodes left out, faces dropped) is often why.
        let notes = if warnings.is_empty() { String::new() } else { format!(" (also: {})", warnings.join("; ")) };
        return Err(Error::input(path, format!("{NO_TRIANGLES}{notes}")));
    }
    let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "model".into());
    let mut model = Model::from_groups(&name, materials, groups)
        .map_err(|_| Error::input(path, "no triangles with finite vertices"))?;
    warnings.extend(model.fit_to_f32().map_err(|problem| Error::input(path, problem))?);
    if model.is_normal_mapped() {
        // Sized before they are made: the file's triangles were, without them.
        let triangles = model.triangle_count() as u64;
        let per_triangle = budget::BYTES_PER_TRIANGLE + budget::TANGENT_BYTES_PER_TRIANGLE;
        budget::check(Share::Geometry, triangles.saturating_mul(per_triangle), || {
            format!("{triangles} triangles with tangents for their normal maps")
        })
        .map_err(|problem| Error::input(path, problem))?;
    }
    model.generate_tangents(given_tangents);
    model.weld();
    warnings.extend(model.cut_away());
    log_capped(log::Level::Warn, path, &warnings);
    model.warnings = warnings;
    Ok(model)
}

/// The most lines of one kind of message a load logs; the rest are counted in one line (a model of
/// a hundred thousand materials said a hundred thousand lines).
const LOGGED_LINES: usize = 20;

/// Logs `lines` about the model file `path` at `level`, the first [`LOGGED_LINES`] of them, then
/// how many more there are (all of them stay on the model).
pub(super) fn log_capped(level: log::Level, path: &Path, lines: &[String]) {
    for line in lines.iter().take(LOGGED_LINES) {
        log::log!(level, "{}: {line}", path.display());
    }
    if lines.len() > LOGGED_LINES {
        log::log!(level, "{}: and {} more such lines", path.display(), lines.len() - LOGGED_LINES);
    }
}

pub(super) const NO_TRIANGLES: &str = "no triangles to draw (no faces, or only points and lines)";
