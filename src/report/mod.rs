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

pub mod metrics;
mod plot;
pub mod scenes;
mod table;

use std::path::PathBuf;
use std::time::Instant;

use glam::Vec3;

use crate::gpu::Gpu;
use crate::reference::{self, ReferenceScene, TraceSettings};
use crate::render::capture::{capture, CAPTURE_FORMAT};
use crate::render::readback::{read_depth, read_r16f, read_rgba16f};
use crate::render::{Mode, Renderer, SenderSky, Settings, Variant};
use crate::scene::{self, OrbitCamera, Scene, Skybox};
use crate::{Error, Result};

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
    /// Median GPU milliseconds of the whole frame.
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
        Some(path) => (scene::model::load_obj(path)?, None),
        None => scenes::by_name(&options.scene)?,
    };
    let sky_path = options.skybox.clone().or(scene_sky);
    let sky = match &sky_path {
        Some(path) if path.is_dir() => Skybox::load(path)?,
        Some(path) => return Err(Error::input(path, "skybox folder not found")),
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
    let depth = read_depth(gpu, &renderer.targets().depth.texture)?;
    let bvh = ReferenceScene::new(&scene.model);
    let target = crate::render::capture::output_texture(gpu, options.size);
    let view = target.create_view(&wgpu::TextureViewDescriptor::default());
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
        let truth = reference::Reference::mean(&a, &b);
        let valid: Vec<usize> = (0..truth.valid.len()).filter(|&i| truth.valid[i]).collect();
        // Nothing to measure is an error, not a table of zeros and infinite PSNRs.
        if valid.is_empty() {
            return Err(Error::Setting(format!(
                "the view shows no surface pixel that the ray tracer and the GPU agree on ({} background, {} \
                 silhouette, {} under a light's cube): nothing to measure",
                truth.valid.len() - truth.mismatched - truth.covered,
                truth.mismatched,
                truth.covered
            )));
        }
        // A sky so bright that the truth overflows 32-bit floats gives no number worth a row.
        if valid.iter().any(|&i| !truth.radiance(i, ambient).is_finite()) {
            let sky_name = sky_path.as_ref().map_or_else(|| "the sky".to_string(), |p| p.display().to_string());
            return Err(Error::Setting(format!(
                "{sky_name}: the ray-traced truth overflows 32-bit floats under this sky (radiance up to {:e}); \
                 scale the sky down",
                sky.max_value()
            )));
        }
        let half_difference = |f: &dyn Fn(&reference::Reference, usize) -> Vec3| {
            metrics::rmse(valid.iter().flat_map(|&i| {
                let (x, y) = (f(&a, i), f(&b, i));
                (0..3).map(move |c| (0.5 * x[c], 0.5 * y[c]))
            }))
        };
        let noise = NoiseFloor {
            hdr: half_difference(&|r, i| r.radiance(i, ambient)),
            directional: half_difference(&|r, i| r.directional(i)),
            ao: half_difference(&|r, i| Vec3::splat(r.ao[i])),
        };

        for variant in [Variant::Classic, Variant::Points, Variant::March] {
            // (mode, samples or slices, steps, blur, depth pyramid, bounce senders)
            let bounce = Some(base.sender_sky);
            let mut configs: Vec<(Mode, usize, usize, bool, bool, Option<SenderSky>)> = Vec::new();
            if r_index == 0 && variant != Variant::Points {
                // Off has no sampling pass: once for the sky-lit composite (under the default
                // variant's name; points is the same image), once for classic.
                configs.push((Mode::Off, 0, 0, false, false, None));
            }
            let counts: Vec<(usize, usize)> = if variant.marches() {
                options.march.clone()
            } else {
                options.samples.iter().map(|&n| (n, 0)).collect()
            };
            for mode in [Mode::Ssao, Mode::Ssdo, Mode::Both] {
                let bounce = if mode == Mode::Ssao { None } else { bounce };
                for &(samples, steps) in &counts {
                    configs.extend([
                        (mode, samples, steps, true, false, bounce),
                        (mode, samples, steps, false, false, bounce),
                    ]);
                    // The march once more with its far steps on the depth pyramid (blurred).
                    if variant.marches() && mode != Mode::Ssao {
                        configs.push((mode, samples, steps, true, true, bounce));
                    }
                    // The default settings with the bounce's other senders, and with no bounce.
                    if variant == Variant::default()
                        && mode != Mode::Ssao
                        && (samples, steps) == (base.slices, base.steps)
                    {
                        for other in SenderSky::ALL.map(Some).into_iter().chain([None]) {
                            if other != bounce {
                                configs.push((mode, samples, steps, true, false, other));
                            }
                        }
                    }
                }
            }
            for (mode, samples, steps, blur, depth_pyramid, bounce) in configs {
                // Every configuration renders the same lighting (the classic variant keeps its
                // own composite, not its own ambient), so all meet one truth.
                let (slices, steps_or_default) =
                    if variant.marches() { (samples, steps) } else { (base.slices, base.steps) };
                renderer.settings = Settings {
                    mode,
                    variant,
                    samples: if variant.marches() { base.samples } else { samples.max(1) },
                    slices,
                    steps: steps_or_default,
                    blur,
                    depth_pyramid,
                    radius: Some(radius),
                    sender_sky: bounce.unwrap_or(base.sender_sky),
                    // No bounce (`none`) is the bounce's strength at 0.
                    indirect_strength: if bounce.is_none() && mode.declaration().directional_occlusion {
                        0.0
                    } else {
                        base.indirect_strength
                    },
                    ..base
                };
                let ms = crate::render::timing::measure(gpu, &mut renderer, &camera, &view, options.frames)?.frame_ms;
                let image = capture(gpu, &mut renderer, &camera)?;
                let s = renderer.settings;
                // The half-float buffers hold radiance × pre-exposure: divided out here.
                let unexpose = 1.0 / renderer.pre_exposure();
                let targets = renderer.targets().occlusion();
                let directional =
                    targets.directional.as_ref().map(|t| read_rgba16f(gpu, &t.texture)).transpose()?.map(|d| {
                        d.into_iter()
                            .map(|p| [p[0] * unexpose, p[1] * unexpose, p[2] * unexpose, p[3]])
                            .collect::<Vec<_>>()
                    });
                let ao = match (&targets.ao, &directional) {
                    (Some(t), _) => Some(read_r16f(gpu, &t.texture)?),
                    (None, Some(d)) if mode.declaration().ambient_occlusion => Some(d.iter().map(|p| p[3]).collect()),
                    _ => None,
                };
                let hdr: Vec<Vec3> = read_rgba16f(gpu, &renderer.targets().hdr()?.texture)?
                    .into_iter()
                    .map(|p| Vec3::new(p[0], p[1], p[2]) * unexpose)
                    .collect();
                let against = |want: &dyn Fn(usize) -> Vec3| {
                    metrics::rmse(valid.iter().flat_map(|&i| {
                        let (got, want) = (hdr[i], want(i));
                        (0..3).map(move |c| (got[c], want[c]))
                    }))
                };
                let hdr_rmse = against(&|i| truth.radiance(i, ambient));
                let hdr_rmse_near = against(&|i| truth.radiance_near(i, ambient));
                let hdr_peak =
                    valid.iter().map(|&i| truth.radiance(i, ambient).max_element()).fold(1e-6f32, f32::max) as f64;
                let ao_rmse = ao.as_ref().map(|ao| metrics::rmse(valid.iter().map(|&i| (ao[i], truth.ao[i]))));
                let do_against = |want: &dyn Fn(usize) -> Vec3| {
                    directional.as_ref().map(|d| {
                        metrics::rmse(valid.iter().flat_map(|&i| {
                            let w = want(i);
                            (0..3).map(move |c| (d[i][c], w[c]))
                        }))
                    })
                };
                let do_rmse = do_against(&|i| truth.directional(i));
                let do_rmse_near = do_against(&|i| truth.directional_near(i));
                // The bounce alone (the DO-indirect view zeroes the sky), against the truth's:
                // a ratio of means, so noise cancels and only the estimator's bias remains.
                let bounce_ratio = if directional.is_some() && bounce.is_some() {
                    renderer.settings.view = crate::render::View::DoIndirect;
                    capture(gpu, &mut renderer, &camera)?;
                    renderer.settings.view = s.view;
                    let bounce =
                        renderer.targets().occlusion().directional.as_ref().map(|t| read_rgba16f(gpu, &t.texture));
                    let bounce = bounce.transpose()?.unwrap_or_default();
                    let mean = |f: &dyn Fn(usize) -> f32| {
                        valid.iter().map(|&i| f(i) as f64).sum::<f64>() / valid.len().max(1) as f64
                    };
                    let got =
                        mean(&|i| reference::luminance(Vec3::new(bounce[i][0], bounce[i][1], bounce[i][2]) * unexpose));
                    let want = mean(&|i| reference::luminance(truth.bounce[i]));
                    (want > 0.0).then(|| got / want)
                } else {
                    None
                };

                let gpu_image = image::DynamicImage::ImageRgba8(image).to_rgb8();
                let mut ref_image = gpu_image.clone();
                for &i in &valid {
                    let (x, y) = ((i as u32) % options.size.0, (i as u32) / options.size.0);
                    ref_image.put_pixel(x, y, image::Rgb(metrics::display(truth.radiance(i, ambient), s.exposure)));
                }
                let (flip, flip_map) = metrics::flip(&ref_image, &gpu_image, &truth.valid);
                let shown = (base.slices, base.steps);
                if variant == Variant::default()
                    && (samples, steps) == shown
                    && !depth_pyramid
                    && blur
                    && bounce == Some(base.sender_sky)
                    && mode == Mode::Both
                    && r_index == 0
                {
                    plot::write_maps(&options.out, &truth, &ao, &ref_image, &gpu_image, &flip_map)?;
                }
                rows.push(Row {
                    mode,
                    variant,
                    samples,
                    steps,
                    pyramid: depth_pyramid,
                    blur,
                    bounce: if mode == Mode::Ssao { None } else { bounce },
                    radius: if mode == Mode::Off { 0.0 } else { radius },
                    ms,
                    ao_rmse,
                    do_rmse,
                    do_rmse_near,
                    bounce_ratio,
                    hdr_rmse,
                    hdr_rmse_near,
                    hdr_psnr: metrics::psnr(hdr_rmse, hdr_peak),
                    flip,
                    pareto: false,
                });
                progress(&format!(
                    "{mode} {variant} {}, radius {radius:.3}, blur {blur}, bounce {}: {ms:.2} ms, HDR RMSE {hdr_rmse:.4}",
                    Row::count_label(variant, samples, steps, depth_pyramid),
                    Row::bounce_label(mode, bounce)
                ));
            }
        }
        if r_index == 0 {
            kept = Some((truth, noise));
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
