//! `ssdo bench`'s measurement: frames rendered, waited for and timed (per pass where the
//! adapter has timestamp queries), reduced to medians, and its report.

use crate::gpu::Gpu;
use crate::render::graph::Role;
use crate::render::{passes, Mode, Renderer, Settings};
use crate::scene::OrbitCamera;
use crate::Result;

/// Medians over measured frames.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// GPU milliseconds of the whole frame (the passes' sum), or wall time without timestamps.
    pub frame_ms: f64,
    /// Wall-clock milliseconds from encoding to the GPU going idle.
    pub wall_ms: f64,
    /// GPU milliseconds per pass, by name; empty without timestamp queries.
    pub passes: Vec<(&'static str, f64)>,
    /// The passes' medians summed by what they are for (sampling, denoise, rest), every role
    /// listed; empty without timestamp queries.
    pub split: Vec<(Role, f64)>,
}

impl Measurement {
    /// The denoise passes' time over the sampling passes' (`None` without both, as in Off).
    pub fn denoise_over_sampling(&self) -> Option<f64> {
        let of = |role| self.split.iter().find(|(r, _)| *r == role).map(|(_, ms)| *ms);
        match (of(Role::Denoise), of(Role::Sampling)) {
            (Some(denoise), Some(sampling)) if sampling > 0.0 => Some(denoise / sampling),
            _ => None,
        }
    }
}

/// What `ssdo bench` measured: every mode's frame and pass times with what they were measured
/// on, as JSON or as the table the command prints.
pub struct BenchReport {
    pub device: String,
    pub software: bool,
    /// Timestamp queries (GPU time per pass), or synchronised wall time per frame.
    pub timestamps: bool,
    pub size: (u32, u32),
    pub frames: usize,
    /// Degrees the camera turned about its target every frame (0: a still view).
    pub orbit: f32,
    pub settings: Settings,
    pub modes: Vec<(Mode, Measurement)>,
}

impl BenchReport {
    fn frame(&self, mode: Mode) -> f64 {
        self.modes.iter().find(|(m, _)| *m == mode).map_or(f64::NAN, |(_, r)| r.frame_ms)
    }

    /// SSDO over SSAO, and SSAO+SSDO over SSDO, frame times.
    pub fn ratios(&self) -> (f64, f64) {
        (self.frame(Mode::Ssdo) / self.frame(Mode::Ssao), self.frame(Mode::Both) / self.frame(Mode::Ssdo))
    }

    pub fn json(&self) -> serde_json::Value {
        let modes: serde_json::Map<String, serde_json::Value> = self
            .modes
            .iter()
            .map(|(mode, r)| {
                let passes: serde_json::Map<String, serde_json::Value> =
                    r.passes.iter().map(|(n, ms)| (n.to_string(), serde_json::json!(ms))).collect();
                let mut split: serde_json::Map<String, serde_json::Value> =
                    r.split.iter().map(|(role, ms)| (role.name().to_string(), serde_json::json!(ms))).collect();
                if !r.split.is_empty() {
                    split.insert("denoise_over_sampling".into(), serde_json::json!(r.denoise_over_sampling()));
                }
                let m = serde_json::json!({ "frame_ms": r.frame_ms, "wall_ms": r.wall_ms, "passes": passes, "split": split });
                (mode.name().to_string(), m)
            })
            .collect();
        let (ssdo_over_ssao, both_over_ssdo) = self.ratios();
        let s = &self.settings;
        serde_json::json!({
            "device": self.device,
            "software": self.software,
            "timing": if self.timestamps { "timestamp" } else { "wall" },
            "size": [self.size.0, self.size.1],
            "frames": self.frames,
            "orbit_deg": self.orbit,
            "variant": s.knobs.variant.name(),
            "samples": s.knobs.samples,
            "blur": s.knobs.blur,
            "modes": modes,
            "ratios": { "ssdo_over_ssao": ssdo_over_ssao, "both_over_ssdo": both_over_ssdo },
        })
    }

    pub fn table(&self) -> String {
        use std::fmt::Write as _;
        let s = &self.settings;
        let mut out = String::new();
        let software = if self.software { " — a CPU rasteriser, not a GPU" } else { "" };
        let method = if self.timestamps {
            "timestamp queries (GPU time per pass)"
        } else {
            "synchronised wall time per frame (no timestamp queries)"
        };
        let count = s.knobs.count_label();
        let _ = writeln!(out, "device: {}{software}", self.device);
        let camera = if self.orbit == 0.0 {
            "a still camera".to_string()
        } else {
            format!("the camera turning {}° a frame", self.orbit)
        };
        let _ = writeln!(out, "timing: {method}; median of {} frames after 2 warm-up frames, {camera}", self.frames);
        let blur = if s.knobs.blur { "on" } else { "off" };
        let _ =
            writeln!(out, "size {}x{}, {} variant, {count}, blur {blur}", self.size.0, self.size.1, s.knobs.variant);
        for (mode, r) in &self.modes {
            let passes: Vec<String> = r.passes.iter().map(|(n, ms)| format!("{n} {ms:.2}")).collect();
            let _ = writeln!(
                out,
                "{:>5}: frame {:8.2} ms (wall {:8.2} ms)  {}",
                mode.name(),
                r.frame_ms,
                r.wall_ms,
                passes.join(", ")
            );
            if !r.split.is_empty() {
                let split: Vec<String> = r.split.iter().map(|(role, ms)| format!("{} {ms:.2}", role.name())).collect();
                let ratio = r.denoise_over_sampling().map_or("—".to_string(), |x| format!("{x:.2}"));
                let _ = writeln!(out, "       split: {}; denoise/sampling {ratio}", split.join(", "));
            }
        }
        let (ssdo_over_ssao, both_over_ssdo) = self.ratios();
        let _ = writeln!(out, "SSDO/SSAO frame-time ratio {ssdo_over_ssao:.3}; Both/SSDO {both_over_ssdo:.3}");
        out
    }
}

fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    match values.len() {
        0 => 0.0,
        n if n % 2 == 1 => values[n / 2],
        n => 0.5 * (values[n / 2 - 1] + values[n / 2]),
    }
}

/// Renders `frames` frames into `output` after two warm-up frames (the first compiles shaders on
/// a software driver), each submitted and waited for, and returns the medians. Enable timing on
/// the renderer first for per-pass GPU times.
pub fn measure(
    gpu: &Gpu,
    renderer: &mut Renderer,
    camera: &OrbitCamera,
    output: &wgpu::TextureView,
    frames: usize,
) -> Result<Measurement> {
    measure_turning(gpu, renderer, camera, output, (frames, 0.0))
}

/// [`measure`] with the camera turned `orbit` degrees about its target every frame (0: still):
/// the frame a person gets while the view moves, which pays the blur and the reprojecting
/// history that a settled view skips.
pub fn measure_turning(
    gpu: &Gpu,
    renderer: &mut Renderer,
    camera: &OrbitCamera,
    output: &wgpu::TextureView,
    (frames, orbit): (usize, f32),
) -> Result<Measurement> {
    renderer.apply(gpu);
    let names = renderer.plan().step_names();
    let (mut totals, mut walls) = (Vec::new(), Vec::new());
    let mut per_pass: Vec<Vec<f64>> = vec![Vec::new(); names.len()];
    for frame in 0..frames + 2 {
        let started = std::time::Instant::now();
        let mut encoder =
            gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("measure_encoder") });
        let turned = OrbitCamera { yaw_deg: camera.yaw_deg + orbit * frame as f32, ..*camera };
        renderer.encode(gpu, &mut encoder, &turned, output);
        gpu.queue.submit([encoder.finish()]);
        renderer.timings_submitted();
        gpu.wait()?;
        let wall = started.elapsed().as_secs_f64() * 1e3;
        let steps = renderer.read_timings(gpu)?;
        if frame < 2 {
            continue;
        }
        walls.push(wall);
        match steps {
            Some(steps) => {
                totals.push(steps.iter().map(|(_, ms)| ms).sum());
                for ((_, ms), list) in steps.iter().zip(per_pass.iter_mut()) {
                    list.push(*ms);
                }
            }
            None => totals.push(wall),
        }
    }
    gpu.check()?;
    let passes: Vec<(&'static str, f64)> = if per_pass.iter().all(|p| p.is_empty()) {
        Vec::new()
    } else {
        names.into_iter().zip(per_pass).map(|(n, mut v)| (n, median(&mut v))).collect()
    };
    let roles: Vec<Role> = renderer.plan().steps.iter().map(|s| passes::role(*s)).collect();
    let split = if passes.is_empty() {
        Vec::new()
    } else {
        let time =
            |role| passes.iter().zip(&roles).filter(|(_, r)| **r == role).fold(0.0, |sum, ((_, ms), _)| sum + ms);
        Role::ALL.iter().map(|&role| (role, time(role))).collect()
    };
    Ok(Measurement { frame_ms: median(&mut totals), wall_ms: median(&mut walls), passes, split })
}
