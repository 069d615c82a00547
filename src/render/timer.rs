//! Per-step GPU times from timestamp queries: two timestamps per render pass (begin, end),
//! resolved into a buffer after the frame and read back on request.

use super::modes::{Plan, Step};
use crate::gpu::Gpu;
use crate::{Error, Result};

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
