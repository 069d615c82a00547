//! The bodies of the coverage-guided fuzz targets (`fuzz/fuzz_targets/*.rs` include this file
//! and call one function each), so that the test build compiles them and the tests below run
//! them on every seed (`fuzz/seeds/<target>/`) and every input a fuzzer ever failed on
//! (`fuzz/regressions/<target>/`, committed as they were found). Each function writes its bytes
//! as the files its loader reads, loads them, and panics if the loader panicked, even where the
//! loader's own guard caught it: for libFuzzer that is a crash.

#![allow(dead_code)]

/// Runs `load` and fails if a panic reached the loaders' guard on the way.
fn unguarded(what: &str, load: impl FnOnce()) {
    let before = ssdo::guard::caught();
    load();
    assert_eq!(ssdo::guard::caught(), before, "the {what} loader panicked (caught by its guard)");
}

/// The OBJ loader: up to the first NUL byte the OBJ (after `mtllib m.mtl`), the rest its MTL.
pub fn obj(data: &[u8]) {
    let (text, mtl) = match data.iter().position(|&b| b == 0) {
        Some(i) => (&data[..i], &data[i + 1..]),
        None => (data, &[][..]),
    };
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("m.mtl"), mtl).unwrap();
    std::fs::write(dir.path().join("m.obj"), [&b"mtllib m.mtl\n"[..], text].concat()).unwrap();
    unguarded("OBJ", || drop(ssdo::scene::obj_model::load_obj(&dir.path().join("m.obj"))));
}

/// The skybox loader: the bytes split into six faces of several formats.
pub fn skybox(data: &[u8]) {
    let dir = tempfile::tempdir().unwrap();
    let names = ["right.png", "left.png", "top.jpg", "bottom.hdr", "front.exr", "back.png"];
    let chunk = data.len() / 6 + 1;
    for (i, name) in names.iter().enumerate() {
        let (start, end) = ((i * chunk).min(data.len()), ((i + 1) * chunk).min(data.len()));
        std::fs::write(dir.path().join(name), &data[start..end]).unwrap();
    }
    unguarded("skybox", || drop(ssdo::scene::Skybox::load(dir.path())));
}

/// The glTF loader: up to the first NUL byte the `.gltf` document, up to the next a file
/// `b.bin` beside it, the rest a file `i.png` (a document may name either, or reach outside the
/// folder, which must be refused).
pub fn gltf(data: &[u8]) {
    let mut parts = data.splitn(3, |&b| b == 0);
    let dir = tempfile::tempdir().unwrap();
    for name in ["m.gltf", "b.bin", "i.png"] {
        std::fs::write(dir.path().join(name), parts.next().unwrap_or_default()).unwrap();
    }
    unguarded("glTF", || drop(ssdo::scene::load_model_file(&dir.path().join("m.gltf"))));
}

/// The glTF loader on the bytes as a binary `.glb`.
pub fn glb(data: &[u8]) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("m.glb"), data).unwrap();
    unguarded("glTF", || drop(ssdo::scene::load_model_file(&dir.path().join("m.glb"))));
}

/// The panorama loader: the first byte picks the extension (`.hdr`, `.exr`, `.png`, `.jpg`),
/// the rest is the file.
pub fn panorama(data: &[u8]) {
    let Some((&pick, bytes)) = data.split_first() else { return };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(format!("sky.{}", ["hdr", "exr", "png", "jpg"][pick as usize % 4]));
    std::fs::write(&path, bytes).unwrap();
    unguarded("panorama", || drop(ssdo::scene::Skybox::load(&path)));
}

/// The preset reader: the bytes as a preset file. One that is read writes itself back as a file
/// that reads as the same preset, of at most a few kilobytes (its strings are bounded), and its
/// knobs make settings, flags and a label without a panic.
pub fn preset(data: &[u8]) {
    use ssdo::preset::Preset;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("p.json");
    std::fs::write(&path, data).unwrap();
    let Ok(preset) = Preset::load(&path) else { return };
    let text = preset.to_text();
    assert!(text.len() < 4 * ssdo::text::MAX_NAME_CHARS * 4 + 4096, "{} bytes written", text.len());
    assert_eq!(Preset::parse(&path, &text).ok().as_ref(), Some(&preset), "{text}");
    let settings = ssdo::render::Settings::default().with_knobs(preset.knobs);
    drop((settings, preset.knobs.flags(0.5), preset.knobs.label(), preset.elsewhere("a device", (8, 8))));
}

/// A fuzz target: its name and its entry, as `fuzz/Cargo.toml` names them.
pub type Target = (&'static str, fn(&[u8]));

pub const TARGETS: [Target; 6] =
    [("obj", obj), ("skybox", skybox), ("gltf", gltf), ("glb", glb), ("panorama", panorama), ("preset", preset)];

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    #[test]
    fn every_seed_and_every_input_a_fuzzer_failed_on_loads_or_is_refused_without_a_panic() {
        let fuzz = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz");
        let mut ran = 0;
        for (name, body) in TARGETS {
            for folder in [fuzz.join("seeds").join(name), fuzz.join("regressions").join(name)] {
                let Ok(entries) = std::fs::read_dir(&folder) else { continue };
                for entry in entries.flatten() {
                    let data = std::fs::read(entry.path()).unwrap();
                    let outcome = std::panic::catch_unwind(|| body(&data));
                    assert!(outcome.is_ok(), "{name}: {} panicked", entry.path().display());
                    ran += 1;
                }
            }
        }
        assert!(ran >= 4, "the seeds are missing: {ran} inputs");
    }
}
