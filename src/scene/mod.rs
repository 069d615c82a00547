//! What is rendered: a model, point lights, a sky and a camera, with defaults that scale with
//! the model's bounds so a model in millimetres and one in kilometres both look right.

pub mod builtin;
pub mod camera;
pub mod files;
mod gltf_data;
pub mod gltf_model;
pub mod lights;
pub mod model;
pub mod obj_model;
pub mod obj_text;
pub mod panorama;
pub mod room;
mod sky_files;
pub mod skybox;
pub mod texture;
mod triangle;

use std::path::Path;

use glam::Vec3;

pub use camera::OrbitCamera;
pub use lights::{LightRig, PointLight};
pub use model::{Material, Model, Vertex};
pub use room::Layout;
pub use skybox::Skybox;

use crate::Result;

/// The default model, relative to the repository root.
pub const DEFAULT_MODEL: &str = "models/cornell/cornell.obj";
/// The default sky folder, relative to the repository root.
pub const DEFAULT_SKYBOX: &str = "skyboxes/day";
/// Where sky folders live.
pub const SKYBOX_ROOT: &str = "skyboxes";
/// The default number of point lights, as in the SSDO course project.
pub const DEFAULT_LIGHTS: usize = 8;

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

/// A model lit by point lights.
#[derive(Clone, Debug)]
pub struct Scene {
    pub model: Model,
    pub lights: Vec<PointLight>,
    pub rig: LightRig,
}

impl Scene {
    /// `model` with `count` random lights from `seed`.
    pub fn new(model: Model, count: usize, seed: u64) -> Self {
        let rig = LightRig::for_bounds(&model.bounds);
        let lights = lights::random_lights(count, seed, &model.bounds, &rig);
        Self { model, lights, rig }
    }

    /// Replaces the lights (count and seed) keeping the model.
    pub fn relight(&mut self, count: usize, seed: u64) {
        self.lights = lights::random_lights(count, seed, &self.model.bounds, &self.rig);
    }

    /// Default AO/DO sampling radius: a tenth of the scene radius.
    pub fn default_radius(&self) -> f32 {
        0.1 * self.model.bounds.radius()
    }
}

/// Whether `path` names a model file this program loads: `.obj`, `.gltf` or `.glb`.
pub fn is_model(path: &Path) -> bool {
    path.extension().is_some_and(|e| ["obj", "gltf", "glb"].iter().any(|x| e.eq_ignore_ascii_case(x)))
}

/// Loads a model file by its extension: glTF 2.0 (`.gltf`, `.glb`) or else Wavefront OBJ, with
/// its materials and textures, within the run's memory budget.
pub fn load_model_file(path: &Path) -> Result<Model> {
    if panorama::is_image(path) {
        return Err(crate::Error::input(
            path,
            "an image, not a model: a panorama sky goes to --skybox; models load from OBJ (.obj) and glTF 2.0 (.gltf, .glb)",
        ));
    }
    if gltf_model::is_gltf(path) {
        gltf_model::load(path, crate::budget::texture_room())
    } else {
        obj_model::load_obj(path)
    }
}

/// Loads the model at `path`, or the default scene. When the default file is not there (the
/// binary run outside the repository) the same scene is built in memory instead.
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
        None if Path::new(default).exists() => load(Path::new(default)),
        None => builtin(),
    }
}
