//! Loading skies and models off the render thread. A request runs on its own thread; the result
//! comes back through a channel and is applied between frames, so the old sky or model stays on
//! screen until the new one has loaded completely — or stays for good if loading failed.

use std::path::PathBuf;
use std::sync::mpsc::{channel, Receiver, Sender};

use crate::scene::{self, Model, Skybox};
use crate::Error;

pub enum Loaded {
    Sky(PathBuf, Result<Skybox, Error>),
    Model(PathBuf, Result<Model, Error>),
}

pub struct Loader {
    sender: Sender<Loaded>,
    receiver: Receiver<Loaded>,
    pending: usize,
}

impl Default for Loader {
    fn default() -> Self {
        let (sender, receiver) = channel();
        Self { sender, receiver, pending: 0 }
    }
}

impl Loader {
    pub fn sky(&mut self, path: PathBuf) {
        let sender = self.sender.clone();
        self.pending += 1;
        std::thread::spawn(move || {
            let result = Skybox::load(&path);
            let _ = sender.send(Loaded::Sky(path, result));
        });
    }

    pub fn model(&mut self, path: PathBuf) {
        let sender = self.sender.clone();
        self.pending += 1;
        std::thread::spawn(move || {
            let result = scene::model::load_obj(&path);
            let _ = sender.send(Loaded::Model(path, result));
        });
    }

    /// Whether a load is still running.
    pub fn busy(&self) -> bool {
        self.pending > 0
    }

    /// Results that have arrived since the last call.
    pub fn finished(&mut self) -> Vec<Loaded> {
        let done: Vec<Loaded> = self.receiver.try_iter().collect();
        self.pending -= done.len().min(self.pending);
        done
    }
}

/// The subfolders of `skyboxes/` (read anew each time the list is shown).
pub fn skybox_folders() -> Vec<PathBuf> {
    let mut list: Vec<PathBuf> = std::fs::read_dir(scene::SKYBOX_ROOT)
        .map(|entries| entries.flatten().map(|e| e.path()).filter(|p| p.is_dir()).collect())
        .unwrap_or_default();
    list.sort();
    list
}
