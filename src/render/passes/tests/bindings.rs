//! Each pass's declared reads against the bind group its WGSL declares, in every plan.

use super::*;

/// Group 1's bindings as `shader` declares them: (binding, kind); each shader parsed once.
fn shader_group(shader: &'static str) -> Vec<(u32, Kind)> {
    type Parsed = Vec<(&'static str, Vec<(u32, Kind)>)>;
    static PARSED: std::sync::Mutex<Parsed> = std::sync::Mutex::new(Vec::new());
    let mut parsed = PARSED.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, group)) = parsed.iter().find(|(name, _)| *name == shader) {
        return group.clone();
    }
    let group = parse_group(shader);
    parsed.push((shader, group.clone()));
    group
}

fn parse_group(shader: &str) -> Vec<(u32, Kind)> {
    use naga::{AddressSpace, ImageClass, ScalarKind, TypeInner};
    let source = crate::shaders::resolve(shader).unwrap();
    let module = naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{shader}: {e}"));
    module
        .global_variables
        .iter()
        .filter_map(|(_, var)| {
            let binding = var.binding.as_ref().filter(|b| b.group == 1)?;
            let kind = match (&module.types[var.ty].inner, var.space) {
                (_, AddressSpace::Uniform) => Kind::Uniform,
                (TypeInner::Image { class: ImageClass::Sampled { kind: ScalarKind::Uint, .. }, .. }, _) => Kind::Uint,
                (TypeInner::Image { .. }, _) => Kind::Float,
                (other, space) => panic!("{shader}: binding {} is {other:?} in {space:?}", binding.binding),
            };
            Some((binding.binding, kind))
        })
        .collect()
}

/// Whether `io`'s reads are what `entry`'s shaders bind in group 1: each binding a shader
/// declares is the read of its number, of the same kind, and each read is bound by one of them.
fn declared_as_bound(entry: &Entry, io: &PassIo) -> std::result::Result<(), String> {
    let declared = io.kinds();
    let mut used = vec![false; declared.len()];
    for shader in entry.group_shaders {
        for (binding, kind) in shader_group(shader) {
            match declared.get(binding as usize) {
                Some(d) if *d == kind => used[binding as usize] = true,
                other => {
                    return Err(format!(
                        "{}: {shader} binds {binding} as {kind:?}; the pass declares {other:?} there ({declared:?})",
                        entry.step.name()
                    ))
                }
            }
        }
    }
    match used.iter().position(|u| !u) {
        Some(unbound) => Err(format!(
            "{}: declares read {unbound} ({:?}), which none of {:?} binds",
            entry.step.name(),
            io.reads[unbound],
            entry.group_shaders
        )),
        None => Ok(()),
    }
}

#[test]
fn every_pass_declares_what_its_shader_binds_in_every_plan() {
    let mut checked = 0;
    for plan in all_plans() {
        for entry in PASSES.iter().filter(|e| plan.has(e.step)) {
            let io = (entry.io)(&plan);
            if io.reads.is_empty() {
                continue;
            }
            declared_as_bound(entry, &io).unwrap_or_else(|e| panic!("{:?}: {e}", plan.step_names()));
            checked += 1;
        }
    }
    assert!(checked > 1000, "{checked} declarations checked");
}

#[test]
fn a_declaration_that_drops_a_read_fails_the_checks() {
    // The sampling pass of SSDO with lights reads the bounce; a list without it is caught, both
    // against the shader and by the plan (the bounce would be written and never read).
    let plan = Plan::new(Mode::Ssdo, SceneFeatures::lit(8), PlanOptions::default());
    let entry = PASSES.iter().find(|e| e.step == Step::SAMPLING).unwrap();
    let mut io = (entry.io)(&plan);
    declared_as_bound(entry, &io).unwrap();
    io.reads.retain(|r| *r != Read::Target(BOUNCE));
    let error = declared_as_bound(entry, &io).unwrap_err();
    assert!(error.contains(".wgsl binds"), "{error}");
    // A list that reads what no earlier step writes (the temporal pass of a DO plan reading AO)
    // fails the plan's check.
    let mut io = plan.io();
    let temporal = io.iter_mut().find(|(s, _)| *s == Step::TEMPORAL).unwrap();
    temporal.1.reads.retain(|t| *t != Stage::Half.target(true));
    temporal.1.reads.push(Stage::Half.target(false));
    let error = reads_are_written_first(&io).unwrap_err();
    assert!(error.contains("temporal reads ao_half"), "{error}");
}
