//! The report's outputs: the CSV, the Markdown table (sorted by time, the Pareto front marked)
//! and the files written together.

use super::options::ReportOptions;
use super::row::Row;
use super::Report;
use crate::knobs::{self, KNOBS};
use crate::render::{Mode, SenderSky};
use crate::{output, reference, Result};

fn cell(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(String::new, |v| format!("{v:.digits$}"))
}

impl Row {
    /// What lit the bounce's senders: "march", "irradiance", "lights" (the point lights only),
    /// "none" (no bounce), "—" (no DO); " + far side" where the far side layer sends too.
    pub(super) fn bounce_label(&self) -> String {
        let c = &self.config;
        let senders = match (c.mode, c.bounce()) {
            (Mode::Off | Mode::Ssao, _) => "—",
            (_, Some(SenderSky::Off)) => "lights",
            (_, Some(other)) => other.name(),
            (_, None) => "none",
        };
        if c.far_sky() {
            format!("{senders} + far side and its sky")
        } else if c.far_side() {
            format!("{senders} + far side")
        } else {
            senders.to_string()
        }
    }

    /// "1", "16", "16 (1°)" for 16 frames orbiting 1° each, or "16 (cut)" for 16 frames after a
    /// cut.
    pub fn frames_label(&self) -> String {
        let (frames, orbit) = (self.config.knobs.accumulate, self.config.orbit);
        if orbit != 0.0 {
            format!("{frames} ({orbit}°)")
        } else if self.config.cut {
            format!("{frames} (cut)")
        } else {
            frames.to_string()
        }
    }

    /// The row in the Markdown table.
    fn markdown(&self) -> String {
        let off = self.config.mode == Mode::Off;
        let marks = match (self.pareto, self.preset.is_some()) {
            (true, true) => "★ P",
            (false, true) => "P",
            (true, false) => "★",
            (false, false) => "",
        };
        let blur = match (off, self.config.knobs.blur) {
            (true, _) => "—",
            (false, true) => "on",
            (false, false) => "off",
        };
        format!(
            "| {marks} | {} | {} | {} | {blur} | {} | {} | {} | {:.2} | {:.4} | {:.4} | {:.2} | {:.4} | {} | {} | {} | {} | {} |\n",
            self.config.mode.name(),
            self.config.knobs.variant,
            if off { "—".to_string() } else { self.label() },
            self.bounce_label(),
            if off { "—".to_string() } else { format!("{:.3}", self.radius) },
            self.frames_label(),
            self.ms,
            self.hdr_rmse,
            self.hdr_rmse_near,
            self.hdr_psnr,
            self.flip,
            cell(self.do_rmse, 4),
            cell(self.do_rmse_near, 4),
            cell(self.bounce_ratio, 2),
            cell(self.bounce_seen_ratio, 2),
            cell(self.ao_rmse, 4),
        )
    }

    /// "16" samples, or "4×8" slices × steps for the march ("4×8 pyramid" with the pyramid),
    /// and "half" at half resolution.
    pub fn label(&self) -> String {
        let c = &self.config;
        let mut label = c.knobs.variant.decl().count_short(c.samples(), c.samples(), c.steps());
        if c.pyramid() {
            label.push_str(" pyramid");
        }
        if c.knobs.half_resolution {
            label.push_str(" half");
        }
        label
    }
}

impl Report {
    /// The rows, a line each: the mode, the knobs as the knob table names them (tune's CSV has
    /// the same columns), each where it means something for the row, the radius
    /// as a length, the camera's turn and cut, then what was measured.
    pub fn csv(&self) -> String {
        const MEASURED: [&str; 12] = [
            "ms",
            "ao_rmse_within_r",
            "do_rmse",
            "do_rmse_within_r",
            "bounce_ratio",
            "bounce_seen_ratio",
            "hdr_rmse",
            "hdr_rmse_within_r",
            "hdr_psnr",
            "flip",
            "pareto",
            "preset",
        ];
        let header: Vec<&str> =
            ["mode"].into_iter().chain(knobs::keys()).chain(["radius", "orbit", "cut"]).chain(MEASURED).collect();
        let rows = self.rows.iter().map(|r| {
            let c = &r.config;
            // Empty where a knob means nothing for the row; Off samples nothing, and keeps only
            // its variant (the first knob), whose composite it runs.
            let knobs = KNOBS.iter().enumerate().map(|(i, knob)| {
                let off = c.mode == Mode::Off && i > 0;
                if off || !knob.applies(&c.knobs, Some(c.mode)) {
                    String::new()
                } else {
                    knob.text(&c.knobs)
                }
            });
            let place = [format!("{:.5}", r.radius), c.orbit.to_string(), c.cut.to_string()];
            let measured = [
                format!("{:.4}", r.ms),
                cell(r.ao_rmse, 6),
                cell(r.do_rmse, 6),
                cell(r.do_rmse_near, 6),
                cell(r.bounce_ratio, 3),
                cell(r.bounce_seen_ratio, 3),
                format!("{:.6}", r.hdr_rmse),
                format!("{:.6}", r.hdr_rmse_near),
                format!("{:.3}", r.hdr_psnr),
                format!("{:.5}", r.flip),
                r.pareto.to_string(),
                r.preset.clone().unwrap_or_default(),
            ];
            [c.mode.name().to_string()].into_iter().chain(knobs).chain(place).chain(measured).collect::<Vec<_>>()
        });
        output::csv_text(&header, rows)
    }

    pub fn markdown(&self, options: &ReportOptions) -> String {
        let date = crate::text::utc_minute();
        let r = &self.reference;
        let surfaces = r.valid.iter().filter(|v| **v).count();
        let background = r.valid.len() - surfaces - r.mismatched - r.covered;
        let mut out = format!(
            "# ssdo error-versus-time report\n\n- date: {date}\n- device: {}{}\n- timing: {}, median of {} frames\n\
             - scene: {}, {}x{}, {} lights (seed {}), constant ambient {}, default radius {:.4}\n\
             - truth: ray traced, exact visibility at any distance, one bounce from any surface (each sender lit by \
             its direct light: the point lights, and the sky and ambient it sees), the mean of two traces of {} rays per pixel ({:.1} s in all)\n\
             - the truth's noise floor (RMSE of the mean of two traces): HDR {:.4}, DO {:.4}, AO {:.4}\n- {}\n\
             - pixels measured: {} surface pixels; left out: {} background, {} silhouette (traced and rasterised \
             surfaces differ), {} under a light's cube\n\
             - the truth's bounce by where its senders lie for the camera: {}; \"bounce / seen\" is the estimate's \
             bounce over the seen part, what screen space can reach; \"within two layers\": the sender is the first or \
             the second surface on its pixel's eye ray, what a second depth layer could add\n\
             - the sky the truth's occluders block, by where they lie for the camera: {}\n\
             - frames: the frames averaged (`--accumulate`; 1 is a single frame), with the camera's turn a frame \
             over them in brackets (`--orbit`), or \"(cut)\": after as many frames from {}° around the model, the \
             error taken at the last frame in the truth's view; ms is the \
             cost of one frame with the average running\n\
             - rows sorted by time; ★ = on the Pareto front (no row both faster and closer to the truth); P = the \
             preset given (`--preset`, `--quality`){}; \
             \"within R\" columns compare with the image whose occluders and senders beyond the radius are removed\n\n",
            self.device,
            if self.software { " (a CPU rasteriser, not a GPU)" } else { "" },
            self.timing,
            options.frames,
            options.on.model_name(),
            options.on.size.0,
            options.on.size.1,
            options.on.lights,
            options.on.seed,
            self.ambient,
            self.default_radius,
            options.samples_per_pixel,
            self.reference_seconds,
            self.noise.hdr,
            self.noise.directional,
            self.noise.ao,
            self.pattern.line(),
            surfaces,
            background,
            r.mismatched,
            r.covered,
            bounce_places(r),
            blocked_places(r),
            super::sweep::CUT_DEG,
            options.preset.as_ref().map_or_else(String::new, |p| format!(", '{}'", crate::text::markdown_cell(&p.name))),
        );
        out.push_str(
            "| | mode | variant | samples (slices×steps) | blur | bounce senders | radius | frames (orbit) | ms a frame | HDR RMSE | HDR RMSE within R | HDR PSNR | FLIP | DO RMSE | DO RMSE within R | bounce / truth | bounce / seen | AO RMSE within R |\n",
        );
        out.push_str("|---|---|---|--:|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");
        for row in &self.rows {
            out.push_str(&row.markdown());
        }
        out
    }

    /// Writes report.csv, report.md, report.png and the error maps into `out`, together (a run
    /// killed on the way leaves the last run's set or this run's, never a mix).
    pub fn write(&self, options: &ReportOptions) -> Result<()> {
        let mut batch = output::Batch::default();
        for (name, bytes) in &self.maps {
            batch.stage(&options.out.join(name), bytes)?;
        }
        batch.stage(&options.out.join("report.csv"), self.csv().as_bytes())?;
        batch.stage(&options.out.join("report.md"), self.markdown(options).as_bytes())?;
        let plot = options.out.join("report.png");
        batch.stage(&plot, &self.plot(&plot)?)?;
        batch.commit().map(|_| ())
    }
}

/// The truth's bounce by where its senders lie, as the report's header says it: for the hidden
/// and the facing away, the part the first two surfaces on their eye ray hold beside it.
fn bounce_places(r: &reference::Reference) -> String {
    match (r.bounce_shares(), r.two_layer_shares()) {
        (Some(shares), Some(layered)) => place_list(shares, Some(layered)),
        _ => "no bounce".to_string(),
    }
}

/// The sky the truth's occluders block, by where they lie.
fn blocked_places(r: &reference::Reference) -> String {
    r.blocked_shares().map_or_else(|| "nothing blocked".to_string(), |shares| place_list(shares, None))
}

/// Shares by place ([`reference::SenderPlace::ALL`]) in one line, with the hidden and the facing
/// away's part within two layers where `layered` gives it.
fn place_list(shares: [f64; 4], layered: Option<[f64; 4]>) -> String {
    let two_layers = |place, k: usize| match (place, layered) {
        (reference::SenderPlace::Hidden | reference::SenderPlace::FacingAway, Some(l)) => {
            format!(" ({:.1}% within two layers)", 100.0 * l[k])
        }
        _ => String::new(),
    };
    (reference::SenderPlace::ALL.iter().zip(shares).enumerate())
        .map(|(k, (&place, share))| format!("{} {:.1}%{}", place.name(), 100.0 * share, two_layers(place, k)))
        .collect::<Vec<_>>()
        .join(", ")
}
