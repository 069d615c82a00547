//! What is rendered: a model, point lights, a sky and a camera, with defaults that scale with
//! the model's bounds so a model in millimetres and one in kilometres both look right.

pub mod bounds;
pub mod builtin;
pub mod camera;
pub mod files;
mod finish;
mod gltf_data;
mod gltf_mesh;
pub mod gltf_model;
pub mod irradiance;
pub mod lights;
pub mod load;
pub mod model;
pub mod named;
pub mod obj_model;
pub mod obj_text;
pub mod panorama;
pub mod room;
mod sky_files;
pub mod skybox;
mod tangents;
pub mod texture;
pub mod thickness;
mod triangle;

pub use bounds::Bounds;
pub use camera::OrbitCamera;
pub use lights::{LightRig, PointLight};
pub use load::{
    asset, is_model, load_model, load_model_file, load_skybox, DEFAULT_LIGHTS, DEFAULT_MODEL, DEFAULT_SKYBOX,
    SKYBOX_ROOT,
};
pub use model::{Material, Model, Vertex};
pub use room::Layout;
pub use skybox::Skybox;

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
        self.model.default_radius()
    }
}
