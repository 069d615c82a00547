//! One measured configuration of the report, and the truth's noise floor beside the rows.

use super::sweep::Config;

/// One measured configuration.
#[derive(Clone, Debug)]
pub struct Row {
    /// What was measured: the mode, the knobs it ran with, the camera's turn a frame and whether
    /// the frames came after a cut. The far side layer (and its sky) as drawn: only where the
    /// scene has point lights to light it.
    pub config: Config,
    /// Sampling radius in model units (0 for Off).
    pub radius: f32,
    /// Median GPU milliseconds of the whole frame (one frame, with accumulation running).
    pub ms: f64,
    /// AO against the within-R AO, its definition (a diagnostic).
    pub ao_rmse: Option<f64>,
    /// DO (sky light + bounce, before albedo) against the truth, and against the within-R image.
    pub do_rmse: Option<f64>,
    pub do_rmse_near: Option<f64>,
    /// The mean of the DO's bounce over the measured pixels, over the truth's (1 is unbiased).
    pub bounce_ratio: Option<f64>,
    /// The same mean over the truth's bounce from senders the camera sees (`SenderPlace::Seen`):
    /// how much of what the screen can reach the estimate reaches.
    pub bounce_seen_ratio: Option<f64>,
    /// Linear HDR radiance against the truth, and against the within-R image.
    pub hdr_rmse: f64,
    pub hdr_rmse_near: f64,
    pub hdr_psnr: f64,
    /// FLIP of the displayed images, on the valid surface pixels.
    pub flip: f64,
    /// No other row is both as fast and as accurate (HDR RMSE against the truth).
    pub pareto: bool,
    /// The preset this row measures (`--preset`, `--quality`), by name.
    pub preset: Option<String>,
}

/// The truth's own noise: RMSE of the mean of two independent traces (half their difference).
#[derive(Clone, Copy, Debug, Default)]
pub struct NoiseFloor {
    pub hdr: f64,
    pub directional: f64,
    pub ao: f64,
}

impl Row {
    /// The row in one line, as the progress bar shows it.
    pub(super) fn progress_line(&self) -> String {
        let c = &self.config;
        format!(
            "{} {} {}, radius {:.3}, blur {}, bounce {}, {} frames: {:.2} ms, HDR RMSE {:.4}",
            c.mode,
            c.knobs.variant,
            self.label(),
            self.radius,
            c.knobs.blur,
            self.bounce_label(),
            self.frames_label(),
            self.ms,
            self.hdr_rmse
        )
    }
}
