//! Point lights with random saturated colours, placed around the model from a seed, as in the
//! SSDO course project this program grew from (8 by default). Their strength scales with the model so that a model in
//! millimetres and one in kilometres are lit alike.

use glam::Vec3;
use rand::{rngs::StdRng, RngExt, SeedableRng};

use super::bounds::Bounds;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    pub position: Vec3,
    /// Linear colour with its largest channel 1.
    pub color: Vec3,
    /// Radiant intensity: irradiance at distance d is `intensity / max(d², min_distance²)`.
    pub intensity: f32,
}

/// Light placement and strength for a scene of the given bounds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightRig {
    /// Irradiance a light gives at a quarter of the scene radius, before colour.
    pub strength: f32,
    /// Distances below this count as this (guards the 1/d² at a light lying on a surface).
    pub min_distance: f32,
    /// Half the edge of the emissive cube drawn at each light.
    pub cube_half_size: f32,
}

impl LightRig {
    pub fn for_bounds(bounds: &Bounds) -> Self {
        let r = bounds.radius();
        Self { strength: 2.5, min_distance: 0.02 * r, cube_half_size: 0.018 * r }
    }
}

/// A fully saturated colour from a hue in [0, 1).
pub fn hue_to_rgb(hue: f32) -> Vec3 {
    let h = hue.rem_euclid(1.0) * 6.0;
    let x = 1.0 - (h % 2.0 - 1.0).abs();
    match h as u32 {
        0 => Vec3::new(1.0, x, 0.0),
        1 => Vec3::new(x, 1.0, 0.0),
        2 => Vec3::new(0.0, 1.0, x),
        3 => Vec3::new(0.0, x, 1.0),
        4 => Vec3::new(x, 0.0, 1.0),
        _ => Vec3::new(1.0, 0.0, x),
    }
}

/// `count` lights around `bounds`: on a ring between 35% and 85% of the horizontal half-extent,
/// between 30% and 95% of the height, each with a random saturated colour.
pub fn random_lights(count: usize, seed: u64, bounds: &Bounds, rig: &LightRig) -> Vec<PointLight> {
    let mut rng = StdRng::seed_from_u64(seed);
    let center = bounds.center();
    let extent = bounds.max - bounds.min;
    let quarter = 0.25 * bounds.radius();
    (0..count)
        .map(|_| {
            let angle = rng.random::<f32>() * std::f32::consts::TAU;
            let ring = 0.35 + 0.5 * rng.random::<f32>();
            let height = 0.3 + 0.65 * rng.random::<f32>();
            let position = Vec3::new(
                center.x + 0.5 * extent.x * ring * angle.cos(),
                bounds.min.y + extent.y * height,
                center.z + 0.5 * extent.z * ring * angle.sin(),
            );
            let hue = rng.random::<f32>();
            let saturation = 0.8 + 0.2 * rng.random::<f32>();
            let color = Vec3::ONE.lerp(hue_to_rgb(hue), saturation);
            PointLight { position, color, intensity: rig.strength * quarter * quarter }
        })
        .collect()
}
