//! The error-versus-run-time report: every mode × variant × sample count × blur setting, timed on
//! the GPU and compared with the CPU reference (`crate::reference`), written as CSV, a Markdown
//! table and a log-log plot of error against milliseconds.
//!
//! Each row is compared with a reference of its own lighting model (its mode, ambient and
//! strengths) with exact visibility, so the error is the screen-space estimate's, not a difference
//! of models. Linear errors are taken on the surfaces both renderers see (silhouette pixels where
//! the traced and rasterised surfaces differ are left out and counted); FLIP on the whole image.

pub mod metrics;
pub mod scenes;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use glam::Vec3;

use crate::gpu::Gpu;
use crate::reference::{self, ReferenceScene, TraceSettings};
use crate::render::capture::{capture, CAPTURE_FORMAT};
use crate::render::readback::{read_depth, read_r16f, read_rgba16f};
use crate::render::{Mode, Renderer, Settings, Variant};
use crate::scene::{self, OrbitCamera, Scene, Skybox};
use crate::{output, Error, Result};

/// What to sweep.
pub struct ReportOptions {
    pub scene: String,
    /// Overrides the scene's model with an OBJ file.
    pub model: Option<PathBuf>,
    pub skybox: Option<PathBuf>,
    pub size: (u32, u32),
    pub samples: Vec<usize>,
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
    pub samples: usize,
    pub blur: bool,
    /// Median GPU milliseconds of the whole frame.
    pub ms: f64,
    pub ao_rmse: Option<f64>,
    pub ao_psnr: Option<f64>,
    pub do_rmse: Option<f64>,
    pub do_psnr: Option<f64>,
    pub hdr_rmse: f64,
    pub hdr_psnr: f64,
    pub flip: f64,
}

/// The report's result: rows and the facts printed with them.
pub struct Report {
    pub rows: Vec<Row>,
    pub device: String,
    pub software: bool,
    pub timing: &'static str,
    pub reference_seconds: f64,
    pub reference: reference::Reference,
}

/// The reference's linear radiance for `settings`' lighting model at pixel `i`.
fn reference_radiance(r: &reference::Reference, i: usize, s: &Settings) -> Vec3 {
    let decl = s.mode.declaration();
    let ao = if decl.ambient_occlusion { r.ao[i] } else { 1.0 };
    let mut color = s.ambient * r.albedo[i] * ao + r.direct[i];
    if decl.directional_occlusion {
        color += r.albedo[i] * (r.sky[i] * s.sky_strength + r.bounce[i] * s.indirect_strength);
    }
    color
}

/// Runs the sweep. `progress` is told about each finished row of the reference, and each row.
pub fn run(gpu: &Gpu, options: &ReportOptions, progress: &(dyn Fn(&str) + Sync)) -> Result<Report> {
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
    let mut renderer = Renderer::new(gpu, &scene, &sky, options.size, CAPTURE_FORMAT, Settings::default())?;
    let timestamps = renderer.enable_timing(gpu);

    // The G-buffer is the same in every mode: one frame gives the depth the reference checks.
    capture(gpu, &mut renderer, &camera)?;
    let depth = read_depth(gpu, &renderer.targets().depth.texture)?;
    let trace_settings = TraceSettings {
        samples_per_pixel: options.samples_per_pixel,
        seed: options.seed,
        radius: renderer.radius(),
        sky_scale: renderer.settings.sky_scale,
    };
    let started = Instant::now();
    let bvh = ReferenceScene::new(&scene.model);
    let tick = || progress("reference row");
    let reference =
        reference::trace(&bvh, &scene.lights, &scene.rig, &sky, &camera, options.size, &depth, &trace_settings, &tick);
    let reference_seconds = started.elapsed().as_secs_f64();

    let target = crate::render::capture::output_texture(gpu, options.size);
    let view = target.create_view(&wgpu::TextureViewDescriptor::default());
    let valid: Vec<usize> = (0..reference.valid.len()).filter(|&i| reference.valid[i]).collect();
    let mut rows = Vec::new();
    for variant in [Variant::Classic, Variant::Default] {
        for mode in [Mode::Ssao, Mode::Ssdo, Mode::Both] {
            for &samples in &options.samples {
                for blur in [true, false] {
                    let base = if variant == Variant::Classic { Settings::classic() } else { Settings::default() };
                    renderer.settings = Settings { mode, samples, blur, ..base };
                    let ms =
                        crate::render::timing::measure(gpu, &mut renderer, &camera, &view, options.frames)?.frame_ms;
                    let image = capture(gpu, &mut renderer, &camera)?;
                    let s = renderer.settings;
                    let targets = renderer.targets().occlusion();
                    let directional =
                        targets.directional.as_ref().map(|t| read_rgba16f(gpu, &t.texture)).transpose()?;
                    let ao = match (&targets.ao, &directional) {
                        (Some(t), _) => Some(read_r16f(gpu, &t.texture)?),
                        (None, Some(d)) if mode.declaration().ambient_occlusion => {
                            Some(d.iter().map(|p| p[3]).collect())
                        }
                        _ => None,
                    };
                    let hdr = read_rgba16f(gpu, &renderer.targets().hdr.texture)?;

                    let ao_rmse = ao.as_ref().map(|ao| metrics::rmse(valid.iter().map(|&i| (ao[i], reference.ao[i]))));
                    let do_ref =
                        |i: usize| reference.sky[i] * s.sky_strength + reference.bounce[i] * s.indirect_strength;
                    let do_rmse = directional.as_ref().map(|d| {
                        metrics::rmse(valid.iter().flat_map(|&i| (0..3).map(move |c| (d[i][c], do_ref(i)[c]))))
                    });
                    let do_peak = valid.iter().map(|&i| do_ref(i).max_element()).fold(1e-6f32, f32::max) as f64;
                    let hdr = &hdr;
                    let hdr_rmse = metrics::rmse(valid.iter().flat_map(|&i| {
                        let want = reference_radiance(&reference, i, &s);
                        (0..3).map(move |c| (hdr[i][c], want[c]))
                    }));
                    let hdr_peak = valid
                        .iter()
                        .map(|&i| reference_radiance(&reference, i, &s).max_element())
                        .fold(1e-6f32, f32::max) as f64;

                    let gpu_image = image::DynamicImage::ImageRgba8(image).to_rgb8();
                    let mut ref_image = gpu_image.clone();
                    for &i in &valid {
                        let (x, y) = ((i as u32) % options.size.0, (i as u32) / options.size.0);
                        ref_image.put_pixel(
                            x,
                            y,
                            image::Rgb(metrics::display(reference_radiance(&reference, i, &s), s.exposure)),
                        );
                    }
                    let (flip, flip_map) = metrics::flip(&ref_image, &gpu_image);
                    if variant == Variant::Default && samples == 16 && blur && mode == Mode::Both {
                        write_maps(&options.out, &reference, &ao, &ref_image, &gpu_image, &flip_map)?;
                    }
                    rows.push(Row {
                        mode,
                        variant,
                        samples,
                        blur,
                        ms,
                        ao_psnr: ao_rmse.map(|e| metrics::psnr(e, 1.0)),
                        ao_rmse,
                        do_psnr: do_rmse.map(|e| metrics::psnr(e, do_peak)),
                        do_rmse,
                        hdr_rmse,
                        hdr_psnr: metrics::psnr(hdr_rmse, hdr_peak),
                        flip,
                    });
                    progress(&format!(
                        "{mode} {variant} {samples} samples, blur {blur}: {ms:.2} ms, HDR RMSE {hdr_rmse:.4}"
                    ));
                }
            }
        }
    }
    gpu.check()?;
    Ok(Report {
        rows,
        device: gpu.describe(),
        software: gpu.is_software(),
        timing: if timestamps { "GPU timestamp queries" } else { "synchronised wall time" },
        reference_seconds,
        reference,
    })
}

/// Error maps of the default Both configuration: AO error, the two displayed images, FLIP.
fn write_maps(
    out: &Path,
    reference: &reference::Reference,
    ao: &Option<Vec<f32>>,
    ref_image: &image::RgbImage,
    gpu_image: &image::RgbImage,
    flip_map: &image::RgbImage,
) -> Result<()> {
    let (w, h) = (reference.width, reference.height);
    let save = |name: &str, img: &image::RgbImage| {
        let rgba = image::DynamicImage::ImageRgb8(img.clone()).to_rgba8();
        output::save_png(&out.join(name), &rgba)
    };
    if let Some(ao) = ao {
        // Signed AO error: red where the GPU is darker than the truth, blue where lighter.
        let map = image::RgbImage::from_fn(w, h, |x, y| {
            let i = (y * w + x) as usize;
            if !reference.valid[i] {
                return image::Rgb([40, 40, 40]);
            }
            let e = ((ao[i] - reference.ao[i]) * 4.0).clamp(-1.0, 1.0);
            let v = (255.0 * e.abs()) as u8;
            if e < 0.0 {
                image::Rgb([255, 255 - v, 255 - v])
            } else {
                image::Rgb([255 - v, 255 - v, 255])
            }
        });
        save("error_ao_both_default_16.png", &map)?;
        let reference_ao = image::RgbImage::from_fn(w, h, |x, y| {
            let i = (y * w + x) as usize;
            let v = (reference.ao[i].clamp(0.0, 1.0) * 255.0) as u8;
            if reference.valid[i] {
                image::Rgb([v, v, v])
            } else {
                image::Rgb([40, 40, 40])
            }
        });
        save("reference_ao.png", &reference_ao)?;
    }
    save("reference_both_default.png", ref_image)?;
    save("gpu_both_default_16.png", gpu_image)?;
    save("error_flip_both_default_16.png", flip_map)
}

fn cell(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(String::new, |v| format!("{v:.digits$}"))
}

impl Report {
    pub fn csv(&self) -> String {
        let mut out =
            String::from("mode,variant,samples,blur,ms,ao_rmse,ao_psnr,do_rmse,do_psnr,hdr_rmse,hdr_psnr,flip\n");
        for r in &self.rows {
            let _ = writeln!(
                out,
                "{},{},{},{},{:.4},{},{},{},{},{:.6},{:.3},{:.5}",
                r.mode.name(),
                r.variant,
                r.samples,
                r.blur,
                r.ms,
                cell(r.ao_rmse, 6),
                cell(r.ao_psnr, 3),
                cell(r.do_rmse, 6),
                cell(r.do_psnr, 3),
                r.hdr_rmse,
                r.hdr_psnr,
                r.flip
            );
        }
        out
    }

    pub fn markdown(&self, options: &ReportOptions) -> String {
        let date = jiff::Timestamp::now().to_zoned(jiff::tz::TimeZone::UTC).strftime("%Y-%m-%d %H:%M UTC").to_string();
        let r = &self.reference;
        let mut out = format!(
            "# ssdo error-versus-time report\n\n- date: {date}\n- device: {}{}\n- timing: {}, median of {} frames\n\
             - scene: {}, {}x{}, {} lights (seed {})\n- reference: {} rays per pixel, {:.1} s; its own standard error: \
             AO {:.4}, sky {:.4}, bounce {:.4}; {} silhouette pixels left out\n\n",
            self.device,
            if self.software { " (a CPU rasteriser, not a GPU)" } else { "" },
            self.timing,
            options.frames,
            options.model.as_ref().map_or(options.scene.clone(), |p| p.display().to_string()),
            options.size.0,
            options.size.1,
            options.lights,
            options.seed,
            options.samples_per_pixel,
            self.reference_seconds,
            r.ao_error,
            r.sky_error,
            r.bounce_error,
            r.mismatched,
        );
        out.push_str("| mode | variant | samples | blur | ms | AO RMSE | AO PSNR | DO RMSE | DO PSNR | HDR RMSE | HDR PSNR | FLIP |\n");
        out.push_str("|---|---|--:|---|--:|--:|--:|--:|--:|--:|--:|--:|\n");
        for row in &self.rows {
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} | {:.2} | {} | {} | {} | {} | {:.4} | {:.2} | {:.4} |",
                row.mode.name(),
                row.variant,
                row.samples,
                if row.blur { "on" } else { "off" },
                row.ms,
                cell(row.ao_rmse, 4),
                cell(row.ao_psnr, 2),
                cell(row.do_rmse, 4),
                cell(row.do_psnr, 2),
                row.hdr_rmse,
                row.hdr_psnr,
                row.flip
            );
        }
        out
    }

    /// Log-log plot of HDR RMSE against milliseconds, one line per mode and variant (blurred).
    pub fn plot(&self, path: &Path) -> Result<()> {
        use plotters::prelude::*;
        let (w, h) = (960u32, 640u32);
        let mut buffer = vec![0u8; (w * h * 3) as usize];
        let font_result =
            plotters::style::register_font("sans-serif", FontStyle::Normal, epaint_default_fonts::UBUNTU_LIGHT);
        if font_result.is_err() {
            return Err(Error::output(path, "the plot font could not be loaded"));
        }
        let fail = |e: &dyn std::fmt::Display| Error::output(path, format!("plotting failed: {e}"));
        {
            let root = BitMapBackend::with_buffer(&mut buffer, (w, h)).into_drawing_area();
            root.fill(&WHITE).map_err(|e| fail(&e))?;
            let rows: Vec<&Row> = self.rows.iter().filter(|r| r.blur).collect();
            let (min_ms, max_ms) = rows.iter().fold((f64::MAX, 0.0f64), |(a, b), r| (a.min(r.ms), b.max(r.ms)));
            let (min_e, max_e) =
                rows.iter().fold((f64::MAX, 0.0f64), |(a, b), r| (a.min(r.hdr_rmse), b.max(r.hdr_rmse)));
            let mut chart = ChartBuilder::on(&root)
                .caption("HDR RMSE against GPU frame time (blur on; points: 4 … 64 samples)", ("sans-serif", 22))
                .margin(16)
                .x_label_area_size(48)
                .y_label_area_size(72)
                // Log-log: the axes carry log10 of the values, labelled with the values.
                .build_cartesian_2d(
                    (min_ms * 0.8).log10()..(max_ms * 1.25).log10(),
                    (min_e * 0.8).log10()..(max_e * 1.25).log10(),
                )
                .map_err(|e| fail(&e))?;
            chart
                .configure_mesh()
                .x_labels(12)
                .y_labels(12)
                .x_label_formatter(&|v| format!("{:.1}", 10f64.powf(*v)))
                .y_label_formatter(&|v| format!("{:.4}", 10f64.powf(*v)))
                .x_desc(format!("frame time, ms ({})", if self.software { "lavapipe" } else { "GPU" }))
                .y_desc("RMSE of linear HDR radiance")
                .label_style(("sans-serif", 16))
                .draw()
                .map_err(|e| fail(&e))?;
            let colours = [RGBColor(31, 119, 180), RGBColor(255, 127, 14), RGBColor(44, 160, 44)];
            for (m, mode) in [Mode::Ssao, Mode::Ssdo, Mode::Both].into_iter().enumerate() {
                for variant in [Variant::Default, Variant::Classic] {
                    let mut points: Vec<(f64, f64)> = rows
                        .iter()
                        .filter(|r| r.mode == mode && r.variant == variant)
                        .map(|r| (r.ms.log10(), r.hdr_rmse.log10()))
                        .collect();
                    points.sort_by(|a, b| a.0.total_cmp(&b.0));
                    let colour = colours[m];
                    let style = if variant == Variant::Default {
                        colour.stroke_width(3)
                    } else {
                        colour.mix(0.6).stroke_width(1)
                    };
                    let label = format!("{} {}", mode.title(), variant);
                    chart
                        .draw_series(LineSeries::new(points.clone(), style))
                        .map_err(|e| fail(&e))?
                        .label(label)
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], style));
                    chart
                        .draw_series(points.iter().map(|p| Circle::new(*p, 4, colour.filled())))
                        .map_err(|e| fail(&e))?;
                }
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font(("sans-serif", 16))
                .draw()
                .map_err(|e| fail(&e))?;
            root.present().map_err(|e| fail(&e))?;
        }
        let image = image::RgbImage::from_raw(w, h, buffer).expect("plot buffer has its size");
        output::save_png(path, &image::DynamicImage::ImageRgb8(image).to_rgba8())
    }

    /// Writes report.csv, report.md and report.png into `out`.
    pub fn write(&self, options: &ReportOptions) -> Result<()> {
        output::write_atomic(&options.out.join("report.csv"), self.csv().as_bytes())?;
        output::write_atomic(&options.out.join("report.md"), self.markdown(options).as_bytes())?;
        self.plot(&options.out.join("report.png"))
    }
}
