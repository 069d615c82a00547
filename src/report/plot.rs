//! The report's plot: error against time, with the Pareto front.

use std::path::Path;

use super::row::Row;
use super::Report;
use crate::knobs::Knobs;
use crate::render::{Mode, Variant};
use crate::{output, Error, Result};

impl Report {
    /// Log-log plot of HDR RMSE against the truth, against milliseconds a frame: every mode on
    /// one chart, one line per mode × variant through its sample counts (a single frame at full
    /// resolution, blur on, the first radius); for the default variant, dashed lines with hollow
    /// markers through its most accumulated still rows (at full and at half resolution); every
    /// other row as a faint point, and the Pareto front as a dashed black line.
    /// The plot as PNG bytes (`path` names it in errors).
    pub fn plot(&self, path: &Path) -> Result<Vec<u8>> {
        use plotters::prelude::*;
        let (w, h) = (1024u32, 680u32);
        let mut buffer = vec![0u8; (w * h * 3) as usize];
        let font_result =
            plotters::style::register_font("sans-serif", FontStyle::Normal, epaint_default_fonts::UBUNTU_LIGHT);
        if font_result.is_err() {
            return Err(Error::output(path, "the plot font could not be loaded"));
        }
        let fail = |e: &dyn std::fmt::Display| Error::output(path, format!("plotting failed: {e}"));
        {
            let root = BitMapBackend::with_buffer(&mut buffer, (w, h)).into_drawing_area();
            root.fill(&WHITE).map_err(|e| fail(&e))?;
            let rows = &self.rows;
            let ms: Vec<f64> = rows.iter().map(|r| r.ms).collect();
            let errors: Vec<f64> = rows.iter().map(|r| r.hdr_rmse).collect();
            let mut chart = ChartBuilder::on(&root)
                .caption("HDR RMSE against the one ray-traced truth, against the time of one frame", ("sans-serif", 22))
                .margin(16)
                .x_label_area_size(48)
                .y_label_area_size(72)
                .build_cartesian_2d(log_axis(&ms), log_axis(&errors))
                .map_err(|e| fail(&e))?;
            chart
                .configure_mesh()
                .x_labels(12)
                .y_labels(12)
                .x_label_formatter(&|v| format!("{:.1}", 10f64.powf(*v)))
                .y_label_formatter(&|v| format!("{:.4}", 10f64.powf(*v)))
                .x_desc(format!(
                    "frame time, ms ({})",
                    if self.software { "lavapipe / llvmpipe, a CPU rasteriser" } else { "GPU" }
                ))
                .y_desc("RMSE of linear HDR radiance")
                .label_style(("sans-serif", 16))
                .draw()
                .map_err(|e| fail(&e))?;
            let colours =
                [RGBColor(120, 120, 120), RGBColor(31, 119, 180), RGBColor(255, 127, 14), RGBColor(44, 160, 44)];
            // Every row, faint: the other radii and blur settings.
            chart
                .draw_series(rows.iter().map(|r| {
                    let m = Mode::ALL.iter().position(|m| *m == r.config.mode).unwrap_or(0);
                    Circle::new((log_value(r.ms), log_value(r.hdr_rmse)), 2, colours[m].mix(0.35).filled())
                }))
                .map_err(|e| fail(&e))?;
            draw_lines(&mut chart, lines(rows), &colours).map_err(|e| fail(&e))?;
            let (front, stairs) = pareto_stairs(rows);
            chart
                .draw_series(DashedLineSeries::new(stairs, 6, 4, BLACK.stroke_width(2)))
                .map_err(|e| fail(&e))?
                .label("Pareto front")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], BLACK.stroke_width(2)));
            chart.draw_series(front.iter().map(|p| Cross::new(*p, 7, BLACK.stroke_width(2)))).map_err(|e| fail(&e))?;
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font(("sans-serif", 15))
                .draw()
                .map_err(|e| fail(&e))?;
            root.present().map_err(|e| fail(&e))?;
        }
        let image = image::RgbImage::from_raw(w, h, buffer).expect("plot buffer has its size");
        output::png_bytes(path, &image::DynamicImage::ImageRgb8(image).to_rgba8())
    }
}

type Chart<'a, 'b> = plotters::chart::ChartContext<
    'a,
    plotters::backend::BitMapBackend<'b>,
    plotters::coord::cartesian::Cartesian2d<
        plotters::coord::types::RangedCoordf64,
        plotters::coord::types::RangedCoordf64,
    >,
>;
type DrawError = plotters::drawing::DrawingAreaErrorKind<
    <plotters::backend::BitMapBackend<'static> as plotters::backend::DrawingBackend>::ErrorType,
>;

/// Draws the lines in their modes' `colours`: the single-frame ones solid with filled markers,
/// the accumulated ones dashed with hollow markers, each with its legend entry.
fn draw_lines(
    chart: &mut Chart<'_, '_>,
    lines: Vec<Line>,
    colours: &[plotters::style::RGBColor; 4],
) -> std::result::Result<(), DrawError> {
    use plotters::prelude::*;
    for line in lines {
        let (colour, variant) = (colours[line.mode_index], line.kind.variant);
        let style = colour.mix(variant.decl().plot_opacity).stroke_width(variant.decl().plot_width);
        let points = line.points;
        if line.kind.accumulate > 1 {
            let dash = if line.kind.half_resolution { 3 } else { 8 };
            chart
                .draw_series(DashedLineSeries::new(points.clone(), dash, 4, style))?
                .label(line.label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 8, y), (x + 16, y)], style));
            chart.draw_series(points.iter().map(|p| Circle::new(*p, 5, colour.stroke_width(2))))?;
            continue;
        }
        chart
            .draw_series(LineSeries::new(points.clone(), style))?
            .label(line.label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], style));
        let marker = if variant == Variant::default() { 5 } else { 3 };
        chart.draw_series(points.iter().map(|p| Circle::new(*p, marker, colour.filled())))?;
    }
    Ok(())
}

/// One line of the plot: a mode (its index, for its colour) and variant through its sample
/// counts, at a number of frames averaged and a resolution, in log-log coordinates.
struct Line {
    mode_index: usize,
    /// The knobs the line's rows share: the variant, the frames averaged, the resolution.
    kind: Knobs,
    label: String,
    points: Vec<(f64, f64)>,
}

/// The plot's lines: for each mode, one a variant through its sample counts (a single frame at
/// full resolution, blur on, the first radius), and for the default variant its most
/// accumulated still rows at full and at half resolution.
fn lines(rows: &[Row]) -> Vec<Line> {
    let first_radius = rows.iter().find(|r| r.config.mode != Mode::Off).map_or(0.0, |r| r.radius);
    let most = rows.iter().map(|r| r.config.knobs.accumulate).max().unwrap_or(1);
    // The variant, frames averaged and resolution of each line of a mode.
    let line_kind =
        |variant, accumulate, half_resolution| Knobs { variant, accumulate, half_resolution, ..Knobs::default() };
    let mut kinds: Vec<Knobs> = Variant::ALL.iter().map(|&v| line_kind(v, 1, false)).collect();
    if most > 1 {
        kinds.extend([false, true].map(|half| line_kind(Variant::default(), most, half)));
    }
    let mut out = Vec::new();
    for (mode_index, mode) in Mode::ALL.into_iter().enumerate() {
        for &kind in &kinds {
            // Through the sample counts in order (timings are noisy; samples are not).
            let mut line: Vec<&Row> = rows
                .iter()
                .filter(|r| {
                    let (c, k) = (&r.config, &r.config.knobs);
                    c.mode == mode
                        && line_kind(k.variant, k.accumulate, k.half_resolution) == kind
                        && !c.pyramid()
                        && c.orbit == 0.0
                        && !c.cut
                        && (mode == Mode::Off || (k.blur && r.radius == first_radius))
                })
                .collect();
            if line.is_empty() {
                continue;
            }
            line.sort_by_key(|r| r.config.samples() * 1000 + r.config.steps());
            let mut label = format!("{} {}", mode.title(), kind.variant);
            if kind.accumulate > 1 {
                label = format!(
                    "{label} ×{} frames{}",
                    kind.accumulate,
                    if kind.half_resolution { ", half res" } else { "" }
                );
            }
            let points = line.iter().map(|r| (log_value(r.ms), log_value(r.hdr_rmse))).collect();
            out.push(Line { mode_index, kind, label, points });
        }
    }
    out
}

/// Points of the plot: (log time, log error).
type Points = Vec<(f64, f64)>;

/// The Pareto front's rows in time order, and the staircase through them.
fn pareto_stairs(rows: &[Row]) -> (Points, Points) {
    let front: Vec<(f64, f64)> =
        rows.iter().filter(|r| r.pareto).map(|r| (log_value(r.ms), log_value(r.hdr_rmse))).collect();
    let mut stairs = Vec::new();
    for (k, p) in front.iter().enumerate() {
        if k > 0 {
            stairs.push((p.0, front[k - 1].1));
        }
        stairs.push(*p);
    }
    (front, stairs)
}

/// The plotted position of a positive value on a log axis: log10 of it clamped to [1e-9, 1e30]
/// (a non-finite value sits at the top), so any finite or infinite metric gives a finite point.
fn log_value(v: f64) -> f64 {
    if v.is_nan() {
        return 30.0;
    }
    v.clamp(1e-9, 1e30).log10()
}

/// A log axis spanning `values` with a margin, finite and never empty: the charting library's
/// tick search does not end on an infinite or a zero-width range.
fn log_axis(values: &[f64]) -> std::ops::Range<f64> {
    let (low, high) = values.iter().map(|v| log_value(*v)).fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)));
    if low > high {
        return -1.0..1.0;
    }
    let margin = ((high - low) * 0.05).max(0.1);
    (low - margin)..(high + margin)
}

#[cfg(test)]
mod tests {
    use super::{lines, log_axis, log_value};
    use crate::knobs::Knobs;
    use crate::render::{Mode, Variant};
    use crate::report::row::Row;
    use crate::report::sweep::Config;

    fn row(mode: Mode, knobs: Knobs) -> Row {
        Row {
            config: Config::new(mode, knobs),
            radius: 1.0,
            ms: knobs.samples as f64,
            ao_rmse: None,
            do_rmse: None,
            do_rmse_near: None,
            bounce_ratio: None,
            bounce_seen_ratio: None,
            hdr_rmse: 0.1,
            hdr_rmse_near: 0.1,
            hdr_psnr: 20.0,
            flip: 0.1,
            pareto: false,
            preset: None,
        }
    }

    #[test]
    fn each_line_takes_the_rows_of_its_variant_frames_and_resolution_only() {
        let mut rows = Vec::new();
        for variant in Variant::ALL {
            for (samples, accumulate, half) in [(8, 1, false), (16, 1, false), (16, 1, true), (16, 4, false)] {
                let knobs = Knobs { samples, accumulate, half_resolution: half, ..Knobs::for_variant(variant) };
                rows.push(row(Mode::Ssao, knobs));
            }
        }
        let ssao: Vec<_> = lines(&rows).into_iter().filter(|l| l.mode_index == 1).collect();
        let counts: Vec<(String, usize)> = ssao.iter().map(|l| (l.label.clone(), l.points.len())).collect();
        // A single-frame line at full resolution per variant (two sample counts each), and the
        // default variant's most accumulated rows at full resolution (there are none at half).
        let mut expected: Vec<(String, usize)> =
            Variant::ALL.iter().map(|v| (format!("{} {v}", Mode::Ssao.title()), 2)).collect();
        expected.push((format!("{} {} ×4 frames", Mode::Ssao.title(), Variant::default()), 1));
        assert_eq!(counts, expected);
    }

    #[test]
    fn log_axes_are_finite_and_not_empty_for_any_values() {
        for values in
            [vec![], vec![0.0], vec![3e38, 3e38], vec![f64::INFINITY, 1.0], vec![f64::NAN], vec![1e-300, 1e300]]
        {
            let axis = log_axis(&values);
            assert!(axis.start.is_finite() && axis.end.is_finite() && axis.start < axis.end, "{values:?}: {axis:?}");
            assert!(values.iter().all(|v| log_value(*v).is_finite()));
        }
        let axis = log_axis(&[0.01, 0.1]);
        assert!(axis.start < -2.0 && axis.end > -1.0);
    }
}
