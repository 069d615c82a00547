//! The far side layer (`--far-side`): the surfaces turned from the eye send their point lights'
//! light in SSDO's bounce, measured against the CPU truth where only such a surface can send it;
//! the pass runs only where it is asked for, the mode bounces and there are lights.

use crate::common;

use common::{gpu, looking, renderer, shoot, H, W};
use glam::Vec3;
use rand::{rngs::StdRng, SeedableRng};
use ssdo::headless::readback::read_rgba16f;
use ssdo::knobs::Knobs;
use ssdo::reference::{ReferenceScene, TraceSettings};
use ssdo::render::{Mode, Settings, Step, Variant, View};
use ssdo::scene::{OrbitCamera, PointLight, Scene, Skybox};

/// A red block (1.2 wide, 0.25 tall, 0.4 deep: thicker than the march's slab) on a white floor,
/// and one light behind it, low: it lights the block's far face, which faces the floor behind
/// the block and is turned from a camera in front.
fn block_lit_from_behind() -> Scene {
    let v = Vec3::new;
    let (mut b, block) = common::on_floor([0.8; 3], 2.0, "block", [0.8, 0.1, 0.1]);
    b.cuboid(block, v(-0.6, 0.0, -0.2), v(0.6, 0.25, 0.2), false);
    let mut scene = Scene::new(b.build("block").unwrap(), 0, 1);
    scene.lights = vec![PointLight { position: v(0.0, 0.12, -0.8), color: Vec3::ONE, intensity: 0.5 }];
    scene
}

/// SSDO under a black sky with no ambient, from the default march with more slices: its DO is
/// the bounce alone.
fn bounce_only(far_side: bool, indirect_strength: f32) -> Settings {
    Settings {
        mode: Mode::Ssdo,
        knobs: Knobs { variant: Variant::March, slices: 8, steps: 16, indirect_strength, far_side, ..Knobs::default() },
        ambient: 0.0,
        view: View::Final,
        ..Settings::default()
    }
}

/// The march's mean bounce over `at` (its DO less the same frame's with the bounce off).
fn march_bounce(
    gpu: &ssdo::gpu::Gpu,
    scene: &Scene,
    camera: &OrbitCamera,
    far_side: bool,
    at: &[(usize, usize)],
) -> Vec3 {
    let directional = |indirect_strength: f32| {
        let settings = bounce_only(far_side, indirect_strength);
        let mut r = renderer(gpu, scene, &Skybox::constant(Vec3::ZERO), (W, H), settings);
        assert_eq!(r.plan().far_side, far_side && indirect_strength > 0.0, "the far side pass runs where asked");
        shoot(gpu, &mut r, camera);
        read_rgba16f(gpu, &r.targets().occlusion().directional.unwrap().texture).unwrap()
    };
    let (with, without) = (directional(1.0), directional(0.0));
    let texel = |d: &[[f32; 4]], (x, y): (usize, usize)| Vec3::from_slice(&d[y * W as usize + x][..3]);
    at.iter().map(|&pixel| texel(&with, pixel) - texel(&without, pixel)).sum::<Vec3>() / at.len() as f32
}

/// The floor behind the block that `camera` sees over it, the width of its middle (the block's
/// face that faces it is one the camera cannot see), and the truth's mean bounce there under `sky`.
fn floor_behind_block(scene: &Scene, camera: &OrbitCamera, sky: Vec3) -> (Vec<(usize, usize)>, Vec3) {
    let truth = ReferenceScene::new(&scene.model);
    let mut at = Vec::new();
    for y in 0..H as usize {
        for x in 0..W as usize {
            let (eye, dir) = common::eye_ray_in(camera, (W, H), (x, y));
            let Some(s) = truth.trace(eye, dir, 1e4) else { continue };
            let p = s.position;
            if s.normal.y > 0.99 && p.y.abs() < 1e-3 && (-0.7..-0.45).contains(&p.z) && p.x.abs() < 0.4 {
                at.push(((x, y), s));
            }
        }
    }
    assert!(at.len() >= 20, "only {} floor pixels behind the block", at.len());
    let settings = TraceSettings { samples_per_pixel: 256, seed: 3, radius: 1.0, sky_scale: 1.0, ambient: 0.0 };
    let mut rng = StdRng::seed_from_u64(5);
    let sky = Skybox::constant(sky);
    let bounce = at
        .iter()
        .map(|(_, s)| truth.estimate(s, &scene.lights, &scene.rig, &sky, &settings, &mut rng).bounce)
        .sum::<Vec3>()
        / at.len() as f32;
    (at.into_iter().map(|(pixel, _)| pixel).collect(), bounce)
}

#[test]
fn the_floor_behind_a_block_gets_the_bounce_of_its_far_face() {
    let Some(gpu) = gpu() else { return };
    let scene = block_lit_from_behind();
    let camera = looking(Vec3::new(0.0, 0.0, -0.45), 0.0, 50.0, 3.0);
    let (pixels, truth_bounce) = floor_behind_block(&scene, &camera, Vec3::ZERO);
    let near_only = march_bounce(gpu, &scene, &camera, false, &pixels);
    let far_side = march_bounce(gpu, &scene, &camera, true, &pixels);
    eprintln!(
        "bounce on the floor behind the block ({} pixels): truth {truth_bounce}, near side only {near_only}, far side {far_side}",
        pixels.len()
    );
    // The red comes from the block's far face, lit from behind.
    assert!(truth_bounce.x > 3.0 * truth_bounce.z, "the truth's bounce is the block's: {truth_bounce}");
    let (before, after) = (near_only.x / truth_bounce.x, far_side.x / truth_bounce.x);
    assert!(before < 0.3, "the near side, facing away, sends little: {before:.2} of the truth's red");
    assert!((0.5..=1.5).contains(&after), "the far side sends the truth's red: {after:.2} of it");
}

/// A deep block (0.5 wide, 0.8 tall, 2.4 long, closed) on a white floor, and one light (the far
/// side is drawn where there are point lights).
fn deep_block() -> Scene {
    let v = Vec3::new;
    let (mut b, block) = common::on_floor([0.8; 3], 3.0, "block", [0.8; 3]);
    b.cuboid(block, v(-0.25, 0.0, -1.2), v(0.25, 0.8, 1.2), true);
    let mut scene = Scene::new(b.build("deep block").unwrap(), 0, 1);
    scene.lights = vec![PointLight { position: v(-1.5, 1.5, 1.5), color: Vec3::ONE, intensity: 0.2 }];
    scene
}

/// The march's mean sky light (white sky) over `at`, one frame of 8 slices.
fn march_sky(gpu: &ssdo::gpu::Gpu, scene: &Scene, camera: &OrbitCamera, far_side: bool, at: &[(usize, usize)]) -> f32 {
    let settings = Settings { view: View::DoDirect, ..bounce_only(far_side, 1.0) };
    let mut r = renderer(gpu, scene, &Skybox::constant(Vec3::ONE), (W, H), settings);
    assert_eq!(r.plan().far_side, far_side);
    shoot(gpu, &mut r, camera);
    let d = read_rgba16f(gpu, &r.targets().occlusion().directional.unwrap().texture).unwrap();
    at.iter().map(|&(x, y)| d[y * W as usize + x][0]).sum::<f32>() / at.len() as f32
}

#[test]
fn the_floor_beside_a_deep_block_is_shaded_by_its_depth_not_a_slab() {
    let Some(gpu) = gpu() else { return };
    let scene = deep_block();
    let truth = ReferenceScene::new(&scene.model);
    // From in front and above: the block's top and front show, its sides are turned away (the far
    // side layer holds them); the floor beside it, within a radius, sees the sky past the block.
    let camera = looking(Vec3::new(0.0, 0.3, 0.2), 0.0, 45.0, 3.0);
    let mut at = Vec::new();
    for y in 0..H as usize {
        for x in 0..W as usize {
            let (eye, dir) = common::eye_ray_in(&camera, (W, H), (x, y));
            let Some(s) = truth.trace(eye, dir, 1e4) else { continue };
            let p = s.position;
            if s.normal.y > 0.99 && p.y.abs() < 1e-3 && (0.3..0.55).contains(&p.x.abs()) && (-0.9..0.6).contains(&p.z) {
                at.push(((x, y), s));
            }
        }
    }
    assert!(at.len() >= 40, "only {} floor pixels beside the block", at.len());
    let settings = TraceSettings { samples_per_pixel: 256, seed: 3, radius: 1.0, sky_scale: 1.0, ambient: 0.0 };
    let mut rng = StdRng::seed_from_u64(5);
    let sky = Skybox::constant(Vec3::ONE);
    let truth_sky =
        at.iter().map(|(_, s)| truth.estimate(s, &[], &scene.rig, &sky, &settings, &mut rng).sky.x).sum::<f32>()
            / at.len() as f32;
    let pixels: Vec<_> = at.iter().map(|&(pixel, _)| pixel).collect();
    let slab = march_sky(gpu, &scene, &camera, false, &pixels);
    let extent = march_sky(gpu, &scene, &camera, true, &pixels);
    eprintln!(
        "sky on the floor beside a deep block ({} pixels): truth {truth_sky:.4}, slab {slab:.4}, far side {extent:.4}",
        at.len()
    );
    let error = |x: f32| (x - truth_sky).abs() / truth_sky;
    assert!(error(slab) > 0.05, "a slab lets the sky through the block: {:.3}", error(slab));
    assert!(
        error(extent) <= 0.5 * error(slab),
        "the far side's depth closes it: {:.3} against {:.3}",
        error(extent),
        error(slab)
    );
}

/// The march's mean bounce over `at` under a white sky and no point lights (the DO-indirect view:
/// the bounce alone), with the far side and its sky or without.
fn sky_bounce(gpu: &ssdo::gpu::Gpu, scene: &Scene, camera: &OrbitCamera, far: bool, at: &[(usize, usize)]) -> Vec3 {
    let mut settings = Settings { view: View::DoIndirect, ..bounce_only(far, 1.0) };
    settings.knobs.far_sky = far;
    let mut r = renderer(gpu, scene, &Skybox::constant(Vec3::ONE), (W, H), settings);
    assert_eq!(r.plan().has(Step::FAR_SKY), far, "the far sky runs where asked");
    shoot(gpu, &mut r, camera);
    let d = read_rgba16f(gpu, &r.targets().occlusion().directional.unwrap().texture).unwrap();
    at.iter().map(|&(x, y)| Vec3::from_slice(&d[y * W as usize + x][..3])).sum::<Vec3>() / at.len() as f32
}

#[test]
fn under_a_sky_alone_the_floor_behind_a_block_gets_the_bounce_of_its_far_faces_sky() {
    let Some(gpu) = gpu() else { return };
    let mut scene = block_lit_from_behind();
    scene.lights.clear();
    let camera = looking(Vec3::new(0.0, 0.0, -0.45), 0.0, 50.0, 3.0);
    let (pixels, truth_bounce) = floor_behind_block(&scene, &camera, Vec3::ONE);
    let near_only = sky_bounce(gpu, &scene, &camera, false, &pixels);
    let far_sky = sky_bounce(gpu, &scene, &camera, true, &pixels);
    eprintln!("sky-lit bounce behind the block ({} pixels): truth {truth_bounce}, near side only {near_only}, far side's sky {far_sky}", pixels.len());
    // The red is the block's far face's, lit by the sky it sees.
    let red = |b: Vec3| b.x - b.z;
    assert!(red(truth_bounce) > 0.02, "the truth's bounce is the block's: {truth_bounce}");
    let (before, after) = (red(near_only) / red(truth_bounce), red(far_sky) / red(truth_bounce));
    assert!(before < 0.3, "the near side, facing away, sends little: {before:.2} of the truth's red");
    assert!((0.5..=1.5).contains(&after), "the far side's sky sends the truth's red: {after:.2} of it");
}
