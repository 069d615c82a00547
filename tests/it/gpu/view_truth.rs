//! The truth of a captured view (`ssdo capture --truth`): the same truth and the same errors as
//! the report's for the same view and settings, and the files the command writes.

use ssdo::headless::capture::capture_converged;
use ssdo::headless::truth::ViewTruth;
use ssdo::render::{Mode, Settings, Variant};
use ssdo::report::{self, RadiusChoice, ReportOptions, TruthScene};
use ssdo::scene::{OrbitCamera, Scene, Skybox};

use crate::common;

#[test]
fn a_captures_errors_against_the_truth_are_the_reports_for_its_view() {
    let Some((gpu, out)) = common::gpu_and_folder() else { return };
    let base = Settings::default();
    let options = ReportOptions {
        on: TruthScene {
            skybox: Some("skyboxes/day".into()),
            lights: 3,
            seed: 7,
            ..TruthScene::named("cornell", (48, 36))
        },
        samples: vec![4],
        march: vec![(base.knobs.slices, base.knobs.steps)],
        radii: vec![RadiusChoice::Times(1.0)],
        samples_per_pixel: 8,
        frames: 1,
        accumulate: vec![base.knobs.accumulate],
        orbit: 0.0,
        out: out.path().to_path_buf(),
        preset: None,
    };
    let report = report::run(gpu, &options, &|_| {}).unwrap();

    // The same view captured: the report's scene, sky, lights and camera, the default settings.
    let (model, _) = report::scenes::by_name("cornell").unwrap();
    let scene = Scene::new(model, options.on.lights, options.on.seed);
    let sky = Skybox::load(std::path::Path::new("skyboxes/day")).unwrap();
    let camera = OrbitCamera::framing(&scene.model.bounds);
    for mode in [Mode::Ssao, Mode::Both] {
        let settings = Settings { mode, ..base };
        let mut renderer = common::renderer(gpu, &scene, &sky, options.on.size, settings);
        renderer.keep_hdr(gpu, true);
        let rays = (options.samples_per_pixel, options.on.seed);
        let truth = ViewTruth::trace(gpu, &mut renderer, (&scene, &sky), &camera, rays, &|| {}).unwrap();
        let image = capture_converged(gpu, &mut renderer, &camera).unwrap();
        let measured = truth.measure(gpu, &renderer, mode, &image).unwrap();
        let row = report
            .rows
            .iter()
            .find(|r| {
                let (c, k) = (&r.config, &r.config.knobs);
                c.mode == mode
                    && k.variant == Variant::default()
                    && k.blur
                    && !c.pyramid()
                    && !c.far_side()
                    && k.half_resolution == base.knobs.half_resolution
                    && k.accumulate == base.knobs.accumulate
                    && (mode == Mode::Ssao || c.bounce() == Some(base.knobs.sender_sky))
            })
            .expect("the report has the default row");
        assert!(measured.hdr_rmse > 1e-3 && measured.flip > 1e-3, "{mode}: an error to compare");
        let close = |a: f64, b: f64| (a - b).abs() <= 5e-5;
        assert!(
            close(measured.hdr_rmse, row.hdr_rmse),
            "{mode}: HDR {} vs the report's {}",
            measured.hdr_rmse,
            row.hdr_rmse
        );
        assert!(close(measured.flip, row.flip), "{mode}: FLIP {} vs the report's {}", measured.flip, row.flip);
        match (measured.do_rmse, row.do_rmse) {
            (Some(a), Some(b)) => assert!(close(a, b), "{mode}: DO {a} vs the report's {b}"),
            (a, b) => assert_eq!(a.is_some(), b.is_some(), "{mode}: DO measured by one side only"),
        }
        assert!((truth.noise_hdr() - report.noise.hdr).abs() <= 5e-5, "the same truth's noise");
        assert!(measured.per_pixel.iter().flatten().all(|e| e.is_finite() && *e >= 0.0));
    }
}

#[test]
fn capture_truth_writes_the_truth_the_maps_and_the_numbers() {
    if !common::has_adapter() {
        return;
    }
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().to_str().unwrap();
    let args =
        ["capture", "--truth", "--spp", "4", "--size", "40x30", "--lights", "2", "--out", dir, "--stats", "--json"];
    let result = common::run_ssdo(&args);
    assert_eq!(result.status.code(), Some(0), "{}", common::stderr(&result));
    let json: serde_json::Value = serde_json::from_slice(&result.stdout).expect("standard output is JSON");
    let truth = &json["truth"];
    assert_eq!(truth["rays_per_pixel"], 4);
    for mode in Mode::ALL {
        let errors = &truth["modes"][mode.name()];
        assert!(errors["hdr_rmse"].as_f64().is_some_and(|e| e.is_finite() && e > 0.0), "{mode}: {errors}");
        assert_eq!(errors["do_rmse"].is_null(), !mode.declaration().directional_occlusion, "{mode}: {errors}");
        let map = image::open(out.path().join(format!("error_{}.png", mode.name()))).unwrap();
        assert_eq!(map.width(), 40);
        assert!(map.height() > 30, "the colour bar under the map");
    }
    let truth_png = image::open(out.path().join("truth.png")).unwrap().to_rgba8();
    assert_eq!(truth_png.dimensions(), (40, 30));
    assert!(truth_png.pixels().any(|p| p[0] > 20), "the truth is not black");
    // compare.png: the four modes and the truth, two a row.
    let compare = image::open(out.path().join("compare.png")).unwrap();
    let four = common::run_ssdo(&["capture", "--size", "40x30", "--lights", "2", "--out", &format!("{dir}/plain")]);
    assert_eq!(four.status.code(), Some(0));
    let plain = image::open(out.path().join("plain/compare.png")).unwrap();
    assert!(compare.height() > plain.height(), "a third row for the truth");
    // --spp asks for --truth.
    common::refused(&["capture", "--spp", "8"], 2, "--truth");
}

#[test]
fn the_viewers_truth_in_rounds_is_the_reports_truth_within_its_noise() {
    let Some(gpu) = common::gpu() else { return };
    let (model, _) = report::scenes::by_name("cornell").unwrap();
    let scene = Scene::new(model, 3, 7);
    let sky = Skybox::load(std::path::Path::new("skyboxes/day")).unwrap();
    let camera = OrbitCamera::framing(&scene.model.bounds);
    let size = (40, 30);
    let settings = Settings::default();
    let mut renderer = common::renderer(gpu, &scene, &sky, size, settings);
    renderer.keep_hdr(gpu, true);
    // The report's truth: two traces of 16 rays.
    let report_truth = ViewTruth::trace(gpu, &mut renderer, (&scene, &sky), &camera, (16, 7), &|| {}).unwrap();
    // The viewer's: rounds of 1, 1, 2, 4, 8 rays added up to 16 in each of its two traces.
    let depth = ssdo::headless::readback::read_depth(gpu, &renderer.targets().depth().texture).unwrap();
    let key = ssdo::app::truth::ViewKey {
        camera,
        scene: 0,
        size,
        sky_scale: settings.sky_scale,
        ambient: settings.ambient,
        radius: renderer.radius(),
    };
    let job = ssdo::app::truth::Job {
        key,
        model: std::sync::Arc::new(scene.model.clone()),
        sky: std::sync::Arc::new(sky.clone()),
        lights: scene.lights.clone(),
        rig: scene.rig,
        depth,
        seed: 7,
    };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let rounds = ssdo::app::truth::trace_to(&pool, &job, 16).expect("the rounds end");
    assert_eq!(rounds.rays(), 32);
    let viewer_truth =
        ViewTruth::from_traces((&rounds.a, &rounds.b), settings.ambient, &sky, rounds.rays_per_trace, 0.0).unwrap();
    // Two independent estimates of one image: they differ by about √2 of either's noise.
    let (a, b) = (report_truth.overlay(1.0), viewer_truth.overlay(1.0));
    assert_eq!(report_truth.pixels(), viewer_truth.pixels(), "the same pixels measured");
    let noise = (report_truth.noise_hdr().powi(2) + viewer_truth.noise_hdr().powi(2)).sqrt();
    let difference = report_truth.rmse_against(&viewer_truth);
    assert!(difference > 0.0, "independent rays");
    assert!(difference < 2.0 * noise, "the truths differ by {difference:.4}, their noise {noise:.4}");
    assert_ne!(a, b);
}
