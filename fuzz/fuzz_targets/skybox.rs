//! The skybox loader on arbitrary bytes split into six faces.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let dir = tempfile::tempdir().unwrap();
    let names = ["right.png", "left.png", "top.jpg", "bottom.hdr", "front.exr", "back.png"];
    let chunk = data.len() / 6 + 1;
    for (i, name) in names.iter().enumerate() {
        let start = (i * chunk).min(data.len());
        let end = ((i + 1) * chunk).min(data.len());
        std::fs::write(dir.path().join(name), &data[start..end]).unwrap();
    }
    // Errors are fine; a panic is a finding, even one the loader's guard catches.
    let before = ssdo::guard::caught();
    let _ = ssdo::scene::Skybox::load(dir.path());
    assert_eq!(ssdo::guard::caught(), before, "the skybox loader panicked (caught by its guard)");
});
