//! What a key (or a dropped file) does in the viewer: the modes' digits, the actions' letters,
//! Escape; the fly camera's keys are the camera controls' (`controls.rs`).

use std::path::PathBuf;

use winit::event_loop::ActiveEventLoop;
use winit::keyboard::KeyCode;

use super::controls::mode_for_key;
use super::panel_state::Action;
use super::truth_ui::Display;

impl super::Viewer {
    pub(super) fn key(&mut self, event_loop: &ActiveEventLoop, key: KeyCode) {
        if let Some(mode) = mode_for_key(key) {
            return self.act(Action::Mode(mode));
        }
        match key {
            KeyCode::F12 => self.act(Action::Screenshot),
            KeyCode::KeyC => self.act(Action::Compare),
            KeyCode::KeyR => self.act(Action::ResetCamera),
            KeyCode::KeyT => self.act(Action::ToggleAccumulation),
            KeyCode::KeyF => self.act(Action::ToggleFly),
            KeyCode::KeyP => self.act(Action::CopyCommand),
            // The truth (G), the current mode's error against it (X), the split view (V: the
            // truth right of the divider, then each mode in turn).
            KeyCode::KeyG => self.panel.truth.toggle(Display::Truth),
            KeyCode::KeyX => self.panel.truth.toggle(Display::Error),
            KeyCode::KeyV => self.panel.truth.cycle_split(),
            KeyCode::Escape => event_loop.exit(),
            _ => {}
        }
    }

    pub(super) fn drop_file(&mut self, path: PathBuf) {
        if path.is_dir() || crate::scene::panorama::is_image(&path) {
            self.act(Action::LoadSky(path));
        } else if crate::scene::is_model(&path) {
            self.act(Action::LoadModel(path));
        } else {
            self.panel.say(
                format!(
                    "{}: drop a skybox folder, a panorama image or a model ({})",
                    path.display(),
                    crate::scene::files::model_extensions()
                ),
                true,
            );
        }
    }
}
