//! SSAO and SSDO against answers known in closed form, and against each other: the white
//! furnace, AO of an open plane and of a corner, colour bleeding, directional sky light, one
//! pass for Both, the plan of each mode, and finite buffers everywhere.

use crate::common;

use common::{gpu, looking, project, red_wall_view, renderer, shoot, Furnace, H, W};
use glam::Vec3;
use ssdo::gpu::Gpu;
use ssdo::headless::readback::{read_occlusion, read_rgba16f, OcclusionValues};
use ssdo::knobs::Knobs;
use ssdo::render::{GivenLengths, Mode, Renderer, Settings, Variant};
use ssdo::scene::builtin::{self, MeshBuilder};
use ssdo::scene::{Material, Model, OrbitCamera, Scene, Skybox};

/// Full resolution: these tests check the estimators at each pixel (tests/temporal.rs checks the
/// half-resolution upsample, and the white furnace with it).
fn settings(mode: Mode) -> Settings {
    Settings { mode, ambient: 0.0, knobs: Knobs { half_resolution: false, ..Knobs::default() }, ..Settings::default() }
}

/// The default sampling at radius `r`.
fn radius(r: f32) -> GivenLengths {
    GivenLengths { radius: Some(r), ..Default::default() }
}

/// Pixel coordinates of world point `p`.
fn at<T: Copy>(buffer: &[T], (x, y): (usize, usize)) -> T {
    buffer[y * W as usize + x]
}

fn rgb(p: [f32; 4]) -> Vec3 {
    Vec3::new(p[0], p[1], p[2])
}

struct Buffers {
    /// AO from its own target (SSAO) or from DO's alpha (SSAO+SSDO).
    ao: Option<Vec<f32>>,
    /// SSDO's sky light + bounce (rgb) as the sampling pass wrote it.
    directional: Option<Vec<[f32; 4]>>,
    hdr: Vec<[f32; 4]>,
}

/// Renders one frame and reads the sampling pass's raw (or the blurred) outputs and HDR.
fn render(gpu: &Gpu, r: &mut Renderer, camera: &OrbitCamera, blurred: bool) -> Buffers {
    shoot(gpu, r, camera);
    let t = r.targets();
    let set = if blurred { t.occlusion() } else { t.raw() };
    let OcclusionValues { ao, directional } = read_occlusion(gpu, set, r.plan().decl.ambient_occlusion).unwrap();
    Buffers { ao, directional, hdr: read_rgba16f(gpu, &t.hdr().unwrap().texture).unwrap() }
}

fn open_plane(albedo: f32) -> Scene {
    Scene::new(builtin::plane(100.0, [albedo; 3]).unwrap(), 0, 1)
}

#[test]
fn white_furnace_open_plane_returns_albedo_times_sky() {
    let Some(gpu) = gpu() else { return };
    let Furnace { scene, sky, radiance: sky_radiance, camera } = Furnace::new();
    let albedo = Furnace::ALBEDO;
    for (variant, blur, samples) in [false, true].into_iter().flat_map(|blur| {
        [(Variant::Points, 4), (Variant::Points, 16), (Variant::Points, 64), (Variant::March, 1), (Variant::March, 4)]
            .map(|(v, n)| (v, blur, n))
    }) {
        {
            // Points take `samples` points; the march takes `samples` slices.
            let base = settings(Mode::Ssdo);
            let knobs = Knobs { variant, samples, slices: samples, blur, ..base.knobs };
            let s = Settings { knobs, given: radius(0.5), ..base };
            let mut r = renderer(gpu, &scene, &sky, (W, H), s);
            let b = render(gpu, &mut r, &camera, true);
            let direct = b.directional.unwrap();
            for p in Furnace::PIXELS {
                let got = rgb(at(&direct, p));
                assert!(
                    (got / sky_radiance - 1.0).abs().max_element() < 0.01,
                    "{variant}: DO direct {got} at {p:?}, {samples} samples, blur {blur}"
                );
                let hdr = rgb(at(&b.hdr, p));
                let want = albedo * sky_radiance;
                assert!((hdr / want - 1.0).abs().max_element() < 0.01, "radiance {hdr} vs {want} at {p:?}");
            }
        }
    }
    // Every mode is lit by the same sky: Off (the sky's irradiance), SSAO (× AO = 1) and Both
    // give ρ·L as well, with and without a constant ambient A on top (ρ·(L + A)).
    for ambient in [0.0, 0.2] {
        for mode in Mode::ALL {
            let s = Settings { given: radius(0.5), ambient, ..settings(mode) };
            let mut r = renderer(gpu, &scene, &sky, (W, H), s);
            let hdr = render(gpu, &mut r, &camera, true).hdr;
            let want = albedo * (sky_radiance + Vec3::splat(ambient));
            for p in Furnace::PIXELS {
                let got = rgb(at(&hdr, p));
                assert!((got / want - 1.0).abs().max_element() < 0.01, "{mode}, A {ambient}: {got} vs ρ·(L+A) {want}");
            }
        }
    }
}

#[test]
fn open_plane_ao_is_one_everywhere_including_the_edges() {
    let Some(gpu) = gpu() else { return };
    let scene = open_plane(0.8);
    let sky = Skybox::constant(Vec3::ONE);
    // Looking down steeply: samples near the borders project off-screen and must be skipped.
    let camera = looking(Vec3::ZERO, 0.0, 70.0, 2.0);
    for variant in Variant::ALL {
        let base = settings(Mode::Ssao);
        let knobs = Knobs { variant, samples: 32, blur: false, ..base.knobs };
        let s = Settings { knobs, given: radius(0.4), ..base };
        let mut r = renderer(gpu, &scene, &sky, (W, H), s);
        let ao = render(gpu, &mut r, &camera, false).ao.unwrap();
        let low = ao.iter().copied().fold(1.0, f32::min);
        assert!(low >= 0.99, "{variant}: lowest AO on an open plane {low}");
        assert!(ao.iter().all(|a| *a <= 1.0));
    }
}

#[test]
fn inside_corner_is_more_occluded_than_open_floor() {
    let Some(gpu) = gpu() else { return };
    // Facing the wall: the corner is a horizontal line across the middle of the view.
    let (mut scene, sky, camera) = red_wall_view(Vec3::ONE);
    scene.lights.clear();
    for variant in Variant::ALL {
        let base = settings(Mode::Ssao);
        let s = Settings { knobs: Knobs { variant, samples: 32, ..base.knobs }, given: radius(0.5), ..base };
        let mut r = renderer(gpu, &scene, &sky, (W, H), s);
        let ao = render(gpu, &mut r, &camera, true).ao.unwrap();
        let corner = at(&ao, project(&camera, Vec3::new(0.1, 0.0, 0.0)));
        let open = at(&ao, project(&camera, Vec3::new(1.8, 0.0, 1.0)));
        assert!(open > 0.95, "{variant}: open floor AO {open}");
        assert!(corner < open - 0.1, "{variant}: floor at the wall's foot {corner} vs open floor {open}");
    }
}

/// A white floor (x from 0 to 4) meeting a red wall at x = 0, lit by one white light.
#[test]
fn red_wall_bleeds_onto_white_floor_in_ssdo_not_in_ssao() {
    let Some(gpu) = gpu() else { return };
    let (scene, sky, camera) = red_wall_view(Vec3::ZERO);
    let near = project(&camera, Vec3::new(0.12, 0.0, 0.0));
    let far = project(&camera, Vec3::new(1.8, 0.0, 1.0));
    let ratio = |c: Vec3| c.x / c.y.max(1e-6);

    let base = settings(Mode::Ssdo);
    let s = Settings { knobs: Knobs { samples: 32, ..base.knobs }, given: radius(0.5), ..base };
    let mut r = renderer(gpu, &scene, &sky, (W, H), s);
    let b = render(gpu, &mut r, &camera, true);
    // The sky is black: DO is the indirect bounce alone.
    let indirect = common::window_mean(&b.directional.unwrap(), near, 1);
    assert!(indirect.x > 0.01 && indirect.x > 5.0 * indirect.y, "red bounce near the wall: {indirect}");
    let ssdo_near = common::window_mean(&b.hdr, near, 1);
    let ssdo_far = common::window_mean(&b.hdr, far, 1);

    r.set_mode(gpu, Mode::Ssao);
    let b = render(gpu, &mut r, &camera, true);
    let ssao_near = common::window_mean(&b.hdr, near, 1);
    assert!((ratio(ssao_near) - 1.0).abs() < 0.02, "SSAO floor stays white: {ssao_near}");
    assert!(
        ratio(ssdo_near) > 1.1 * ratio(ssao_near),
        "SSDO floor near the wall is redder: {ssdo_near} vs {ssao_near}"
    );
    assert!(ratio(ssdo_near) > ratio(ssdo_far) + 0.05, "bleeding fades with distance: {ssdo_near} vs {ssdo_far}");
}

/// A lone sphere under the blue-above, red-below sky, and a camera level with it.
fn redblue_ball() -> (Scene, Skybox, OrbitCamera) {
    let mut b = MeshBuilder::default();
    let m = b.material(Material::plain("ball", [0.8; 3]));
    b.sphere(m, Vec3::new(0.0, 2.0, 0.0), 1.0, 48, 24);
    let scene = Scene::new(b.build("ball").unwrap(), 0, 1);
    let sky = Skybox::load(std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/skyboxes/redblue"))).unwrap();
    (scene, sky, looking(Vec3::new(0.0, 2.0, 0.0), 0.0, 0.0, 5.0))
}

#[test]
fn redblue_sky_lights_tops_blue_and_bottoms_red_in_the_sky_lit_modes() {
    let Some(gpu) = gpu() else { return };
    let (scene, sky, camera) = redblue_ball();
    let top = project(&camera, Vec3::new(0.0, 2.8, 0.6));
    let bottom = project(&camera, Vec3::new(0.0, 1.2, 0.6));
    let blueness = |c: Vec3| c.z - c.x;

    let mut r = renderer(gpu, &scene, &sky, (W, H), Settings { ambient: 0.3, ..settings(Mode::Ssdo) });
    let hdr = render(gpu, &mut r, &camera, true).hdr;
    let (up, down) = (common::window_mean(&hdr, top, 1), common::window_mean(&hdr, bottom, 1));
    assert!(blueness(up) > 0.1 && blueness(down) < -0.1, "SSDO: top {up}, bottom {down}");

    // Off sees the same sky, unoccluded (its irradiance per normal): also blue on top.
    r.set_mode(gpu, Mode::Off);
    let hdr = render(gpu, &mut r, &camera, true).hdr;
    let (up, down) = (common::window_mean(&hdr, top, 1), common::window_mean(&hdr, bottom, 1));
    assert!(blueness(up) > 0.1 && blueness(down) < -0.1, "Off: top {up}, bottom {down}");

    // The classic variant keeps the SSDO course project's constant grey ambient in Off: no sky.
    r.settings.knobs.variant = Variant::Classic;
    let hdr = render(gpu, &mut r, &camera, true).hdr;
    let (up, down) = (common::window_mean(&hdr, top, 1), common::window_mean(&hdr, bottom, 1));
    assert!((up - down).abs().max_element() < 1e-3, "classic Off has no directional sky: top {up}, bottom {down}");
}

#[test]
fn ssao_and_ssdo_differ_only_where_the_sky_is_occluded() {
    // A lone sphere: nothing occludes its top, so SSAO (the sky's irradiance × AO) and SSDO (the
    // visible sky per direction) must agree there: the difference between them is occlusion alone.
    let Some(gpu) = gpu() else { return };
    let (scene, sky, camera) = redblue_ball();
    let top = project(&camera, Vec3::new(0.0, 2.8, 0.6));
    let base = settings(Mode::Ssao);
    let s = Settings { knobs: Knobs { samples: 64, ..base.knobs }, ..base };
    let mut r = renderer(gpu, &scene, &sky, (W, H), s);
    let ssao = common::window_mean(&render(gpu, &mut r, &camera, true).hdr, top, 1);
    r.set_mode(gpu, Mode::Ssdo);
    let ssdo = common::window_mean(&render(gpu, &mut r, &camera, true).hdr, top, 1);
    assert!((ssao - ssdo).abs().max_element() < 0.05 * ssao.max_element(), "open top: SSAO {ssao}, SSDO {ssdo}");
}

#[test]
fn both_is_one_pass_with_the_same_ao_and_do_as_the_separate_modes() {
    let Some(gpu) = gpu() else { return };
    let scene = Scene::new(builtin::cornell().unwrap(), 8, 3);
    let sky = ssdo::scene::load_skybox(None).unwrap();
    let camera = OrbitCamera::framing(&scene.model.bounds);
    for variant in Variant::ALL {
        let base = settings(Mode::Ssao);
        let s = Settings { knobs: Knobs { variant, blur: false, ..base.knobs }, ..base };
        let mut r = renderer(gpu, &scene, &sky, (W, H), s);
        let ao = render(gpu, &mut r, &camera, false).ao.unwrap();
        r.set_mode(gpu, Mode::Ssdo);
        let ssdo = render(gpu, &mut r, &camera, false);
        r.set_mode(gpu, Mode::Both);
        assert_eq!(r.plan().step_names().iter().filter(|n| ["ssao", "ssdo", "ssao_ssdo"].contains(n)).count(), 1);
        let both = render(gpu, &mut r, &camera, false);
        // Compared pixel by pixel; the count of differing pixels is what a failure reports.
        let ao_off = both.ao.unwrap().iter().zip(&ao).filter(|(a, b)| a != b).count();
        assert_eq!(ao_off, 0, "{variant}: AO differs at {ao_off} pixels");
        let (d_both, d_ssdo) = (both.directional.unwrap(), ssdo.directional.unwrap());
        let do_off = d_both.iter().zip(&d_ssdo).filter(|(a, b)| a[..3] != b[..3]).count();
        assert_eq!(do_off, 0, "{variant}: DO differs at {do_off} pixels");
    }
}

#[test]
fn each_mode_plans_exactly_its_passes_and_targets() {
    let Some(gpu) = gpu() else { return };
    let sky = Skybox::constant(Vec3::ONE);
    let lit = Scene::new(builtin::cornell().unwrap(), 4, 1);
    let mut r = renderer(gpu, &lit, &sky, (32, 24), settings(Mode::Off));
    // The DO modes' steps, around their sampling step.
    let directional = |sampling: &'static str| {
        let after = ["blur", "temporal", "composite", "skybox", "light_cubes", "tonemap"];
        [vec!["gbuffer", "sender_sky", "lighting", sampling], after.to_vec()].concat()
    };
    let expect = [
        (Mode::Off, vec!["gbuffer", "composite", "skybox", "light_cubes", "tonemap"]),
        (Mode::Ssao, vec!["gbuffer", "ssao", "blur", "temporal", "composite", "skybox", "light_cubes", "tonemap"]),
        (Mode::Ssdo, directional("ssdo")),
        (Mode::Both, directional("ssao_ssdo")),
    ];
    let names = |r: &Renderer| r.allocations().into_iter().map(|(n, _)| n).collect::<Vec<_>>();
    for (mode, steps) in &expect {
        r.set_mode(gpu, *mode);
        assert_eq!(&r.plan().step_names(), steps, "{mode}");
    }
    r.set_mode(gpu, Mode::Off);
    let off = names(&r);
    assert!(
        !off.iter()
            .any(|n| n.starts_with("ao") || n.starts_with("do_") || n.starts_with("bounce") || n == "occlusion_params"),
        "{off:?}"
    );
    r.set_mode(gpu, Mode::Ssao);
    let ssao = names(&r);
    assert!(
        ssao.contains(&"ao_raw".into()) && !ssao.iter().any(|n| n.starts_with("do_") || n.starts_with("bounce")),
        "{ssao:?}"
    );
    r.set_mode(gpu, Mode::Both);
    let both = names(&r);
    for wanted in ["do_raw", "do_blurred", "bounce_radiance", "sender_sky"] {
        assert!(both.contains(&wanted.to_string()), "{wanted} in {both:?}");
    }
    assert!(!both.iter().any(|n| n.starts_with("ao_")), "Both keeps AO in DO's alpha: {both:?}");
    assert!(!r.uses_texture_path(), "an untextured model takes no texture path");

    // No lights: no cubes, but the sky still bounces (the senders' sky light).
    r.set_lights(gpu, Vec::new());
    assert_eq!(
        r.plan().step_names(),
        vec!["gbuffer", "sender_sky", "lighting", "ssao_ssdo", "blur", "temporal", "composite", "skybox", "tonemap"]
    );
    assert!(names(&r).iter().any(|n| n.starts_with("bounce")));
    // No lights and senders lit by the point lights alone: nothing to bounce, no lighting pass.
    r.settings.knobs.sender_sky = ssdo::render::SenderSky::Off;
    r.apply(gpu);
    assert_eq!(
        r.plan().step_names(),
        vec!["gbuffer", "ssao_ssdo", "blur", "temporal", "composite", "skybox", "tonemap"]
    );
    assert!(!names(&r).iter().any(|n| n.starts_with("bounce") || n == "sender_sky"));
    // A bounce of strength 0 runs none of it either, whatever lights the senders.
    r.settings.knobs.sender_sky = ssdo::render::SenderSky::March;
    r.settings.knobs.indirect_strength = 0.0;
    r.apply(gpu);
    assert_eq!(
        r.plan().step_names(),
        vec!["gbuffer", "ssao_ssdo", "blur", "temporal", "composite", "skybox", "tonemap"]
    );
    r.settings.knobs.indirect_strength = 1.0;
    r.settings.knobs.sender_sky = ssdo::render::SenderSky::Off;
    // No blur: no blur pass and no blurred targets.
    r.settings.knobs.blur = false;
    r.apply(gpu);
    assert_eq!(r.plan().step_names(), vec!["gbuffer", "ssao_ssdo", "temporal", "composite", "skybox", "tonemap"]);
    assert!(!names(&r).iter().any(|n| n.ends_with("blurred")));
    // One frame: no temporal pass, no accumulated target, no history.
    r.settings.knobs.accumulate = 1;
    r.apply(gpu);
    assert_eq!(r.plan().step_names(), vec!["gbuffer", "ssao_ssdo", "composite", "skybox", "tonemap"]);
    assert!(!names(&r).iter().any(|n| n.ends_with("accumulated") || n.starts_with("history_")));
}

#[test]
fn every_buffer_is_finite_on_the_default_scene_in_every_mode_and_variant() {
    let Some(gpu) = gpu() else { return };
    let scene = Scene::new(ssdo::scene::load_model(None).unwrap(), 8, 1);
    let sky = ssdo::scene::load_skybox(None).unwrap();
    let camera = OrbitCamera::framing(&scene.model.bounds);
    for variant in Variant::ALL {
        for mode in Mode::ALL {
            let mut r = renderer(
                gpu,
                &scene,
                &sky,
                (W, H),
                Settings { mode, knobs: Knobs { variant, ..Knobs::default() }, ..Settings::default() },
            );
            for blurred in [false, true] {
                let b = render(gpu, &mut r, &camera, blurred);
                let finite = |v: &[[f32; 4]]| v.iter().all(|p| p.iter().all(|c| c.is_finite() && *c >= 0.0));
                assert!(finite(&b.hdr), "{mode} {variant}: HDR");
                if let Some(ao) = &b.ao {
                    assert!(ao.iter().all(|a| (0.0..=1.0).contains(a)), "{mode} {variant}: AO in [0, 1]");
                    assert!(ao.iter().any(|a| *a < 0.9), "{mode} {variant}: some occlusion on the default scene");
                }
                if let Some(buffer) = &b.directional {
                    assert!(finite(buffer), "{mode} {variant}: DO finite and >= 0");
                    assert!(buffer.iter().any(|p| p[0] > 0.0), "{mode} {variant}: DO not all zero");
                }
            }
            let normals = ssdo::headless::readback::read_surfaces(gpu, &r.targets().normal().texture).unwrap();
            assert!(normals.iter().all(|p| p.iter().all(|c| c.is_finite())));
        }
    }
}

#[test]
fn blur_does_not_bleed_across_silhouettes() {
    let Some(gpu) = gpu() else { return };
    // A box on an open floor: floor pixels right beside the box's silhouette (seen from above at
    // an angle the box hides floor behind it) keep the open floor's AO when blurred bilaterally.
    let v = Vec3::new;
    let mut b = MeshBuilder::default();
    let floor = b.material(Material::plain("floor", [0.8; 3]));
    let block = b.material(Material::plain("block", [0.8; 3]));
    b.floor(floor, 50.0);
    b.cuboid(block, v(-0.5, 0.0, -0.5), v(0.5, 1.5, 0.5), false);
    let model: Model = b.build("block").unwrap();
    let scene = Scene::new(model, 0, 1);
    let sky = Skybox::constant(Vec3::ONE);
    let camera = looking(v(0.0, 0.5, 0.0), 0.0, 30.0, 4.0);
    let base = settings(Mode::Ssao);
    let s = Settings { knobs: Knobs { samples: 32, ..base.knobs }, given: radius(0.3), ..base };
    let mut r = renderer(gpu, &scene, &sky, (W, H), s);
    let ao = render(gpu, &mut r, &camera, true).ao.unwrap();
    // The top face of the block is open: its AO must stay 1 up to the silhouette edge.
    let top_edge = project(&camera, v(0.0, 1.5, -0.45));
    assert!(at(&ao, top_edge) > 0.97, "block top near its back edge: {}", at(&ao, top_edge));
}

#[test]
fn kernels_stay_inside_the_unit_hemisphere() {
    use ssdo::render::kernel::{kernel, rotations};
    for variant in Variant::ALL {
        for n in [1, 16, 256] {
            let k = kernel(variant.decl().kernel, n);
            assert_eq!(k.len(), n);
            assert!(k.iter().all(|s| s.z >= 0.0 && s.length() <= 1.0 + 1e-6 && s.length() > 0.0), "{variant} {n}");
        }
        assert!(rotations(variant.decl().kernel).iter().all(|r| r[0].is_finite() && r[1].is_finite()));
    }
    // Default directions cover the hemisphere evenly: the mean cosine of a uniform hemisphere is 1/2.
    let k = kernel(Variant::Points.decl().kernel, 256);
    let mean_cos = k.iter().map(|s| s.normalize().z).sum::<f32>() / 256.0;
    assert!((mean_cos - 0.5).abs() < 0.03, "mean cos {mean_cos}");
}
