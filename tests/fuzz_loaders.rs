//! Property tests of the loaders (run in CI): OBJ and MTL text generated from a grammar of real and
//! broken statements, and random bytes as skybox faces. Loading may fail, but only with an error:
//! any panic — even one the loader's safety net would catch — fails the test. Longer runs:
//! `cargo fuzz run obj` / `cargo fuzz run skybox` in `fuzz/`.

use std::cell::Cell;
use std::sync::Once;

use proptest::prelude::*;
use ssdo::scene::{model::load_obj, Skybox};

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

fn panics() -> usize {
    PANICS.with(Cell::get)
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

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

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
