//! The CPU reference against answers known in closed form, and the GPU against the reference.

use crate::common;

use glam::Vec3;
use rand::{rngs::StdRng, SeedableRng};
use ssdo::reference::{Estimate, ReferenceScene, Surface, TraceSettings};
use ssdo::render::{Mode, SenderSky, Variant};
use ssdo::report::{self, RadiusChoice, ReportOptions, TruthScene};
use ssdo::scene::builtin::{self, MeshBuilder};
use ssdo::scene::{LightRig, Material, PointLight, Scene, Skybox};

fn settings(radius: f32, spp: u32) -> TraceSettings {
    TraceSettings { samples_per_pixel: spp, seed: 7, radius, sky_scale: 1.0, ambient: 0.0 }
}

/// The surface the reference sees looking down at `point` from above. The probe is tilted a
/// little: a ray parallel to two axes can slip past a perfectly flat BVH box (obvhs's slab test).
fn floor_point(scene: &ReferenceScene, point: Vec3) -> Surface {
    let dir = Vec3::new(1e-3, -1.0, 1.3e-3).normalize();
    scene.trace(point - dir, dir, 10.0).expect("the floor is there")
}

fn rig() -> LightRig {
    LightRig { strength: 1.0, min_distance: 0.01, cube_half_size: 0.01 }
}

#[test]
fn open_plane_has_no_occlusion_and_passes_the_white_furnace() {
    let model = builtin::plane(100.0, [0.5; 3]).unwrap();
    let scene = ReferenceScene::new(&model);
    let sky = Skybox::constant(Vec3::new(0.3, 0.6, 0.9));
    let surface = floor_point(&scene, Vec3::new(0.3, 0.0, -0.2));
    assert!((surface.normal - Vec3::Y).length() < 1e-6);
    let e = scene.estimate(&surface, &[], &rig(), &sky, &settings(1.0, 512), &mut StdRng::seed_from_u64(1));
    assert_eq!(e.ao, 1.0, "open plane AO");
    assert_eq!(e.ao_error, 0.0);
    assert!((e.sky - Vec3::new(0.3, 0.6, 0.9)).abs().max_element() < 1e-5, "white furnace: {}", e.sky);
    assert!(e.sky_error < 1e-5, "every ray sees the same sky: {}", e.sky_error);
    assert_eq!(e.bounce, Vec3::ZERO);
    assert_eq!(e.open, 1.0, "every ray escapes");
    assert_eq!(e.sky_near, e.sky, "nothing beyond the radius either");
}

#[test]
fn floor_at_the_foot_of_a_large_wall_has_ao_one_half() {
    let v = Vec3::new;
    let mut b = MeshBuilder::default();
    let m = b.material(Material::plain("white", [0.8; 3]));
    b.quad(m, [v(-100.0, 0.0, 100.0), v(100.0, 0.0, 100.0), v(100.0, 0.0, -100.0), v(-100.0, 0.0, -100.0)]);
    b.quad(m, [v(0.0, 0.0, -100.0), v(0.0, 0.0, 100.0), v(0.0, 100.0, 100.0), v(0.0, 100.0, -100.0)]);
    let scene = ReferenceScene::new(&b.build("wall").unwrap());
    let surface = floor_point(&scene, v(1e-4, 0.0, 0.0));
    let e = under_a_white_sky(&scene, &surface, 10.0, 3);
    assert!(e.ao_error > 0.0 && e.ao_error < 0.01, "standard error {}", e.ao_error);
    assert!((e.ao - 0.5).abs() <= 3.0 * e.ao_error, "AO {} vs 0.5 ± 3σ (σ = {})", e.ao, e.ao_error);
    // Half the cosine-weighted hemisphere sees the sky.
    assert!((e.sky.x - 0.5).abs() <= 3.0 * e.sky_error + 1e-3, "sky {} ± {}", e.sky.x, e.sky_error);
    assert!((e.open - 0.5).abs() <= 3.0 * e.ao_error, "openness {}", e.open);

    // A receiver 3 units from the wall, with a radius of 1: the truth still sees the wall (any
    // distance), the within-R diagnostic does not.
    let far = floor_point(&scene, v(3.0, 0.0, 0.0));
    let e = under_a_white_sky(&scene, &far, 1.0, 4);
    // The form factor from a floor point at distance d to an infinitely long wall of height h
    // (Hottel's crossed strings): (1 − d/√(d² + h²))/2; d = 3, h = 100 hides 0.485 of the sky.
    let hidden = 0.5 * (1.0 - 3.0 / (9.0f32 + 100.0 * 100.0).sqrt());
    assert!((e.sky.x - (1.0 - hidden)).abs() < 0.02, "sky beyond R sees the wall: {} vs {}", e.sky.x, 1.0 - hidden);
    assert_eq!(e.sky_near, Vec3::ONE, "within R = 1 nothing is in the way");
    assert_eq!(e.ao, 1.0);
}

#[test]
fn a_lit_wall_sends_its_diffuse_radiance_as_the_bounce() {
    // Floor beside an infinite red wall lit by one light: the bounce is red and finite.
    let v = Vec3::new;
    let mut b = MeshBuilder::default();
    let floor = b.material(Material::plain("floor", [0.8; 3]));
    let wall = b.material(Material::plain("wall", [0.9, 0.05, 0.05]));
    b.floor(floor, 100.0);
    b.quad(wall, [v(0.0, 0.0, -100.0), v(0.0, 0.0, 100.0), v(0.0, 100.0, 100.0), v(0.0, 100.0, -100.0)]);
    let scene = ReferenceScene::new(&b.build("wall").unwrap());
    let lights = [PointLight { position: v(1.0, 1.0, 0.0), color: Vec3::ONE, intensity: 1.0 }];
    let surface = floor_point(&scene, v(0.05, 0.0, 0.0));
    let e = scene.estimate(
        &surface,
        &lights,
        &rig(),
        &Skybox::constant(Vec3::ZERO),
        &settings(1.0, 1024),
        &mut StdRng::seed_from_u64(5),
    );
    assert!(e.bounce.x > 0.01 && e.bounce.x > 10.0 * e.bounce.y, "red bounce {}", e.bounce);
    assert!(e.bounce.is_finite());
}

#[test]
fn gpu_error_falls_from_the_smallest_setting_to_the_largest_for_each_mode_and_variant() {
    let Some((gpu, out)) = common::gpu_and_folder() else { return };
    let options = ReportOptions {
        on: TruthScene { lights: 8, ..TruthScene::named("open", (160, 120)) },
        samples: vec![8, 64],
        march: vec![(1, 4), (4, 16)],
        samples_per_pixel: 64,
        ..tiny_report(out.path(), None, None)
    };
    let result = report::run(gpu, &options, &|_| {}).unwrap();
    assert!(result.reference.mismatched < 300, "silhouette pixels left out: {}", result.reference.mismatched);
    for (mode, variant, small, large) in [Mode::Ssao, Mode::Ssdo, Mode::Both]
        .into_iter()
        .flat_map(|m| [(m, Variant::Points, (8, 0), (64, 0)), (m, Variant::March, (1, 4), (4, 16))])
    {
        let row = |(samples, steps)| {
            result
                .rows
                .iter()
                .find(|r| {
                    let c = &r.config;
                    c.mode == mode
                        && c.knobs.variant == variant
                        && (c.samples(), c.steps()) == (samples, steps)
                        && !c.knobs.blur
                })
                .unwrap()
        };
        let (few, many) = (row(small), row(large));
        let (a, b) = (many.hdr_rmse, few.hdr_rmse);
        assert!(a < b, "{mode} {variant}: HDR RMSE {a} at {} vs {b} at {}", many.label(), few.label());
        if let (Some(a), Some(b)) = (many.ao_rmse, few.ao_rmse) {
            assert!(a < b, "{mode} {variant}: AO RMSE {a} at {} vs {b} at {}", many.label(), few.label());
        }
        if let (Some(a), Some(b)) = (many.do_rmse, few.do_rmse) {
            assert!(a < b, "{mode} {variant}: DO RMSE {a} at {} vs {b} at {}", many.label(), few.label());
        }
    }
    // The march sees beyond the radius: below the points at their most samples, in SSDO.
    let best = |variant| {
        result
            .rows
            .iter()
            .filter(|r| r.config.mode == Mode::Ssdo && r.config.knobs.variant == variant)
            .map(|r| r.hdr_rmse)
            .fold(f64::MAX, f64::min)
    };
    assert!(
        best(Variant::March) < best(Variant::Points),
        "march {} vs points {}",
        best(Variant::March),
        best(Variant::Points)
    );
    // The report files are complete.
    result.write(&options).unwrap();
    let csv = std::fs::read_to_string(out.path().join("report.csv")).unwrap();
    assert!(csv.starts_with(
        "mode,variant,samples,slices,steps,accumulate,blur,half_resolution,radius_scale,thickness_scale,reach_scale,depth_pyramid,sender_sky,far_side,far_sky,indirect_strength,radius,orbit,cut,ms,ao_rmse_within_r,do_rmse,do_rmse_within_r,bounce_ratio,bounce_seen_ratio,hdr_rmse"
    ));
    // Each knob's cell holds its value where it means something for the row, empty elsewhere:
    // the points variant has no steps, SSAO no senders, Off nothing but its variant.
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let cells = |prefix: &str| -> Vec<Vec<String>> {
        csv.lines().filter(|l| l.starts_with(prefix)).map(|l| l.split(',').map(str::to_string).collect()).collect()
    };
    for row in cells("ssao,points,") {
        assert_eq!((row[column("steps")].as_str(), row[column("sender_sky")].as_str()), ("", ""), "{row:?}");
        assert!(!row[column("samples")].is_empty() && !row[column("blur")].is_empty(), "{row:?}");
    }
    for row in cells("both,march,") {
        assert!(["1", "4"].contains(&row[column("slices")].as_str()), "{row:?}");
        assert_eq!(row[column("samples")], "", "{row:?}");
        assert!(!row[column("sender_sky")].is_empty(), "{row:?}");
    }
    for row in cells("off,") {
        assert!(row[column("blur")].is_empty() && !row[column("variant")].is_empty(), "{row:?}");
    }
    assert_eq!(
        csv.lines().count(),
        1 + 2 + 3 * 3 * 2 * 3 + 2 * 2,
        "Off sky-lit and classic, the rest swept (blur on, off, and on at half resolution), the march on the pyramid in SSDO and Both"
    );
    let md = std::fs::read_to_string(out.path().join("report.md")).unwrap();
    assert!(md.contains("| both | points | 64 |") && md.contains("| both | march | 4×16 |"), "{md}");
    assert!(result.rows.iter().any(|r| r.pareto), "a Pareto front is marked");
    // The truth's own noise is measured (not 0) and well below what Off, with no occlusion at
    // all, gets wrong.
    let off =
        result.rows.iter().find(|r| r.config.mode == Mode::Off && r.config.knobs.variant == Variant::March).unwrap();
    assert!(
        result.noise.hdr > 0.0 && result.noise.hdr < 0.5 * off.hdr_rmse,
        "noise {} vs Off {}",
        result.noise.hdr,
        off.hdr_rmse
    );
    assert!(image::open(out.path().join("report.png")).is_ok());
    // Default beats classic on the displayed image at every sample count.
    for mode in [Mode::Ssao, Mode::Ssdo, Mode::Both] {
        for samples in [8, 64] {
            let flip = |variant| {
                result
                    .rows
                    .iter()
                    .find(|r| {
                        let (c, k) = (&r.config, &r.config.knobs);
                        c.mode == mode && k.variant == variant && c.samples() == samples && k.blur && !k.half_resolution
                    })
                    .unwrap()
                    .flip
            };
            assert!(flip(Variant::Points) < flip(Variant::Classic), "{mode} {samples}: FLIP points vs classic");
        }
    }
}

/// The report renders the default single frame under each entry of the sample schedule: entry 0
/// is the single-frame rows' own pattern (the same errors to the last bit as the default row's),
/// and the entries differ, so the spread says how far two single frames differ by luck alone.
#[test]
fn the_report_measures_how_much_a_single_frames_error_owes_to_its_pattern() {
    let Some((gpu, out)) = common::gpu_and_folder() else { return };
    let options = ReportOptions {
        on: TruthScene { lights: 2, ..TruthScene::named("cornell", (48, 36)) },
        march: vec![(2, 16)],
        ..tiny_report(out.path(), None, None)
    };
    let result = report::run(gpu, &options, &|_| {}).unwrap();
    let row = result
        .rows
        .iter()
        .find(|r| {
            let (c, k) = (&r.config, &r.config.knobs);
            (c.mode, k.variant, c.samples(), c.steps(), k.accumulate) == (Mode::Both, Variant::March, 2, 16, 1)
                && k.blur
                && k.half_resolution
                && !c.pyramid()
                && c.bounce() == Some(SenderSky::LastFrame)
                && !c.far_side()
        })
        .expect("the default single-frame row");
    let p = result.pattern;
    assert_eq!(p.entries, 16);
    assert_eq!(
        (p.hdr.first, Some(p.directional.first), Some(p.ao.first)),
        (row.hdr_rmse, row.do_rmse, row.ao_rmse),
        "entry 0 is the single-frame row's pattern"
    );
    for (name, s) in [("HDR", p.hdr), ("DO", p.directional), ("AO", p.ao)] {
        assert!(s.min <= s.first && s.first <= s.max && s.min < s.max, "{name}: {s:?}");
    }
    assert!(result.markdown(&options).contains("a single frame's sample pattern"));
}

#[test]
fn report_scenes_build_and_unknown_names_are_errors() {
    for name in report::scenes::NAMES {
        let (model, _) = report::scenes::by_name(name).unwrap();
        assert!(model.triangle_count() > 10, "{name}");
    }
    let e = report::scenes::by_name("nowhere").unwrap_err();
    assert!(e.to_string().contains("nowhere") && e.exit_code() == 2);
    let _ = Scene::new(report::scenes::crevices().unwrap(), 1, 1);
}

#[test]
fn report_divides_pre_exposure_out_so_brighter_scenes_are_measured_alike() {
    // An open plane under a constant sky: no occlusion and no bounce, so every mode's image is
    // right up to rounding and SSAO's error must not change with the number of lights. The GPU's
    // buffers hold radiance × pre-exposure, which falls below 1 as lights are added; a report that
    // forgot to divide it out would see a growing error.
    let Some((gpu, dir)) = common::gpu_and_folder() else { return };
    let model = builtin::plane(3.0, [0.6; 3]).unwrap();
    builtin::write_obj(&model, &dir.path().join("plane.obj")).unwrap();
    let sky_dir = dir.path().join("sky");
    std::fs::create_dir(&sky_dir).unwrap();
    builtin::write_skybox(&Skybox::constant(Vec3::new(0.4, 0.5, 0.6)), &sky_dir, true).unwrap();
    let error = |lights: usize| {
        let tiny = tiny_report(&dir.path().join("out"), Some(dir.path().join("plane.obj")), Some(sky_dir.clone()));
        let options = ReportOptions {
            on: TruthScene { size: (96, 72), lights, ..tiny.on.clone() },
            samples: vec![16],
            march: vec![(2, 8)],
            samples_per_pixel: 8,
            ..tiny
        };
        let report = report::run(gpu, &options, &|_| {}).unwrap();
        // One row per resolution, named by its settings: the rows come sorted by time, which
        // differs from run to run.
        let hdr_rmse = |half: bool| {
            let mut rows = report.rows.iter().filter(|r| {
                let k = &r.config.knobs;
                r.config.mode == Mode::Ssao && k.variant == Variant::Points && k.blur && k.half_resolution == half
            });
            let row = rows.next().expect("the sweep has this row");
            assert!(rows.next().is_none(), "one row with half = {half}");
            row.hdr_rmse
        };
        [hdr_rmse(false), hdr_rmse(true)]
    };
    // The test means something only if the brighter scenes are pre-exposed.
    let scene = Scene::new(model.clone(), 32, 1);
    let sky = Skybox::constant(Vec3::new(0.4, 0.5, 0.6));
    let r = common::renderer(gpu, &scene, &sky, (96, 72), ssdo::render::Settings::default());
    assert!(r.pre_exposure() < 0.5, "32 lights are pre-exposed: {}", r.pre_exposure());
    let base = error(8);
    for lights in [16, 32] {
        for (e, base, resolution) in
            error(lights).into_iter().zip(base).zip(["full", "half"]).map(|((e, b), r)| (e, b, r))
        {
            eprintln!("SSAO {resolution} res HDR RMSE: {base:.5} with 8 lights, {e:.5} with {lights}");
            assert!(
                (e - base).abs() <= 0.1 * base,
                "{lights} lights, {resolution} res: SSAO HDR RMSE {e} vs {base} with 8"
            );
        }
    }
}

/// The truth at `surface` under a white sky, no lights, within `radius`, from 4096 rays.
fn under_a_white_sky(scene: &ReferenceScene, surface: &Surface, radius: f32, seed: u64) -> Estimate {
    scene.estimate(
        surface,
        &[],
        &rig(),
        &Skybox::constant(Vec3::ONE),
        &settings(radius, 4096),
        &mut StdRng::seed_from_u64(seed),
    )
}

fn tiny_report(
    out: &std::path::Path,
    model: Option<std::path::PathBuf>,
    skybox: Option<std::path::PathBuf>,
) -> ReportOptions {
    ReportOptions {
        on: TruthScene { model, skybox, lights: 2, ..TruthScene::named("cornell", (16, 12)) },
        samples: vec![4],
        march: vec![(1, 4)],
        radii: vec![RadiusChoice::Times(1.0)],
        samples_per_pixel: 4,
        frames: 1,
        accumulate: vec![1],
        orbit: 0.0,
        out: out.to_path_buf(),
        preset: None,
    }
}

/// A sky folder of six `size`² EXR faces of constant radiance `value`.
fn constant_exr_sky(dir: &std::path::Path, value: f32) {
    for face in ["right", "left", "top", "bottom", "front", "back"] {
        let image = image::Rgb32FImage::from_pixel(8, 8, image::Rgb([value; 3]));
        image::DynamicImage::ImageRgb32F(image).save(dir.join(format!("{face}.exr"))).unwrap();
    }
}

#[test]
fn the_report_copes_with_any_finite_sky_and_refuses_what_it_cannot_measure() {
    let Some((gpu, out)) = common::gpu_and_folder() else { return };
    // A sky of 1e19: every figure is huge but finite; the plot's axes are clamped and finish.
    let bright = tempfile::tempdir().unwrap();
    constant_exr_sky(bright.path(), 1e19);
    let options = tiny_report(out.path(), None, Some(bright.path().to_path_buf()));
    let result = report::run(gpu, &options, &|_| {}).unwrap();
    assert!(result.rows.iter().all(|r| r.hdr_rmse.is_finite()), "finite errors under a 1e19 sky");
    result.write(&options).unwrap();
    assert!(image::open(out.path().join("report.png")).is_ok());
    // A sky of 3e38 (finite, from EXR faces) would overflow the truth's 32-bit sums: it is
    // clamped as it loads, with a warning, as in every command, and measured like the others.
    let blinding = tempfile::tempdir().unwrap();
    constant_exr_sky(blinding.path(), 3e38);
    let sky = ssdo::scene::Skybox::load(blinding.path()).unwrap();
    assert_eq!(sky.max_value(), ssdo::scene::skybox::MAX_SKY_RADIANCE);
    assert!(sky.warnings.iter().any(|w| w.contains("clamped")), "{:?}", sky.warnings);
    let options = tiny_report(out.path(), None, Some(blinding.path().to_path_buf()));
    let result = report::run(gpu, &options, &|_| {}).unwrap();
    assert!(result.rows.iter().all(|r| r.hdr_rmse.is_finite()), "finite errors under a clamped 3e38 sky");
    // A model 1e-20 across (fitted to a radius of 1 as it loads) is measured like any other.
    let model = out.path().join("tiny.obj");
    std::fs::write(&model, "v 0 0 0\nv 1e-20 0 0\nv 0 1e-20 0\nf 1 2 3\n").unwrap();
    let result = report::run(gpu, &tiny_report(out.path(), Some(model), None), &|_| {}).unwrap();
    assert!(result.rows.iter().all(|r| r.hdr_rmse.is_finite() && r.hdr_psnr.is_finite()));
    // A sliver far thinner than a pixel covers no pixel centre: nothing to measure is an error,
    // not a table of zeros and PSNR inf.
    let sliver = out.path().join("sliver.obj");
    std::fs::write(&sliver, "v 0 0 0\nv 1 0 0\nv 0.5 1e-7 0\nf 1 2 3\n").unwrap();
    match report::run(gpu, &tiny_report(out.path(), Some(sliver), None), &|_| {}) {
        Err(e) => assert!(e.to_string().contains("no surface pixel") && e.exit_code() == 2, "{e}"),
        Ok(r) => panic!("a report of nothing: {} rows", r.rows.len()),
    }
}
