//! The report's outputs: the CSV, the Markdown table (sorted by time, the Pareto front marked)
//! and the files written together.

use super::options::ReportOptions;
use super::row::Row;
use super::Report;
use crate::render::{Mode, SenderSky, Variant};
use crate::{output, reference, Result};

fn cell(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(String::new, |v| format!("{v:.digits$}"))
}

impl Row {
    /// "16" samples, or "4×8" slices × steps for the march ("4×8 pyramid" with the pyramid).
    pub(super) fn count_label(variant: Variant, samples: usize, steps: usize, pyramid: bool) -> String {
        // A row's `samples` holds the slices where the variant marches.
        let short = variant.decl().count_short(samples, samples, steps);
        if pyramid {
            format!("{short} pyramid")
        } else {
            short
        }
    }

    /// What lit the bounce's senders: "march", "irradiance", "lights" (the point lights only),
    /// "none" (no bounce), "—" (no DO); " + far side" where the far side layer sends too.
    pub(super) fn bounce_label(mode: Mode, bounce: Option<SenderSky>, (far_side, far_sky): (bool, bool)) -> String {
        let senders = match (mode, bounce) {
            (Mode::Off | Mode::Ssao, _) => "—",
            (_, Some(SenderSky::Off)) => "lights",
            (_, Some(other)) => other.name(),
            (_, None) => "none",
        };
        if far_sky {
            format!("{senders} + far side and its sky")
        } else if far_side {
            format!("{senders} + far side")
        } else {
            senders.to_string()
        }
    }

    /// "1", "16", "16 (1°)" for 16 frames orbiting 1° each, or "16 (cut)" for 16 frames after a
    /// cut.
    pub fn frames_label(&self) -> String {
        if self.orbit != 0.0 {
            format!("{} ({}°)", self.accumulate, self.orbit)
        } else if self.cut {
            format!("{} (cut)", self.accumulate)
        } else {
            self.accumulate.to_string()
        }
    }

    /// The row in the Markdown table.
    fn markdown(&self) -> String {
        let off = self.mode == Mode::Off;
        let marks = match (self.pareto, self.preset.is_some()) {
            (true, true) => "★ P",
            (false, true) => "P",
            (true, false) => "★",
            (false, false) => "",
        };
        let blur = match (off, self.blur) {
            (true, _) => "—",
            (false, true) => "on",
            (false, false) => "off",
        };
        format!(
            "| {marks} | {} | {} | {} | {blur} | {} | {} | {} | {:.2} | {:.4} | {:.4} | {:.2} | {:.4} | {} | {} | {} | {} | {} |\n",
            self.mode.name(),
            self.variant,
            if off { "—".to_string() } else { self.label() },
            Row::bounce_label(self.mode, self.bounce, (self.far_side, self.far_sky)),
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

    pub fn label(&self) -> String {
        let count = Self::count_label(self.variant, self.samples, self.steps, self.pyramid);
        if self.half_resolution {
            format!("{count} half")
        } else {
            count
        }
    }
}

impl Report {
    pub fn csv(&self) -> String {
        const HEADER: [&str; 24] = [
            "mode",
            "variant",
            "samples",
            "steps",
            "pyramid",
            "blur",
            "bounce",
            "radius",
            "accumulate",
            "orbit",
            "half",
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
            "cut",
        ];
        let rows = self.rows.iter().map(|r| -> [String; 24] {
            [
                r.mode.name().to_string(),
                r.variant.to_string(),
                r.samples.to_string(),
                r.steps.to_string(),
                r.pyramid.to_string(),
                r.blur.to_string(),
                Row::bounce_label(r.mode, r.bounce, (r.far_side, r.far_sky)),
                format!("{:.5}", r.radius),
                r.accumulate.to_string(),
                r.orbit.to_string(),
                r.half_resolution.to_string(),
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
                r.cut.to_string(),
            ]
        });
        output::csv_text(&HEADER, rows)
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
