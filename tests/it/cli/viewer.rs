//! The viewer as a person uses it: a real window under Xvfb on the software driver, keys sent with
//! xdotool (Tab into the panel, then 1-4 with F12 after each, then C, then Escape; in a second
//! window, the fly camera and the command it logs for its view). The screenshots must exist, differ by
//! mode, and match a headless `ssdo capture` of the same view: mean absolute difference at most
//! 0.5 of 255 and no channel off by more than 6 (the window encodes sRGB in the shader, the
//! capture in the texture format, so single levels differ).

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// Window size: the 3D view is this less the 300-pixel panel.
const WINDOW: (u32, u32) = (620, 300);
const VIEW: (u32, u32) = (WINDOW.0 - 300, WINDOW.1);

fn have(tool: &str) -> bool {
    Command::new("sh")
        .arg("-c")
        .arg(format!("command -v {tool}"))
        .stdout(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// Kills the child when dropped, so a failing test leaves no Xvfb or viewer behind.
struct Guard(Child);

impl Drop for Guard {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn xdotool(display: &str, args: &[&str]) -> String {
    let out = Command::new("xdotool").args(args).env("DISPLAY", display).output().expect("xdotool runs");
    String::from_utf8_lossy(&out.stdout).trim().to_owned()
}

fn wait_for(what: &str, timeout: Duration, mut done: impl FnMut() -> bool) {
    let start = Instant::now();
    while !done() {
        assert!(start.elapsed() < timeout, "timed out waiting for {what}");
        std::thread::sleep(Duration::from_millis(100));
    }
}

fn pngs(dir: &Path, prefix: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|e| {
            e.flatten()
                .map(|e| e.path())
                .filter(|p| p.file_name().is_some_and(|n| n.to_string_lossy().starts_with(prefix)))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
}

/// What the viewer started in `dir` wrote to stderr (shown when it did not end as it should).
fn log(dir: &Path) -> String {
    std::fs::read_to_string(dir.join("viewer-stderr.txt")).unwrap_or_default()
}

fn ssdo() -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_ssdo"));
    command
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("WGPU_BACKEND", std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "vulkan".into()));
    command
}

/// Xvfb on a display it picks itself (`-displayfd`: it writes the number once it accepts
/// connections), so a display left locked by an earlier run is never reused; stopped with SIGTERM
/// when dropped, so it removes its lock and socket.
fn start_xvfb() -> (Xvfb, String) {
    let mut child = Command::new("Xvfb")
        // -noreset: Xvfb otherwise resets when its last client leaves, and the second viewer
        // below can meet a server in the middle of that reset ("failed to open connection").
        .args(["-displayfd", "1", "-screen", "0", "800x600x24", "-nolisten", "tcp", "-noreset"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("Xvfb starts");
    let mut number = String::new();
    let stdout = child.stdout.take().expect("Xvfb's standard output");
    let server = Xvfb(child);
    std::io::BufRead::read_line(&mut std::io::BufReader::new(stdout), &mut number).expect("Xvfb's display number");
    let number = number.trim();
    assert!(!number.is_empty() && number.bytes().all(|b| b.is_ascii_digit()), "Xvfb wrote no display number");
    (server, format!(":{number}"))
}

/// Xvfb, stopped with SIGTERM (not `Child::kill`'s SIGKILL, which leaves its lock file behind).
struct Xvfb(Child);

impl Drop for Xvfb {
    fn drop(&mut self) {
        let stopped = Command::new("kill").arg(self.0.id().to_string()).status().is_ok_and(|s| s.success());
        if !stopped {
            let _ = self.0.kill();
        }
        let _ = self.0.wait();
    }
}

/// Starts the viewer on `display` at the test's window size, and waits for its window.
fn start_viewer(display: &str, shots: &Path, extra: &[&str]) -> (Guard, String) {
    let size = format!("{}x{}", WINDOW.0, WINDOW.1);
    let viewer = Guard(
        ssdo()
            .args(["view", "--size", &size, "--screenshot-dir", shots.to_str().unwrap()])
            .args(extra)
            .env("DISPLAY", display)
            .stdout(Stdio::null())
            .stderr(std::fs::File::create(shots.join("viewer-stderr.txt")).expect("a log file"))
            .spawn()
            .expect("the viewer starts"),
    );
    let mut window = String::new();
    wait_for("the viewer's window", Duration::from_secs(60), || {
        window = xdotool(display, &["search", "--name", "^ssdo"]).lines().next().unwrap_or("").to_owned();
        !window.is_empty()
    });
    (viewer, window)
}

#[test]
fn viewer_switches_modes_and_writes_screenshots_that_match_capture() {
    if !have("Xvfb") || !have("xdotool") {
        assert!(
            std::env::var("CI").map_or(true, |v| v != "true"),
            "CI needs Xvfb and xdotool (scripts/test.sh installs them)"
        );
        eprintln!("skipping: Xvfb or xdotool not installed");
        return;
    }
    if ssdo::gpu::Gpu::headless().is_err() {
        assert!(std::env::var("CI").map_or(true, |v| v != "true"), "{}", ssdo::gpu::NO_ADAPTER_HELP);
        return;
    }
    let (_xvfb, display) = start_xvfb();
    let shots = tempfile::tempdir().unwrap();
    let (mut viewer, window) = start_viewer(&display, shots.path(), &["--mode", "off"]);
    xdotool(&display, &["windowfocus", "--sync", &window]);
    // Tab moves egui's keyboard focus into the panel (onto a button, not a text field): the keys
    // below must still reach the view.
    xdotool(&display, &["key", "--clearmodifiers", "Tab", "Tab"]);

    let modes = ["off", "ssao", "ssdo", "both"];
    for (i, mode) in modes.iter().enumerate() {
        xdotool(&display, &["key", "--clearmodifiers", &(i + 1).to_string()]);
        xdotool(&display, &["key", "--clearmodifiers", "F12"]);
        wait_for(&format!("the {mode} screenshot"), Duration::from_secs(60), || {
            pngs(shots.path(), "screenshot-").iter().any(|p| p.to_string_lossy().ends_with(&format!("-{mode}.png")))
        });
    }
    xdotool(&display, &["key", "--clearmodifiers", "c"]);
    wait_for("the comparison", Duration::from_secs(120), || !pngs(shots.path(), "compare-").is_empty());
    xdotool(&display, &["key", "--clearmodifiers", "Escape"]);
    wait_for("the viewer to quit", Duration::from_secs(30), || viewer.0.try_wait().ok().flatten().is_some());
    assert_eq!(viewer.0.wait().unwrap().code(), Some(0), "Escape quits cleanly; its stderr:\n{}", log(shots.path()));

    // A window destroyed from outside (not closed by its user) ends the viewer cleanly too,
    // not with a panic on the next frame.
    let shots2 = tempfile::tempdir().unwrap();
    let (mut viewer, window) = start_viewer(&display, shots2.path(), &[]);
    // Once it is drawing (a screenshot proves it), not while it is still starting up.
    xdotool(&display, &["windowfocus", "--sync", &window]);
    xdotool(&display, &["key", "--clearmodifiers", "F12"]);
    wait_for("the second viewer's screenshot", Duration::from_secs(60), || {
        !pngs(shots2.path(), "screenshot-").is_empty()
    });
    // The fly camera: F, then W held for a moment and a drag to look around; F12 writes the
    // screenshot and logs the `ssdo capture` command of that view, which must render the same.
    // Each step waits for the viewer to have taken the last: the keys go to a busy window. F is
    // pressed until the viewer's log says the fly camera is on (each toggle is logged), so a
    // press that comes late or not at all is seen rather than assumed.
    let toggles = || {
        log(shots2.path()).lines().filter(|l| l.contains("fly camera o")).map(|l| l.ends_with("on")).collect::<Vec<_>>()
    };
    for attempt in 0.. {
        assert!(attempt < 4, "the fly camera did not turn on; the viewer's stderr:\n{}", log(shots2.path()));
        let before = toggles().len();
        xdotool(&display, &["key", "--clearmodifiers", "f"]);
        let start = Instant::now();
        while toggles().len() == before && start.elapsed() < Duration::from_secs(20) {
            std::thread::sleep(Duration::from_millis(100));
        }
        if toggles().last() == Some(&true) {
            break;
        }
    }
    xdotool(&display, &["keydown", "w"]);
    std::thread::sleep(Duration::from_millis(400));
    xdotool(&display, &["keyup", "w"]);
    xdotool(&display, &["mousemove", "--window", &window, "450", "150", "mousedown", "1"]);
    xdotool(&display, &["mousemove", "--window", &window, "480", "140", "mouseup", "1"]);
    xdotool(&display, &["key", "--clearmodifiers", "F12"]);
    // The flown screenshot is the one logged after the fly camera turned on, found by its log
    // line (`<path>: the same view headless: ssdo <command>`), not by counting files: on a loaded
    // machine an F12 has been seen to arrive twice (CI, 2026-12-03), which only adds a file.
    let (mut flown, mut command) = (std::path::PathBuf::new(), String::new());
    wait_for("the fly camera's screenshot and its command in the log", Duration::from_secs(60), || {
        let text = log(shots2.path());
        let after_fly = text.lines().skip_while(|l| !l.ends_with("fly camera on"));
        if let Some(line) = after_fly.filter(|l| l.contains(": the same view headless: ssdo ")).last() {
            let (head, rest) = line.split_once(": the same view headless: ssdo ").unwrap();
            flown = std::path::PathBuf::from(head.rsplit("] ").next().unwrap().trim());
            command = rest.trim().to_owned();
        }
        !command.is_empty() && flown.exists()
    });
    xdotool(&display, &["windowclose", &window]);
    wait_for("the viewer to quit after its window was destroyed", Duration::from_secs(30), || {
        viewer.0.try_wait().ok().flatten().is_some()
    });
    assert_eq!(
        viewer.0.wait().unwrap().code(),
        Some(0),
        "a destroyed window quits cleanly; its stderr:\n{}",
        log(shots2.path())
    );

    let screenshots = pngs(shots.path(), "screenshot-");
    for mode in modes {
        assert!(
            screenshots.iter().any(|p| p.to_string_lossy().ends_with(&format!("-{mode}.png"))),
            "{mode}: {screenshots:?}"
        );
    }
    let compare = image::open(&pngs(shots.path(), "compare-")[0]).unwrap();
    assert!(compare.width() > 2 * VIEW.0 && compare.height() > 2 * VIEW.1);

    let captured = tempfile::tempdir().unwrap();
    let view_size = format!("{}x{}", VIEW.0, VIEW.1);
    let status = ssdo()
        .args(["capture", "--mode", "all", "--size", &view_size, "--out", captured.path().to_str().unwrap()])
        .status()
        .unwrap();
    assert!(status.success());

    // The logged command of the flown view renders the flown screenshot.
    assert!(
        command.contains("--eye ") && command.contains("--look-at ") && !command.contains('\''),
        "{command}\nthe viewer's stderr:\n{}",
        log(shots2.path())
    );
    let flown_out = tempfile::tempdir().unwrap();
    let args: Vec<&str> = command.split_whitespace().collect();
    let status = ssdo().args(&args).args(["--out", flown_out.path().to_str().unwrap()]).status().unwrap();
    assert!(status.success(), "{command}");
    let mode = args.iter().skip_while(|a| **a != "--mode").nth(1).expect("the command names the mode");
    let shot = image::open(&flown).unwrap().to_rgb8();
    let headless = image::open(flown_out.path().join(format!("{mode}.png"))).unwrap().to_rgb8();
    let first = image::open(&pngs(shots2.path(), "screenshot-")[0]).unwrap().to_rgb8();
    assert_ne!(shot, first, "flying moved the view");
    let diffs: Vec<u8> = shot.as_raw().iter().zip(headless.as_raw()).map(|(a, b)| a.abs_diff(*b)).collect();
    let mean = diffs.iter().map(|d| *d as f64).sum::<f64>() / diffs.len() as f64;
    let max = diffs.iter().copied().max().unwrap_or(0);
    assert!(
        mean <= 0.5 && max <= 6,
        "flown view: screenshot vs its command's capture mean {mean:.3}, max {max} (as for the modes above): {command}"
    );

    let mut images = Vec::new();
    for mode in modes {
        let shot = screenshots.iter().find(|p| p.to_string_lossy().ends_with(&format!("-{mode}.png"))).unwrap();
        let shot = image::open(shot).unwrap().to_rgb8();
        let headless = image::open(captured.path().join(format!("{mode}.png"))).unwrap().to_rgb8();
        assert_eq!(shot.dimensions(), VIEW, "{mode}: the screenshot is the 3D view without the panel");
        let diffs: Vec<u8> = shot.as_raw().iter().zip(headless.as_raw()).map(|(a, b)| a.abs_diff(*b)).collect();
        let mean = diffs.iter().map(|d| *d as f64).sum::<f64>() / diffs.len() as f64;
        let max = diffs.iter().copied().max().unwrap_or(0);
        assert!(mean <= 0.5 && max <= 6, "{mode}: screenshot vs capture mean {mean:.3}, max {max}");
        images.push(shot);
    }
    for i in 0..images.len() {
        for j in i + 1..images.len() {
            assert_ne!(images[i], images[j], "{} and {} look the same", modes[i], modes[j]);
        }
    }
}

/// Presses `key` until the viewer in `dir` has logged `line` last among its "view: " lines
/// (each press is logged as the view it leads to).
fn press_until(display: &str, dir: &Path, key: &str, line: &str) {
    let last_view = || log(dir).lines().rev().find_map(|l| l.split("] view: ").nth(1).map(str::to_owned));
    let wanted = line.trim_start_matches("view: ");
    for attempt in 0.. {
        assert!(attempt < 12, "'{key}' never led to '{line}'; the viewer's stderr:\n{}", log(dir));
        if last_view().as_deref() == Some(wanted) {
            return;
        }
        let seen = log(dir).matches("] view: ").count();
        xdotool(display, &["key", "--clearmodifiers", key]);
        let start = Instant::now();
        while log(dir).matches("] view: ").count() == seen && start.elapsed() < Duration::from_secs(20) {
            std::thread::sleep(Duration::from_millis(100));
        }
    }
}

/// The rays a pixel of the truth's rounds the viewer in `dir` has logged, in order.
fn truth_rounds(dir: &Path) -> Vec<u32> {
    log(dir).lines().filter_map(|l| l.split("the truth: ").nth(1)?.split(' ').next()?.parse().ok()).collect()
}

#[test]
fn viewer_traces_the_truth_of_its_view_and_splits_two_modes_at_a_divider() {
    if !have("Xvfb") || !have("xdotool") || ssdo::gpu::Gpu::headless().is_err() {
        assert!(std::env::var("CI").map_or(true, |v| v != "true"), "CI has Xvfb, xdotool and an adapter");
        return;
    }
    let (_xvfb, display) = start_xvfb();
    let shots = tempfile::tempdir().unwrap();
    let dir = shots.path();
    let (mut viewer, window) = start_viewer(&display, dir, &["--mode", "off"]);
    xdotool(&display, &["windowfocus", "--sync", &window]);
    // G: the truth of the view, traced in rounds that double its rays. Pressed until the log
    // says the view shows it (a key sent to a window still starting can be lost).
    press_until(&display, dir, "g", "view: truth");
    wait_for("the truth's rounds", Duration::from_secs(120), || truth_rounds(dir).iter().any(|&r| r >= 8));
    // A camera that turns starts the truth anew: its rays fall back to the first round's.
    let before = truth_rounds(dir).len();
    xdotool(&display, &["mousemove", "--window", &window, "450", "150", "mousedown", "1"]);
    xdotool(&display, &["mousemove", "--window", &window, "500", "140", "mouseup", "1"]);
    wait_for("the truth traced anew after the turn", Duration::from_secs(120), || {
        truth_rounds(dir).get(before..).is_some_and(|after| after.first() == Some(&2))
    });
    // V three times: the split with the truth, with Off, then with SSAO right of the divider;
    // F12 saves what is on screen, with the command of the view in the log.
    press_until(&display, dir, "v", "view: split with SSAO");
    xdotool(&display, &["key", "--clearmodifiers", "F12"]);
    let mut command = String::new();
    wait_for("the split's screenshot and its command", Duration::from_secs(60), || {
        let text = log(dir);
        if let Some(line) = text.lines().rev().find(|l| l.contains(": the same view headless: ssdo ")) {
            command = line.split(": the same view headless: ssdo ").nth(1).unwrap().trim().to_owned();
        }
        !command.is_empty() && !pngs(dir, "screenshot-").is_empty()
    });
    // Escape while the truth traces ends the viewer at once.
    let rounds = truth_rounds(dir).len();
    press_until(&display, dir, "g", "view: truth");
    wait_for("the truth tracing again", Duration::from_secs(60), || truth_rounds(dir).len() > rounds);
    let asked = Instant::now();
    xdotool(&display, &["key", "--clearmodifiers", "Escape"]);
    wait_for("the viewer to quit", Duration::from_secs(30), || viewer.0.try_wait().ok().flatten().is_some());
    assert!(asked.elapsed() < Duration::from_secs(10), "Escape took {:?} while tracing", asked.elapsed());
    assert_eq!(viewer.0.wait().unwrap().code(), Some(0), "{}", log(dir));

    // The split screenshot: Off's own image left of the divider (the view's middle), SSAO's right.
    let out = tempfile::tempdir().unwrap();
    // The command with every mode instead of the one it names.
    let words: Vec<&str> = command.split_whitespace().collect();
    let mode_at = words.iter().position(|w| *w == "--mode").expect("the command names its mode");
    let args: Vec<&str> =
        words.iter().enumerate().filter(|(i, _)| *i != mode_at && *i != mode_at + 1).map(|(_, w)| *w).collect();
    let status = ssdo().args(&args).args(["--mode", "all", "--out", out.path().to_str().unwrap()]).status().unwrap();
    assert!(status.success(), "{command}");
    let shot = image::open(&pngs(dir, "screenshot-")[0]).unwrap().to_rgb8();
    let column = VIEW.0 / 2;
    for (mode, columns) in [("off", 0..column), ("ssao", column..VIEW.0)] {
        let own = image::open(out.path().join(format!("{mode}.png"))).unwrap().to_rgb8();
        let (shot, own) = (&shot, &own);
        let diffs: Vec<u8> = (0..VIEW.1)
            .flat_map(|y| columns.clone().map(move |x| (x, y)))
            .flat_map(|(x, y)| (0..3).map(move |c| shot.get_pixel(x, y)[c].abs_diff(own.get_pixel(x, y)[c])))
            .collect();
        let mean = diffs.iter().map(|d| *d as f64).sum::<f64>() / diffs.len() as f64;
        let max = diffs.iter().copied().max().unwrap_or(0);
        if !(mean <= 0.5 && max <= 6) {
            // Kept for a look: the screenshot, the mode's own capture and the viewer's log.
            let kept = Path::new(env!("CARGO_TARGET_TMPDIR")).join("viewer-split");
            std::fs::create_dir_all(&kept).unwrap();
            shot.save(kept.join("screenshot.png")).unwrap();
            own.save(kept.join(format!("{mode}.png"))).unwrap();
            std::fs::write(kept.join("viewer.log"), log(dir)).unwrap();
            panic!("{mode}'s side of the split: mean {mean:.3}, max {max}: {command} (images in {})", kept.display());
        }
    }
    let off = image::open(out.path().join("off.png")).unwrap().to_rgb8();
    assert_ne!(shot, off, "the right of the divider is not Off's");
}
