//! WGSL sources, embedded in the binary (every file under `shaders/`, listed by `build.rs`), and a
//! tiny `#include "path"` resolver.
//!
//! Shared code (uniform structs, the full-screen triangle, lighting, sampling helpers) lives in
//! `shaders/common/`. A line `#include "common/x.wgsl"` is replaced by that file's text the
//! first time it is seen and dropped after that (include-once), so two includes of the same
//! helper never define it twice. Variants are WGSL `override` constants, never string surgery.

use crate::{Error, Result};

// `SOURCES`: every WGSL file under `shaders/`, listed by `build.rs`.
include!(concat!(env!("OUT_DIR"), "/shader_sources.rs"));

/// The shaders that are compiled as modules (the rest are only included).
pub fn entry_points() -> impl Iterator<Item = &'static str> {
    SOURCES.iter().map(|(name, _)| *name).filter(|name| !name.starts_with("common/"))
}

fn source(name: &str) -> Result<&'static str> {
    SOURCES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, text)| *text)
        .ok_or_else(|| Error::Setting(format!("shader {name}: no such embedded WGSL file")))
}

/// Returns `name` with every `#include` resolved, each file included at most once.
pub fn resolve(name: &str) -> Result<String> {
    let mut seen = Vec::new();
    let mut out = String::new();
    append(name, &mut seen, &mut out)?;
    Ok(out)
}

fn append(name: &str, seen: &mut Vec<String>, out: &mut String) -> Result<()> {
    if seen.iter().any(|s| s == name) {
        return Ok(());
    }
    seen.push(name.to_owned());
    for line in source(name)?.lines() {
        match line.trim().strip_prefix("#include") {
            Some(rest) => {
                let target = rest.trim().trim_matches('"');
                append(target, seen, out)
                    .map_err(|e| Error::Setting(format!("{name}: include of {target} failed: {e}")))?;
            }
            None => {
                out.push_str(line);
                out.push('\n');
            }
        }
    }
    Ok(())
}

/// Compiles `name` (with its includes) into a shader module labelled after the file.
pub fn module(device: &wgpu::Device, name: &str) -> Result<wgpu::ShaderModule> {
    let code = resolve(name)?;
    let label = format!("{}_shader", name.trim_end_matches(".wgsl"));
    Ok(device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(&label),
        source: wgpu::ShaderSource::Wgsl(code.into()),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn includes_are_pasted_once_and_a_missing_one_names_both_files() {
        // blur.wgsl includes uniforms.wgsl itself and through gbuffer_read.wgsl.
        let blur = resolve("blur.wgsl").unwrap();
        assert_eq!(blur.matches("struct Frame {").count(), 1);
        assert!(!blur.contains("#include"));
        let e = resolve("no_such.wgsl").unwrap_err().to_string();
        assert!(e.contains("no_such.wgsl"), "{e}");
    }
}
