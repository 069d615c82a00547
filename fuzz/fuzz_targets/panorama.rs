//! The panorama loader on arbitrary bytes: the first byte picks the file's extension (`.hdr`,
//! `.exr`, `.png`, `.jpg`), the rest is the file.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, bytes)) = data.split_first() else { return };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(format!("sky.{}", ["hdr", "exr", "png", "jpg"][pick as usize % 4]));
    std::fs::write(&path, bytes).unwrap();
    // Errors are fine; a panic is a finding, even one the loader's guard catches.
    let before = ssdo::guard::caught();
    let _ = ssdo::scene::Skybox::load(&path);
    assert_eq!(ssdo::guard::caught(), before, "the panorama loader panicked (caught by its guard)");
});
