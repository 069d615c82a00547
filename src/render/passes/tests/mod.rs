//! The plans every option makes: their steps, reads, writes and targets, against the rules and
//! against the tables of ARCHITECTURE.md and `modes/mod.rs`.

use super::*;
use crate::render::graph::io::{Kind, Read};
use crate::render::modes::{MODES, SURFACE_HISTORY};
use crate::render::targets::{Stage, BOUNCE, BOUNCE_WITH_FAR, HDR, OUTPUT};
use crate::render::SenderSky;
use depth_pyramid::PYRAMID;
use sampling::LAST_SKY;
use sender_sky::{SENDER_SKY, SENDER_SKY_QUARTER};

// Each pass's declared reads against what its WGSL binds.
mod bindings;

/// The old set of flags, read from the plan's targets.
struct Set {
    hdr: bool,
    bounce: bool,
    ao: bool,
    directional: bool,
    blurred: bool,
    accumulated: bool,
    half: bool,
    pyramid: bool,
    sender_sky: bool,
}

fn set(plan: &Plan) -> Set {
    let has = |id| plan.allocates(id);
    Set {
        hdr: has(HDR),
        bounce: has(BOUNCE) || has(BOUNCE_WITH_FAR),
        // What the sampling pass writes: at full size, or at half size with an upsample after it.
        ao: [Stage::Raw, Stage::Half].into_iter().any(|s| has(s.target(false))),
        directional: [Stage::Raw, Stage::Half].into_iter().any(|s| has(s.target(true))),
        blurred: [Stage::Blurred, Stage::HalfBlurred].into_iter().flat_map(Stage::targets).any(has),
        accumulated: [Stage::Accumulated, Stage::HalfAccumulated].into_iter().flat_map(Stage::targets).any(has),
        half: Stage::Half.targets().into_iter().any(has),
        pyramid: has(PYRAMID),
        // At half or at quarter size, never both.
        sender_sky: has(SENDER_SKY) || has(SENDER_SKY_QUARTER),
    }
}

/// Every plan the options can make.
fn all_plans() -> Vec<Plan> {
    let mut plans = Vec::new();
    for mode in Mode::ALL {
        for lights in [0, 8] {
            for bits in 0..512u32 {
                for sender_sky in SenderSky::ALL {
                    // Every switch both ways over the default (its material thickness on).
                    let mut o = PlanOptions { sender_sky, ..PlanOptions::default() };
                    [
                        o.blur,
                        o.pyramid,
                        o.display,
                        o.indirect,
                        o.accumulate,
                        o.half_resolution,
                        o.bilateral,
                        o.far_side,
                        o.far_sky,
                    ] = [0, 1, 2, 3, 4, 5, 6, 7, 8].map(|b| bits & (1 << b) != 0);
                    plans.push(Plan::new(mode, SceneFeatures::lit(lights), o));
                }
            }
        }
    }
    plans
}

/// Whether every step reads only what an earlier step wrote (a history excepted: what it holds
/// is the last frame's).
fn reads_are_written_first(io: &[(Step, StepIo)]) -> std::result::Result<(), String> {
    for (i, (step, step_io)) in io.iter().enumerate() {
        for read in step_io.reads.iter().filter(|t| !t.persistent()) {
            if !io[..i].iter().any(|(_, e)| e.writes.contains(read)) {
                return Err(format!("{} reads {} before any step writes it", step.name(), read.name()));
            }
        }
    }
    Ok(())
}

#[test]
fn every_read_is_written_by_an_earlier_step_and_the_targets_are_what_the_steps_write() {
    for plan in all_plans() {
        reads_are_written_first(&plan.io()).unwrap_or_else(|e| panic!("{:?}: {e}", plan.step_names()));
        assert!(plan.writes(OUTPUT), "{:?}: nothing reaches the output", plan.steps);
        // The set by hand, as the plan's rules say it.
        let (sampled, half) = (plan.decl.runs_sampling(), plan.half_resolution);
        let t = set(&plan);
        assert_eq!(t.hdr, plan.keeps_hdr(), "{:?}", plan.steps);
        assert_eq!(t.bounce, plan.has(Step::LIGHTING));
        assert_eq!(
            (t.ao, t.directional),
            (sampled && !plan.decl.directional_occlusion, plan.decl.directional_occlusion)
        );
        // A blurred target where a blur pass runs; none where the temporal pass blurs as it reads.
        assert_eq!(t.blurred, plan.has(Step::BLUR));
        assert_eq!(plan.blur, plan.has(Step::BLUR) || plan.temporal_blurs, "{:?}", plan.steps);
        assert_eq!(plan.temporal_blurs, plan.blur && half && plan.accumulates() && !plan.has(Step::BLUR));
        assert_eq!(t.accumulated, plan.accumulates());
        assert_eq!(t.half, half);
        // The composite upsamples a half-size chain as it reads it; an upsample pass makes a
        // full-size copy only for an HDR plan's readers (the debug views, the report).
        assert_eq!(plan.has(Step::UPSAMPLE), half && !plan.display);
        // The average over frames lives where the samples are.
        let half_average = Stage::HalfAccumulated.targets().into_iter().any(|t| plan.allocates(t));
        assert_eq!(half_average, half && plan.accumulates(), "{:?}", plan.steps);
        assert_eq!(plan.accumulates(), sampled && plan.has(Step::TEMPORAL));
        // After the temporal pass at half size the composite reads the samples' surfaces from
        // the surface history that pass has just written.
        let guided = half && plan.accumulates();
        assert_eq!(Step::COMPOSITE.io(&plan).reads.contains(&SURFACE_HISTORY), guided, "{:?}", plan.steps);
        // The temporal pass's two; the senders' sky for the next frame where the plan keeps it.
        let last_sky = plan.sender_sky == SenderSky::LastFrame;
        let kept = 2 * usize::from(plan.accumulates()) + usize::from(last_sky);
        assert_eq!(plan.history.len(), kept, "{:?}", plan.steps);
        assert_eq!(Step::SAMPLING.io(&plan).writes.contains(&LAST_SKY), last_sky);
        assert_eq!(Step::LIGHTING.io(&plan).reads.contains(&LAST_SKY), last_sky);
        assert_eq!((t.pyramid, t.sender_sky), (plan.has(Step::DEPTH_PYRAMID), plan.has(Step::SENDER_SKY)));
        let quarter = plan.sender_sky == SenderSky::MarchQuarter;
        assert!(!plan.allocates(SENDER_SKY) || !quarter, "{:?}", plan.steps);
        assert!(!plan.allocates(SENDER_SKY_QUARTER) || quarter, "{:?}", plan.steps);
        // With the far side (and no thickness given) the lighting pass writes the depth with each
        // surface's extent, and the march reads it in place of the thickness layer.
        let extent = crate::render::passes::far_side::EXTENT_LAYER;
        assert_eq!(plan.extent_layer, plan.has(Step::FAR_SIDE), "{:?}", plan.steps);
        assert_eq!(Step::LIGHTING.io(&plan).writes.contains(&extent), plan.extent_layer);
        assert_eq!(Step::SAMPLING.io(&plan).reads.contains(&extent), plan.extent_layer);
        // The far side's sky: its own march, where asked for and the senders take the sky at all
        // (then the far side is drawn with no point lights too), read by the lighting pass.
        let far_sky = plan.has(Step::FAR_SKY);
        assert!(!far_sky || plan.has(Step::FAR_SIDE), "{:?}", plan.steps);
        assert_eq!(Step::LIGHTING.io(&plan).reads.contains(&super::far_sky::FAR_SKY), far_sky);
    }
}

#[test]
fn the_architecture_pages_mode_table_is_what_the_plans_are() {
    let page = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/ARCHITECTURE.md")).unwrap();
    let lit = SceneFeatures::lit(8);
    let mut previous: Option<Vec<String>> = None;
    let mut rows = 0;
    for line in page.lines().filter(|l| l.starts_with("| ")) {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let Some(mode) = MODES.iter().find(|d| d.title == cells[1]).map(|d| d.mode) else { continue };
        let plan = Plan::new(mode, lit, PlanOptions::default());
        assert_eq!(cells[2].replace(" → ", ", "), plan.step_names().join(", "), "{mode}: steps");
        let mut named: Vec<String> = cells[3].split('`').skip(1).step_by(2).map(String::from).collect();
        if cells[3].starts_with("as ") {
            named = previous.clone().expect("'as' names an earlier row");
        }
        let mut written: Vec<String> = plan
            .io()
            .iter()
            .flat_map(|(_, io)| io.writes.clone())
            .filter(|t| !t.in_gbuffer() && !t.persistent() && *t != OUTPUT)
            .map(|t| t.name().to_string())
            .collect();
        written.sort();
        written.dedup();
        let mut sorted = named.clone();
        sorted.sort();
        assert_eq!(sorted, written, "{mode}: targets besides the G-buffer");
        previous = Some(named);
        rows += 1;
    }
    assert_eq!(rows, MODES.len(), "one row a mode in ARCHITECTURE.md");
}

#[test]
fn every_mode_has_one_row_with_its_own_key_and_names() {
    for (i, d) in MODES.iter().enumerate() {
        assert_eq!(Mode::ALL[i], d.mode);
        assert_eq!(Mode::from_key(d.key), Some(d.mode));
        assert_eq!(d.name.parse::<Mode>().unwrap(), d.mode);
        assert_eq!(d.mode.declaration(), d);
    }
    let err = "ssdo2".parse::<Mode>().unwrap_err().to_string();
    assert!(err.contains("expected off, ssao, ssdo, both"), "{err}");
    assert_eq!(Mode::sampled().collect::<Vec<_>>(), [Mode::Ssao, Mode::Ssdo, Mode::Both]);
    assert_eq!(Mode::from_key(0), None);
}

#[test]
fn the_table_at_the_top_of_this_file_is_what_the_plans_are() {
    let lit = SceneFeatures::lit(8);
    // (mode, steps, (hdr, bounce, ao, directional))
    let rows = [
        (Mode::Off, "gbuffer, composite, light_cubes", (false, false, false, false)),
        (Mode::Ssao, "gbuffer, ssao, temporal, composite, light_cubes", (false, false, true, false)),
        (
            Mode::Ssdo,
            "gbuffer, sender_sky, lighting, ssdo, temporal, composite, light_cubes",
            (true, true, false, true),
        ),
        (
            Mode::Both,
            "gbuffer, sender_sky, lighting, ssao_ssdo, temporal, composite, light_cubes",
            (true, true, false, true),
        ),
    ];
    for (mode, steps, targets) in rows {
        let plan = Plan::new(mode, lit, PlanOptions::default());
        assert_eq!(plan.step_names().join(", "), steps, "{mode}");
        let t = set(&plan);
        assert_eq!((t.hdr, t.bounce, t.ao, t.directional), targets, "{mode}");
        // The temporal pass blurs as it reads the samples: no blurred target.
        assert_eq!((t.blurred, t.pyramid), (false, false), "{mode}");
        assert_eq!(plan.temporal_blurs, plan.decl.runs_sampling(), "{mode}");
    }
}

#[test]
fn a_display_plan_has_no_skybox_or_tonemap_pass_and_keeps_hdr_only_for_the_lighting_pass() {
    let lit = SceneFeatures::lit(8);
    for mode in Mode::ALL {
        let hdr = Plan::new(mode, lit, PlanOptions { display: false, ..PlanOptions::default() });
        let display = Plan::new(mode, lit, PlanOptions::default());
        assert!(hdr.has(Step::SKYBOX) && hdr.has(Step::TONEMAP) && hdr.keeps_hdr());
        assert!(!display.has(Step::SKYBOX) && !display.has(Step::TONEMAP));
        assert_eq!(display.keeps_hdr(), display.has(Step::LIGHTING), "{mode}");
        // ... nor the upsample's full-size copy of the half-size chain, which only the HDR
        // plan's readers (the debug views, the report) read.
        let hdr_only = |s: &Step| matches!(*s, Step::SKYBOX | Step::TONEMAP | Step::UPSAMPLE);
        let without = |p: &Plan| p.steps.iter().filter(|s| !hdr_only(s)).count();
        assert_eq!(without(&hdr), display.steps.len(), "{mode}: the same passes otherwise");
        assert!(!display.has(Step::UPSAMPLE), "{mode}");
    }
    let dark = Plan::new(Mode::Ssdo, SceneFeatures::lit(0), PlanOptions::default());
    assert!(dark.has(Step::LIGHTING), "under a sky alone the senders' sky light is bounced");
    assert!(!dark.keeps_hdr(), "no lights: the lighting pass writes the bounce alone, no HDR target");
}

#[test]
fn the_lighting_pass_runs_where_there_is_light_to_bounce_and_nowhere_else() {
    // (mode, lights, indirect, sender sky) -> lighting pass, bounce target, light cubes
    let (march, irradiance, off) = (SenderSky::March, SenderSky::Irradiance, SenderSky::Off);
    let rows = [
        (Mode::Ssdo, 0, true, march, (true, true, false)),
        (Mode::Both, 0, true, irradiance, (true, true, false)),
        (Mode::Ssdo, 0, true, SenderSky::LastFrame, (true, true, false)),
        (Mode::Ssdo, 0, true, off, (false, false, false)),
        (Mode::Ssdo, 8, true, off, (true, true, true)),
        (Mode::Ssdo, 8, false, march, (false, false, true)),
        (Mode::Ssdo, 0, false, irradiance, (false, false, false)),
        (Mode::Off, 8, true, march, (false, false, true)),
        (Mode::Ssao, 0, true, march, (false, false, false)),
    ];
    for (mode, lights, indirect, sender_sky, want) in rows {
        let o = PlanOptions { indirect, sender_sky, ..PlanOptions::default() };
        let plan = Plan::new(mode, SceneFeatures::lit(lights), o);
        let got = (plan.has(Step::LIGHTING), set(&plan).bounce, plan.has(Step::LIGHT_CUBES));
        assert_eq!(got, want, "{mode}, {lights} lights, indirect {indirect}, sender sky {sender_sky:?}");
        // Without a lighting pass that writes it, the composite runs the light loop itself.
        assert_eq!(plan.light_loop(), lights > 0 && !plan.has(Step::LIGHTING));
        assert_eq!(plan.lighting_writes_direct(), plan.has(Step::LIGHTING) && lights > 0);
        // The senders' own march runs exactly where a lighting pass reads it.
        let marched = plan.has(Step::LIGHTING) && sender_sky.marches();
        assert_eq!((plan.has(Step::SENDER_SKY), set(&plan).sender_sky), (marched, marched));
    }
}

/// `bench`'s split follows the data: in every plan the other sampling passes come before the
/// sampling pass and feed it (directly, or through the lighting pass's bounce), a denoise pass reads what a sampling or denoise pass wrote (it
/// cleans samples, not the G-buffer alone), and a plan without a sampling pass has neither.
#[test]
fn each_pass_role_is_what_its_reads_and_writes_make_it() {
    for plan in all_plans() {
        let io = plan.io();
        let mut chain: Vec<TargetId> = Vec::new();
        let mut seen_sampling = false;
        // What the sampling pass reads, directly or through the steps before it.
        let mut feeds_sampling = Step::SAMPLING.io(&plan).reads;
        for (_, step_io) in io.iter().rev().skip_while(|(s, _)| *s != Step::SAMPLING).skip(1) {
            if step_io.writes.iter().any(|w| feeds_sampling.contains(w)) {
                feeds_sampling.extend(&step_io.reads);
            }
        }
        for (step, step_io) in &io {
            match role(*step) {
                Role::Sampling => {
                    assert!(plan.has(Step::SAMPLING), "{}: {} in a plan without sampling", plan.mode, step.name());
                    if *step != Step::SAMPLING {
                        assert!(
                            !seen_sampling && step_io.writes.iter().any(|w| feeds_sampling.contains(w)),
                            "{}: {} does not feed the sampling pass",
                            plan.mode,
                            step.name()
                        );
                    }
                    seen_sampling |= *step == Step::SAMPLING;
                    chain.extend(&step_io.writes);
                }
                Role::Denoise => {
                    assert!(seen_sampling, "{}: {} before the sampling pass", plan.mode, step.name());
                    assert!(
                        step_io.reads.iter().any(|r| chain.contains(r)),
                        "{}: {} reads no samples: {:?}",
                        plan.mode,
                        step.name(),
                        step_io.reads
                    );
                    chain.extend(&step_io.writes);
                }
                Role::Rest => {}
            }
        }
    }
    assert_eq!(
        PASSES.iter().filter(|e| e.role == Role::Denoise).map(|e| e.step.name()).collect::<Vec<_>>(),
        ["blur", "temporal", "upsample"]
    );
}
