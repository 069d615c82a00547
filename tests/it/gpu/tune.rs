//! `ssdo tune` on a small scene: the pick is on the measured front and nothing measured within the
//! budget is both cheaper and closer to the truth; its files round-trip; the quality levels are
//! ordered in error on the scene they were made on.

use crate::common;

use ssdo::preset::{Preset, Quality};
use ssdo::render::Mode;
use ssdo::report::TruthScene;
use ssdo::tune::{self, Budget, TuneOptions, Verdict};

fn options(out: &std::path::Path) -> TuneOptions {
    TuneOptions {
        on: TruthScene { lights: 2, ..TruthScene::named("cornell", (64, 48)) },
        mode: Mode::Ssdo,
        budget: Some(Budget::OffTimes(6.0)),
        target_error: None,
        views: 2,
        spread: 20.0,
        frames: 2,
        samples_per_pixel: 8,
        max_settings: 12,
        also: Vec::new(),
        out: out.to_path_buf(),
    }
}

#[test]
fn the_pick_is_on_the_front_and_no_setting_within_the_budget_is_cheaper_and_closer() {
    let Some((gpu, out)) = common::gpu_and_folder() else { return };
    let options = options(out.path());
    let result = tune::run(gpu, &options, &|_| {}).unwrap();
    let budget = result.budget_ms.unwrap();
    assert!(result.points.len() <= options.max_settings && result.points.len() >= 5);
    // Timed on the first view; a front setting whose time lies near the budget, once more.
    assert!(
        result.points.iter().all(|p| p.hdr_per_view.len() == 2 && [2, 4].contains(&p.frames_timed)),
        "timed once on the first view (twice near the budget)"
    );
    let Some(pick) = result.picked() else {
        assert_eq!(result.verdict, Verdict::BelowCheapest);
        assert!(result.cheapest().ms > budget);
        return;
    };
    assert!(pick.front && pick.ms <= budget, "pick {} at {} ms, budget {budget}", pick.label(), pick.ms);
    for p in result.points.iter().filter(|p| p.ms <= budget) {
        assert!(
            !(p.ms < pick.ms && p.hdr_rmse < pick.hdr_rmse),
            "{} ({} ms, {}) beats the pick {} ({} ms, {})",
            p.label(),
            p.ms,
            p.hdr_rmse,
            pick.label(),
            pick.ms,
            pick.hdr_rmse
        );
    }
    // The files: the preset holds the pick and its figures, and reads back to the same.
    let written = result.write(&options).unwrap();
    assert_eq!(written.len(), 3);
    let preset = Preset::load(&out.path().join("preset.json")).unwrap();
    assert_eq!(Some(&preset), result.preset(&options).as_ref());
    let measured = preset.measured.unwrap();
    assert_eq!((measured.ms, measured.hdr_rmse, measured.views), (pick.ms, pick.hdr_rmse, 2));
    let csv = std::fs::read_to_string(out.path().join("front.csv")).unwrap();
    assert_eq!(csv.lines().count(), result.points.len() + 1);
    assert_eq!(csv.lines().filter(|l| l.starts_with("true,true,")).count(), 1, "one pick, on the front");
    let command = result.capture_command(&options).unwrap();
    assert!(command.starts_with("ssdo capture --mode ssdo --size 64x48 --lights 2"), "{command}");
    let table = result.markdown(&options);
    assert!(table.contains("median of 2 frames") && table.contains("▶"), "{table}");
}

#[test]
fn quality_levels_are_ordered_in_error_on_the_scene_they_were_made_on() {
    let Some((gpu, out)) = common::gpu_and_folder() else { return };
    let options = TuneOptions {
        on: TruthScene { lights: 8, ..TruthScene::named("cornell", (160, 120)) },
        views: 1,
        samples_per_pixel: 64,
        max_settings: 0,
        budget: None,
        also: Quality::ALL.map(Quality::preset).to_vec(),
        ..options(out.path())
    };
    let result = tune::run(gpu, &options, &|_| {}).unwrap();
    let errors: Vec<f64> = result.points.iter().map(|p| p.hdr_rmse).collect();
    assert_eq!(errors.len(), 4);
    assert!(errors.windows(2).all(|w| w[0] > w[1]), "low, medium, high, ultra: HDR RMSE {errors:?}");
}
