//! Procedural geometry and skies: the default scene (`models/cornell/`), the committed skyboxes
//! (`skyboxes/`), and the small test scenes. `cargo run --example make_assets` writes the files;
//! the same functions serve as a fallback when the repository's assets are not beside the binary.

use std::f32::consts::{PI, TAU};
use std::fmt::Write as _;
use std::path::Path;

use glam::Vec3;

use super::model::{Material, Model, Vertex};
use super::skybox::Skybox;
use crate::output::write_atomic;
use crate::Result;

/// Collects triangles by material.
#[derive(Default)]
pub struct MeshBuilder {
    materials: Vec<Material>,
    groups: Vec<Vec<Vertex>>,
}

impl MeshBuilder {
    pub fn material(&mut self, material: Material) -> usize {
        self.materials.push(material);
        self.groups.push(Vec::new());
        self.materials.len() - 1
    }

    /// A flat quad; corners counter-clockwise as seen from the side the normal points to.
    pub fn quad(&mut self, material: usize, c: [Vec3; 4]) {
        let n = (c[1] - c[0]).cross(c[2] - c[0]).normalize();
        let uv = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
        for k in [0, 1, 2, 0, 2, 3] {
            self.groups[material].push(Vertex { position: c[k].into(), normal: n.into(), uv: uv[k] });
        }
    }

    /// A square floor at y = 0, `half` either way from the origin, facing up.
    pub fn floor(&mut self, material: usize, half: f32) {
        let v = |x: f32, z: f32| Vec3::new(x, 0.0, z);
        self.quad(material, [v(-half, half), v(half, half), v(half, -half), v(-half, -half)]);
    }

    /// An axis-aligned box with outward faces; `bottom` false leaves the face on the floor out.
    pub fn cuboid(&mut self, material: usize, min: Vec3, max: Vec3, bottom: bool) {
        let v = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
        let (a, b) = (min, max);
        self.quad(material, [v(a.x, a.y, b.z), v(b.x, a.y, b.z), v(b.x, b.y, b.z), v(a.x, b.y, b.z)]);
        self.quad(material, [v(b.x, a.y, a.z), v(a.x, a.y, a.z), v(a.x, b.y, a.z), v(b.x, b.y, a.z)]);
        self.quad(material, [v(b.x, a.y, b.z), v(b.x, a.y, a.z), v(b.x, b.y, a.z), v(b.x, b.y, b.z)]);
        self.quad(material, [v(a.x, a.y, a.z), v(a.x, a.y, b.z), v(a.x, b.y, b.z), v(a.x, b.y, a.z)]);
        self.quad(material, [v(a.x, b.y, b.z), v(b.x, b.y, b.z), v(b.x, b.y, a.z), v(a.x, b.y, a.z)]);
        if bottom {
            self.quad(material, [v(a.x, a.y, a.z), v(b.x, a.y, a.z), v(b.x, a.y, b.z), v(a.x, a.y, b.z)]);
        }
    }

    /// A UV sphere with smooth normals.
    pub fn sphere(&mut self, material: usize, center: Vec3, radius: f32, segments: u32, rings: u32) {
        let point = |i: u32, j: u32| {
            let (theta, phi) = (PI * j as f32 / rings as f32, TAU * i as f32 / segments as f32);
            Vec3::new(theta.sin() * phi.cos(), theta.cos(), -theta.sin() * phi.sin())
        };
        for j in 0..rings {
            for i in 0..segments {
                let n = [point(i, j), point(i, j + 1), point(i + 1, j + 1), point(i + 1, j)];
                for k in [0, 1, 2, 0, 2, 3] {
                    let uv = [(i + (k == 2 || k == 3) as u32) as f32 / segments as f32, j as f32 / rings as f32];
                    self.groups[material].push(Vertex {
                        position: (center + radius * n[k]).into(),
                        normal: n[k].into(),
                        uv,
                    });
                }
            }
        }
    }

    pub fn build(self, name: &str) -> Result<Model> {
        let mut model = Model::from_groups(name, self.materials, self.groups)?;
        model.weld();
        Ok(model)
    }
}

pub const WHITE: [f32; 3] = [0.75, 0.75, 0.75];
pub const RED: [f32; 3] = [0.75, 0.06, 0.05];
pub const BLUE: [f32; 3] = [0.06, 0.12, 0.75];

/// The default scene: a 4 m floor, a red wall (x = -2) and a blue wall (z = -2) as in a Cornell
/// box, and a light-grey object with crevices and overhangs: an arch whose slab overhangs the
/// floor, a stepped pyramid, a sphere touching the floor and a block pushed into the corner.
pub fn cornell() -> Result<Model> {
    let v = Vec3::new;
    let mut b = MeshBuilder::default();
    let floor = b.material(Material::plain("floor", WHITE));
    let red = b.material(Material::plain("red_wall", RED));
    let blue = b.material(Material::plain("blue_wall", BLUE));
    let object =
        b.material(Material { specular: [0.35; 3], shininess: 48.0, ..Material::plain("object", [0.72, 0.7, 0.66]) });
    b.floor(floor, 2.0);
    b.quad(red, [v(-2.0, 0.0, -2.0), v(-2.0, 0.0, 2.0), v(-2.0, 2.2, 2.0), v(-2.0, 2.2, -2.0)]);
    b.quad(blue, [v(-2.0, 0.0, -2.0), v(-2.0, 2.2, -2.0), v(2.0, 2.2, -2.0), v(2.0, 0.0, -2.0)]);
    // Arch: two pillars under an overhanging slab.
    b.cuboid(object, v(-0.75, 0.0, -0.55), v(-0.5, 0.9, -0.3), false);
    b.cuboid(object, v(0.35, 0.0, -0.55), v(0.6, 0.9, -0.3), false);
    b.cuboid(object, v(-1.0, 0.9, -0.8), v(0.85, 1.05, -0.05), true);
    // Stepped pyramid: three crevices where the steps meet.
    for (k, half) in [0.45f32, 0.32, 0.19].iter().enumerate() {
        let y = 0.25 * k as f32;
        b.cuboid(object, v(0.95 - half, y, 0.95 - half), v(0.95 + half, y + 0.25, 0.95 + half), false);
    }
    // A sphere resting on the floor and a block in the corner of the two walls.
    b.sphere(object, v(-0.95, 0.38, 0.95), 0.38, 32, 16);
    b.cuboid(object, v(-2.0, 0.0, -2.0), v(-1.45, 0.55, -1.45), false);
    b.build("cornell")
}

/// A square floor of half-size `half` at y = 0 (the open-plane tests).
pub fn plane(half: f32, albedo: [f32; 3]) -> Result<Model> {
    let v = Vec3::new;
    let mut b = MeshBuilder::default();
    let m = b.material(Material::plain("floor", albedo));
    b.quad(m, [v(-half, 0.0, half), v(half, 0.0, half), v(half, 0.0, -half), v(-half, 0.0, -half)]);
    b.build("plane")
}

/// Daylight: deep blue zenith, pale horizon, a warm glow towards the sun, brownish ground.
pub fn day_sky(d: Vec3) -> Vec3 {
    let zenith = Vec3::new(0.16, 0.32, 0.78);
    let horizon = Vec3::new(0.72, 0.8, 0.92);
    let ground = Vec3::new(0.22, 0.19, 0.16);
    let sun = Vec3::new(0.5, 0.6, 0.62).normalize();
    let glow = Vec3::new(1.0, 0.85, 0.6) * 0.25 * d.dot(sun).max(0.0).powi(8);
    if d.y >= 0.0 {
        horizon.lerp(zenith, d.y.powf(0.6)) + glow
    } else {
        horizon.lerp(ground, (-d.y * 4.0).min(1.0).sqrt())
    }
}

/// The SSDO course project's directional-sky demonstration: blue above, red below, neutral sides.
pub fn redblue_face(face: usize) -> Vec3 {
    match face {
        2 => Vec3::new(0.05, 0.15, 1.0),
        3 => Vec3::new(1.0, 0.05, 0.03),
        _ => Vec3::splat(0.35),
    }
}

/// Direction of the sun in [`sun_sky`].
pub fn sun_direction() -> Vec3 {
    Vec3::new(0.55, 0.5, 0.35).normalize()
}

/// An HDR sky with a sun of radiance 4000 and 2° angular radius over a dim blue sky.
pub fn sun_sky(d: Vec3) -> Vec3 {
    let cos = d.dot(sun_direction());
    let disk = if cos > 2.0f32.to_radians().cos() { Vec3::new(4000.0, 3600.0, 3000.0) } else { Vec3::ZERO };
    let halo = Vec3::new(2.0, 1.6, 1.0) * cos.max(0.0).powi(64);
    0.6 * day_sky(d) + disk + halo
}

fn linear_to_srgb8(c: f32) -> u8 {
    let s = if c <= 0.0031308 { 12.92 * c } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
    (s.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
}

/// Writes a skybox as six faces into `dir`: sRGB PNG, or Radiance `.hdr` when `hdr`.
pub fn write_skybox(sky: &Skybox, dir: &Path, hdr: bool) -> Result<()> {
    use crate::Error;
    for (face, (name, _)) in super::skybox::FACE_NAMES.iter().enumerate() {
        let texels = &sky.faces[face];
        let mut bytes = Vec::new();
        let path = dir.join(format!("{name}.{}", if hdr { "hdr" } else { "png" }));
        let fail = |e: image::ImageError| Error::output(&path, format!("encoding failed: {e}"));
        if hdr {
            let pixels: Vec<image::Rgb<f32>> = texels.iter().map(|t| image::Rgb(*t)).collect();
            image::codecs::hdr::HdrEncoder::new(&mut bytes)
                .encode(&pixels, sky.size as usize, sky.size as usize)
                .map_err(fail)?;
        } else {
            let rgb: Vec<u8> = texels.iter().flat_map(|t| t.map(linear_to_srgb8)).collect();
            let image = image::RgbImage::from_raw(sky.size, sky.size, rgb).expect("size matches");
            image.write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png).map_err(fail)?;
        }
        write_atomic(&path, &bytes)?;
    }
    Ok(())
}

/// Writes `model` as an OBJ with a sibling MTL (untextured materials only).
pub fn write_obj(model: &Model, obj_path: &Path) -> Result<()> {
    let mtl_name =
        obj_path.with_extension("mtl").file_name().expect("obj path has a name").to_string_lossy().into_owned();
    let mut obj = format!("# {} — generated by `cargo run --example make_assets`\nmtllib {mtl_name}\n", model.name);
    for v in &model.vertices {
        let (p, n, t) = (v.position, v.normal, v.uv);
        let _ =
            writeln!(obj, "v {} {} {}\nvn {} {} {}\nvt {} {}", p[0], p[1], p[2], n[0], n[1], n[2], t[0], 1.0 - t[1]);
    }
    for part in &model.parts {
        let _ = writeln!(obj, "usemtl {}", model.materials[part.material].name);
        let range = part.first_index as usize..(part.first_index + part.index_count) as usize;
        for tri in model.indices[range].chunks_exact(3) {
            let f = tri.iter().map(|i| format!("{0}/{0}/{0}", i + 1)).collect::<Vec<_>>().join(" ");
            let _ = writeln!(obj, "f {f}");
        }
    }
    let mut mtl = String::from("# generated by `cargo run --example make_assets`\n");
    for m in &model.materials {
        let (d, s) = (m.diffuse, m.specular);
        let _ = writeln!(
            mtl,
            "newmtl {}\nKd {} {} {}\nKs {} {} {}\nNs {}\n",
            m.name, d[0], d[1], d[2], s[0], s[1], s[2], m.shininess
        );
    }
    write_atomic(&obj_path.with_extension("mtl"), mtl.as_bytes())?;
    write_atomic(obj_path, obj.as_bytes())
}
