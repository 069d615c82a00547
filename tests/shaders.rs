//! WGSL checks that need no GPU: every shader parses and validates with naga (the same
//! front end wgpu uses), every file under shaders/ is embedded, and the uniform structs have the
//! same size in Rust and WGSL.

use ssdo::render::uniforms::{FrameUniforms, GpuLight, MaterialParams};
use ssdo::shaders;

fn parse(name: &str) -> naga::Module {
    let source = shaders::resolve(name).expect("shader resolves");
    naga::front::wgsl::parse_str(&source)
        .unwrap_or_else(|e| panic!("{name} does not parse:\n{}", e.emit_to_string(&source)))
}

#[test]
fn every_shader_parses_and_validates() {
    let mut count = 0;
    for name in shaders::entry_points() {
        let module = parse(name);
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name} does not validate: {e:?}"));
        count += 1;
    }
    assert!(count >= 5, "expected the pass shaders, found {count}");
}

#[test]
fn every_wgsl_file_is_embedded() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
    let mut on_disk = Vec::new();
    for dir in [root.clone(), root.join("common")] {
        for entry in std::fs::read_dir(&dir).unwrap().flatten() {
            let path = entry.path();
            if path.extension().is_some_and(|e| e == "wgsl") {
                on_disk.push(path.strip_prefix(&root).unwrap().to_string_lossy().replace('\\', "/"));
            }
        }
    }
    for name in &on_disk {
        assert!(shaders::SOURCES.iter().any(|(n, _)| n == name), "{name} is not in shaders::SOURCES");
    }
    assert_eq!(on_disk.len(), shaders::SOURCES.len(), "SOURCES lists a file that is not on disk");
}

#[test]
fn includes_are_resolved_once() {
    let source = shaders::resolve("composite.wgsl").unwrap();
    assert!(!source.contains("#include"));
    assert_eq!(source.matches("struct Frame {").count(), 1, "uniforms.wgsl included twice");
}

fn wgsl_size(module: &naga::Module, name: &str) -> u32 {
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).unwrap();
    let (handle, _) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no struct {name}"));
    layouter[handle].size
}

#[test]
fn uniform_structs_match_wgsl() {
    let gbuffer = parse("gbuffer.wgsl");
    assert_eq!(wgsl_size(&gbuffer, "Frame") as usize, std::mem::size_of::<FrameUniforms>());
    assert_eq!(wgsl_size(&gbuffer, "Light") as usize, std::mem::size_of::<GpuLight>());
    assert_eq!(wgsl_size(&gbuffer, "MaterialParams") as usize, std::mem::size_of::<MaterialParams>());
}
