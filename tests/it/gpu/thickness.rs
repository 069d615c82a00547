//! The march's thickness from the scene: a cut-out is a sheet and a thin solid its own thickness,
//! measured against the CPU truth on the pixels it changes; a scene with no thin material and a
//! given `--thickness` draw no thickness layer.

use crate::common;

use common::{gpu, looking, renderer, shoot, H, W};
use glam::Vec3;
use rand::{rngs::StdRng, SeedableRng};
use ssdo::headless::readback::read_rgba16f;
use ssdo::knobs::Knobs;
use ssdo::reference::{ReferenceScene, Surface, TraceSettings};
use ssdo::render::{GivenLengths, Mode, Settings, Variant, View};
use ssdo::scene::builtin::MeshBuilder;
use ssdo::scene::{LightRig, Material, Model, OrbitCamera, Scene, Skybox};

/// The SSDO mode's sky light alone under a white sky, from the default march with more slices
/// (so one frame is near its converged value), at the scene's default lengths.
fn sky_light(thickness: Option<f32>) -> Settings {
    Settings {
        mode: Mode::Ssdo,
        knobs: Knobs { variant: Variant::March, slices: 8, steps: 16, ..Knobs::default() },
        given: GivenLengths { thickness, ..GivenLengths::default() },
        ambient: 0.0,
        view: View::DoDirect,
        ..Settings::default()
    }
}

/// The eye ray through the centre of pixel `(x, y)` of a test-sized image.
fn eye_ray(camera: &OrbitCamera, pixel: (usize, usize)) -> (Vec3, Vec3) {
    common::eye_ray_in(camera, (W, H), pixel)
}

/// The pixels whose surface, and every neighbour's, `keep` accepts (so no pixel measured lies on
/// an edge the half-resolution march blurs across), every `stride`-th of them, with the
/// surface the truth sees there.
fn pixels(
    truth: &ReferenceScene,
    camera: &OrbitCamera,
    stride: usize,
    keep: impl Fn(&Surface) -> bool,
) -> Vec<((usize, usize), Surface)> {
    let hits: Vec<Option<Surface>> = (0..(W * H) as usize)
        .map(|i| {
            let (eye, dir) = eye_ray(camera, (i % W as usize, i / W as usize));
            truth.trace(eye, dir, 1e4).filter(|s| keep(s))
        })
        .collect();
    let inner = |x: usize, y: usize| {
        (x > 0 && y > 0 && x + 1 < W as usize && y + 1 < H as usize)
            && (y - 1..=y + 1).all(|yy| (x - 1..=x + 1).all(|xx| hits[yy * W as usize + xx].is_some()))
    };
    (0..(W * H) as usize)
        .filter(|&i| inner(i % W as usize, i / W as usize))
        .step_by(stride)
        .map(|i| ((i % W as usize, i / W as usize), hits[i].unwrap()))
        .collect()
}

/// The truth's mean sky light (white sky, no lights) over `at`.
fn truth_sky(truth: &ReferenceScene, at: &[((usize, usize), Surface)]) -> f32 {
    let settings = TraceSettings { samples_per_pixel: 256, seed: 3, radius: 1.0, sky_scale: 1.0, ambient: 0.0 };
    let rig = LightRig { strength: 1.0, min_distance: 0.01, cube_half_size: 0.01 };
    let sky = Skybox::constant(Vec3::ONE);
    let mut rng = StdRng::seed_from_u64(5);
    let sum: f32 = at.iter().map(|(_, s)| truth.estimate(s, &[], &rig, &sky, &settings, &mut rng).sky.x).sum();
    sum / at.len() as f32
}

/// The march's mean sky light over `at`, from one frame.
fn march_sky(
    gpu: &ssdo::gpu::Gpu,
    model: &Model,
    camera: &OrbitCamera,
    settings: Settings,
    at: &[((usize, usize), Surface)],
) -> f32 {
    let scene = Scene::new(model.clone(), 0, 1);
    let mut r = renderer(gpu, &scene, &Skybox::constant(Vec3::ONE), (W, H), settings);
    shoot(gpu, &mut r, camera);
    let d = read_rgba16f(gpu, &r.targets().occlusion().directional.unwrap().texture).unwrap();
    at.iter().map(|&((x, y), _)| d[y * W as usize + x][0]).sum::<f32>() / at.len() as f32
}

/// The mean sky light over some pixels: the truth's, the march's with each material's own
/// thickness, and with every surface a slab of the scene's default thickness (as before).
struct SkyAt {
    pixels: usize,
    truth: f32,
    own: f32,
    slab: f32,
}

impl SkyAt {
    fn measure(gpu: &ssdo::gpu::Gpu, model: &Model, camera: &OrbitCamera, at: &[((usize, usize), Surface)]) -> Self {
        let default = Scene::new(model.clone(), 0, 1).default_radius() * ssdo::render::THICKNESS_RADII;
        Self {
            pixels: at.len(),
            truth: truth_sky(&ReferenceScene::new(model), at),
            own: march_sky(gpu, model, camera, sky_light(None), at),
            slab: march_sky(gpu, model, camera, sky_light(Some(default)), at),
        }
    }

    /// The relative errors of the march with the materials' thickness and with the slab.
    fn own_error(&self) -> f32 {
        (self.own - self.truth).abs() / self.truth
    }

    fn slab_error(&self) -> f32 {
        (self.slab - self.truth).abs() / self.truth
    }
}

impl std::fmt::Display for SkyAt {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        let (pixels, truth, own, slab) = (self.pixels, self.truth, self.own, self.slab);
        write!(f, "{pixels} pixels: truth {truth:.4}, own thickness {own:.4}, one slab {slab:.4}")
    }
}

/// Whether the renderer plans a thickness layer for `model` with `settings`.
fn plans_layer(gpu: &ssdo::gpu::Gpu, model: &Model, settings: Settings) -> bool {
    let scene = Scene::new(model.clone(), 0, 1);
    let r = renderer(gpu, &scene, &Skybox::constant(Vec3::ONE), (W, H), settings);
    r.plan().thickness_layer
}

/// The report's checker-cut fence, its truth, and a camera in front of it and above, through
/// whose holes the floor behind it shows.
fn fence_from_the_front() -> (Model, ReferenceScene, OrbitCamera) {
    let model = ssdo::report::scenes::fence().unwrap();
    let truth = ReferenceScene::new(&model);
    (model, truth, looking(Vec3::new(0.0, 0.45, -0.3), 0.0, 24.0, 3.2))
}

#[test]
fn the_floor_seen_through_a_checker_fence_gets_the_truths_sky() {
    let Some(gpu) = gpu() else { return };
    let (model, truth, camera) = fence_from_the_front();
    let behind = |s: &Surface| s.normal.y > 0.99 && s.position.y.abs() < 1e-3 && s.position.z < -0.05;
    let seen_through = pixels(&truth, &camera, 1, behind)
        .into_iter()
        .filter(|&((x, y), _)| {
            // Only the floor whose eye ray crossed the fence's plane below its top.
            let (eye, dir) = eye_ray(&camera, (x, y));
            let t = -eye.z / dir.z;
            let crossing = eye + t * dir;
            crossing.y > 0.05 && crossing.y < 1.15 && crossing.x.abs() < 1.45
        })
        .collect::<Vec<_>>();
    assert!(seen_through.len() >= 40, "only {} floor pixels show through the fence", seen_through.len());
    let at: Vec<_> = seen_through.into_iter().step_by(3).collect();
    let sky = SkyAt::measure(gpu, &model, &camera, &at);
    eprintln!("floor behind the fence: {sky}");
    assert!(sky.own_error() <= 0.05, "the floor behind the fence: {sky}");
    assert!(sky.slab_error() > 0.05, "a slab closes the holes: {sky}");
}

/// Three thin fins (0.2 wide, 0.8 tall, 0.03 thick) in a row on a floor: a thin solid material.
fn fins() -> Model {
    let v = Vec3::new;
    let mut b = MeshBuilder::default();
    let floor = b.material(Material::plain("floor", [0.8; 3]));
    let fins = b.material(Material::plain("fins", [0.8; 3]));
    b.floor(floor, 2.0);
    for k in 0..3 {
        let x = -1.0 + 0.9 * k as f32;
        b.cuboid(fins, v(x, 0.0, -0.015), v(x + 0.2, 0.8, 0.015), false);
    }
    b.build("fins").unwrap()
}

#[test]
fn the_far_side_of_a_thin_fin_is_not_taken_for_a_slab() {
    let Some(gpu) = gpu() else { return };
    let model = fins();
    let truth = ReferenceScene::new(&model);
    // From the front: the floor behind the fins, within a slab's depth of them (the default
    // thickness here is 0.28), sees the sky past their sides and over their tops.
    let camera = looking(Vec3::new(0.0, 0.3, 0.0), 0.0, 25.0, 3.5);
    let behind = |s: &Surface| {
        let p = s.position;
        s.normal.y > 0.99 && p.y.abs() < 1e-3 && p.z < 0.0 && p.z > -0.6 && p.x > -1.1 && p.x < 1.0
    };
    let at = pixels(&truth, &camera, 2, behind);
    assert!(at.len() >= 40, "only {} floor pixels behind the fins", at.len());
    let sky = SkyAt::measure(gpu, &model, &camera, &at);
    eprintln!("floor behind thin fins: {sky}");
    assert!(sky.own_error() <= 0.03, "behind the fins: {sky}");
    assert!(sky.slab_error() > 0.05, "a slab darkens the floor behind: {sky}");
}

#[test]
fn only_a_scene_with_a_thin_material_and_no_given_thickness_draws_the_thickness_layer() {
    let Some(gpu) = gpu() else { return };
    let thin = fins();
    assert!(plans_layer(gpu, &thin, sky_light(None)), "thin fins take their own thickness");
    assert!(!plans_layer(gpu, &thin, sky_light(Some(0.1))), "a given thickness is every sample's");
    let points = Settings { knobs: Knobs::for_variant(Variant::Points), ..sky_light(None) };
    assert!(!plans_layer(gpu, &thin, points), "the point estimator has no thickness");
    let off = Settings { mode: Mode::Off, view: View::Final, ..sky_light(None) };
    assert!(!plans_layer(gpu, &thin, off), "Off samples nothing");
    let shown = Settings { mode: Mode::Off, view: View::Thickness, ..sky_light(None) };
    assert!(plans_layer(gpu, &thin, shown), "the thickness view shows the layer in any mode");
    let solid = ssdo::scene::builtin::plane(10.0, [0.5; 3]).unwrap();
    assert!(!plans_layer(gpu, &solid, sky_light(None)), "an open floor is no thin material");
    let cornell = ssdo::scene::load_model(None).unwrap();
    assert!(!plans_layer(gpu, &cornell, sky_light(None)), "the default scene runs today's passes");
}

#[test]
fn the_thickness_view_shows_a_cut_out_as_a_sheet_and_the_floor_as_the_default_slab() {
    let Some(gpu) = gpu() else { return };
    let (model, truth, camera) = fence_from_the_front();
    let fence = pixels(&truth, &camera, 1, |s| s.position.z.abs() < 1e-3 && s.normal.z.abs() > 0.99);
    let floor = pixels(&truth, &camera, 1, |s| s.normal.y > 0.99 && s.position.z > 0.3);
    assert!(fence.len() >= 20 && floor.len() >= 20, "{} fence and {} floor pixels", fence.len(), floor.len());
    let scene = Scene::new(model, 0, 1);
    let settings = Settings { view: View::Thickness, ..sky_light(None) };
    let mut r = renderer(gpu, &scene, &Skybox::constant(Vec3::ONE), (W, H), settings);
    let image = shoot(gpu, &mut r, &camera);
    let mean = |at: &[((usize, usize), Surface)]| {
        let rgb = |(x, y): (usize, usize)| {
            let p = image.get_pixel(x as u32, y as u32).0;
            Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32)
        };
        at.iter().map(|&(pixel, _)| rgb(pixel)).sum::<Vec3>() / at.len() as f32
    };
    let (sheet, slab) = (mean(&fence), mean(&floor));
    eprintln!("thickness view: fence {sheet}, floor {slab}");
    assert!(slab.min_element() > 250.0, "the floor is the default slab (white): {slab}");
    assert!(sheet.x > 150.0 && sheet.y < 0.5 * sheet.x, "the fence, a sheet seen face-on, is red: {sheet}");
}

/// The march's mean bounce over `at` (SSDO's DO less its sky light: the same frame rendered
/// with the bounce off), from one frame under a white sky.
fn march_bounce(gpu: &ssdo::gpu::Gpu, model: &Model, camera: &OrbitCamera, at: &[((usize, usize), Surface)]) -> Vec3 {
    let scene = Scene::new(model.clone(), 0, 1);
    let directional = |indirect_strength: f32| {
        let base = sky_light(None);
        let settings = Settings { knobs: Knobs { indirect_strength, ..base.knobs }, view: View::Final, ..base };
        let mut r = renderer(gpu, &scene, &Skybox::constant(Vec3::ONE), (W, H), settings);
        shoot(gpu, &mut r, camera);
        read_rgba16f(gpu, &r.targets().occlusion().directional.unwrap().texture).unwrap()
    };
    let (with, without) = (directional(1.0), directional(0.0));
    let texel = |d: &[[f32; 4]], (x, y): (usize, usize)| Vec3::from_slice(&d[y * W as usize + x][..3]);
    at.iter().map(|&(pixel, _)| texel(&with, pixel) - texel(&without, pixel)).sum::<Vec3>() / at.len() as f32
}

#[test]
fn the_floor_behind_a_fence_gets_the_bounce_of_the_fences_far_side() {
    let Some(gpu) = gpu() else { return };
    let (model, truth, camera) = fence_from_the_front();
    // The floor just behind the fence, seen through its holes: the fence's side that faces it
    // is the one the camera does not see.
    let behind = |s: &Surface| s.normal.y > 0.99 && s.position.y.abs() < 1e-3 && (-0.4..-0.05).contains(&s.position.z);
    let at: Vec<_> = pixels(&truth, &camera, 1, behind)
        .into_iter()
        .filter(|&((x, y), _)| {
            let (eye, dir) = eye_ray(&camera, (x, y));
            let crossing = eye + (-eye.z / dir.z) * dir;
            crossing.y > 0.05 && crossing.y < 1.15 && crossing.x.abs() < 1.2
        })
        .collect();
    assert!(at.len() >= 20, "only {} floor pixels behind the fence", at.len());
    let settings = TraceSettings { samples_per_pixel: 256, seed: 3, radius: 1.0, sky_scale: 1.0, ambient: 0.0 };
    let rig = LightRig { strength: 1.0, min_distance: 0.01, cube_half_size: 0.01 };
    let mut rng = StdRng::seed_from_u64(5);
    let sky = Skybox::constant(Vec3::ONE);
    let truth_bounce =
        at.iter().map(|(_, s)| truth.estimate(s, &[], &rig, &sky, &settings, &mut rng).bounce).sum::<Vec3>()
            / at.len() as f32;
    let bounce = march_bounce(gpu, &model, &camera, &at);
    eprintln!("bounce on the floor behind the fence ({} pixels): truth {truth_bounce}, march {bounce}", at.len());
    // Brown slats: the bounce is redder than it is blue, on both sides.
    assert!(truth_bounce.x > 1.15 * truth_bounce.z, "the truth's bounce is the fence's: {truth_bounce}");
    assert!(bounce.x > 1.15 * bounce.z, "the march's bounce is the fence's: {bounce}");
    // With the far side sending nothing the march's red was a tenth of the truth's (0.006 against
    // 0.060); with it, about 1.5 times (the near side's light stands in for the far side's, and
    // the march takes the holes between two samples on the fence for fence).
    let ratio = bounce.x / truth_bounce.x;
    assert!((0.5..=2.0).contains(&ratio), "the march's bounce over the truth's: {ratio:.2}");
}
