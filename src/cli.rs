//! The command line's arguments and their checks: every flag, its default and the range it is
//! refused outside of (with the range in the message). `main.rs` runs the commands.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

use ssdo::render::Mode;
use ssdo::scene;
pub(crate) use ssdo::spec::{RenderArgs, SceneArgs};

#[derive(Parser)]
#[command(name = "ssdo", version, about = "Screen-space directional occlusion renderer (wgpu)")]
pub(crate) struct Cli {
    /// Without a command, the viewer opens with its defaults.
    #[command(subcommand)]
    pub(crate) command: Option<Command>,
    /// Memory the run may use, such as 4G or 512M [default: half of this machine's memory]
    #[arg(long, global = true, value_parser = ssdo::budget::parse_size, allow_hyphen_values = true)]
    pub(crate) memory_budget: Option<u64>,
}

#[derive(Subcommand)]
pub(crate) enum Command {
    /// Open the interactive viewer (the default).
    // A negative number is a value, for the flag's range check to refuse by name.
    #[command(allow_negative_numbers = true)]
    View(ViewArgs),
    /// Render the scene offscreen and write PNGs: <out>/<mode>.png (and compare.png for all).
    // A negative number is a value, for the flag's range check to refuse by name.
    #[command(allow_negative_numbers = true)]
    Capture(CaptureArgs),
    /// Render each mode repeatedly and print per-pass GPU times.
    // A negative number is a value, for the flag's range check to refuse by name.
    #[command(allow_negative_numbers = true)]
    Bench(BenchArgs),
    /// Error of every mode and setting against a CPU ray-traced reference, against GPU time.
    // A negative number is a value, for the flag's range check to refuse by name.
    #[command(allow_negative_numbers = true)]
    Report(ReportArgs),
    /// The best setting a frame budget buys on this scene and device, measured against the
    /// report's truth: the front, the pick as a preset file and as a capture command.
    // A negative number is a value, for the flag's range check to refuse by name.
    #[command(allow_negative_numbers = true)]
    Tune(TuneArgs),
}

/// The scene a report or tune measures against its truth: a named scene or a model, its sky, the
/// image size and the lights.
#[derive(Args)]
pub(crate) struct TruthSceneArgs {
    /// Scene: cornell (the default scene), crevices (thin features, deep slots), fence (a
    /// checker-cut fence), open (redblue sky) or stairs (stairs under an overhang, a scene nobody
    /// tuned on)
    #[arg(long, default_value = "cornell")]
    pub(crate) scene: String,
    /// A model (OBJ or glTF) instead of a named scene
    #[arg(long)]
    pub(crate) model: Option<PathBuf>,
    /// Leave out the model's normal maps and alpha cutouts, on the GPU and in the truth
    #[arg(long)]
    pub(crate) no_surface_maps: bool,
    /// Skybox folder [default: the scene's own sky]
    #[arg(long)]
    pub(crate) skybox: Option<PathBuf>,
    /// Image size, WIDTHxHEIGHT
    #[arg(long, default_value = "320x240", value_parser = parse_size, allow_hyphen_values = true)]
    pub(crate) size: Size,
    /// Number of random point lights, 0-4096
    #[arg(long, default_value_t = scene::DEFAULT_LIGHTS, value_parser = ssdo::spec::parse_lights)]
    pub(crate) lights: usize,
    /// Seed of the lights and of the reference's rays
    #[arg(long, default_value_t = 1, value_parser = ssdo::spec::parse_seed)]
    pub(crate) seed: u64,
}

impl TruthSceneArgs {
    /// The flags as the library's scene to measure on.
    fn scene(&self) -> ssdo::report::TruthScene {
        ssdo::report::TruthScene {
            scene: self.scene.clone(),
            model: self.model.clone(),
            no_surface_maps: self.no_surface_maps,
            skybox: self.skybox.clone(),
            size: (self.size.0, self.size.1),
            lights: self.lights,
            seed: self.seed,
        }
    }
}

#[derive(Args)]
pub(crate) struct TuneArgs {
    /// The frame budget in GPU milliseconds
    #[arg(long, conflicts_with = "budget_off")]
    pub(crate) budget_ms: Option<f64>,
    /// The frame budget as a multiple of the Off frame's time, measured in the same run
    #[arg(long)]
    pub(crate) budget_off: Option<f64>,
    /// Pick the cheapest setting whose HDR RMSE is at most this (within the budget, if given)
    #[arg(long)]
    pub(crate) target_error: Option<f64>,
    /// Mode to tune: ssao, ssdo or both
    #[arg(long, default_value = "ssdo")]
    pub(crate) mode: Mode,
    #[command(flatten)]
    pub(crate) on: TruthSceneArgs,
    /// Views measured: the report's, and the others turned about the model up to --spread
    /// degrees either side, 1-8
    #[arg(long, default_value_t = 3, value_parser = |s: &str| ssdo::spec::whole_number(s, (1, ssdo::tune::MAX_VIEWS)))]
    pub(crate) views: usize,
    /// Degrees the farthest views turn from the report's, 0-90
    #[arg(long, default_value_t = 20.0)]
    pub(crate) spread: f32,
    /// Frames timed per setting, on the report's view (after two warm-up frames), 1-10000
    #[arg(long, default_value_t = 10, value_parser = parse_frames)]
    pub(crate) frames: usize,
    /// Reference rays per pixel, in each of the two traces of each view, 2-65536
    #[arg(long, default_value_t = 128, value_parser = parse_spp)]
    pub(crate) spp: u32,
    /// The most settings the search measures, 0-400 (0: measure the --also presets only)
    #[arg(long, default_value_t = 60, value_parser = |s: &str| ssdo::spec::whole_number(s, (0, ssdo::tune::MAX_SETTINGS)))]
    pub(crate) max_settings: usize,
    /// Also measure this preset file (repeatable): its figures here, picked if it is the best
    #[arg(long)]
    pub(crate) also: Vec<PathBuf>,
    /// Also measure the built-in quality levels
    #[arg(long)]
    pub(crate) also_levels: bool,
    /// Output folder for tune.md, front.csv and preset.json
    #[arg(long, default_value = "tune")]
    pub(crate) out: PathBuf,
}

impl TuneArgs {
    pub(crate) fn options(&self) -> ssdo::Result<ssdo::tune::TuneOptions> {
        use ssdo::preset::{Preset, Quality};
        use ssdo::tune::Budget;
        let mut also = self.also.iter().map(|p| Preset::load(p)).collect::<ssdo::Result<Vec<_>>>()?;
        if self.also_levels {
            also.extend(Quality::ALL.map(Quality::preset));
        }
        Ok(ssdo::tune::TuneOptions {
            on: self.on.scene(),
            mode: self.mode,
            budget: self.budget_ms.map(Budget::Ms).or(self.budget_off.map(Budget::OffTimes)),
            target_error: self.target_error,
            views: self.views,
            spread: self.spread,
            frames: self.frames,
            samples_per_pixel: self.spp,
            max_settings: self.max_settings,
            also,
            out: self.out.clone(),
        })
    }
}

/// A size written as WIDTHxHEIGHT.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Size(pub(crate) u32, pub(crate) u32);

pub(crate) fn parse_size(s: &str) -> std::result::Result<Size, String> {
    let bad = || format!("'{s}' is not WIDTHxHEIGHT (two whole numbers of pixels, such as 800x600)");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let parse = |v: &str| v.trim().parse::<u32>().map_err(|_| bad());
    Ok(Size(parse(w)?, parse(h)?))
}

/// Which modes to render: one, or `all` four.
#[derive(Clone, Copy, Debug)]
pub(crate) enum ModeChoice {
    One(Mode),
    All,
}

pub(crate) fn parse_mode(s: &str) -> std::result::Result<ModeChoice, String> {
    if s.eq_ignore_ascii_case("all") {
        return Ok(ModeChoice::All);
    }
    s.parse::<Mode>().map(ModeChoice::One).map_err(|e| e.to_string())
}

#[derive(Args)]
pub(crate) struct CaptureArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArgs,
    #[command(flatten)]
    pub(crate) render: RenderArgs,
    /// Mode to render: off, ssao, ssdo, both, or all (also writes compare.png)
    #[arg(long, default_value = "all", value_parser = parse_mode)]
    pub(crate) mode: ModeChoice,
    /// Image size, WIDTHxHEIGHT
    #[arg(long, default_value = "800x600", value_parser = parse_size, allow_hyphen_values = true)]
    pub(crate) size: Size,
    /// Output folder
    #[arg(long, default_value = "out")]
    pub(crate) out: PathBuf,
    /// Print each mode's passes, in order, and the bytes each target uses
    #[arg(long)]
    pub(crate) print_plan: bool,
    /// Print min, max, mean and non-finite count of each linear buffer (AO, DO, HDR)
    #[arg(long)]
    pub(crate) stats: bool,
    /// With --stats: print JSON
    #[arg(long)]
    pub(crate) json: bool,
    /// Also write the linear HDR image as <out>/<mode>.exr
    #[arg(long)]
    pub(crate) raw: bool,
    /// Also trace the view's truth (as the report's): write truth.png and error_<mode>.png, add
    /// the truth to compare.png, and print each mode's HDR RMSE, DO RMSE and FLIP against it
    #[arg(long)]
    pub(crate) truth: bool,
    /// With --truth: rays per pixel in each of the truth's two traces, 2-65536
    #[arg(long, default_value_t = 256, value_parser = parse_spp, requires = "truth")]
    pub(crate) spp: u32,
}

#[derive(Args)]
pub(crate) struct ViewArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArgs,
    #[command(flatten)]
    pub(crate) render: RenderArgs,
    /// Mode to start in: off, ssao, ssdo or both
    #[arg(long, default_value = "both")]
    pub(crate) mode: Mode,
    /// Window size, WIDTHxHEIGHT (the 3D view is the window less the 300-pixel panel)
    #[arg(long, default_value = "1280x720", value_parser = parse_size, allow_hyphen_values = true)]
    pub(crate) size: Size,
    /// Where F12 screenshots and C comparisons are written
    #[arg(long, default_value = "screenshots")]
    pub(crate) screenshot_dir: PathBuf,
}

impl ReportArgs {
    /// The report's options from the flags (checked by `ReportOptions::check`).
    pub(crate) fn options(&self) -> ssdo::report::ReportOptions {
        ssdo::report::ReportOptions {
            on: self.on.scene(),
            samples: self.samples.clone(),
            march: self.march.clone(),
            radii: self.radius.clone(),
            samples_per_pixel: self.spp,
            frames: self.frames,
            accumulate: self.accumulate.clone(),
            orbit: self.orbit,
            out: self.out.clone(),
            preset: None,
        }
    }

    /// The preset to measure beside the sweep: `--preset FILE` or a `--quality` level.
    pub(crate) fn preset(&self) -> ssdo::Result<Option<ssdo::preset::Preset>> {
        ssdo::preset::Preset::chosen(self.preset.as_deref(), self.quality)
    }
}

#[derive(Args)]
pub(crate) struct ReportArgs {
    /// Also measure this preset file's setting (as `ssdo tune` writes), marked P in the table
    #[arg(long, conflicts_with = "quality")]
    pub(crate) preset: Option<PathBuf>,
    /// Also measure a built-in quality level (low, medium, high, ultra), marked P in the table
    #[arg(long)]
    pub(crate) quality: Option<ssdo::preset::Quality>,
    #[command(flatten)]
    pub(crate) on: TruthSceneArgs,
    /// Sample counts of the points and classic variants to sweep (the help states the range)
    #[arg(long, default_value = "4,8,16,32,64", value_delimiter = ',')]
    pub(crate) samples: Vec<usize>,
    /// Slices x steps of the march variant to sweep (the help states the ranges)
    #[arg(long, default_value = "1x8,2x12,2x16,4x16", value_delimiter = ',', value_parser = parse_march)]
    pub(crate) march: Vec<(usize, usize)>,
    /// Sampling radii to sweep, comma-separated: multiples of the scene's default (2x) or lengths
    /// in model units (0.3); at most 16
    #[arg(long, default_value = "1x", value_delimiter = ',')]
    pub(crate) radius: Vec<ssdo::report::RadiusChoice>,
    /// Reference rays per pixel, in each of the two independent traces, 2-65536
    #[arg(long, default_value_t = 256, value_parser = parse_spp)]
    pub(crate) spp: u32,
    /// Frames timed per configuration (after two warm-up frames), 1-10000
    #[arg(long, default_value_t = 20, value_parser = parse_frames)]
    pub(crate) frames: usize,
    /// Frames averaged to sweep, comma-separated (each 1-64; 1 is a single frame); each
    /// accumulated row renders that many frames and measures the last
    #[arg(long, default_value = "1,4,16", value_delimiter = ',')]
    pub(crate) accumulate: Vec<usize>,
    /// Degrees the camera turns about the model each frame of an accumulated row, ending in the
    /// truth's view: those rows are measured still and turning, and each mode's default setting
    /// also after a cut (as many frames first from 90° around the model; 0: still only)
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub(crate) orbit: f32,
    /// Output folder for report.csv, report.md, report.png and the error maps
    #[arg(long, default_value = "report")]
    pub(crate) out: PathBuf,
}

/// The most frames a bench or report times per configuration.
pub(crate) const MAX_FRAMES: u64 = 10_000;
/// The most reference rays per pixel in each trace.
pub(crate) const MAX_SPP: u64 = 65_536;
/// The most values in each of the report's sweep lists.
pub(crate) use ssdo::report::MAX_SWEEP;

pub(crate) fn parse_frames(s: &str) -> std::result::Result<usize, String> {
    ssdo::spec::count_in(s, 1, MAX_FRAMES).map(|n| n as usize)
}

pub(crate) fn parse_spp(s: &str) -> std::result::Result<u32, String> {
    ssdo::spec::count_in(s, 2, MAX_SPP).map(|n| n as u32)
}

/// `4x8`: slices × steps of the march.
pub(crate) fn parse_march(s: &str) -> std::result::Result<(usize, usize), String> {
    let (a, b) = s.split_once(['x', 'X']).ok_or_else(|| format!("'{s}': expected SLICESxSTEPS like 4x8"))?;
    let parse = |t: &str| t.trim().parse::<usize>().map_err(|_| format!("'{s}': expected SLICESxSTEPS like 4x8"));
    Ok((parse(a)?, parse(b)?))
}

#[derive(Args)]
pub(crate) struct BenchArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArgs,
    #[command(flatten)]
    pub(crate) render: RenderArgs,
    /// Image size, WIDTHxHEIGHT
    #[arg(long, default_value = "800x600", value_parser = parse_size, allow_hyphen_values = true)]
    pub(crate) size: Size,
    /// Frames measured per mode (after two warm-up frames), 1-10000
    #[arg(long, default_value_t = 20, value_parser = parse_frames)]
    pub(crate) frames: usize,
    /// Print JSON instead of a table
    #[arg(long)]
    pub(crate) json: bool,
    /// Time the HDR path (what the report, --raw and --stats take): the composite writes HDR and
    /// the sky and the tone map are passes of their own
    #[arg(long)]
    pub(crate) hdr: bool,
    /// Degrees the camera turns about its target every frame, -180 to 180 (0: a still view,
    /// which stops blurring and reprojecting once it has settled) [default: 0]
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) orbit: Option<f32>,
}

impl ViewArgs {
    /// The viewer's arguments when `ssdo` is run without a command.
    pub(crate) fn parse_default() -> Self {
        #[derive(Parser)]
        struct Only {
            #[command(flatten)]
            view: ViewArgs,
        }
        Only::parse_from(["ssdo"]).view
    }
}
