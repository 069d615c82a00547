//! The `ssdo` command line: a thin layer over the library. Errors print one line
//! (`ssdo: error: <file or setting>: <problem>`) and exit with the code of their kind
//! (see `Error::exit_code` and the README).

use std::process::ExitCode;
use std::time::Instant;

use ssdo::gpu::Gpu;
use ssdo::headless::bench::BenchReport;
use ssdo::headless::capture::{capture_converged, output_texture, CAPTURE_FORMAT};
use ssdo::render::{Mode, Renderer};
use ssdo::{compare, output, Error, Result};

mod cli;

use cli::*;

fn run_report(args: &ReportArgs) -> Result<()> {
    use ssdo::render::{ACCUMULATE, SAMPLES, SLICES, STEPS};
    for &n in &args.samples {
        SAMPLES.check(n)?;
    }
    for &n in &args.accumulate {
        ACCUMULATE.check(n)?;
    }
    ssdo::spec::in_range("orbit", args.orbit, -90.0, 90.0)?;
    for &(slices, steps) in &args.march {
        SLICES.check(slices)?;
        STEPS.check(steps)?;
    }
    if args.samples.is_empty() || args.radius.is_empty() || args.march.is_empty() || args.accumulate.is_empty() {
        return Err(Error::Setting("--samples, --march, --radius and --accumulate must each give at least one".into()));
    }
    let lists = [
        ("samples", args.samples.len()),
        ("march", args.march.len()),
        ("radius", args.radius.len()),
        ("accumulate", args.accumulate.len()),
    ];
    for (name, count) in lists {
        if count > MAX_SWEEP {
            return Err(Error::Setting(format!("--{name}: {count} values; a sweep takes at most {MAX_SWEEP}")));
        }
    }
    let options = ssdo::report::ReportOptions {
        scene: args.scene.clone(),
        model: args.model.clone(),
        skybox: args.skybox.clone(),
        size: (args.size.0, args.size.1),
        samples: args.samples.clone(),
        march: args.march.clone(),
        radii: args.radius.clone(),
        samples_per_pixel: args.spp,
        frames: args.frames,
        accumulate: args.accumulate.clone(),
        orbit: args.orbit,
        lights: args.lights,
        seed: args.seed,
        out: args.out.clone(),
    };
    output::check_folder(&args.out)?;
    let gpu = Gpu::headless()?;
    let started = Instant::now();
    let rows = args.size.1 as u64;
    let radii = args.radius.len() as u64;
    let configs = ssdo::report::planned_configurations(&options) as u64;
    let (w, h) = (args.size.0 as u64, args.size.1 as u64);
    log::info!(
        "planned: {configs} configurations × {} timed frames (and up to {} more where a row accumulates) at {w}x{h}, \
         and a truth of 2 × {} rays over {} pixels per radius",
        args.frames + 2,
        2 * args.accumulate.iter().max().copied().unwrap_or(1),
        args.spp,
        w * h
    );
    let bar = indicatif::ProgressBar::new(2 * rows * radii + configs);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} {msg}")
            .expect("valid template"),
    );
    let progress = |message: &str| {
        bar.inc(1);
        if message != "reference row" {
            bar.set_message(message.to_owned());
        }
    };
    let report = ssdo::report::run(&gpu, &options, &progress)?;
    bar.finish_and_clear();
    report.write(&options)?;
    output::print_line(&report.markdown(&options))?;
    output::print_line(&format!(
        "wrote {0}/report.csv, {0}/report.md, {0}/report.png in {1:.0} s",
        args.out.display(),
        started.elapsed().as_secs_f64()
    ))
}

/// Runs `work`, showing a spinner with the elapsed time on standard error once it has taken a
/// second (a 2M-triangle model takes several); nothing when standard error is not a terminal.
fn with_spinner<T>(message: &str, work: impl FnOnce() -> T) -> T {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Arc;
    let done = Arc::new(AtomicBool::new(false));
    let bar = indicatif::ProgressBar::hidden();
    let watcher = {
        let (done, bar, message) = (done.clone(), bar.clone(), message.to_owned());
        std::thread::spawn(move || {
            for _ in 0..20 {
                std::thread::sleep(std::time::Duration::from_millis(50));
                if done.load(Ordering::Relaxed) {
                    return;
                }
            }
            bar.set_draw_target(indicatif::ProgressDrawTarget::stderr());
            bar.set_style(
                indicatif::ProgressStyle::with_template("{spinner} {msg} ({elapsed})").expect("valid template"),
            );
            bar.set_message(message);
            bar.enable_steady_tick(std::time::Duration::from_millis(120));
        })
    };
    let out = work();
    done.store(true, std::sync::atomic::Ordering::Relaxed);
    let _ = watcher.join();
    bar.finish_and_clear();
    out
}

fn run_capture(args: &CaptureArgs) -> Result<()> {
    let modes: Vec<Mode> = match args.mode {
        ModeChoice::One(mode) => vec![mode],
        ModeChoice::All => Mode::ALL.to_vec(),
    };
    let settings = args.render.settings(modes[0])?;
    let (size, features) = ((args.size.0, args.size.1), ssdo::render::SceneFeatures { lights: args.scene.lights });
    Renderer::check_memory(size, &settings, features, args.raw || args.stats, &modes)?;
    output::check_folder(&args.out)?;
    let (scene, sky) = load_scene(&args.scene)?;
    let camera = args.scene.camera(&scene)?;
    let gpu = Gpu::headless()?;
    gpu.check_size(size.0, size.1)?;
    let mut renderer = Renderer::new(&gpu, &scene, &sky, size, CAPTURE_FORMAT, settings)?;
    // --raw and --stats read the linear HDR image back; otherwise the frame tone-maps in place.
    renderer.keep_hdr(&gpu, args.raw || args.stats);
    let mut panels = Vec::new();
    let mut stats_json = serde_json::Map::new();
    // Every file of the run lands together, or none does; leftovers of killed runs go first.
    output::remove_stale_temporaries(&args.out);
    let mut batch = output::Batch::default();
    // With --json, standard output is the JSON document alone.
    let say = |line: String| -> Result<()> {
        if args.json {
            log::info!("{line}");
            Ok(())
        } else {
            output::print_line(&line)
        }
    };
    for mode in modes {
        renderer.set_mode(&gpu, mode);
        if args.print_plan {
            print_plan(&renderer)?;
        }
        if args.stats {
            let stats = ssdo::headless::stats::frame_stats(&gpu, &mut renderer, &camera)?;
            if args.json {
                let buffers: serde_json::Map<String, serde_json::Value> =
                    stats.iter().map(|s| (s.name.to_string(), s.json())).collect();
                stats_json.insert(mode.name().to_string(), serde_json::Value::Object(buffers));
            } else {
                for s in &stats {
                    output::print_line(&format!(
                        "{mode:>5} {:<12} min {:>12.5e} max {:>12.5e} mean {:>12.5e} non_finite {}",
                        s.name, s.min, s.max, s.mean, s.non_finite
                    ))?;
                }
            }
        }
        let started = Instant::now();
        let image = capture_converged(&gpu, &mut renderer, &camera)?;
        let path = args.out.join(format!("{}.png", mode.name()));
        batch.stage(&path, &output::png_bytes(&path, &image)?)?;
        if args.raw {
            let exr = args.out.join(format!("{}.exr", mode.name()));
            batch.stage(&exr, &output::exr_bytes(&exr, &ssdo::headless::stats::hdr_image(&gpu, &renderer)?)?)?;
        }
        log::info!("{mode}: {}x{} in {:.0} ms", size.0, size.1, started.elapsed().as_secs_f64() * 1e3);
        panels.push((compare::caption(&renderer.settings, renderer.radius(), &sky.name, scene.lights.len()), image));
    }
    if args.stats && args.json {
        output::print_line(
            &serde_json::to_string_pretty(&serde_json::Value::Object(stats_json)).expect("JSON of numbers"),
        )?;
    }
    if panels.len() > 1 {
        let path = args.out.join("compare.png");
        batch.stage(&path, &output::png_bytes(&path, &compare::grid(&panels))?)?;
    }
    for path in batch.commit()? {
        say(format!("wrote {}", path.display()))?;
    }
    Ok(())
}

/// The scene and sky of `args`, with a spinner on the terminal while each loads.
fn load_scene(args: &SceneArgs) -> Result<(ssdo::scene::Scene, ssdo::scene::Skybox)> {
    let model = with_spinner("loading the model", || args.load_model())?;
    let sky = with_spinner("loading the sky", || args.load_sky())?;
    Ok((args.scene(model), sky))
}

fn print_plan(renderer: &Renderer) -> Result<()> {
    let plan = renderer.plan();
    let mut text = format!("plan {}:", plan.mode);
    let names = |ids: &[ssdo::render::TargetId]| ids.iter().map(|t| t.name()).collect::<Vec<_>>().join(" ");
    for (step, io) in plan.io() {
        let (name, reads, writes) = (step.name_in(plan.mode), names(&io.reads), names(&io.writes));
        text += &format!("\n  pass {name} reads [{reads}] writes [{writes}]");
    }
    let allocations = renderer.allocations();
    for (name, bytes) in &allocations {
        text += &format!("\n  bytes {name} {bytes}");
    }
    text += &format!("\n  bytes total {}", allocations.iter().map(|(_, b)| b).sum::<u64>());
    output::print_line(&text)
}

fn run_bench(args: &BenchArgs) -> Result<()> {
    let settings = args.render.settings(Mode::Off)?;
    let (size, features) = ((args.size.0, args.size.1), ssdo::render::SceneFeatures { lights: args.scene.lights });
    Renderer::check_memory(size, &settings, features, args.hdr, &Mode::ALL)?;
    let (scene, sky) = load_scene(&args.scene)?;
    let camera = args.scene.camera(&scene)?;
    let gpu = Gpu::headless()?;
    gpu.check_size(size.0, size.1)?;
    let mut renderer = Renderer::new(&gpu, &scene, &sky, size, CAPTURE_FORMAT, settings)?;
    renderer.keep_hdr(&gpu, args.hdr);
    let timestamps = renderer.enable_timing(&gpu);
    log::info!("planned: {} modes × {} frames at {}x{}", Mode::ALL.len(), args.frames + 2, size.0, size.1);
    let bar = indicatif::ProgressBar::new(Mode::ALL.len() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} modes {msg}")
            .expect("valid template"),
    );
    let target = output_texture(&gpu, size);
    let view = target.create_view(&wgpu::TextureViewDescriptor::default());
    let mut modes = Vec::new();
    for mode in Mode::ALL {
        renderer.set_mode(&gpu, mode);
        bar.set_message(mode.name());
        modes.push((mode, ssdo::headless::bench::measure(&gpu, &mut renderer, &camera, &view, args.frames)?));
        bar.inc(1);
    }
    bar.finish_and_clear();
    let report = BenchReport {
        device: gpu.describe(),
        software: gpu.is_software(),
        timestamps,
        size,
        frames: args.frames,
        settings: renderer.settings,
        modes,
    };
    if args.json {
        output::print_line(&serde_json::to_string_pretty(&report.json()).expect("JSON of numbers and strings"))
    } else {
        output::print_line(report.table().trim_end_matches('\n'))
    }
}

fn run_view(args: ViewArgs) -> Result<()> {
    let size = (args.size.0, args.size.1);
    if size.0 == 0 || size.1 == 0 {
        return Err(Error::Setting(format!("--size {}x{}: both sides must be at least 1", size.0, size.1)));
    }
    // Window systems refuse (X11: panic inside winit at 65536) what no adapter could draw anyway.
    const MAX_WINDOW_SIDE: u32 = 16384;
    if size.0 > MAX_WINDOW_SIDE || size.1 > MAX_WINDOW_SIDE {
        return Err(Error::Setting(format!(
            "--size {}x{}: the viewer's window can be at most {MAX_WINDOW_SIDE} on a side",
            size.0, size.1
        )));
    }
    let settings = args.render.settings(args.mode)?;
    let ViewArgs { scene, screenshot_dir, .. } = args;
    ssdo::app::run(ssdo::app::ViewerOptions { scene, settings, size, screenshot_dir })
}

/// Mesa's implicit Vulkan layer `VK_LAYER_MESA_device_select` (installed with its drivers) only
/// reorders the adapters, which we rank ourselves (`ssdo::gpu`); with no Wayland session it prints
/// `error: XDG_RUNTIME_DIR is invalid or not set` twice, on every successful run. Turned off unless
/// the user set its switch, here before any other thread exists.
fn quiet_mesa_device_select() {
    if std::env::var_os("NODEVICE_SELECT").is_none() {
        std::env::set_var("NODEVICE_SELECT", "1");
    }
}

/// `text` with control characters (a newline in a file name, say) written as escapes, so an error
/// stays one line.
fn one_line(text: &str) -> String {
    text.chars().flat_map(|c| if c.is_control() { c.escape_default().collect::<Vec<_>>() } else { vec![c] }).collect()
}

fn main() -> ExitCode {
    quiet_mesa_device_select();
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn,ssdo=info"))
        .format_timestamp(None)
        .init();
    // The parser's errors in this program's one-line form (help and version print as usual).
    let cli = match Cli::try_parse_with_ranges() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            // The first paragraph: clap lists missing or conflicting arguments on the lines
            // under its first.
            let text = e.to_string();
            let paragraph: Vec<&str> = text
                .lines()
                .skip_while(|l| l.trim().is_empty())
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            let first = if paragraph.is_empty() { "bad command line".to_string() } else { paragraph.join(" ") };
            let first = first.trim_start_matches("error:").trim();
            error_line(&format!("{} (see ssdo --help)", one_line(first)));
            return ExitCode::from(2);
        }
    };
    let budget = cli.memory_budget.map(ssdo::budget::set).unwrap_or(Ok(()));
    let result = budget.and_then(|()| match cli.command {
        Some(Command::Capture(args)) => run_capture(&args),
        Some(Command::Bench(args)) => run_bench(&args),
        Some(Command::View(args)) => run_view(args),
        Some(Command::Report(args)) => run_report(&args),
        None => run_view(ViewArgs::parse_default()),
    });
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // The reader of standard output went away (`| head`): nothing to say, as a Unix tool.
        Err(Error::StdoutClosed) => ExitCode::from(Error::StdoutClosed.exit_code() as u8),
        Err(e) => {
            error_line(&one_line(&e.to_string()));
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

/// `ssdo: error: <text>` on standard error; a closed or full standard error is not worth a panic.
fn error_line(text: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "ssdo: error: {text}");
}
