//! Per-step GPU times from timestamp queries: two timestamps per render pass (begin, end),
//! resolved into a buffer after the frame and read back on request.

use super::modes::{Mode, Plan, Step};
use super::settings::Settings;
use super::Renderer;
use crate::gpu::Gpu;
use crate::scene::OrbitCamera;
use crate::{Error, Result};

/// Medians over measured frames.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// GPU milliseconds of the whole frame (the passes' sum), or wall time without timestamps.
    pub frame_ms: f64,
    /// Wall-clock milliseconds from encoding to the GPU going idle.
    pub wall_ms: f64,
    /// GPU milliseconds per pass, by name; empty without timestamp queries.
    pub passes: Vec<(&'static str, f64)>,
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
                (
                    mode.name().to_string(),
                    serde_json::json!({ "frame_ms": r.frame_ms, "wall_ms": r.wall_ms, "passes": passes }),
                )
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
            "variant": s.variant.name(),
            "samples": s.samples,
            "blur": s.blur,
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
        let count = if s.variant.marches() {
            format!("{} slices × {} steps", s.slices, s.steps)
        } else {
            format!("{} samples", s.samples)
        };
        let _ = writeln!(out, "device: {}{software}", self.device);
        let _ = writeln!(out, "timing: {method}; median of {} frames after 2 warm-up frames", self.frames);
        let blur = if s.blur { "on" } else { "off" };
        let _ = writeln!(out, "size {}x{}, {} variant, {count}, blur {blur}", self.size.0, self.size.1, s.variant);
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
    renderer.apply(gpu);
    let names = renderer.plan().step_names();
    let (mut totals, mut walls) = (Vec::new(), Vec::new());
    let mut per_pass: Vec<Vec<f64>> = vec![Vec::new(); names.len()];
    for frame in 0..frames + 2 {
        let started = std::time::Instant::now();
        let mut encoder =
            gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("measure_encoder") });
        renderer.encode(gpu, &mut encoder, camera, output);
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
    let passes = if per_pass.iter().all(|p| p.is_empty()) {
        Vec::new()
    } else {
        names.into_iter().zip(per_pass).map(|(n, mut v)| (n, median(&mut v))).collect()
    };
    Ok(Measurement { frame_ms: median(&mut totals), wall_ms: median(&mut walls), passes })
}

/// Readback buffers in flight: a frame's timestamps are read back two frames later at the latest,
/// and a frame that finds every buffer still busy records none (its timings are simply skipped).
const RING: usize = 3;

/// Where one readback buffer is in its cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum SlotState {
    /// Free to receive the next frame's timestamps.
    Free,
    /// Holds a copy recorded into an encoder that has not been submitted yet.
    Recorded,
    /// Submitted; `map_async` asked for it, the callback has not run.
    Mapping,
}

struct Slot {
    buffer: wgpu::Buffer,
    state: SlotState,
    /// Set by the map callback: `Some(true)` mapped, `Some(false)` failed.
    mapped: std::sync::Arc<std::sync::Mutex<Option<bool>>>,
    /// Frame number of the timestamps it holds (newer wins when several arrive at once).
    frame: u64,
}

/// Per-step GPU times from timestamp queries, read back through a small ring of buffers so the
/// viewer never waits on the GPU inside a frame ([`GpuTimer::poll`]); the bench and the report,
/// which wait for each frame anyway, read the newest frame with [`GpuTimer::wait`].
pub struct GpuTimer {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    slots: Vec<Slot>,
    count: u32,
    period_ns: f64,
    frames: u64,
}

impl GpuTimer {
    pub fn new(gpu: &Gpu, plan: &Plan) -> Self {
        let count = 2 * plan.steps.len() as u32;
        let queries = gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("timing_queries"),
            ty: wgpu::QueryType::Timestamp,
            count,
        });
        let bytes = count as u64 * 8;
        let resolve = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timing_resolve"),
            size: bytes,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let slots = (0..RING)
            .map(|_| Slot {
                buffer: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("timing_readback"),
                    size: bytes,
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
                state: SlotState::Free,
                mapped: Default::default(),
                frame: 0,
            })
            .collect();
        Self { queries, resolve, slots, count, period_ns: gpu.queue.get_timestamp_period() as f64, frames: 0 }
    }

    /// Timestamp writes for the render pass of step `index`.
    pub fn writes(&self, index: usize) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(2 * index as u32),
            end_of_pass_write_index: Some(2 * index as u32 + 1),
        }
    }

    /// Resolves this frame's timestamps into a free readback buffer (none free: skipped).
    pub fn resolve(&mut self, encoder: &mut wgpu::CommandEncoder) {
        self.frames += 1;
        encoder.resolve_query_set(&self.queries, 0..self.count, &self.resolve, 0);
        // A buffer recorded but never submitted (an encoder dropped) is reused.
        let free = self.slots.iter_mut().find(|s| matches!(s.state, SlotState::Free | SlotState::Recorded));
        if let Some(slot) = free {
            encoder.copy_buffer_to_buffer(&self.resolve, 0, &slot.buffer, 0, self.resolve.size());
            slot.state = SlotState::Recorded;
            slot.frame = self.frames;
        }
    }

    /// Call after submitting the encoder given to [`GpuTimer::resolve`]: starts the readback.
    pub fn submitted(&mut self) {
        for slot in self.slots.iter_mut().filter(|s| s.state == SlotState::Recorded) {
            let mapped = slot.mapped.clone();
            if let Ok(mut m) = mapped.lock() {
                *m = None;
            }
            slot.buffer.slice(..).map_async(wgpu::MapMode::Read, move |result| {
                if let Ok(mut m) = mapped.lock() {
                    *m = Some(result.is_ok());
                }
            });
            slot.state = SlotState::Mapping;
        }
    }

    /// Milliseconds per step of the newest frame whose timestamps have arrived, without waiting
    /// for the GPU; `None` when none arrived since the last call.
    pub fn poll(&mut self, gpu: &Gpu, plan: &Plan) -> Result<Option<Vec<(Step, f64)>>> {
        let _ = gpu.device.poll(wgpu::PollType::Poll);
        self.collect(plan)
    }

    /// Like [`GpuTimer::poll`], but waits for every submitted frame first.
    pub fn wait(&mut self, gpu: &Gpu, plan: &Plan) -> Result<Option<Vec<(Step, f64)>>> {
        gpu.wait()?;
        self.collect(plan)
    }

    fn collect(&mut self, plan: &Plan) -> Result<Option<Vec<(Step, f64)>>> {
        let mut newest: Option<(u64, Vec<u64>)> = None;
        for slot in self.slots.iter_mut().filter(|s| s.state == SlotState::Mapping) {
            let done = slot.mapped.lock().map_err(|_| Error::Gpu("timing readback poisoned".into()))?.take();
            let Some(ok) = done else { continue };
            if ok {
                let ticks: Vec<u64> = {
                    let view = slot
                        .buffer
                        .slice(..)
                        .get_mapped_range()
                        .map_err(|e| Error::Gpu(format!("reading timestamps: {e}")))?;
                    bytemuck::cast_slice(&view).to_vec()
                };
                slot.buffer.unmap();
                if newest.as_ref().is_none_or(|(frame, _)| slot.frame > *frame) {
                    newest = Some((slot.frame, ticks));
                }
            }
            slot.state = SlotState::Free;
        }
        Ok(newest.map(|(_, ticks)| {
            plan.steps
                .iter()
                .enumerate()
                .map(|(i, step)| {
                    let (begin, end) = (ticks[2 * i], ticks[2 * i + 1]);
                    (*step, end.saturating_sub(begin) as f64 * self.period_ns * 1e-6)
                })
                .collect()
        }))
    }
}
