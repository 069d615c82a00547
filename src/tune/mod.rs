//! `ssdo tune`: the best estimate a frame budget buys, on the user's scene and device. It measures
//! settings against the report's truth (the same traces, pixels and metrics, `crate::report`) on a
//! few views of the scene, walks from each variant's defaults along the knobs one rung at a time
//! where the front is near the budget, keeps the Pareto front of time against HDR error, and picks
//! the most accurate setting within the budget (or the cheapest that reaches a target error).
//!
//! The search: every start is measured; then, over and over, the focus (the current pick, and the
//! front's settings just cheaper and just dearer than it) has its neighbours measured, one setting
//! of the focus at a time, until every setting of the focus has been expanded or the cap on
//! measured settings is reached. Timing noise: each setting is timed on the report's view (the
//! median of `frames` frames after two warm-up frames; a frame costs the same from the other views,
//! and timing them too tripled tune's run); the front's settings within [`RETIME_MARGIN`] of the
//! budget are timed again as long before the pick is made, and Off, the budget's unit, four times.

mod options;
mod search;
mod space;
mod table;

use std::collections::{HashMap, HashSet};
use std::time::Instant;

use crate::gpu::Gpu;
use crate::headless::capture::{capture, output_texture, CAPTURE_FORMAT};
use crate::headless::readback::read_depth;
use crate::render::{Mode, Renderer, SceneFeatures, Settings, Variant};
use crate::report::measure::{Bench, Truth, TruthSource};
use crate::report::{Config, ReportOptions};
use crate::scene::OrbitCamera;
use crate::Result;
pub use options::{Budget, TuneOptions, MAX_SETTINGS, MAX_VIEWS};
use search::{choose, focus, mark_front, Role};
pub use search::{Point, Verdict, EQUAL_ERROR};
pub use space::Candidate;

/// Settings whose time is within this share of the budget are timed again before the pick.
pub const RETIME_MARGIN: f64 = 0.1;
/// Tune's result.
pub struct Tune {
    pub points: Vec<Point>,
    pub off: Point,
    /// The index into `points` of the pick (`None`: the budget is below every setting).
    pub pick: Option<usize>,
    pub verdict: Verdict,
    pub budget_ms: Option<f64>,
    pub device: String,
    pub software: bool,
    pub timing: &'static str,
    pub default_radius: f32,
    pub views: Vec<f32>,
    pub noise_hdr: f64,
    pub seconds: f64,
    /// Settings timed again for being near the budget.
    pub retimed: usize,
    /// When the run ended (UTC, to the minute).
    pub date: String,
}

impl Tune {
    pub fn picked(&self) -> Option<&Point> {
        self.pick.map(|i| &self.points[i])
    }

    /// The cheapest setting measured.
    pub fn cheapest(&self) -> &Point {
        self.points.iter().min_by(|a, b| a.ms.total_cmp(&b.ms)).expect("the starts are measured")
    }

    /// The most accurate setting measured.
    pub fn most_accurate(&self) -> &Point {
        self.points.iter().min_by(|a, b| a.hdr_rmse.total_cmp(&b.hdr_rmse)).expect("the starts are measured")
    }
}

/// Measures settings on the views: each timed on the report's view and measured against every
/// view's truth.
struct Measurer<'a> {
    gpu: &'a Gpu,
    renderer: Renderer,
    benches: Vec<Bench<'a>>,
    truths: Vec<Truth>,
    default_radius: f32,
    frames: usize,
}

impl<'a> Measurer<'a> {
    /// The views' truths traced, and a bench for each (`cameras`, rendering into `view`).
    fn new(
        gpu: &'a Gpu,
        mut renderer: Renderer,
        (cameras, view, options): (&'a [OrbitCamera], &'a wgpu::TextureView, &'a ReportOptions),
        source: &TruthSource,
        progress: &(dyn Fn(&str) + Sync),
    ) -> Result<Self> {
        let default_radius = renderer.radius();
        let truths = cameras
            .iter()
            .map(|camera| {
                capture(gpu, &mut renderer, camera)?;
                let depth = read_depth(gpu, &renderer.targets().depth().texture)?;
                source.trace(camera, &depth, default_radius, &|| progress("reference row"))
            })
            .collect::<Result<_>>()?;
        let ambient = renderer.settings.ambient;
        let benches = cameras
            .iter()
            .enumerate()
            // A frame costs the same from every view: the report's view is timed.
            .map(|(i, camera)| Bench { gpu, camera, view, options, ambient, diagnostics: false, timed: i == 0 })
            .collect();
        Ok(Self { gpu, renderer, benches, truths, default_radius, frames: options.frames })
    }

    /// Times `config` at `scale` default radii on the report's view, `repeats` medians of the
    /// frames, and measures its error on every view.
    fn measure(&mut self, config: Config, scale: f32, repeats: usize) -> Result<Point> {
        let mut point = Point {
            candidate: None,
            knobs: None,
            name: None,
            ms: 0.0,
            frames_timed: 0,
            hdr_rmse: 0.0,
            do_rmse: None,
            flip: 0.0,
            hdr_per_view: Vec::new(),
            front: false,
        };
        let share = 1.0 / self.benches.len() as f64;
        for (bench, truth) in self.benches.iter().zip(&self.truths) {
            let row = bench.measure(&mut self.renderer, config, scale * self.default_radius, truth, None)?;
            if bench.timed {
                let mut ms = row.ms;
                for _ in 1..repeats {
                    ms += crate::headless::bench::measure(
                        self.gpu,
                        &mut self.renderer,
                        bench.camera,
                        bench.view,
                        self.frames,
                    )?
                    .frame_ms;
                }
                point.ms = ms / repeats as f64;
                point.frames_timed = self.frames * repeats;
            }
            point.hdr_rmse += share * row.hdr_rmse;
            point.do_rmse = row.do_rmse.map(|d| point.do_rmse.unwrap_or(0.0) + share * d);
            point.flip += share * row.flip;
            point.hdr_per_view.push(row.hdr_rmse);
        }
        Ok(point)
    }
}

/// Walks from the starts along the knobs (see the module's notes), measuring each new setting
/// into `points` until the focus is expanded or the cap is reached.
fn search(
    m: &mut Measurer,
    options: &TuneOptions,
    budget_ms: Option<f64>,
    points: &mut Vec<Point>,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<()> {
    let mut index: HashMap<Candidate, usize> = HashMap::new();
    let mut expanded: HashSet<(Candidate, Role)> = HashSet::new();
    let mut turn = 0;
    let mut queue = if options.max_settings > 0 { Candidate::starts(options.mode) } else { Vec::new() };
    loop {
        for candidate in std::mem::take(&mut queue) {
            if index.contains_key(&candidate) {
                continue;
            }
            if index.len() >= options.max_settings {
                return Ok(());
            }
            let (config, scale) = candidate.config();
            let mut point = m.measure(config, scale, 1)?;
            (point.candidate, point.knobs) = (Some(candidate), Some(candidate.knobs));
            progress(&format!("{}: {:.2} ms, HDR RMSE {:.4}", candidate.knobs.label(), point.ms, point.hdr_rmse));
            index.insert(candidate, points.len());
            points.push(point);
        }
        mark_front(points);
        let next = focus(points, budget_ms, options.target_error, turn)
            .into_iter()
            .filter_map(|(i, role)| Some((points[i].candidate?, role)))
            .find(|step| !expanded.contains(step));
        let Some((next, role)) = next else { return Ok(()) };
        expanded.insert((next, role));
        turn += 1;
        queue = role.neighbours(&next).into_iter().filter(|c| !index.contains_key(c)).collect();
    }
}

/// Timing noise: the front's settings within [`RETIME_MARGIN`] of the budget are timed again, as
/// long, and pooled. How many were.
fn retime(m: &mut Measurer, mode: Mode, budget_ms: f64, points: &mut [Point]) -> Result<usize> {
    let mut retimed = 0;
    let (camera, view) = (m.benches[0].camera, m.benches[0].view);
    for point in points.iter_mut().filter(|p| p.front && (p.ms - budget_ms).abs() <= RETIME_MARGIN * budget_ms) {
        let Some(knobs) = point.knobs else { continue };
        let (config, scale) = Config::of_knobs(mode, &knobs);
        m.renderer.settings = config.settings(scale * m.default_radius);
        let again = crate::headless::bench::measure(m.gpu, &mut m.renderer, camera, view, m.frames)?.frame_ms;
        point.ms = 0.5 * (point.ms + again);
        point.frames_timed *= 2;
        retimed += 1;
    }
    mark_front(points);
    Ok(retimed)
}

/// Runs the search. `progress` is told about each finished truth row and each measured setting.
pub fn run(gpu: &Gpu, options: &TuneOptions, progress: &(dyn Fn(&str) + Sync)) -> Result<Tune> {
    options.check()?;
    let started = Instant::now();
    let report_options = options.report_options();
    Renderer::check_memory(
        options.on.size,
        &Settings::default(),
        SceneFeatures::lit(options.on.lights),
        true,
        &Mode::ALL,
    )?;
    log::info!("{}", options.planned());
    let (scene, sky, sky_name) = crate::report::load_scene(&report_options)?;
    gpu.check_size(options.on.size.0, options.on.size.1)?;
    let base = Settings::default();
    let mut renderer = Renderer::new(gpu, &scene, &sky, options.on.size, CAPTURE_FORMAT, base)?;
    renderer.keep_hdr(gpu, true);
    let timestamps = renderer.enable_timing(gpu);
    let default_radius = renderer.radius();
    let framing = OrbitCamera::framing(&scene.model.bounds);
    let offsets = options.yaw_offsets();
    let cameras: Vec<OrbitCamera> =
        offsets.iter().map(|&d| OrbitCamera { yaw_deg: framing.yaw_deg + d, ..framing }).collect();

    // One truth a view, as the report's.
    let source = TruthSource::new(&scene, &sky, &sky_name, &report_options, &base);
    let target = output_texture(gpu, options.on.size);
    let view = target.create_view(&wgpu::TextureViewDescriptor::default());
    let mut m = Measurer::new(gpu, renderer, (&cameras, &view, &report_options), &source, progress)?;
    let noise = m.truths.iter().map(|t| t.noise.hdr / cameras.len() as f64).sum();

    // Off is the budget's unit (`--budget-off`): timed four times as long as a setting.
    let off = m.measure(Config::off(Variant::default()), 1.0, 4)?;
    progress(&format!("off: {:.2} ms, HDR RMSE {:.4}", off.ms, off.hdr_rmse));
    let budget_ms = options.budget.map(|b| match b {
        Budget::Ms(ms) => ms,
        Budget::OffTimes(k) => k * off.ms,
    });
    let mut points = Vec::new();
    for preset in &options.also {
        let (config, scale) = Config::of_knobs(options.mode, &preset.knobs);
        let point =
            Point { knobs: Some(preset.knobs), name: Some(preset.name.clone()), ..m.measure(config, scale, 1)? };
        progress(&format!("{}: {:.2} ms, HDR RMSE {:.4}", preset.name, point.ms, point.hdr_rmse));
        points.push(point);
    }
    search(&mut m, options, budget_ms, &mut points, progress)?;
    let retimed = budget_ms.map(|b| retime(&mut m, options.mode, b, &mut points)).transpose()?.unwrap_or(0);
    gpu.check()?;
    let (pick, verdict) = choose(&points, budget_ms, options.target_error);
    Ok(Tune {
        points,
        off,
        pick,
        verdict,
        budget_ms,
        device: gpu.describe(),
        software: gpu.is_software(),
        timing: if timestamps { "GPU timestamp queries" } else { "synchronised wall time" },
        default_radius,
        views: offsets,
        noise_hdr: noise,
        seconds: started.elapsed().as_secs_f64(),
        retimed,
        date: crate::text::utc_minute(),
    })
}
