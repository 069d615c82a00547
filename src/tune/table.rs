//! Tune's outputs: the front as a Markdown table and every measured setting as CSV, the pick as a
//! preset and as an `ssdo capture` command, written together into the output folder.

use std::fmt::Write as _;

use super::{Point, Tune, TuneOptions, Verdict};
use crate::preset::{Measured, Preset};
use crate::{output, Result};

fn cell(v: Option<f64>) -> String {
    v.map_or_else(String::new, |v| format!("{v:.4}"))
}

impl Point {
    /// The setting in words ("off" for the Off frame).
    pub fn label(&self) -> String {
        match (&self.name, self.knobs) {
            (Some(name), Some(k)) => format!("{name} ({})", k.label()),
            (_, Some(k)) => k.label(),
            (_, None) => "off (no sampling)".to_string(),
        }
    }
}

impl Tune {
    /// The lines that say what the pick is and why (the budget, the edges).
    pub fn verdict_lines(&self, options: &TuneOptions) -> Vec<String> {
        let budget = self.budget_ms.map_or_else(String::new, |b| format!("{b:.2} ms ({:.1}× Off)", b / self.off.ms));
        let cheapest = self.cheapest();
        let best = self.most_accurate();
        let target = options.target_error.map_or_else(String::new, |e| format!("{e}"));
        let line = match (&self.verdict, self.picked()) {
            (Verdict::BelowCheapest, _) => format!(
                "the budget of {budget} is below every setting measured: the cheapest is {} at {:.2} ms",
                cheapest.label(),
                cheapest.ms
            ),
            (Verdict::NotBinding, Some(p)) => format!(
                "the budget of {budget} is not binding: the most accurate setting measured, {}, costs {:.2} ms",
                p.label(),
                p.ms
            ),
            (Verdict::TargetMissed, Some(p)) => format!(
                "no setting measured reaches HDR RMSE {target}{}: the closest is {} at {:.4} (the most accurate \
                 measured at any time: {:.4})",
                if budget.is_empty() { String::new() } else { format!(" within {budget}") },
                p.label(),
                p.hdr_rmse,
                best.hdr_rmse
            ),
            (Verdict::Target, Some(p)) => {
                format!("the cheapest setting measured with HDR RMSE ≤ {target}: {} at {:.2} ms", p.label(), p.ms)
            }
            (_, Some(p)) => format!("the most accurate setting within {budget}: {} at {:.2} ms", p.label(), p.ms),
            (_, None) => String::new(),
        };
        vec![line]
    }

    /// The front (sorted by time) as a Markdown document, with the run's facts.
    pub fn markdown(&self, options: &TuneOptions) -> String {
        let mut out = String::new();
        let _ = writeln!(out, "# ssdo tune: {} in {}\n", options.mode, options.on.name());
        let software = if self.software { " (a CPU rasteriser, not a GPU)" } else { "" };
        let _ = writeln!(out, "- device: {}{software}", self.device);
        let _ = writeln!(
            out,
            "- {} at {}x{}, {} lights (seed {}); views: yaw {} degrees from the report's",
            options.on.name(),
            options.on.size.0,
            options.on.size.1,
            options.on.lights,
            options.on.seed,
            self.views.iter().map(|d| format!("{d:+}")).collect::<Vec<_>>().join(", ")
        );
        let _ = writeln!(
            out,
            "- timing: {}, median of {} frames after two warm-up frames, on the report's view (a frame costs the same from the others); \
             the {} front settings within {:.0}% of the budget timed again as long",
            self.timing,
            options.frames,
            self.retimed,
            100.0 * super::RETIME_MARGIN
        );
        let _ = writeln!(
            out,
            "- truth: as the report's, 2 × {} rays a pixel a view; its noise floor, HDR RMSE {:.4}",
            options.samples_per_pixel, self.noise_hdr
        );
        let searched = self.points.iter().filter(|p| p.candidate.is_some()).count();
        let presets = self.points.len() - searched;
        let _ = writeln!(
            out,
            "- measured: {searched} settings of the search (at most {}){} and Off ({:.2} ms) in {:.0} s",
            options.max_settings,
            if presets > 0 { format!(", {presets} presets (--also)") } else { String::new() },
            self.off.ms,
            self.seconds
        );
        for line in self.verdict_lines(options) {
            let _ = writeln!(out, "- **{line}**");
        }
        let _ = writeln!(
            out,
            "\nThe Pareto front (no measured setting both faster and closer to the truth); ▶ = the pick:\n"
        );
        out.push_str("| | ms a frame | × Off | HDR RMSE | DO RMSE | FLIP | setting |\n|---|--:|--:|--:|--:|--:|---|\n");
        let mut front: Vec<(usize, &Point)> = self.points.iter().enumerate().filter(|(_, p)| p.front).collect();
        front.sort_by(|a, b| a.1.ms.total_cmp(&b.1.ms));
        for (i, p) in front {
            let _ = writeln!(
                out,
                "| {} | {:.2} | {:.1} | {:.4} | {} | {:.4} | {} |",
                if Some(i) == self.pick { "▶" } else { "" },
                p.ms,
                p.ms / self.off.ms,
                p.hdr_rmse,
                cell(p.do_rmse),
                p.flip,
                crate::text::markdown_cell(&p.label())
            );
        }
        out
    }

    /// Every measured setting, one row each, the front marked.
    pub fn csv(&self, options: &TuneOptions) -> String {
        let measured = ["front", "pick", "ms", "off_multiple", "frames_timed", "hdr_rmse", "do_rmse", "flip"];
        let header: Vec<&str> = measured
            .into_iter()
            .chain(["hdr_rmse_per_view", "mode"])
            .chain(crate::knobs::keys())
            .chain(["preset"])
            .collect();
        let rows = self.points.iter().enumerate().filter_map(|(i, p)| {
            let k = p.knobs?;
            let per_view: Vec<String> = p.hdr_per_view.iter().map(|e| format!("{e:.6}")).collect();
            let measured = [
                p.front.to_string(),
                (Some(i) == self.pick).to_string(),
                format!("{:.4}", p.ms),
                format!("{:.3}", p.ms / self.off.ms),
                p.frames_timed.to_string(),
                format!("{:.6}", p.hdr_rmse),
                p.do_rmse.map_or_else(String::new, |d| format!("{d:.6}")),
                format!("{:.6}", p.flip),
                per_view.join(" "),
                options.mode.to_string(),
            ];
            let knobs = crate::knobs::KNOBS.iter().map(|knob| knob.text(&k));
            Some(measured.into_iter().chain(knobs).chain([p.name.clone().unwrap_or_default()]).collect::<Vec<_>>())
        });
        output::csv_text(&header, rows)
    }

    /// The pick as a preset, with what was measured of it.
    pub fn preset(&self, options: &TuneOptions) -> Option<Preset> {
        let p = self.picked()?;
        let knobs = p.knobs?;
        let name = match self.budget_ms {
            Some(b) => format!(
                "{} {} {}x{} within {b:.1} ms",
                options.mode,
                options.on.name(),
                options.on.size.0,
                options.on.size.1
            ),
            None => format!("{} {} {}x{}", options.mode, options.on.name(), options.on.size.0, options.on.size.1),
        };
        Some(Preset {
            name,
            mode: options.mode,
            knobs,
            measured: Some(Measured {
                device: self.device.clone(),
                scene: options.on.name(),
                size: options.on.size,
                lights: options.on.lights,
                budget_ms: self.budget_ms,
                ms: p.ms,
                off_ms: self.off.ms,
                hdr_rmse: p.hdr_rmse,
                do_rmse: p.do_rmse,
                flip: p.flip,
                views: self.views.len(),
                frames_timed: p.frames_timed,
                date: self.date.clone(),
            }),
        })
    }

    /// The pick as a command that renders it, or `None` without a pick: on the model file, or on
    /// the named scene (`--scene`, which every command takes).
    pub fn capture_command(&self, options: &TuneOptions) -> Option<String> {
        let knobs = self.picked()?.knobs?;
        let mut words = vec!["capture".to_string()];
        if options.on.model.is_none() && options.on.scene != "cornell" {
            words.extend(["--scene".into(), options.on.scene.clone()]);
        }
        words.extend(["--mode".into(), options.mode.name().into()]);
        words.extend(["--size".into(), format!("{}x{}", options.on.size.0, options.on.size.1)]);
        if let Some(model) = &options.on.model {
            words.extend(["--model".into(), model.display().to_string()]);
        }
        if let Some(sky) = &options.on.skybox {
            words.extend(["--skybox".into(), sky.display().to_string()]);
        }
        if options.on.no_surface_maps {
            words.push("--no-surface-maps".into());
        }
        if options.on.lights != crate::scene::DEFAULT_LIGHTS {
            words.extend(["--lights".into(), options.on.lights.to_string()]);
        }
        if options.on.seed != 1 {
            words.extend(["--seed".into(), options.on.seed.to_string()]);
        }
        words.extend(knobs.flags(self.default_radius));
        Some(crate::reproduce::shell_line(&words))
    }

    /// Writes front.csv, tune.md and (with a pick) preset.json into the output folder, together.
    pub fn write(&self, options: &TuneOptions) -> Result<Vec<std::path::PathBuf>> {
        output::remove_stale_temporaries(&options.out);
        let mut batch = output::Batch::default();
        batch.stage(&options.out.join("front.csv"), self.csv(options).as_bytes())?;
        batch.stage(&options.out.join("tune.md"), self.markdown(options).as_bytes())?;
        if let Some(preset) = self.preset(options) {
            batch.stage(&options.out.join("preset.json"), preset.to_text().as_bytes())?;
        }
        batch.commit()
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Candidate, Point, Tune, TuneOptions, Verdict};
    use crate::knobs::Knobs;
    use crate::render::{Mode, Variant};
    use crate::report::TruthScene;

    fn point(ms: f64, hdr_rmse: f64, slices: usize) -> Point {
        let candidate = Candidate::new(Mode::Ssdo, Knobs { slices, ..Knobs::for_variant(Variant::March) });
        Point {
            candidate: Some(candidate),
            knobs: Some(candidate.knobs),
            name: None,
            ms,
            frames_timed: 18,
            hdr_rmse,
            do_rmse: Some(hdr_rmse),
            flip: 0.1,
            hdr_per_view: vec![hdr_rmse; 3],
            front: true,
        }
    }

    fn tune(pick: Option<usize>, verdict: Verdict, budget_ms: f64) -> Tune {
        Tune {
            points: vec![point(10.0, 0.05, 1), point(20.0, 0.02, 2)],
            off: Point { candidate: None, knobs: None, ..point(5.0, 0.09, 1) },
            pick,
            verdict,
            budget_ms: Some(budget_ms),
            device: "llvmpipe".into(),
            software: true,
            timing: "GPU timestamp queries",
            default_radius: 0.3,
            views: vec![0.0, -20.0, 20.0],
            noise_hdr: 0.01,
            seconds: 1.0,
            retimed: 0,
            date: "2026-12-03 12:00 UTC".into(),
        }
    }

    fn options() -> TuneOptions {
        TuneOptions {
            on: TruthScene { lights: 8, ..TruthScene::named("open", (320, 240)) },
            mode: Mode::Ssdo,
            budget: None,
            target_error: Some(0.01),
            views: 3,
            spread: 20.0,
            frames: 6,
            samples_per_pixel: 128,
            max_settings: 60,
            also: Vec::new(),
            out: "tune".into(),
        }
    }

    #[test]
    fn each_edge_says_what_it_is() {
        let o = options();
        let below = tune(None, Verdict::BelowCheapest, 2.0).verdict_lines(&o).join(" ");
        assert!(below.contains("budget of 2.00 ms (0.4× Off) is below every setting measured"), "{below}");
        assert!(
            below.contains("the cheapest is march 1 slices × 16 steps") && below.contains("at 10.00 ms"),
            "{below}"
        );
        let free = tune(Some(1), Verdict::NotBinding, 100.0).verdict_lines(&o).join(" ");
        assert!(free.contains("is not binding") && free.contains("costs 20.00 ms"), "{free}");
        let missed = tune(Some(1), Verdict::TargetMissed, 100.0).verdict_lines(&o).join(" ");
        assert!(missed.contains("no setting measured reaches HDR RMSE 0.01 within 100.00 ms"), "{missed}");
        let t = tune(Some(0), Verdict::Best, 15.0);
        let table = t.markdown(&o);
        assert!(table.contains("median of 6 frames"), "{table}");
        assert!(table.contains("the most accurate setting within 15.00 ms (3.0× Off)"), "{table}");
        // No preset and no command without a pick; a named scene is the command's `--scene`.
        let none = tune(None, Verdict::BelowCheapest, 2.0);
        assert!(none.preset(&o).is_none() && none.capture_command(&o).is_none());
        let command = t.capture_command(&o).unwrap();
        assert!(command.starts_with("ssdo capture --scene open --mode ssdo --size 320x240 --slices 1"), "{command}");
    }

    #[test]
    fn a_name_with_commas_quotes_or_a_formula_stays_in_its_own_csv_field() {
        let o = options();
        let mut t = tune(Some(0), Verdict::Best, 15.0);
        let names = ["ultra, 8 ms", "a \"quoted\" name", "=cmd|' /C calc'!A0", "plain"];
        t.points = names.iter().map(|n| Point { name: Some(n.to_string()), ..point(10.0, 0.05, 1) }).collect();
        let text = t.csv(&o);
        let mut reader = csv::Reader::from_reader(text.as_bytes());
        let width = reader.headers().unwrap().len();
        let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
        assert_eq!(rows.len(), names.len(), "{text}");
        for (row, name) in rows.iter().zip(names) {
            assert_eq!(row.len(), width, "{text}");
            let kept = &row[width - 1];
            // A formula is kept as text: a quote mark before it, the name otherwise whole.
            assert_eq!(kept.trim_start_matches('\''), name, "{text}");
            assert!(!kept.starts_with('='), "{text}");
        }
        // The table's rows keep their eight unescaped pipes.
        let table = t.markdown(&o);
        let pipes = |l: &str| l.matches('|').count() - l.matches("\\|").count();
        assert!(table.lines().filter(|l| l.starts_with('|')).all(|l| pipes(l) == 8), "{table}");
    }
}
