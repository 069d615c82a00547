//! The `ssdo` command line: a thin layer over the library. Errors print one line
//! (`ssdo: error: <file or setting>: <problem>`) and exit with the code of their kind
//! (see `Error::exit_code` and the README).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

use ssdo::gpu::Gpu;
use ssdo::render::capture::{capture, CAPTURE_FORMAT};
use ssdo::render::{Mode, Renderer, Settings};
use ssdo::scene::{self, OrbitCamera, Scene};
use ssdo::{output, Error, Result};

#[derive(Parser)]
#[command(name = "ssdo", version, about = "Screen-space directional occlusion renderer (wgpu)")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render the scene offscreen and write PNGs: <out>/<mode>.png.
    Capture(CaptureArgs),
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
    /// Exposure applied before tone mapping
    #[arg(long, default_value_t = 1.0)]
    exposure: f32,
    /// Constant ambient radiance
    #[arg(long, default_value_t = 0.25)]
    ambient: f32,
    /// Multiplier on the sky's radiance
    #[arg(long, default_value_t = 1.0)]
    sky_scale: f32,
}

#[derive(Args)]
struct CaptureArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Mode to render: off, ssao, ssdo, both, or all
    #[arg(long, default_value = "off", value_parser = parse_mode)]
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
}

fn finite_positive(name: &str, value: f32) -> Result<f32> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::Setting(format!("--{name} {value}: must be a finite number >= 0")))
    }
}

impl SceneArgs {
    fn load(&self) -> Result<(Scene, scene::Skybox)> {
        let model = scene::load_model(self.model.as_deref())?;
        let sky = scene::load_skybox(self.skybox.as_deref())?;
        Ok((Scene::new(model, self.lights, self.seed), sky))
    }

    fn camera(&self, scene: &Scene) -> Result<OrbitCamera> {
        let mut camera = OrbitCamera::framing(&scene.model.bounds);
        if let Some(yaw) = self.yaw {
            camera.yaw_deg = yaw;
        }
        if let Some(pitch) = self.pitch {
            camera.pitch_deg = pitch;
        }
        if let Some(distance) = self.distance {
            if !(distance.is_finite() && distance > 0.0) {
                return Err(Error::Setting(format!("--distance {distance}: must be a finite number > 0")));
            }
            camera.distance = distance;
            camera.near = camera.near.min(distance * 1e-3);
        }
        Ok(camera)
    }

    fn settings(&self, mode: Mode) -> Result<Settings> {
        Ok(Settings {
            mode,
            exposure: finite_positive("exposure", self.exposure)?,
            ambient: finite_positive("ambient", self.ambient)?,
            sky_scale: finite_positive("sky-scale", self.sky_scale)?,
        })
    }
}

fn run_capture(args: &CaptureArgs) -> Result<()> {
    let modes: Vec<Mode> = match args.mode {
        ModeChoice::One(mode) => vec![mode],
        ModeChoice::All => Mode::ALL.to_vec(),
    };
    let (scene, sky) = args.scene.load()?;
    let camera = args.scene.camera(&scene)?;
    let gpu = Gpu::headless()?;
    let size = (args.size.0, args.size.1);
    gpu.check_size(size.0, size.1)?;
    let mut renderer = Renderer::new(&gpu, &scene, &sky, size, CAPTURE_FORMAT, args.scene.settings(modes[0])?)?;
    for mode in modes {
        renderer.set_mode(&gpu, mode)?;
        if args.print_plan {
            print_plan(&renderer);
        }
        let started = std::time::Instant::now();
        let image = capture(&gpu, &mut renderer, &camera)?;
        let path = args.out.join(format!("{}.png", mode.name()));
        output::save_png(&path, &image)?;
        log::info!("{mode}: {}x{} in {:.0} ms", size.0, size.1, started.elapsed().as_secs_f64() * 1e3);
        println!("wrote {}", path.display());
    }
    Ok(())
}

fn print_plan(renderer: &Renderer) {
    let plan = renderer.plan();
    println!("plan {}:", plan.mode);
    for step in &plan.steps {
        println!("  pass {}", step.name());
    }
    let allocations = renderer.allocations();
    for (name, bytes) in &allocations {
        println!("  bytes {name} {bytes}");
    }
    println!("  bytes total {}", allocations.iter().map(|(_, b)| b).sum::<u64>());
}

fn main() -> ExitCode {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn,ssdo=info"))
        .format_timestamp(None)
        .init();
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Capture(args) => run_capture(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("ssdo: error: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}
