//! Property tests of the loaders (run in CI): OBJ and MTL text generated from a grammar of real and
//! broken statements, glTF documents whose buffers, views and accessors disagree, and random
//! bytes as skybox faces and panoramas. Loading may fail, but only with an error:
//! any panic — even one the loader's safety net would catch — fails the test. Longer runs:
//! `cargo fuzz run obj` / `cargo fuzz run skybox` in `fuzz/`.

use std::cell::Cell;
use std::sync::Once;

use proptest::prelude::*;
use serde_json::json;
use ssdo::scene::{obj_model::load_obj, Skybox};

thread_local! {
    /// Panics on this thread (the hook runs on the panicking thread; tests run in parallel).
    static PANICS: Cell<usize> = const { Cell::new(0) };
}
static HOOK: Once = Once::new();

fn count_panics() {
    HOOK.call_once(|| {
        let default = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            PANICS.with(|p| p.set(p.get() + 1));
            default(info);
        }));
    });
}

/// Panics on this thread, and those the loaders' guard caught anywhere (it keeps them from this
/// hook's predecessor): a caught panic is a bug too.
fn panics() -> usize {
    PANICS.with(Cell::get) + ssdo::guard::caught()
}

fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        (-1e3f32..1e3).prop_map(|f| f.to_string()),
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("-inf".to_string()),
        Just("1e39".to_string()),
        Just("".to_string()),
        "[a-z]{1,3}",
    ]
}

fn index() -> impl Strategy<Value = String> {
    prop_oneof![(-12i64..12).prop_map(|i| i.to_string()), Just(String::new()), Just("99999999999999999999".to_string())]
}

fn obj_line() -> impl Strategy<Value = String> {
    prop_oneof![
        (number(), number(), number()).prop_map(|(a, b, c)| format!("v {a} {b} {c}")),
        (number(), number()).prop_map(|(a, b)| format!("vt {a} {b}")),
        (number(), number(), number()).prop_map(|(a, b, c)| format!("vn {a} {b} {c}")),
        prop::collection::vec((index(), index(), index(), 0..4usize), 0..6).prop_map(|vs| {
            let refs: Vec<String> = vs
                .into_iter()
                .map(|(v, t, n, form)| match form {
                    0 => v,
                    1 => format!("{v}/{t}"),
                    2 => format!("{v}//{n}"),
                    _ => format!("{v}/{t}/{n}"),
                })
                .collect();
            format!("f {}", refs.join(" "))
        }),
        "[a-z]{0,8}".prop_map(|m| format!("usemtl {m}")),
        Just("mtllib fuzz.mtl".to_string()),
        Just("mtllib ..\\nowhere\\x.mtl".to_string()),
        (index(), index()).prop_map(|(a, b)| format!("l {a} {b}")),
        index().prop_map(|a| format!("p {a}")),
        "[ -~]{0,30}",
    ]
}

fn mtl_line() -> impl Strategy<Value = String> {
    prop_oneof![
        "[a-z]{0,6}".prop_map(|m| format!("newmtl {m}")),
        (prop_oneof![Just("Ka"), Just("Kd"), Just("Ks"), Just("Ke")], prop::collection::vec(number(), 0..5))
            .prop_map(|(k, v)| format!("{k} {}", v.join(" "))),
        number().prop_map(|n| format!("Ns {n}")),
        "[ -~]{0,20}".prop_map(|t| format!("map_Kd {t}")),
        "[ -~]{0,20}".prop_map(|t| format!("map_Ks -bm {t}")),
        "[ -~]{0,30}",
    ]
}

/// One accessor of a glTF primitive: view offset and length, accessor offset, count, component
/// type and type (`None`: the right ones for its use), and the view's stride.
type Accessor = (usize, usize, usize, usize, Option<(u32, &'static str)>, Option<usize>);

fn accessor() -> impl Strategy<Value = Accessor> {
    let kind = (
        prop_oneof![Just(5120u32), Just(5121), Just(5122), Just(5123), Just(5125), Just(5126), Just(7)],
        prop_oneof![Just("SCALAR"), Just("VEC2"), Just("VEC3"), Just("VEC4"), Just("MAT4")],
    );
    (
        prop_oneof![2 => Just(0usize), 1 => 0..80usize],
        prop_oneof![2 => 48..120usize, 1 => 0..48usize],
        prop_oneof![3 => Just(0usize), 1 => 0..16usize],
        prop_oneof![3 => 0..12usize, 1 => 0..40usize],
        prop_oneof![3 => Just(None), 1 => kind.prop_map(Some)],
        prop_oneof![3 => Just(None), 1 => (1..16usize).prop_map(|k| Some(4 * k)), 1 => (0..40usize).prop_map(Some)],
    )
}

/// A glTF document with one primitive whose four accessors (positions, normals, UVs, indices)
/// are as generated, over a buffer of `data` that claims `claimed` bytes, under a parent node
/// scaled by `scale` in x.
fn gltf_document(accessors: &[Accessor], data: &[u8], claimed: usize, mode: u32, scale: f32) -> serde_json::Value {
    let views: Vec<serde_json::Value> = accessors
        .iter()
        .enumerate()
        .map(|(i, &(offset, len, _, _, kind, stride))| {
            // Well-typed indices read the buffer's last 32 bytes, which hold small numbers.
            let (offset, len) = if i == 3 && kind.is_none() && data.len() == 160 { (128, 32) } else { (offset, len) };
            let mut view = json!({ "buffer": 0, "byteOffset": offset, "byteLength": len });
            if let Some(stride) = stride {
                view["byteStride"] = json!(stride);
            }
            view
        })
        .collect();
    let accessors: Vec<serde_json::Value> = accessors
        .iter()
        .enumerate()
        .map(|(i, &(_, _, offset, count, kind, _))| {
            // Positions, normals, UVs and indices, as glTF wants them.
            let (component, kind) =
                kind.unwrap_or([(5126, "VEC3"), (5126, "VEC3"), (5126, "VEC2"), (5123, "SCALAR")][i]);
            json!({ "bufferView": i, "byteOffset": offset, "componentType": component, "count": count, "type": kind,
                    "min": [-1.0, -1.0, -1.0], "max": [1.0, 1.0, 1.0] })
        })
        .collect();
    let uri = format!("data:application/octet-stream;base64,{}", base64_of(data));
    json!({
        "asset": { "version": "2.0" },
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "children": [1], "scale": [scale, 1.0, 1.0] }, { "mesh": 0, "rotation": [0.0, 0.0, 0.0, 1.0] }],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2 }, "indices": 3, "mode": mode }] }],
        "buffers": [{ "uri": uri, "byteLength": claimed }],
        "bufferViews": views,
        "accessors": accessors
    })
}

fn base64_of(bytes: &[u8]) -> String {
    use base64::Engine;
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn gltf_with_inconsistent_buffers_never_panics(
        accessors in prop::collection::vec(accessor(), 4),
        data in prop_oneof![
            3 => (prop::collection::vec(prop_oneof![3 => Just(0x3fu8), 1 => any::<u8>()], 128), prop::collection::vec(0..10u16, 16))
                .prop_map(|(floats, indices)| [floats, indices.iter().flat_map(|i| i.to_le_bytes()).collect()].concat()),
            1 => prop::collection::vec(any::<u8>(), 0..160),
        ],
        short in prop_oneof![3 => Just(0usize), 1 => 0..200usize],
        mode in prop_oneof![6 => Just(4u32), 1 => Just(0), 1 => Just(5), 1 => Just(9)],
        scale in prop_oneof![3 => Just(1.0f32), 1 => Just(-1.0), 1 => Just(0.0), 1 => Just(1e30)],
        glb in any::<bool>(),
    ) {
        count_panics();
        let dir = tempfile::tempdir().unwrap();
        // Mostly a buffer as long as it claims to be; now and then one shorter.
        let document = gltf_document(&accessors, &data, data.len() + short, mode, scale);
        let path = dir.path().join(if glb { "fuzz.glb" } else { "fuzz.gltf" });
        std::fs::write(&path, document.to_string()).unwrap();
        let before = panics();
        if let Ok(model) = ssdo::scene::load_model_file(&path) {
            prop_assert!(model.vertices.iter().all(|v| v.position.iter().chain(&v.normal).chain(&v.uv).all(|c| c.is_finite())));
            prop_assert!(model.indices.iter().all(|&i| (i as usize) < model.vertices.len()));
        }
        prop_assert_eq!(panics(), before, "the glTF loader panicked");
    }

    #[test]
    fn panoramas_of_random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..256), ext in 0..4usize) {
        count_panics();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(format!("pano.{}", ["png", "jpg", "hdr", "exr"][ext]));
        let mut data = if bytes.len() % 2 == 0 { b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n".to_vec() } else { Vec::new() };
        data.extend_from_slice(&bytes);
        std::fs::write(&path, data).unwrap();
        let before = panics();
        let _ = Skybox::load(&path);
        prop_assert_eq!(panics(), before, "the panorama loader panicked");
    }

    #[test]
    fn obj_and_mtl_never_panic(obj in prop::collection::vec(obj_line(), 0..40), mtl in prop::collection::vec(mtl_line(), 0..12), noise in prop::collection::vec(any::<u8>(), 0..64)) {
        count_panics();
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("fuzz.mtl"), mtl.join("\n")).unwrap();
        let mut text = obj.join("\n").into_bytes();
        text.extend_from_slice(&noise);
        std::fs::write(dir.path().join("fuzz.obj"), &text).unwrap();
        let before = panics();
        if let Ok(model) = load_obj(&dir.path().join("fuzz.obj")) {
            prop_assert!(model.vertices.iter().all(|v| v.position.iter().chain(&v.normal).chain(&v.uv).all(|c| c.is_finite())));
            prop_assert!(model.indices.iter().all(|&i| (i as usize) < model.vertices.len()));
            prop_assert!(model.bounds.min.is_finite() && model.bounds.max.is_finite());
        }
        prop_assert_eq!(panics(), before, "the loader panicked");
    }

    #[test]
    fn skybox_faces_of_random_bytes_never_panic(faces in prop::collection::vec((prop::collection::vec(any::<u8>(), 0..256), 0..5usize), 6)) {
        count_panics();
        let dir = tempfile::tempdir().unwrap();
        let names = ["right", "left", "top", "bottom", "front", "back"];
        let exts = ["png", "jpg", "hdr", "exr", "jpeg"];
        for ((bytes, ext), name) in faces.iter().zip(names) {
            // Valid PNG signatures now and then, so decoding gets past the first byte.
            let mut data = if bytes.len() % 3 == 0 { b"\x89PNG\r\n\x1a\n".to_vec() } else { Vec::new() };
            data.extend_from_slice(bytes);
            std::fs::write(dir.path().join(format!("{name}.{}", exts[*ext])), data).unwrap();
        }
        let before = panics();
        let _ = Skybox::load(dir.path());
        prop_assert_eq!(panics(), before, "the skybox loader panicked");
    }
}
