//! The error-versus-run-time report: every mode × variant × sample count × blur × radius, timed
//! on the GPU and compared with one CPU-traced truth (`crate::reference`), written as CSV, a
//! Markdown table sorted by time and a log-log plot of error against milliseconds with the
//! Pareto front marked.
//!
//! **One truth for every mode**: the physical image under the scene's sky, lights and constant
//! ambient, with exact visibility at any distance and one bounce from any surface. Off, SSAO, SSDO
//! and SSAO+SSDO, default and classic, are all measured against it, so their errors are
//! comparable. The **within-R** image (occluders and senders beyond the sampling radius removed)
//! is a diagnostic beside it: the gap between the two errors is what a method's reach costs.
//!
//! Measured right: the GPU's half-float buffers hold radiance × pre-exposure, which is divided out
//! before any metric; RMSE, PSNR and FLIP are taken on the surfaces both renderers see
//! (background and silhouette pixels left out, and counted); the truth is the mean of two
//! independent traces, whose difference gives its own noise floor.

mod measure;
pub mod metrics;
mod plot;
pub mod scenes;
pub mod sweep;
mod table;

use std::path::PathBuf;
use std::time::Instant;

use crate::gpu::Gpu;
use crate::headless::capture::{capture, CAPTURE_FORMAT};
use crate::headless::readback::read_depth;
use crate::reference::{self, ReferenceScene, TraceSettings};
use crate::render::{Mode, Renderer, SenderSky, Settings, Variant};
use crate::scene::{self, OrbitCamera, Scene, Skybox};
use crate::{Error, Result};
pub use sweep::{planned_configurations, Config};

/// A sampling radius to sweep: a multiple of the scene's default, or a length in model units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RadiusChoice {
    Times(f32),
    Units(f32),
}

impl std::str::FromStr for RadiusChoice {
    type Err = Error;
    /// `2x` (twice the default radius) or `0.3` (model units).
    fn from_str(s: &str) -> Result<Self> {
        let bad = || Error::Setting(format!("--radius {s}: expected a length or a multiple of the default like 2x"));
        let (text, times) = match s.trim().strip_suffix(['x', 'X']) {
            Some(t) => (t, true),
            None => (s.trim(), false),
        };
        let value: f32 = text.parse().map_err(|_| bad())?;
        if !value.is_finite() || value <= 0.0 {
            return Err(bad());
        }
        Ok(if times { Self::Times(value) } else { Self::Units(value) })
    }
}

impl RadiusChoice {
    pub fn resolve(self, default: f32) -> f32 {
        match self {
            Self::Times(k) => k * default,
            Self::Units(r) => r,
        }
    }
}

/// What to sweep.
pub struct ReportOptions {
    pub scene: String,
    /// Overrides the scene's model with an OBJ file.
    pub model: Option<PathBuf>,
    pub skybox: Option<PathBuf>,
    pub size: (u32, u32),
    /// Sample counts of the points and classic variants.
    pub samples: Vec<usize>,
    /// Slices × steps of the march variant.
    pub march: Vec<(usize, usize)>,
    pub radii: Vec<RadiusChoice>,
    /// Reference rays per pixel in each of the two traces (at least 2).
    pub samples_per_pixel: u32,
    pub frames: usize,
    /// Frames averaged, each count a row (1: a single frame).
    pub accumulate: Vec<usize>,
    /// Degrees the camera turns about the model each accumulated frame (0: still rows only).
    pub orbit: f32,
    pub lights: usize,
    pub seed: u64,
    pub out: PathBuf,
}

/// One measured configuration.
#[derive(Clone, Debug)]
pub struct Row {
    pub mode: Mode,
    pub variant: Variant,
    /// Samples per pixel of the sampling pass (0 for Off, which has none); slices for the march.
    pub samples: usize,
    /// Steps per side of each slice (the march; 0 otherwise).
    pub steps: usize,
    /// The march's far steps read the depth pyramid.
    pub pyramid: bool,
    pub blur: bool,
    /// What lights the bounce's senders (DO modes); `None`: no bounce (`--indirect-strength 0`).
    pub bounce: Option<SenderSky>,
    /// Sampling radius in model units (0 for Off).
    pub radius: f32,
    /// Frames averaged, and the camera's turn a frame over them, in degrees.
    pub accumulate: usize,
    pub orbit: f32,
    /// The sampling pass at half resolution, upsampled.
    pub half: bool,
    /// Median GPU milliseconds of the whole frame (one frame, with accumulation running).
    pub ms: f64,
    /// AO against the within-R AO, its definition (a diagnostic).
    pub ao_rmse: Option<f64>,
    /// DO (sky light + bounce, before albedo) against the truth, and against the within-R image.
    pub do_rmse: Option<f64>,
    pub do_rmse_near: Option<f64>,
    /// The mean of the DO's bounce over the measured pixels, over the truth's (1 is unbiased).
    pub bounce_ratio: Option<f64>,
    /// Linear HDR radiance against the truth, and against the within-R image.
    pub hdr_rmse: f64,
    pub hdr_rmse_near: f64,
    pub hdr_psnr: f64,
    /// FLIP of the displayed images, on the valid surface pixels.
    pub flip: f64,
    /// No other row is both as fast and as accurate (HDR RMSE against the truth).
    pub pareto: bool,
}

/// The truth's own noise: RMSE of the mean of two independent traces (half their difference).
#[derive(Clone, Copy, Debug, Default)]
pub struct NoiseFloor {
    pub hdr: f64,
    pub directional: f64,
    pub ao: f64,
}

/// The report's result: rows and the facts printed with them.
pub struct Report {
    pub rows: Vec<Row>,
    pub device: String,
    pub software: bool,
    pub timing: &'static str,
    pub reference_seconds: f64,
    pub reference: reference::Reference,
    pub noise: NoiseFloor,
    /// The constant ambient radiance every configuration and the truth share.
    pub ambient: f32,
    pub default_radius: f32,
}

/// Marks the rows no other row beats on both time and HDR error.
fn mark_pareto(rows: &mut [Row]) {
    let points: Vec<(f64, f64)> = rows.iter().map(|r| (r.ms, r.hdr_rmse)).collect();
    for (i, row) in rows.iter_mut().enumerate() {
        let (ms, e) = points[i];
        row.pareto =
            !points.iter().enumerate().any(|(j, &(m2, e2))| j != i && m2 <= ms && e2 <= e && (m2 < ms || e2 < e));
    }
}

/// Runs the sweep. `progress` is told about each finished row of the reference, and each row.
pub fn run(gpu: &Gpu, options: &ReportOptions, progress: &(dyn Fn(&str) + Sync)) -> Result<Report> {
    if options.samples_per_pixel < 2 {
        return Err(Error::Setting(format!(
            "--spp {}: the reference needs at least 2 rays per pixel for an error estimate",
            options.samples_per_pixel
        )));
    }
    let features = crate::render::SceneFeatures { lights: options.lights };
    Renderer::check_memory(options.size, &Settings::default(), features, true, &Mode::ALL)?;
    let (model, scene_sky) = match &options.model {
        Some(path) => (scene::load_model_file(path)?, None),
        None => scenes::by_name(&options.scene)?,
    };
    let sky_path = options.skybox.clone().or(scene_sky);
    let sky = match &sky_path {
        Some(path) => Skybox::load(path)?,
        None => scene::load_skybox(None)?,
    };
    let scene = Scene::new(model, options.lights, options.seed);
    let camera = OrbitCamera::framing(&scene.model.bounds);
    gpu.check_size(options.size.0, options.size.1)?;
    let base = Settings::default();
    let ambient = base.ambient;
    let mut renderer = Renderer::new(gpu, &scene, &sky, options.size, CAPTURE_FORMAT, base)?;
    renderer.keep_hdr(gpu, true);
    let timestamps = renderer.enable_timing(gpu);
    let default_radius = renderer.radius();

    // The G-buffer is the same in every mode: one frame gives the depth the reference checks.
    capture(gpu, &mut renderer, &camera)?;
    let depth = read_depth(gpu, &renderer.targets().depth().texture)?;
    let bvh = ReferenceScene::new(&scene.model);
    let target = crate::headless::capture::output_texture(gpu, options.size);
    let view = target.create_view(&wgpu::TextureViewDescriptor::default());
    let bench = measure::Bench { gpu, camera: &camera, view: &view, options, ambient };
    let sky_name = sky_path.as_ref().map_or_else(|| "the sky".to_string(), |p| p.display().to_string());
    let mut rows = Vec::new();
    let mut reference_seconds = 0.0;
    let mut kept = None;
    for (r_index, choice) in options.radii.iter().enumerate() {
        let radius = choice.resolve(default_radius);
        let started = Instant::now();
        let tick = || progress("reference row");
        let trace = |seed: u64| {
            let settings = TraceSettings {
                samples_per_pixel: options.samples_per_pixel,
                seed,
                radius,
                sky_scale: base.sky_scale,
                ambient,
            };
            reference::trace(&bvh, &scene.lights, &scene.rig, &sky, &camera, options.size, &depth, &settings, &tick)
        };
        let (a, b) = (trace(options.seed), trace(options.seed ^ 0x5DEE_CE66_D1CE_4E5B));
        reference_seconds += started.elapsed().as_secs_f64();
        let truth = measure::Truth::from_traces(&a, &b, ambient, &sky_name, sky.max_value())?;
        for config in sweep::configurations(options, r_index == 0) {
            let maps = r_index == 0 && config.is_the_default_both();
            let row = bench.measure(&mut renderer, config, radius, &truth, maps)?;
            progress(&format!(
                "{} {} {}{}, radius {radius:.3}, blur {}, bounce {}, {} frames, orbit {}°: {:.2} ms, HDR RMSE {:.4}",
                row.mode,
                row.variant,
                Row::count_label(row.variant, row.samples, row.steps, row.pyramid),
                if row.half { " half" } else { "" },
                row.blur,
                Row::bounce_label(row.mode, config.bounce),
                row.accumulate,
                row.orbit,
                row.ms,
                row.hdr_rmse
            ));
            rows.push(row);
        }
        if r_index == 0 {
            kept = Some((truth.reference, truth.noise));
        }
    }
    gpu.check()?;
    mark_pareto(&mut rows);
    rows.sort_by(|a, b| a.ms.total_cmp(&b.ms));
    let (reference, noise) = kept.ok_or_else(|| Error::Setting("--radius: give at least one radius".into()))?;
    Ok(Report {
        rows,
        device: gpu.describe(),
        software: gpu.is_software(),
        timing: if timestamps { "GPU timestamp queries" } else { "synchronised wall time" },
        reference_seconds,
        reference,
        noise,
        ambient,
        default_radius,
    })
}
