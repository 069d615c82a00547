//! Which loader reads a file, where the repository's own files are (the working folder, or the
//! sources the binary was built from), the default model and sky (or, where neither has them,
//! the same scenes built in memory), and the defaults a run starts from.

use std::path::{Path, PathBuf};

use super::model::Model;
use super::skybox::Skybox;
use super::{builtin, gltf_model, obj_model, panorama};
use crate::Result;

/// The default model, relative to the repository root.
pub const DEFAULT_MODEL: &str = "models/cornell/cornell.obj";
/// The default sky folder, relative to the repository root.
pub const DEFAULT_SKYBOX: &str = "skyboxes/day";
/// Where sky folders live.
pub const SKYBOX_ROOT: &str = "skyboxes";
/// The default number of point lights, as in the SSDO course project.
pub const DEFAULT_LIGHTS: usize = 8;

/// The path to read one of the repository's own files (`models/…`, `skyboxes/…`, relative to
/// its root) at: in the working folder where it is there, else beside the sources this binary
/// was built from where it is there (so a run from another folder of the same machine reads the
/// same files and measures the same figures), else `path` as given (whose absence a loader
/// reports, or a built-in stands in for).
pub fn asset(path: &str) -> PathBuf {
    let beside = Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    if Path::new(path).exists() || !beside.exists() {
        PathBuf::from(path)
    } else {
        beside
    }
}

/// Whether `path` names a model file this program loads (`files::MODEL_FORMATS`).
pub fn is_model(path: &Path) -> bool {
    super::files::MODEL_FORMATS.iter().any(|(_, extensions)| super::files::has_extension(path, extensions))
}

/// Loads a model file by its extension: glTF 2.0 (`.gltf`, `.glb`) or else Wavefront OBJ, with
/// its materials and textures, within the run's memory budget.
pub fn load_model_file(path: &Path) -> Result<Model> {
    if panorama::is_image(path) {
        let formats = super::files::model_formats();
        return Err(crate::Error::input(
            path,
            format!("an image, not a model: a panorama sky goes to --skybox; models load from {formats}"),
        ));
    }
    if gltf_model::is_gltf(path) {
        gltf_model::load(path, crate::budget::texture_room())
    } else {
        obj_model::load_obj(path)
    }
}

/// Loads the model at `path`, or the default scene. When the default file is not there
/// ([`asset`]: a binary run away from its repository) the same scene is built in memory instead.
pub fn load_model(path: Option<&Path>) -> Result<Model> {
    load_or_builtin(path, DEFAULT_MODEL, load_model_file, || {
        log::info!("{DEFAULT_MODEL} not found; using the built-in default scene");
        builtin::cornell()
    })
}

/// Loads the sky folder at `path`, or the default sky (built in memory if its folder is absent).
pub fn load_skybox(path: Option<&Path>) -> Result<Skybox> {
    load_or_builtin(path, DEFAULT_SKYBOX, Skybox::load, || {
        log::info!("{DEFAULT_SKYBOX} not found; using the built-in daylight sky");
        Ok(Skybox::from_fn("day", 128, builtin::day_sky))
    })
}

/// `load(path)`; without a path, `load(default)` where the default is there and `builtin()`
/// where it is not.
fn load_or_builtin<T>(
    path: Option<&Path>,
    default: &str,
    load: impl FnOnce(&Path) -> Result<T>,
    builtin: impl FnOnce() -> Result<T>,
) -> Result<T> {
    match path {
        Some(p) => load(p),
        None => match asset(default) {
            found if found.exists() => load(&found),
            _ => builtin(),
        },
    }
}
