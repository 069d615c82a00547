//! Display plans: with nothing reading HDR after the frame, the G-buffer pass draws the displayed
//! sky, the composite tone-maps straight into the output (no HDR write, no skybox or tone-map
//! pass) and the light
//! cubes test depth in their shader. The image must be the one the HDR path makes, and it must
//! land at the origin it is given in a larger output (the viewer's window beside its panel).

use crate::common;

use common::{gpu, renderer, shoot};
use ssdo::headless::capture::{output_texture, CAPTURE_FORMAT};
use ssdo::headless::readback::read_texture;
use ssdo::knobs::Knobs;
use ssdo::render::{Mode, Settings, Step, Variant};
use ssdo::scene::{self, OrbitCamera, Scene};

const SIZE: (u32, u32) = (common::W, common::H);

fn default_scene() -> (Scene, scene::Skybox, OrbitCamera) {
    let scene = Scene::new(scene::load_model(None).unwrap(), 8, 1);
    let sky = scene::load_skybox(None).unwrap();
    let camera = OrbitCamera::framing(&scene.model.bounds);
    (scene, sky, camera)
}

/// Largest channel difference, and how many pixels differ by more than `tolerance`.
fn compare(a: &image::RgbaImage, b: &image::RgbaImage, tolerance: u8) -> (u8, usize) {
    let mut worst = 0;
    let mut over = 0;
    for (p, q) in a.pixels().zip(b.pixels()) {
        let d = p.0.iter().zip(q.0).map(|(x, y)| x.abs_diff(y)).max().unwrap();
        worst = worst.max(d);
        over += (d > tolerance) as usize;
    }
    (worst, over)
}

#[test]
fn display_frames_match_the_hdr_path_in_every_mode_and_variant() {
    let Some(gpu) = gpu() else { return };
    let (scene, sky, camera) = default_scene();
    let mut r = renderer(gpu, &scene, &sky, SIZE, Settings::default());
    for variant in Variant::ALL {
        for mode in Mode::ALL {
            r.settings = Settings { mode, knobs: Knobs { variant, ..Knobs::default() }, ..Settings::default() };
            r.keep_hdr(gpu, true);
            // Both frames the first of their average, so that they hold the same samples.
            r.reset_history();
            let hdr = shoot(gpu, &mut r, &camera);
            assert!(r.plan().has(Step::TONEMAP) && r.targets().hdr().is_ok());
            r.keep_hdr(gpu, false);
            r.reset_history();
            let display = shoot(gpu, &mut r, &camera);
            let plan = r.plan();
            assert!(!plan.has(Step::TONEMAP) && !plan.has(Step::SKYBOX), "{variant} {mode}: {:?}", plan.steps);
            assert_eq!(r.targets().hdr().is_ok(), plan.has(Step::LIGHTING), "{variant} {mode}: HDR only for lighting");
            // The HDR path rounds radiance to half floats before its tone map: one step of 255 at most.
            let (worst, over) = compare(&hdr, &display, 1);
            println!("{variant} {mode}: largest difference {worst}/255, {over} pixels over 1");
            assert!(worst <= 1, "{variant} {mode}: {over} pixels differ by up to {worst}/255");
            assert!(display.pixels().any(|p| p.0[0] > 40), "{variant} {mode}: the display frame is not black");
        }
    }
}

#[test]
fn display_frames_land_at_their_origin_in_a_larger_output() {
    let Some(gpu) = gpu() else { return };
    let (scene, sky, camera) = default_scene();
    let mut r = renderer(gpu, &scene, &sky, SIZE, Settings { mode: Mode::Both, ..Settings::default() });
    r.keep_hdr(gpu, false);
    let alone = shoot(gpu, &mut r, &camera);
    let origin = (37u32, 21u32);
    let big = (SIZE.0 + 60, SIZE.1 + 30);
    let texture = output_texture(gpu, big);
    let view = texture.create_view(&Default::default());
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    r.reset_history();
    r.encode(gpu, &mut encoder, &camera, ssdo::render::Canvas { view: &view, origin });
    gpu.queue.submit([encoder.finish()]);
    assert_eq!(texture.format(), CAPTURE_FORMAT);
    let bytes = read_texture(gpu, &texture).unwrap();
    let placed = image::RgbaImage::from_raw(big.0, big.1, bytes).unwrap();
    let inside = image::imageops::crop_imm(&placed, origin.0, origin.1, SIZE.0, SIZE.1).to_image();
    let (worst, over) = compare(&alone, &inside, 1);
    assert!(worst <= 1, "the image at its origin differs by up to {worst}/255 ({over} pixels over 1)");
    // Outside the image the output is cleared, not drawn over.
    assert_eq!(placed.get_pixel(0, 0).0, [0, 0, 0, 0]);
    assert_eq!(placed.get_pixel(big.0 - 1, big.1 - 1).0, [0, 0, 0, 0]);
}

#[test]
fn a_nearer_light_cube_covers_a_farther_one_in_both_paths() {
    let Some(gpu) = gpu() else { return };
    let (mut scene, sky, camera) = default_scene();
    // Two cubes on one line of sight, the far one listed last (drawn last in list order): the
    // near red one must show where they overlap, with or without a depth buffer between them.
    let eye = camera.eye();
    let towards = (camera.target - eye).normalize();
    let near = eye + towards * (0.35 * camera.distance);
    let far = eye + towards * (0.45 * camera.distance);
    let light = |position, color| scene::PointLight { position, color, intensity: 0.5 };
    scene.lights = vec![light(near, glam::Vec3::X), light(far, glam::Vec3::Y)];
    let mut r = renderer(gpu, &scene, &sky, SIZE, Settings { mode: Mode::Off, ..Settings::default() });
    let (x, y) = common::project_to(&camera, SIZE, near);
    for keep_hdr in [true, false] {
        r.keep_hdr(gpu, keep_hdr);
        let image = shoot(gpu, &mut r, &camera);
        let [red, green, _, _] = image.get_pixel(x as u32, y as u32).0;
        assert!(red > 200 && green < 60, "HDR path {keep_hdr}: the pixel is ({red}, {green}), not the near red cube");
    }
}

#[test]
fn the_sky_is_filtered_across_its_cube_faces_on_every_backend() {
    let Some(gpu) = gpu() else { return };
    // Faces of 4x4 texels, ±X red and ±Z blue (±Y green): looking level along a diagonal of the
    // XZ plane, the middle of the view is the edge between an X face and a Z face. Filtered
    // across the edge (Vulkan, OpenGL ES, desktop GL with seamless filtering on) the colour ramps
    // from red to blue over tens of pixels at this magnification; filtered face by face (desktop
    // GL's default) it steps from one to the other.
    let sky = scene::Skybox::from_fn("face colours", 4, |d| {
        let a = d.abs();
        if a.x >= a.y && a.x >= a.z {
            glam::Vec3::X
        } else if a.z >= a.y {
            glam::Vec3::Z
        } else {
            glam::Vec3::Y
        }
    });
    let scene = Scene::new(scene::builtin::plane(1.0, [0.5; 3]).unwrap(), 0, 1);
    // Far above the small plane, looking level: the view holds sky alone.
    let camera = common::looking(glam::Vec3::new(0.0, 50.0, 0.0), 45.0, 0.0, 1.0);
    let mut r = renderer(gpu, &scene, &sky, SIZE, Settings::default());
    for keep_hdr in [true, false] {
        r.keep_hdr(gpu, keep_hdr);
        let image = shoot(gpu, &mut r, &camera);
        let row: Vec<[u8; 4]> = (0..SIZE.0).map(|x| image.get_pixel(x, SIZE.1 / 3).0).collect();
        let (reds, blues) = (row.iter().filter(|p| p[0] > 200).count(), row.iter().filter(|p| p[2] > 200).count());
        let mixed = row.iter().filter(|p| p[0] > 60 && p[2] > 60).count();
        assert!(reds > 10 && blues > 10, "HDR path {keep_hdr}: the row is not split between two faces: {row:?}");
        assert!(mixed >= 8, "HDR path {keep_hdr}: {mixed} pixels blend the faces at their edge: {row:?}");
    }
}
