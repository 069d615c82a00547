//! The OBJ loader on arbitrary bytes; the first NUL byte splits them into the OBJ and its MTL.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let (obj, mtl) = match data.iter().position(|&b| b == 0) {
        Some(i) => (&data[..i], &data[i + 1..]),
        None => (data, &[][..]),
    };
    let dir = tempfile::tempdir().unwrap();
    let mut text = b"mtllib m.mtl\n".to_vec();
    text.extend_from_slice(obj);
    std::fs::write(dir.path().join("m.mtl"), mtl).unwrap();
    std::fs::write(dir.path().join("m.obj"), text).unwrap();
    // Errors are fine; a panic is a finding, even one the loader's guard catches.
    let before = ssdo::guard::caught();
    let _ = ssdo::scene::obj_model::load_obj(&dir.path().join("m.obj"));
    assert_eq!(ssdo::guard::caught(), before, "the OBJ loader panicked (caught by its guard)");
});
