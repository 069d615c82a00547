//! Per-step GPU times from timestamp queries: two timestamps per render pass (begin, end),
//! resolved into a buffer after the frame and read back on request.

use super::modes::{Plan, Step};
use crate::gpu::Gpu;
use crate::{Error, Result};

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
