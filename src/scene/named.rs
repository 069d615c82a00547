//! Named scenes, for the report (`ssdo report --scene`) and for every command (`--scene`): the
//! default scene, three that stress the screen-space methods (deep crevices, thin fins, a
//! checker-cut fence), an open one under the red-blue sky, and a held-out one (`stairs`) that no
//! estimator or default was tuned on.

use std::path::PathBuf;

use glam::Vec3;

use super::builtin::{self, MeshBuilder};
use super::model::{self, Material, Model};
use crate::{Error, Result};

pub const NAMES: [&str; 5] = ["cornell", "crevices", "fence", "open", "stairs"];

/// The sky `open` is seen under (the repository's; a run without it says so).
const REDBLUE: &str = "skyboxes/redblue";

/// A scene by name, with the sky folder it is meant to be seen under.
pub fn by_name(name: &str) -> Result<(Model, Option<PathBuf>)> {
    match name {
        "cornell" => Ok((super::load::load_model(None)?, None)),
        "crevices" => Ok((crevices()?, None)),
        "fence" => Ok((fence()?, None)),
        "open" => Ok((open()?, sky_of(name))),
        "stairs" => Ok((stairs()?, None)),
        other => Err(Error::Setting(format!("unknown scene '{other}' (expected one of {})", NAMES.join(", ")))),
    }
}

/// The sky the scene `name` is meant to be seen under, where it is not the default.
pub fn sky_of(name: &str) -> Option<PathBuf> {
    (name == "open").then(|| super::load::asset(REDBLUE))
}

/// Thin features and deep crevices: a comb of thin fins with narrow slots between them, a deep
/// slot cut into a block, and thin poles — what a depth buffer sees least of.
pub fn crevices() -> Result<Model> {
    let v = Vec3::new;
    let mut b = MeshBuilder::default();
    let floor = b.material(Material::plain("floor", builtin::WHITE));
    let fins = b.material(Material::plain("fins", [0.8, 0.55, 0.3]));
    let block = b.material(Material::plain("block", [0.3, 0.6, 0.8]));
    b.floor(floor, 2.0);
    for k in 0..8 {
        let x = -1.6 + 0.2 * k as f32;
        b.cuboid(fins, v(x, 0.0, -1.2), v(x + 0.04, 1.0, 0.2), false);
    }
    // A block with a deep, narrow slot from the top.
    b.cuboid(block, v(0.3, 0.0, -1.2), v(0.8, 1.2, 0.2), false);
    b.cuboid(block, v(0.88, 0.0, -1.2), v(1.4, 1.2, 0.2), false);
    b.cuboid(block, v(0.3, 0.0, -1.2), v(1.4, 0.2, 0.2), false);
    for (x, z) in [(-1.2, 1.0), (-0.6, 1.2), (0.0, 0.9), (0.6, 1.3), (1.2, 1.0)] {
        b.cuboid(fins, v(x, 0.0, z), v(x + 0.03, 1.4, z + 0.03), false);
    }
    b.build("crevices")
}

/// A thin cut-out: a fence of one quad whose checker mask cuts half of it away, standing on a
/// floor beside a low block, with a post of its own. The floor behind it sees the sky through
/// the holes; a slab as thick as the scene's default closes them.
pub fn fence() -> Result<Model> {
    let v = Vec3::new;
    let mut b = MeshBuilder::default();
    let floor = b.material(Material::plain("floor", builtin::WHITE));
    let (cells, texels) = ((10u32, 4u32), 8u32);
    let (w, h) = (cells.0 * texels, cells.1 * texels);
    let rgba = (0..w * h)
        .flat_map(|i| {
            let open = ((i % w) / texels + (i / w) / texels) % 2 == 1;
            [150, 110, 70, if open { 0 } else { 255 }]
        })
        .collect();
    let mask = super::texture::TextureImage { width: w, height: h, rgba: std::sync::Arc::new(rgba) };
    let mut slats = Material::plain("fence", [0.6, 0.45, 0.3]);
    slats.cutout = Some(model::Cutout { mask: Some(mask), factor: 1.0, cutoff: 0.5 });
    let fence = b.material(slats);
    let block = b.material(Material::plain("block", [0.3, 0.6, 0.8]));
    b.floor(floor, 2.5);
    b.quad(fence, [v(-1.5, 0.0, 0.0), v(1.5, 0.0, 0.0), v(1.5, 1.2, 0.0), v(-1.5, 1.2, 0.0)]);
    b.cuboid(block, v(-1.2, 0.0, -1.4), v(-0.2, 0.5, -0.8), false);
    b.cuboid(block, v(1.5, 0.0, -0.08), v(1.66, 1.3, 0.08), false);
    b.build("fence")
}

/// An open scene: spheres and a low box on a wide floor, nothing overhead — sky light dominates.
pub fn open() -> Result<Model> {
    let v = Vec3::new;
    let mut b = MeshBuilder::default();
    let floor = b.material(Material::plain("floor", builtin::WHITE));
    let balls = b.material(Material::plain("balls", [0.8, 0.8, 0.75]));
    b.floor(floor, 4.0);
    b.sphere(balls, v(-1.0, 0.6, 0.0), 0.6, 32, 16);
    b.sphere(balls, v(0.6, 0.35, 0.8), 0.35, 24, 12);
    b.sphere(balls, v(1.0, 0.9, -1.0), 0.9, 32, 16);
    b.cuboid(balls, v(-2.5, 0.0, -2.0), v(-1.5, 0.4, -1.0), false);
    b.build("open")
}

/// The held-out scene: a flight of stairs climbing under a deep overhang, with a green side wall
/// and a low parapet — sky light blocked from far away above, coloured bounce from the side, and
/// many small steps for AO. Added to check the estimators on geometry nobody tuned them on.
pub fn stairs() -> Result<Model> {
    let v = Vec3::new;
    let mut b = MeshBuilder::default();
    let ground = b.material(Material::plain("ground", [0.55, 0.5, 0.45]));
    let stone = b.material(Material::plain("stone", [0.75, 0.72, 0.68]));
    let wall = b.material(Material::plain("green_wall", [0.15, 0.6, 0.2]));
    let roof = b.material(Material::plain("roof", [0.6, 0.6, 0.65]));
    b.quad(ground, [v(-3.0, 0.0, 3.0), v(3.0, 0.0, 3.0), v(3.0, 0.0, -3.0), v(-3.0, 0.0, -3.0)]);
    // Eight steps climbing towards -z.
    for k in 0..8 {
        let z = 1.2 - 0.3 * k as f32;
        b.cuboid(stone, v(-1.0, 0.0, z - 0.3), v(1.0, 0.15 * (k + 1) as f32, z), false);
    }
    // The green wall on the left of the flight, full height.
    b.cuboid(wall, v(-1.3, 0.0, -1.6), v(-1.0, 2.2, 1.4), false);
    // An overhang over the upper half, on two pillars, 2.2 high.
    b.cuboid(roof, v(-1.3, 2.2, -1.6), v(1.6, 2.4, 0.0), true);
    b.cuboid(stone, v(1.3, 0.0, -0.3), v(1.5, 2.2, -0.1), false);
    b.cuboid(stone, v(1.3, 0.0, -1.5), v(1.5, 2.2, -1.3), false);
    // A low parapet along the right of the lower steps.
    b.cuboid(stone, v(1.0, 0.0, 0.0), v(1.1, 0.5, 1.4), false);
    b.build("stairs")
}
