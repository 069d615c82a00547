//! The average over frames as the renderer keeps it: its histories, how far a still view's
//! average has come, and the reset when the view jumps.

use super::history::{History, StillView};
use super::settings::MAX_HISTORY_TURN_DEG;
use super::{modes, Renderer};
use crate::scene::OrbitCamera;

/// The frames a history holds before its view stops blurring the samples it averages (a still
/// view, or one turning at most [`SLOW_TURN_DEG`] a frame). The blur makes a young average clean
/// at once, and keeps a fast-turning view's clean; later frames go into the average raw, since
/// by then the average over frames does most of the blur's work, and a settled frame costs no
/// blur. Measured on the default scene (docs/performance.md): SSAO's
/// error within R 0.0361 → 0.0324 at 16 frames; SSDO's image 0.0195 → 0.0197 and DO 0.0303 →
/// 0.0307 (+1%, within what the frame must hold; open +0.3%, stairs −0.2%) for a tenth of a DO
/// frame's time.
pub const BLURRED_FRAMES: u32 = 4;

/// The fastest turn (degrees a frame) at which a moving view skips the blur once its history
/// holds [`BLURRED_FRAMES`]: at or below it a surface keeps at least that many frames
/// ([`MAX_HISTORY_TURN_DEG`] over the turn), which do the blur's work as a still view's do.
/// Measured at 1° a frame (cornell 320x240, 16 frames, docs/performance.md): SSAO's AO within R
/// 0.0378 → 0.0355 without the blur, SSDO's image 0.0201 → 0.0206 (DO 0.0309 → 0.0319), and the
/// temporal pass 2.4 ms shorter on the room; at 10° the blur stays (nothing is kept).
pub const SLOW_TURN_DEG: f32 = MAX_HISTORY_TURN_DEG / BLURRED_FRAMES as f32;

/// A turn about what the camera looks at beyond this, from one frame to the next, is a cut: the
/// next frame starts anew, as after a reset. The temporal pass keeps none of the last frame's
/// average past [`MAX_HISTORY_TURN_DEG`], and the senders' sky the last frame measured, seen from
/// that far away, lights them worse than a march of their own this frame (cornell, 16 frames
/// turning 45° a frame: SSDO's DO 0.0370 → 0.0355; 4 frames after a cut from 90° away 0.0370 →
/// 0.0348, the still view's; docs/accuracy.md). Not from 12°: a view that keeps turning 20° a
/// frame would gain 1% of DO (0.0358 → 0.0355) for that march every frame (SSDO 1.13× the frame).
pub const CUT_TURN_DEG: f32 = 30.0;

/// The average over frames: what the temporal pass keeps, and where a still view stands.
impl Renderer {
    /// The histories the plan keeps across frames.
    pub fn history(&self) -> &History {
        &self.history
    }

    /// The frames a still camera renders before its image is the converged one: the number
    /// averaged where the plan accumulates, 1 otherwise.
    pub fn accumulation(&self) -> u32 {
        if self.plan.accumulates() {
            self.settings.knobs.accumulate as u32
        } else {
            1
        }
    }

    /// The frames the temporal pass's history holds (0 without one): since it was made or reset.
    pub fn frames_accumulated(&self) -> u32 {
        self.history.get(modes::OCCLUSION_HISTORY).map_or(0, |h| h.frames)
    }

    /// Frames of the current still view averaged so far (at most [`Renderer::accumulation`]):
    /// since the camera last moved (that frame counting), the history was reset or a setting
    /// changed what it means.
    pub fn still_frames(&self) -> u32 {
        let history = self.history.get(modes::OCCLUSION_HISTORY);
        let current = history.is_some_and(|h| h.frames > 0 && h.generation == self.still.generation);
        if current {
            self.still.frames.min(self.accumulation())
        } else {
            0
        }
    }

    /// The frames still to render with `camera` before the next one completes the still
    /// average (call after `apply`): all but one where the camera is another than the last
    /// frame's or the average starts anew.
    pub fn frames_to_settle(&self, camera: &OrbitCamera) -> u32 {
        let held = if self.still.camera == Some(*camera) { self.still_frames() } else { 0 };
        self.accumulation().saturating_sub(held + 1)
    }

    /// Whether the average `camera`'s next frames complete holds that view's frames alone: false
    /// when the camera came to rest after moving (the history keeps what it reprojected), so a
    /// screenshot starts anew and shows what `capture` does.
    pub fn still_average_is_clean(&self, camera: &OrbitCamera) -> bool {
        self.still.camera == Some(*camera) && self.still.clean && self.still_frames() > 0
    }

    /// Whether a still view has frames left to average before its image is converged: the
    /// viewer keeps drawing while it does.
    pub fn converging(&self) -> bool {
        self.plan.accumulates() && self.still_frames() < self.accumulation()
    }

    /// Whether the last frame recorded (inside `encode`: the frame being recorded) blurred its
    /// samples: the plan blurs, and it does not average over frames, or the frame is one of a
    /// still view's first [`BLURRED_FRAMES`] while its history holds no more than that many
    /// (counting this frame), or the view turns faster than [`SLOW_TURN_DEG`].
    pub fn blurs(&self) -> bool {
        let still_young = self.still.frames <= BLURRED_FRAMES;
        let history_young = self.frames_accumulated() <= BLURRED_FRAMES || self.still.turn_deg > SLOW_TURN_DEG;
        self.plan.blur && (!self.plan.accumulates() || (still_young && history_young))
    }

    /// Frames take the sample schedule from `entry` on: a single frame (or an average's first)
    /// samples with that entry's pattern rather than the first's. Every view starts at 0; the
    /// report measures how much a single frame's error owes to its pattern by rendering it under
    /// each entry a default average goes through.
    pub fn start_schedule_at(&mut self, entry: u32) {
        self.schedule_start = entry;
    }

    /// Whether `camera` cuts from the last frame's: the angle at its target between the last eye
    /// and its own (the view's turn, as `StillView::turn_deg` measures it) is over
    /// [`CUT_TURN_DEG`].
    pub fn cuts_to(&self, camera: &OrbitCamera) -> bool {
        self.still.camera.is_some_and(|last| {
            let (then, now) = (last.eye() - camera.target, camera.eye() - camera.target);
            then.angle_between(now).to_degrees() > CUT_TURN_DEG
        })
    }

    /// The view jumped or what it shows changed: the next frame reuses nothing from the last
    /// (no history, and its previous camera is its own).
    pub fn reset_history(&mut self) {
        self.history.reset();
        self.frame.forget_previous();
        self.still = StillView::default();
    }
}
