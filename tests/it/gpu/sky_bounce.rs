//! SSDO's bounce under a sky: the senders bounce their own direct light, sky included, so a red
//! wall turns the floor beside it red under a white sky with no lights at all; a wall on a floor
//! sends the closed-form bounce, on the GPU and in the ray-traced truth; the point lights' part
//! is what it was.

use crate::common;

use common::{gpu, looking, project, red_wall_view, renderer, shoot, H, W};
use glam::Vec3;
use rand::{rngs::StdRng, SeedableRng};
use ssdo::gpu::Gpu;
use ssdo::headless::readback::read_rgba16f;
use ssdo::knobs::Knobs;
use ssdo::reference::{ReferenceScene, TraceSettings};
use ssdo::render::targets::BOUNCE;
use ssdo::render::{GivenLengths, Mode, Renderer, SenderSky, Settings, View};
use ssdo::scene::builtin::MeshBuilder;
use ssdo::scene::{LightRig, Material, OrbitCamera, Scene, Skybox};

/// One frame's HDR image and (DO modes) its DO buffer, pre-exposure divided out.
fn frame(gpu: &Gpu, scene: &Scene, sky: &Skybox, camera: &OrbitCamera, s: Settings) -> (Vec<[f32; 4]>, Vec<[f32; 4]>) {
    let mut r = renderer(gpu, scene, sky, (W, H), s);
    shoot(gpu, &mut r, camera);
    let k = 1.0 / r.pre_exposure();
    let unexpose = |v: Vec<[f32; 4]>| v.into_iter().map(|p| [p[0] * k, p[1] * k, p[2] * k, p[3]]).collect::<Vec<_>>();
    let hdr = unexpose(read_rgba16f(gpu, &r.targets().hdr().unwrap().texture).unwrap());
    let directional = r.targets().occlusion().directional.map(|t| unexpose(read_rgba16f(gpu, &t.texture).unwrap()));
    (hdr, directional.unwrap_or_default())
}

/// `s` with the bounce's senders lit by `sender_sky`.
fn with_senders(sender_sky: SenderSky, s: Settings) -> Settings {
    Settings { knobs: Knobs { sender_sky, ..s.knobs }, ..s }
}

fn settings(mode: Mode) -> Settings {
    Settings {
        mode,
        ambient: 0.0,
        given: GivenLengths { radius: Some(0.3), ..Default::default() },
        ..Settings::default()
    }
}

/// The truth's bounce (E/π) at the floor point under `point`, from many rays.
fn traced_bounce(scene: &Scene, sky: &Skybox, point: Vec3, spp: u32) -> (Vec3, f32) {
    let reference = ReferenceScene::new(&scene.model);
    let dir = Vec3::new(1e-3, -1.0, 1.3e-3).normalize();
    let surface = reference.trace(point - dir, dir, 10.0).expect("the floor is there");
    let settings = TraceSettings { samples_per_pixel: spp, seed: 11, radius: 0.3, sky_scale: 1.0, ambient: 0.0 };
    let rig = LightRig { strength: 1.0, min_distance: 0.01, cube_half_size: 0.01 };
    let e = reference.estimate(&surface, &scene.lights, &rig, sky, &settings, &mut StdRng::seed_from_u64(2));
    (e.bounce, e.bounce_error)
}

/// The red wall's scene with no lights under a white sky, and the camera that sees the floor
/// beside the wall (the floor point 0.15 from it is the one the tests read).
fn red_wall_under_a_white_sky() -> (Scene, Skybox, OrbitCamera) {
    let (mut scene, sky, camera) = red_wall_view(Vec3::ONE);
    scene.lights.clear();
    (scene, sky, camera)
}

#[test]
fn under_a_white_sky_alone_the_red_wall_turns_the_floor_beside_it_red_in_ssdo_only() {
    let Some(gpu) = gpu() else { return };
    let (scene, sky, camera) = red_wall_under_a_white_sky();
    let near_point = Vec3::new(0.15, 0.0, 0.0);
    let (near, far) = (project(&camera, near_point), project(&camera, Vec3::new(1.8, 0.0, 1.0)));
    let redness = |c: Vec3| c.x / c.y.max(1e-6);

    for mode in [Mode::Off, Mode::Ssao] {
        let (hdr, _) = frame(gpu, &scene, &sky, &camera, settings(mode));
        let c = common::window_mean(&hdr, near, 1);
        assert!((redness(c) - 1.0).abs() < 0.02, "{mode}: the floor by the wall stays white: {c}");
    }
    for mode in [Mode::Ssdo, Mode::Both] {
        let (hdr, _) = frame(gpu, &scene, &sky, &camera, settings(mode));
        let (by_wall, open) = (common::window_mean(&hdr, near, 1), common::window_mean(&hdr, far, 1));
        assert!(redness(by_wall) > 1.15, "{mode}: the floor by the wall turns red: {by_wall}");
        assert!(redness(by_wall) > redness(open) + 0.1, "{mode}: the red fades away from the wall: {open}");
    }

    // The bounce alone, against the truth's at the same floor point.
    let s = Settings { view: View::DoIndirect, ..settings(Mode::Ssdo) };
    let (_, directional) = frame(gpu, &scene, &sky, &camera, s);
    let got = common::window_mean(&directional, near, 1);
    let (want, sigma) = traced_bounce(&scene, &sky, near_point, 8192);
    eprintln!("bounce 0.15 from the red wall under a white sky: GPU {got}, truth {want} ± {sigma}");
    assert!(got.x > 5.0 * got.y, "the bounce is red: {got}");
    assert!((got.x / want.x - 1.0).abs() < 0.25, "GPU bounce {got} against the truth {want} (±25%)");

    // Senders lit by the point lights alone: no light, so no bounce at all.
    let s = with_senders(SenderSky::Off, Settings { view: View::DoIndirect, ..settings(Mode::Ssdo) });
    let mut r = renderer(gpu, &scene, &sky, (W, H), s);
    shoot(gpu, &mut r, &camera);
    let d = read_rgba16f(gpu, &r.targets().occlusion().directional.unwrap().texture).unwrap();
    assert!(d.iter().all(|p| p[..3] == [0.0; 3]), "no lights and no sky for the senders: no bounce");
}

/// A wall in the plane z = 0, `h` high and 20 wide, facing +z, standing on a floor that reaches
/// `depth` in front of it, both grey.
fn wall_on_floor(h: f32, depth: f32, half_width: f32) -> Scene {
    let v = Vec3::new;
    let mut b = MeshBuilder::default();
    let floor = b.material(Material::plain("floor", [0.5; 3]));
    let wall = b.material(Material::plain("wall", [0.8; 3]));
    let w = half_width;
    b.quad(floor, [v(-w, 0.0, depth), v(w, 0.0, depth), v(w, 0.0, -depth), v(-w, 0.0, -depth)]);
    b.quad(wall, [v(-10.0, 0.0, 0.0), v(10.0, 0.0, 0.0), v(10.0, h, 0.0), v(-10.0, h, 0.0)]);
    Scene::new(b.build("wall").unwrap(), 0, 1)
}

#[test]
fn the_truth_bounces_the_sky_a_wall_on_a_floor_sees_in_closed_form() {
    // On a floor reaching far in every direction the wall's hemisphere is cut in half, so each of
    // its points sees half the sky (E/π = L/2) and sends ρ·L/2; a floor point at distance d sees
    // the wall through the form factor of an infinitely long wall (crossed strings),
    // (1 − d/√(d² + h²))/2.
    let (h, d, albedo) = (3.0f32, 0.9f32, 0.8f32);
    let scene = wall_on_floor(h, 40.0, 40.0);
    let sky = Skybox::constant(Vec3::ONE);
    let want = albedo * 0.5 * 0.5 * (1.0 - d / (d * d + h * h).sqrt());
    let (traced, sigma) = traced_bounce(&scene, &sky, Vec3::new(0.0, 0.0, d), 16384);
    eprintln!("wall on a floor at d = {d}: closed form {want:.4}, truth {:.4} ± {sigma:.4}", traced.x);
    // The wall is 20 wide, not infinite, and the floor ends 40 out: both within 2%.
    assert!(
        (traced.x - want).abs() < 3.0 * sigma + 0.02 * want,
        "the truth {} against the closed form {want}",
        traced.x
    );
}

#[test]
fn a_floor_point_facing_a_wall_gets_the_truths_bounce_when_the_screen_shows_what_the_wall_sees() {
    let Some(gpu) = gpu() else { return };
    // The floor reaches 2 in front of the wall, all of it on screen: the wall's own march sees
    // everything that hides its sky, so the screen-space estimate can match the truth.
    let (h, d) = (3.0f32, 0.9f32);
    let scene = wall_on_floor(h, 2.0, 10.0);
    let sky = Skybox::constant(Vec3::ONE);
    let receiver = Vec3::new(0.0, 0.0, d);
    let (want, sigma) = traced_bounce(&scene, &sky, receiver, 16384);
    let camera = looking(Vec3::new(0.0, 1.3, 0.0), 0.0, 12.0, 9.0);
    // 32 steps: with 12 the sparse far steps see the floor from the wall's upper half short by a
    // step, and the bounce comes out 11% high (0.232 against 0.209, measured).
    let base = settings(Mode::Ssdo);
    let knobs = Knobs { slices: 8, steps: 32, ..base.knobs };
    let given = GivenLengths { reach: Some(10.0), thickness: Some(1.0), ..base.given };
    let s = Settings { view: View::DoIndirect, knobs, given, ..base };
    let (_, directional) = frame(gpu, &scene, &sky, &camera, s);
    let got = common::window_mean(&directional, project(&camera, receiver), 1).x;
    eprintln!("wall on a floor strip at d = {d}: GPU bounce {got:.4}, truth {:.4} ± {sigma:.4}", want.x);
    assert!((got / want.x - 1.0).abs() < 0.1, "GPU bounce {got} against the truth {} (±10%)", want.x);

    // The senders' sky marched at quarter resolution: each sender stands for its 4x4 block, and
    // the bounce holds as well.
    let quarter = with_senders(SenderSky::MarchQuarter, s);
    let got = common::window_mean(&frame(gpu, &scene, &sky, &camera, quarter).1, project(&camera, receiver), 1).x;
    eprintln!("the same with the senders' sky at quarter resolution: {got:.4}");
    assert!((got / want.x - 1.0).abs() < 0.1, "quarter-resolution senders: {got} against the truth {}", want.x);

    // The senders' sky from the last frame's march: the second frame reads what the first one's
    // sampling pass saw (all its 8 slices), and the bounce holds as well.
    let last_frame = Settings { knobs: Knobs { sender_sky: SenderSky::LastFrame, accumulate: 1, ..s.knobs }, ..s };
    let mut r = renderer(gpu, &scene, &sky, (W, H), last_frame);
    shoot(gpu, &mut r, &camera);
    shoot(gpu, &mut r, &camera);
    let d = read_rgba16f(gpu, &r.targets().occlusion().directional.unwrap().texture).unwrap();
    let got = common::window_mean(&d, project(&camera, receiver), 1).x / r.pre_exposure();
    eprintln!("the same with the senders' sky from the last frame: {got:.4}");
    assert!((got / want.x - 1.0).abs() < 0.1, "the last frame's senders: {got} against the truth {}", want.x);

    // The senders' unoccluded irradiance ignores the floor below the wall: measurably too bright.
    let s = with_senders(SenderSky::Irradiance, s);
    let (_, directional) = frame(gpu, &scene, &sky, &camera, s);
    let unoccluded = common::window_mean(&directional, project(&camera, receiver), 1).x;
    assert!(unoccluded > 1.25 * want.x, "unoccluded senders {unoccluded} against the truth {}", want.x);
}

#[test]
fn under_a_black_sky_the_bounce_is_the_point_lights_alone_as_before() {
    let Some(gpu) = gpu() else { return };
    let (scene, sky, camera) = red_wall_view(Vec3::ZERO);
    let lit = |sender_sky| frame(gpu, &scene, &sky, &camera, with_senders(sender_sky, settings(Mode::Both))).1;
    let before = lit(SenderSky::Off);
    for sender_sky in [SenderSky::March, SenderSky::MarchQuarter, SenderSky::LastFrame, SenderSky::Irradiance] {
        let now = lit(sender_sky);
        let worst = now.iter().zip(&before).map(|(a, b)| (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f32::max));
        let worst = worst.fold(0.0, f32::max);
        assert!(worst < 1e-6, "{sender_sky:?}: a black sky and no ambient add nothing to the bounce ({worst})");
    }
    assert!(before.iter().any(|p| p[0] > 0.01), "the lights' red bounce is there");
}

#[test]
fn the_sky_strength_scales_the_senders_sky_as_it_scales_the_receivers() {
    let Some(gpu) = gpu() else { return };
    let (scene, sky, camera) = red_wall_under_a_white_sky();
    let near = project(&camera, Vec3::new(0.15, 0.0, 0.0));
    for sender_sky in [SenderSky::March, SenderSky::MarchQuarter, SenderSky::LastFrame, SenderSky::Irradiance] {
        let bounce = |sky_strength| {
            let s = with_senders(sender_sky, Settings { sky_strength, view: View::DoIndirect, ..settings(Mode::Ssdo) });
            common::window_mean(&frame(gpu, &scene, &sky, &camera, s).1, near, 1).x
        };
        let (one, two) = (bounce(1.0), bounce(2.0));
        assert!(one > 0.01 && (two / one - 2.0).abs() < 0.02, "{sender_sky:?}: bounce {one} at 1, {two} at 2");
    }
}

#[test]
fn the_senders_sky_from_the_last_frame_bounces_what_their_own_march_does_still_and_turning() {
    let Some(gpu) = gpu() else { return };
    let (scene, sky, camera) = red_wall_under_a_white_sky();
    let near_point = Vec3::new(0.15, 0.0, 0.0);
    // One frame each (no average), the bounce alone.
    let s = |sender_sky| {
        let base = Settings { view: View::DoIndirect, ..settings(Mode::Ssdo) };
        Settings { knobs: Knobs { sender_sky, accumulate: 1, ..base.knobs }, ..base }
    };
    let bounce = |r: &Renderer| read_rgba16f(gpu, &r.targets().occlusion().directional.unwrap().texture).unwrap();
    let red = |d: &[[f32; 4]], camera: &OrbitCamera| common::window_mean(d, project(camera, near_point), 1).x;

    let mut march = renderer(gpu, &scene, &sky, (W, H), s(SenderSky::March));
    let mut last = renderer(gpu, &scene, &sky, (W, H), s(SenderSky::LastFrame));
    shoot(gpu, &mut march, &camera);
    shoot(gpu, &mut last, &camera);
    // The first frame has no last frame: it marches the senders as `march` does.
    assert!(bounce(&march) == bounce(&last), "the first frame is the senders' own march's");
    let want = red(&bounce(&march), &camera);
    assert!(want > 0.01, "the red wall bounces: {want}");

    // The next frame reads the sky the last frame's march saw at each sender.
    shoot(gpu, &mut last, &camera);
    let still = red(&bounce(&last), &camera);
    eprintln!("red bounce 0.15 from the wall: the senders' march {want:.4}, the last frame's {still:.4}");
    assert!((still / want - 1.0).abs() < 0.1, "still: {still} against the senders' own march's {want}");

    // What each sender sends, against what it sends after its own march, over the image: the
    // sky a sender reads differs by the march's noise alone, and by as little after a turn far
    // enough that most pixels show another surface than a frame before, since each reads its
    // sky where the last camera saw it.
    let sent = |r: &Renderer| read_rgba16f(gpu, &r.targets().expect(BOUNCE).texture).unwrap();
    // (Over 4x4 blocks, which average most of the one-slice march's noise away.)
    let blocks = |v: &[[f32; 4]]| {
        let mut out = vec![0.0f32; (W as usize / 4) * (H as usize / 4)];
        for (i, p) in v.iter().enumerate() {
            let (x, y) = (i % W as usize / 4, i / W as usize / 4);
            out[y * (W as usize / 4) + x] += p[0];
        }
        out
    };
    let apart = |a: &[[f32; 4]], b: &[[f32; 4]]| {
        let (a, b) = (blocks(a), blocks(b));
        a.iter().zip(&b).map(|(a, b)| (a - b).abs()).sum::<f32>() / b.iter().sum::<f32>()
    };
    let still_apart = apart(&sent(&last), &sent(&march));
    let turned = OrbitCamera { yaw_deg: camera.yaw_deg + 20.0, ..camera };
    shoot(gpu, &mut last, &turned);
    let mut fresh = renderer(gpu, &scene, &sky, (W, H), s(SenderSky::March));
    shoot(gpu, &mut fresh, &turned);
    let turned_apart = apart(&sent(&last), &sent(&fresh));
    let (got, want) = (red(&bounce(&last), &turned), red(&bounce(&fresh), &turned));
    eprintln!("after turning 20°: the senders' march {want:.4}, the last frame's reprojected {got:.4}");
    eprintln!("senders' light apart from their own march's: still {still_apart:.4}, turned {turned_apart:.4}");
    assert!((got / want - 1.0).abs() < 0.1, "turning: {got} against the senders' own march's {want}");
    // (Measured 0.029 still and 0.036 turned; each pixel reading its own texel after the turn,
    // 0.078.)
    assert!(still_apart < 0.05 && turned_apart < 0.055, "senders apart: still {still_apart}, turned {turned_apart}");
}
