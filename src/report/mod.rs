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

mod maps;
pub(crate) mod measure;
pub mod metrics;
mod options;
mod pattern;
mod plot;
mod row;
pub use crate::scene::named as scenes;
pub mod sweep;
mod table;

use std::time::Instant;

use crate::gpu::Gpu;
use crate::headless::capture::{capture, CAPTURE_FORMAT};
use crate::headless::readback::read_depth;
use crate::reference;
use crate::render::{Mode, Renderer, Settings};
use crate::scene::{self, OrbitCamera, Scene, Skybox};
use crate::{Error, Result};
pub use options::{RadiusChoice, ReportOptions, TruthScene, MAX_SWEEP};
pub use pattern::{PatternSpread, Spread};
pub use row::{NoiseFloor, Row};
pub use sweep::{planned_configurations, Config};

/// The work a report plans, in one line for the log.
fn planned_work(options: &ReportOptions) -> String {
    let (w, h) = (options.on.size.0 as u64, options.on.size.1 as u64);
    format!(
        "planned: {} configurations × {} timed frames (and up to {} more where a row accumulates) at {w}x{h}, \
         and a truth of 2 × {} rays over {} pixels per radius",
        planned_configurations(options),
        options.frames + 2,
        2 * options.accumulate.iter().max().copied().unwrap_or(1),
        options.samples_per_pixel,
        w * h
    )
}

/// The progress steps [`run`] reports: two reference rows per pixel row and radius, and one
/// per configuration.
pub fn progress_steps(options: &ReportOptions) -> u64 {
    2 * options.on.size.1 as u64 * options.radii.len() as u64 + planned_configurations(options) as u64
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
    /// The default single frame's errors under each entry of the sample schedule.
    pub pattern: PatternSpread,
    /// The constant ambient radiance every configuration and the truth share.
    pub ambient: f32,
    pub default_radius: f32,
    /// The default Both configuration's error maps (PNG files by name), written with the tables.
    pub maps: Vec<(String, Vec<u8>)>,
}

/// The report's scene (its model, or `--model`), its lights, its sky (the scene's, or
/// `--skybox`, or the default) and the sky's name for messages.
pub(crate) fn load_scene(options: &ReportOptions) -> Result<(Scene, Skybox, String)> {
    let (mut model, scene_sky) = match &options.on.model {
        Some(path) => (scene::load_model_file(path)?, None),
        None => scenes::by_name(&options.on.scene)?,
    };
    if options.on.no_surface_maps {
        model.drop_surface_maps();
    }
    let sky_path = options.on.skybox.clone().or(scene_sky);
    let sky = match &sky_path {
        Some(path) => Skybox::load(path)?,
        None => scene::load_skybox(None)?,
    };
    let sky_name = sky_path.as_ref().map_or_else(|| "the sky".to_string(), |p| p.display().to_string());
    Ok((Scene::new(model, options.on.lights, options.on.seed), sky, sky_name))
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
    let features = crate::render::SceneFeatures::lit(options.on.lights);
    Renderer::check_memory(options.on.size, &Settings::default(), features, true, &Mode::ALL)?;
    log::info!("{}", planned_work(options));
    let (scene, sky, sky_name) = load_scene(options)?;
    let camera = OrbitCamera::framing(&scene.model.bounds);
    gpu.check_size(options.on.size.0, options.on.size.1)?;
    let base = Settings::default();
    let ambient = base.ambient;
    let mut renderer = Renderer::new(gpu, &scene, &sky, options.on.size, CAPTURE_FORMAT, base)?;
    renderer.keep_hdr(gpu, true);
    let timestamps = renderer.enable_timing(gpu);
    let default_radius = renderer.radius();

    // The G-buffer is the same in every mode: one frame gives the depth the reference checks.
    capture(gpu, &mut renderer, &camera)?;
    let depth = read_depth(gpu, &renderer.targets().depth().texture)?;
    let source = measure::TruthSource::new(&scene, &sky, &sky_name, options, &base);
    let target = crate::headless::capture::output_texture(gpu, options.on.size);
    let view = target.create_view(&wgpu::TextureViewDescriptor::default());
    let bench = measure::Bench { gpu, camera: &camera, view: &view, options, ambient, diagnostics: true, timed: true };
    let mut rows = Vec::new();
    let mut reference_seconds = 0.0;
    let mut kept = None;
    let mut map_files = Vec::new();
    for (r_index, choice) in options.radii.iter().enumerate() {
        let radius = choice.resolve(default_radius);
        let started = Instant::now();
        let truth = source.trace(&camera, &depth, radius, &|| progress("reference row"))?;
        reference_seconds += started.elapsed().as_secs_f64();
        for config in sweep::configurations(options, r_index == 0) {
            let maps = (r_index == 0 && config.is_the_default_both()).then_some(&mut map_files);
            let mut row = bench.measure(&mut renderer, config, radius, &truth, maps)?;
            // (The radius as the knob holds it: a multiple of the scene's default.)
            row.config.knobs.radius_scale = radius / default_radius;
            progress(&row.progress_line());
            rows.push(row);
        }
        if let (0, Some(preset)) = (r_index, &options.preset) {
            let (config, scale) = Config::of_knobs(preset.mode, &preset.knobs);
            let mut row = bench.measure(&mut renderer, config, scale * default_radius, &truth, None)?;
            row.preset = Some(preset.name.clone());
            row.config.knobs.radius_scale = scale;
            progress(&row.progress_line());
            rows.push(row);
        }
        if r_index == 0 {
            let pattern = pattern::measure(gpu, &mut renderer, &camera, (&truth, radius, ambient))?;
            log::info!("{}", pattern.line());
            kept = Some((truth.reference, truth.noise, pattern));
        }
    }
    gpu.check()?;
    mark_pareto(&mut rows);
    rows.sort_by(|a, b| a.ms.total_cmp(&b.ms));
    let (reference, noise, pattern) =
        kept.ok_or_else(|| Error::Setting("--radius: give at least one radius".into()))?;
    Ok(Report {
        rows,
        device: gpu.describe(),
        software: gpu.is_software(),
        timing: if timestamps { "GPU timestamp queries" } else { "synchronised wall time" },
        reference_seconds,
        reference,
        noise,
        pattern,
        ambient,
        default_radius,
        maps: map_files,
    })
}
