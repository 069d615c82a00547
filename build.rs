//! Embeds every WGSL file under `shaders/` in the library (`shaders::SOURCES`): a new shader is
//! a file there and nothing else.

use std::path::Path;

fn main() {
    println!("cargo:rerun-if-changed=shaders");
    let mut names = Vec::new();
    collect(Path::new("shaders"), "", &mut names);
    names.sort();
    let mut out = String::from("/// Every WGSL file under `shaders/`, by its path relative to that folder.\n");
    out += "pub const SOURCES: &[(&str, &str)] = &[\n";
    for name in &names {
        out += &format!("    ({name:?}, include_str!(concat!(env!(\"CARGO_MANIFEST_DIR\"), \"/shaders/{name}\"))),\n");
    }
    out += "];\n";
    let path = Path::new(&std::env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("shader_sources.rs");
    std::fs::write(path, out).expect("the build's output folder is writable");
}

/// The `.wgsl` files below `dir`, as paths relative to `shaders/` (`prefix` is `dir`'s).
fn collect(dir: &Path, prefix: &str, names: &mut Vec<String>) {
    let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    for entry in entries.flatten() {
        let (path, name) = (entry.path(), entry.file_name().to_string_lossy().into_owned());
        if path.is_dir() {
            collect(&path, &format!("{prefix}{name}/"), names);
        } else if name.ends_with(".wgsl") {
            names.push(format!("{prefix}{name}"));
        }
    }
}
