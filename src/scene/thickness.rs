//! How thick each material's surfaces are, measured from the model's own triangles, for the
//! march (`shaders/common/march.wgsl`): a depth sample is taken to be a slab of the scene's default
//! thickness unless its material says it is thinner.
//!
//! - A **cut-out** material (an alpha mask: OBJ `map_d`, glTF `MASK`) is a sheet: thickness 0.
//!   Its holes are the point of it, and a slab would close them.
//! - Any other material is cut into its connected pieces (triangles that share a corner's
//!   position); a piece's thickness is its least extent over 13 directions (the three axes, the
//!   six face diagonals, the four body diagonals: a box's is its thinnest side, a sphere's its
//!   diameter). A flat piece (an open floor, a wall quad) has none to measure and counts as
//!   solid: consecutive samples on it are bridged in the march, and a sheet the camera sees
//!   edge-on only at a silhouette gains nothing from being thin, while sparse far steps along a
//!   receding floor would leak sky between them.
//! - The material's thickness is the area-weighted median of its pieces'. Only one thinner than
//!   half the default thickness is kept ([`THIN_SHARE`]): the march takes the thinner of the two,
//!   and a material within a factor of two of the default changes too little to pay for the
//!   G-buffer's thickness layer.

use glam::Vec3;
use hashbrown::HashMap;

use super::model::Model;

/// The 13 directions of the extents (unnormalised: each extent is divided by its length).
const DIRECTIONS: [[f32; 3]; 13] = [
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 0.0, 1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, 1.0],
    [0.0, 1.0, -1.0],
    [1.0, 1.0, 1.0],
    [1.0, 1.0, -1.0],
    [1.0, -1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// A piece thinner than this share of the model's bounding radius is flat (a sheet with no
/// inside): its thickness is not measured.
const FLAT: f32 = 1e-4;

/// One connected piece of a material: its triangles' area and its extents.
#[derive(Clone, Copy)]
struct Piece {
    area: f32,
    low: [f32; 13],
    high: [f32; 13],
}

impl Piece {
    fn new() -> Self {
        Self { area: 0.0, low: [f32::INFINITY; 13], high: [f32::NEG_INFINITY; 13] }
    }

    fn add(&mut self, p: Vec3) {
        for (k, d) in DIRECTIONS.iter().enumerate() {
            let x = p.dot(Vec3::from(*d)) / Vec3::from(*d).length();
            self.low[k] = self.low[k].min(x);
            self.high[k] = self.high[k].max(x);
        }
    }

    /// The least extent over the directions.
    fn thickness(&self) -> f32 {
        (0..13).map(|k| self.high[k] - self.low[k]).fold(f32::INFINITY, f32::min)
    }
}

/// Union-find over a material's corners, by position.
struct Pieces {
    parent: Vec<u32>,
}

impl Pieces {
    fn root(&mut self, mut i: u32) -> u32 {
        while self.parent[i as usize] != i {
            let up = self.parent[self.parent[i as usize] as usize];
            self.parent[i as usize] = up;
            i = up;
        }
        i
    }

    fn join(&mut self, a: u32, b: u32) {
        let (a, b) = (self.root(a), self.root(b));
        if a != b {
            self.parent[a.max(b) as usize] = a.min(b);
        }
    }
}

/// A material is thin where it is thinner than this share of the default thickness.
pub const THIN_SHARE: f32 = 0.5;

/// The thickness class of the default slab. The G-buffer's thickness layer keeps, in the low
/// 8 bits of each pixel's depth, the surface's class in bits 0-2 (7 the default
/// thickness, 0 a sheet, `k` in 1-6 the default times 2^(k − 7), from a 64th to a half) and its
/// tilt from the view ray in bits 3-7 (`shaders/common/thickness.wgsl`).
pub const FULL_THICKNESS: u32 = 7;

const _: () = assert!(FULL_THICKNESS < 1 << 3, "a class fits its three bits");

/// The class of a thickness `ratio` times the default (`None`: the default), the nearest power
/// of two, never above half the default nor below a 64th of it; 0 (a sheet) only for 0.
pub fn thickness_code(ratio: Option<f32>) -> u32 {
    match ratio {
        None => FULL_THICKNESS,
        Some(r) if !(r > 0.0) => 0,
        Some(r) => (7.0 + r.log2()).round().clamp(1.0, 6.0) as u32,
    }
}

/// The ratio to the default thickness a class stands for (the march's decoding).
pub fn thickness_ratio(code: u32) -> f32 {
    match code {
        0 => 0.0,
        FULL_THICKNESS.. => 1.0,
        k => (k as f32 - 7.0).exp2(),
    }
}

impl Model {
    /// The scene's default sampling radius: a tenth of the model's bounding radius.
    pub fn default_radius(&self) -> f32 {
        0.1 * self.bounds.radius()
    }

    /// Each material's thickness code for the G-buffer's thickness layer ([`thickness_code`]
    /// of [`Model::material_thickness`] against the scene's default thickness).
    /// Logs the thin ones, so a user can see why a scene draws the thickness layer.
    pub fn thickness_codes(&self) -> Vec<u32> {
        let default = crate::render::THICKNESS_RADII * self.default_radius();
        let thickness = self.material_thickness(THIN_SHARE * default);
        let thin: Vec<String> = (self.materials.iter().zip(&thickness))
            .filter_map(|(m, t)| {
                t.map(|t| match t {
                    0.0 => format!("'{}' a cut-out sheet", crate::text::bounded_name(&m.name)),
                    t => format!("'{}' {t:.3}", crate::text::bounded_name(&m.name)),
                })
            })
            .collect();
        if !thin.is_empty() {
            log::info!("thinner than the march's default thickness {default:.3}: {}", thin.join(", "));
        }
        thickness.into_iter().map(|t| thickness_code(t.map(|t| t / default))).collect()
    }

    /// Each material's thickness where it is thinner than `thin` (model units), `None` where
    /// it is not (module docs): cut-outs 0, thin solids their measured thickness.
    pub fn material_thickness(&self, thin: f32) -> Vec<Option<f32>> {
        let mut thickness = vec![None; self.materials.len()];
        let flat = FLAT * self.bounds.radius();
        for part in &self.parts {
            let Some(material) = self.materials.get(part.material) else { continue };
            let measured = if material.cutout.is_some() { 0.0 } else { self.part_thickness(part, flat) };
            if measured < thin {
                thickness[part.material] = Some(measured);
            }
        }
        thickness
    }

    /// The area-weighted median thickness of a part's connected pieces (a flat piece counts as
    /// infinitely thick); infinity for a part with no area.
    fn part_thickness(&self, part: &super::model::Part, flat: f32) -> f32 {
        let first = part.first_index as usize;
        let indices = &self.indices[first..first + part.index_count as usize];
        let position = |i: u32| Vec3::from(self.vertices[i as usize].position);
        // Corners numbered within the part, one number a position.
        let mut numbers: HashMap<[u32; 3], u32> = HashMap::new();
        let corners: Vec<u32> = indices
            .iter()
            .map(|&i| {
                let key = position(i).to_array().map(f32::to_bits);
                let next = numbers.len() as u32;
                *numbers.entry(key).or_insert(next)
            })
            .collect();
        let mut pieces = Pieces { parent: (0..numbers.len() as u32).collect() };
        for t in corners.chunks_exact(3) {
            pieces.join(t[0], t[1]);
            pieces.join(t[0], t[2]);
        }
        let mut by_root: HashMap<u32, Piece> = HashMap::new();
        for (t, c) in indices.chunks_exact(3).zip(corners.chunks_exact(3)) {
            let piece = by_root.entry(pieces.root(c[0])).or_insert_with(Piece::new);
            let [a, b, c] = [position(t[0]), position(t[1]), position(t[2])];
            piece.area += 0.5 * (b - a).cross(c - a).length();
            for p in [a, b, c] {
                piece.add(p);
            }
        }
        let mut measured: Vec<(f32, f32)> = by_root
            .values()
            .filter(|p| p.area > 0.0 && p.area.is_finite())
            .map(|p| {
                let t = p.thickness();
                (if t > flat { t } else { f32::INFINITY }, p.area)
            })
            .collect();
        measured.sort_by(|a, b| a.0.total_cmp(&b.0));
        let total: f32 = measured.iter().map(|m| m.1).sum();
        let mut below = 0.0;
        for (t, area) in measured {
            below += area;
            if below >= 0.5 * total {
                return t;
            }
        }
        f32::INFINITY
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::{thickness_code, thickness_ratio, FULL_THICKNESS};
    use crate::scene::builtin::MeshBuilder;
    use crate::scene::model::{Cutout, Material};

    #[test]
    fn a_class_stands_for_its_thickness_within_a_factor_of_the_square_root_of_two() {
        assert_eq!(thickness_code(None), FULL_THICKNESS);
        assert_eq!(thickness_code(Some(0.0)), 0);
        assert_eq!(thickness_ratio(0), 0.0);
        assert_eq!(thickness_ratio(FULL_THICKNESS), 1.0);
        for ratio in [0.5, 0.3, 0.14, 0.05, 0.02] {
            let back = thickness_ratio(thickness_code(Some(ratio)));
            assert!((back / ratio).log2().abs() <= 0.5 + 1e-6, "{ratio} -> {back}");
        }
        assert_eq!(thickness_ratio(thickness_code(Some(0.9))), 0.5, "a thin class is never above half");
        assert_eq!(thickness_code(Some(1e-9)), 1, "the thinnest class, not a sheet");
    }

    #[test]
    fn thin_boxes_measure_their_thinnest_side_and_open_floors_count_as_solid() {
        let v = Vec3::new;
        let mut b = MeshBuilder::default();
        let floor = b.material(Material::plain("floor", [1.0; 3]));
        let fins = b.material(Material::plain("fins", [1.0; 3]));
        let block = b.material(Material::plain("block", [1.0; 3]));
        b.floor(floor, 2.0);
        for k in 0..4 {
            let x = 0.2 * k as f32;
            b.cuboid(fins, v(x, 0.0, -1.0), v(x + 0.04, 1.0, 0.0), false);
        }
        b.cuboid(block, v(-1.0, 0.0, -1.0), v(-0.5, 0.8, 0.0), true);
        let model = b.build("pieces").unwrap();
        let t = model.material_thickness(0.3);
        assert_eq!(t[0], None, "an open floor is a sheet with no inside: solid");
        let fin = t[1].expect("the fins are thinner than the default");
        assert!((fin - 0.04).abs() < 1e-4, "fins {fin}");
        assert_eq!(t[2], None, "a 0.5-wide block is thicker than 0.3");
        // Thicker than the default: not kept.
        assert_eq!(model.material_thickness(0.03)[1], None);
    }

    #[test]
    fn a_cut_out_material_is_a_sheet_and_a_turned_slab_measures_its_own_thickness() {
        let v = Vec3::new;
        let mut b = MeshBuilder::default();
        let mut leaf = Material::plain("leaf", [0.2, 0.8, 0.2]);
        leaf.cutout = Some(Cutout { mask: None, factor: 1.0, cutoff: 0.5 });
        let leaf = b.material(leaf);
        let slab = b.material(Material::plain("slab", [1.0; 3]));
        b.quad(leaf, [v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(1.0, 1.0, 0.0), v(0.0, 1.0, 0.0)]);
        // A slab 0.05 thick, turned 45° about y: its thin side along a face diagonal.
        let turn = glam::Quat::from_rotation_y(std::f32::consts::FRAC_PI_4);
        let mut corners = |a: Vec3, b2: Vec3, c: Vec3, d: Vec3| b.quad(slab, [a, b2, c, d].map(|p| turn * p));
        let (x0, x1, y1, z0, z1) = (-1.0, 1.0, 1.0, 0.0, 0.05);
        corners(v(x0, 0.0, z1), v(x1, 0.0, z1), v(x1, y1, z1), v(x0, y1, z1));
        corners(v(x1, 0.0, z0), v(x0, 0.0, z0), v(x0, y1, z0), v(x1, y1, z0));
        corners(v(x1, 0.0, z1), v(x1, 0.0, z0), v(x1, y1, z0), v(x1, y1, z1));
        corners(v(x0, 0.0, z0), v(x0, 0.0, z1), v(x0, y1, z1), v(x0, y1, z0));
        let model = b.build("sheets").unwrap();
        let t = model.material_thickness(0.5);
        assert_eq!(t[0], Some(0.0));
        let slab = t[1].expect("thin");
        assert!((slab - 0.05).abs() < 1e-3, "slab {slab}");
    }
}
