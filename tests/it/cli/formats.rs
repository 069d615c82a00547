//! The skies and models people have: equirectangular panoramas and glTF 2.0 files, written by
//! the tests themselves.

use crate::common;
use common::{one_node, plain_material, quad_buffer, quad_gltf, write_glb};

use std::path::Path;

use base64::Engine;
use glam::Vec3;
use serde_json::json;
use ssdo::scene::builtin;
use ssdo::scene::load_model_file;
use ssdo::scene::model::Model;
use ssdo::scene::panorama::Panorama;
use ssdo::scene::skybox::direction_to_face;
use ssdo::scene::Skybox;

/// Writes a panorama as Radiance `.hdr`.
fn write_hdr(panorama: &Panorama, path: &Path) {
    let pixels: Vec<image::Rgb<f32>> = panorama.texels.iter().map(|t| image::Rgb(*t)).collect();
    let mut bytes = Vec::new();
    image::codecs::hdr::HdrEncoder::new(&mut bytes)
        .encode(&pixels, panorama.width as usize, panorama.height as usize)
        .unwrap();
    std::fs::write(path, bytes).unwrap();
}

fn redblue_panorama(dir: &Path) -> std::path::PathBuf {
    let path = dir.join("redblue.hdr");
    write_hdr(&Panorama::from_fn(256, 128, |d| builtin::redblue_face(direction_to_face(d).0)), &path);
    path
}

#[test]
fn a_panorama_file_loads_as_a_sky_on_the_documented_faces() {
    let dir = tempfile::tempdir().unwrap();
    // Warm above, cold below, and a marker colour on each horizontal axis.
    let colour = |d: Vec3| {
        let a = d.abs();
        if a.y >= a.x && a.y >= a.z {
            if d.y > 0.0 {
                Vec3::new(1.0, 0.5, 0.0)
            } else {
                Vec3::new(0.0, 0.25, 1.0)
            }
        } else if a.x >= a.z {
            if d.x > 0.0 {
                Vec3::new(2.0, 0.0, 0.0)
            } else {
                Vec3::new(0.0, 2.0, 0.0)
            }
        } else if d.z > 0.0 {
            Vec3::new(0.0, 0.0, 2.0)
        } else {
            Vec3::new(3.0, 3.0, 3.0)
        }
    };
    let path = dir.path().join("marked.hdr");
    write_hdr(&Panorama::from_fn(128, 64, colour), &path);
    let sky = Skybox::load(&path).unwrap();
    assert_eq!((sky.name.as_str(), sky.size), ("marked", 32));
    for d in [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::Z, Vec3::NEG_Z] {
        let got = sky.sample(d);
        assert!((got - colour(d)).abs().max_element() < 1e-3, "{d}: {got} vs {}", colour(d));
    }
    // The panorama's centre column is -Z: the pixel there holds -Z's colour.
    let image = image::open(&path).unwrap().to_rgb32f();
    assert_eq!(Vec3::from(image.get_pixel(64, 32).0), colour(Vec3::NEG_Z));
    // A folder holding just that panorama is a sky too (the viewer's list shows such folders).
    let folder = tempfile::tempdir().unwrap();
    std::fs::copy(&path, folder.path().join("studio.hdr")).unwrap();
    assert_eq!(Skybox::load(folder.path()).unwrap().name, "studio");
}

#[test]
fn an_ldr_panorama_is_srgb_and_bad_panoramas_are_one_clear_line() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("grey.png");
    image::RgbImage::from_pixel(64, 32, image::Rgb([188, 188, 188])).save(&png).unwrap();
    let sky = Skybox::load(&png).unwrap();
    // sRGB 188 is linear 0.5.
    assert!((sky.sample(Vec3::X).x - 0.5029).abs() < 1e-3, "{}", sky.sample(Vec3::X));

    let square = dir.path().join("square.jpg");
    image::RgbImage::from_pixel(32, 32, image::Rgb([10, 10, 10])).save(&square).unwrap();
    let message = Skybox::load(&square).unwrap_err().to_string();
    assert!(message.contains("square.jpg: panorama is 32x32") && message.contains("twice as wide"), "{message}");

    let text = dir.path().join("notes.txt");
    std::fs::write(&text, "not a sky").unwrap();
    let message = Skybox::load(&text).unwrap_err().to_string();
    assert!(message.contains("notes.txt: not a sky"), "{message}");

    let corrupt = dir.path().join("corrupt.hdr");
    std::fs::write(&corrupt, b"#?RADIANCE\nnonsense").unwrap();
    let message = Skybox::load(&corrupt).unwrap_err().to_string();
    assert!(message.contains("corrupt.hdr") && !message.contains('\n'), "{message}");

    // Larger than the budget: refused from the header, before the pixels are read.
    let huge = dir.path().join("huge.hdr");
    std::fs::write(&huge, b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 9000 +X 18000\n").unwrap();
    let message = Skybox::load(&huge).unwrap_err().to_string();
    assert!(message.contains("huge.hdr") && !message.contains('\n'), "{message}");

    // Negative and non-finite texels become 0, with a warning.
    let mut texels = vec![1.0f32; 16 * 8 * 3];
    texels[9..12].copy_from_slice(&[-1.0, f32::NAN, f32::INFINITY]);
    let path = dir.path().join("bad.exr");
    image::Rgb32FImage::from_raw(16, 8, texels).unwrap().save(&path).unwrap();
    let sky = Skybox::load(&path).unwrap();
    assert!(sky.warnings.iter().any(|w| w.contains("replaced by 0")), "{:?}", sky.warnings);
    assert!(sky.faces.iter().flatten().flatten().all(|c| c.is_finite() && *c >= 0.0));

    // The command line says the same, with the input exit code.
    let line = common::refused(&["capture", "--skybox", square.to_str().unwrap(), "--size", "32x24"], 3, "square.jpg");
    assert!(line.contains("twice as wide"), "{line}");
}

#[test]
fn a_redblue_panorama_renders_like_the_redblue_folder() {
    let Some((gpu, dir)) = common::gpu_and_folder() else { return };
    let from_panorama = Skybox::load(&redblue_panorama(dir.path())).unwrap();
    let folder = Skybox::load(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/skyboxes/redblue"))).unwrap();
    let scene = ssdo::scene::Scene::new(builtin::cornell().unwrap(), 0, 1);
    let camera = ssdo::scene::OrbitCamera::framing(&scene.model.bounds);
    let size = (96, 72);
    let settings = ssdo::render::Settings { ambient: 0.0, ..Default::default() };
    let mut images = Vec::new();
    for sky in [&folder, &from_panorama] {
        let mut renderer = common::renderer(gpu, &scene, sky, size, settings);
        images.push(common::shoot(gpu, &mut renderer, &camera));
    }
    let (a, b) = (&images[0], &images[1]);
    let differences: Vec<f32> = a
        .pixels()
        .zip(b.pixels())
        .flat_map(|(p, q)| (0..3).map(move |c| (p.0[c] as f32 - q.0[c] as f32).abs()))
        .collect();
    let mean = differences.iter().sum::<f32>() / differences.len() as f32;
    let mean_level =
        a.pixels().flat_map(|p| p.0[..3].iter().map(|&c| c as f32)).sum::<f32>() / differences.len() as f32;
    eprintln!("redblue panorama vs folder: mean |difference| {mean:.2} of 255 (image mean {mean_level:.1})");
    assert!(mean_level > 20.0, "the image is lit");
    // The seams between faces blend over a texel in the panorama; the rest is the same sky.
    assert!(mean < 2.0, "mean difference {mean}");
}

fn sorted_positions(model: &Model) -> Vec<[i32; 3]> {
    let mut p: Vec<[i32; 3]> = model.vertices.iter().map(|v| v.position.map(|x| (x * 1000.0).round() as i32)).collect();
    p.sort();
    p
}

#[test]
fn gltf_with_external_embedded_or_binary_buffers_loads_the_same_quad() {
    let dir = tempfile::tempdir().unwrap();
    let bin = quad_buffer();
    std::fs::write(dir.path().join("quad data.bin"), &bin).unwrap();
    let external = dir.path().join("external.gltf");
    let buffer = json!({ "uri": "quad%20data.bin", "byteLength": 144 });
    std::fs::write(&external, quad_gltf(buffer, one_node(), plain_material()).to_string()).unwrap();
    let embedded = dir.path().join("embedded.gltf");
    let uri =
        format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(&bin));
    std::fs::write(
        &embedded,
        quad_gltf(json!({ "uri": uri, "byteLength": 144 }), one_node(), plain_material()).to_string(),
    )
    .unwrap();
    let glb = dir.path().join("binary.GLB");
    write_glb(&glb, &quad_gltf(json!({ "byteLength": 144 }), one_node(), plain_material()), &bin);

    let models: Vec<Model> = [&external, &embedded, &glb].iter().map(|p| load_model_file(p).unwrap()).collect();
    for (m, path) in models.iter().zip([&external, &embedded, &glb]) {
        assert_eq!(m.triangle_count(), 2, "{}", path.display());
        assert!(m.warnings.is_empty(), "{}: {:?}", path.display(), m.warnings);
        assert_eq!(sorted_positions(m), sorted_positions(&models[0]));
        assert!(m.vertices.iter().all(|v| v.normal == [0.0, 1.0, 0.0]), "faces up");
        // Metallic 0: the base colour is the diffuse albedo, 0.04 the specular strength, and
        // roughness 0.5 a Blinn-Phong exponent of 2/0.0625 - 2 = 30.
        let paint = &m.materials[0];
        assert_eq!(paint.name, "paint");
        assert_eq!(paint.diffuse, [0.2, 0.4, 0.6]);
        assert!((paint.specular[0] - 0.04).abs() < 1e-6 && (paint.shininess - 30.0).abs() < 1e-3);
    }
    assert_eq!(models[0].name, "external");
}

#[test]
fn gltf_node_transforms_compose_and_a_mirror_keeps_the_outside_out() {
    let dir = tempfile::tempdir().unwrap();
    let bin = quad_buffer();
    std::fs::write(dir.path().join("quad.bin"), &bin).unwrap();
    // A parent moved by (5, 0, 0) holding a child scaled by 2 with the quad; and a second root,
    // mirrored in x, with the quad too.
    let nodes = json!([
        { "translation": [5.0, 0.0, 0.0], "children": [1] },
        { "scale": [2.0, 2.0, 2.0], "mesh": 0 },
        { "matrix": [-1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -3.0, 0.0, 0.0, 1.0], "mesh": 0 }
    ]);
    let path = dir.path().join("tree.gltf");
    std::fs::write(
        &path,
        quad_gltf(json!({ "uri": "quad.bin", "byteLength": 144 }), nodes, plain_material()).to_string(),
    )
    .unwrap();
    let m = load_model_file(&path).unwrap();
    assert_eq!(m.triangle_count(), 4);
    // The triangles' corners (the quad's two triangles share two of their vertices).
    let xs: Vec<f32> = (0..m.triangle_count()).flat_map(|t| m.triangle(t)).map(|p| p.x).collect();
    assert!(xs.iter().filter(|&&x| x >= 5.0).count() == 6 && xs.iter().any(|&x| (x - 7.0).abs() < 1e-6), "{xs:?}");
    assert!(xs.iter().filter(|&&x| x <= -3.0).count() == 6 && xs.iter().any(|&x| (x + 4.0).abs() < 1e-6), "{xs:?}");
    assert!((m.bounds.max.z - 2.0).abs() < 1e-6, "the child's scale reaches z");
    // Every triangle, mirrored or not, winds counter-clockwise seen from above, as its normal says.
    for t in 0..m.triangle_count() {
        let [a, b, c] = m.triangle(t);
        assert!((b - a).cross(c - a).y > 0.0, "triangle {t} winds downwards");
    }
    assert!(m.vertices.iter().all(|v| v.normal == [0.0, 1.0, 0.0]));
}

#[test]
fn gltf_textures_load_and_what_is_missing_is_a_checker_and_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("quad.bin"), quad_buffer()).unwrap();
    // Named in another letter case than the file says, as Windows exports often are.
    image::RgbaImage::from_pixel(4, 2, image::Rgba([255, 0, 0, 255])).save(dir.path().join("Red.PNG")).unwrap();
    let textured = |image: &str, metallic: f32| {
        let material = json!({
            "pbrMetallicRoughness": {
                "baseColorFactor": [0.5, 0.5, 0.5, 1.0],
                "baseColorTexture": { "index": 0 },
                "metallicFactor": metallic,
                "roughnessFactor": 1.0
            },
            "normalTexture": { "index": 0 }
        });
        let mut document = quad_gltf(json!({ "uri": "quad.bin", "byteLength": 144 }), one_node(), material);
        document["images"] = json!([{ "uri": image }]);
        document["textures"] = json!([{ "source": 0 }]);
        document
    };
    let path = dir.path().join("textured.gltf");
    std::fs::write(&path, textured("red.png", 1.0).to_string()).unwrap();
    let m = load_model_file(&path).unwrap();
    let map = m.materials[0].diffuse_map.as_ref().expect("the base colour texture");
    assert_eq!((map.width, map.height, &map.rgba[..4]), (4, 2, &[255u8, 0, 0, 255][..]));
    // Metallic 1: no diffuse, and the base colour's mean as the specular strength.
    assert_eq!(m.materials[0].diffuse, [0.0; 3]);
    assert!((m.materials[0].specular[0] - 0.5).abs() < 1e-6 && m.materials[0].shininess == 1.0);
    // The normal texture is read (here the same picture), in MikkTSpace tangents (no TANGENT).
    assert!(m.materials[0].normal_map.is_some() && m.tangents.len() == m.vertices.len());
    assert!(m.warnings.iter().all(|w| !w.contains("not rendered")), "{:?}", m.warnings);
    let uvs: Vec<[f32; 2]> = m.vertices.iter().map(|v| v.uv).collect();
    assert!(uvs.contains(&[1.0, 1.0]) && uvs.contains(&[0.0, 0.0]), "{uvs:?}");

    let missing = dir.path().join("missing.gltf");
    std::fs::write(&missing, textured("nowhere.png", 0.0).to_string()).unwrap();
    let m = load_model_file(&missing).unwrap();
    let checker = ssdo::scene::model::TextureImage::checker();
    assert_eq!(m.materials[0].diffuse_map.as_ref().unwrap().rgba, checker.rgba);
    assert!(m.warnings.iter().any(|w| w.contains("nowhere.png") && w.contains("checker")), "{:?}", m.warnings);
    // The same missing picture as the normal texture: the vertex normals, no tangents.
    assert!(m.materials[0].normal_map.is_none() && m.tangents.is_empty());
    assert!(m.warnings.iter().any(|w| w.contains("keeps its vertex normals")), "{:?}", m.warnings);
}

#[test]
fn an_image_view_past_the_end_of_every_address_is_a_checker_not_a_panic() {
    // The view's offset and length are the file's numbers: their sum overflows a usize.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("quad.bin"), quad_buffer()).unwrap();
    let material = json!({ "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } });
    let mut document = quad_gltf(json!({ "uri": "quad.bin", "byteLength": 144 }), one_node(), material);
    document["bufferViews"]
        .as_array_mut()
        .unwrap()
        .push(json!({ "buffer": 0, "byteOffset": u64::MAX - 7, "byteLength": 16 }));
    document["images"] = json!([{ "bufferView": 4, "mimeType": "image/png" }]);
    document["textures"] = json!([{ "source": 0 }]);
    let path = dir.path().join("overflow.gltf");
    std::fs::write(&path, document.to_string()).unwrap();
    match load_model_file(&path) {
        Ok(m) => {
            let checker = ssdo::scene::model::TextureImage::checker();
            assert_eq!(m.materials[0].diffuse_map.as_ref().unwrap().rgba, checker.rgba);
            assert!(m.warnings.iter().any(|w| w.contains("outside its buffer")), "{:?}", m.warnings);
        }
        Err(e) => assert!(e.to_string().contains("overflow.gltf"), "{e}"),
    }
}

#[test]
fn broken_gltf_files_are_one_line_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let bin = quad_buffer();
    let write = |name: &str, bytes: &[u8]| {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    };
    let no_buffer = quad_gltf(json!({ "uri": "gone.bin", "byteLength": 144 }), one_node(), plain_material());
    let short = quad_gltf(
        json!({ "uri": format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(&bin[..64])), "byteLength": 144 }),
        one_node(),
        plain_material(),
    );
    let mut glb = Vec::new();
    write_glb(
        &dir.path().join("whole.glb"),
        &quad_gltf(json!({ "byteLength": 144 }), one_node(), plain_material()),
        &bin,
    );
    glb.extend(std::fs::read(dir.path().join("whole.glb")).unwrap());
    let cases = [
        (write("syntax.gltf", b"{\"asset\": "), "syntax.gltf: malformed glTF"),
        (write("gone.gltf", no_buffer.to_string().as_bytes()), "gone.bin"),
        (write("short.gltf", short.to_string().as_bytes()), "buffer 0 holds 64 bytes; the file says 144"),
        (write("truncated.glb", &glb[..glb.len() / 2]), "truncated.glb: malformed glTF"),
        (write("empty.gltf", b"{\"asset\":{\"version\":\"2.0\"}}"), "empty.gltf: no triangles to draw"),
        (write("zeros.glb", &[0u8; 64]), "zeros.glb: malformed glTF"),
    ];
    for (path, needle) in cases {
        let message = load_model_file(&path).unwrap_err().to_string();
        assert!(message.contains(needle) && !message.contains('\n'), "{}: {message}", path.display());
    }
}

#[test]
fn capture_and_report_take_a_glb_model_and_a_panorama_sky() {
    if !common::has_adapter() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("quad.glb");
    write_glb(&glb, &quad_gltf(json!({ "byteLength": 144 }), one_node(), plain_material()), &quad_buffer());
    let sky = redblue_panorama(dir.path());
    let out = dir.path().join("out");
    let (glb_arg, sky_arg, out_arg) = (glb.to_str().unwrap(), sky.to_str().unwrap(), out.to_str().unwrap());
    let result = common::run_ssdo(&[
        "capture", "--model", glb_arg, "--skybox", sky_arg, "--size", "64x48", "--mode", "ssdo", "--out", out_arg,
    ]);
    assert!(result.status.success(), "{}", common::stderr(&result));
    let image = image::open(out.join("ssdo.png")).unwrap().to_rgb8();
    // The quad faces the blue sky above: it is lit, and bluer than red.
    let centre = image.get_pixel(32, 24).0;
    assert!(centre[2] > centre[0] && centre[2] > 40, "{centre:?}");
    let report = dir.path().join("report");
    let result = common::run_ssdo(&[
        "report",
        "--model",
        glb_arg,
        "--skybox",
        sky_arg,
        "--size",
        "32x24",
        "--samples",
        "4",
        "--march",
        "1x4",
        "--spp",
        "4",
        "--frames",
        "1",
        "--accumulate",
        "1",
        "--out",
        report.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", common::stderr(&result));
    assert!(std::fs::read_to_string(report.join("report.csv")).unwrap().lines().count() > 4);
}

#[test]
fn gltf_strips_and_fans_are_triangles_and_unread_extensions_are_named() {
    let dir = tempfile::tempdir().unwrap();
    for (mode, order) in [(5, [0u16, 1, 2, 3]), (6, [0, 1, 3, 2])] {
        let mut bin = quad_buffer();
        bin[128..136].copy_from_slice(bytemuck::cast_slice(&order));
        let mut document = quad_gltf(json!({ "byteLength": 144 }), one_node(), plain_material());
        document["meshes"][0]["primitives"][0]["mode"] = json!(mode);
        document["accessors"][3]["count"] = json!(4);
        let path = dir.path().join(format!("mode{mode}.glb"));
        write_glb(&path, &document, &bin);
        let m = load_model_file(&path).unwrap();
        assert_eq!(m.triangle_count(), 2, "mode {mode}");
        for t in 0..2 {
            let [a, b, c] = m.triangle(t);
            assert!((b - a).cross(c - a).y > 0.0, "mode {mode}: triangle {t} winds downwards");
        }
    }
    let mut document = quad_gltf(json!({ "byteLength": 144 }), one_node(), plain_material());
    document["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
    document["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
    let path = dir.path().join("draco.glb");
    write_glb(&path, &document, &quad_buffer());
    let message = load_model_file(&path).unwrap_err().to_string();
    assert!(message.contains("draco.glb: needs the glTF extension(s) KHR_draco_mesh_compression"), "{message}");
}
