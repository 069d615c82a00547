//! The `ssdo` command line: a thin layer over the library. Errors print one line
//! (`ssdo: error: <file or setting>: <problem>`) and exit with the code of their kind
//! (see `Error::exit_code` and the README).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::{Args, Parser, Subcommand};

use ssdo::gpu::Gpu;
use ssdo::render::capture::{capture, output_texture, CAPTURE_FORMAT};
use ssdo::render::{Mode, Renderer, Settings, Variant, View};
use ssdo::scene::{self, OrbitCamera, Scene};
use ssdo::{compare, output, Error, Result};

#[derive(Parser)]
#[command(name = "ssdo", version, about = "Screen-space directional occlusion renderer (wgpu)")]
struct Cli {
    /// Without a command, the viewer opens with its defaults.
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Open the interactive viewer (the default).
    View(ViewArgs),
    /// Render the scene offscreen and write PNGs: <out>/<mode>.png (and compare.png for all).
    Capture(CaptureArgs),
    /// Render each mode repeatedly and print per-pass GPU times.
    Bench(BenchArgs),
    /// Error of every mode and setting against a CPU ray-traced reference, against GPU time.
    Report(ReportArgs),
}

/// A size written as WIDTHxHEIGHT.
#[derive(Clone, Copy, Debug)]
struct Size(u32, u32);

fn parse_size(s: &str) -> std::result::Result<Size, String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(|| format!("'{s}' is not WIDTHxHEIGHT"))?;
    let parse = |v: &str| v.trim().parse::<u32>().map_err(|_| format!("'{s}' is not WIDTHxHEIGHT"));
    Ok(Size(parse(w)?, parse(h)?))
}

/// Which modes to render: one, or `all` four.
#[derive(Clone, Copy, Debug)]
enum ModeChoice {
    One(Mode),
    All,
}

fn parse_mode(s: &str) -> std::result::Result<ModeChoice, String> {
    if s.eq_ignore_ascii_case("all") {
        return Ok(ModeChoice::All);
    }
    s.parse::<Mode>().map(ModeChoice::One).map_err(|e| e.to_string())
}

fn parse_variant(s: &str) -> std::result::Result<Variant, String> {
    s.parse::<Variant>().map_err(|e| e.to_string())
}

fn parse_view(s: &str) -> std::result::Result<View, String> {
    s.parse::<View>().map_err(|e| e.to_string())
}

#[derive(Args)]
struct SceneArgs {
    /// OBJ model to load [default: models/cornell/cornell.obj]
    #[arg(long)]
    model: Option<PathBuf>,
    /// Skybox folder with six faces [default: skyboxes/day]
    #[arg(long)]
    skybox: Option<PathBuf>,
    /// Number of random point lights
    #[arg(long, default_value_t = scene::DEFAULT_LIGHTS)]
    lights: usize,
    /// Seed for the lights' colours and positions
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Camera yaw around the model in degrees [default: 35]
    #[arg(long, allow_negative_numbers = true)]
    yaw: Option<f32>,
    /// Camera elevation in degrees [default: 22]
    #[arg(long, allow_negative_numbers = true)]
    pitch: Option<f32>,
    /// Camera distance from the model's centre [default: frames the model]
    #[arg(long, allow_negative_numbers = true)]
    distance: Option<f32>,
    /// Near plane distance [default: a thousandth of the camera distance]
    #[arg(long, allow_negative_numbers = true)]
    near: Option<f32>,
    /// Far plane distance, or inf [default: inf]
    #[arg(long, value_parser = parse_far)]
    far: Option<f32>,
    /// Scale the model by this factor (defaults scale with it)
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    scale: f32,
}

fn parse_far(s: &str) -> std::result::Result<f32, String> {
    if s.eq_ignore_ascii_case("inf") {
        return Ok(f32::INFINITY);
    }
    s.parse::<f32>().map_err(|_| format!("'{s}' is not a number or inf"))
}

#[derive(Args)]
struct RenderArgs {
    /// Algorithm family: march (the default), points (the paper's point sampling) or classic (the source chapters' SSAO and SSDO)
    #[arg(long, default_value = "default", value_parser = parse_variant)]
    variant: Variant,
    /// Samples per pixel of the points and classic variants, 1-256 [default: 16; classic 64]
    #[arg(long)]
    samples: Option<usize>,
    /// The march: slices (directions around the view vector) per pixel, 1-32
    #[arg(long, default_value_t = 2)]
    slices: usize,
    /// The march: steps along each side of a slice, 1-64 (half within the radius)
    #[arg(long, default_value_t = 12)]
    steps: usize,
    /// The march's reach, in model units [default: 24 radii]
    #[arg(long, allow_negative_numbers = true)]
    reach: Option<f32>,
    /// The march's surface thickness, in model units [default: 1 radius]
    #[arg(long, allow_negative_numbers = true)]
    thickness: Option<f32>,
    /// The march's far steps read a closest-depth pyramid (off: it over-occludes, see README)
    #[arg(long)]
    depth_pyramid: bool,
    /// Sampling radius in model units [default: a tenth of the scene's bounding radius]
    #[arg(long, allow_negative_numbers = true)]
    radius: Option<f32>,
    /// Depth bias of the occlusion test, as a fraction of the radius
    #[arg(long, default_value_t = 0.03, allow_negative_numbers = true)]
    bias: f32,
    /// How much of the AO is applied (0 to 1)
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    ao_strength: f32,
    /// AO is raised to this power
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    ao_power: f32,
    /// Multiplier on SSDO's sky light
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    sky_strength: f32,
    /// Multiplier on SSDO's indirect bounce
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    indirect_strength: f32,
    /// Leave the AO/DO noise unfiltered
    #[arg(long)]
    no_blur: bool,
    /// Exposure applied before tone mapping
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    exposure: f32,
    /// Constant ambient radiance, on top of the sky [default: 0.1; classic 0.5]
    #[arg(long, allow_negative_numbers = true)]
    ambient: Option<f32>,
    /// Multiplier on the sky's radiance
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    sky_scale: f32,
    /// What to show: final, albedo, normals, depth, ao, do-direct, do-indirect, lighting
    #[arg(long, default_value = "final", value_parser = parse_view)]
    view: View,
}

#[derive(Args)]
struct CaptureArgs {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    render: RenderArgs,
    /// Mode to render: off, ssao, ssdo, both, or all (also writes compare.png)
    #[arg(long, default_value = "all", value_parser = parse_mode)]
    mode: ModeChoice,
    /// Image size, WIDTHxHEIGHT
    #[arg(long, default_value = "800x600", value_parser = parse_size)]
    size: Size,
    /// Output folder
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Print each mode's passes, in order, and the bytes each target uses
    #[arg(long)]
    print_plan: bool,
    /// Print min, max, mean and non-finite count of each linear buffer (AO, DO, HDR)
    #[arg(long)]
    stats: bool,
    /// With --stats: print JSON
    #[arg(long)]
    json: bool,
    /// Also write the linear HDR image as <out>/<mode>.exr
    #[arg(long)]
    raw: bool,
}

#[derive(Args)]
struct ViewArgs {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    render: RenderArgs,
    /// Mode to start in: off, ssao, ssdo or both
    #[arg(long, default_value = "both", value_parser = parse_single_mode)]
    mode: Mode,
    /// Window size, WIDTHxHEIGHT (the 3D view is the window less the 300-pixel panel)
    #[arg(long, default_value = "1280x720", value_parser = parse_size)]
    size: Size,
    /// Where F12 screenshots and C comparisons are written
    #[arg(long, default_value = "screenshots")]
    screenshot_dir: PathBuf,
}

#[derive(Args)]
struct ReportArgs {
    /// Scene: cornell (the default scene), crevices (thin features, deep slots), open (redblue
    /// sky) or stairs (stairs under an overhang, a scene nobody tuned on)
    #[arg(long, default_value = "cornell")]
    scene: String,
    /// An OBJ model instead of a named scene
    #[arg(long)]
    model: Option<PathBuf>,
    /// Skybox folder [default: the scene's own sky]
    #[arg(long)]
    skybox: Option<PathBuf>,
    /// Image size, WIDTHxHEIGHT
    #[arg(long, default_value = "320x240", value_parser = parse_size)]
    size: Size,
    /// Sample counts of the points and classic variants to sweep, comma-separated
    #[arg(long, default_value = "4,8,16,32,64", value_delimiter = ',')]
    samples: Vec<usize>,
    /// Slices x steps of the march variant to sweep, comma-separated
    #[arg(long, default_value = "1x8,2x8,2x12,4x16", value_delimiter = ',', value_parser = parse_march)]
    march: Vec<(usize, usize)>,
    /// Sampling radii to sweep, comma-separated: multiples of the scene's default (2x) or lengths
    /// in model units (0.3)
    #[arg(long, default_value = "1x", value_delimiter = ',')]
    radius: Vec<ssdo::report::RadiusChoice>,
    /// Reference rays per pixel, in each of the two independent traces (at least 2)
    #[arg(long, default_value_t = 256)]
    spp: u32,
    /// Frames timed per configuration (after two warm-up frames)
    #[arg(long, default_value_t = 20)]
    frames: usize,
    /// Number of random point lights
    #[arg(long, default_value_t = scene::DEFAULT_LIGHTS)]
    lights: usize,
    /// Seed of the lights and of the reference's rays
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Output folder for report.csv, report.md, report.png and the error maps
    #[arg(long, default_value = "report")]
    out: PathBuf,
}

fn run_report(args: &ReportArgs) -> Result<()> {
    if let Some(&bad) = args.samples.iter().find(|s| !(1..=256).contains(*s)) {
        return Err(Error::Setting(format!("--samples {bad}: each count must be between 1 and 256")));
    }
    if let Some(&(slices, steps)) = args.march.iter().find(|(a, b)| !(1..=32).contains(a) || !(1..=64).contains(b)) {
        return Err(Error::Setting(format!("--march {slices}x{steps}: slices must be 1-32 and steps 1-64")));
    }
    if args.frames == 0 || args.samples.is_empty() || args.radius.is_empty() {
        return Err(Error::Setting("--frames, --samples and --radius must each give at least one".into()));
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
        lights: args.lights,
        seed: args.seed,
        out: args.out.clone(),
    };
    let gpu = Gpu::headless()?;
    let started = Instant::now();
    let rows = args.size.1 as u64;
    let radii = args.radius.len() as u64;
    let configs = 2 + radii * (3 * 2 * (2 * args.samples.len() + args.march.len()) + 2 * args.march.len()) as u64;
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
    println!("{}", report.markdown(&options));
    println!(
        "wrote {0}/report.csv, {0}/report.md, {0}/report.png in {1:.0} s",
        args.out.display(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
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

/// `4x8`: slices × steps of the march.
fn parse_march(s: &str) -> std::result::Result<(usize, usize), String> {
    let (a, b) = s.split_once(['x', 'X']).ok_or_else(|| format!("'{s}': expected SLICESxSTEPS like 4x8"))?;
    let parse = |t: &str| t.trim().parse::<usize>().map_err(|_| format!("'{s}': expected SLICESxSTEPS like 4x8"));
    Ok((parse(a)?, parse(b)?))
}

fn parse_single_mode(s: &str) -> std::result::Result<Mode, String> {
    s.parse::<Mode>().map_err(|e| e.to_string())
}

#[derive(Args)]
struct BenchArgs {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    render: RenderArgs,
    /// Image size, WIDTHxHEIGHT
    #[arg(long, default_value = "800x600", value_parser = parse_size)]
    size: Size,
    /// Frames measured per mode (after two warm-up frames)
    #[arg(long, default_value_t = 20)]
    frames: usize,
    /// Print JSON instead of a table
    #[arg(long)]
    json: bool,
}

impl ViewArgs {
    /// The viewer's arguments when `ssdo` is run without a command.
    fn parse_default() -> Self {
        #[derive(Parser)]
        struct Only {
            #[command(flatten)]
            view: ViewArgs,
        }
        Only::parse_from(["ssdo"]).view
    }
}

/// The largest radiance-like setting (ambient, strengths, exposure, sky scale) taken: beyond it
/// a frame's light no longer fits even pre-exposed half floats, and the sky and the light cubes
/// would turn black instead of white.
const MAX_GAIN: f32 = 1e6;
/// The largest length setting (radius, reach, thickness), in model units.
const MAX_LENGTH: f32 = 1e9;

fn non_negative(name: &str, value: f32) -> Result<f32> {
    in_range(name, value, 0.0, MAX_LENGTH)
}

/// `value` if it is finite and within [lo, hi]; otherwise an error naming the flag and the range.
fn in_range(name: &str, value: f32, lo: f32, hi: f32) -> Result<f32> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(Error::Setting(format!("--{name} {}: must be a finite number from {} to {}", num(value), num(lo), num(hi))))
    }
}

/// A number as people write it: 0.25, 1e6, 3.0e-5 (not 30 digits of a huge or tiny float).
fn num(v: f32) -> String {
    if v != 0.0 && v.is_finite() && !(1e-4..1e6).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

impl SceneArgs {
    fn load(&self) -> Result<(Scene, scene::Skybox)> {
        // Beyond these, positions lose the precision the depth buffer and the march need.
        in_range("scale", self.scale, 1e-6, 1e6)?;
        let model = with_spinner("loading the model", || scene::load_model(self.model.as_deref()))?.scaled(self.scale);
        let sky = with_spinner("loading the sky", || scene::load_skybox(self.skybox.as_deref()))?;
        Ok((Scene::new(model, self.lights, self.seed), sky))
    }

    fn camera(&self, scene: &Scene) -> Result<OrbitCamera> {
        let mut camera = OrbitCamera::framing(&scene.model.bounds);
        if let Some(yaw) = self.yaw {
            camera.yaw_deg = in_range("yaw", yaw, -36000.0, 36000.0)?;
        }
        if let Some(pitch) = self.pitch {
            // ±90 would look along the orbit's up axis, where the view has no defined roll.
            camera.pitch_deg = in_range("pitch", pitch, -89.0, 89.0)?;
        }
        if let Some(distance) = self.distance {
            // From inside the model out to where it is a speck, in the model's own size.
            let r = scene.model.bounds.radius().max(f32::MIN_POSITIVE);
            let (lo, hi) = (1e-5 * r, 1e5 * r);
            if !(distance.is_finite() && (lo..=hi).contains(&distance)) {
                return Err(Error::Setting(format!(
                    "--distance {}: must be from {lo:.3e} to {hi:.3e} for this model (1e-5 to 1e5 of its bounding radius)",
                    num(distance)
                )));
            }
            camera.distance = distance;
            camera.near = camera.near.min(distance * 1e-3);
        }
        if let Some(near) = self.near {
            // Reverse-Z keeps precision down to a tiny near plane, but not to a denormal one.
            let lo = camera.distance * 1e-9;
            if !(near.is_finite() && near >= lo) {
                return Err(Error::Setting(format!(
                    "--near {}: must be a finite number of at least {lo:.3e} (1e-9 of the camera distance)",
                    num(near)
                )));
            }
            camera.near = near;
        }
        if let Some(far) = self.far {
            if !(far > camera.near) {
                return Err(Error::Setting(format!("--far {far}: must be beyond the near plane ({})", camera.near)));
            }
            camera.far = far.is_finite().then_some(far);
        }
        Ok(camera)
    }
}

impl RenderArgs {
    fn settings(&self, mode: Mode) -> Result<Settings> {
        let base = match self.variant {
            Variant::March | Variant::Points => Settings::default(),
            Variant::Classic => Settings::classic(),
        };
        let samples = self.samples.unwrap_or(base.samples);
        if !(1..=256).contains(&samples) {
            return Err(Error::Setting(format!("--samples {samples}: must be between 1 and 256")));
        }
        let radius = self.radius.map(|r| non_negative("radius", r)).transpose()?;
        if !(1..=32).contains(&self.slices) || !(1..=64).contains(&self.steps) {
            return Err(Error::Setting(format!(
                "--slices {} --steps {}: slices must be 1-32 and steps 1-64",
                self.slices, self.steps
            )));
        }
        Ok(Settings {
            mode,
            variant: self.variant,
            samples,
            slices: self.slices,
            steps: self.steps,
            reach: self.reach.map(|r| non_negative("reach", r)).transpose()?,
            thickness: self.thickness.map(|r| non_negative("thickness", r)).transpose()?,
            depth_pyramid: self.depth_pyramid,
            radius,
            bias: non_negative("bias", self.bias)?,
            ao_strength: in_range("ao-strength", self.ao_strength, 0.0, 1.0)?,
            ao_power: in_range("ao-power", self.ao_power, 0.0, 100.0)?,
            sky_strength: in_range("sky-strength", self.sky_strength, 0.0, MAX_GAIN)?,
            indirect_strength: in_range("indirect-strength", self.indirect_strength, 0.0, MAX_GAIN)?,
            blur: !self.no_blur,
            exposure: in_range("exposure", self.exposure, 0.0, MAX_GAIN)?,
            ambient: in_range("ambient", self.ambient.unwrap_or(base.ambient), 0.0, MAX_GAIN)?,
            sky_scale: in_range("sky-scale", self.sky_scale, 0.0, MAX_GAIN)?,
            view: self.view,
        })
    }
}

fn run_capture(args: &CaptureArgs) -> Result<()> {
    let modes: Vec<Mode> = match args.mode {
        ModeChoice::One(mode) => vec![mode],
        ModeChoice::All => Mode::ALL.to_vec(),
    };
    let settings = args.render.settings(modes[0])?;
    let (scene, sky) = args.scene.load()?;
    let camera = args.scene.camera(&scene)?;
    let gpu = Gpu::headless()?;
    let size = (args.size.0, args.size.1);
    gpu.check_size(size.0, size.1)?;
    let mut renderer = Renderer::new(&gpu, &scene, &sky, size, CAPTURE_FORMAT, settings)?;
    let mut panels = Vec::new();
    let mut stats_json = serde_json::Map::new();
    // Every file of the run lands together, or none does; leftovers of killed runs go first.
    output::remove_stale_temporaries(&args.out);
    let mut batch = output::Batch::default();
    // With --json, standard output is the JSON document alone.
    let say = |line: String| if args.json { log::info!("{line}") } else { println!("{line}") };
    for mode in modes {
        renderer.set_mode(&gpu, mode);
        if args.print_plan {
            print_plan(&renderer);
        }
        if args.stats {
            let stats = ssdo::render::stats::frame_stats(&gpu, &mut renderer, &camera)?;
            if args.json {
                let buffers: serde_json::Map<String, serde_json::Value> =
                    stats.iter().map(|s| (s.name.to_string(), s.json())).collect();
                stats_json.insert(mode.name().to_string(), serde_json::Value::Object(buffers));
            } else {
                for s in &stats {
                    println!(
                        "{mode:>5} {:<12} min {:>12.5e} max {:>12.5e} mean {:>12.5e} non_finite {}",
                        s.name, s.min, s.max, s.mean, s.non_finite
                    );
                }
            }
        }
        let started = Instant::now();
        let image = capture(&gpu, &mut renderer, &camera)?;
        let path = args.out.join(format!("{}.png", mode.name()));
        batch.stage(&path, &output::png_bytes(&path, &image)?)?;
        if args.raw {
            let exr = args.out.join(format!("{}.exr", mode.name()));
            batch.stage(&exr, &output::exr_bytes(&exr, &ssdo::render::stats::hdr_image(&gpu, &renderer)?)?)?;
        }
        log::info!("{mode}: {}x{} in {:.0} ms", size.0, size.1, started.elapsed().as_secs_f64() * 1e3);
        panels.push((compare::caption(&renderer.settings, renderer.radius(), &sky.name, scene.lights.len()), image));
    }
    if args.stats && args.json {
        println!("{}", serde_json::to_string_pretty(&serde_json::Value::Object(stats_json)).expect("JSON of numbers"));
    }
    if panels.len() > 1 {
        let path = args.out.join("compare.png");
        batch.stage(&path, &output::png_bytes(&path, &compare::grid(&panels))?)?;
    }
    for path in batch.commit()? {
        say(format!("wrote {}", path.display()));
    }
    Ok(())
}

fn print_plan(renderer: &Renderer) {
    let plan = renderer.plan();
    println!("plan {}:", plan.mode);
    for name in plan.step_names() {
        println!("  pass {name}");
    }
    let allocations = renderer.allocations();
    for (name, bytes) in &allocations {
        println!("  bytes {name} {bytes}");
    }
    println!("  bytes total {}", allocations.iter().map(|(_, b)| b).sum::<u64>());
}

fn run_bench(args: &BenchArgs) -> Result<()> {
    if args.frames == 0 {
        return Err(Error::Setting("--frames 0: measure at least one frame".into()));
    }
    let settings = args.render.settings(Mode::Off)?;
    let (scene, sky) = args.scene.load()?;
    let camera = args.scene.camera(&scene)?;
    let gpu = Gpu::headless()?;
    let size = (args.size.0, args.size.1);
    gpu.check_size(size.0, size.1)?;
    let mut renderer = Renderer::new(&gpu, &scene, &sky, size, CAPTURE_FORMAT, settings)?;
    let timestamps = renderer.enable_timing(&gpu);
    let target = output_texture(&gpu, size);
    let view = target.create_view(&wgpu::TextureViewDescriptor::default());
    let mut results = Vec::new();
    for mode in Mode::ALL {
        renderer.set_mode(&gpu, mode);
        results.push((mode, ssdo::render::timing::measure(&gpu, &mut renderer, &camera, &view, args.frames)?));
    }
    let frame = |m: Mode| results.iter().find(|(mode, _)| *mode == m).map_or(f64::NAN, |(_, r)| r.frame_ms);
    let ratio_ssdo_ssao = frame(Mode::Ssdo) / frame(Mode::Ssao);
    let ratio_both_ssdo = frame(Mode::Both) / frame(Mode::Ssdo);
    let method = if timestamps {
        "timestamp queries (GPU time per pass)"
    } else {
        "synchronised wall time per frame (no timestamp queries)"
    };
    let s = &renderer.settings;
    if args.json {
        let modes: serde_json::Map<String, serde_json::Value> = results
            .iter()
            .map(|(mode, r)| {
                let passes: serde_json::Map<String, serde_json::Value> =
                    r.passes.iter().map(|(n, ms)| (n.to_string(), serde_json::json!(ms))).collect();
                (
                    mode.name().to_string(),
                    serde_json::json!({ "frame_ms": r.frame_ms, "wall_ms": r.wall_ms, "passes": passes }),
                )
            })
            .collect();
        let json = serde_json::json!({
            "device": gpu.describe(),
            "software": gpu.is_software(),
            "timing": if timestamps { "timestamp" } else { "wall" },
            "size": [size.0, size.1],
            "frames": args.frames,
            "variant": s.variant.name(),
            "samples": s.samples,
            "blur": s.blur,
            "modes": modes,
            "ratios": { "ssdo_over_ssao": ratio_ssdo_ssao, "both_over_ssdo": ratio_both_ssdo },
        });
        println!("{}", serde_json::to_string_pretty(&json).expect("JSON of numbers and strings"));
    } else {
        println!("device: {}{}", gpu.describe(), if gpu.is_software() { " — a CPU rasteriser, not a GPU" } else { "" });
        println!("timing: {method}; median of {} frames after 2 warm-up frames", args.frames);
        let count = if s.variant.marches() {
            format!("{} slices × {} steps", s.slices, s.steps)
        } else {
            format!("{} samples", s.samples)
        };
        println!(
            "size {}x{}, {} variant, {count}, blur {}",
            size.0,
            size.1,
            s.variant,
            if s.blur { "on" } else { "off" }
        );
        for (mode, r) in &results {
            let passes: Vec<String> = r.passes.iter().map(|(n, ms)| format!("{n} {ms:.2}")).collect();
            println!(
                "{:>5}: frame {:8.2} ms (wall {:8.2} ms)  {}",
                mode.name(),
                r.frame_ms,
                r.wall_ms,
                passes.join(", ")
            );
        }
        println!("SSDO/SSAO frame-time ratio {ratio_ssdo_ssao:.3}; Both/SSDO {ratio_both_ssdo:.3}");
    }
    Ok(())
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
    ssdo::app::run(ssdo::app::ViewerOptions {
        model: scene.model.clone(),
        skybox: scene.skybox.clone(),
        lights: scene.lights,
        seed: scene.seed,
        scale: scene.scale,
        settings,
        size,
        screenshot_dir,
        camera: Box::new(move |s| scene.camera(s)),
    })
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
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            let text = e.to_string();
            let first = text.lines().find(|l| !l.trim().is_empty()).unwrap_or("bad command line");
            let first = first.trim().trim_start_matches("error:").trim();
            eprintln!("ssdo: error: {} (see ssdo --help)", one_line(first));
            return ExitCode::from(2);
        }
    };
    let result = match cli.command {
        Some(Command::Capture(args)) => run_capture(&args),
        Some(Command::Bench(args)) => run_bench(&args),
        Some(Command::View(args)) => run_view(args),
        Some(Command::Report(args)) => run_report(&args),
        None => run_view(ViewArgs::parse_default()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("ssdo: error: {}", one_line(&e.to_string()));
            ExitCode::from(e.exit_code() as u8)
        }
    }
}
