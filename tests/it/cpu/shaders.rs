//! WGSL checks that need no GPU: every shader parses and validates with naga (the same
//! front end wgpu uses), every file under shaders/ is embedded, and the uniform structs have the
//! same members at the same offsets in Rust and WGSL.

use ssdo::render::uniforms::{FilterParams, FrameUniforms, GpuLight, MaterialParams, SamplingParams};
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

/// The WGSL struct `name` as naga lays it out: its size and each member's (name, offset).
fn wgsl_layout(module: &naga::Module, name: &str) -> (usize, Vec<(String, usize)>) {
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).unwrap();
    let (handle, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no struct {name}"));
    let naga::TypeInner::Struct { members, .. } = &ty.inner else { panic!("{name} is not a struct") };
    let members = members.iter().map(|m| (m.name.clone().unwrap_or_default(), m.offset as usize)).collect();
    (layouter[handle].size as usize, members)
}

/// Checks a Rust struct against its WGSL mirror: the same size, and the same members (names
/// included) at the same offsets.
macro_rules! same_layout {
    ($module:expr, $wgsl:literal, $rust:ty { $($field:ident),* $(,)? }) => {{
        let (size, members) = wgsl_layout($module, $wgsl);
        assert_eq!(size, std::mem::size_of::<$rust>(), "{}: size", $wgsl);
        let rust: Vec<(String, usize)> =
            vec![$((stringify!($field).to_string(), std::mem::offset_of!($rust, $field))),*];
        assert_eq!(members, rust, "{} against {}: members and offsets", $wgsl, stringify!($rust));
    }};
}

#[test]
fn uniform_structs_match_wgsl_member_for_member() {
    let gbuffer = parse("gbuffer.wgsl");
    same_layout!(
        &gbuffer,
        "Frame",
        FrameUniforms {
            world_to_view,
            view_to_clip,
            view_to_world,
            viewport,
            near,
            far,
            display_scale,
            min_light_distance2,
            ambient,
            orbit_distance,
            sky_scale,
            sky_mips,
            pre_exposure,
            ao_strength,
            ao_power,
            light_count,
            frame_index,
            default_thickness,
            output_origin,
            _pad1,
            sky_irradiance,
            previous_world_to_clip,
            previous_projection,
            view_to_previous_view,
            previous_eye,
            _pad2,
            first_lights,
        }
    );
    same_layout!(
        &gbuffer,
        "Light",
        GpuLight { world_position, intensity, view_position, _pad0, color, cube_half_size }
    );
    same_layout!(
        &gbuffer,
        "MaterialParams",
        MaterialParams { albedo, specular, shininess_bits, normal_scale, alpha_cutoff, alpha_factor, thickness_code }
    );
    same_layout!(
        &parse("points.wgsl"),
        "SamplingParams",
        SamplingParams {
            kernel,
            rotations,
            radius,
            bias_length,
            sample_count,
            sky_mip,
            sky_strength,
            indirect_strength,
            sender_sky_strength,
            _pad0,
            slices,
            steps,
            reach,
            thickness,
            schedule,
        }
    );
    same_layout!(
        &parse("temporal.wgsl"),
        "FilterParams",
        FilterParams { radius, accumulate, motion_accumulate, history_frames }
    );
}

/// The members of the frame uniforms that `name`'s fragment stages read, directly or through
/// the functions they call (the whole struct, where one loads it whole, as "*").
fn frame_members_read_per_pixel(name: &str) -> std::collections::BTreeSet<String> {
    use naga::{Expression, Statement};
    let module = parse(name);
    let (frame, _) = module.global_variables.iter().find(|(_, g)| g.name.as_deref() == Some("frame")).unwrap();
    let members = match &module.types[module.global_variables[frame].ty].inner {
        naga::TypeInner::Struct { members, .. } => members.clone(),
        other => panic!("frame is a {other:?}"),
    };
    fn calls(block: &naga::Block, out: &mut Vec<naga::Handle<naga::Function>>) {
        for statement in block.iter() {
            match statement {
                Statement::Call { function, .. } => out.push(*function),
                Statement::Block(b) => calls(b, out),
                Statement::If { accept, reject, .. } => {
                    calls(accept, out);
                    calls(reject, out);
                }
                Statement::Loop { body, continuing, .. } => {
                    calls(body, out);
                    calls(continuing, out);
                }
                Statement::Switch { cases, .. } => cases.iter().for_each(|c| calls(&c.body, out)),
                _ => {}
            }
        }
    }
    let mut read = std::collections::BTreeSet::new();
    let mut pending: Vec<&naga::Function> =
        module.entry_points.iter().filter(|e| e.stage == naga::ShaderStage::Fragment).map(|e| &e.function).collect();
    let mut seen = std::collections::HashSet::new();
    while let Some(function) = pending.pop() {
        for (_, expression) in function.expressions.iter() {
            let is_frame = |h: naga::Handle<Expression>| matches!(function.expressions[h], Expression::GlobalVariable(g) if g == frame);
            match *expression {
                Expression::AccessIndex { base, index } if is_frame(base) => {
                    read.insert(members[index as usize].name.clone().unwrap());
                }
                Expression::Load { pointer } if is_frame(pointer) => {
                    read.insert("*".to_owned());
                }
                _ => {}
            }
        }
        let mut called = Vec::new();
        calls(&function.body, &mut called);
        for handle in called {
            if seen.insert(handle) {
                pending.push(&module.functions[handle]);
            }
        }
    }
    read
}

/// The composite and the lighting pass take the frame's constants from their triangle as flat
/// varyings (common/frame_varyings.wgsl): on a CPU rasteriser a uniform read costs a load for
/// every eight pixels. Their pixels may read the lights (an array no varying could carry, but for
/// a loop built for one light, which takes it from the varyings: tests/it/gpu/render.rs) and,
/// in the lighting pass's reprojection of the last frame's sky, the last view and projection it
/// takes there.
#[test]
fn the_lit_passes_read_no_frame_constant_per_pixel() {
    let lights = ["first_lights", "light_count"];
    let composite = frame_members_read_per_pixel("composite.wgsl");
    assert!(composite.iter().all(|m| lights.contains(&m.as_str())), "composite reads {composite:?}");
    assert!(composite.contains("first_lights"), "the walk found no read at all: {composite:?}");
    let lighting = frame_members_read_per_pixel("lighting.wgsl");
    let reprojection = ["view_to_previous_view", "previous_projection"];
    assert!(
        lighting.iter().all(|m| lights.contains(&m.as_str()) || reprojection.contains(&m.as_str())),
        "lighting reads {lighting:?}"
    );
    // The walk itself: the march reads the frame's constants where it is.
    assert!(frame_members_read_per_pixel("march.wgsl").contains("view_to_clip"));
}
