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
mod help;
mod progress;

use cli::*;

fn run_report(args: &ReportArgs) -> Result<()> {
    let mut options = args.options();
    options.check()?;
    options.preset = args.preset()?;
    output::check_folder(&options.out)?;
    let gpu = Gpu::headless()?;
    warn_if_elsewhere(options.preset.as_ref(), &gpu, options.on.size);
    let started = Instant::now();
    let bar = progress::bar(ssdo::report::progress_steps(&options), "");
    let report = ssdo::report::run(&gpu, &options, &|message: &str| {
        bar.inc(1);
        if message != "reference row" {
            bar.set_message(message.to_owned());
        }
    })?;
    bar.finish_and_clear();
    report.write(&options)?;
    output::print_line(&report.markdown(&options))?;
    output::print_line(&format!(
        "wrote {0}/report.csv, {0}/report.md, {0}/report.png in {1:.0} s",
        options.out.display(),
        started.elapsed().as_secs_f64()
    ))
}

fn run_tune(args: &TuneArgs) -> Result<()> {
    let options = args.options()?;
    options.check()?;
    output::check_folder(&options.out)?;
    let gpu = Gpu::headless()?;
    let bar = progress::bar(2 * options.on.size.1 as u64 * options.views as u64, " truth rows");
    let tune = ssdo::tune::run(&gpu, &options, &|message: &str| {
        if message == "reference row" {
            bar.inc(1);
        } else {
            bar.set_message(message.to_owned());
        }
    })?;
    bar.finish_and_clear();
    let written = tune.write(&options)?;
    output::print_line(tune.markdown(&options).trim_end())?;
    if let Some(command) = tune.capture_command(&options) {
        output::print_line(&format!("\nrender the pick: {command}"))?;
    }
    let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
    output::print_line(&format!("wrote {}", names.join(", ")))?;
    match tune.verdict {
        ssdo::tune::Verdict::BelowCheapest => Err(Error::Setting(tune.verdict_lines(&options).join(" "))),
        _ => Ok(()),
    }
}

/// A warning when the run's preset was measured on another device or at another size.
fn warn_if_elsewhere(preset: Option<&ssdo::preset::Preset>, gpu: &Gpu, size: (u32, u32)) {
    if let Some(warning) = preset.and_then(|p| p.elsewhere(&gpu.describe(), size)) {
        log::warn!("{warning}");
    }
}

fn run_capture(args: &CaptureArgs) -> Result<()> {
    let modes: Vec<Mode> = match args.mode {
        ModeChoice::One(mode) => vec![mode],
        ModeChoice::All => Mode::ALL.to_vec(),
    };
    // --raw, --stats and --truth read the linear HDR image back; otherwise the frame tone-maps
    // in place.
    let hdr = args.raw || args.stats || args.truth;
    let Headless { gpu, scene, sky, camera, mut renderer, size } =
        set_up((&args.scene, &args.render), args.size, (&modes, hdr), Some(&args.out))?;
    let truth = if args.truth { Some(trace_truth(&gpu, &mut renderer, (&scene, &sky), &camera, args)?) } else { None };
    let mut errors = Vec::new();
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
            output::print_line(&renderer.plan_listing())?;
        }
        if args.stats {
            let stats = ssdo::headless::stats::frame_stats(&gpu, &mut renderer, &camera)?;
            if let Some(buffers) = say_stats(mode, &stats, args.json)? {
                stats_json.insert(mode.name().to_string(), buffers);
            }
        }
        let started = Instant::now();
        let image = capture_converged(&gpu, &mut renderer, &camera)?;
        if let Some(truth) = &truth {
            errors.push(truth.measure(&gpu, &renderer, mode, &image)?);
        }
        let path = args.out.join(format!("{}.png", mode.name()));
        batch.stage(&path, &output::png_bytes(&path, &image)?)?;
        if args.raw {
            let exr = args.out.join(format!("{}.exr", mode.name()));
            batch.stage(&exr, &output::exr_bytes(&exr, &ssdo::headless::stats::hdr_image(&gpu, &renderer)?)?)?;
        }
        log::info!("{mode}: {}x{} in {:.0} ms", size.0, size.1, started.elapsed().as_secs_f64() * 1e3);
        panels.push((compare::caption(&renderer, &sky.name, scene.lights.len()), image));
    }
    if let Some(truth) = &truth {
        let image = &panels[panels.len() - 1].1;
        let said = truth.outputs(&errors, (image, renderer.settings.exposure), &args.out, &mut batch)?;
        stats_json.insert("truth".into(), said.json);
        for line in said.lines {
            say(line)?;
        }
        panels.push(said.panel);
    }
    if args.json && (args.stats || args.truth) {
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

/// `--stats` of `mode`'s buffers: printed a line each, or (`json`) as the JSON object returned.
fn say_stats(
    mode: Mode,
    stats: &[ssdo::headless::stats::BufferStats],
    json: bool,
) -> Result<Option<serde_json::Value>> {
    if json {
        return Ok(Some(serde_json::Value::Object(stats.iter().map(|s| (s.name.to_string(), s.json())).collect())));
    }
    for s in stats {
        output::print_line(&format!(
            "{mode:>5} {:<12} min {:>12.5e} max {:>12.5e} mean {:>12.5e} non_finite {}",
            s.name, s.min, s.max, s.mean, s.non_finite
        ))?;
    }
    Ok(None)
}

/// The truth of the capture's view, with a progress bar over its rows.
fn trace_truth(
    gpu: &Gpu,
    renderer: &mut Renderer,
    scene: (&ssdo::scene::Scene, &ssdo::scene::Skybox),
    camera: &ssdo::scene::OrbitCamera,
    args: &CaptureArgs,
) -> Result<ssdo::headless::truth::ViewTruth> {
    let bar = progress::bar(2 * args.size.1 as u64, " truth rows");
    let rays = (args.spp, args.scene.seed);
    let truth = ssdo::headless::truth::ViewTruth::trace(gpu, renderer, scene, camera, rays, &|| bar.inc(1));
    bar.finish_and_clear();
    truth
}

/// What `capture` and `bench` set up alike: the device, the scene and sky, the camera, and the
/// renderer at the first of the modes.
struct Headless {
    gpu: Gpu,
    scene: ssdo::scene::Scene,
    sky: ssdo::scene::Skybox,
    camera: ssdo::scene::OrbitCamera,
    renderer: Renderer,
    size: (u32, u32),
}

/// The settings from the preset and the flags, checked against the memory budget for `modes`
/// (with the HDR image kept: `hdr`) before `out` (where there is one) is checked and anything is
/// loaded; then the scene, the camera, the device and the renderer.
fn set_up(
    (scene_args, render_args): (&SceneArgs, &ssdo::spec::RenderArgs),
    size: cli::Size,
    (modes, hdr): (&[Mode], bool),
    out: Option<&std::path::Path>,
) -> Result<Headless> {
    let preset = render_args.preset()?;
    let settings = render_args.settings_with(modes[0], preset.as_ref())?;
    let (size, features) = ((size.0, size.1), ssdo::render::SceneFeatures::lit(scene_args.lights));
    Renderer::check_memory(size, &settings, features, hdr, modes)?;
    if let Some(out) = out {
        output::check_folder(out)?;
    }
    let (scene, sky) = load_scene(scene_args)?;
    let camera = scene_args.camera(&scene)?;
    let gpu = Gpu::headless()?;
    gpu.check_size(size.0, size.1)?;
    warn_if_elsewhere(preset.as_ref(), &gpu, size);
    let mut renderer = Renderer::new(&gpu, &scene, &sky, size, CAPTURE_FORMAT, settings)?;
    renderer.keep_hdr(&gpu, hdr);
    Ok(Headless { gpu, scene, sky, camera, renderer, size })
}

/// The scene and sky of `args`, with a spinner on the terminal while each loads.
fn load_scene(args: &SceneArgs) -> Result<(ssdo::scene::Scene, ssdo::scene::Skybox)> {
    let model = progress::spinner("loading the model", || args.load_model())?;
    let sky = progress::spinner("loading the sky", || args.load_sky())?;
    Ok((args.scene(model), sky))
}

fn run_bench(args: &BenchArgs) -> Result<()> {
    let orbit = ssdo::spec::in_range("orbit", args.orbit.unwrap_or(0.0), -180.0, 180.0)?;
    let Headless { gpu, camera, mut renderer, size, .. } =
        set_up((&args.scene, &args.render), args.size, (&Mode::ALL, args.hdr), None)?;
    let timestamps = renderer.enable_timing(&gpu);
    log::info!("planned: {} modes × {} frames at {}x{}", Mode::ALL.len(), args.frames + 2, size.0, size.1);
    let bar = progress::bar(Mode::ALL.len() as u64, " modes");
    let target = output_texture(&gpu, size);
    let view = target.create_view(&wgpu::TextureViewDescriptor::default());
    let mut modes = Vec::new();
    for mode in Mode::ALL {
        renderer.set_mode(&gpu, mode);
        bar.set_message(mode.name());
        let frames = (args.frames, orbit);
        modes.push((mode, ssdo::headless::bench::measure_turning(&gpu, &mut renderer, &camera, &view, frames)?));
        bar.inc(1);
    }
    bar.finish_and_clear();
    let report = BenchReport {
        device: gpu.describe(),
        software: gpu.is_software(),
        timestamps,
        size,
        frames: args.frames,
        orbit,
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
    let preset = args.render.preset()?;
    let settings = args.render.settings_with(args.mode, preset.as_ref())?;
    let ViewArgs { scene, screenshot_dir, .. } = args;
    ssdo::app::run(ssdo::app::ViewerOptions { scene, settings, preset, size, screenshot_dir })
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
            error_line(&format!("{} (see ssdo --help)", ssdo::text::one_line(first)));
            return ExitCode::from(2);
        }
    };
    let budget = cli.memory_budget.map(ssdo::budget::set).unwrap_or(Ok(()));
    let result = budget.and_then(|()| match cli.command {
        Some(Command::Capture(args)) => run_capture(&args),
        Some(Command::Bench(args)) => run_bench(&args),
        Some(Command::View(args)) => run_view(args),
        Some(Command::Report(args)) => run_report(&args),
        Some(Command::Tune(args)) => run_tune(&args),
        None => run_view(ViewArgs::parse_default()),
    });
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // The reader of standard output went away (`| head`): nothing to say, as a Unix tool.
        Err(Error::StdoutClosed) => ExitCode::from(Error::StdoutClosed.exit_code() as u8),
        Err(e) => {
            error_line(&ssdo::text::one_line(&e.to_string()));
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

/// `ssdo: error: <text>` on standard error; a closed or full standard error is not worth a panic.
fn error_line(text: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "ssdo: error: {text}");
}
