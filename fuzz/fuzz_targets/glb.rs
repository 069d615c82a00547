//! The glTF loader on arbitrary bytes as a binary `.glb` file.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("m.glb"), data).unwrap();
    // Errors are fine; a panic is a finding, even one the loader's guard catches.
    let before = ssdo::guard::caught();
    let _ = ssdo::scene::load_model_file(&dir.path().join("m.glb"));
    assert_eq!(ssdo::guard::caught(), before, "the glTF loader panicked (caught by its guard)");
});
