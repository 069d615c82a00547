//! Normal maps and alpha cutouts, from the files people have (each test writes its own small
//! OBJ, MTL, glTF and PNG files) through the G-buffer, the sampling passes and the truth: a
//! tilted normal map takes the tilted side's sky, a flat normal-mapped surface does not occlude
//! itself, cut-out texels are holes the sky shows through on both sides, and the tangent frame
//! is the same whether the file gives it or MikkTSpace makes it.

use crate::common;

use std::path::{Path, PathBuf};

use common::{looking, renderer, shoot, H, W};
use glam::Vec3;
use ssdo::gpu::Gpu;
use ssdo::headless::readback::{read_depth, read_occlusion, read_rgba16f, read_surfaces};
use ssdo::reference::{self, Reference, ReferenceScene, TraceSettings};
use ssdo::render::{Mode, Settings, View};
use ssdo::scene::{self, OrbitCamera, Scene, Skybox};

/// Writes an RGBA PNG of `w` x `h` texels.
pub fn write_png(path: &Path, w: u32, h: u32, texel: impl Fn(u32, u32) -> [u8; 4]) {
    image::RgbaImage::from_fn(w, h, |x, y| image::Rgba(texel(x, y))).save(path).unwrap();
}

/// The RGB of a tangent-space normal as a normal map stores it.
pub fn encode(n: Vec3) -> [u8; 4] {
    let n = n.normalize();
    let c = |x: f32| ((x * 0.5 + 0.5) * 255.0).round() as u8;
    [c(n.x), c(n.y), c(n.z), 255]
}

/// A 4x4 normal map whose every normal leans `degrees` from straight out towards the map's +u.
fn write_leaning_normal_map(path: &Path, degrees: f32) {
    let lean = degrees.to_radians();
    write_png(path, 4, 4, |_, _| encode(Vec3::new(lean.sin(), 0.0, lean.cos())));
}

/// One quad of an OBJ: corners counter-clockwise seen from the side `normal` points to, each
/// corner's (u, v) (OBJ's v up the image), the material.
pub struct Quad {
    pub corners: [Vec3; 4],
    pub uvs: [[f32; 2]; 4],
    pub normal: Vec3,
    pub material: &'static str,
}

/// The floor quad y = 0 from -h to h, textures repeated `repeat` times across it: u along +x,
/// v (up the image) along -z.
pub fn floor(h: f32, repeat: f32, material: &'static str) -> Quad {
    let v = Vec3::new;
    Quad {
        corners: [v(-h, 0.0, h), v(h, 0.0, h), v(h, 0.0, -h), v(-h, 0.0, -h)],
        uvs: [[0.0, 0.0], [repeat, 0.0], [repeat, repeat], [0.0, repeat]],
        normal: Vec3::Y,
        material,
    }
}

/// Writes `name.obj` with `quads` and `name.mtl` with `mtl` into `dir`; returns the OBJ's path.
pub fn write_obj(dir: &Path, name: &str, quads: &[Quad], mtl: &str) -> PathBuf {
    let mut obj = format!("mtllib {name}.mtl\n");
    for (i, q) in quads.iter().enumerate() {
        for c in q.corners {
            obj += &format!("v {} {} {}\n", c.x, c.y, c.z);
        }
        for uv in q.uvs {
            obj += &format!("vt {} {}\n", uv[0], uv[1]);
        }
        obj += &format!("vn {} {} {}\nusemtl {}\n", q.normal.x, q.normal.y, q.normal.z, q.material);
        let k = 4 * i + 1;
        let n = i + 1;
        obj += &format!("f {a}/{a}/{n} {b}/{b}/{n} {c}/{c}/{n} {d}/{d}/{n}\n", a = k, b = k + 1, c = k + 2, d = k + 3);
    }
    std::fs::write(dir.join(format!("{name}.mtl")), mtl).unwrap();
    let path = dir.join(format!("{name}.obj"));
    std::fs::write(&path, obj).unwrap();
    path
}

fn settings(mode: Mode) -> Settings {
    Settings { mode, ambient: 0.0, ..Settings::default() }
}

/// The linear HDR image of `scene` in `mode` (the defaults: half resolution, blur, 16 frames).
fn hdr(gpu: &Gpu, scene: &Scene, sky: &Skybox, camera: &OrbitCamera, s: Settings) -> Vec<[f32; 4]> {
    let mut r = renderer(gpu, scene, sky, (W, H), s);
    shoot(gpu, &mut r, camera);
    read_rgba16f(gpu, &r.targets().hdr().unwrap().texture).unwrap()
}

/// The truth for `scene` seen by `camera` (two traces of `spp` rays a pixel, their mean), at the
/// default radius, with the ambient of `settings(..)`.
fn trace_truth(gpu: &Gpu, scene: &Scene, sky: &Skybox, camera: &OrbitCamera, spp: u32) -> Reference {
    let mut r = renderer(gpu, scene, sky, (W, H), settings(Mode::Off));
    shoot(gpu, &mut r, camera);
    let depth = read_depth(gpu, &r.targets().depth().texture).unwrap();
    let bvh = ReferenceScene::new(&scene.model);
    let trace = |seed| {
        let s = TraceSettings { samples_per_pixel: spp, seed, radius: r.radius(), sky_scale: 1.0, ambient: 0.0 };
        reference::trace(&bvh, &scene.lights, &scene.rig, sky, camera, (W, H), &depth, &s, &|| {})
    };
    Reference::mean(&trace(1), &trace(2))
}

fn truth_window(truth: &Reference, (x, y): (usize, usize), r: usize) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for yy in y - r..=y + r {
        for xx in x - r..=x + r {
            let i = yy * W as usize + xx;
            assert!(truth.valid[i], "pixel ({xx}, {yy}) is measured");
            sum += truth.radiance(i, 0.0);
        }
    }
    sum / ((2 * r + 1) * (2 * r + 1)) as f32
}

/// A sky red where x > 0 and blue where x < 0.
fn split_sky() -> Skybox {
    Skybox::from_fn("split", 32, |d| if d.x > 0.0 { Vec3::new(1.0, 0.1, 0.1) } else { Vec3::new(0.1, 0.1, 1.0) })
}

/// The red share r / (r + b) of a colour.
fn red_share(c: Vec3) -> f32 {
    c.x / (c.x + c.z)
}

/// A floor whose normal map leans every normal 40° towards +x (the map's +u) under a sky red on
/// that side and blue on the other: every mode shows the floor red, as the truth does, where the
/// floor without the map is purple.
#[test]
fn a_tilted_normal_map_takes_the_sky_of_the_side_it_leans_to_in_every_mode_and_in_the_truth() {
    let Some((gpu, dir)) = common::gpu_and_folder() else { return };
    write_leaning_normal_map(&dir.path().join("tilt.png"), 40.0);
    let mtl = "newmtl floor\nKd 0.8 0.8 0.8\nnorm tilt.png\n";
    let model = scene::obj_model::load_obj(&write_obj(dir.path(), "tilted", &[floor(20.0, 4.0, "floor")], mtl));
    let model = model.unwrap();
    assert!(model.is_normal_mapped() && model.tangents.len() == model.vertices.len());
    let flat = {
        let mut m = model.clone();
        m.drop_surface_maps();
        m
    };
    let sky = split_sky();
    let camera = looking(Vec3::ZERO, 0.0, 50.0, 4.0);
    let centre = (W as usize / 2, H as usize / 2);
    let (mapped, flat) = (Scene::new(model, 0, 1), Scene::new(flat, 0, 1));
    let truth = red_share(truth_window(&trace_truth(gpu, &mapped, &sky, &camera, 64), centre, 6));
    let flat_truth = red_share(truth_window(&trace_truth(gpu, &flat, &sky, &camera, 64), centre, 6));
    // The flat floor sees both halves alike; the mapped one mostly the red half.
    assert!((flat_truth - 0.5).abs() < 0.02, "flat floor's truth: red share {flat_truth}");
    assert!(truth > 0.7, "mapped floor's truth: red share {truth}");
    for mode in Mode::ALL {
        let share = red_share(common::window_mean(&hdr(gpu, &mapped, &sky, &camera, settings(mode)), centre, 6));
        let flat_share = red_share(common::window_mean(&hdr(gpu, &flat, &sky, &camera, settings(mode)), centre, 6));
        assert!((flat_share - 0.5).abs() < 0.03, "{mode}: the flat floor has red share {flat_share}");
        // Off and SSAO light by the sky's irradiance for the normal, over the whole hemisphere
        // around it (no visibility): a little redder than the truth, which sees no sky below the
        // floor's plane. SSDO and Both cut their hemisphere at the plane, as the truth does.
        let tolerance = if mode.declaration().directional_occlusion { 0.05 } else { 0.12 };
        assert!(
            (share - truth).abs() < tolerance,
            "{mode}: red share {share} against the truth's {truth} (± {tolerance})"
        );
    }
}

/// A normal map of strong detail (a checker of normals leaning 45° four ways) on a flat floor
/// under a constant sky: AO stays 1 wherever the floor is (its own plane never occludes it),
/// and SSDO returns albedo × sky, as the truth does.
#[test]
fn a_flat_normal_mapped_surface_does_not_occlude_itself() {
    let Some((gpu, dir)) = common::gpu_and_folder() else { return };
    let lean = 45f32.to_radians();
    let (s, c) = (lean.sin(), lean.cos());
    let leans = [Vec3::new(s, 0.0, c), Vec3::new(-s, 0.0, c), Vec3::new(0.0, s, c), Vec3::new(0.0, -s, c)];
    // Cells of 4 texels, a unit wide on the floor: a few pixels each at the test's size, at mip
    // levels that keep their lean.
    write_png(&dir.path().join("bumps.png"), 16, 16, |x, y| encode(leans[((x / 4 + y / 4) % 4) as usize]));
    let mtl = "newmtl floor\nKd 0.5 0.5 0.5\nmap_Bump bumps.png\n";
    let path = write_obj(dir.path(), "bumpy", &[floor(20.0, 10.0, "floor")], mtl);
    let scene = Scene::new(scene::obj_model::load_obj(&path).unwrap(), 0, 1);
    assert!(scene.model.is_normal_mapped());
    let radiance = Vec3::new(0.3, 0.6, 0.9);
    let sky = Skybox::constant(radiance);
    let camera = looking(Vec3::ZERO, 10.0, 60.0, 3.0);

    // The mapped normals reach the G-buffer: its normals lean ±45° from the floor's.
    let mut r = renderer(gpu, &scene, &sky, (W, H), settings(Mode::Off));
    shoot(gpu, &mut r, &camera);
    let normals = read_surfaces(gpu, &r.targets().normal().texture).unwrap();
    let up = (camera.world_to_view() * Vec3::Y.extend(0.0)).truncate();
    let leaning = normals.iter().filter(|n| (Vec3::new(n[0], n[1], n[2]).dot(up) - c).abs() < 0.05).count();
    assert!(leaning > normals.len() / 2, "{leaning} of {} normals lean 45° from the floor's", normals.len());

    for mode in [Mode::Ssao, Mode::Both] {
        let mut r = renderer(gpu, &scene, &sky, (W, H), settings(mode));
        shoot(gpu, &mut r, &camera);
        let t = r.targets();
        let ao = read_occlusion(gpu, t.occlusion(), true).unwrap().ao.unwrap();
        let lowest = ao.iter().copied().fold(f32::MAX, f32::min);
        assert!(lowest >= 0.97, "{mode}: AO {lowest} somewhere on the open floor");
    }
    let truth = trace_truth(gpu, &scene, &sky, &camera, 32);
    for mode in [Mode::Ssdo, Mode::Both] {
        let image = hdr(gpu, &scene, &sky, &camera, settings(mode));
        let mut worst = 0.0f32;
        for (i, p) in image.iter().enumerate() {
            if !truth.valid[i] {
                continue;
            }
            let (gpu_value, truth_value) = (Vec3::new(p[0], p[1], p[2]), truth.radiance(i, 0.0));
            // The truth is exact here: every ray escapes to the constant sky.
            assert!((truth_value - 0.5 * radiance).abs().max_element() < 1e-4, "truth {truth_value} at {i}");
            worst = worst.max(((gpu_value - truth_value) / truth_value).abs().max_element());
        }
        assert!(worst < 0.02, "{mode}: SSDO {worst:.4} from albedo × sky (the truth) at worst");
    }
}

/// A white floor with a low red fence on it, the fence cut by a checker mask (`map_d`, a grey
/// one-channel picture): half the fence's texels show what is behind it, and the floor just
/// behind the fence, seen over it from above, gets more sky through the holes than behind the
/// same fence uncut, on the GPU and in the truth alike.
#[test]
fn a_checker_masked_fence_lets_half_its_texels_through_on_the_gpu_and_in_the_truth() {
    let Some((gpu, dir)) = common::gpu_and_folder() else { return };
    image::GrayImage::from_fn(8, 2, |x, y| image::Luma([if (x + y) % 2 == 0 { 255 } else { 0 }]))
        .save(dir.path().join("checker.png"))
        .unwrap();
    let v = Vec3::new;
    let fence = |material| Quad {
        corners: [v(-1.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(1.0, 0.5, 0.0), v(-1.0, 0.5, 0.0)],
        uvs: [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        normal: Vec3::Z,
        material,
    };
    let mtl =
        "newmtl floor\nKd 0.8 0.8 0.8\nnewmtl cut\nKd 0.8 0.1 0.1\nmap_d checker.png\nnewmtl solid\nKd 0.8 0.1 0.1\n";
    let cut = write_obj(dir.path(), "cut", &[floor(3.0, 1.0, "floor"), fence("cut")], mtl);
    let solid = write_obj(dir.path(), "solid", &[floor(3.0, 1.0, "floor"), fence("solid")], mtl);
    let cut = Scene::new(scene::obj_model::load_obj(&cut).unwrap(), 0, 1);
    let solid = Scene::new(scene::obj_model::load_obj(&solid).unwrap(), 0, 1);
    assert!(cut.model.materials.iter().any(|m| m.cutout.is_some()));
    let sky = Skybox::constant(Vec3::ONE);
    let camera = looking(v(0.0, 0.0, -0.2), 0.0, 60.0, 3.0);

    // The albedo view: about half the fence's rectangle is red, the rest the floor behind it.
    let s = Settings { view: View::Albedo, ..settings(Mode::Off) };
    let mut r = renderer(gpu, &cut, &sky, (W, H), s);
    shoot(gpu, &mut r, &camera);
    let albedo = read_rgba16f(gpu, &r.targets().hdr().unwrap().texture).unwrap();
    let (x0, y0) = common::project(&camera, v(-0.9, 0.45, 0.0));
    let (x1, y1) = common::project(&camera, v(0.9, 0.05, 0.0));
    let (mut red, mut all) = (0, 0);
    for y in y0..=y1 {
        for x in x0..=x1 {
            let p = albedo[y * W as usize + x];
            all += 1;
            red += usize::from(p[0] > 2.0 * p[1]);
        }
    }
    let share = red as f32 / all as f32;
    assert!((0.35..0.65).contains(&share), "{share} of the fence's pixels are the fence ({red} of {all})");

    // The floor just behind the fence, in blue (the red fence bounces red light, less of it where
    // it is cut). The march takes every depth sample to be a slab `thickness` deep; by default
    // that is the radius (0.43 here), which closes holes narrower than it and darkens the floor
    // within it behind a thin fence (relative RMSE 0.092 against the truth, Off's 0.060). A
    // fence is as thin as its quad: measured with a thickness of 0.05 (relative RMSE 0.025),
    // the GPU sees what the truth sees through the holes. See docs/accuracy.md.
    let behind = common::project(&camera, v(0.0, 0.0, -0.4));
    let given = ssdo::render::GivenLengths { thickness: Some(0.05), ..Default::default() };
    let s = Settings { given, ..settings(Mode::Ssdo) };
    let through = |scene: &Scene| common::window_mean(&hdr(gpu, scene, &sky, &camera, s), behind, 1).z;
    let (gpu_cut, gpu_solid) = (through(&cut), through(&solid));
    let truth_cut = trace_truth(gpu, &cut, &sky, &camera, 64);
    let truth_solid = trace_truth(gpu, &solid, &sky, &camera, 64);
    let (true_cut, true_solid) = (truth_window(&truth_cut, behind, 1).z, truth_window(&truth_solid, behind, 1).z);
    assert!(true_cut > true_solid + 0.04, "truth: {true_cut} behind the cut fence, {true_solid} behind the solid one");
    assert!(gpu_cut > gpu_solid + 0.04, "SSDO: {gpu_cut} behind the cut fence, {gpu_solid} behind the solid one");
    assert!((gpu_cut - true_cut).abs() < 0.03, "behind the cut fence: SSDO {gpu_cut}, truth {true_cut}");
    // GPU and truth agree on the cut scene as well as on the solid one (relative RMSE over the
    // measured pixels: 0.025 and 0.029 when this was written), and much better than Off (0.060).
    let relative_rmse = |truth: &Reference, scene: &Scene, s: Settings| {
        let image = hdr(gpu, scene, &sky, &camera, s);
        let (mut sq, mut sum, mut n) = (0.0f64, 0.0f64, 0usize);
        for (i, p) in image.iter().enumerate().filter(|(i, _)| truth.valid[*i]) {
            let t = truth.radiance(i, 0.0);
            sq += ((Vec3::new(p[0], p[1], p[2]) - t).length_squared() / 3.0) as f64;
            sum += (t.element_sum() / 3.0) as f64;
            n += 1;
        }
        (sq / n as f64).sqrt() / (sum / n as f64)
    };
    let (e_cut, e_solid) = (relative_rmse(&truth_cut, &cut, s), relative_rmse(&truth_solid, &solid, s));
    let e_off = relative_rmse(&truth_cut, &cut, settings(Mode::Off));
    assert!(e_cut < 0.1 && e_cut < 1.5 * e_solid, "relative RMSE {e_cut:.4} cut, {e_solid:.4} solid");
    assert!(e_cut < 0.7 * e_off, "relative RMSE {e_cut:.4} cut, {e_off:.4} Off on the cut scene");
}

/// A glTF leaf (a unit quad, `doubleSided`, a normal map and a `MASK` cutout) seen from behind
/// with a light on the camera's side: its visible side is lit; and it renders the same whether
/// the file gives `TANGENT` or the loader makes MikkTSpace tangents.
#[test]
fn a_gltf_leaf_seen_from_behind_is_lit_and_given_tangents_match_generated_ones() {
    let Some((gpu, dir)) = common::gpu_and_folder() else { return };
    write_leaning_normal_map(&dir.path().join("leaf_normal.png"), 30.0);
    // Opaque but for a hole in the middle.
    write_png(&dir.path().join("leaf_colour.png"), 8, 8, |x, y| {
        [60, 200, 60, if (3..5).contains(&x) && (3..5).contains(&y) { 0 } else { 255 }]
    });
    let write = |name: &str, tangents: bool| {
        let path = dir.path().join(name);
        let (document, bytes) = leaf_gltf(tangents);
        std::fs::write(dir.path().join("leaf.bin"), bytes).unwrap();
        std::fs::write(&path, serde_json::to_vec(&document).unwrap()).unwrap();
        scene::load_model_file(&path).unwrap()
    };
    let given = write("given.gltf", true);
    let generated = write("generated.gltf", false);
    assert!(given.is_normal_mapped() && generated.is_normal_mapped());
    for (a, b) in given.tangents.iter().zip(&generated.tangents) {
        assert!((0..4).all(|k| (a[k] - b[k]).abs() < 1e-3), "given {a:?}, generated {b:?}");
    }
    let sky = Skybox::constant(Vec3::splat(0.2));
    // Below the leaf (it faces +y), looking up at its back; the light is below too.
    let camera = looking(Vec3::new(0.5, 0.0, 0.5), 20.0, -60.0, 2.0);
    // One light 1 unit below (side -1) or above (+1) the leaf's centre.
    let lit = |model: scene::Model, side: f32| {
        let mut scene = Scene::new(model, 0, 1);
        scene.lights =
            vec![scene::PointLight { position: Vec3::new(0.5, side, 0.5), color: Vec3::ONE, intensity: 2.0 }];
        scene
    };
    let s = settings(Mode::Ssdo);
    let a = hdr(gpu, &lit(given.clone(), -1.0), &sky, &camera, s);
    let b = hdr(gpu, &lit(generated, -1.0), &sky, &camera, s);
    let difference = a.iter().zip(&b).flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs())).fold(0.0, f32::max);
    assert!(difference < 1e-3, "given and generated tangents differ by {difference}");
    // The leaf's back, seen from below, is lit by a light below it, and not by the same light
    // above it (where its front, out of sight, faces it).
    let edge = common::project(&camera, Vec3::new(0.2, 0.0, 0.2));
    let below = common::window_mean(&a, edge, 1);
    let above = common::window_mean(&hdr(gpu, &lit(given, 1.0), &sky, &camera, s), edge, 1);
    assert!(below.y > 1.5 * above.y, "seen from below: {below} lit from below, {above} lit from above");
    // The hole in the middle shows the sky behind (the sky's colour, not the leaf's green).
    let hole = a[{
        let (x, y) = common::project(&camera, Vec3::new(0.5, 0.0, 0.5));
        y * W as usize + x
    }];
    assert!((hole[0] - hole[1]).abs() < 0.01, "the hole shows the grey sky: {hole:?}");
}

/// A glTF leaf: a unit quad on y = 0 (u along +x, v along +z), `doubleSided`, with a normal
/// texture and a base colour texture cut as a `MASK`, with `TANGENT` (+x, w = 1) or without;
/// and its buffer, `leaf.bin`.
fn leaf_gltf(tangents: bool) -> (serde_json::Value, Vec<u8>) {
    let mut bytes = crate::common::quad_bytes(bytemuck::cast_slice(&[[1.0f32, 0.0, 0.0, 1.0]; 4]));
    bytes.resize(bytes.len().next_multiple_of(4), 0);
    let view =
        |offset: usize, length: usize| serde_json::json!({ "buffer": 0, "byteOffset": offset, "byteLength": length });
    let mut attributes = serde_json::json!({ "POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2 });
    if tangents {
        attributes["TANGENT"] = serde_json::json!(4);
    }
    let document = serde_json::json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0 }],
        "meshes": [{ "primitives": [{ "attributes": attributes, "indices": 3, "material": 0 }] }],
        "materials": [{
            "name": "leaf",
            "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 }, "metallicFactor": 0.0, "roughnessFactor": 0.8 },
            "normalTexture": { "index": 1, "scale": 1.0 },
            "alphaMode": "MASK",
            "alphaCutoff": 0.5,
            "doubleSided": true
        }],
        "textures": [{ "source": 0 }, { "source": 1 }],
        "images": [{ "uri": "leaf_colour.png" }, { "uri": "leaf_normal.png" }],
        "buffers": [{ "uri": "leaf.bin", "byteLength": bytes.len() }],
        "bufferViews": [view(0, 48), view(48, 48), view(96, 32), view(128, 64), view(192, 12)],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 0.0, 1.0] },
            { "bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3" },
            { "bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2" },
            { "bufferView": 4, "componentType": 5123, "count": 6, "type": "SCALAR" },
            { "bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC4" }
        ]
    });
    (document, bytes)
}

/// A red wall whose normal map leans its normals 80° up, away from the floor in front of it,
/// under a white sky: the wall's surface faces the floor, so the floor still gets its bounce.
/// The bounce's facing test reads the sender's own plane (from the depth), not the map, which
/// would have it face the sky and send nothing down.
#[test]
fn a_wall_whose_normal_map_leans_away_from_the_floor_still_bounces_onto_it() {
    let Some((gpu, dir)) = common::gpu_and_folder() else { return };
    let lean = 80f32.to_radians();
    write_png(&dir.path().join("up.png"), 4, 4, |_, _| encode(Vec3::new(0.0, lean.sin(), lean.cos())));
    let v = Vec3::new;
    // The wall x = 0.6 facing -x, u along +z and v up it.
    let wall = Quad {
        corners: [v(0.6, 0.0, -1.5), v(0.6, 0.0, 1.5), v(0.6, 1.5, 1.5), v(0.6, 1.5, -1.5)],
        uvs: [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        normal: -Vec3::X,
        material: "wall",
    };
    let mtl = "newmtl floor\nKd 0.8 0.8 0.8\nnewmtl wall\nKd 0.8 0.1 0.1\nnorm up.png\n";
    let path = write_obj(dir.path(), "wall", &[floor(4.0, 1.0, "floor"), wall], mtl);
    let mapped = scene::obj_model::load_obj(&path).unwrap();
    let plain = {
        let mut m = mapped.clone();
        m.drop_surface_maps();
        m
    };
    // The map does lean the wall's shading normal up (the truth reads it as the G-buffer does).
    let lit = ReferenceScene::new(&mapped).trace(v(-1.0, 0.75, 0.01), Vec3::X, 10.0).expect("the wall");
    assert!(lit.normal.y > 0.9, "the mapped normal leans up: {}", lit.normal);
    let sky = Skybox::constant(Vec3::ONE);
    let camera = looking(v(0.0, 0.3, 0.0), -90.0, 35.0, 3.0);
    let receiver = common::project(&camera, v(0.3, 0.0, 0.0));
    let bounce = |model: &scene::Model| {
        let s = Settings { view: View::DoIndirect, ..settings(Mode::Ssdo) };
        let mut r = renderer(gpu, &Scene::new(model.clone(), 0, 1), &sky, (W, H), s);
        shoot(gpu, &mut r, &camera);
        let d = read_rgba16f(gpu, &r.targets().occlusion().directional.unwrap().texture).unwrap();
        common::window_mean(&d, receiver, 2)
    };
    let (with_map, without) = (bounce(&mapped), bounce(&plain));
    eprintln!("the floor's bounce from the wall: with the map {with_map}, without {without}");
    assert!(without.x > 0.02 && without.x > 3.0 * without.y, "the plain wall bounces red: {without}");
    assert!(with_map.x > 0.5 * without.x, "the mapped wall still bounces: {with_map} against {without}");
}

/// A floor whose map leans its normals 40-75° under a sky bright only in a band just above the
/// horizon on the side they lean to: the light comes from directions just above the floor's
/// plane, where the plane cuts the normal's hemisphere. SSDO weighs the sectors left above the
/// plane by their own measure and reads their sky there, and comes within 20% of the truth; taking
/// a cut group's measure by its share of sectors and its sky from its middle (below the plane)
/// gave 0.60-0.72 of it from some views.
#[test]
fn a_leaning_normal_map_takes_the_horizon_light_above_its_plane_as_the_truth_does() {
    let Some((gpu, dir)) = common::gpu_and_folder() else { return };
    let sky =
        Skybox::from_fn(
            "band",
            32,
            |d| if d.y > 0.0 && d.y < 0.35 && d.x > 0.0 { Vec3::ONE } else { Vec3::splat(0.05) },
        );
    let centre = (W as usize / 2, H as usize / 2);
    for lean in [40.0, 60.0, 75.0] {
        write_leaning_normal_map(&dir.path().join("tilt.png"), lean);
        let mtl = "newmtl floor\nKd 0.8 0.8 0.8\nnorm tilt.png\n";
        let model = scene::obj_model::load_obj(&write_obj(dir.path(), "tilted", &[floor(20.0, 4.0, "floor")], mtl));
        let scene = Scene::new(model.unwrap(), 0, 1);
        for yaw in [0.0, 90.0] {
            let camera = looking(Vec3::ZERO, yaw, 50.0, 4.0);
            let truth = truth_window(&trace_truth(gpu, &scene, &sky, &camera, 64), centre, 6).x;
            let got = common::window_mean(&hdr(gpu, &scene, &sky, &camera, settings(Mode::Ssdo)), centre, 6).x;
            let ratio = got / truth;
            assert!((0.8..1.2).contains(&ratio), "lean {lean}°, yaw {yaw}°: SSDO {got} against the truth's {truth}");
        }
    }
}

/// A floor whose normal map alternates stripes leaning 45° towards +x and towards -x, each
/// stripe about 1.5 pixels wide on the screen, under a sky red on the +x side and blue on the
/// other: a pixel is red or blue by its own stripe. Off lights each pixel by the sky's
/// irradiance at its own normal; SSDO samples at half resolution, every other pixel, and holds
/// each sample's DO over the sky's irradiance at the sample's normal for the upsample to multiply
/// by that at each pixel's own: its red shares follow Off's (0.02 from them, which spread 0.19).
/// Taking the samples' DO as it is gave the odd pixels their neighbours' stripe (0.14).
#[test]
fn stripes_of_a_normal_map_finer_than_the_samples_keep_their_colours_at_half_resolution() {
    let Some((gpu, dir)) = common::gpu_and_folder() else { return };
    let lean = 45f32.to_radians();
    write_png(&dir.path().join("stripes.png"), 2, 1, |x, _| {
        let side = if x == 0 { 1.0 } else { -1.0 };
        encode(Vec3::new(side * lean.sin(), 0.0, lean.cos()))
    });
    let mtl = "newmtl floor\nKd 0.8 0.8 0.8\nnorm stripes.png\n";
    let model = scene::obj_model::load_obj(&write_obj(dir.path(), "stripes", &[floor(20.0, 480.0, "floor")], mtl));
    let scene = Scene::new(model.unwrap(), 0, 1);
    let sky = split_sky();
    let camera = looking(Vec3::ZERO, 0.0, 50.0, 4.0);
    let off = hdr(gpu, &scene, &sky, &camera, settings(Mode::Off));
    let ssdo = hdr(gpu, &scene, &sky, &camera, settings(Mode::Ssdo));
    // Over the middle of the floor: how far each pixel's red share lies from Off's, against how
    // far Off's shares spread.
    let (mut spread, mut error, mut mean, mut n) = (0.0, 0.0, 0.0, 0.0);
    let share = |p: [f32; 4]| red_share(Vec3::new(p[0], p[1], p[2]));
    let window = |f: &mut dyn FnMut(usize)| {
        for y in H as usize / 2 - 20..H as usize / 2 + 20 {
            for x in W as usize / 2 - 40..W as usize / 2 + 40 {
                f(y * W as usize + x);
            }
        }
    };
    window(&mut |i| {
        mean += share(off[i]);
        n += 1.0;
    });
    mean /= n;
    window(&mut |i| {
        spread += (share(off[i]) - mean).powi(2);
        error += (share(ssdo[i]) - share(off[i])).powi(2);
    });
    let (spread, error) = ((spread / n).sqrt(), (error / n).sqrt());
    println!("Off's red shares spread {spread:.4} about {mean:.4}; SSDO's differ from them by {error:.4}");
    assert!(spread > 0.1, "the stripes show in Off: red shares spread {spread}");
    assert!(error < 0.25 * spread, "SSDO's red shares are {error} from Off's, which spread {spread}");
}
