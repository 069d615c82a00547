//! The `ssdo` binary as a user runs it: files written atomically, one-line errors with
//! documented exit codes, never a panic (exit 101).

use crate::common;

use std::path::Path;
use std::process::Command;

use common::{error_line, has_adapter, refused, run_ssdo as ssdo, stderr};

#[test]
fn capture_writes_the_png_and_no_temporary_files() {
    let Some(out) = common::folder_if_adapter() else { return };
    let result =
        ssdo(&["capture", "--mode", "off", "--size", "161x97", "--out", out.path().to_str().unwrap(), "--print-plan"]);
    assert!(result.status.success(), "{}", stderr(&result));
    let stdout = String::from_utf8_lossy(&result.stdout);
    // A capture without --raw or --stats tone-maps in the composite: no skybox, tonemap or HDR.
    assert!(stdout.contains("pass gbuffer") && stdout.contains("pass composite"), "{stdout}");
    assert!(!stdout.contains("pass tonemap") && !stdout.contains("hdr_color"), "{stdout}");
    let files = common::file_names(out.path());
    assert_eq!(files, vec!["off.png".to_string()]);
    let image = image::open(out.path().join("off.png")).unwrap();
    assert_eq!((image.width(), image.height()), (161, 97));
}

#[test]
fn bad_inputs_are_one_line_with_their_exit_code() {
    let out = tempfile::tempdir().unwrap();
    let out = out.path().to_str().unwrap();
    let broken = tempfile::tempdir().unwrap();
    std::fs::write(broken.path().join("bad.obj"), "v 1 2 zz\nf 1 2 3\n").unwrap();
    let bad_obj = broken.path().join("bad.obj");
    let cases: Vec<(Vec<&str>, i32, &str)> = vec![
        (vec!["capture", "--model", "no/such/model.obj", "--out", out], 3, "no/such/model.obj"),
        (vec!["capture", "--model", bad_obj.to_str().unwrap(), "--out", out], 3, "bad.obj: malformed OBJ"),
        (vec!["capture", "--skybox", "no/such/sky", "--out", out], 3, "no/such/sky: skybox not found"),
        (vec!["capture", "--exposure", "NaN", "--out", out], 2, "--exposure"),
        (vec!["capture", "--distance", "-1", "--out", out], 2, "--distance"),
    ];
    for (args, code, needle) in cases {
        let result = ssdo(&args);
        let line = error_line(&result);
        assert_eq!(result.status.code(), Some(code), "{args:?}: {}", stderr(&result));
        assert!(line.contains(needle), "{args:?}: '{line}'");
    }
    assert!(std::fs::read_dir(out).unwrap().next().is_none(), "nothing written on error");
}

#[test]
fn usage_errors_come_from_the_parser() {
    for args in [vec!["capture", "--mode", "sideways"], vec!["capture", "--size", "12by4"]] {
        let result = ssdo(&args);
        assert_eq!(result.status.code(), Some(2), "{args:?}");
        assert!(stderr(&result).contains(args[2]), "{}", stderr(&result));
    }
}

#[test]
fn zero_and_oversized_sizes_are_refused() {
    let Some(out) = common::folder_if_adapter() else { return };
    for size in ["0x10", "100000x10"] {
        let result = ssdo(&["capture", "--size", size, "--out", out.path().to_str().unwrap()]);
        assert_eq!(result.status.code(), Some(2), "{size}: {}", stderr(&result));
        assert!(error_line(&result).contains("size"), "{}", stderr(&result));
    }
    assert!(!Path::new(out.path()).join("off.png").exists());
}

#[test]
fn capture_all_writes_four_modes_and_the_comparison() {
    let Some(out) = common::folder_if_adapter() else { return };
    let result =
        ssdo(&["capture", "--mode", "all", "--size", "96x72", "--samples", "8", "--out", out.path().to_str().unwrap()]);
    assert!(result.status.success(), "{}", stderr(&result));
    let files = common::file_names(out.path());
    assert_eq!(files, ["both.png", "compare.png", "off.png", "ssao.png", "ssdo.png"]);
    let compare = image::open(out.path().join("compare.png")).unwrap();
    assert!(compare.width() > 2 * 96 && compare.height() > 2 * 72, "a 2x2 grid with captions");
    let off = image::open(out.path().join("off.png")).unwrap().to_rgb8();
    let ssdo_img = image::open(out.path().join("ssdo.png")).unwrap().to_rgb8();
    assert_ne!(off, ssdo_img, "the modes differ");
}

#[test]
fn bench_json_has_every_mode_and_pass() {
    if !has_adapter() {
        return;
    }
    let result = ssdo(&["bench", "--size", "64x48", "--frames", "2", "--samples", "8", "--json"]);
    assert!(result.status.success(), "{}", stderr(&result));
    let json: serde_json::Value = serde_json::from_slice(&result.stdout).expect("stdout is JSON");
    assert!(json["device"].is_string());
    for mode in ["off", "ssao", "ssdo", "both"] {
        let m = &json["modes"][mode];
        assert!(m["frame_ms"].as_f64().is_some_and(|ms| ms > 0.0), "{mode}: {m}");
        if json["timing"] == "timestamp" {
            assert!(m["passes"]["gbuffer"].as_f64().is_some(), "{mode}: {m}");
            // The split adds up to the passes: the sampling passes, the denoise passes, the rest.
            let sum = |v: &serde_json::Value| v.as_object().unwrap().values().filter_map(|x| x.as_f64()).sum::<f64>();
            let split = &m["split"];
            let parts = ["sampling", "denoise", "rest"].map(|k| split[k].as_f64().expect("every role"));
            assert!((parts.iter().sum::<f64>() - sum(&m["passes"])).abs() < 1e-6, "{mode}: {m}");
            assert!(parts[2] >= m["passes"]["gbuffer"].as_f64().unwrap(), "{mode}: the G-buffer is in the rest: {m}");
            let denoise = m["passes"]["blur"].as_f64().unwrap_or(0.0)
                + m["passes"]["upsample"].as_f64().unwrap_or(0.0)
                + m["passes"]["temporal"].as_f64().unwrap_or(0.0);
            assert!((parts[1] - denoise).abs() < 1e-6, "{mode}: denoise is blur + upsample + temporal: {m}");
            if mode == "off" {
                assert!(parts[0] == 0.0 && split["denoise_over_sampling"].is_null(), "{m}");
            } else {
                let ratio = split["denoise_over_sampling"].as_f64().expect("a sampled mode has the ratio");
                assert!((ratio - parts[1] / parts[0]).abs() < 1e-9, "{mode}: {m}");
            }
        }
    }
    assert!(json["modes"]["both"]["passes"].get("ssao_ssdo").is_some() || json["timing"] != "timestamp");
    assert!(json["ratios"]["ssdo_over_ssao"].as_f64().is_some());
    assert_eq!(json["orbit_deg"], 0.0, "a still camera by default");
    // --orbit: the camera turns every frame, and the report says so; past half a turn is refused.
    let turning = ssdo(&["bench", "--size", "32x24", "--frames", "2", "--orbit", "-1.5", "--json"]);
    assert!(turning.status.success(), "{}", stderr(&turning));
    let json: serde_json::Value = serde_json::from_slice(&turning.stdout).expect("stdout is JSON");
    assert_eq!(json["orbit_deg"], -1.5);
    let table = ssdo(&["bench", "--size", "32x24", "--frames", "2", "--orbit", "1"]);
    assert!(String::from_utf8_lossy(&table.stdout).contains("the camera turning 1° a frame"), "{}", stderr(&table));
    crate::common::refused(&["bench", "--orbit", "200"], 2, "--orbit 200: must be a finite number from -180 to 180");
}

#[test]
fn the_room_benches_on_both_paths_and_its_flags_are_checked() {
    for (args, needle) in [
        (vec!["bench", "--scene", "cellar"], "cellar"),
        (vec!["bench", "--triangles", "5000"], "--triangles 5000"),
        (vec!["bench", "--scene", "room", "--triangles", "0"], "--triangles 0"),
        (
            vec!["bench", "--scene", "room", "--model", "models/cornell/cornell.obj", "--triangles", "10"],
            "--triangles 10",
        ),
    ] {
        let result = ssdo(&args);
        assert_eq!(result.status.code(), Some(2), "{args:?}: {}", stderr(&result));
        assert!(stderr(&result).contains(needle), "{args:?}: {}", stderr(&result));
    }
    if !has_adapter() {
        return;
    }
    let room = ["bench", "--scene", "room", "--triangles", "2000", "--lights", "1", "--size", "64x48", "--frames", "1"];
    let passes = |extra: &[&str]| {
        let result = ssdo(&[&room[..], &["--json", "--variant", "classic"], extra].concat());
        assert!(result.status.success(), "{extra:?}: {}", stderr(&result));
        let json: serde_json::Value = serde_json::from_slice(&result.stdout).expect("stdout is JSON");
        json["modes"]["ssao"]["passes"].as_object().cloned().unwrap_or_default()
    };
    let (display, hdr) = (passes(&[]), passes(&["--hdr"]));
    // Without timestamp queries there are no per-pass times to look at.
    if !display.is_empty() {
        assert!(display.contains_key("composite") && !display.contains_key("tonemap"), "{display:?}");
        assert!(hdr.contains_key("tonemap") && hdr.contains_key("skybox"), "{hdr:?}");
    }
}

/// The report's scenes are scenes of every command: captured as the report frames them, open
/// under its own red-blue sky; a named scene takes no model file.
#[test]
fn the_reports_scenes_capture_as_the_report_sees_them() {
    refused(
        &["capture", "--scene", "fence", "--model", "models/cornell/cornell.obj"],
        2,
        "--model models/cornell/cornell.obj: --scene fence builds its own model",
    );
    let Some(out) = common::folder_if_adapter() else { return };
    for scene in ["crevices", "fence", "open", "stairs"] {
        let dir = out.path().join(scene);
        let args = ["capture", "--scene", scene, "--mode", "ssdo", "--size", "64x48", "--far-side"];
        let result = ssdo(&[&args[..], &["--out", dir.to_str().unwrap()]].concat());
        assert!(result.status.success(), "{scene}: {}", stderr(&result));
        assert!(dir.join("ssdo.png").is_file(), "{scene}");
    }
    // Open's sky is red below the horizon: the background below the floor is red.
    let image = image::open(out.path().join("open/ssdo.png")).unwrap().to_rgb8();
    let below = image.get_pixel(32, 47).0;
    assert!(below[0] > 2 * below[2], "open's sky below the floor is red: {below:?}");
}

#[test]
fn viewer_refuses_bad_input_before_opening_a_window() {
    let result = ssdo(&["view", "--model", "no/such/model.obj"]);
    assert_eq!(result.status.code(), Some(3), "{}", stderr(&result));
    assert!(error_line(&result).contains("no/such/model.obj"), "{}", stderr(&result));
    let result = ssdo(&["view", "--size", "0x100"]);
    assert_eq!(result.status.code(), Some(2), "{}", stderr(&result));
}

#[test]
fn stats_json_reports_every_linear_buffer_and_raw_writes_exr() {
    let Some(out) = common::folder_if_adapter() else { return };
    let result = ssdo(&[
        "capture",
        "--mode",
        "both",
        "--size",
        "48x36",
        "--stats",
        "--json",
        "--raw",
        "--out",
        out.path().to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", stderr(&result));
    let json: serde_json::Value = serde_json::from_slice(&result.stdout).expect("stdout is only JSON");
    for buffer in ["ao", "do_direct", "do_indirect", "hdr"] {
        let b = &json["both"][buffer];
        assert_eq!(b["non_finite"], 0, "{buffer}: {b}");
        assert!(b["max"].as_f64().unwrap() >= b["min"].as_f64().unwrap(), "{buffer}: {b}");
    }
    let exr = image::open(out.path().join("both.exr")).expect("a readable EXR").to_rgba32f();
    assert_eq!(exr.dimensions(), (48, 36));
    assert!(exr.pixels().all(|p| p.0.iter().all(|c| c.is_finite())));
    let hdr_max = json["both"]["hdr"]["max"].as_f64().unwrap() as f32;
    let exr_max = exr.pixels().flat_map(|p| p.0[..3].to_vec()).fold(0.0f32, f32::max);
    assert!((exr_max - hdr_max).abs() <= 1e-3 * hdr_max, "EXR holds the same radiance: {exr_max} vs {hdr_max}");
}

#[test]
fn every_error_is_one_line_in_one_form() {
    // The parser's own errors too, and a newline in a file name does not split the line.
    let result = ssdo(&["capture", "--mode", "sideways"]);
    assert_eq!(result.status.code(), Some(2));
    assert!(error_line(&result).contains("sideways"), "{}", stderr(&result));
    let result = ssdo(&["capture", "--model", "no/such\nmodel.obj"]);
    assert_eq!(result.status.code(), Some(3));
    let errors: Vec<&str> =
        std::str::from_utf8(&result.stderr).unwrap().lines().filter(|l| l.contains("error")).collect();
    assert_eq!(errors.len(), 1, "{errors:?}");
    assert!(errors[0].starts_with("ssdo: error:") && errors[0].contains("no/such\\nmodel.obj"), "{errors:?}");
}

#[test]
fn capture_all_writes_everything_or_nothing_and_sweeps_stale_temporaries() {
    let Some(out) = common::folder_if_adapter() else { return };
    let dir = out.path().to_str().unwrap();
    // compare.png cannot be written (a folder has its name): not one of the five files lands.
    std::fs::create_dir(out.path().join("compare.png")).unwrap();
    // A temporary file a killed run left behind (no process has this id), and a user's file
    // whose name merely looks like one: only the first is swept.
    std::fs::write(out.path().join(".ssdo-tmp.4000000.0123456789abcdef.off.png"), b"half").unwrap();
    std::fs::write(out.path().join(".off.png.4000000.tmp"), b"mine").unwrap();
    let result = ssdo(&["capture", "--mode", "all", "--size", "48x36", "--out", dir]);
    assert_eq!(result.status.code(), Some(5), "{}", stderr(&result));
    assert!(error_line(&result).contains("compare.png"), "{}", stderr(&result));
    let left = common::file_names(out.path());
    assert_eq!(
        left,
        vec![".off.png.4000000.tmp".to_string(), "compare.png".to_string()],
        "nothing else written, the stale temporary gone, the user's file kept"
    );
}

#[test]
fn the_viewer_without_a_display_says_so_as_a_setting() {
    let result = Command::new(env!("CARGO_BIN_EXE_ssdo"))
        .args(["view", "--size", "64x48"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    assert_eq!(result.status.code(), Some(2), "{}", stderr(&result));
    assert!(error_line(&result).contains("needs a display"), "{}", stderr(&result));
}

#[test]
fn special_and_huge_files_are_refused_before_they_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe.obj");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let sparse = dir.path().join("sparse.obj");
    std::fs::File::create(&sparse).unwrap().set_len(2 << 30).unwrap();
    for (model, needle) in [
        ("/dev/zero", "/dev/zero: is a device, not a regular file"),
        (fifo.to_str().unwrap(), "pipe.obj: is a FIFO (a named pipe), not a regular file"),
        (sparse.to_str().unwrap(), "sparse.obj: is 2048 MiB; files over 1024 MiB are refused"),
        (dir.path().to_str().unwrap(), "is a folder, not a file"),
    ] {
        // Refused from the file's type and size, before any read (reading the FIFO would hang).
        let result = ssdo(&["capture", "--model", model, "--out", dir.path().join("out").to_str().unwrap()]);
        assert_eq!(result.status.code(), Some(3), "{model}: {}", stderr(&result));
        assert!(error_line(&result).contains(needle), "{model}: {}", stderr(&result));
    }
}

#[test]
fn a_window_no_adapter_could_draw_is_refused_before_it_opens() {
    let result = ssdo(&["view", "--size", "65536x100"]);
    assert_eq!(result.status.code(), Some(2), "{}", stderr(&result));
    assert!(error_line(&result).contains("at most 16384"), "{}", stderr(&result));
}

#[test]
fn a_camera_said_as_an_orbit_or_as_an_eye_and_a_point_gives_one_picture() {
    if !has_adapter() {
        return;
    }
    // Bad camera points are refused in refusals.txt.
    let dir = tempfile::tempdir().unwrap();
    let shoot = |name: &str, camera: &[&str]| {
        let out = dir.path().join(name);
        let mut args = vec!["capture", "--mode", "ssao", "--size", "64x48", "--accumulate", "1"];
        args.extend(camera);
        args.extend(["--out", out.to_str().unwrap()]);
        let result = common::run_ssdo(&args);
        assert!(result.status.success(), "{}", common::stderr(&result));
        image::open(out.join("ssao.png")).unwrap().to_rgb8()
    };
    let orbit =
        shoot("orbit", &["--target", "0,0.5,0", "--yaw", "0", "--pitch", "0", "--distance", "5", "--near", "0.005"]);
    let fly = shoot("fly", &["--eye", "0,0.5,5", "--look-at", "0,0.5,0", "--near", "0.005"]);
    assert_eq!(orbit, fly);
    let moved =
        shoot("moved", &["--target", "0.5,0.5,0", "--yaw", "0", "--pitch", "0", "--distance", "5", "--near", "0.005"]);
    assert_ne!(orbit, moved, "--target moves the view");
}

#[test]
fn tune_names_the_cheapest_under_a_budget_below_it_and_its_preset_drives_capture() {
    let Some(dir) = common::folder_if_adapter() else { return };
    let out = dir.path().join("tune");
    let small = ["--size", "32x24", "--lights", "1", "--views", "1", "--frames", "1", "--spp", "2"];
    let mut args = vec!["tune", "--budget-ms", "0.0001", "--max-settings", "3", "--out", out.to_str().unwrap()];
    args.extend(small);
    let line = refused(&args, 2, "is below every setting measured: the cheapest is ");
    assert!(line.contains(" ms"), "{line}");
    assert!(out.join("front.csv").exists() && !out.join("preset.json").exists(), "the front, and no preset");
    // A budget no setting reaches is not binding: the most accurate is picked and written.
    let mut args = vec!["tune", "--budget-ms", "1e9", "--max-settings", "3", "--out", out.to_str().unwrap()];
    args.extend(small);
    let result = ssdo(&args);
    assert_eq!(result.status.code(), Some(0), "{}", stderr(&result));
    let printed = String::from_utf8_lossy(&result.stdout);
    assert!(printed.contains("is not binding") && printed.contains("render the pick: ssdo capture"), "{printed}");
    // The preset renders through capture, with a warning at another size than it was tuned at.
    let preset = out.join("preset.json");
    let shots = dir.path().join("shots");
    let result = ssdo(&[
        "capture",
        "--mode",
        "ssdo",
        "--size",
        "40x30",
        "--lights",
        "1",
        "--preset",
        preset.to_str().unwrap(),
        "--out",
        shots.to_str().unwrap(),
    ]);
    assert_eq!(result.status.code(), Some(0), "{}", stderr(&result));
    assert!(stderr(&result).contains("at 32x24 (this run: 40x30)"), "{}", stderr(&result));
    assert!(shots.join("ssdo.png").exists());
}

#[test]
fn a_bad_preset_is_one_line_and_exit_3_everywhere() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.json");
    std::fs::write(&bad, r#"{"ssdo_preset": 1, "settings": {"slices": 99}}"#).unwrap();
    let bad = bad.to_str().unwrap();
    let out = dir.path().join("out");
    for command in ["capture", "bench", "report", "view"] {
        let mut args = vec![command, "--preset", bad];
        if command != "view" {
            args.extend(["--out", out.to_str().unwrap()].iter().take(if command == "bench" { 0 } else { 2 }));
        }
        let line = refused(&args, 3, "bad.json: settings.slices: 99 is out of range");
        assert!(!line.contains('\n'));
    }
    refused(&["capture", "--preset", "no/such.json"], 3, "no/such.json: cannot read");
    refused(&["capture", "--quality", "best"], 2, "best");
    refused(&["tune", "--out", out.to_str().unwrap()], 2, "give --budget-ms");
    assert!(!out.exists(), "nothing written on error");
}

/// From another folder the binary reads the repository's own model and skies (beside the
/// sources it was built from), not their built-in stand-ins: the same files, the same figures;
/// the report's `open` scene, whose sky is a folder, runs there too.
#[test]
fn a_run_from_another_folder_reads_the_repositorys_files() {
    let Some(out) = common::folder_if_adapter() else { return };
    let run = |args: &[&str]| common::run_ssdo_in(out.path(), args);
    let result = run(&["capture", "--mode", "off", "--size", "32x24", "--out", "shots"]);
    assert!(result.status.success(), "{}", stderr(&result));
    assert!(!stderr(&result).contains("built-in"), "{}", stderr(&result));
    assert!(out.path().join("shots/off.png").is_file());
    let small = ["--size", "16x12", "--samples", "4", "--march", "1x4", "--spp", "2", "--frames", "1"];
    let result = run(&[&["report", "--scene", "open", "--accumulate", "1", "--out", "r"], &small[..]].concat());
    assert!(result.status.success(), "{}", stderr(&result));
    assert!(out.path().join("r/report.md").is_file());
}
