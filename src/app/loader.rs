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

/// A finished load and the order it was asked for in.
type Ticket = (u64, Loaded);

/// Loads run in parallel and may finish in any order; only the newest request of each kind is
/// applied. An earlier load that finishes after a newer request of its kind was made, before or
/// after that one finished, is dropped, so the panel never names a model or sky other than the
/// one on screen, and the last thing asked for is what ends up there (or, if it fails, what was
/// there before).
pub struct Loader {
    sender: Sender<Ticket>,
    receiver: Receiver<Ticket>,
    pending: usize,
    next: u64,
    /// The newest request of each kind: (sky, model).
    requested: (u64, u64),
    /// What the newest request loads and since when, for the panel's progress line.
    current: Option<(String, std::time::Instant)>,
}

impl Default for Loader {
    fn default() -> Self {
        let (sender, receiver) = channel();
        Self { sender, receiver, pending: 0, next: 0, requested: (0, 0), current: None }
    }
}

impl Loader {
    fn ticket(&mut self) -> u64 {
        self.next += 1;
        self.pending += 1;
        self.next
    }

    /// Runs `load` on a thread of its own; its result arrives with the returned ticket.
    fn start(&mut self, what: String, load: impl FnOnce() -> Loaded + Send + 'static) -> u64 {
        let (sender, id) = (self.sender.clone(), self.ticket());
        self.current = Some((what, std::time::Instant::now()));
        std::thread::spawn(move || {
            let _ = sender.send((id, load()));
        });
        id
    }

    pub fn sky(&mut self, path: PathBuf) {
        let what = format!("sky {}", path.display());
        self.requested.0 = self.start(what, move || {
            let result = Skybox::load(&path);
            Loaded::Sky(path, result)
        });
    }

    pub fn model(&mut self, path: PathBuf) {
        let what = format!("model {}", path.display());
        self.requested.1 = self.start(what, move || {
            let result = scene::load_model_file(&path);
            Loaded::Model(path, result)
        });
    }

    /// Whether a load is still running.
    pub fn busy(&self) -> bool {
        self.pending > 0
    }

    /// "loading model x.obj… 3 s" while a load runs.
    pub fn progress(&self) -> Option<String> {
        let (what, since) = self.current.as_ref().filter(|_| self.busy())?;
        Some(format!("loading {what}… {:.0} s", since.elapsed().as_secs_f64()))
    }

    /// Results that have arrived since the last call that are still the newest request of
    /// their kind; the others are dropped (and logged).
    pub fn finished(&mut self) -> Vec<Loaded> {
        self.accept(self.receiver.try_iter().collect())
    }

    fn accept(&mut self, done: Vec<Ticket>) -> Vec<Loaded> {
        self.pending -= done.len().min(self.pending);
        let mut out = Vec::new();
        for (id, loaded) in done {
            let (newest, path) = match &loaded {
                Loaded::Sky(p, _) => (self.requested.0, p),
                Loaded::Model(p, _) => (self.requested.1, p),
            };
            if id == newest {
                out.push(loaded);
            } else {
                log::info!("{}: a newer request replaced this load; dropped", path.display());
            }
        }
        out
    }
}

/// The skies under `skyboxes/`: its subfolders and the panorama images beside them (read anew
/// each time the list is shown).
pub fn skybox_folders() -> Vec<PathBuf> {
    let mut list: Vec<PathBuf> = std::fs::read_dir(scene::asset(scene::SKYBOX_ROOT))
        .map(|entries| {
            entries.flatten().map(|e| e.path()).filter(|p| p.is_dir() || scene::panorama::is_image(p)).collect()
        })
        .unwrap_or_default();
    list.sort();
    list
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model(id: u64, name: &str) -> Ticket {
        (id, Loaded::Model(PathBuf::from(name), Err(Error::Setting("stand-in".into()))))
    }

    fn names(list: &[Loaded]) -> Vec<String> {
        list.iter()
            .map(|l| match l {
                Loaded::Sky(p, _) | Loaded::Model(p, _) => p.display().to_string(),
            })
            .collect()
    }

    #[test]
    fn a_slow_earlier_load_never_replaces_a_newer_one() {
        let mut loader = Loader::default();
        let (slow, fast) = (loader.ticket(), loader.ticket());
        loader.requested.1 = fast;
        // The newer one finishes first and is applied; the older one, later, is dropped.
        assert_eq!(names(&loader.accept(vec![model(fast, "fast.obj")])), ["fast.obj"]);
        assert!(loader.accept(vec![model(slow, "slow.obj")]).is_empty());
        assert!(!loader.busy());
    }

    #[test]
    fn an_earlier_load_is_dropped_while_a_newer_one_runs() {
        let mut loader = Loader::default();
        let first = loader.ticket();
        loader.requested.1 = first;
        let second = loader.ticket();
        loader.requested.1 = second;
        assert!(loader.accept(vec![model(first, "first.obj")]).is_empty());
        assert!(loader.busy(), "the newer load still runs");
        assert_eq!(names(&loader.accept(vec![model(second, "second.obj")])), ["second.obj"]);
    }
}
