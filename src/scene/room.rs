//! The benchmark room: any model lying on the floor of a closed room that fills the screen, seen
//! by a fixed camera — the set-up of the classic SSAO chapter (a model on its back on the floor
//! of a 15-unit cube (here across the view rather than along it), the camera 5 units in front of it looking down -Z, 45° field of view, near
//! 0.1, far 50). Every pixel is geometry, so the screen-space passes do full work everywhere and
//! their costs compare with a program measured on that set-up (`ssdo bench --scene room`).

use std::path::Path;

use glam::Vec3;

use super::bounds::Bounds;
use super::builtin::MeshBuilder;
use super::camera::OrbitCamera;
use super::model::{Material, Model, Part};
use crate::error::named_choice;
use crate::{Error, Result};

/// Half the room's edge: the chapter's cube is scaled by 7.5.
const HALF_EDGE: f32 = 7.5;
/// The floor's height (the chapter's cube stands at y = 7, so its floor is at -0.5).
const FLOOR: f32 = -0.5;
/// The model's longest side once laid down, and where its middle lies on the floor.
const MODEL_LENGTH: f32 = 8.0;
const MODEL_CENTER_Z: f32 = -2.0;
/// The chapter's room albedo.
const ROOM_ALBEDO: [f32; 3] = [0.95, 0.95, 0.95];

/// How the loaded model is placed: as it is (framed by the orbit camera) or in the room; or one
/// of the report's named scenes (`super::named`), framed as the model is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Layout {
    #[default]
    Model,
    Room,
    Crevices,
    Fence,
    Open,
    Stairs,
}

impl Layout {
    pub const ALL: [Layout; 6] =
        [Layout::Model, Layout::Room, Layout::Crevices, Layout::Fence, Layout::Open, Layout::Stairs];

    pub fn name(self) -> &'static str {
        match self {
            Layout::Model => "model",
            Layout::Room => "room",
            Layout::Crevices => "crevices",
            Layout::Fence => "fence",
            Layout::Open => "open",
            Layout::Stairs => "stairs",
        }
    }

    /// Whether the layout is a named scene, which builds its own model.
    fn named(self) -> bool {
        !matches!(self, Layout::Model | Layout::Room)
    }

    /// The sky the layout is meant to be seen under, where it is not the default (open's
    /// red-blue sky).
    pub fn sky(self) -> Option<std::path::PathBuf> {
        super::named::sky_of(self.name())
    }
}

named_choice!(Layout, "scene", Layout::ALL.map(|l| (l.name(), l)));

/// The built-in figure's size when none is asked for: about a scanned character's.
pub const DEFAULT_FIGURE_TRIANGLES: usize = 50_000;
/// The most triangles the built-in figure is made with (about 320 MB of vertices and indices).
pub const MAX_FIGURE_TRIANGLES: usize = 10_000_000;

impl Layout {
    /// The model of this layout: the file at `path` (or the default scene) scaled by `scale`,
    /// placed; in the room without a file, the built-in figure of `triangles` triangles.
    pub fn load(self, path: Option<&Path>, scale: f32, triangles: Option<usize>) -> Result<Model> {
        if let Some(n) = triangles {
            if self != Self::Room || path.is_some() {
                return Err(Error::Setting(format!(
                    "--triangles {n}: sizes the room's built-in figure; use it with --scene room and no --model"
                )));
            }
            if !(1..=MAX_FIGURE_TRIANGLES).contains(&n) {
                return Err(Error::Setting(format!("--triangles {n}: must be from 1 to {MAX_FIGURE_TRIANGLES}")));
            }
            // The same check as a model file's, before the figure is built.
            let needed = (n as u64).saturating_mul(crate::budget::BYTES_PER_TRIANGLE);
            crate::budget::check(crate::budget::Share::Geometry, needed, || format!("--triangles {n}"))
                .map_err(Error::Setting)?;
        }
        let model = match (self, path) {
            (Self::Room, None) => figure(triangles.unwrap_or(DEFAULT_FIGURE_TRIANGLES))?,
            (named, Some(path)) if named.named() => {
                return Err(Error::Setting(format!(
                    "--model {}: --scene {} builds its own model; --model goes with --scene model or room",
                    path.display(),
                    named.name()
                )))
            }
            (named, None) if named.named() => super::named::by_name(named.name())?.0,
            (_, path) => super::load::load_model(path)?,
        };
        self.arrange(model.scaled(scale))
    }

    pub fn arrange(self, model: Model) -> Result<Model> {
        match self {
            Self::Room => in_room(model),
            _ => Ok(model),
        }
    }

    /// The camera before the command line's flags: the model framed (the report's view of a
    /// named scene too), or the room's fixed view.
    pub fn camera(self, bounds: &Bounds) -> OrbitCamera {
        match self {
            Self::Room => OrbitCamera {
                target: Vec3::ZERO,
                yaw_deg: 0.0,
                pitch_deg: 0.0,
                distance: 5.0,
                fov_y_deg: 45.0,
                near: 0.1,
                far: Some(50.0),
            },
            _ => OrbitCamera::framing(bounds),
        }
    }
}

/// The room's occupant when no model is given: a lying figure of about `triangles` triangles,
/// a body of revolution along +Y (laid down by `in_room`) with a head, a waist and bumps around
/// and along it, so that it has creases for AO and enough triangles to stand for a scanned model.
pub fn figure(triangles: usize) -> Result<Model> {
    use std::f32::consts::{PI, TAU};
    // 2·segments·rings triangles, twice as many rings as segments.
    let segments = ((triangles as f32 / 4.0).sqrt().round() as usize).max(4);
    let rings = 2 * segments;
    let radius = |t: f32, phi: f32| {
        let body = (PI * t).sin().max(0.0).sqrt();
        let neck = 1.0 - 0.45 * (-((t - 0.8) / 0.04).powi(2)).exp();
        let waist = 1.0 - 0.2 * (-((t - 0.45) / 0.08).powi(2)).exp();
        let bumps = 1.0 + 0.06 * (7.0 * phi).cos() * (9.0 * PI * t).sin();
        0.12 * body * neck * waist * bumps
    };
    let mut vertices = Vec::with_capacity((rings + 1) * (segments + 1));
    for j in 0..=rings {
        let t = j as f32 / rings as f32;
        for i in 0..=segments {
            let phi = TAU * i as f32 / segments as f32;
            let r = radius(t, phi);
            vertices.push(super::model::Vertex {
                position: [r * phi.cos(), t, r * phi.sin()],
                normal: [0.0; 3],
                uv: [i as f32 / segments as f32, t],
            });
        }
    }
    let at = |i: usize, j: usize| (j * (segments + 1) + i) as u32;
    let mut indices = Vec::with_capacity(6 * rings * segments);
    for j in 0..rings {
        for i in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            indices.extend_from_slice(&[a, c, b, a, d, c]);
        }
    }
    // Smooth normals: area-weighted face normals summed at each vertex, the seam's two copies
    // joined so it does not show.
    let mut normals = vec![Vec3::ZERO; vertices.len()];
    for tri in indices.chunks_exact(3) {
        let p = |k: usize| Vec3::from(vertices[tri[k] as usize].position);
        let n = (p(1) - p(0)).cross(p(2) - p(0));
        for &k in tri {
            normals[k as usize] += n;
        }
    }
    for j in 0..=rings {
        let sum = normals[at(0, j) as usize] + normals[at(segments, j) as usize];
        normals[at(0, j) as usize] = sum;
        normals[at(segments, j) as usize] = sum;
    }
    for (v, n) in vertices.iter_mut().zip(normals) {
        let up = if v.position[1] < 0.5 { -Vec3::Y } else { Vec3::Y };
        v.normal = n.try_normalize().unwrap_or(up).into();
    }
    let bounds = Bounds::from_points(vertices.iter().map(|v| Vec3::from(v.position))).expect("finite by construction");
    Ok(Model {
        name: format!("figure ({} triangles)", indices.len() / 3),
        parts: vec![Part { first_index: 0, index_count: indices.len() as u32, material: 0 }],
        materials: vec![Material::plain("figure", [0.8, 0.78, 0.74])],
        vertices,
        indices,
        bounds,
        tangents: Vec::new(),
        warnings: Vec::new(),
    })
}

/// `model` laid on its back across the view (its +Y turned to -X, its front +Z up),
/// scaled to `MODEL_LENGTH` along its longest side, centred on the floor of the room; the room is
/// one extra material, a closed cube of six quads (faces are two-sided in the G-buffer).
pub fn in_room(mut model: Model) -> Result<Model> {
    let lay = |v: [f32; 3]| Vec3::new(-v[1], v[2], -v[0]);
    let laid = Bounds::from_points(model.vertices.iter().map(|v| lay(v.position)))
        .ok_or_else(|| Error::input(&model.name, "no triangles with finite vertices"))?;
    let longest = (laid.max - laid.min).max_element();
    let scale = if longest > 0.0 && longest.is_finite() { MODEL_LENGTH / longest } else { 1.0 };
    let offset =
        Vec3::new(0.0, FLOOR, MODEL_CENTER_Z) - scale * Vec3::new(laid.center().x, laid.min.y, laid.center().z);
    for v in &mut model.vertices {
        v.position = (scale * lay(v.position) + offset).into();
        v.normal = lay(v.normal).into();
    }
    for t in &mut model.tangents {
        let [x, y, z] = lay([t[0], t[1], t[2]]).into();
        *t = [x, y, z, t[3]];
    }

    let mut room = MeshBuilder::default();
    let walls = room.material(Material::plain("room", ROOM_ALBEDO));
    let half = Vec3::new(HALF_EDGE, 0.0, HALF_EDGE);
    room.cuboid(walls, -half + FLOOR * Vec3::Y, half + (FLOOR + 2.0 * HALF_EDGE) * Vec3::Y, true);
    let room = room.build("room")?;

    let base = model.vertices.len() as u32;
    let first_index = model.indices.len() as u32;
    model.vertices.extend_from_slice(&room.vertices);
    if !model.tangents.is_empty() {
        // The room's walls have no normal map: no tangents (w = 0).
        model.tangents.resize(model.vertices.len(), [0.0; 4]);
    }
    model.indices.extend(room.indices.iter().map(|i| i + base));
    model.parts.push(Part { first_index, index_count: room.indices.len() as u32, material: model.materials.len() });
    model.materials.extend(room.materials);
    model.bounds = Bounds::from_points(model.vertices.iter().map(|v| Vec3::from(v.position)))
        .expect("the room's own corners are finite");
    model.name = format!("{} in the room", model.name);
    Ok(model)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin;

    #[test]
    fn the_model_lies_on_the_floor_inside_the_room() {
        let model = builtin::cornell().unwrap();
        let triangles = model.triangle_count();
        let room = in_room(model).unwrap();
        assert_eq!(room.triangle_count(), triangles + 12);
        let part = room.parts.last().unwrap();
        assert_eq!(room.materials[part.material].name, "room");
        // The model (every vertex before the room's) rests on the floor, within the walls.
        let model_points = room.vertices[..room.vertices.len() - 36].iter().map(|v| Vec3::from(v.position));
        let b = Bounds::from_points(model_points).unwrap();
        assert!((b.min.y - FLOOR).abs() < 1e-4, "{b:?}");
        assert!(((b.max - b.min).max_element() - MODEL_LENGTH).abs() < 1e-3, "{b:?}");
        assert!(b.min.x > -HALF_EDGE && b.max.x < HALF_EDGE && b.min.z > -HALF_EDGE && b.max.z < HALF_EDGE);
        // The camera stands inside the room.
        let eye = Layout::Room.camera(&room.bounds).eye();
        assert!(eye.abs().max_element() < HALF_EDGE && eye.y > FLOOR);
    }

    #[test]
    fn the_figure_has_the_triangles_asked_for_and_outward_normals() {
        for asked in [1_000, 50_000] {
            let figure = figure(asked).unwrap();
            let got = figure.triangle_count() as f32;
            assert!((got / asked as f32 - 1.0).abs() < 0.05, "{asked} asked, {got} made");
            // Normals point away from the axis (the figure is convex around it).
            for v in figure.vertices.iter().filter(|v| (0.1..0.9).contains(&v.position[1])) {
                let out = Vec3::new(v.position[0], 0.0, v.position[2]);
                assert!(Vec3::from(v.normal).dot(out) > 0.0, "{v:?}");
            }
        }
    }
}
