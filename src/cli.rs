//! The command line's arguments and their checks: every flag, its default and the range it is
//! refused outside of (with the range in the message). `main.rs` runs the commands.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

use ssdo::render::{Mode, Settings, Variant, View};
use ssdo::scene::{self, OrbitCamera, Scene};
use ssdo::{Error, Result};

#[derive(Parser)]
#[command(name = "ssdo", version, about = "Screen-space directional occlusion renderer (wgpu)")]
pub(crate) struct Cli {
    /// Without a command, the viewer opens with its defaults.
    #[command(subcommand)]
    pub(crate) command: Option<Command>,
}

#[derive(Subcommand)]
pub(crate) enum Command {
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
pub(crate) struct Size(pub(crate) u32, pub(crate) u32);

pub(crate) fn parse_size(s: &str) -> std::result::Result<Size, String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(|| format!("'{s}' is not WIDTHxHEIGHT"))?;
    let parse = |v: &str| v.trim().parse::<u32>().map_err(|_| format!("'{s}' is not WIDTHxHEIGHT"));
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

pub(crate) fn parse_variant(s: &str) -> std::result::Result<Variant, String> {
    s.parse::<Variant>().map_err(|e| e.to_string())
}

pub(crate) fn parse_view(s: &str) -> std::result::Result<View, String> {
    s.parse::<View>().map_err(|e| e.to_string())
}

#[derive(Args)]
pub(crate) struct SceneArgs {
    /// model: the model framed by the orbit camera; room: the model lying on the floor of a closed
    /// room that fills the screen, seen by a fixed camera (the classic SSAO chapter's set-up)
    #[arg(long = "scene", default_value = "model", value_parser = parse_layout)]
    pub(crate) layout: scene::Layout,
    /// With --scene room and no --model: the built-in figure's triangle count [default: 50000]
    #[arg(long)]
    pub(crate) triangles: Option<usize>,
    /// OBJ model to load [default: models/cornell/cornell.obj]
    #[arg(long)]
    pub(crate) model: Option<PathBuf>,
    /// Skybox folder with six faces [default: skyboxes/day]
    #[arg(long)]
    pub(crate) skybox: Option<PathBuf>,
    /// Number of random point lights
    #[arg(long, default_value_t = scene::DEFAULT_LIGHTS)]
    pub(crate) lights: usize,
    /// Seed for the lights' colours and positions
    #[arg(long, default_value_t = 1)]
    pub(crate) seed: u64,
    /// Camera yaw around the model in degrees [default: 35]
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) yaw: Option<f32>,
    /// Camera elevation in degrees [default: 22]
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) pitch: Option<f32>,
    /// Camera distance from the model's centre [default: frames the model]
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) distance: Option<f32>,
    /// Near plane distance [default: a thousandth of the camera distance]
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) near: Option<f32>,
    /// Far plane distance, or inf [default: inf]
    #[arg(long, value_parser = parse_far)]
    pub(crate) far: Option<f32>,
    /// Scale the model by this factor (defaults scale with it)
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub(crate) scale: f32,
}

pub(crate) fn parse_layout(s: &str) -> std::result::Result<scene::Layout, String> {
    s.parse::<scene::Layout>().map_err(|e| e.to_string())
}

pub(crate) fn parse_far(s: &str) -> std::result::Result<f32, String> {
    if s.eq_ignore_ascii_case("inf") {
        return Ok(f32::INFINITY);
    }
    s.parse::<f32>().map_err(|_| format!("'{s}' is not a number or inf"))
}

#[derive(Args)]
pub(crate) struct RenderArgs {
    /// Algorithm family: march (the default), points (the paper's point sampling) or classic (the source chapters' SSAO and SSDO)
    #[arg(long, default_value = "default", value_parser = parse_variant)]
    pub(crate) variant: Variant,
    /// Samples per pixel of the points and classic variants, 1-256 [default: 16; classic 64]
    #[arg(long)]
    pub(crate) samples: Option<usize>,
    /// The march: slices (directions around the view vector) per pixel, 1-32
    #[arg(long, default_value_t = 2)]
    pub(crate) slices: usize,
    /// The march: steps along each side of a slice, 1-64 (half within the radius)
    #[arg(long, default_value_t = 12)]
    pub(crate) steps: usize,
    /// The march's reach, in model units [default: 24 radii]
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) reach: Option<f32>,
    /// The march's surface thickness, in model units [default: 1 radius]
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) thickness: Option<f32>,
    /// The march's far steps read a closest-depth pyramid (off: it over-occludes, see README)
    #[arg(long)]
    pub(crate) depth_pyramid: bool,
    /// Sampling radius in model units [default: a tenth of the scene's bounding radius]
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) radius: Option<f32>,
    /// Depth bias of the occlusion test, as a fraction of the radius
    #[arg(long, default_value_t = 0.03, allow_negative_numbers = true)]
    pub(crate) bias: f32,
    /// How much of the AO is applied (0 to 1)
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub(crate) ao_strength: f32,
    /// AO is raised to this power
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub(crate) ao_power: f32,
    /// Multiplier on SSDO's sky light
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub(crate) sky_strength: f32,
    /// Multiplier on SSDO's indirect bounce
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub(crate) indirect_strength: f32,
    /// Leave the AO/DO noise unfiltered
    #[arg(long)]
    pub(crate) no_blur: bool,
    /// Exposure applied before tone mapping
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub(crate) exposure: f32,
    /// Constant ambient radiance, on top of the sky [default: 0.1; classic 0.5]
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) ambient: Option<f32>,
    /// Multiplier on the sky's radiance
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub(crate) sky_scale: f32,
    /// What to show: final, albedo, normals, depth, ao, do-direct, do-indirect, lighting
    #[arg(long, default_value = "final", value_parser = parse_view)]
    pub(crate) view: View,
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
    #[arg(long, default_value = "800x600", value_parser = parse_size)]
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
}

#[derive(Args)]
pub(crate) struct ViewArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArgs,
    #[command(flatten)]
    pub(crate) render: RenderArgs,
    /// Mode to start in: off, ssao, ssdo or both
    #[arg(long, default_value = "both", value_parser = parse_single_mode)]
    pub(crate) mode: Mode,
    /// Window size, WIDTHxHEIGHT (the 3D view is the window less the 300-pixel panel)
    #[arg(long, default_value = "1280x720", value_parser = parse_size)]
    pub(crate) size: Size,
    /// Where F12 screenshots and C comparisons are written
    #[arg(long, default_value = "screenshots")]
    pub(crate) screenshot_dir: PathBuf,
}

#[derive(Args)]
pub(crate) struct ReportArgs {
    /// Scene: cornell (the default scene), crevices (thin features, deep slots), open (redblue
    /// sky) or stairs (stairs under an overhang, a scene nobody tuned on)
    #[arg(long, default_value = "cornell")]
    pub(crate) scene: String,
    /// An OBJ model instead of a named scene
    #[arg(long)]
    pub(crate) model: Option<PathBuf>,
    /// Skybox folder [default: the scene's own sky]
    #[arg(long)]
    pub(crate) skybox: Option<PathBuf>,
    /// Image size, WIDTHxHEIGHT
    #[arg(long, default_value = "320x240", value_parser = parse_size)]
    pub(crate) size: Size,
    /// Sample counts of the points and classic variants to sweep, comma-separated
    #[arg(long, default_value = "4,8,16,32,64", value_delimiter = ',')]
    pub(crate) samples: Vec<usize>,
    /// Slices x steps of the march variant to sweep, comma-separated
    #[arg(long, default_value = "1x8,2x8,2x12,4x16", value_delimiter = ',', value_parser = parse_march)]
    pub(crate) march: Vec<(usize, usize)>,
    /// Sampling radii to sweep, comma-separated: multiples of the scene's default (2x) or lengths
    /// in model units (0.3)
    #[arg(long, default_value = "1x", value_delimiter = ',')]
    pub(crate) radius: Vec<ssdo::report::RadiusChoice>,
    /// Reference rays per pixel, in each of the two independent traces (at least 2)
    #[arg(long, default_value_t = 256)]
    pub(crate) spp: u32,
    /// Frames timed per configuration (after two warm-up frames)
    #[arg(long, default_value_t = 20)]
    pub(crate) frames: usize,
    /// Number of random point lights
    #[arg(long, default_value_t = scene::DEFAULT_LIGHTS)]
    pub(crate) lights: usize,
    /// Seed of the lights and of the reference's rays
    #[arg(long, default_value_t = 1)]
    pub(crate) seed: u64,
    /// Output folder for report.csv, report.md, report.png and the error maps
    #[arg(long, default_value = "report")]
    pub(crate) out: PathBuf,
}

/// `4x8`: slices × steps of the march.
pub(crate) fn parse_march(s: &str) -> std::result::Result<(usize, usize), String> {
    let (a, b) = s.split_once(['x', 'X']).ok_or_else(|| format!("'{s}': expected SLICESxSTEPS like 4x8"))?;
    let parse = |t: &str| t.trim().parse::<usize>().map_err(|_| format!("'{s}': expected SLICESxSTEPS like 4x8"));
    Ok((parse(a)?, parse(b)?))
}

pub(crate) fn parse_single_mode(s: &str) -> std::result::Result<Mode, String> {
    s.parse::<Mode>().map_err(|e| e.to_string())
}

#[derive(Args)]
pub(crate) struct BenchArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArgs,
    #[command(flatten)]
    pub(crate) render: RenderArgs,
    /// Image size, WIDTHxHEIGHT
    #[arg(long, default_value = "800x600", value_parser = parse_size)]
    pub(crate) size: Size,
    /// Frames measured per mode (after two warm-up frames)
    #[arg(long, default_value_t = 20)]
    pub(crate) frames: usize,
    /// Print JSON instead of a table
    #[arg(long)]
    pub(crate) json: bool,
    /// Time the HDR path (what the report, --raw and --stats take): the composite writes HDR and
    /// the sky and the tone map are passes of their own
    #[arg(long)]
    pub(crate) hdr: bool,
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

/// The largest radiance-like setting (ambient, strengths, exposure, sky scale) taken: beyond it
/// a frame's light no longer fits even pre-exposed half floats, and the sky and the light cubes
/// would turn black instead of white.
pub(crate) const MAX_GAIN: f32 = 1e6;
/// The largest length setting (radius, reach, thickness), in model units.
pub(crate) const MAX_LENGTH: f32 = 1e9;

pub(crate) fn non_negative(name: &str, value: f32) -> Result<f32> {
    in_range(name, value, 0.0, MAX_LENGTH)
}

/// `value` if it is finite and within [lo, hi]; otherwise an error naming the flag and the range.
pub(crate) fn in_range(name: &str, value: f32, lo: f32, hi: f32) -> Result<f32> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(Error::Setting(format!("--{name} {}: must be a finite number from {} to {}", num(value), num(lo), num(hi))))
    }
}

/// A number as people write it: 0.25, 1e6, 3.0e-5 (not 30 digits of a huge or tiny float).
pub(crate) fn num(v: f32) -> String {
    if v != 0.0 && v.is_finite() && !(1e-4..1e6).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

impl SceneArgs {
    pub(crate) fn load(&self) -> Result<(Scene, scene::Skybox)> {
        // Beyond these, positions lose the precision the depth buffer and the march need.
        in_range("scale", self.scale, 1e-6, 1e6)?;
        let model = crate::with_spinner("loading the model", || {
            self.layout.load(self.model.as_deref(), self.scale, self.triangles)
        })?;
        let sky = crate::with_spinner("loading the sky", || scene::load_skybox(self.skybox.as_deref()))?;
        Ok((Scene::new(model, self.lights, self.seed), sky))
    }

    pub(crate) fn camera(&self, scene: &Scene) -> Result<OrbitCamera> {
        let mut camera = self.layout.camera(&scene.model.bounds);
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
    pub(crate) fn settings(&self, mode: Mode) -> Result<Settings> {
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
