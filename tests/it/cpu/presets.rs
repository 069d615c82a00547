//! Preset files: they round-trip exactly, flags given beside one override it, a bad file is one
//! error naming the file and the key, and one measured elsewhere says so.

use std::path::Path;

use clap::Parser;
use ssdo::knobs::Knobs;
use ssdo::preset::{Measured, Preset, Quality};
use ssdo::render::{Mode, SenderSky, Settings, Variant};
use ssdo::spec::RenderArgs;

fn measured() -> Measured {
    Measured {
        device: "llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, llvmpipe)".into(),
        scene: "cornell".into(),
        size: (320, 240),
        lights: 8,
        budget_ms: Some(21.5),
        ms: 20.654_321_987_654_3,
        off_ms: 5.531_234_567,
        hdr_rmse: 0.020_412_345_678_9,
        do_rmse: Some(0.032_4),
        flip: 0.046_7,
        views: 3,
        frames_timed: 18,
        date: "2026-12-03 10:00 UTC".into(),
    }
}

fn preset() -> Preset {
    Preset {
        name: "ssdo cornell 320x240 within 21.5 ms".into(),
        mode: Mode::Ssdo,
        knobs: Knobs {
            variant: Variant::March,
            samples: 16,
            slices: 2,
            steps: 24,
            depth_pyramid: false,
            radius_scale: std::f32::consts::SQRT_2,
            thickness_scale: 0.3,
            reach_scale: 0.5,
            blur: false,
            half_resolution: true,
            accumulate: 8,
            sender_sky: SenderSky::Irradiance,
            far_side: true,
            far_sky: true,
            indirect_strength: 0.0,
        },
        measured: Some(measured()),
    }
}

#[test]
fn presets_round_trip_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("preset.json");
    for p in [preset(), Preset { measured: None, ..preset() }, Quality::Low.preset(), Quality::Ultra.preset()] {
        p.save(&path).unwrap();
        let back = Preset::load(&path).unwrap();
        assert_eq!(back, p);
        assert_eq!(back.to_text(), std::fs::read_to_string(&path).unwrap());
    }
    // Every f64 of the figures survives to the last bit (serde_json's float_roundtrip).
    let mut m = measured();
    for k in 1..2000u64 {
        m.off_ms = 1.0 + k as f64 * 0.000_123_456_789_012_3;
        m.ms = (k as f64).sqrt() * 3.3;
        let p = Preset { measured: Some(m.clone()), ..preset() };
        assert_eq!(Preset::parse(Path::new("p.json"), &p.to_text()).unwrap(), p, "{k}");
    }
    // The odd float survives to the last bit.
    let back = Preset::parse(Path::new("p.json"), &preset().to_text()).unwrap();
    assert_eq!(back.knobs.radius_scale.to_bits(), std::f32::consts::SQRT_2.to_bits());
    assert_eq!(back.measured.unwrap().ms.to_bits(), measured().ms.to_bits());
}

#[test]
fn a_missing_setting_keeps_its_default_and_knobs_become_the_same_settings() {
    let p = Preset::parse(Path::new("p.json"), r#"{"ssdo_preset": 1, "settings": {"slices": 4}}"#).unwrap();
    assert_eq!(p.knobs, Knobs { slices: 4, ..Knobs::default() });
    assert_eq!((p.name.as_str(), p.mode), ("p", Mode::Ssdo));
    // Points from a file bring the points' defaults for what the file leaves out.
    let p = Preset::parse(Path::new("p.json"), r#"{"ssdo_preset": 1, "settings": {"variant": "classic"}}"#).unwrap();
    assert_eq!(p.knobs.samples, Settings::classic().knobs.samples);
    assert_eq!(Settings::default().with_knobs(p.knobs).ambient, Settings::classic().ambient);
}

#[test]
fn a_bad_preset_is_one_error_naming_the_file_and_what_is_wrong() {
    let cases = [
        ("not json", "not a preset (JSON"),
        ("[1, 2]", "the file: expected an object"),
        (r#"{"settings": {}}"#, "no \"ssdo_preset\": 1"),
        (r#"{"ssdo_preset": 7}"#, "preset format 7"),
        (r#"{"ssdo_preset": 1, "setings": {}}"#, "unknown key 'setings'"),
        (r#"{"ssdo_preset": 1, "settings": {"slice": 2}}"#, "settings: unknown key 'slice'"),
        (
            r#"{"ssdo_preset": 1, "settings": {"slices": 0}}"#,
            "settings.slices: 0 is out of range; expected a whole number from 1 to 32",
        ),
        (r#"{"ssdo_preset": 1, "settings": {"steps": -3}}"#, "settings.steps: expected a whole number"),
        (r#"{"ssdo_preset": 1, "settings": {"blur": "yes"}}"#, "settings.blur: expected true or false"),
        (r#"{"ssdo_preset": 1, "settings": {"variant": "fast"}}"#, "unknown variant 'fast'"),
        (r#"{"ssdo_preset": 1, "settings": {"radius_scale": 100}}"#, "settings.radius_scale: 100 is out of range"),
        // A number is written as people write it, not as 45 digits.
        (
            r#"{"ssdo_preset": 1, "settings": {"radius_scale": 1e-45}}"#,
            "settings.radius_scale: 1e-45 is out of range; expected a finite number from 0.125 to 8",
        ),
        (r#"{"ssdo_preset": 2.5}"#, "ssdo_preset: preset format 2.5; this build reads format 1"),
        (r#"{"ssdo_preset": "1"}"#, "ssdo_preset: expected the format number 1, not \"1\""),
        // Strings are one line of a bounded length: a name that would split a CSV row or a
        // table, or that is megabytes long, is refused by its key.
        (r#"{"ssdo_preset": 1, "name": "a\n=cmd|x"}"#, "name: holds the control character \\n"),
        (
            r#"{"ssdo_preset": 1, "measured": {"device": "x\ty", "size": [1, 1]}}"#,
            "measured.device: holds the control character",
        ),
        (r#"{"ssdo_preset": 1, "mode": "sideways"}"#, "unknown mode 'sideways'"),
        (r#"{"ssdo_preset": 1, "measured": {"device": "x"}}"#, "is missing"),
    ];
    for (text, needle) in cases {
        let e = Preset::parse(Path::new("dir/p.json"), text).unwrap_err();
        let line = e.to_string();
        assert_eq!(e.exit_code(), 3, "{text}: {line}");
        assert!(line.starts_with("dir/p.json: ") && line.contains(needle), "{text}: {line}");
        assert!(!line.contains('\n'), "one line: {line}");
    }
    let long = format!(r#"{{"ssdo_preset": 1, "name": "{}"}}"#, "n".repeat(100_000));
    let line = Preset::parse(Path::new("dir/p.json"), &long).unwrap_err().to_string();
    assert!(line.contains("name: 100000 characters; at most 256 are accepted") && line.len() < 200, "{line}");
    // What editors and exporters write that is still a preset: a byte-order mark, 1.0 for 1.
    for text in ["\u{feff}{\"ssdo_preset\": 1}", r#"{"ssdo_preset": 1.0, "name": "ultra, 8 ms"}"#] {
        assert!(Preset::parse(Path::new("dir/p.json"), text).is_ok(), "{text}");
    }
    let e = Preset::load(Path::new("no/such/preset.json")).unwrap_err();
    assert!(e.to_string().starts_with("no/such/preset.json: cannot read"), "{e}");
}

#[derive(Parser)]
struct Flags {
    #[command(flatten)]
    render: RenderArgs,
}

fn settings(args: &[&str]) -> ssdo::Result<Settings> {
    let flags = Flags::try_parse_from(std::iter::once("ssdo").chain(args.iter().copied())).unwrap();
    flags.render.settings(Mode::Ssdo)
}

#[test]
fn flags_given_beside_a_preset_override_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("p.json");
    preset().save(&path).unwrap();
    let file = path.to_str().unwrap();
    let s = settings(&["--preset", file]).unwrap();
    assert_eq!(
        (
            s.knobs.slices,
            s.knobs.steps,
            s.knobs.accumulate,
            s.knobs.blur,
            s.knobs.sender_sky,
            s.knobs.indirect_strength
        ),
        (2, 24, 8, false, SenderSky::Irradiance, 0.0)
    );
    assert_eq!((s.given.radius, s.knobs.radius_scale), (None, std::f32::consts::SQRT_2));
    let s = settings(&[
        "--preset",
        file,
        "--slices",
        "3",
        "--accumulate",
        "1",
        "--sender-sky",
        "march",
        "--indirect-strength",
        "2",
        "--radius",
        "0.5",
    ])
    .unwrap();
    assert_eq!(
        (s.knobs.slices, s.knobs.steps, s.knobs.accumulate, s.knobs.sender_sky, s.knobs.indirect_strength),
        (3, 24, 1, SenderSky::March, 2.0)
    );
    // An explicit radius wins over the preset's scale.
    assert_eq!(s.lengths(0.1).radius, 0.5);
    // Another variant than the preset's brings its own sample count.
    let s = settings(&["--preset", file, "--variant", "classic"]).unwrap();
    assert_eq!((s.knobs.variant, s.knobs.samples), (Variant::Classic, Settings::classic().knobs.samples));
    // No preset, no flags: the defaults; a level is its knobs; high is the default.
    assert_eq!(settings(&[]).unwrap(), Settings { mode: Mode::Ssdo, ..Settings::default() });
    assert_eq!(settings(&["--quality", "high"]).unwrap(), settings(&[]).unwrap());
    let low = settings(&["--quality", "low", "--no-blur"]).unwrap();
    assert_eq!(low.knobs, Knobs { blur: false, ..Quality::Low.knobs() });
    // A preset's flags are checked as the command line's are.
    let e = settings(&["--preset", file, "--steps", "0"]).unwrap_err();
    assert!(e.to_string().contains("--steps 0"), "{e}");
    assert!(Flags::try_parse_from(["ssdo", "--preset", file, "--quality", "low"]).is_err());
}

#[test]
fn a_preset_measured_elsewhere_says_so() {
    let p = preset();
    let here = &p.measured.as_ref().unwrap().device.clone();
    assert_eq!(p.elsewhere(here, (320, 240)), None);
    let w = p.elsewhere("NVIDIA H200 (Vulkan)", (320, 240)).unwrap();
    assert!(w.contains("measured on llvmpipe") && w.contains("(this run: NVIDIA H200 (Vulkan))"), "{w}");
    let w = p.elsewhere(here, (800, 600)).unwrap();
    assert!(w.contains("at 320x240 (this run: 800x600)"), "{w}");
    // A level carries no figures, so nothing to warn about.
    assert_eq!(Quality::Low.preset().elsewhere("anything", (1, 1)), None);
}

#[test]
fn quality_levels_are_named_and_high_is_the_default() {
    assert_eq!(Quality::High.knobs(), Knobs::default());
    for q in Quality::ALL {
        assert_eq!(q.name().parse::<Quality>().unwrap(), q);
        q.knobs().check().unwrap();
    }
    assert!("best".parse::<Quality>().unwrap_err().to_string().contains("low, medium, high, ultra"));
}
