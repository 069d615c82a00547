//! How much of a single frame's error is its sample pattern's luck. Each frame of an average
//! samples with the next entry of the sample schedule (`render::kernel::schedule`); a single
//! frame takes entry 0, as every view's first frame does, and a camera turning too fast to keep
//! any history shows a later entry every frame. The report renders the default SSAO+SSDO setting's
//! single frame under each entry a default average goes through and measures each against the
//! truth: two single-frame rows closer than that spread differ by their patterns, not by their
//! settings, and a fast-turning row's last frame is one of those entries.

use super::measure::{Errors, Frame, Truth};
use super::sweep::Config;
use crate::gpu::Gpu;
use crate::headless::capture::capture_path;
use crate::knobs::Knobs;
use crate::render::{Mode, Renderer, Settings};
use crate::scene::OrbitCamera;
use crate::Result;

/// One error over the schedule's entries: under entry 0 (a single-frame row's), and its least
/// and greatest.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spread {
    pub first: f64,
    pub min: f64,
    pub max: f64,
}

impl Spread {
    fn of(values: &[f64]) -> Self {
        let first = values.first().copied().unwrap_or(0.0);
        let min = values.iter().copied().fold(f64::INFINITY, f64::min);
        let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Self { first, min, max }
    }

    /// "min-max (first)", to `digits` places.
    fn text(&self, digits: usize) -> String {
        format!("{:.digits$}-{:.digits$} ({:.digits$})", self.min, self.max, self.first)
    }
}

/// The default single frame's errors over the schedule's entries.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatternSpread {
    /// The entries measured: those a default average goes through.
    pub entries: u32,
    pub hdr: Spread,
    pub directional: Spread,
    /// SSAO's part: the AO within R.
    pub ao: Spread,
}

impl PatternSpread {
    /// The report's header line (and the log's).
    pub fn line(&self) -> String {
        format!(
            "a single frame's sample pattern: the default SSAO+SSDO setting's single frame under each of the {} \
             entries of the sample schedule a default average goes through (a view turning too fast to keep any \
             history shows a later entry every frame): HDR RMSE {}, DO RMSE {}, AO RMSE within R {} (in brackets \
             entry 0, the single-frame rows' pattern); single-frame rows closer than this differ by their patterns",
            self.entries,
            self.hdr.text(4),
            self.directional.text(4),
            self.ao.text(4),
        )
    }
}

/// Renders the default SSAO+SSDO setting's single frame at `radius` from `camera` under each
/// entry of the schedule a default average goes through, and measures each against `truth`.
pub(crate) fn measure(
    gpu: &Gpu,
    renderer: &mut Renderer,
    camera: &OrbitCamera,
    (truth, radius, ambient): (&Truth, f32, f32),
) -> Result<PatternSpread> {
    let entries = Settings::default().knobs.accumulate as u32;
    renderer.settings = Config::new(Mode::Both, Knobs { accumulate: 1, ..Knobs::default() }).settings(radius);
    let measured: Result<Vec<Errors>> = (0..entries)
        .map(|entry| {
            renderer.start_schedule_at(entry);
            capture_path(gpu, renderer, |_| *camera)?;
            Ok(Frame::read(gpu, renderer, Mode::Both)?.errors(truth, ambient))
        })
        .collect();
    renderer.start_schedule_at(0);
    let errors = measured?;
    let of = |value: &dyn Fn(&Errors) -> Option<f64>| {
        Spread::of(&errors.iter().map(|e| value(e).unwrap_or(f64::NAN)).collect::<Vec<_>>())
    };
    Ok(PatternSpread {
        entries,
        hdr: of(&|e| Some(e.hdr_rmse)),
        directional: of(&|e| e.do_rmse),
        ao: of(&|e| e.ao_rmse),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_spread_keeps_the_first_entry_and_the_range() {
        let s = Spread::of(&[0.0368, 0.0391, 0.0360, 0.0371]);
        assert_eq!(s, Spread { first: 0.0368, min: 0.0360, max: 0.0391 });
        assert_eq!(s.text(4), "0.0360-0.0391 (0.0368)");
    }
}
