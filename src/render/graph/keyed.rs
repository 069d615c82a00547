//! A pass's pipelines by key ([`KeyedPipeline`]).

/// The pipelines a pass has built, one per key it was asked for (a plan's variant, view,
/// resolution...), the current one first. A key asked for again takes its pipeline back instead
/// of building it anew: a viewer switching between modes or variants it has shown, and a report
/// sweeping them, build each pipeline once (on lavapipe a mode switch spent 0.12-0.23 s
/// rebuilding what it had had a moment before). At most [`KEPT_PIPELINES`] are kept, the least
/// recently used going first: a pipeline holds its compiled code, which on a CPU driver lives in
/// the machine's memory.
pub struct KeyedPipeline<K, P = wgpu::RenderPipeline> {
    built: Vec<(K, P)>,
    /// `built[0]` is the pipeline of the pass's current key (not where the plan has no step for
    /// the pass).
    current: bool,
}

/// The pipelines one pass keeps for the keys it may be asked for again: the four modes' worth.
/// (Measured on lavapipe, docs/performance.md: 2 kept the stability suite's mode switching at
/// 80 s against 63 with 4, and 8 saved nothing more for 55 MiB more of the report's peak.)
pub const KEPT_PIPELINES: usize = 4;

impl<K: PartialEq + Copy, P> Default for KeyedPipeline<K, P> {
    fn default() -> Self {
        Self::new()
    }
}

impl<K: PartialEq + Copy, P> KeyedPipeline<K, P> {
    pub fn new() -> Self {
        Self { built: Vec::new(), current: false }
    }

    /// The pipeline for `key`, which becomes the current one: kept from before, or built by
    /// `build`.
    pub fn ensure(&mut self, key: K, build: impl FnOnce(K) -> P) -> &P {
        match self.built.iter().position(|(k, _)| *k == key) {
            Some(i) => self.built[..=i].rotate_right(1),
            None => {
                self.built.truncate(KEPT_PIPELINES - 1);
                self.built.insert(0, (key, build(key)));
            }
        }
        self.current = true;
        &self.built[0].1
    }

    /// The current key and its pipeline.
    pub fn get(&self) -> Option<(&K, &P)> {
        self.built.first().filter(|_| self.current).map(|(k, p)| (k, p))
    }

    /// No key is current (the plan has no step for the pass); the pipelines are kept for when
    /// one comes back.
    pub fn park(&mut self) {
        self.current = false;
    }

    /// Drops every pipeline: what they were built with (a bind group layout) is gone.
    pub fn clear(&mut self) {
        self.built.clear();
        self.current = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A key asked for again gets the pipeline built for it before, including after the pass
    /// left the plan; past `KEPT_PIPELINES` keys the least recently used is built again.
    #[test]
    fn a_key_asked_for_again_takes_its_pipeline_back() {
        let mut builds = 0;
        let mut pipelines: KeyedPipeline<u32, u32> = KeyedPipeline::new();
        let mut ask = |p: &mut KeyedPipeline<u32, u32>, key| {
            *p.ensure(key, |k| {
                builds += 1;
                k * 10
            })
        };
        assert_eq!((ask(&mut pipelines, 1), ask(&mut pipelines, 2), ask(&mut pipelines, 1)), (10, 20, 10));
        pipelines.park();
        assert!(pipelines.get().is_none(), "no key is current while the plan has no step");
        assert_eq!((ask(&mut pipelines, 2), pipelines.get().map(|(k, p)| (*k, *p))), (20, Some((2, 20))));
        for key in 3..3 + KEPT_PIPELINES as u32 {
            ask(&mut pipelines, key);
        }
        ask(&mut pipelines, 2);
        ask(&mut pipelines, 1);
        pipelines.clear();
        ask(&mut pipelines, 2);
        // 1 and 2 once, the new keys, 2 and 1 again (the new keys pushed them out), 2 after the clear.
        assert_eq!(builds, 2 + KEPT_PIPELINES + 3);
    }
}
