//! State that lives across frames. Every other screen target is rebuilt whenever the plan or the
//! size changes; a history is not: it is a pair of textures (ping-pong: the frame reads what the
//! last frame wrote and writes the other) that survives frames and re-plans until the size or
//! its own inputs change. The previous frame's camera is beside it, in the frame uniforms
//! (`previous_world_to_clip`, see `frame.rs`), so a pass can reproject into it.
//!
//! A pass that accumulates over frames asks for its history through the plan
//! ([`Plan::history`](super::Plan::history)), reads [`PingPong::read`], writes
//! [`PingPong::write`], and may update per-frame state in `Pass::begin_frame`. The renderer swaps
//! every pair at the end of a frame and resets them when the view jumps or the scene changes.
//! A plan that asks for none allocates none.

use super::targets::{texel_bytes, Target};
use crate::scene::OrbitCamera;

/// What a history is, and what it is valid for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HistorySpec {
    /// Its target's name (`modes::OCCLUSION_HISTORY`, ...).
    pub name: &'static str,
    pub format: wgpu::TextureFormat,
    /// A digest of the inputs whose change makes the history meaningless (the settings it
    /// accumulates under, the model, the sky, the lights): another key drops it.
    pub key: u64,
}

impl HistorySpec {
    /// The bytes of its pair of textures of `size` ([`Plan::history_size`](super::Plan::history_size)).
    pub fn bytes(&self, size: (u32, u32)) -> u64 {
        2 * texel_bytes(size, self.format)
    }
}

/// One history: the texture this frame reads (the last frame's result) and the one it writes.
pub struct PingPong {
    pub spec: HistorySpec,
    /// Its textures' size (where the samples are, [`Plan::history_size`](super::Plan::history_size)):
    /// another size drops it.
    pub size: (u32, u32),
    targets: [Target; 2],
    /// Which of the two this frame writes.
    written: usize,
    /// Frames written since the pair was made or reset.
    pub frames: u32,
    /// A serial number of the allocation: a new one each time a pair is made.
    pub generation: u64,
}

impl PingPong {
    /// What the last frame wrote.
    pub fn read(&self) -> &Target {
        &self.targets[1 - self.written]
    }

    /// What this frame writes.
    pub fn write(&self) -> &Target {
        &self.targets[self.written]
    }

    pub fn bytes(&self) -> u64 {
        self.targets.iter().map(|t| t.bytes).sum()
    }

    /// Which of the two this frame writes (0 or 1): a pass that binds the read side prepares a
    /// bind group for each and picks this one's.
    pub fn parity(&self) -> usize {
        self.written
    }

    /// What a frame of `parity` reads (the other frame's write).
    pub fn read_side(&self, parity: usize) -> &Target {
        &self.targets[1 - parity]
    }

    /// What a frame of `parity` writes.
    pub fn write_side(&self, parity: usize) -> &Target {
        &self.targets[parity]
    }
}

/// Every history of the renderer.
#[derive(Default)]
pub struct History {
    pairs: Vec<PingPong>,
    made: u64,
}

impl History {
    /// Keeps each history of `specs` that exists at `size` under the same key, makes the ones
    /// that do not (with no frames), and drops the histories no spec names any more. Every
    /// history follows the samples: `size` is the plan's `history_size`.
    pub fn ensure(&mut self, device: &wgpu::Device, size: (u32, u32), specs: &[HistorySpec]) {
        self.pairs.retain(|p| specs.contains(&p.spec) && p.size == size);
        for spec in specs {
            if !self.pairs.iter().any(|p| p.spec.name == spec.name) {
                self.made += 1;
                let target = || Target::new(device, spec.name, size, spec.format);
                let targets = [target(), target()];
                self.pairs.push(PingPong { spec: *spec, size, targets, written: 0, frames: 0, generation: self.made });
            }
        }
    }

    /// The end of a frame: what each pair wrote becomes what the next frame reads.
    pub fn advance(&mut self) {
        for pair in &mut self.pairs {
            pair.written = 1 - pair.written;
            pair.frames = pair.frames.saturating_add(1);
        }
    }

    /// The view jumped or the scene changed: the next frame starts every history anew (the
    /// textures stay; a pass reads `frames == 0` as "nothing to reuse").
    pub fn reset(&mut self) {
        for pair in &mut self.pairs {
            pair.frames = 0;
        }
    }

    /// The history of that name (`modes::OCCLUSION_HISTORY`, or its name).
    pub fn get(&self, name: impl AsRef<str>) -> Option<&PingPong> {
        self.pairs.iter().find(|p| p.spec.name == name.as_ref())
    }

    pub fn all(&self) -> impl Iterator<Item = &PingPong> {
        self.pairs.iter()
    }

    /// Bytes held by every pair.
    pub fn bytes(&self) -> u64 {
        self.pairs.iter().map(PingPong::bytes).sum()
    }
}

/// Where a still view's average stands (see `Renderer::still_frames`).
#[derive(Default)]
pub struct StillView {
    pub frames: u32,
    pub camera: Option<OrbitCamera>,
    /// The history's generation the frames went into.
    pub generation: u64,
    /// The view's first frame went into an empty history: the average holds this view's frames
    /// alone, none reprojected from a moving camera's.
    pub clean: bool,
    /// The degrees the view turned about what it looks at since the last frame (0 on a first
    /// frame): the angle at the camera's target between the last eye and this one. A camera that
    /// turns in place sees every surface from where it was: 0.
    pub turn_deg: f32,
}

impl StillView {
    /// Counts a frame of `camera` going into `history`.
    pub fn count(&mut self, camera: &OrbitCamera, history: Option<&PingPong>) {
        let same =
            history.is_some_and(|h| h.frames > 0 && h.generation == self.generation) && self.camera == Some(*camera);
        if !same {
            self.clean = history.is_none_or(|h| h.frames == 0);
        }
        self.frames = if same { self.frames.saturating_add(1) } else { 1 };
        self.turn_deg = self.camera.map_or(0.0, |last| {
            let (then, now) = (last.eye() - camera.target, camera.eye() - camera.target);
            then.angle_between(now).to_degrees()
        });
        self.camera = Some(*camera);
        self.generation = history.map_or(0, |h| h.generation);
    }
}
