//! The glTF loader on arbitrary bytes: up to the first NUL byte the `.gltf` document, then up to
//! the next one a file `b.bin` beside it, and the rest a file `i.png` (documents may name either,
//! or reach outside the folder, which must be refused).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut parts = data.splitn(3, |&b| b == 0);
    let (document, bin, image) = (parts.next().unwrap_or(&[]), parts.next().unwrap_or(&[]), parts.next().unwrap_or(&[]));
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("m.gltf"), document).unwrap();
    std::fs::write(dir.path().join("b.bin"), bin).unwrap();
    std::fs::write(dir.path().join("i.png"), image).unwrap();
    // Errors are fine; a panic is a finding, even one the loader's guard catches.
    let before = ssdo::guard::caught();
    let _ = ssdo::scene::load_model_file(&dir.path().join("m.gltf"));
    assert_eq!(ssdo::guard::caught(), before, "the glTF loader panicked (caught by its guard)");
});
