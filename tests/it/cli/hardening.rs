//! Hostile use of the binary and its files: a closed pipe and a full disk on standard output,
//! counts with no sensible upper limit, values that look like flags, models of other kinds or
//! of scales and offsets 32-bit floats cannot shade, and concurrent runs into one folder.

use crate::common;

use std::path::Path;
use std::process::Command;

use common::{error_line, has_adapter, refused, run_ssdo as ssdo, stderr};

/// The binary with `args`, on the test's backend, standard output going to `stdout`.
fn ssdo_into(args: &[&str], stdout: std::process::Stdio) -> std::process::Child {
    Command::new(env!("CARGO_BIN_EXE_ssdo"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("WGPU_BACKEND", std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "vulkan".into()))
        .stdout(stdout)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the binary runs")
}

#[test]
fn a_closed_pipe_ends_quietly_and_a_full_disk_is_one_error_line() {
    let Some(out) = common::folder_if_adapter() else { return };
    let dir = out.path().to_str().unwrap();
    let args = ["capture", "--mode", "all", "--size", "16x12", "--stats", "--print-plan", "--out", dir];
    // `| head -1` with the reader gone before the first line: SIGPIPE's status, nothing said.
    let mut child = ssdo_into(&args, std::process::Stdio::piped());
    drop(child.stdout.take());
    let result = child.wait_with_output().unwrap();
    assert_eq!(result.status.code(), Some(141), "{}", stderr(&result));
    assert!(!stderr(&result).contains("panicked") && error_line(&result).is_empty(), "{}", stderr(&result));
    // Standard output on a full device: one line naming it, and the output kind's exit code.
    if Path::new("/dev/full").exists() {
        let full = std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
        let result = ssdo_into(&args, full.into()).wait_with_output().unwrap();
        assert_eq!(result.status.code(), Some(5), "{}", stderr(&result));
        let line = error_line(&result);
        assert!(line.contains("standard output") && line.contains("No space left"), "{}", stderr(&result));
    }
}

/// Every case of `refusals.txt`: the command line exits 2 with one error line that says why.
#[test]
fn every_refused_command_line_says_why_in_one_line() {
    let cases = include_str!("refusals.txt").lines().filter(|l| !l.trim().is_empty() && !l.starts_with('#'));
    let mut count = 0;
    for case in cases {
        let (args, needle) = case.split_once(" => ").unwrap_or_else(|| panic!("no ' => ' in '{case}'"));
        let result = ssdo(&args.split_whitespace().collect::<Vec<_>>());
        assert_eq!(result.status.code(), Some(2), "{case}: {}", stderr(&result));
        assert!(error_line(&result).contains(needle), "{case}: {}", stderr(&result));
        assert_eq!(stderr(&result).lines().filter(|l| l.starts_with("ssdo: error:")).count(), 1, "{case}");
        count += 1;
    }
    assert!(count >= 40, "{count} cases read");
}

#[test]
fn the_memory_budget_is_refused_before_the_work() {
    // The budget's own values are in refusals.txt. Targets are sized from the plan before a device or a model is touched.
    let args = ["capture", "--size", "16384x16384", "--mode", "off", "--memory-budget", "1G"];
    let line = refused(&args, 2, "16384x16384 in Off would need");
    assert!(line.contains("render targets"), "{line}");
    // A model: one polygon of two million corners is refused by name from a stream of its file.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("polygon.obj");
    let corners: Vec<&str> = ["1", "2", "3", "4", "5", "6"].iter().copied().cycle().take(2_000_000).collect();
    let text = format!("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\nv 0 0 1\nv 1 0 1\nf {}\n", corners.join(" "));
    std::fs::write(&path, text).unwrap();
    let args = ["capture", "--model", path.to_str().unwrap(), "--memory-budget", "512M", "--mode", "off"];
    refused(&args, 3, "polygon.obj: 1999998 triangles would need");
    // Materials: each costs its GPU objects and draws whatever its maps' few texels (a hundred
    // thousand of them outgrew every budget), counted before any map is read.
    let mut mtl = String::new();
    let mut obj = String::from("mtllib many.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\n");
    for i in 0..2000 {
        mtl.push_str(&format!("newmtl m{i}\nKd 0.5 0.5 0.5\nmap_Bump n{i}.png\n"));
        obj.push_str(&format!("usemtl m{i}\nf 1 3 2\n"));
    }
    std::fs::write(dir.path().join("many.mtl"), mtl).unwrap();
    std::fs::write(dir.path().join("many.obj"), obj).unwrap();
    let path = dir.path().join("many.obj");
    let args = ["capture", "--model", path.to_str().unwrap(), "--memory-budget", "64M", "--mode", "off"];
    let line = refused(&args, 3, "many.obj: 2001 materials with 2000 distinct maps would need");
    assert!(line.contains("memory budget for textures"), "{line}");
    // The image plan halves the largest first in steps of a heap: a hundred thousand pictures
    // planned into almost nothing end at 1x1 each (this took minutes as a scan a halving).
    let fitted = ssdo::budget::fit_images(&vec![(64, 64); 100_000], 0);
    assert!(fitted.iter().all(|&s| s == (1, 1)));
}

#[test]
fn other_model_kinds_say_so() {
    // A known kind of model that does not load (STL) is named as such, not read as an OBJ with
    // "no triangles"; a glTF is read as glTF (this one holds nothing to draw).
    let dir = tempfile::tempdir().unwrap();
    for (name, needle) in
        [("part.stl", "STL file; models load from OBJ"), ("scene.gltf", "no triangles"), ("scene.GLB", "no triangles")]
    {
        let path = dir.path().join(name);
        std::fs::write(&path, b"{\"asset\":{\"version\":\"2.0\"}}").unwrap();
        let result = ssdo(&["capture", "--model", path.to_str().unwrap()]);
        assert_eq!(result.status.code(), Some(3), "{name}: {}", stderr(&result));
        let line = error_line(&result);
        assert!(line.contains(name) && line.contains(needle), "{name}: {line}");
    }
}

#[test]
fn concurrent_batches_into_one_folder_each_land_whole() {
    // Six writers commit five files each into one folder at the same moment, round after round;
    // after every round the five files must come from one writer's batch, never a mix of two.
    let out = tempfile::tempdir().unwrap();
    let names = ["off.png", "ssao.png", "ssdo.png", "both.png", "compare.png"];
    let writers = 6;
    let barrier = std::sync::Barrier::new(writers);
    let mixed = std::sync::atomic::AtomicUsize::new(0);
    std::thread::scope(|scope| {
        for writer in 0..writers as u8 {
            let (dir, barrier, mixed) = (out.path().to_path_buf(), &barrier, &mixed);
            scope.spawn(move || {
                for round in 0..30u8 {
                    let mut batch = ssdo::output::Batch::default();
                    for name in names {
                        batch.stage(&dir.join(name), &[writer, round]).unwrap();
                    }
                    barrier.wait();
                    batch.commit().unwrap();
                    barrier.wait();
                    if writer == 0 {
                        let contents: Vec<Vec<u8>> =
                            names.iter().map(|n| std::fs::read(dir.join(n)).unwrap()).collect();
                        if contents.iter().any(|c| *c != contents[0]) {
                            mixed.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        }
                    }
                    barrier.wait();
                }
            });
        }
    });
    assert_eq!(mixed.into_inner(), 0, "rounds whose five files came from different batches");
    let left = common::file_names(out.path());
    assert_eq!(left.len(), names.len(), "no temporary or lock left: {left:?}");
}

#[test]
fn models_outside_what_f32_shades_are_rescaled_rebased_or_refused() {
    let Some(dir) = common::folder_if_adapter() else { return };
    let quad = |name: &str, offset: f64, size: f64| {
        let path = dir.path().join(name);
        let v = |x: f64, y: f64| format!("v {} {} 0\n", offset + x * size, y * size);
        std::fs::write(
            &path,
            [v(0.0, 0.0), v(1.0, 0.0), v(0.0, 1.0), v(1.0, 1.0), "f 1 2 4\nf 1 4 3\n".into()].concat(),
        )
        .unwrap();
        path
    };
    // 1e-20 across (its own coordinates, not --scale) and 1e4 from the origin: warned about,
    // fitted, and every linear buffer of every mode finite.
    for (path, warning) in [(quad("tiny.obj", 0.0, 1e-20), "scaled by"), (quad("offset.obj", 1e4, 1.0), "moved by")] {
        let out = dir.path().join("out");
        let args = ["capture", "--model", path.to_str().unwrap(), "--mode", "all", "--size", "32x24", "--stats"];
        let result = ssdo(&[&args[..], &["--out", out.to_str().unwrap()]].concat());
        assert!(result.status.success(), "{}", stderr(&result));
        assert!(stderr(&result).contains(warning), "{path:?}: {}", stderr(&result));
        let stdout = String::from_utf8_lossy(&result.stdout);
        let rows: Vec<&str> = stdout.lines().filter(|l| l.contains("non_finite")).collect();
        assert!(!rows.is_empty() && rows.iter().all(|l| l.ends_with("non_finite 0")), "{path:?}: {stdout}");
    }
    // A unit quad 1e9 from the origin has lost its shape in 32-bit positions: refused, by name.
    let far = quad("far.obj", 1e9, 1.0);
    let result = ssdo(&["capture", "--model", far.to_str().unwrap(), "--size", "32x24"]);
    assert_eq!(result.status.code(), Some(3), "{}", stderr(&result));
    assert!(error_line(&result).contains("far.obj") && error_line(&result).contains("nearer the origin"));
}

#[test]
fn the_command_line_refuses_far_cameras_bad_budgets_and_bad_folders_before_the_work() {
    // A negative budget is a value with a message, not an unknown flag.
    refused(&["capture", "--memory-budget", "-1"], 2, "'-1' is not a size");
    // Camera points far from the model leave f32 nothing to draw with: refused with the range.
    for flag in ["--target", "--eye"] {
        let mut args = vec!["capture", flag, "3e8,0,0", "--size", "16x12"];
        if flag == "--eye" {
            args.extend(["--look-at", "0,0,0"]);
        }
        let line = refused(&args, 2, "must lie within");
        assert!(line.contains("of the model's centre") && line.contains(flag), "{line}");
    }
    // An output folder that is a dangling link: refused before anything is loaded or rendered.
    #[cfg(unix)]
    {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        std::os::unix::fs::symlink(dir.path().join("gone"), &out).unwrap();
        let result = ssdo(&["capture", "--size", "16x12", "--out", out.to_str().unwrap()]);
        assert_eq!(result.status.code(), Some(5), "{}", stderr(&result));
        assert!(error_line(&result).contains("which does not exist"), "{}", stderr(&result));
        assert!(!stderr(&result).contains("adapter:"), "the run opened a device first: {}", stderr(&result));
    }
    // A panorama given as the model says what it is.
    let dir = tempfile::tempdir().unwrap();
    let sky = dir.path().join("sky.hdr");
    std::fs::write(&sky, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n").unwrap();
    refused(&["capture", "--model", sky.to_str().unwrap()], 3, "an image, not a model");
}

#[test]
fn a_stale_or_foreign_lock_is_taken_over_at_once_with_a_line() {
    if !has_adapter() {
        return;
    }
    // An empty lock (a writer killed between creating it and writing its pid), and one naming
    // pid 1 (alive, but no run of this program): each taken over at once, with a line saying so.
    for (contents, needle) in [("", "an empty or garbled lock"), ("1", "pid 1 is no run of ssdo")] {
        let out = tempfile::tempdir().unwrap();
        let lock = out.path().join(".ssdo-tmp.lock");
        std::fs::write(&lock, contents).unwrap();
        let old = std::time::SystemTime::now() - std::time::Duration::from_secs(60);
        std::fs::File::options().write(true).open(&lock).unwrap().set_modified(old).unwrap();
        let result = ssdo(&["capture", "--mode", "off", "--size", "16x12", "--out", out.path().to_str().unwrap()]);
        assert!(result.status.success(), "{}", stderr(&result));
        assert!(stderr(&result).contains(needle), "{}", stderr(&result));
        assert!(out.path().join("off.png").is_file());
        assert!(!lock.exists(), "the lock was left behind");
    }
}

#[test]
fn a_preset_that_is_a_device_and_a_model_cut_away_whole_are_each_said_in_a_line() {
    // /dev/zero was read to 4 GB before "out of memory".
    if Path::new("/dev/zero").exists() {
        refused(
            &["capture", "--preset", "/dev/zero", "--mode", "off"],
            3,
            "/dev/zero: is a device, not a regular file",
        );
    }
    if !has_adapter() {
        return;
    }
    // A quad whose map_d is alpha 0 everywhere drew the sky alone with nothing said.
    let dir = tempfile::tempdir().unwrap();
    image::RgbaImage::from_pixel(4, 4, image::Rgba([200, 200, 200, 0])).save(dir.path().join("clear.png")).unwrap();
    std::fs::write(dir.path().join("q.mtl"), "newmtl glass\nmap_Kd clear.png\nmap_d clear.png\n").unwrap();
    let quad = "v -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 1 0\n";
    std::fs::write(dir.path().join("q.obj"), format!("mtllib q.mtl\n{quad}usemtl glass\nf 1/1/1 2/2/1 3/3/1 4/4/1\n"))
        .unwrap();
    let model = dir.path().join("q.obj");
    let out = dir.path().join("out");
    let args = [
        "capture",
        "--model",
        model.to_str().unwrap(),
        "--size",
        "16x12",
        "--mode",
        "off",
        "--out",
        out.to_str().unwrap(),
    ];
    let result = ssdo(&args);
    assert_eq!(result.status.code(), Some(0), "{}", stderr(&result));
    let said = stderr(&result);
    assert!(said.contains("nothing of the model is left to draw") && said.contains("'glass'"), "{said}");
}
