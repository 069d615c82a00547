//! Model, sky, light and camera code on the CPU: what loads, what is repaired with a warning,
//! and what fails with a message naming the file and the problem.

use std::path::Path;

use glam::{Vec3, Vec4Swizzles};
use ssdo::scene::camera::reverse_z_perspective;
use ssdo::scene::model::texture_file_name;
use ssdo::scene::obj_model::load_obj;
use ssdo::scene::skybox::{direction_to_face, face_direction};
use ssdo::scene::{builtin, lights, Bounds, OrbitCamera, Scene, Skybox};
use ssdo::Error;

fn write(dir: &Path, name: &str, bytes: &[u8]) {
    std::fs::write(dir.join(name), bytes).unwrap();
}

fn png(dir: &Path, name: &str, w: u32, h: u32, rgb: [u8; 3]) {
    image::RgbImage::from_pixel(w, h, image::Rgb(rgb)).save(dir.join(name)).unwrap();
}

const QUAD: &str = "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 1 0\n";

#[test]
fn default_model_loads_with_bounds() {
    let model = load_obj(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/models/cornell/cornell.obj"))).unwrap();
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
    assert!(model.triangle_count() > 1000);
    assert!((model.bounds.min - Vec3::new(-2.0, 0.0, -2.0)).abs().max_element() < 1e-4);
    assert!((model.bounds.max - Vec3::new(2.0, 2.2, 2.0)).abs().max_element() < 1e-4);
    let names: Vec<_> = model.materials.iter().map(|m| m.name.as_str()).collect();
    for wanted in ["floor", "red_wall", "blue_wall", "object"] {
        assert!(names.contains(&wanted), "{names:?}");
    }
    let red = model.materials.iter().find(|m| m.name == "red_wall").unwrap();
    assert!(red.diffuse[0] > 5.0 * red.diffuse[1]);
}

#[test]
fn generated_obj_matches_builtin_scene() {
    let dir = tempfile::tempdir().unwrap();
    let built = builtin::cornell().unwrap();
    let path = dir.path().join("scene.obj");
    builtin::write_obj(&built, &path).unwrap();
    let loaded = load_obj(&path).unwrap();
    assert_eq!(loaded.triangle_count(), built.triangle_count());
    assert_eq!(loaded.bounds, built.bounds);
}

#[test]
fn textures_resolve_through_backslashes_options_and_case() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("tex")).unwrap();
    png(&dir.path().join("tex"), "Bricks.png", 4, 4, [200, 10, 10]);
    png(dir.path(), "spec.png", 2, 2, [128, 128, 128]);
    write(
        dir.path(),
        "m.mtl",
        b"newmtl a\nKd 1 1 1\nKs 0.5 0.5 0.5\nNs 64\nmap_Kd -bm 0.5 -s 1 1 1 .\\tex\\bricks.png\nmap_Ks spec.png\n",
    );
    write(dir.path(), "m.obj", format!("mtllib m.mtl\n{QUAD}usemtl a\nf 1/1/1 4/4/1 3/3/1 2/2/1\n").as_bytes());
    let model = load_obj(&dir.path().join("m.obj")).unwrap();
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
    let material = &model.materials[model.parts[0].material];
    let diffuse = material.diffuse_map.as_ref().expect("diffuse map loaded");
    assert_eq!((diffuse.width, diffuse.height), (4, 4));
    assert_eq!(&diffuse.rgba[..3], &[200, 10, 10]);
    assert!(material.specular_map.is_some());
    assert_eq!(material.shininess, 64.0);
    assert!(model.is_textured());
}

#[test]
fn texture_statement_options_are_skipped() {
    assert_eq!(texture_file_name("-o 0.5 0.5 -clamp on wood.jpg").as_deref(), Some("wood.jpg"));
    assert_eq!(texture_file_name("textures\\My Wood.jpg").as_deref(), Some("textures/My Wood.jpg"));
    assert_eq!(texture_file_name("-bm 1"), None);
}

#[test]
fn missing_texture_and_mtl_fall_back_with_warnings() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "m.mtl", b"newmtl a\nKd 0.5\nmap_Kd nowhere.png\n");
    write(dir.path(), "m.obj", format!("mtllib m.mtl\nmtllib absent.mtl\n{QUAD}usemtl a\nf 1 2 3\n").as_bytes());
    let model = load_obj(&dir.path().join("m.obj")).unwrap();
    let material = &model.materials[model.parts[0].material];
    assert_eq!(material.diffuse, [0.5, 0.5, 0.5], "single-value Kd is grey");
    assert!(material.diffuse_map.is_some(), "missing texture becomes a checker");
    let text = model.warnings.join("\n");
    assert!(text.contains("nowhere.png") && text.contains("absent.mtl"), "{text}");
}

#[test]
fn missing_normals_are_computed_and_bad_triangles_dropped() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "m.obj", b"v 0 0 0\nv 1 0 0\nv 0 0 -1\nv nan 0 0\nf 1 2 3\nf 1 2 4\n");
    let model = load_obj(&dir.path().join("m.obj")).unwrap();
    assert_eq!(model.triangle_count(), 1);
    assert!(model.warnings.iter().any(|w| w.contains("dropped 1")), "{:?}", model.warnings);
    for v in &model.vertices {
        assert!((Vec3::from(v.normal) - Vec3::Y).length() < 1e-6, "normal {:?}", v.normal);
    }
    assert_eq!(model.bounds.max, Vec3::new(1.0, 0.0, 0.0), "bounds ignore the NaN vertex");
}

#[test]
fn bad_models_fail_with_the_file_and_problem() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "empty.obj", b"");
    write(dir.path(), "lines.obj", b"v 0 0 0\nv 1 0 0\nl 1 2\n");
    write(dir.path(), "junk.obj", b"v 0 0 zz\nf 1 2 3\n");
    for (name, problem) in [
        ("empty.obj", "empty"),
        ("lines.obj", "no triangles"),
        ("junk.obj", "malformed"),
        ("absent.obj", "cannot read"),
    ] {
        let path = dir.path().join(name);
        match load_obj(&path) {
            Err(e @ Error::Input { .. }) => {
                let message = e.to_string();
                assert!(message.contains(name) && message.contains(problem), "{message}");
                assert_eq!(e.exit_code(), 3);
            }
            other => panic!("{name}: expected an input error, got {other:?}"),
        }
    }
}

#[test]
fn latin1_and_utf16_files_load() {
    let dir = tempfile::tempdir().unwrap();
    let mut latin1 = b"# caf\xe9\n".to_vec();
    latin1.extend_from_slice(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write(dir.path(), "latin1.obj", &latin1);
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let mut utf16 = vec![0xFF, 0xFE];
    utf16.extend(text.encode_utf16().flat_map(u16::to_le_bytes));
    write(dir.path(), "utf16.obj", &utf16);
    for name in ["latin1.obj", "utf16.obj"] {
        assert_eq!(load_obj(&dir.path().join(name)).unwrap().triangle_count(), 1, "{name}");
    }
}

fn sky_folder(faces: &[(&str, u32)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (name, size) in faces {
        png(dir.path(), &format!("{name}.png"), *size, *size, [128, 128, 128]);
    }
    dir
}

#[test]
fn repository_skies_load() {
    for (name, size) in [("day", 128), ("redblue", 32), ("sun", 64)] {
        let sky = Skybox::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("skyboxes").join(name)).unwrap();
        assert_eq!(sky.size, size, "{name}");
        assert!(sky.max_value().is_finite());
    }
    let sun = Skybox::load(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/skyboxes/sun"))).unwrap();
    assert!(sun.max_value() > 1000.0, "the HDR sun keeps its radiance");
}

#[test]
fn redblue_is_blue_above_and_red_below() {
    let sky = Skybox::load(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/skyboxes/redblue"))).unwrap();
    let up = sky.sample(Vec3::Y);
    let down = sky.sample(-Vec3::Y);
    assert!(up.z > 5.0 * up.x, "up {up}");
    assert!(down.x > 5.0 * down.z, "down {down}");
}

#[test]
fn short_face_names_are_accepted() {
    let dir = sky_folder(&[("px", 8), ("nx", 8), ("py", 8), ("ny", 8), ("pz", 8), ("nz", 8)]);
    assert_eq!(Skybox::load(dir.path()).unwrap().size, 8);
}

#[test]
fn incomplete_or_inconsistent_skies_fail_naming_the_face() {
    let five = sky_folder(&[("right", 8), ("left", 8), ("top", 8), ("bottom", 8), ("front", 8)]);
    let message = Skybox::load(five.path()).unwrap_err().to_string();
    assert!(message.contains("'back'") && message.contains("missing"), "{message}");

    let mismatched = sky_folder(&[("right", 8), ("left", 8), ("top", 16), ("bottom", 8), ("front", 8), ("back", 8)]);
    let message = Skybox::load(mismatched.path()).unwrap_err().to_string();
    assert!(message.contains("top.png") && message.contains("same size"), "{message}");

    let dir = sky_folder(&[("right", 8), ("left", 8), ("top", 8), ("bottom", 8), ("front", 8)]);
    png(dir.path(), "back.png", 8, 4, [0, 0, 0]);
    let message = Skybox::load(dir.path()).unwrap_err().to_string();
    assert!(message.contains("back.png") && message.contains("square"), "{message}");

    let message = Skybox::load(Path::new("/nonexistent/sky")).unwrap_err().to_string();
    assert!(message.contains("/nonexistent/sky") && message.contains("not found"), "{message}");
}

#[test]
fn cube_face_mapping_round_trips() {
    for face in 0..6 {
        for (s, t) in [(0.0, 0.0), (0.5, -0.25), (-0.9, 0.8)] {
            let (f, s2, t2) = direction_to_face(face_direction(face, s, t) * 3.0);
            assert_eq!(f, face);
            assert!((s - s2).abs() < 1e-5 && (t - t2).abs() < 1e-5, "face {face}: ({s},{t}) -> ({s2},{t2})");
        }
    }
    assert_eq!(direction_to_face(Vec3::Y).0, 2, "+Y is the top face");
}

#[test]
fn constant_sky_mean_and_mips_are_exact() {
    let sky = Skybox::constant(Vec3::new(0.5, 1.0, 2.0));
    assert!((sky.mean() - Vec3::new(0.5, 1.0, 2.0)).length() < 1e-5);
    let mips = sky.mip_chain();
    assert_eq!(mips.len(), 3, "4 -> 2 -> 1");
    assert_eq!(mips[2][0][0], [0.5, 1.0, 2.0]);
}

#[test]
fn reverse_z_maps_near_to_one_and_infinity_to_zero() {
    for far in [None, Some(100.0)] {
        let p = reverse_z_perspective(1.0, 1.5, 0.1, far);
        let depth = |z: f32| {
            let c = p * glam::Vec4::new(0.0, 0.0, z, 1.0);
            c.z / c.w
        };
        assert!((depth(-0.1) - 1.0).abs() < 1e-6);
        assert!(depth(-10.0) < depth(-1.0), "farther is smaller");
        match far {
            Some(f) => assert!(depth(-f).abs() < 1e-6),
            None => assert!(depth(-1e9) < 1e-7),
        }
    }
}

#[test]
fn camera_frames_any_scale() {
    for scale in [1e-3f32, 1.0, 1e4] {
        let bounds = Bounds { min: Vec3::splat(-scale), max: Vec3::splat(scale) };
        let camera = OrbitCamera::framing(&bounds);
        let view = camera.world_to_view();
        let center = view * bounds.center().extend(1.0);
        assert!(
            (center.xyz().length() - camera.distance).abs() < 1e-3 * camera.distance,
            "the centre is straight ahead"
        );
        assert!(camera.distance > bounds.radius() && camera.near < 0.1 * camera.distance);
    }
}

#[test]
fn lights_are_seeded_saturated_and_scaled() {
    let model = builtin::cornell().unwrap();
    let a = Scene::new(model.clone(), 8, 7);
    let b = Scene::new(model.clone(), 8, 7);
    let c = Scene::new(model.clone(), 8, 8);
    assert_eq!(a.lights, b.lights);
    assert_ne!(a.lights, c.lights);
    for light in &a.lights {
        assert!((light.color.max_element() - 1.0).abs() < 1e-6);
        assert!(light.color.min_element() < 0.25, "saturated: {}", light.color);
        let p = light.position;
        assert!(p.cmpge(model.bounds.min).all() && p.cmple(model.bounds.max).all(), "inside the bounds: {p}");
    }
    let big = Scene::new(model.scaled(1000.0), 8, 7);
    let ratio = big.lights[0].intensity / a.lights[0].intensity;
    assert!((ratio / 1e6 - 1.0).abs() < 1e-3, "intensity scales with size squared");
    assert!(lights::hue_to_rgb(0.0).abs_diff_eq(Vec3::X, 1e-6));
}

#[test]
fn textures_are_shared_by_path_link_and_content_and_kept_within_the_budget() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let png = |name: &str, colour: [u8; 3]| {
        image::RgbImage::from_pixel(64, 64, image::Rgb(colour)).save(d.join(name)).unwrap();
    };
    png("a.png", [200, 10, 10]);
    std::fs::copy(d.join("a.png"), d.join("copy_of_a.png")).unwrap();
    std::os::unix::fs::symlink(d.join("a.png"), d.join("link_to_a.png")).unwrap();
    png("b.png", [10, 200, 10]);
    // 32 materials naming a.png, its link and its copy; one naming b.png.
    let mut mtl = String::new();
    for i in 0..32 {
        let file = ["a.png", "link_to_a.png", "copy_of_a.png"][i % 3];
        mtl += &format!("newmtl m{i}\nKd 1 1 1\nmap_Kd {file}\n");
    }
    mtl += "newmtl other\nKd 1 1 1\nmap_Kd b.png\n";
    std::fs::write(d.join("m.mtl"), mtl).unwrap();
    let mut obj = String::from("mtllib m.mtl\n");
    for i in 0..33 {
        let name = if i < 32 { format!("m{i}") } else { "other".into() };
        obj +=
            &format!("v {i} 0 0\nv {i} 0 1\nv {i}.5 0 0\nusemtl {name}\nf {} {} {}\n", 3 * i + 1, 3 * i + 2, 3 * i + 3);
    }
    std::fs::write(d.join("m.obj"), obj).unwrap();

    // A budget of one 64x64 texture and a half: a.png fits, b.png is halved to fit.
    let model = ssdo::scene::obj_model::load_obj_with_budget(&d.join("m.obj"), 64 * 64 * 4 * 3 / 2).unwrap();
    let maps: Vec<_> = model.materials.iter().filter_map(|m| m.diffuse_map.as_ref()).collect();
    assert_eq!(maps.len(), 33);
    let first = &maps[0].rgba;
    assert!(maps[..32].iter().all(|t| std::sync::Arc::ptr_eq(&t.rgba, first)), "one copy of a.png for 32 materials");
    let b = maps[32];
    assert!(!std::sync::Arc::ptr_eq(&b.rgba, first));
    assert_eq!((b.width, b.height), (32, 32), "b.png halved to fit the budget");
    assert!(model.warnings.iter().any(|w| w.contains("b.png") && w.contains("budget")), "{:?}", model.warnings);
}

#[test]
fn a_sky_larger_than_the_budget_is_downscaled_as_it_loads() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["right", "left", "top", "bottom", "front", "back"] {
        // 2304² of one colour: a few KB as PNG; more than the 2048² a face keeps.
        image::RgbImage::from_pixel(2304, 2304, image::Rgb([128, 160, 200]))
            .save(dir.path().join(format!("{name}.png")))
            .unwrap();
    }
    let sky = ssdo::scene::Skybox::load(dir.path()).unwrap();
    assert_eq!(sky.size, ssdo::scene::skybox::STORED_FACE_SIDE);
    assert!(sky.faces.iter().all(|f| f.len() == (sky.size * sky.size) as usize));
    assert!(sky.warnings.iter().any(|w| w.contains("downscaled")), "{:?}", sky.warnings);
}

#[test]
fn a_model_built_in_code_is_wound_to_agree_with_its_normals() {
    // The G-buffer takes the side of a surface the camera sees from the rasteriser's facing, so
    // every model's triangles must be wound the way their normals say is out, whoever built it.
    use ssdo::scene::model::Vertex;
    use ssdo::scene::{Material, Model};
    let v = |p: [f32; 3], normal: [f32; 3]| Vertex { position: p, normal, uv: [0.0; 2] };
    let up = [0.0, 1.0, 0.0];
    // Counter-clockwise seen from +Y (agreeing), clockwise (against), and a sliver against.
    let agreeing = [v([0.0, 0.0, 0.0], up), v([0.0, 0.0, 1.0], up), v([1.0, 0.0, 0.0], up)];
    let against = [agreeing[0], agreeing[2], agreeing[1]];
    let sliver = [v([0.0, 0.0, 0.0], up), v([2.0, 0.0, 0.0], up), v([1.0, 0.0, 1e-7], up)];
    let triangles = [agreeing, against, sliver].concat();
    let model = Model::from_groups("quad", vec![Material::plain("m", [0.5; 3])], vec![triangles]).unwrap();
    let face = |t: usize| {
        let p = |k: usize| Vec3::from(model.vertices[model.indices[3 * t + k] as usize].position);
        (p(1) - p(0)).cross(p(2) - p(0))
    };
    assert!(face(0).y > 0.0, "kept as it was: {}", face(0));
    assert!(face(1).y > 0.0, "turned to agree with its normals: {}", face(1));
    assert!(face(2).y < 0.0, "a sliver has no trustworthy winding and is left: {}", face(2));
}

#[test]
fn welding_shares_equal_vertices_and_changes_no_corner() {
    use ssdo::scene::model::Vertex;
    use ssdo::scene::{Material, Model};
    // A quad as two triangles and a third triangle on one of its edges: 9 corners, 5 distinct
    // vertices, except that one corner of the third carries another tangent than its twin.
    let v = |x: f32, z: f32| Vertex { position: [x, 0.0, z], normal: [0.0, 1.0, 0.0], uv: [x, z] };
    let corners = vec![v(0.0, 0.0), v(0.0, 1.0), v(1.0, 1.0), v(0.0, 0.0), v(1.0, 1.0), v(1.0, 0.0)];
    let edge = vec![v(1.0, 0.0), v(1.0, 1.0), v(2.0, 0.0)];
    let materials = vec![Material::plain("a", [0.5; 3]), Material::plain("b", [0.5; 3])];
    let mut model = Model::from_groups("welded", materials, vec![corners, edge]).unwrap();
    let mut tangents = vec![[1.0, 0.0, 0.0, 1.0]; 9];
    tangents[7] = [0.0, 0.0, 1.0, -1.0];
    model.tangents = tangents;
    let corner = |m: &Model, k: usize| {
        let i = m.indices[k] as usize;
        (m.vertices[i], m.tangents[i])
    };
    let before: Vec<_> = (0..9).map(|k| corner(&model, k)).collect();
    let parts: Vec<_> = model.parts.iter().map(|p| (p.first_index, p.index_count, p.material)).collect();
    model.weld();
    let after: Vec<_> = (0..9).map(|k| corner(&model, k)).collect();
    assert_eq!(after, before, "every corner keeps its vertex and tangent");
    assert_eq!(model.vertices.len(), 6, "4 of the quad, the edge's twin with its own tangent and one new");
    assert_eq!(model.tangents.len(), model.vertices.len());
    assert_eq!(model.parts.iter().map(|p| (p.first_index, p.index_count, p.material)).collect::<Vec<_>>(), parts);
    // In order of first use.
    assert_eq!(model.indices[..6], [0, 1, 2, 0, 2, 3]);

    // The loaders weld: the default scene's OBJ shares its corners.
    let cornell = load_obj(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/models/cornell/cornell.obj"))).unwrap();
    assert!(cornell.vertices.len() < cornell.indices.len() / 2, "{} vertices", cornell.vertices.len());
}

/// A model is smooth-shaded where a vertex normal turns from its triangle's face: a sphere's
/// triangles are, a box's and a quad's are not, so the default scene (with its sphere) and the
/// open scene (spheres) take the half-size DO over the sky's irradiance, and stairs and fence,
/// all boxes and quads, run as before.
#[test]
fn smooth_shading_is_told_from_flat_faces() {
    use ssdo::scene::named;
    assert!(builtin::cornell().unwrap().has_smooth_normals(), "the default scene's sphere");
    assert!(named::open().unwrap().has_smooth_normals(), "the open scene's spheres");
    assert!(!builtin::plane(1.0, [0.5; 3]).unwrap().has_smooth_normals(), "a quad");
    assert!(!named::stairs().unwrap().has_smooth_normals(), "stairs: boxes");
    assert!(!named::fence().unwrap().has_smooth_normals(), "fence: quads");
    let mut b = builtin::MeshBuilder::default();
    let m = b.material(ssdo::scene::model::Material::plain("box", [0.5; 3]));
    b.cuboid(m, Vec3::ZERO, Vec3::ONE, true);
    assert!(!b.build("box").unwrap().has_smooth_normals(), "a box");
}
