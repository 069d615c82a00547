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

mod space;
mod table;

use std::collections::{HashMap, HashSet};
use std::path::PathBuf;
use std::time::Instant;

use crate::gpu::Gpu;
use crate::headless::capture::{capture, output_texture, CAPTURE_FORMAT};
use crate::headless::readback::read_depth;
use crate::render::{Mode, Renderer, SceneFeatures, Settings, Variant};
use crate::report::measure::{Bench, TruthSource};
use crate::report::{Config, RadiusChoice, ReportOptions};
use crate::scene::OrbitCamera;
use crate::{Error, Result};
pub use space::Candidate;

/// Settings whose time is within this share of the budget are timed again before the pick.
pub const RETIME_MARGIN: f64 = 0.1;
/// Errors within this share of each other count as equal when picking: the cheaper is taken. The
/// truth's noise and the views' spread make smaller differences meaningless, and on cornell the
/// last 1% of error within a budget costs up to half the frame again.
pub const EQUAL_ERROR: f64 = 0.01;
/// The most views and the most measured settings a run takes.
pub const MAX_VIEWS: usize = 8;
pub const MAX_SETTINGS: usize = 400;

/// The budget: milliseconds, or a multiple of the Off frame's time measured in the same run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Budget {
    Ms(f64),
    OffTimes(f64),
}

/// What to tune, on what.
#[derive(Clone, Debug)]
pub struct TuneOptions {
    pub scene: String,
    pub model: Option<PathBuf>,
    pub no_surface_maps: bool,
    pub skybox: Option<PathBuf>,
    pub size: (u32, u32),
    pub lights: usize,
    pub seed: u64,
    pub mode: Mode,
    pub budget: Option<Budget>,
    /// The cheapest setting whose HDR RMSE is at most this (within the budget, if one is given).
    pub target_error: Option<f64>,
    /// Views of the scene: the report's view, and the others turned about the model by up to
    /// `spread` degrees either side.
    pub views: usize,
    pub spread: f32,
    /// Frames timed per setting (on the report's view; a frame costs the same from the others).
    pub frames: usize,
    /// Reference rays per pixel in each of the two traces of each view.
    pub samples_per_pixel: u32,
    /// The most settings the search measures (0: no search, only `also` and Off).
    pub max_settings: usize,
    /// Presets measured beside the search's settings (`--also`): their figures on this scene and
    /// device, and picked if they are the best.
    pub also: Vec<crate::preset::Preset>,
    pub out: PathBuf,
}

impl TuneOptions {
    /// A goal given, every number within its range; the first that is not, as the setting error.
    pub fn check(&self) -> Result<()> {
        if self.budget.is_none() && self.target_error.is_none() && self.max_settings > 0 {
            return Err(Error::Setting(
                "give --budget-ms, --budget-off or --target-error (or --max-settings 0 to measure --also presets only)"
                    .into(),
            ));
        }
        let positive = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(Error::Setting(format!("--{name} {v}: must be a positive number")))
            }
        };
        match self.budget {
            Some(Budget::Ms(ms)) => positive("budget-ms", ms)?,
            Some(Budget::OffTimes(k)) => positive("budget-off", k)?,
            None => {}
        }
        if let Some(e) = self.target_error {
            positive("target-error", e)?;
        }
        if self.mode == Mode::Off {
            return Err(Error::Setting("--mode off: Off samples nothing, so it has no setting to tune".into()));
        }
        if !(1..=MAX_VIEWS).contains(&self.views) {
            return Err(Error::Setting(format!("--views {}: must be from 1 to {MAX_VIEWS}", self.views)));
        }
        crate::spec::in_range("spread", self.spread, 0.0, 90.0)?;
        if self.max_settings > MAX_SETTINGS {
            return Err(Error::Setting(format!(
                "--max-settings {}: must be from 0 to {MAX_SETTINGS}",
                self.max_settings
            )));
        }
        if self.max_settings == 0 && self.also.is_empty() {
            return Err(Error::Setting("--max-settings 0: give --also presets to measure".into()));
        }
        if self.samples_per_pixel < 2 {
            return Err(Error::Setting(format!(
                "--spp {}: the reference needs at least 2 rays per pixel for an error estimate",
                self.samples_per_pixel
            )));
        }
        Ok(())
    }

    /// The report's options for the same scene (what its loaders and measurements read).
    fn report_options(&self) -> ReportOptions {
        ReportOptions {
            scene: self.scene.clone(),
            model: self.model.clone(),
            no_surface_maps: self.no_surface_maps,
            skybox: self.skybox.clone(),
            size: self.size,
            samples: vec![16],
            march: vec![(2, 16)],
            radii: vec![RadiusChoice::Times(1.0)],
            samples_per_pixel: self.samples_per_pixel,
            frames: self.frames,
            accumulate: vec![1],
            orbit: 0.0,
            lights: self.lights,
            seed: self.seed,
            out: self.out.clone(),
            preset: None,
        }
    }

    /// The views' yaw offsets from the report's view: 0 first, then ± the spread, evenly between.
    pub fn yaw_offsets(&self) -> Vec<f32> {
        let mut offsets = vec![0.0];
        let pairs = (self.views - 1).div_ceil(2);
        for k in 1..=pairs {
            let angle = self.spread * k as f32 / pairs as f32;
            offsets.push(-angle);
            if offsets.len() < self.views {
                offsets.push(angle);
            }
        }
        offsets
    }

    /// The scene in words: the model file, or the named scene.
    pub fn scene_name(&self) -> String {
        let name = self.model.as_ref().map_or_else(|| self.scene.clone(), |p| p.display().to_string());
        match &self.skybox {
            Some(sky) => format!("{name} under {}", sky.display()),
            None => name,
        }
    }

    /// The work planned, in a line.
    pub fn planned(&self) -> String {
        format!(
            "planned: {} views at {}x{} (a truth of 2 × {} rays a pixel each), up to {} settings × {} timed frames a view",
            self.views, self.size.0, self.size.1, self.samples_per_pixel, self.max_settings, self.frames
        )
    }
}

/// One measured setting: its time (on the report's view) and its errors, averaged over the views.
#[derive(Clone, Debug)]
pub struct Point {
    /// The search's setting (`None` for Off and for the `also` presets).
    pub candidate: Option<Candidate>,
    /// The setting's knobs (`None` for Off), and the preset's name for an `also` preset.
    pub knobs: Option<crate::knobs::Knobs>,
    pub name: Option<String>,
    pub ms: f64,
    /// Frames timed for `ms`.
    pub frames_timed: usize,
    pub hdr_rmse: f64,
    pub do_rmse: Option<f64>,
    pub flip: f64,
    /// HDR RMSE of each view.
    pub hdr_per_view: Vec<f64>,
    /// On the Pareto front of time against HDR error.
    pub front: bool,
}

/// Why the pick is what it is, when it is not plainly "the most accurate within the budget".
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// The most accurate setting within the budget.
    Best,
    /// The cheapest that reaches the target error.
    Target,
    /// No setting measured reaches the target within the budget: the most accurate is picked.
    TargetMissed,
    /// Even the most accurate setting measured fits: the budget does not bind.
    NotBinding,
    /// No setting measured fits the budget; nothing is picked.
    BelowCheapest,
}

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

/// Marks the points no other point beats on both time and HDR error.
fn mark_front(points: &mut [Point]) {
    let all: Vec<(f64, f64)> = points.iter().map(|p| (p.ms, p.hdr_rmse)).collect();
    for (i, p) in points.iter_mut().enumerate() {
        let (ms, e) = all[i];
        p.front = !all.iter().enumerate().any(|(j, &(m2, e2))| j != i && m2 <= ms && e2 <= e && (m2 < ms || e2 < e));
    }
}

/// The pick among `points` for a budget and a target, and why.
fn choose(points: &[Point], budget: Option<f64>, target: Option<f64>) -> (Option<usize>, Verdict) {
    let within: Vec<usize> = (0..points.len()).filter(|&i| budget.is_none_or(|b| points[i].ms <= b)).collect();
    let most_accurate = within.iter().copied().min_by(|&a, &b| points[a].hdr_rmse.total_cmp(&points[b].hdr_rmse));
    let Some(most_accurate) = most_accurate else {
        return (None, Verdict::BelowCheapest);
    };
    // The cheapest of those as accurate as the most accurate, within [`EQUAL_ERROR`].
    let as_good = points[most_accurate].hdr_rmse * (1.0 + EQUAL_ERROR);
    let best = within
        .iter()
        .copied()
        .filter(|&i| points[i].hdr_rmse <= as_good)
        .min_by(|&a, &b| points[a].ms.total_cmp(&points[b].ms))
        .unwrap_or(most_accurate);
    if let Some(e) = target {
        let reaching = within.iter().copied().filter(|&i| points[i].hdr_rmse <= e);
        return match reaching.min_by(|&a, &b| points[a].ms.total_cmp(&points[b].ms)) {
            Some(i) => (Some(i), Verdict::Target),
            None => (Some(best), Verdict::TargetMissed),
        };
    }
    let overall = (0..points.len()).min_by(|&a, &b| points[a].hdr_rmse.total_cmp(&points[b].hdr_rmse));
    if overall == Some(most_accurate) && points.iter().all(|p| budget.is_none_or(|b| p.ms <= b)) {
        (Some(best), Verdict::NotBinding)
    } else {
        (Some(best), Verdict::Best)
    }
}

/// Where a setting of the focus stands, and so which of its neighbours are worth measuring.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Role {
    /// The pick: every neighbour.
    Pick,
    /// The front's setting just dearer than the pick (often over the budget): the neighbours
    /// that cost no more, which may fit the budget and keep its accuracy.
    Dearer,
    /// The front's setting just cheaper: the neighbours that cost no less.
    Cheaper,
}

impl Role {
    fn neighbours(self, c: &Candidate) -> Vec<Candidate> {
        let keep = |n: &Candidate| match self {
            Role::Pick => true,
            Role::Dearer => c.dearer(n) != Some(true),
            Role::Cheaper => c.dearer(n) != Some(false),
        };
        c.neighbours().into_iter().filter(keep).collect()
    }
}

/// The settings to expand next, in the order to try them: the pick and the front's settings
/// either side of it in time; on odd `turn`s the dearer first, so a start just over the budget
/// (the defaults, often) is walked down while the pick climbs.
fn focus(points: &[Point], budget: Option<f64>, target: Option<f64>, turn: usize) -> Vec<(usize, Role)> {
    let mut front: Vec<usize> = (0..points.len()).filter(|&i| points[i].front).collect();
    front.sort_by(|&a, &b| points[a].ms.total_cmp(&points[b].ms));
    let (pick, _) = choose(points, budget, target);
    // Below the cheapest: the cheapest setting is where cheaper ones are found.
    let pick = pick.unwrap_or_else(|| front[0]);
    let at = front.iter().position(|&i| i == pick);
    let dearer = at.and_then(|k| front.get(k + 1)).map(|&i| (i, Role::Dearer));
    let cheaper = at.and_then(|k| k.checked_sub(1)).map(|k| (front[k], Role::Cheaper));
    let mut out = Vec::new();
    if turn % 2 == 1 {
        out.extend(dearer);
        out.push((pick, Role::Pick));
    } else {
        out.push((pick, Role::Pick));
        out.extend(dearer);
    }
    out.extend(cheaper);
    out
}

/// Runs the search. `progress` is told about each finished truth row and each measured setting.
pub fn run(gpu: &Gpu, options: &TuneOptions, progress: &(dyn Fn(&str) + Sync)) -> Result<Tune> {
    options.check()?;
    let started = Instant::now();
    let report_options = options.report_options();
    Renderer::check_memory(options.size, &Settings::default(), SceneFeatures::lit(options.lights), true, &Mode::ALL)?;
    log::info!("{}", options.planned());
    let (scene, sky, sky_name) = crate::report::load_scene(&report_options)?;
    gpu.check_size(options.size.0, options.size.1)?;
    let base = Settings::default();
    let mut renderer = Renderer::new(gpu, &scene, &sky, options.size, CAPTURE_FORMAT, base)?;
    renderer.keep_hdr(gpu, true);
    let timestamps = renderer.enable_timing(gpu);
    let default_radius = renderer.radius();
    let framing = OrbitCamera::framing(&scene.model.bounds);
    let offsets = options.yaw_offsets();
    let cameras: Vec<OrbitCamera> =
        offsets.iter().map(|&d| OrbitCamera { yaw_deg: framing.yaw_deg + d, ..framing }).collect();

    // One truth a view, as the report's.
    let source = TruthSource::new(&scene, &sky, &sky_name, &report_options, &base);
    let mut truths = Vec::new();
    let mut noise = 0.0;
    for camera in &cameras {
        capture(gpu, &mut renderer, camera)?;
        let depth = read_depth(gpu, &renderer.targets().depth().texture)?;
        let truth = source.trace(camera, &depth, default_radius, &|| progress("reference row"))?;
        noise += truth.noise.hdr / cameras.len() as f64;
        truths.push(truth);
    }
    let target = output_texture(gpu, options.size);
    let view = target.create_view(&wgpu::TextureViewDescriptor::default());
    let benches: Vec<Bench> = cameras
        .iter()
        .enumerate()
        .map(|(i, camera)| Bench {
            gpu,
            camera,
            view: &view,
            options: &report_options,
            ambient: base.ambient,
            diagnostics: false,
            // A frame costs the same from every view: the report's view is timed.
            timed: i == 0,
        })
        .collect();
    // Times `config` on the report's view, `repeats` medians of `frames` frames, and measures its
    // error on every view.
    let mut measure = |config: Config, scale: f32, repeats: usize| -> Result<Point> {
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
        let share = 1.0 / benches.len() as f64;
        for (bench, truth) in benches.iter().zip(&truths) {
            let row = bench.measure(&mut renderer, config, scale * default_radius, truth, None)?;
            if bench.timed {
                let mut ms = row.ms;
                for _ in 1..repeats {
                    ms += crate::headless::bench::measure(gpu, &mut renderer, bench.camera, &view, options.frames)?
                        .frame_ms;
                }
                point.ms = ms / repeats as f64;
                point.frames_timed = options.frames * repeats;
            }
            point.hdr_rmse += share * row.hdr_rmse;
            point.do_rmse = row.do_rmse.map(|d| point.do_rmse.unwrap_or(0.0) + share * d);
            point.flip += share * row.flip;
            point.hdr_per_view.push(row.hdr_rmse);
        }
        Ok(point)
    };

    // Off is the budget's unit (`--budget-off`): timed four times as long as a setting.
    let off = measure(Config::off(Variant::default()), 1.0, 4)?;
    progress(&format!("off: {:.2} ms, HDR RMSE {:.4}", off.ms, off.hdr_rmse));
    let budget_ms = options.budget.map(|b| match b {
        Budget::Ms(ms) => ms,
        Budget::OffTimes(k) => k * off.ms,
    });

    let mut points: Vec<Point> = Vec::new();
    for preset in &options.also {
        let (config, scale) = Config::of_knobs(options.mode, &preset.knobs);
        let mut point = measure(config, scale, 1)?;
        (point.knobs, point.name) = (Some(preset.knobs), Some(preset.name.clone()));
        progress(&format!("{}: {:.2} ms, HDR RMSE {:.4}", preset.name, point.ms, point.hdr_rmse));
        points.push(point);
    }
    let mut index: HashMap<Candidate, usize> = HashMap::new();
    let mut expanded: HashSet<(Candidate, Role)> = HashSet::new();
    let mut turn = 0;
    let mut queue = if options.max_settings > 0 { Candidate::starts(options.mode) } else { Vec::new() };
    'search: loop {
        for candidate in std::mem::take(&mut queue) {
            if index.contains_key(&candidate) {
                continue;
            }
            if index.len() >= options.max_settings {
                break 'search;
            }
            let (config, scale) = candidate.config();
            let mut point = measure(config, scale, 1)?;
            (point.candidate, point.knobs) = (Some(candidate), Some(candidate.knobs));
            progress(&format!("{}: {:.2} ms, HDR RMSE {:.4}", candidate.knobs.label(), point.ms, point.hdr_rmse));
            index.insert(candidate, points.len());
            points.push(point);
        }
        mark_front(&mut points);
        let next = focus(&points, budget_ms, options.target_error, turn)
            .into_iter()
            .filter_map(|(i, role)| Some((points[i].candidate?, role)))
            .find(|step| !expanded.contains(step));
        let Some((next, role)) = next else { break };
        expanded.insert((next, role));
        turn += 1;
        queue = role.neighbours(&next).into_iter().filter(|c| !index.contains_key(c)).collect();
    }

    // Timing noise: the front's settings near the budget are timed again, as long, and pooled.
    let mut retimed = 0;
    if let Some(b) = budget_ms {
        for point in points.iter_mut().filter(|p| p.front && (p.ms - b).abs() <= RETIME_MARGIN * b) {
            let Some(knobs) = point.knobs else { continue };
            let (config, scale) = Config::of_knobs(options.mode, &knobs);
            renderer.settings = config.settings(scale * default_radius);
            let again =
                crate::headless::bench::measure(gpu, &mut renderer, &cameras[0], &view, options.frames)?.frame_ms;
            point.ms = 0.5 * (point.ms + again);
            point.frames_timed *= 2;
            retimed += 1;
        }
        mark_front(&mut points);
    }
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
        date: jiff::Timestamp::now().to_zoned(jiff::tz::TimeZone::UTC).strftime("%Y-%m-%d %H:%M UTC").to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(ms: f64, hdr_rmse: f64) -> Point {
        Point {
            candidate: None,
            knobs: None,
            name: None,
            ms,
            frames_timed: 1,
            hdr_rmse,
            do_rmse: None,
            flip: 0.0,
            hdr_per_view: vec![hdr_rmse],
            front: false,
        }
    }

    #[test]
    fn the_pick_is_the_most_accurate_within_the_budget_or_the_cheapest_reaching_the_target() {
        let mut points = vec![point(5.0, 0.09), point(10.0, 0.05), point(12.0, 0.06), point(20.0, 0.03)];
        mark_front(&mut points);
        assert_eq!(points.iter().map(|p| p.front).collect::<Vec<_>>(), [true, true, false, true]);
        // Within 1% of the most accurate is as good: the cheaper of the two is taken.
        let mut close = points.clone();
        close.push(point(14.0, 0.0499));
        assert_eq!(choose(&close, Some(15.0), None), (Some(1), Verdict::Best));
        close.push(point(14.5, 0.0480));
        assert_eq!(choose(&close, Some(15.0), None), (Some(5), Verdict::Best));
        assert_eq!(choose(&points, Some(15.0), None), (Some(1), Verdict::Best));
        assert_eq!(choose(&points, Some(4.0), None), (None, Verdict::BelowCheapest));
        assert_eq!(choose(&points, Some(25.0), None), (Some(3), Verdict::NotBinding));
        assert_eq!(choose(&points, None, Some(0.06)), (Some(1), Verdict::Target));
        assert_eq!(choose(&points, Some(15.0), Some(0.04)), (Some(1), Verdict::TargetMissed));
        // The focus: the pick and the front's settings either side of it in time.
        let (p, d, c) = (Role::Pick, Role::Dearer, Role::Cheaper);
        assert_eq!(focus(&points, Some(15.0), None, 0), [(1, p), (3, d), (0, c)]);
        assert_eq!(focus(&points, Some(15.0), None, 1), [(3, d), (1, p), (0, c)]);
        assert_eq!(focus(&points, Some(4.0), None, 0), [(0, p), (1, d)]);
    }

    #[test]
    fn views_start_at_the_reports_and_spread_evenly_both_ways() {
        let mut o = TuneOptions {
            scene: "cornell".into(),
            model: None,
            no_surface_maps: false,
            skybox: None,
            size: (16, 12),
            lights: 0,
            seed: 1,
            mode: Mode::Ssdo,
            budget: Some(Budget::Ms(10.0)),
            target_error: None,
            views: 1,
            spread: 20.0,
            frames: 1,
            samples_per_pixel: 2,
            max_settings: 10,
            also: Vec::new(),
            out: "tune".into(),
        };
        assert_eq!(o.yaw_offsets(), [0.0]);
        o.views = 3;
        assert_eq!(o.yaw_offsets(), [0.0, -20.0, 20.0]);
        o.views = 4;
        assert_eq!(o.yaw_offsets(), [0.0, -10.0, 10.0, -20.0]);
        assert!(o.check().is_ok());
        o.budget = None;
        assert!(o.check().unwrap_err().to_string().contains("--budget-ms"));
        o.budget = Some(Budget::OffTimes(-1.0));
        assert!(o.check().unwrap_err().to_string().contains("--budget-off -1"));
        o.budget = Some(Budget::Ms(1.0));
        o.mode = Mode::Off;
        assert!(o.check().unwrap_err().to_string().contains("--mode off"));
    }
}
