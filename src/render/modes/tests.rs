//! The plans every option makes: their steps, reads, writes and targets, against the rules and
//! against the tables of ARCHITECTURE.md and `mod.rs`.

use super::*;

/// Every plan the options can make.
fn all_plans() -> Vec<Plan> {
    let mut plans = Vec::new();
    for mode in Mode::ALL {
        for lights in [0, 8] {
            for bits in 0..64u32 {
                for sender_sky in SenderSky::ALL {
                    let [blur, pyramid, display, indirect, accumulate, half] =
                        [0, 1, 2, 3, 4, 5].map(|b| bits & (1 << b) != 0);
                    let o = PlanOptions { blur, pyramid, display, indirect, sender_sky, half, accumulate };
                    plans.push(Plan::new(mode, SceneFeatures { lights }, o));
                }
            }
        }
    }
    plans
}

#[test]
fn every_read_is_written_by_an_earlier_step_and_the_targets_are_what_the_steps_write() {
    for plan in all_plans() {
        let io = plan.io();
        for (i, (step, step_io)) in io.iter().enumerate() {
            // A history is read before it is written: what it holds is the last frame's.
            for read in step_io.reads.iter().filter(|t| !t.persistent()) {
                let earlier = io[..i].iter().any(|(_, e)| e.writes.contains(read));
                assert!(earlier, "{:?}: {step:?} reads {} before any step writes it", plan.steps, read.name());
            }
        }
        assert!(plan.writes(TargetId::Output), "{:?}: nothing reaches the output", plan.steps);
        // The set by hand, as the plan's rules say it.
        let sampled = plan.decl.runs_sampling();
        let t = plan.target_set();
        assert_eq!(t.hdr, plan.keeps_hdr(), "{:?}", plan.steps);
        assert_eq!(t.bounce, plan.has(Step::Lighting));
        assert_eq!(
            (t.ao, t.directional),
            (sampled && !plan.decl.directional_occlusion, plan.decl.directional_occlusion)
        );
        assert_eq!(t.blurred, plan.blur);
        assert_eq!(t.accumulated, plan.accumulates());
        assert_eq!(t.half, plan.half());
        assert_eq!(plan.half(), sampled && plan.has(Step::Upsample));
        assert_eq!(plan.accumulates(), sampled && plan.has(Step::Temporal));
        assert_eq!(plan.history.len(), if plan.accumulates() { 2 } else { 0 }, "{:?}", plan.steps);
        assert_eq!((t.pyramid, t.sender_sky), (plan.has(Step::DepthPyramid), plan.has(Step::SenderSky)));
    }
}

#[test]
fn the_architecture_pages_mode_table_is_what_the_plans_are() {
    let page = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/ARCHITECTURE.md")).unwrap();
    let lit = SceneFeatures { lights: 8 };
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
            .filter(|t| !t.in_gbuffer() && !t.persistent() && *t != TargetId::Output)
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
    let lit = SceneFeatures { lights: 8 };
    // (mode, steps, (hdr, bounce, ao, directional))
    let rows = [
        (Mode::Off, "gbuffer, composite, light_cubes", (false, false, false, false)),
        (Mode::Ssao, "gbuffer, ssao, upsample, blur, temporal, composite, light_cubes", (false, false, true, false)),
        (
            Mode::Ssdo,
            "gbuffer, sender_sky, lighting, ssdo, upsample, blur, temporal, composite, light_cubes",
            (true, true, false, true),
        ),
        (
            Mode::Both,
            "gbuffer, sender_sky, lighting, ssao_ssdo, upsample, blur, temporal, composite, light_cubes",
            (true, true, false, true),
        ),
    ];
    for (mode, steps, targets) in rows {
        let plan = Plan::new(mode, lit, PlanOptions::default());
        assert_eq!(plan.step_names().join(", "), steps, "{mode}");
        let t = plan.target_set();
        assert_eq!((t.hdr, t.bounce, t.ao, t.directional), targets, "{mode}");
        assert_eq!((t.blurred, t.pyramid), (plan.decl.runs_sampling(), false), "{mode}");
    }
}

#[test]
fn a_display_plan_has_no_skybox_or_tonemap_pass_and_keeps_hdr_only_for_the_lighting_pass() {
    let lit = SceneFeatures { lights: 8 };
    for mode in Mode::ALL {
        let hdr = Plan::new(mode, lit, PlanOptions { display: false, ..PlanOptions::default() });
        let display = Plan::new(mode, lit, PlanOptions::default());
        assert!(hdr.has(Step::Skybox) && hdr.has(Step::Tonemap) && hdr.keeps_hdr());
        assert!(!display.has(Step::Skybox) && !display.has(Step::Tonemap));
        assert_eq!(display.keeps_hdr(), display.has(Step::Lighting), "{mode}");
        let without = |p: &Plan| p.steps.iter().filter(|s| !matches!(s, Step::Skybox | Step::Tonemap)).count();
        assert_eq!(without(&hdr), display.steps.len(), "{mode}: the same passes otherwise");
    }
    let dark = Plan::new(Mode::Ssdo, SceneFeatures { lights: 0 }, PlanOptions::default());
    assert!(dark.has(Step::Lighting), "under a sky alone the senders' sky light is bounced");
    assert!(!dark.keeps_hdr(), "no lights: the lighting pass writes the bounce alone, no HDR target");
}

#[test]
fn the_lighting_pass_runs_where_there_is_light_to_bounce_and_nowhere_else() {
    // (mode, lights, indirect, sender sky) -> lighting pass, bounce target, light cubes
    let (march, irradiance, off) = (SenderSky::March, SenderSky::Irradiance, SenderSky::Off);
    let rows = [
        (Mode::Ssdo, 0, true, march, (true, true, false)),
        (Mode::Both, 0, true, irradiance, (true, true, false)),
        (Mode::Ssdo, 0, true, off, (false, false, false)),
        (Mode::Ssdo, 8, true, off, (true, true, true)),
        (Mode::Ssdo, 8, false, march, (false, false, true)),
        (Mode::Ssdo, 0, false, irradiance, (false, false, false)),
        (Mode::Off, 8, true, march, (false, false, true)),
        (Mode::Ssao, 0, true, march, (false, false, false)),
    ];
    for (mode, lights, indirect, sender_sky, want) in rows {
        let o = PlanOptions { indirect, sender_sky, ..PlanOptions::default() };
        let plan = Plan::new(mode, SceneFeatures { lights }, o);
        let got = (plan.has(Step::Lighting), plan.target_set().bounce, plan.has(Step::LightCubes));
        assert_eq!(got, want, "{mode}, {lights} lights, indirect {indirect}, sender sky {sender_sky:?}");
        // Without a lighting pass that writes it, the composite runs the light loop itself.
        assert_eq!(plan.light_loop(), lights > 0 && !plan.has(Step::Lighting));
        assert_eq!(plan.lighting_writes_direct(), plan.has(Step::Lighting) && lights > 0);
        // The senders' own march runs exactly where a lighting pass reads it.
        let marched = plan.has(Step::Lighting) && sender_sky == march;
        assert_eq!((plan.has(Step::SenderSky), plan.target_set().sender_sky), (marched, marched));
    }
}
