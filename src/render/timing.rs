//! Per-step GPU times from timestamp queries: two timestamps per render pass (begin, end),
//! resolved into a buffer after the frame and read back on request.

use super::modes::{Plan, Step};
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

pub struct GpuTimer {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    count: u32,
    period_ns: f64,
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
        let readback = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timing_readback"),
            size: bytes,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self { queries, resolve, readback, count, period_ns: gpu.queue.get_timestamp_period() as f64 }
    }

    /// Timestamp writes for the render pass of step `index`.
    pub fn writes(&self, index: usize) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(2 * index as u32),
            end_of_pass_write_index: Some(2 * index as u32 + 1),
        }
    }

    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.queries, 0..self.count, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, self.resolve.size());
    }

    /// Milliseconds per step of the last resolved frame (waits for the GPU).
    pub fn read(&self, gpu: &Gpu, plan: &Plan) -> Result<Vec<(Step, f64)>> {
        let slice = self.readback.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        gpu.wait()?;
        let ticks: Vec<u64> = {
            let view = slice.get_mapped_range().map_err(|e| Error::Gpu(format!("reading timestamps: {e}")))?;
            bytemuck::cast_slice(&view).to_vec()
        };
        self.readback.unmap();
        Ok(plan
            .steps
            .iter()
            .enumerate()
            .map(|(i, step)| {
                let (begin, end) = (ticks[2 * i], ticks[2 * i + 1]);
                (*step, end.saturating_sub(begin) as f64 * self.period_ns * 1e-6)
            })
            .collect())
    }
}
