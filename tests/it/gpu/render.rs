//! Rendered-image tests on the software adapter, at small sizes. Each would fail if its pass
//! were wrong: the G-buffer's normals and depth, the point lights, the sky, the light cubes,
//! tone mapping and the padded readback.

use crate::common;

use common::{displayed, gpu, looking, mean_rgb, renderer, shoot, H, W};
use glam::{Vec3, Vec4Swizzles};
use ssdo::gpu::Gpu;
use ssdo::headless::capture::capture_converged;
use ssdo::headless::readback::{read_depth, read_rgba16f, read_surfaces};
use ssdo::render::{Mode, Settings, Step, UNIFORM_LIGHTS, UNROLLED_LIGHTS};
use ssdo::scene::{builtin, PointLight, Scene, Skybox};

fn no_ambient() -> Settings {
    Settings { ambient: 0.0, ..Settings::default() }
}

#[test]
fn plane_normal_and_depth_come_out_as_expected() {
    let Some(gpu) = gpu() else { return };
    let scene = Scene::new(builtin::plane(10.0, builtin::WHITE).unwrap(), 0, 1);
    let sky = Skybox::constant(Vec3::splat(0.5));
    let mut r = renderer(gpu, &scene, &sky, (W, H), Settings::default());
    let camera = looking(Vec3::ZERO, 20.0, 30.0, 4.0);
    shoot(gpu, &mut r, &camera);
    let normals = read_surfaces(gpu, &r.targets().normal().texture).unwrap();
    let expected = (camera.world_to_view() * Vec3::Y.extend(0.0)).xyz();
    let centre = normals[60 * 160 + 80];
    assert!((Vec3::new(centre[0], centre[1], centre[2]) - expected).length() < 2e-3, "{centre:?} vs {expected}");
    assert!((centre[3] - 32.0).abs() < 0.04 * 32.0, "shininess travels with the normal: {}", centre[3]);
    let depth = read_depth(gpu, &r.targets().depth().texture).unwrap();
    // Reverse-Z, infinite far: depth = near / (distance along the view axis). Intersect the ray
    // through the centre of pixel (80, 60) with the plane y = 0.
    let p = camera.view_to_clip(160.0 / 120.0);
    let ndc = (80.5 / 160.0 * 2.0 - 1.0, 1.0 - 60.5 / 120.0 * 2.0);
    let view_dir = Vec3::new(ndc.0 / p.x_axis.x, ndc.1 / p.y_axis.y, -1.0);
    let world_dir = (camera.world_to_view().inverse() * view_dir.extend(0.0)).xyz();
    let t = -camera.eye().y / world_dir.y;
    let d = depth[60 * 160 + 80];
    assert!((d - camera.near / t).abs() < 1e-4 * d, "centre depth {d} vs {}", camera.near / t);
}

#[test]
fn readback_is_correct_at_an_odd_size() {
    let Some(gpu) = gpu() else { return };
    // A level camera over an endless floor: the horizon is one straight row. A wrong row pitch
    // in the readback shears it.
    let scene = Scene::new(builtin::plane(1e4, builtin::WHITE).unwrap(), 0, 1);
    let sky = Skybox::constant(Vec3::new(0.2, 0.4, 0.8));
    let mut r = renderer(gpu, &scene, &sky, (161, 97), Settings::default());
    let camera = looking(Vec3::new(0.0, 1.0, 0.0), 0.0, 0.0, 1.0);
    let image = shoot(gpu, &mut r, &camera);
    assert_eq!(image.dimensions(), (161, 97));
    let depth = read_depth(gpu, &r.targets().depth().texture).unwrap();
    assert_eq!(depth.len(), 161 * 97);
    let horizon = |x: usize| (0..97).find(|&y| depth[y * 161 + x] > 0.0).expect("floor visible");
    let first = horizon(0);
    assert!((40..=56).contains(&first), "horizon near the middle, got row {first}");
    for x in [1, 80, 159, 160] {
        assert_eq!(horizon(x), first, "column {x}");
    }
    let sky_pixel = image.get_pixel(100, 5).0;
    assert!(sky_pixel[2] > sky_pixel[0] + 40, "sky above the horizon: {sky_pixel:?}");
    let floor_pixel = image.get_pixel(100, 90).0;
    assert_ne!(floor_pixel, sky_pixel);
}

#[test]
fn background_shows_the_sky_through_tone_mapping() {
    let Some(gpu) = gpu() else { return };
    let radiance = Vec3::new(0.1, 0.3, 0.9);
    let scene = Scene::new(builtin::plane(1.0, builtin::WHITE).unwrap(), 0, 1);
    let sky = Skybox::constant(radiance);
    let mut r = renderer(gpu, &scene, &sky, (W, H), Settings::default());
    // Looking up: only sky in view.
    let image = shoot(gpu, &mut r, &looking(Vec3::new(0.0, 5.0, 0.0), 0.0, -80.0, 1.0));
    let got = mean_rgb(&image, 10, 10, 140, 100);
    let want = Vec3::new(displayed(radiance.x), displayed(radiance.y), displayed(radiance.z));
    assert!((got - want).abs().max_element() < 2.5, "sky {got} vs {want}");
    // sky_scale multiplies it.
    r.settings.sky_scale = 0.5;
    let half = mean_rgb(&shoot(gpu, &mut r, &looking(Vec3::new(0.0, 5.0, 0.0), 0.0, -80.0, 1.0)), 10, 10, 140, 100);
    assert!((half.z - displayed(0.45)).abs() < 2.5, "{half}");
}

#[test]
fn floor_under_a_red_light_is_redder_than_elsewhere() {
    let Some(gpu) = gpu() else { return };
    let mut scene = Scene::new(builtin::plane(2.0, builtin::WHITE).unwrap(), 0, 1);
    let intensity = 1.0;
    scene.lights = vec![PointLight { position: Vec3::new(-1.0, 0.3, 0.0), color: Vec3::new(1.0, 0.0, 0.0), intensity }];
    let sky = Skybox::constant(Vec3::ZERO);
    let mut r = renderer(gpu, &scene, &sky, (W, H), Settings { ambient: 0.2, ..Settings::default() });
    assert!(r.plan().has(Step::LIGHT_CUBES));
    // Straight down on the plane: x maps to columns, the light sits left of centre.
    let camera = looking(Vec3::ZERO, 0.0, 89.9, 5.0);
    let image = shoot(gpu, &mut r, &camera);
    let project = |p: Vec3| {
        let clip = camera.view_to_clip(160.0 / 120.0) * camera.world_to_view() * p.extend(1.0);
        ((clip.x / clip.w * 0.5 + 0.5) * 160.0, (0.5 - clip.y / clip.w * 0.5) * 120.0)
    };
    // Just beside the light (the cube covers the point straight below it).
    let (x, y) = project(Vec3::new(-1.0, 0.0, 0.25));
    let under = mean_rgb(&image, x as u32 - 1, y as u32 - 1, 3, 3);
    let (fx, fy) = project(Vec3::new(1.5, 0.0, 0.0));
    let far = mean_rgb(&image, fx as u32 - 1, fy as u32 - 1, 3, 3);
    assert!(under.x > under.y + 40.0, "red near the light: {under}");
    assert!(under.x > far.x + 40.0, "redder than far away: {under} vs {far}");
    assert!((far.x - far.y).abs() < 12.0, "grey far from it: {far}");
    // Irradiance falls as 1/d²: check the HDR value straight against the formula.
    let hdr = read_rgba16f(gpu, &r.targets().hdr().unwrap().texture).unwrap();
    let (hx, hy) = project(Vec3::new(1.5, 0.0, 0.0));
    let got = hdr[hy as usize * 160 + hx as usize][0];
    let to_light = Vec3::new(-1.0, 0.3, 0.0) - Vec3::new(1.5, 0.0, 0.0);
    let cos = 0.3 / to_light.length();
    let want = 0.2 * 0.75 + 0.75 / std::f32::consts::PI * intensity * cos / to_light.length_squared();
    assert!((got - want).abs() < 0.03 * want, "HDR red {got} vs {want}");
}

#[test]
fn a_light_loop_built_for_its_count_lights_as_one_that_reads_the_count() {
    let Some(gpu) = gpu() else { return };
    // Coloured lights over a floor, then the same with lights under it, which face the floor's
    // back and add nothing: up to UNROLLED_LIGHTS the pipelines are built for the count, past it
    // the loop reads the frame's; up to UNIFORM_LIGHTS the lights are read from the frame
    // uniforms' copy, past it from the storage array; a loop built for one light takes it from
    // the full-screen triangle's varyings. A loop built for a wrong count drops or repeats a
    // light, a copy out of step with the array lights the floor differently.
    let above = [
        (Vec3::new(-1.0, 0.4, 0.0), Vec3::X),
        (Vec3::new(0.8, 0.5, 0.6), Vec3::Y),
        (Vec3::new(0.3, 0.6, -0.9), Vec3::Z),
    ];
    let three = [
        (0, 3, true),
        (UNROLLED_LIGHTS - 3, UNROLLED_LIGHTS as u32, true),
        (UNROLLED_LIGHTS - 2, 0, true),
        (UNIFORM_LIGHTS - 3, 0, true),
        (UNIFORM_LIGHTS - 2, 0, false),
    ];
    // (The first case of each list is the one the others are held to.)
    let one = [(0, 1, true), (2, 3, true), (UNIFORM_LIGHTS - 1, 0, true), (UNIFORM_LIGHTS, 0, false)];
    lit_alike_by_every_loop(gpu, &above, &three);
    lit_alike_by_every_loop(gpu, &above[..1], &one);
}

/// Renders the floor under `lit` plus each case's count of lights under it (hidden), in Off and
/// SSDO, checks the plan's light loop is the case's (unrolled count, uniform reads), and that
/// every case's HDR image is the first's.
fn lit_alike_by_every_loop(gpu: &Gpu, lit: &[(Vec3, Vec3)], cases: &[(usize, u32, bool)]) {
    let lights = |under: usize| {
        let lit = lit.iter().map(|&(position, color)| PointLight { position, color, intensity: 0.5 });
        // On a grid under the floor's middle, so their cubes stay hidden too.
        let hidden = (0..under).map(|i| PointLight {
            position: Vec3::new((i % 16) as f32 / 16.0 - 0.5, -0.5, (i / 16) as f32 / 16.0 - 0.5),
            color: Vec3::ONE,
            intensity: 2.0,
        });
        lit.chain(hidden).collect::<Vec<_>>()
    };
    let camera = looking(Vec3::ZERO, 0.0, 89.9, 5.0);
    let sky = Skybox::constant(Vec3::splat(0.1));
    for mode in [Mode::Off, Mode::Ssdo] {
        let mut images = Vec::new();
        for &(under, unrolled, uniform) in cases {
            let mut scene = Scene::new(builtin::plane(2.0, builtin::WHITE).unwrap(), 0, 1);
            scene.lights = lights(under);
            let mut r = renderer(gpu, &scene, &sky, (W, H), Settings { mode, ..no_ambient() });
            assert_eq!(r.plan().unrolled_lights(), unrolled, "{mode:?} with {} lights", scene.lights.len());
            assert_eq!(r.plan().uniform_lights(), uniform, "{mode:?} with {} lights", scene.lights.len());
            shoot(gpu, &mut r, &camera);
            // The HDR target holds radiance × the pre-exposure, which counts every light.
            let unexpose = 1.0 / r.pre_exposure();
            let hdr = read_rgba16f(gpu, &r.targets().hdr().unwrap().texture).unwrap();
            images.push(hdr.iter().map(|p| p.map(|c| c * unexpose)).collect::<Vec<_>>());
        }
        let reds = images[0].iter().filter(|p| p[0] > 2.0 * p[1] + 0.05).count();
        assert!(reds > 100, "{mode:?}: the red light lights the floor ({reds} pixels)");
        for (i, image) in images.iter().enumerate().skip(1) {
            let worst = image
                .iter()
                .zip(&images[0])
                .map(|(a, b)| (0..3).map(|c| (a[c] - b[c]).abs() / (b[c].abs() + 0.01)).fold(0.0, f32::max));
            let worst = worst.fold(0.0, f32::max);
            assert!(worst < 4e-3, "{mode:?}, {} lit: image {i} differs from the first's by {worst}", lit.len());
        }
    }
}

#[test]
fn light_cubes_show_their_colour_and_leave_with_the_lights() {
    let Some(gpu) = gpu() else { return };
    let mut scene = Scene::new(builtin::plane(2.0, builtin::WHITE).unwrap(), 0, 1);
    scene.rig.cube_half_size = 0.2;
    scene.lights =
        vec![PointLight { position: Vec3::new(0.0, 1.0, 0.0), color: Vec3::new(0.0, 1.0, 0.0), intensity: 0.01 }];
    let sky = Skybox::constant(Vec3::ZERO);
    let mut r = renderer(gpu, &scene, &sky, (W, H), no_ambient());
    let camera = looking(Vec3::ZERO, 0.0, 89.9, 5.0);
    let image = shoot(gpu, &mut r, &camera);
    let centre = mean_rgb(&image, 78, 58, 4, 4);
    assert!(centre.y > 200.0 && centre.x < 30.0, "green cube in the middle: {centre}");

    r.set_lights(gpu, Vec::new());
    assert!(!r.plan().has(Step::LIGHT_CUBES), "no lights, no cube pass");
    let image = shoot(gpu, &mut r, &camera);
    assert!(mean_rgb(&image, 78, 58, 4, 4).max_element() < 3.0, "nothing lights the floor now");
}

#[test]
fn default_scene_renders_finite_with_every_part_visible() {
    let Some(gpu) = gpu() else { return };
    let model = ssdo::scene::load_model(None).unwrap();
    let scene = Scene::new(model, 8, 1);
    let sky = ssdo::scene::load_skybox(None).unwrap();
    let mut r = renderer(gpu, &scene, &sky, (W, H), Settings::default());
    let camera = ssdo::scene::OrbitCamera::framing(&scene.model.bounds);
    let image = shoot(gpu, &mut r, &camera);
    let hdr = read_rgba16f(gpu, &r.targets().hdr().unwrap().texture).unwrap();
    assert!(hdr.iter().all(|p| p.iter().all(|c| c.is_finite() && *c >= 0.0)), "HDR finite and non-negative");
    // Clearly red and clearly blue (the sky's light pales both walls a little).
    let (r8, g8, b8) =
        (|p: &image::Rgba<u8>| p[0] as i32, |p: &image::Rgba<u8>| p[1] as i32, |p: &image::Rgba<u8>| p[2] as i32);
    let red = image.pixels().filter(|p| r8(p) > 120 && r8(p) > g8(p) + 60 && r8(p) > b8(p) + 60).count();
    let blue = image.pixels().filter(|p| b8(p) > 120 && b8(p) > r8(p) + 60 && b8(p) > g8(p) + 40).count();
    assert!(red > 500 && blue > 500, "both walls visible: red {red}, blue {blue}");
    let depth = read_depth(gpu, &r.targets().depth().texture).unwrap();
    let background = depth.iter().filter(|d| **d == 0.0).count();
    assert!(background > 1000, "sky visible around the room: {background}");
}

#[test]
fn textured_model_renders_its_texture() {
    let Some((gpu, dir)) = common::gpu_and_folder() else { return };
    // Top row red, blue; bottom row green, white. OBJ's v = 1 is the top of the image.
    let mut img = image::RgbImage::new(2, 2);
    img.put_pixel(0, 0, image::Rgb([255, 0, 0]));
    img.put_pixel(1, 0, image::Rgb([0, 0, 255]));
    img.put_pixel(0, 1, image::Rgb([0, 255, 0]));
    img.put_pixel(1, 1, image::Rgb([255, 255, 255]));
    img.save(dir.path().join("lr.png")).unwrap();
    std::fs::write(dir.path().join("m.mtl"), "newmtl t\nKd 1 1 1\nmap_Kd lr.png\n").unwrap();
    std::fs::write(
        dir.path().join("m.obj"),
        "mtllib m.mtl\nv -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 1 0\nusemtl t\nf 1/1/1 2/2/1 3/3/1 4/4/1\n",
    )
    .unwrap();
    let model = ssdo::scene::obj_model::load_obj(&dir.path().join("m.obj")).unwrap();
    let scene = Scene::new(model, 0, 1);
    let mut r =
        renderer(gpu, &scene, &Skybox::constant(Vec3::ZERO), (W, H), Settings { ambient: 1.0, ..Settings::default() });
    // Looking down with -Z up on screen: texel centres (u, v = 0.25, 0.75) land 24 px from the
    // middle of the 160x120 view.
    let image = shoot(gpu, &mut r, &looking(Vec3::ZERO, 0.0, 89.9, 3.0));
    let at = |x: u32, y: u32| mean_rgb(&image, x - 1, y - 1, 3, 3);
    let (top_left, top_right, bottom_left, bottom_right) = (at(56, 36), at(104, 36), at(56, 84), at(104, 84));
    assert!(top_left.x > 150.0 && top_left.y < 60.0 && top_left.z < 60.0, "top left red: {top_left}");
    assert!(top_right.z > 150.0 && top_right.x < 60.0, "top right blue: {top_right}");
    assert!(bottom_left.y > 150.0 && bottom_left.x < 60.0, "bottom left green: {bottom_left}");
    assert!(bottom_right.min_element() > 150.0, "bottom right white: {bottom_right}");
}

#[test]
fn the_specular_map_reaches_the_gbuffer_in_its_own_texture_or_in_the_diffuse_maps_alpha() {
    use ssdo::scene::model::{Material, TextureImage};
    let Some(gpu) = gpu() else { return };
    let image = |size: u32, texel: [u8; 4]| TextureImage {
        width: size,
        height: size,
        rgba: std::sync::Arc::new(texel.repeat((size * size) as usize)),
    };
    let with = |diffuse: Option<TextureImage>, specular: Option<TextureImage>| Material {
        specular: [0.5; 3],
        diffuse_map: diffuse,
        specular_map: specular,
        ..Material::plain("m", [1.0; 3])
    };
    // Diffuse maps with an alpha of 0, which is not a specular strength: it must not be read as one.
    let colour = [200, 100, 50, 0];
    let cases = [
        // Two maps of one size: packed into one texture. Strength 0.5 × 0.2.
        (with(Some(image(4, colour)), Some(image(4, [51, 0, 0, 255]))), 0.1),
        // Two sizes: the specular map keeps its own texture. 0.5 × 0.8.
        (with(Some(image(4, colour)), Some(image(2, [204, 0, 0, 255]))), 0.4),
        // A specular map alone. 0.5 × 1.
        (with(None, Some(image(4, [255, 0, 0, 255]))), 0.5),
        // A diffuse map alone: the material's strength, whatever the map's alpha.
        (with(Some(image(4, colour)), None), 0.5),
    ];
    let mut b = builtin::MeshBuilder::default();
    for (i, (material, _)) in cases.iter().enumerate() {
        let m = b.material(material.clone());
        let x = i as f32 - 2.0;
        let v = |x: f32, z: f32| Vec3::new(x, 0.0, z);
        b.quad(m, [v(x, 0.5), v(x + 1.0, 0.5), v(x + 1.0, -0.5), v(x, -0.5)]);
    }
    let scene = Scene::new(b.build("maps").unwrap(), 0, 1);
    let mut r = renderer(gpu, &scene, &Skybox::constant(Vec3::ZERO), (W, H), no_ambient());
    let camera = looking(Vec3::ZERO, 0.0, 89.9, 4.0);
    shoot(gpu, &mut r, &camera);
    let albedo = ssdo::headless::readback::read_texture(gpu, &r.targets().albedo().texture).unwrap();
    for (i, (material, strength)) in cases.iter().enumerate() {
        let (x, y) = common::project(&camera, Vec3::new(i as f32 - 1.5, 0.0, 0.0));
        let texel = &albedo[4 * (y * W as usize + x)..][..4];
        let got = texel[3] as f32 / 255.0;
        assert!((got - strength).abs() < 1.5 / 255.0, "case {i}: specular strength {got}, want {strength}");
        if material.diffuse_map.is_some() {
            let off = (0..3).map(|c| (texel[c] as i32 - colour[c] as i32).abs()).max().unwrap();
            assert!(off <= 1, "case {i}: the diffuse colour {:?} as the map has it, {:?}", &texel[..3], &colour[..3]);
        }
    }
}

#[test]
fn a_presets_lengths_follow_the_model_they_are_used_on() {
    let Some(gpu) = gpu() else { return };
    // Ultra's radius is twice the scene's default; the thickness a third of it, the reach half.
    let knobs =
        ssdo::knobs::Knobs { thickness_scale: 1.0 / 3.0, reach_scale: 0.5, ..ssdo::preset::Quality::Ultra.knobs() };
    let settings = Settings { mode: Mode::Ssdo, ..Settings::default() }.with_knobs(knobs);
    let sky = Skybox::constant(Vec3::ONE);
    let room = Scene::new(builtin::cornell().unwrap(), 2, 1);
    let plane = Scene::new(builtin::plane(40.0, [0.5; 3]).unwrap(), 2, 1);
    let mut r = renderer(gpu, &room, &sky, (W, H), settings);
    let want = |scene: &Scene| {
        let radius = scene.default_radius();
        let reach = ssdo::render::REACH_RADII * radius * knobs.reach_scale;
        (radius * 2.0, ssdo::render::THICKNESS_RADII * radius * knobs.thickness_scale, reach)
    };
    let lengths = r.lengths();
    assert_eq!((lengths.radius, lengths.thickness, lengths.reach), want(&room));
    // A model dropped in: the same knobs, this model's lengths, and the image a renderer made
    // for it from the start draws.
    r.set_scene(gpu, &plane);
    let lengths = r.lengths();
    assert_eq!((lengths.radius, lengths.thickness, lengths.reach), want(&plane));
    assert_ne!(want(&plane), want(&room));
    let camera = looking(Vec3::ZERO, 10.0, 40.0, 3.0);
    let dropped = ssdo::headless::capture::capture_settled(gpu, &mut r, &camera).unwrap();
    let fresh =
        ssdo::headless::capture::capture_settled(gpu, &mut renderer(gpu, &plane, &sky, (W, H), settings), &camera)
            .unwrap();
    assert!(dropped == fresh, "the dropped model draws other than a renderer made for it");
}

#[test]
fn a_mode_switched_back_to_draws_what_a_renderer_made_in_it_draws() {
    // A pass keeps the pipelines of its last keys: SSDO after SSAO and the points variant takes
    // its pipelines back, passes the plans in between left out included (the lighting pass), and
    // must draw what a renderer built in SSDO draws, to the byte.
    let Some(gpu) = gpu() else { return };
    let scene = Scene::new(builtin::cornell().unwrap(), 8, 1);
    let sky = Skybox::from_fn("day", 16, builtin::day_sky);
    let camera = ssdo::scene::OrbitCamera::framing(&scene.model.bounds);
    let ssdo = Settings { mode: Mode::Ssdo, ..Settings::default() };
    let fresh = capture_converged(gpu, &mut renderer(gpu, &scene, &sky, (W, H), ssdo), &camera).unwrap();
    let mut r = renderer(gpu, &scene, &sky, (W, H), ssdo);
    let first = capture_converged(gpu, &mut r, &camera).unwrap();
    r.settings.mode = Mode::Ssao;
    capture_converged(gpu, &mut r, &camera).unwrap();
    assert!(!r.plan().has(Step::LIGHTING), "SSAO leaves the lighting pass out");
    r.settings.knobs.variant = ssdo::render::Variant::Points;
    capture_converged(gpu, &mut r, &camera).unwrap();
    r.settings = ssdo;
    let back = capture_converged(gpu, &mut r, &camera).unwrap();
    assert!(first == fresh && back == fresh, "SSDO drawn again after SSAO differs from a fresh renderer's");
}
