//! What the loaders make of normal maps and alpha masks, from files written here: which
//! statement is taken, a height map told from a normal map, `-bm` as the scale, masks from
//! alpha or from grey, tangents that follow the UVs, and the bad inputs each with its warning
//! and a surface that still draws.

use std::path::Path;

use glam::Vec3;
use ssdo::scene::obj_model::load_obj;
use ssdo::scene::Model;

/// A 2x2 floor quad facing +y with UVs (u along +x, OBJ's v along -z), material `m` described
/// by `mtl`, written as `name.obj` and `name.mtl` into `dir` and loaded.
fn quad(dir: &Path, name: &str, mtl: &str) -> Model {
    let obj = format!(
        "mtllib {name}.mtl\nv -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 1 0\n\
         usemtl m\nf 1/1/1 2/2/1 3/3/1 4/4/1\n"
    );
    std::fs::write(dir.join(format!("{name}.mtl")), format!("newmtl m\nKd 0.5 0.5 0.5\n{mtl}")).unwrap();
    let path = dir.join(format!("{name}.obj"));
    std::fs::write(&path, obj).unwrap();
    load_obj(&path).unwrap()
}

fn rgba(dir: &Path, name: &str, w: u32, h: u32, texel: impl Fn(u32, u32) -> [u8; 4]) {
    image::RgbaImage::from_fn(w, h, |x, y| image::Rgba(texel(x, y))).save(dir.join(name)).unwrap();
}

fn grey(dir: &Path, name: &str, w: u32, h: u32, value: impl Fn(u32, u32) -> u8) {
    image::GrayImage::from_fn(w, h, |x, y| image::Luma([value(x, y)])).save(dir.join(name)).unwrap();
}

fn warned(model: &Model, needle: &str) -> bool {
    model.warnings.iter().any(|w| w.contains(needle))
}

#[test]
fn a_normal_map_under_map_bump_is_read_with_its_scale_and_tangents_follow_the_uvs() {
    let dir = tempfile::tempdir().unwrap();
    rgba(dir.path(), "n.png", 4, 4, |x, _| [128 + 20 * x as u8, 128, 250, 255]);
    let model = quad(dir.path(), "bump", "map_Bump -bm 0.5 n.png\n");
    let map = model.materials[0].normal_map.as_ref().expect("the normal map is read");
    assert_eq!(map.scale, 0.5);
    assert_eq!((map.image.width, map.image.height), (4, 4));
    // One tangent a vertex, along +u (+x), the bitangent (w · n × t) up the image (-z).
    assert_eq!(model.tangents.len(), model.vertices.len());
    for (t, v) in model.tangents.iter().zip(&model.vertices) {
        let (tangent, normal) = (Vec3::new(t[0], t[1], t[2]), Vec3::from(v.normal));
        assert!((tangent - Vec3::X).length() < 1e-4, "tangent {t:?}");
        assert!((normal.cross(tangent) * t[3] - Vec3::NEG_Z).length() < 1e-4, "bitangent sign {}", t[3]);
    }
    // `bump` is the same statement; `norm` names a normal map explicitly and wins over it.
    let model = quad(dir.path(), "old", "bump n.png\n");
    assert!(model.materials[0].normal_map.is_some());
    rgba(dir.path(), "m.png", 2, 2, |_, _| [128, 200, 220, 255]);
    let model = quad(dir.path(), "both", "norm m.png\nmap_Bump n.png\n");
    let map = model.materials[0].normal_map.as_ref().unwrap();
    assert_eq!(map.image.width, 2, "norm is taken");
    assert!(warned(&model, "map_Bump n.png left out: the normal map is norm m.png"), "{:?}", model.warnings);
}

#[test]
fn a_height_map_under_map_bump_is_recognised_and_not_read_as_normals() {
    let dir = tempfile::tempdir().unwrap();
    // Sponza's `*_bump.png`: grey heights, saved in colour or as one channel.
    rgba(dir.path(), "height_rgb.png", 8, 8, |x, y| {
        let h = (x * 30 + y * 3) as u8;
        [h, h, h, 255]
    });
    grey(dir.path(), "height_grey.png", 8, 8, |x, y| (x * 30 + y) as u8);
    for file in ["height_rgb.png", "height_grey.png"] {
        let model = quad(dir.path(), file.trim_end_matches(".png"), &format!("map_Bump {file}\n"));
        assert!(model.materials[0].normal_map.is_none(), "{file} is not a normal map");
        assert!(model.tangents.is_empty(), "no normal map, no tangents");
        assert!(warned(&model, &format!("map_Bump {file} is a height map")), "{:?}", model.warnings);
    }
    // A height map beside a normal map: the normal map is taken.
    rgba(dir.path(), "n.png", 2, 2, |_, _| [140, 128, 250, 255]);
    let model = quad(dir.path(), "pair", "norm n.png\nmap_Bump height_rgb.png\n");
    assert!(model.materials[0].normal_map.is_some());
}

#[test]
fn a_mask_comes_from_the_alpha_of_the_colour_map_or_from_a_grey_picture() {
    let dir = tempfile::tempdir().unwrap();
    // The usual case: map_d names the RGBA colour map itself; mask and colour share its pixels.
    rgba(dir.path(), "leaf.png", 4, 4, |x, _| [40, 160, 40, if x < 2 { 255 } else { 0 }]);
    let model = quad(dir.path(), "leaf", "map_Kd leaf.png\nmap_d leaf.png\n");
    let m = &model.materials[0];
    let cutout = m.cutout.as_ref().expect("map_d cuts");
    let mask = cutout.mask.as_ref().unwrap();
    assert!(std::sync::Arc::ptr_eq(&mask.rgba, &m.diffuse_map.as_ref().unwrap().rgba), "one picture, shared");
    assert_eq!(cutout.cutoff, 0.5);
    assert!(cutout.coverage_at([0.1, 0.5]) > 0.5 && cutout.coverage_at([0.9, 0.5]) < 0.5);
    // A one-channel mask: coverage is its grey, on a material without a colour map.
    grey(dir.path(), "mask.png", 4, 1, |x, _| if x % 2 == 0 { 255 } else { 0 });
    let model = quad(dir.path(), "grey", "map_d mask.png\n");
    let m = &model.materials[0];
    assert!(m.diffuse_map.is_none(), "an untextured material");
    let cutout = m.cutout.as_ref().expect("a grey mask cuts");
    assert!(cutout.coverage_at([0.1, 0.0]) > 0.99 && cutout.coverage_at([0.4, 0.0]) < 0.01);
}

#[test]
fn maps_that_are_missing_or_of_another_size_warn_and_the_surface_still_draws() {
    let dir = tempfile::tempdir().unwrap();
    // A missing mask: one warning, and the surface stays opaque (not a checker of holes).
    let model = quad(dir.path(), "nomask", "map_d gone.png\n");
    assert!(model.materials[0].cutout.is_none());
    assert!(warned(&model, "gone.png") && warned(&model, "the surface stays opaque"), "{:?}", model.warnings);
    // A missing normal map: one warning, the vertex normals, no tangents.
    let model = quad(dir.path(), "nonormals", "norm gone.png\n");
    assert!(model.materials[0].normal_map.is_none() && model.tangents.is_empty());
    assert!(warned(&model, "the surface keeps its vertex normals"), "{:?}", model.warnings);
    // A corrupt normal map: the same.
    std::fs::write(dir.path().join("broken.png"), b"\x89PNG\r\n\x1a\nnot really").unwrap();
    let model = quad(dir.path(), "broken", "norm broken.png\n");
    assert!(model.materials[0].normal_map.is_none());
    assert!(warned(&model, "broken.png") && warned(&model, "the surface keeps its vertex normals"));
    // A normal map of another size than the colour map: each is read at its own size.
    rgba(dir.path(), "colour.png", 16, 8, |_, _| [200, 100, 50, 255]);
    rgba(dir.path(), "n.png", 4, 4, |_, _| [150, 128, 240, 255]);
    let model = quad(dir.path(), "sizes", "map_Kd colour.png\nnorm n.png\n");
    let m = &model.materials[0];
    assert_eq!(m.diffuse_map.as_ref().map(|i| (i.width, i.height)), Some((16, 8)));
    assert_eq!(m.normal_map.as_ref().map(|n| (n.image.width, n.image.height)), Some((4, 4)));
    assert!(model.warnings.is_empty(), "{:?}", model.warnings);
}

#[test]
fn gltf_blend_is_a_mask_with_one_warning_and_opaque_materials_cut_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let material = |mode: &str| {
        serde_json::json!({
            "name": "glass",
            "pbrMetallicRoughness": { "baseColorFactor": [1.0, 1.0, 1.0, 0.3], "metallicFactor": 0.0 },
            "alphaMode": mode
        })
    };
    let bin = dir.path().join("quad.bin");
    std::fs::write(&bin, crate::common::quad_buffer()).unwrap();
    let load = |mode: &str| {
        let document = crate::common::quad_gltf(
            serde_json::json!({ "uri": "quad.bin", "byteLength": 144 }),
            crate::common::one_node(),
            material(mode),
        );
        let path = dir.path().join(format!("{mode}.gltf"));
        std::fs::write(&path, serde_json::to_vec(&document).unwrap()).unwrap();
        ssdo::scene::load_model_file(&path).unwrap()
    };
    let blend = load("BLEND");
    let cutout = blend.materials[0].cutout.as_ref().expect("BLEND is drawn as a mask");
    assert_eq!((cutout.cutoff, cutout.factor), (0.5, 0.3));
    assert!(cutout.coverage_at([0.5, 0.5]) < cutout.cutoff, "alpha 0.3 is cut at 0.5");
    assert_eq!(blend.warnings.iter().filter(|w| w.contains("BLEND")).count(), 1, "{:?}", blend.warnings);
    let opaque = load("OPAQUE");
    assert!(opaque.materials[0].cutout.is_none() && opaque.materials[0].normal_map.is_none());
    assert!(opaque.tangents.is_empty());
}

#[test]
fn a_normal_scale_that_is_no_number_or_overflows_is_said_and_kept_finite() {
    let dir = tempfile::tempdir().unwrap();
    rgba(dir.path(), "n.png", 4, 4, |x, _| [128 + 20 * x as u8, 128, 250, 255]);
    for (i, (bm, scale, needle)) in [
        ("NaN", 1.0, "-bm NaN is not a finite number; the normal map is read at scale 1"),
        ("inf", 1.0, "-bm inf is not a finite number"),
        ("abc", 1.0, "-bm abc is not a number; the normal map is read at scale 1"),
        ("1e18", 1e3, "-bm 1e18 is beyond ±1000; the normal map is read at scale 1000"),
        ("-1e38", -1e3, "is read at scale -1000"),
        ("0.5", 0.5, ""),
    ]
    .into_iter()
    .enumerate()
    {
        let model = quad(dir.path(), &format!("q{i}"), &format!("map_Bump -bm {bm} n.png\n"));
        let map = model.materials[0].normal_map.as_ref().expect("the map is read");
        assert_eq!(map.scale, scale, "-bm {bm}");
        let said = model.warnings.iter().filter(|w| w.contains("-bm")).count();
        assert_eq!(said, usize::from(!needle.is_empty()), "-bm {bm}: {:?}", model.warnings);
        assert!(needle.is_empty() || warned(&model, needle), "-bm {bm}: {:?}", model.warnings);
    }
}

#[test]
fn a_model_its_cut_outs_remove_entirely_says_so_and_which_material() {
    let dir = tempfile::tempdir().unwrap();
    rgba(dir.path(), "clear.png", 4, 4, |_, _| [200, 200, 200, 0]);
    rgba(dir.path(), "leaf.png", 4, 4, |x, _| [40, 160, 40, if x < 2 { 0 } else { 255 }]);
    let gone = quad(dir.path(), "gone", "map_Kd clear.png\nmap_d clear.png\n");
    let note = gone.cut_away().expect("a model cut away whole says so");
    assert!(note.contains("nothing of the model is left to draw") && note.contains("material 'm'"), "{note}");
    assert!(warned(&gone, "nothing of the model is left to draw"), "{:?}", gone.warnings);
    // A leaf keeps half its texels: nothing to say.
    let leaf = quad(dir.path(), "leaf", "map_Kd leaf.png\nmap_d leaf.png\n");
    assert_eq!(leaf.cut_away(), None);
    // glTF: a cutoff above every texel, or a base colour alpha of 0.
    let bin = dir.path().join("quad.bin");
    std::fs::write(&bin, crate::common::quad_buffer()).unwrap();
    for (name, material) in [
        ("cutoff", serde_json::json!({ "name": "fence", "alphaMode": "MASK", "alphaCutoff": 2.0 })),
        ("huge", serde_json::json!({ "name": "fence", "alphaMode": "MASK", "alphaCutoff": 1e38 })),
        (
            "alpha",
            serde_json::json!({
                "name": "fence", "alphaMode": "MASK",
                "pbrMetallicRoughness": { "baseColorFactor": [1.0, 1.0, 1.0, 0.0] }
            }),
        ),
    ] {
        let document = crate::common::quad_gltf(
            serde_json::json!({ "uri": "quad.bin", "byteLength": 144 }),
            crate::common::one_node(),
            material,
        );
        let path = dir.path().join(format!("{name}.gltf"));
        std::fs::write(&path, serde_json::to_vec(&document).unwrap()).unwrap();
        let model = ssdo::scene::load_model_file(&path).unwrap();
        let note = model.cut_away().unwrap_or_else(|| panic!("{name}: nothing said"));
        assert!(note.contains("nothing of the model is left") && note.contains("'fence'"), "{name}: {note}");
    }
}
