//! Files made to hurt the program, on the loaders (no adapter needed): glTF and OBJ references
//! that reach outside the model's folder or into special files, what the `gltf` crate would
//! panic on, node graphs that branch back, panoramas below 2x1, skies too bright for f32 sums,
//! scales f32 cannot shade. Each case is one clear error or a correct model with a warning; no
//! file outside the folder is read, and no panic reaches the guard.

use std::path::{Path, PathBuf};

use glam::Vec3;
use serde_json::json;
use ssdo::scene::{load_model_file, Model, Skybox};

use crate::common::{one_node, plain_material, quad_buffer, quad_gltf};

/// A model folder `m/` with the quad's buffer as `quad.bin`, beside a folder `secret/` holding
/// the same bytes: any load that reads `secret/` would succeed, so an error proves it did not.
fn folders() -> (tempfile::TempDir, PathBuf) {
    let root = tempfile::tempdir().unwrap();
    let (model, secret) = (root.path().join("m"), root.path().join("secret"));
    std::fs::create_dir_all(model.join("sub")).unwrap();
    std::fs::create_dir_all(&secret).unwrap();
    for path in [model.join("quad.bin"), model.join("sub/quad.bin"), secret.join("outside.bin")] {
        std::fs::write(path, quad_buffer()).unwrap();
    }
    (root, model)
}

fn write_gltf(dir: &Path, name: &str, document: &serde_json::Value) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, document.to_string()).unwrap();
    path
}

fn buffer(uri: &str) -> serde_json::Value {
    json!({ "uri": uri, "byteLength": 144 })
}

/// Loads `path`, checking that no panic was caught on the way.
fn load(path: &Path) -> ssdo::Result<Model> {
    let before = ssdo::guard::caught();
    let result = load_model_file(path);
    assert_eq!(ssdo::guard::caught(), before, "{}: a panic reached the guard", path.display());
    result
}

fn refusal(path: &Path) -> String {
    match load(path) {
        Ok(model) => panic!("{} loaded ({} triangles)", path.display(), model.triangle_count()),
        Err(e) => {
            assert_eq!(e.exit_code(), 3, "{e}");
            e.to_string()
        }
    }
}

#[test]
fn gltf_buffer_uris_stay_in_the_models_folder() {
    let (root, dir) = folders();
    let outside = root.path().join("secret/outside.bin");
    let cases = [
        ("../secret/outside.bin", "leads outside the model's folder"),
        ("sub/../../secret/outside.bin", "leads outside the model's folder"),
        ("%2e%2e/secret/outside.bin", "leads outside the model's folder"),
        ("..\\secret\\outside.bin", "leads outside the model's folder"),
        (outside.to_str().unwrap(), "is an absolute path"),
        (&format!("file://{}", outside.display()), "is an absolute path"),
        ("/etc/passwd", "is an absolute path"),
        ("/proc/self/pagemap", "is an absolute path"),
        ("C:\\Windows\\win.ini", "is an absolute path"),
    ];
    for (i, (uri, needle)) in cases.iter().enumerate() {
        let path = write_gltf(&dir, &format!("c{i}.gltf"), &quad_gltf(buffer(uri), one_node(), plain_material()));
        let message = refusal(&path);
        assert!(message.contains(needle) && message.contains("only files in the model's folder"), "{uri}: {message}");
        assert!(message.contains(&format!("c{i}.gltf")) && message.contains("buffer 0"), "{message}");
    }
    // Inside the folder, by any spelling, loads.
    for uri in ["quad.bin", "./quad.bin", "sub/quad.bin", "sub/../quad.bin", "sub%2Fquad.bin", "sub\\quad.bin"] {
        let path = write_gltf(&dir, "inside.gltf", &quad_gltf(buffer(uri), one_node(), plain_material()));
        assert_eq!(load(&path).unwrap_or_else(|e| panic!("{uri}: {e}")).triangle_count(), 2, "{uri}");
    }
}

#[cfg(unix)]
#[test]
fn links_out_of_the_folder_devices_and_fifos_are_refused_however_they_are_reached() {
    let (root, dir) = folders();
    std::os::unix::fs::symlink(root.path().join("secret/outside.bin"), dir.join("link.bin")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.bin")).unwrap();
    std::os::unix::fs::symlink(root.path().join("secret"), dir.join("elsewhere")).unwrap();
    let fifo = dir.join("fifo.bin");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success());
    let mut cases = vec![("link.bin", "outside the model's folder"), ("zero.bin", "outside the model's folder")];
    cases.push(("elsewhere/outside.bin", "outside the model's folder"));
    if made {
        cases.push(("fifo.bin", "not a regular file"));
    }
    for (uri, needle) in cases {
        let path = write_gltf(&dir, "link.gltf", &quad_gltf(buffer(uri), one_node(), plain_material()));
        let message = refusal(&path);
        assert!(message.contains(needle), "{uri}: {message}");
    }
    // A link that stays inside the folder is followed.
    std::os::unix::fs::symlink("sub/quad.bin", dir.join("inner.bin")).unwrap();
    let path = write_gltf(&dir, "inner.gltf", &quad_gltf(buffer("inner.bin"), one_node(), plain_material()));
    assert_eq!(load(&path).unwrap().triangle_count(), 2);
}

#[test]
fn gltf_images_outside_the_folder_are_checkers_with_the_rule_in_the_warning() {
    let (root, dir) = folders();
    image::RgbaImage::from_pixel(4, 4, image::Rgba([250, 10, 10, 255]))
        .save(root.path().join("secret/red.png"))
        .unwrap();
    let textured = json!({ "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } });
    let mut document = quad_gltf(buffer("quad.bin"), one_node(), textured);
    document["textures"] = json!([{ "source": 0 }]);
    document["images"] = json!([{ "uri": "../secret/red.png" }]);
    let model = load(&write_gltf(&dir, "img.gltf", &document)).unwrap();
    let map = model.materials[0].diffuse_map.as_ref().unwrap();
    assert_ne!(&map.rgba[..3], &[250, 10, 10], "the picture outside was read");
    assert!(model.warnings.iter().any(|w| w.contains("leads outside the model's folder")), "{:?}", model.warnings);
}

#[test]
fn obj_materials_and_maps_stay_in_the_models_folder() {
    let root = tempfile::tempdir().unwrap();
    let (dir, secret) = (root.path().join("m"), root.path().join("secret"));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::create_dir_all(&secret).unwrap();
    std::fs::write(secret.join("x.mtl"), "newmtl red\nKd 1 0 0\n").unwrap();
    let red = image::RgbaImage::from_pixel(4, 4, image::Rgba([250, 10, 10, 255]));
    red.save(secret.join("red.png")).unwrap();
    let quad = "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 1 0\n";
    let face = "f 1/1/1 4/4/1 3/3/1 2/2/1\n";
    // An MTL outside: a default material, and a warning with the rule.
    std::fs::write(dir.join("a.obj"), format!("mtllib ../secret/x.mtl\n{quad}usemtl red\n{face}")).unwrap();
    let model = load(&dir.join("a.obj")).unwrap();
    assert!(model.materials.iter().all(|m| m.name != "red"), "the MTL outside was read");
    assert!(model.warnings.iter().any(|w| w.contains("leads outside the model's folder")), "{:?}", model.warnings);
    // A map outside: the checker. A Windows path whose file lies in the folder: that file, with a note.
    std::fs::write(dir.join("m.mtl"), "newmtl a\nmap_Kd ../secret/red.png\nnewmtl b\nmap_Kd C:\\Users\\x\\Grey.PNG\n")
        .unwrap();
    image::RgbaImage::from_pixel(2, 2, image::Rgba([90, 90, 90, 255])).save(dir.join("grey.png")).unwrap();
    let text = format!("mtllib m.mtl\n{quad}usemtl a\n{face}usemtl b\nf 1/1/1 2/2/1 3/3/1\n");
    std::fs::write(dir.join("b.obj"), text).unwrap();
    let model = load(&dir.join("b.obj")).unwrap();
    let map = |name: &str| model.materials.iter().find(|m| m.name == name).unwrap().diffuse_map.clone().unwrap();
    assert_ne!(&map("a").rgba[..3], &[250, 10, 10], "the map outside was read");
    assert_eq!(&map("b").rgba[..3], &[90, 90, 90]);
    assert!(
        model.warnings.iter().any(|w| w.contains("is an absolute path") && w.contains("grey.png")),
        "{:?}",
        model.warnings
    );
}

#[test]
fn what_the_gltf_crate_would_panic_on_is_one_line_or_a_checker() {
    let (_root, dir) = folders();
    // A primitive naming an accessor that does not exist (the crate's validation indexes it).
    let mut document = quad_gltf(buffer("quad.bin"), one_node(), plain_material());
    document["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(7);
    let message = refusal(&write_gltf(&dir, "accessor.gltf", &document));
    assert!(message.contains("names accessor 7") && message.contains("4 accessor(s)"), "{message}");
    // Images with no source, and in a buffer view without a MIME type (the crate unwraps both).
    let textured = json!({ "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } });
    for (image, needle) in
        [(json!({}), "neither a uri nor a bufferView"), (json!({ "bufferView": 0 }), "has no mimeType")]
    {
        let mut document = quad_gltf(buffer("quad.bin"), one_node(), textured.clone());
        document["textures"] = json!([{ "source": 0 }]);
        document["images"] = json!([image]);
        let model = load(&write_gltf(&dir, "image.gltf", &document)).unwrap();
        assert!(model.warnings.iter().any(|w| w.contains(needle) && w.contains("checker")), "{:?}", model.warnings);
    }
}

#[test]
fn node_graphs_that_branch_back_place_each_node_once() {
    let (_root, dir) = folders();
    let quad = |nodes: serde_json::Value, roots: serde_json::Value| {
        let mut document = quad_gltf(buffer("quad.bin"), nodes, plain_material());
        document["scenes"] = json!([{ "nodes": roots }]);
        document
    };
    // A node that is its own child, twice: one quad, and a warning.
    let model =
        load(&write_gltf(&dir, "self.gltf", &quad(json!([{ "mesh": 0, "children": [0, 0] }]), json!([0])))).unwrap();
    assert_eq!(model.triangle_count(), 2);
    assert!(model.warnings.iter().any(|w| w.contains("already placed")), "{:?}", model.warnings);
    // Seventeen nodes that each name the next twice (2^17 paths to the mesh): one quad.
    let mut nodes: Vec<serde_json::Value> = (1..18).map(|i| json!({ "children": [i, i] })).collect();
    nodes.push(json!({ "mesh": 0, "translation": [0.0, 1.0, 0.0] }));
    let model = load(&write_gltf(&dir, "doubling.gltf", &quad(json!(nodes), json!([0])))).unwrap();
    assert_eq!(model.triangle_count(), 2, "a node graph of 18 nodes drew {} triangles", model.triangle_count());
    // A cycle without a mesh ends too; the file has nothing to draw, and says why.
    let nodes = json!([{ "children": [1] }, { "children": [0, 0] }]);
    let message = refusal(&write_gltf(&dir, "cycle.gltf", &quad(nodes, json!([0]))));
    assert!(message.contains("no triangles to draw") && message.contains("already placed"), "{message}");
    // A chain deeper than the walk goes: the error carries the depth note.
    let mut chain: Vec<serde_json::Value> = (1..80).map(|i| json!({ "children": [i] })).collect();
    chain.push(json!({ "mesh": 0 }));
    let message = refusal(&write_gltf(&dir, "deep.gltf", &quad(json!(chain), json!([0]))));
    assert!(message.contains("no triangles to draw") && message.contains("deeper than 64"), "{message}");
}

/// The quad under one node with `node`'s transform.
fn transformed(dir: &Path, name: &str, node: serde_json::Value) -> ssdo::Result<Model> {
    load(&write_gltf(dir, name, &quad_gltf(buffer("quad.bin"), json!([node]), plain_material())))
}

#[test]
fn extreme_node_scales_keep_their_normals_or_are_refused_by_name() {
    let (_root, dir) = folders();
    // Scales whose inverse over- or underflows f32: fitted to a radius of 1, normals still up.
    for scale in [1e-20f32, 1e-30] {
        let model = transformed(&dir, "s.gltf", json!({ "mesh": 0, "scale": [scale, scale, scale] }))
            .unwrap_or_else(|e| panic!("scale {scale}: {e}"));
        assert!((model.bounds.radius() - 1.0).abs() < 1e-3, "scale {scale}: {:?}", model.bounds);
        for v in &model.vertices {
            assert!((Vec3::from(v.normal) - Vec3::Y).length() < 1e-4, "scale {scale}: normal {:?}", v.normal);
        }
    }
    // A flattening scale keeps the plane's normal; a mirror keeps it outward.
    for scale in [[1.0, 0.0, 1.0], [-1.0, 1.0, 1.0]] {
        let model = transformed(&dir, "f.gltf", json!({ "mesh": 0, "scale": scale })).unwrap();
        assert!(model.vertices.iter().all(|v| (Vec3::from(v.normal) - Vec3::Y).length() < 1e-4), "{scale:?}");
    }
    // Nothing left to shade: one point, or a shape below what f32 holds.
    let zero = transformed(&dir, "z.gltf", json!({ "mesh": 0, "scale": [0.0, 0.0, 0.0] })).err().unwrap().to_string();
    assert!(zero.contains("lie at one point"), "{zero}");
    let matrix = json!({ "mesh": 0, "matrix": vec![0.0f32; 16] });
    let zero = transformed(&dir, "m.gltf", matrix).err().unwrap().to_string();
    assert!(zero.contains("lie at one point"), "{zero}");
    let tiny = transformed(&dir, "t.gltf", json!({ "mesh": 0, "scale": [1e-38, 1e-38, 1e-38] })).err().unwrap();
    assert!(tiny.to_string().contains("cannot hold a shape"), "{tiny}");
    // Positions beyond 1e12 are dropped as they are read; the error says that is why nothing is left.
    let huge = transformed(&dir, "h.gltf", json!({ "mesh": 0, "scale": [1e20, 1e20, 1e20] })).err().unwrap();
    assert!(huge.to_string().contains("no triangles") && huge.to_string().contains("beyond 1e12"), "{huge}");
}

/// Writes a Radiance `.hdr` of `width` x `height` texels, flat (no run-length coding), each
/// texel `texel(x, y)` as RGBE bytes.
fn write_rgbe(path: &Path, width: u32, height: u32, texel: impl Fn(u32, u32) -> [u8; 4]) {
    let mut out = format!("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {height} +X {width}\n").into_bytes();
    for y in 0..height {
        for x in 0..width {
            out.extend(texel(x, y));
        }
    }
    std::fs::write(path, out).unwrap();
}

#[test]
fn panoramas_below_two_by_one_and_skies_that_overflow_are_handled_at_load() {
    let dir = tempfile::tempdir().unwrap();
    for (w, h) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
        let path = dir.path().join(format!("p{w}x{h}.hdr"));
        std::fs::write(&path, format!("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {h} +X {w}\n")).unwrap();
        let before = ssdo::guard::caught();
        let message = Skybox::load(&path).expect_err("refused").to_string();
        assert!(message.contains("at least 2x1") || message.contains("not a readable image"), "{w}x{h}: {message}");
        assert_eq!(ssdo::guard::caught(), before);
    }
    // The smallest panorama loads.
    let small = dir.path().join("small.hdr");
    write_rgbe(&small, 2, 1, |_, _| [128, 128, 128, 129]);
    assert!(Skybox::load(&small).unwrap().max_value() > 0.0);
    // A few texels of about 3e38: clamped with a warning; the faces, mips and irradiance finite.
    let hot = dir.path().join("hot.hdr");
    write_rgbe(
        &hot,
        64,
        32,
        |x, y| if (x, y) == (3, 3) || (x, y) == (40, 20) { [255; 4] } else { [128, 128, 160, 129] },
    );
    let sky = Skybox::load(&hot).unwrap();
    // (Resampled to faces, the clamped texels blend with their neighbours.)
    let peak = sky.max_value();
    assert!(peak <= ssdo::scene::skybox::MAX_SKY_RADIANCE && peak > 1e19, "{peak}");
    assert!(sky.warnings.iter().any(|w| w.contains("clamped")), "{:?}", sky.warnings);
    assert!(sky.faces.iter().flatten().flatten().all(|c| c.is_finite()));
    assert!(sky.irradiance.iter().all(|c| c.is_finite()), "{:?}", sky.irradiance);
    assert!(sky.mip_chain().iter().flatten().flatten().flatten().all(|c| c.is_finite()));
}

#[test]
fn skies_and_models_given_in_the_wrong_place_say_what_they_are() {
    let dir = tempfile::tempdir().unwrap();
    // A folder of two panoramas: which one is the user's to say.
    for name in ["a.hdr", "b.hdr"] {
        write_rgbe(&dir.path().join(name), 4, 2, |_, _| [128, 128, 128, 129]);
    }
    let message = Skybox::load(dir.path()).err().unwrap().to_string();
    assert!(message.contains("2 images and no cube face") && message.contains("a.hdr, b.hdr"), "{message}");
    // Six faces of 0x0: one line naming the first face, before anything reaches the GPU.
    let faces = tempfile::tempdir().unwrap();
    for face in ["right", "left", "top", "bottom", "front", "back"] {
        std::fs::write(faces.path().join(format!("{face}.hdr")), "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n")
            .unwrap();
    }
    let message = Skybox::load(faces.path()).err().unwrap().to_string();
    assert!(message.contains("right.hdr") && (message.contains("0x0") || message.contains("readable")), "{message}");
    // A panorama given as a model.
    let message = load_model_file(&dir.path().join("a.hdr")).err().unwrap().to_string();
    assert!(message.contains("an image, not a model") && message.contains("--skybox"), "{message}");
}

#[test]
fn the_viewer_keeps_its_camera_where_the_command_line_takes_it_back() {
    use ssdo::scene::camera::{DISTANCE_RADII, REACH_RADII};
    let bounds = ssdo::scene::Bounds { min: Vec3::splat(-1.0), max: Vec3::splat(1.0) };
    let r = bounds.radius();
    let mut camera = ssdo::scene::OrbitCamera::framing(&bounds);
    // Flown a long way, zoomed far out: brought back within both ranges.
    camera.translate(Vec3::new(3e9, 0.0, 0.0));
    camera.distance = 1e12;
    camera.keep_in_range(&bounds);
    assert!(camera.distance <= DISTANCE_RADII.1 * r * 1.0001, "{}", camera.distance);
    assert!(camera.target.length() <= REACH_RADII * r && camera.eye().length() <= REACH_RADII * r * 1.0001);
    // Zoomed into nothing: brought back to the nearest distance taken.
    camera.distance = 0.0;
    camera.keep_in_range(&bounds);
    assert!(camera.distance >= DISTANCE_RADII.0 * r * 0.9999, "{}", camera.distance);
    // A camera within range is left alone.
    let framing = ssdo::scene::OrbitCamera::framing(&bounds);
    let mut same = framing;
    same.keep_in_range(&bounds);
    assert_eq!(same, framing);
}
