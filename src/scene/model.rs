//! Models: triangles grouped by material, as the G-buffer pass draws them. The loaders are
//! [`super::obj_model`] (Wavefront OBJ + MTL) and [`super::gltf_model`] (glTF 2.0); both build
//! their triangles with `triangle::push_triangle` and end in `finish::finish`; the tangents of
//! normal-mapped models are `tangents.rs`'s.

use std::hash::{BuildHasher, RandomState};

use glam::Vec3;

use super::bounds::Bounds;
pub use super::texture::{texture_file_name, TextureImage};
pub use super::triangle::Vertex;
use super::triangle::{smooth_shaded, wound_against};
use crate::{Error, Result};

/// Surface description: Blinn-Phong with optional diffuse and specular maps, a tangent-space
/// normal map and an alpha cutout.
#[derive(Clone, Debug)]
pub struct Material {
    pub name: String,
    /// Linear diffuse albedo (multiplies the diffuse map).
    pub diffuse: [f32; 3],
    /// Linear specular colour; the G-buffer keeps its mean as the specular strength.
    pub specular: [f32; 3],
    pub shininess: f32,
    pub diffuse_map: Option<TextureImage>,
    pub specular_map: Option<TextureImage>,
    pub normal_map: Option<NormalMap>,
    pub cutout: Option<Cutout>,
}

/// A tangent-space normal map (linear RGB, OpenGL's convention: x along the texture's u, y up
/// the image, z out of the surface), read in the frame of the model's tangents
/// ([`Model::tangents`]).
#[derive(Clone, Debug)]
pub struct NormalMap {
    pub image: TextureImage,
    /// Multiplies the map's x and y (glTF's `scale`, OBJ's `-bm`): 0 is flat, 1 the map as drawn.
    pub scale: f32,
}

impl NormalMap {
    /// The largest scale kept: past it the map's normals already lie in the surface to four
    /// digits, and a larger one overflows f32 in the shader (a scale of 1e20 squared), where the
    /// surface would fall back to its vertex normals without a word.
    pub const MAX_SCALE: f32 = 1e3;

    /// The scale a file gives (`what` names it in the warning: "material 'a': -bm 1e20"): a
    /// finite number within ±[`NormalMap::MAX_SCALE`]; past it, that bound, and not a finite
    /// number, 1; either with a warning.
    pub fn checked_scale(scale: f32, what: &str, warnings: &mut Vec<String>) -> f32 {
        if !scale.is_finite() {
            warnings.push(format!("{what} is not a finite number; the normal map is read at scale 1"));
            return 1.0;
        }
        if scale.abs() > Self::MAX_SCALE {
            let kept = Self::MAX_SCALE.copysign(scale);
            warnings.push(format!(
                "{what} is beyond ±{}; the normal map is read at scale {kept} (its normals lie in the surface)",
                Self::MAX_SCALE
            ));
            return kept;
        }
        scale
    }
}

/// An alpha cutout: a texel whose coverage is below `cutoff` is a hole in every pass that
/// writes depth, and in the truth.
#[derive(Clone, Debug)]
pub struct Cutout {
    /// Coverage in the alpha channel (often the colour map itself); `None`: `factor` alone.
    pub mask: Option<TextureImage>,
    /// Multiplies the mask's coverage (glTF's base colour alpha).
    pub factor: f32,
    pub cutoff: f32,
}

impl Cutout {
    /// The coverage at texture coordinate `uv` (nearest texel of the mask, times the factor; the
    /// factor alone without a mask).
    pub fn coverage_at(&self, uv: [f32; 2]) -> f32 {
        match &self.mask {
            Some(mask) => self.factor * mask.texel(uv)[3] as f32 / 255.0,
            None => self.factor,
        }
    }
}

impl Cutout {
    /// Whether the cut-out leaves nothing of its surface: every texel's coverage (or the factor
    /// alone, without a mask) is below the cutoff, as [`Cutout::coverage_at`] reads it.
    pub fn removes_all(&self) -> bool {
        let hole = |coverage: f32| !(coverage >= self.cutoff);
        match &self.mask {
            None => hole(self.factor),
            Some(mask) => mask.rgba.chunks_exact(4).all(|t| hole(self.factor * t[3] as f32 / 255.0)),
        }
    }
}

impl Material {
    pub fn plain(name: &str, diffuse: [f32; 3]) -> Self {
        Self {
            name: name.into(),
            diffuse,
            specular: [0.0; 3],
            shininess: 32.0,
            diffuse_map: None,
            specular_map: None,
            normal_map: None,
            cutout: None,
        }
    }

    /// Whether it reads a colour map (diffuse or specular).
    pub fn is_textured(&self) -> bool {
        self.diffuse_map.is_some() || self.specular_map.is_some()
    }
}

/// A run of indices drawn with one material.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Part {
    pub first_index: u32,
    pub index_count: u32,
    pub material: usize,
}

/// A model smaller than this keeps too few bits of its shape in 32-bit positions (its vertices
/// sit near the smallest normal float, 1.2e-38): refused rather than scaled up.
pub const MIN_SHAPE_RADIUS: f32 = 1e-32;
/// The smallest and largest bounding radius a model keeps as it is; outside, it is scaled to 1.
pub const MIN_EXTENT: f32 = 1e-6;
pub const MAX_EXTENT: f32 = 1e9;
/// A model farther than this many of its radii from the origin is moved to its centre...
pub const REBASE_RADII: f32 = 1e3;
/// ...and one farther than this many is refused: its positions hold under 4 bits of its shape.
pub const MAX_OFFSET_RADII: f32 = 1e6;

/// Triangles ready for upload: one vertex and one index buffer, parts sorted by material.
#[derive(Clone, Debug)]
pub struct Model {
    pub name: String,
    pub vertices: Vec<Vertex>,
    /// One per vertex where a material has a normal map, else empty: the tangent along the
    /// texture's u in xyz and in w the bitangent's sign (bitangent = w · normal × tangent, up the
    /// image), from the file or MikkTSpace ([`Model::generate_tangents`]).
    pub tangents: Vec<[f32; 4]>,
    pub indices: Vec<u32>,
    pub parts: Vec<Part>,
    pub materials: Vec<Material>,
    pub bounds: Bounds,
    /// What was repaired or replaced while loading, one line each.
    pub warnings: Vec<String>,
}

impl Model {
    /// Builds a model from triangles grouped by material (`groups[i]` are the triangles, as
    /// vertex triples, of `materials[i]`). Fails when there is nothing to draw. A triangle wound
    /// against its vertex normals is turned to agree with them (the loaders have done so already,
    /// and counted them): the G-buffer takes the side of a surface the camera sees from the
    /// rasteriser's facing.
    pub fn from_groups(name: &str, materials: Vec<Material>, groups: Vec<Vec<Vertex>>) -> Result<Self> {
        let mut vertices = Vec::new();
        let mut indices = Vec::new();
        let mut parts = Vec::new();
        for (material, mut triangles) in groups.into_iter().enumerate() {
            if triangles.is_empty() {
                continue;
            }
            for t in triangles.chunks_exact_mut(3) {
                let pos = [0, 1, 2].map(|k| Vec3::from(t[k].position));
                if wound_against(pos, t.iter().map(|v| Vec3::from(v.normal)).sum()) {
                    t.swap(1, 2);
                }
            }
            let first_index = indices.len() as u32;
            for v in triangles {
                indices.push(vertices.len() as u32);
                vertices.push(v);
            }
            parts.push(Part { first_index, index_count: indices.len() as u32 - first_index, material });
        }
        let bounds = Bounds::from_points(vertices.iter().map(|v| Vec3::from(v.position)))
            .ok_or_else(|| Error::input(name, "no triangles with finite vertices"))?;
        Ok(Self {
            name: name.into(),
            vertices,
            indices,
            parts,
            materials,
            bounds,
            tangents: Vec::new(),
            warnings: Vec::new(),
        })
    }

    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// What the alpha cut-outs remove entirely, in a line: the materials whose every texel is a
    /// hole, the share of the triangles they hold, and whether anything is left to draw. `None`
    /// when no material is cut away whole (leaves and grilles keep some of their texels).
    pub fn cut_away(&self) -> Option<String> {
        let whole: Vec<usize> = (0..self.materials.len())
            .filter(|&i| self.materials[i].cutout.as_ref().is_some_and(Cutout::removes_all))
            .collect();
        let triangles: usize =
            self.parts.iter().filter(|p| whole.contains(&p.material)).map(|p| p.index_count as usize / 3).sum();
        if triangles == 0 {
            return None;
        }
        let mut names: Vec<String> = whole
            .iter()
            .filter(|&&i| self.parts.iter().any(|p| p.material == i))
            .take(4)
            .map(|&i| format!("'{}'", crate::text::bounded_name(&self.materials[i].name)))
            .collect();
        let drawn = whole.iter().filter(|&&i| self.parts.iter().any(|p| p.material == i)).count();
        if drawn > names.len() {
            names.push(format!("and {} more", drawn - names.len()));
        }
        let total = self.triangle_count().max(1);
        let share = 100.0 * triangles as f64 / total as f64;
        let verdict = if triangles >= total {
            "nothing of the model is left to draw".to_string()
        } else {
            format!("{triangles} of its {total} triangles ({share:.1}%) are not drawn")
        };
        Some(format!(
            "{verdict}: the alpha cut-out of material {} removes every texel (coverage below the cutoff everywhere)",
            names.join(", ")
        ))
    }

    pub fn is_textured(&self) -> bool {
        self.materials.iter().any(Material::is_textured)
    }

    /// Leaves out the normal maps and alpha cutouts (`--no-surface-maps`): the surfaces as their
    /// vertex normals and triangles make them.
    pub fn drop_surface_maps(&mut self) {
        for m in &mut self.materials {
            m.normal_map = None;
            m.cutout = None;
        }
        self.tangents.clear();
    }

    /// Whether a drawn material has a normal map (the model then has tangents).
    pub fn is_normal_mapped(&self) -> bool {
        self.parts.iter().any(|p| self.materials[p.material].normal_map.is_some())
    }

    /// Whether the model is smooth-shaded somewhere (a sphere, a figure; not a box): a triangle
    /// whose normal turns across it ([`smooth_shaded`]).
    pub fn has_smooth_normals(&self) -> bool {
        self.indices.chunks_exact(3).any(|t| smooth_shaded([t[0], t[1], t[2]].map(|i| self.vertices[i as usize])))
    }

    /// Whether there is a tangent for every vertex: normal maps are drawn (and traced) only then;
    /// a model built in code with a normal map and no `Model::generate_tangents` draws its
    /// vertex normals.
    pub fn has_tangents(&self) -> bool {
        !self.vertices.is_empty() && self.tangents.len() == self.vertices.len()
    }

    /// Shares each vertex among the triangles that use it: every loader's triangle brings three
    /// vertices of its own (`triangle::push_triangle`), so without this the G-buffer's vertex
    /// stage ran three times a triangle (0.69 times on the nanosuit after it; the G-buffer pass
    /// 6% faster on lavapipe). Vertices merge where they are the same to the bit, tangent
    /// included, so nothing drawn changes. Run after the tangents are made: MikkTSpace writes one
    /// per corner. In place, in the order of first use; the table holds only the kept vertices'
    /// indices (about 5 bytes a vertex besides the model).
    pub fn weld(&mut self) {
        let state = RandomState::new();
        let mut table = hashbrown::HashTable::<u32>::with_capacity(self.vertices.len());
        let mut renumbered = vec![0u32; self.vertices.len()];
        let mut kept = 0usize;
        for (i, number) in renumbered.iter_mut().enumerate() {
            let key = self.weld_key(i);
            let hash = state.hash_one(key);
            if let Some(&earlier) = table.find(hash, |&k| self.weld_key(k as usize) == key) {
                *number = earlier;
                continue;
            }
            // New: moved down to the next place kept (never above `i`, and every place below `i`
            // already read).
            self.vertices[kept] = self.vertices[i];
            if !self.tangents.is_empty() {
                self.tangents[kept] = self.tangents[i];
            }
            table.insert_unique(hash, kept as u32, |&k| state.hash_one(self.weld_key(k as usize)));
            *number = kept as u32;
            kept += 1;
        }
        for index in &mut self.indices {
            *index = renumbered[*index as usize];
        }
        self.vertices.truncate(kept);
        if !self.tangents.is_empty() {
            self.tangents.truncate(kept);
        }
    }

    /// Vertex `i`'s bits, its tangent's with it (zero where the model has none).
    fn weld_key(&self, i: usize) -> [u32; 12] {
        let tangent = self.tangents.get(i).map_or([0; 4], |t| t.map(f32::to_bits));
        let mut key = [0; 12];
        key[..8].copy_from_slice(&bytemuck::cast::<Vertex, [u32; 8]>(self.vertices[i]));
        key[8..].copy_from_slice(&tangent);
        key
    }

    /// World-space triangle `i` as three positions.
    pub fn triangle(&self, i: usize) -> [Vec3; 3] {
        let p = |k: usize| Vec3::from(self.vertices[self.indices[3 * i + k] as usize].position);
        [p(0), p(1), p(2)]
    }

    /// Brings a model whose coordinates 32-bit floats cannot shade into a range they can, saying
    /// what it did, or refuses it.
    ///
    /// * A bounding radius outside [`MIN_EXTENT`, `MAX_EXTENT`] (normals and depths underflow or
    ///   overflow in the shaders: a model 1e-20 across rendered mostly non-finite pixels) is
    ///   scaled about its centre to a radius of 1.
    /// * A model farther from the origin than [`MAX_OFFSET_RADII`] of its radii keeps too few bits
    ///   of its shape in its positions (already rounded when the file was read): refused. One
    ///   farther than [`REBASE_RADII`] radii is moved to its bounding box's centre, so the
    ///   camera-relative maths on the GPU keeps its precision.
    pub fn fit_to_f32(&mut self) -> std::result::Result<Vec<String>, String> {
        let mut said = Vec::new();
        if self.bounds.max == self.bounds.min {
            return Err(format!(
                "all its vertices lie at one point ({:?}): nothing to draw (a scale of 0?)",
                self.bounds.min.to_array()
            ));
        }
        let (center, radius) = (self.bounds.center(), self.bounds.radius());
        if radius < MIN_SHAPE_RADIUS {
            return Err(format!(
                "it is {:e} across: 32-bit floats cannot hold a shape below {MIN_SHAPE_RADIUS:e} (scale it up in the file)",
                2.0 * radius
            ));
        }
        let distance = center.length();
        if !(radius > 0.0) || distance / radius > MAX_OFFSET_RADII {
            return Err(format!(
                "the model lies {distance:e} from the origin and is {:e} across: 32-bit positions cannot hold its \
                 shape there; move it nearer the origin",
                2.0 * radius
            ));
        }
        if distance > REBASE_RADII * radius {
            self.translate(-center);
            said.push(format!(
                "moved by {:?} to its bounding box's centre: {distance:e} from the origin is {:.0} of its radii, \
                 more than the GPU's 32-bit maths keeps precise",
                (-center).to_array(),
                distance / radius
            ));
        }
        if !(MIN_EXTENT..=MAX_EXTENT).contains(&radius) {
            let (c, k) = (self.bounds.center(), 1.0 / radius);
            self.translate(-c);
            self.scale(k);
            self.translate(c * k);
            said.push(format!(
                "scaled by {k:e} to a bounding radius of 1: a radius of {radius:e} is outside what 32-bit floats \
                 shade ({MIN_EXTENT:e} to {MAX_EXTENT:e}); lengths given in model units apply to the scaled model"
            ));
        }
        Ok(said)
    }

    fn translate(&mut self, by: Vec3) {
        for v in &mut self.vertices {
            v.position = (Vec3::from(v.position) + by).into();
        }
        self.bounds = Bounds { min: self.bounds.min + by, max: self.bounds.max + by };
    }

    /// Uniformly scales the model about the origin (the stability suite's scale cases).
    pub fn scaled(mut self, factor: f32) -> Self {
        self.scale(factor);
        self
    }

    fn scale(&mut self, factor: f32) {
        for v in &mut self.vertices {
            v.position = (Vec3::from(v.position) * factor).into();
        }
        self.bounds = Bounds { min: self.bounds.min * factor, max: self.bounds.max * factor };
    }
}
