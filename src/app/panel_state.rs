//! What the side panel keeps between frames, and the actions it asks of the application (the
//! panel itself is `ui.rs`).

use std::path::PathBuf;

use crate::render::{Mode, Settings};

/// Width of the side panel in logical pixels; the 3D view fills the rest of the window.
pub const PANEL_WIDTH: f32 = 300.0;

/// Something the panel asks the application to do.
pub enum Action {
    Mode(Mode),
    LoadSky(PathBuf),
    LoadModel(PathBuf),
    Relight {
        lights: usize,
        seed: u64,
    },
    ResetCamera,
    /// Accumulation on (with the panel's last count) or off.
    ToggleAccumulation,
    Screenshot,
    Compare,
    /// The fly camera on or off.
    ToggleFly,
    /// The `ssdo capture` command of the view onto the clipboard.
    CopyCommand,
    /// Read a preset file and take its settings.
    LoadPreset(PathBuf),
}

/// A line for the user: what happened, or what went wrong.
pub struct Message {
    pub text: String,
    pub error: bool,
}

/// What the panel keeps between frames.
pub struct PanelState {
    pub sky_path: String,
    pub model_path: String,
    pub sky_folders: Vec<PathBuf>,
    pub lights: usize,
    pub seed: u64,
    pub messages: Vec<Message>,
    /// Smoothed GPU milliseconds per pass, and of the whole frame.
    pub timings: Vec<(&'static str, f64)>,
    /// Smoothed wall milliseconds of one frame, from encoding until the GPU has finished it and
    /// it is presented.
    pub frame_ms: f64,
    pub timing_source: &'static str,
    /// Facts shown at the top: adapter, model, sky.
    pub adapter: String,
    pub model_name: String,
    pub sky_name: String,
    /// What is loading and for how long, while a load runs.
    pub loading: Option<String>,
    /// Frames of the still view averaged so far, and the count accumulation returns to when
    /// turned back on.
    pub still_frames: u32,
    pub accumulate: usize,
    /// The fly camera is on.
    pub fly: bool,
    /// The `ssdo capture` command that renders the view.
    pub command: String,
    /// The preset file field, and the preset or quality level last taken.
    pub preset_path: String,
    pub preset: Option<crate::preset::Preset>,
    /// What the view shows (the truth, the error, a split) and the truth's progress.
    pub truth: super::truth_ui::TruthPanel,
}

impl PanelState {
    pub fn say(&mut self, text: impl Into<String>, error: bool) {
        let text = text.into();
        if error {
            log::error!("{text}");
        } else {
            log::info!("{text}");
        }
        self.messages.push(Message { text, error });
        let excess = self.messages.len().saturating_sub(4);
        self.messages.drain(..excess);
    }

    /// Folds one frame's per-pass times into the smoothed ones.
    pub fn record_timings(&mut self, passes: &[(&'static str, f64)]) {
        let names_changed =
            self.timings.len() != passes.len() || self.timings.iter().zip(passes).any(|(a, b)| a.0 != b.0);
        if names_changed {
            self.timings = passes.to_vec();
        } else {
            for (smooth, (_, ms)) in self.timings.iter_mut().zip(passes) {
                smooth.1 = 0.9 * smooth.1 + 0.1 * ms;
            }
        }
    }
}

impl PanelState {
    /// The panel of a viewer started with the flags `args` and `settings` on `gpu`, showing
    /// `scene` under `sky`; `timing`: the adapter has timestamp queries.
    pub fn new(
        (args, settings): (&crate::spec::SceneArgs, &Settings),
        gpu: &crate::gpu::Gpu,
        (scene, sky): (&crate::scene::Scene, &crate::scene::Skybox),
        timing: bool,
    ) -> Self {
        Self {
            sky_path: String::new(),
            model_path: String::new(),
            sky_folders: super::loader::skybox_folders(),
            lights: args.lights,
            seed: args.seed,
            messages: Vec::new(),
            timings: Vec::new(),
            frame_ms: 0.0,
            timing_source: if timing { "timestamp queries" } else { "not available on this adapter" },
            adapter: gpu.describe(),
            model_name: scene.model.name.clone(),
            sky_name: sky.name.clone(),
            loading: None,
            still_frames: 0,
            accumulate: if settings.accumulates() {
                settings.knobs.accumulate
            } else {
                crate::render::ACCUMULATE.default
            },
            fly: args.eye.is_some(),
            command: String::new(),
            preset_path: String::new(),
            preset: None,
            truth: super::truth_ui::TruthPanel::default(),
        }
    }
}
