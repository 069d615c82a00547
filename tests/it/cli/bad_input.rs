//! Every bad input a user can hand the command line: Debian's assimp-testmodels OBJ and glTF files (valid
//! and invalid) and crafted cases. Each either loads (with warnings and fallbacks) and writes its
//! image, or fails with exit code 3 and one line naming the file and the problem — never a panic
//! (exit 101), never a half-written output file.

use crate::common;

use std::path::{Path, PathBuf};

use common::{has_adapter as have_adapter, run_ssdo as ssdo};

/// What one run did.
enum Outcome {
    Loaded,
    Refused(String),
}

/// Captures `extra` args into a fresh folder and checks the invariants every run must keep.
fn run(label: &str, extra: &[&str]) -> Outcome {
    let out = tempfile::tempdir().unwrap();
    let mut args =
        vec!["capture", "--mode", "off", "--size", "32x24", "--lights", "2", "--out", out.path().to_str().unwrap()];
    args.extend_from_slice(extra);
    let result = ssdo(&args);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(!stderr.contains("panicked"), "{label}: panicked:\n{stderr}");
    let files = common::file_names(out.path());
    match result.status.code() {
        Some(0) => {
            assert_eq!(files, vec!["off.png".to_string()], "{label}: output files");
            Outcome::Loaded
        }
        Some(3) => {
            let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("ssdo: error:")).collect();
            assert_eq!(errors.len(), 1, "{label}: one error line:\n{stderr}");
            assert!(files.is_empty(), "{label}: nothing written on error: {files:?}");
            Outcome::Refused(errors[0].to_owned())
        }
        other => panic!("{label}: exit code {other:?}\n{stderr}"),
    }
}

/// A folder of Debian's assimp-testmodels, or `None` (test skipped) when the package is not
/// installed; under `CI=true` its absence fails the test.
fn assimp_models(folder: &str) -> Option<PathBuf> {
    let root = Path::new("/usr/share/assimp/models").join(folder);
    if !root.exists() {
        assert!(
            std::env::var("CI").map_or(true, |v| v != "true"),
            "CI needs assimp-testmodels (scripts/test.sh installs it)"
        );
        eprintln!("skipping: assimp-testmodels not installed");
        return None;
    }
    Some(root)
}

#[test]
fn every_assimp_test_obj_loads_or_fails_cleanly() {
    let Some(root) = assimp_models("") else { return };
    if !have_adapter() {
        return;
    }
    let mut files: Vec<PathBuf> = ["OBJ", "invalid"]
        .iter()
        .flat_map(|d| std::fs::read_dir(root.join(d)).into_iter().flatten().flatten().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj")))
        .collect();
    files.sort();
    assert!(files.len() >= 20, "expected the assimp OBJ files, found {}", files.len());
    let (mut loaded, mut refused) = (0, 0);
    for file in &files {
        match run(&file.display().to_string(), &["--model", file.to_str().unwrap()]) {
            Outcome::Loaded => loaded += 1,
            Outcome::Refused(line) => {
                let name = file.file_name().unwrap().to_string_lossy();
                assert!(line.contains(name.as_ref()), "the error names the file: {line}");
                refused += 1;
            }
        }
    }
    println!("assimp OBJ files: {loaded} loaded, {refused} refused with one line");
    assert!(loaded > refused, "most of assimp's valid OBJ files load");
}

fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = 0xFFFF_FFFFu32;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

/// A PNG whose header claims `w` x `h` pixels and that has no image data.
fn png_header_only(w: u32, h: u32) -> Vec<u8> {
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend_from_slice(&w.to_be_bytes());
    ihdr.extend_from_slice(&h.to_be_bytes());
    ihdr.extend_from_slice(&[8, 2, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    png.extend_from_slice(&13u32.to_be_bytes());
    png.extend_from_slice(&ihdr);
    png.extend_from_slice(&crc32(&ihdr).to_be_bytes());
    png
}

fn write_png(path: &Path, w: u32, h: u32) {
    image::RgbImage::from_pixel(w, h, image::Rgb([120, 130, 140]))
        .save_with_format(path, image::ImageFormat::Png)
        .unwrap();
}

const TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 0 -1\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 1 0\n";

#[test]
fn crafted_models_load_with_fallbacks_or_fail_cleanly() {
    if !have_adapter() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let w = |name: &str, text: &[u8]| std::fs::write(d.join(name), text).unwrap();
    // Textures: a PNG named .jpg, a truncated JPEG, a PNG claiming 30000x30000.
    let mut jpeg = Vec::new();
    image::RgbImage::from_pixel(16, 16, image::Rgb([200, 50, 50]))
        .write_to(&mut std::io::Cursor::new(&mut jpeg), image::ImageFormat::Jpeg)
        .unwrap();
    w("truncated.jpg", &jpeg[..jpeg.len() / 3]);
    write_png(&d.join("really_png.jpg"), 4, 4);
    w("huge.png", &png_header_only(30000, 30000));
    w("mats.mtl", b"newmtl a\nKd 0.5\nKs 0.2\nmap_Kd -bm 1 -s 1 1 1 textures\\really_png.jpg\nnewmtl b\nmap_Kd truncated.jpg\nnewmtl c\nmap_Kd huge.png\nnewmtl d\nmap_Kd missing.png\n");
    std::fs::create_dir(d.join("textures")).unwrap();
    write_png(&d.join("textures").join("really_png.jpg"), 4, 4);
    let face = |m: &str| format!("mtllib mats.mtl\n{TRI}usemtl {m}\nf 1/1/1 2/2/1 3/3/1\n");
    let cases: Vec<(&str, Vec<u8>, bool)> = vec![
        ("single_value_kd_and_options.obj", face("a").into_bytes(), true),
        ("truncated_jpeg.obj", face("b").into_bytes(), true),
        ("huge_png.obj", face("c").into_bytes(), true),
        ("missing_texture.obj", face("d").into_bytes(), true),
        ("unknown_usemtl.obj", face("nonexistent").into_bytes(), true),
        ("missing_mtl.obj", format!("mtllib nowhere.mtl\n{TRI}f 1 2 3\n").into_bytes(), true),
        // A material file that never ends: refused unread, the default material used.
        ("mtl_dev_zero.obj", format!("mtllib /dev/zero\n{TRI}f 1 2 3\n").into_bytes(), true),
        ("texcoord_zero.obj", format!("{TRI}f 1/0 2/0 3/0\n").into_bytes(), false),
        ("texcoord_negative.obj", format!("{TRI}f 1/-9 2/-9 3/-9\n").into_bytes(), false),
        ("mixed_face_formats.obj", format!("{TRI}f 1/1 2/2 3/3\nf 1//1 2//1 3//1\n").into_bytes(), false),
        ("index_out_of_range.obj", format!("{TRI}f 1 2 99\nf 1 2 3\n").into_bytes(), true),
        // Positions far beyond what f32 can place precisely: dropped, nothing left to draw.
        ("huge_coordinates.obj", b"v 1e30 0 0\nv 0 1e30 0\nv 0 0 1e30\nf 1 2 3\n".to_vec(), false),
        // Wound against its normals (the winding is repaired with a warning).
        ("winding_against_normals.obj", format!("{TRI}f 1//1 3//1 2//1\nf 1//1 2//1 3//1\n").into_bytes(), true),
        ("latin1.obj", [b"# caf\xe9 \xfc\n".as_slice(), TRI.as_bytes(), b"f 1 2 3\n"].concat(), true),
        (
            "utf16.obj",
            [vec![0xFF, 0xFE], format!("{TRI}f 1 2 3\n").encode_utf16().flat_map(u16::to_le_bytes).collect()].concat(),
            true,
        ),
        ("empty.obj", Vec::new(), false),
        ("lines_only.obj", b"v 0 0 0\nv 1 0 0\nl 1 2\n".to_vec(), false),
        ("points_only.obj", b"v 0 0 0\np 1\n".to_vec(), false),
        ("garbage.obj", b"\x00\x01\x02 this is not an obj \xff\xfe\nf a b c\n".to_vec(), false),
    ];
    for (name, bytes, must_load) in &cases {
        w(name, bytes);
        let outcome = run(name, &["--model", d.join(name).to_str().unwrap()]);
        match outcome {
            Outcome::Loaded => {}
            Outcome::Refused(line) => {
                assert!(!must_load, "{name} should load with a fallback, got: {line}");
                assert!(line.contains(name), "the error names the file: {line}");
            }
        }
    }
}

#[test]
fn crafted_skies_fail_naming_the_folder_or_face() {
    if !have_adapter() {
        return;
    }
    let root = tempfile::tempdir().unwrap();
    let faces = ["right", "left", "top", "bottom", "front", "back"];
    let sky = |name: &str, make: &dyn Fn(&Path, &str)| {
        let dir = root.path().join(name);
        std::fs::create_dir(&dir).unwrap();
        for f in faces {
            make(&dir, f);
        }
        dir
    };
    let five = sky("five", &|d, f| {
        if f != "back" {
            write_png(&d.join(format!("{f}.png")), 8, 8)
        }
    });
    let non_square =
        sky("non_square", &|d, f| write_png(&d.join(format!("{f}.png")), 8, if f == "top" { 4 } else { 8 }));
    let mismatched = sky("mismatched", &|d, f| {
        write_png(&d.join(format!("{f}.png")), if f == "left" { 16 } else { 8 }, if f == "left" { 16 } else { 8 })
    });
    let mixed = sky("mixed", &|d, f| {
        if f == "front" {
            let pixels = vec![image::Rgb([1.0f32, 2.0, 3.0]); 64];
            let mut bytes = Vec::new();
            image::codecs::hdr::HdrEncoder::new(&mut bytes).encode(&pixels, 8, 8).unwrap();
            std::fs::write(d.join("front.hdr"), bytes).unwrap();
        } else {
            write_png(&d.join(format!("{f}.png")), 8, 8);
        }
    });
    let huge = sky("huge", &|d, f| std::fs::write(d.join(format!("{f}.png")), png_header_only(30000, 30000)).unwrap());
    let corrupt =
        sky("corrupt", &|d, f| std::fs::write(d.join(format!("{f}.jpg")), b"\xff\xd8\xff not really").unwrap());
    // Two files for one face; a face that is a folder; a face that is a link to nowhere.
    let twice = sky("twice", &|d, f| write_png(&d.join(format!("{f}.png")), 8, 8));
    write_png(&twice.join("px.png"), 8, 8);
    let folder_face = sky("folder_face", &|d, f| {
        if f == "top" {
            std::fs::create_dir(d.join("top.png")).unwrap()
        } else {
            write_png(&d.join(format!("{f}.png")), 8, 8)
        }
    });
    let dangling = sky("dangling", &|d, f| {
        if f == "front" {
            std::os::unix::fs::symlink(d.join("nowhere.png"), d.join("front.png")).unwrap()
        } else {
            write_png(&d.join(format!("{f}.png")), 8, 8)
        }
    });
    let a_file = root.path().join("sky.png");
    write_png(&a_file, 8, 8);
    for (dir, needle) in [
        (&twice, "given twice: px.png and right.png"),
        (&folder_face, "top.png: skybox face 'top' is not a regular file"),
        (&dangling, "front.png: skybox face 'front' cannot be read"),
        (&a_file, "sky.png: panorama is 8x8; an equirectangular panorama is twice as wide as it is high"),
        (&five, "'back'"),
        (&non_square, "top.png"),
        (&mismatched, "left.png"),
        (&mixed, "mix HDR"),
        (&huge, ".png"),
        (&corrupt, ".jpg"),
    ] {
        match run(&dir.display().to_string(), &["--skybox", dir.to_str().unwrap()]) {
            Outcome::Refused(line) => assert!(line.contains(needle), "{}: {line}", dir.display()),
            Outcome::Loaded => panic!("{} should be refused", dir.display()),
        }
    }
}

#[test]
fn every_assimp_test_gltf_loads_or_fails_cleanly() {
    let Some(root) = assimp_models("glTF2") else { return };
    // Every .gltf and .glb below, valid samples and broken ones alike, loaded in process (the
    // loader is what is tested; the GPU side is the one OBJ models take).
    let mut files = Vec::new();
    let mut folders = vec![root.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for path in std::fs::read_dir(&folder).unwrap().flatten().map(|e| e.path()) {
            if path.is_dir() {
                folders.push(path);
            } else if ssdo::scene::gltf_model::is_gltf(&path) {
                files.push(path);
            }
        }
    }
    files.sort();
    assert!(files.len() >= 40, "expected the assimp glTF files, found {}", files.len());
    let (mut loaded, mut refused) = (0, 0);
    for file in &files {
        match ssdo::scene::load_model_file(file) {
            Ok(model) => {
                assert!(model.triangle_count() > 0 && model.bounds.min.is_finite(), "{}", file.display());
                loaded += 1;
            }
            Err(e) => {
                let line = e.to_string();
                assert!(line.contains(&*file.to_string_lossy()) && !line.contains('\n'), "{line}");
                assert!(!line.contains("reading its meshes failed"), "the crate panicked: {line}");
                refused += 1;
            }
        }
    }
    println!("assimp glTF files: {loaded} loaded, {refused} refused with one line");
    assert!(loaded >= 20, "the valid samples load: {loaded} of {}", files.len());
    let message = |name: &str| ssdo::scene::load_model_file(&root.join(name)).unwrap_err().to_string();
    assert!(message("MissingBin/BoxTextured.gltf").contains("BoxTextured0.bin"));
    assert!(message("draco/2CylinderEngine.gltf").contains("KHR_draco_mesh_compression"));
}
