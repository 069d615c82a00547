//! What the viewer keeps of its truth and split views between frames: the tracer and the truth
//! on screen with its textures, the current mode's error against it, the split's second
//! renderer. Data alone: `truth_view.rs` and `split.rs` act on it for the viewer.

use std::sync::Arc;
use std::time::Instant;

use image::RgbaImage;

use super::truth::{Rounds, Tracer, ViewKey};
use super::truth_ui::Display;
use crate::headless::truth::{ModeError, ViewTruth};
use crate::render::{Mode, Renderer};
use crate::scene::Model;

/// What the viewer keeps of the truth.
#[derive(Default)]
pub(super) struct TruthState {
    /// The thread, made when the truth is first wanted and gone when it no longer is.
    pub(super) tracer: Option<Tracer>,
    /// The view being traced, and a new one waiting to settle (since when).
    pub(super) traced: Option<ViewKey>,
    pub(super) settling: Option<(ViewKey, Instant)>,
    pub(super) shown: Option<Shown>,
    pub(super) errors: Option<Measured>,
    /// The model as the trace reads it, for its scene number.
    pub(super) model: Option<(u64, Arc<Model>)>,
    /// Why there is no truth for this view (too large for the budget, nothing to measure).
    pub(super) failure: Option<String>,
    /// What the view showed at the last tick (each change is logged).
    pub(super) display: Option<Display>,
}

/// The rounds on screen, the truth made of them and its image.
pub(super) struct Shown {
    pub(super) rounds: Arc<Rounds>,
    pub(super) truth: ViewTruth,
    pub(super) exposure: f32,
    pub(super) image: RgbaImage,
    pub(super) texture: egui::TextureHandle,
}

/// The current mode's error against the shown truth.
pub(super) struct Measured {
    pub(super) mode: Mode,
    pub(super) rays: u32,
    pub(super) error: ModeError,
    /// The heat map's scale: the first mode measured against this round of the truth sets it,
    /// so the modes' maps compare.
    pub(super) scale: f32,
    pub(super) image: RgbaImage,
    pub(super) texture: egui::TextureHandle,
}

/// What the split keeps: the second renderer while the right side is a mode, and whether the
/// divider is being dragged.
#[derive(Default)]
pub(super) struct SplitState {
    pub(super) second: Option<SecondView>,
    pub(super) dragging: bool,
}

/// The renderer of the image right of a split's divider, and the texture it draws into.
pub(super) struct SecondView {
    pub(super) renderer: Renderer,
    pub(super) view: wgpu::TextureView,
    pub(super) id: egui::TextureId,
}

impl SplitState {
    /// The texture of the right side's mode, while there is one.
    pub(super) fn texture(&self) -> Option<egui::TextureId> {
        self.second.as_ref().map(|s| s.id)
    }
}
