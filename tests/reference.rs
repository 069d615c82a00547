//! The CPU reference against answers known in closed form, and the GPU against the reference.

mod common;

use glam::Vec3;
use rand::{rngs::StdRng, SeedableRng};
use ssdo::reference::{ReferenceScene, TraceSettings};
use ssdo::render::{Mode, Variant};
use ssdo::report::{self, ReportOptions};
use ssdo::scene::builtin::{self, MeshBuilder};
use ssdo::scene::{LightRig, Material, PointLight, Scene, Skybox};

fn settings(radius: f32, spp: u32) -> TraceSettings {
    TraceSettings { samples_per_pixel: spp, seed: 7, radius, sky_scale: 1.0 }
}

/// The surface the reference sees looking down at `point` from above. The probe is tilted a
/// little: a ray parallel to two axes can slip past a perfectly flat BVH box (obvhs's slab test).
fn floor_point(scene: &ReferenceScene, point: Vec3) -> ssdo::reference::Surface {
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
    let e = scene.estimate(
        &surface,
        &[],
        &rig(),
        &Skybox::constant(Vec3::ONE),
        &settings(10.0, 4096),
        &mut StdRng::seed_from_u64(3),
    );
    assert!(e.ao_error > 0.0 && e.ao_error < 0.01, "standard error {}", e.ao_error);
    assert!((e.ao - 0.5).abs() <= 3.0 * e.ao_error, "AO {} vs 0.5 ± 3σ (σ = {})", e.ao, e.ao_error);
    // Half the cosine-weighted hemisphere sees the sky.
    assert!((e.sky.x - 0.5).abs() <= 3.0 * e.sky_error + 1e-3, "sky {} ± {}", e.sky.x, e.sky_error);
}

#[test]
fn a_lit_wall_sends_its_diffuse_radiance_as_the_bounce() {
    // Floor beside an infinite red wall lit by one light: the bounce is red and finite.
    let v = Vec3::new;
    let mut b = MeshBuilder::default();
    let floor = b.material(Material::plain("floor", [0.8; 3]));
    let wall = b.material(Material::plain("wall", [0.9, 0.05, 0.05]));
    b.quad(floor, [v(-100.0, 0.0, 100.0), v(100.0, 0.0, 100.0), v(100.0, 0.0, -100.0), v(-100.0, 0.0, -100.0)]);
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
fn gpu_error_at_64_samples_is_below_its_error_at_8_for_each_mode() {
    let Some(gpu) = common::gpu() else { return };
    let out = tempfile::tempdir().unwrap();
    let options = ReportOptions {
        scene: "open".into(),
        model: None,
        skybox: None,
        size: (160, 120),
        samples: vec![8, 64],
        samples_per_pixel: 64,
        frames: 1,
        lights: 8,
        seed: 1,
        out: out.path().to_path_buf(),
    };
    let result = report::run(&gpu, &options, &|_| {}).unwrap();
    assert!(result.reference.mismatched < 300, "silhouette pixels left out: {}", result.reference.mismatched);
    for mode in [Mode::Ssao, Mode::Ssdo, Mode::Both] {
        let row = |samples| {
            result
                .rows
                .iter()
                .find(|r| r.mode == mode && r.variant == Variant::Default && r.samples == samples && !r.blur)
                .unwrap()
        };
        let (few, many) = (row(8), row(64));
        assert!(many.hdr_rmse < few.hdr_rmse, "{mode}: HDR RMSE {} at 64 vs {} at 8", many.hdr_rmse, few.hdr_rmse);
        if let (Some(a), Some(b)) = (many.ao_rmse, few.ao_rmse) {
            assert!(a < b, "{mode}: AO RMSE {a} at 64 vs {b} at 8");
        }
        if let (Some(a), Some(b)) = (many.do_rmse, few.do_rmse) {
            assert!(a < b, "{mode}: DO RMSE {a} at 64 vs {b} at 8");
        }
    }
    // The report files are complete.
    result.write(&options).unwrap();
    let csv = std::fs::read_to_string(out.path().join("report.csv")).unwrap();
    assert!(csv.starts_with("mode,variant,samples,blur,ms,ao_rmse,ao_psnr,do_rmse,do_psnr,hdr_rmse,hdr_psnr,flip"));
    assert_eq!(csv.lines().count(), 1 + 2 * 3 * 2 * 2);
    assert!(std::fs::read_to_string(out.path().join("report.md")).unwrap().contains("| both | default | 64 |"));
    assert!(image::open(out.path().join("report.png")).is_ok());
    // Default beats classic on the displayed image at every sample count.
    for mode in [Mode::Ssao, Mode::Ssdo, Mode::Both] {
        for samples in [8, 64] {
            let flip = |variant| {
                result
                    .rows
                    .iter()
                    .find(|r| r.mode == mode && r.variant == variant && r.samples == samples && r.blur)
                    .unwrap()
                    .flip
            };
            assert!(flip(Variant::Default) < flip(Variant::Classic), "{mode} {samples}: FLIP default vs classic");
        }
    }
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
