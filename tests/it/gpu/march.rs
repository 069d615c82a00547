//! The marched estimator against answers known in closed form: it sees occluders beyond the AO
//! radius (the sky fraction next to a tall wall, the bounce from a wall beyond R), and its
//! thickness keeps a thin pole from shadowing the floor behind it.

use crate::common;

use common::{gpu, looking, project, renderer, shoot, H, W};
use glam::Vec3;
use ssdo::headless::readback::read_rgba16f;
use ssdo::knobs::Knobs;
use ssdo::render::{GivenLengths, Mode, Settings, Variant, View};
use ssdo::scene::builtin::MeshBuilder;
use ssdo::scene::{Material, OrbitCamera, Scene, Skybox};

/// Mean DO (rgb) over a 3x3 window.
fn directional(
    gpu: &ssdo::gpu::Gpu,
    scene: &Scene,
    sky: &Skybox,
    camera: &OrbitCamera,
    s: Settings,
    at: &[(usize, usize)],
) -> Vec<Vec3> {
    let mut r = renderer(gpu, scene, sky, (W, H), s);
    shoot(gpu, &mut r, camera);
    let t = r.targets();
    let d = read_rgba16f(gpu, &t.occlusion().directional.unwrap().texture).unwrap();
    at.iter()
        .map(|&(x, y)| {
            let mut sum = Vec3::ZERO;
            for yy in y - 1..=y + 1 {
                for xx in x - 1..=x + 1 {
                    let p = d[yy * W as usize + xx];
                    sum += Vec3::new(p[0], p[1], p[2]);
                }
            }
            sum / 9.0
        })
        .collect()
}

fn march(radius: f32) -> Settings {
    Settings {
        mode: Mode::Ssdo,
        knobs: Knobs { variant: Variant::March, slices: 8, steps: 16, ..Knobs::default() },
        given: GivenLengths { radius: Some(radius), ..GivenLengths::default() },
        ambient: 0.0,
        ..Settings::default()
    }
}

/// A builder holding a white floor 40 wide at y = 0, and its material.
fn white_floor() -> (MeshBuilder, usize) {
    let v = Vec3::new;
    let mut b = MeshBuilder::default();
    let m = b.material(Material::plain("white", [0.8; 3]));
    b.quad(m, [v(-20.0, 0.0, 20.0), v(20.0, 0.0, 20.0), v(20.0, 0.0, -20.0), v(-20.0, 0.0, -20.0)]);
    (b, m)
}

#[test]
fn a_receiver_three_radii_from_a_tall_wall_sees_the_analytic_sky_fraction() {
    let Some(gpu) = gpu() else { return };
    let v = Vec3::new;
    let (mut b, m) = white_floor();
    // A wall in the plane z = 0, 3 high and 20 wide, facing +z.
    let (h, d, radius) = (3.0f32, 0.9f32, 0.3f32);
    b.quad(m, [v(-10.0, 0.0, 0.0), v(10.0, 0.0, 0.0), v(10.0, h, 0.0), v(-10.0, h, 0.0)]);
    let scene = Scene::new(b.build("wall").unwrap(), 0, 1);
    let sky = Skybox::constant(Vec3::ONE);
    // Far enough back that the whole wall, to its top, is on screen above the receiver.
    let camera = looking(v(0.0, 1.3, 0.0), 0.0, 12.0, 9.0);
    let receiver = project(&camera, v(0.0, 0.0, d));
    // Cosine-weighted share of the sky the wall hides from a floor point at distance d, for a
    // wall long enough to count as infinite (crossed strings): (1 − d/√(d² + h²))/2.
    let want = 1.0 - 0.5 * (1.0 - d / (d * d + h * h).sqrt());
    // The sky light alone: under a white sky the white wall also bounces light onto the floor.
    let s = march(radius);
    let s = Settings {
        given: GivenLengths { reach: Some(10.0), thickness: Some(1.0), ..s.given },
        view: View::DoDirect,
        ..s
    };
    let got = directional(gpu, &scene, &sky, &camera, s, &[receiver])[0].x;
    let points = Settings { knobs: Knobs { variant: Variant::Points, samples: 64, ..s.knobs }, ..s };
    let old = directional(gpu, &scene, &sky, &camera, points, &[receiver])[0].x;
    eprintln!("sky fraction at 3R from the wall: analytic {want:.4}, march {got:.4}, points {old:.4}");
    assert!((got - want).abs() <= 0.05 * want, "march sees {got}, the closed form {want}");
    assert!(old > want + 0.2, "the point estimator cannot see the wall beyond R ({old})");
}

#[test]
fn a_thin_pole_darkens_its_foot_but_not_the_floor_behind_it() {
    let Some(gpu) = gpu() else { return };
    let v = Vec3::new;
    let (mut b, m) = white_floor();
    b.cuboid(m, v(-0.03, 0.0, -0.03), v(0.03, 2.0, 0.03), false);
    let scene = Scene::new(b.build("pole").unwrap(), 0, 1);
    let sky = Skybox::constant(Vec3::ONE);
    // Looking from +z: the floor behind the pole is at negative z.
    let camera = looking(v(0.0, 0.6, -0.5), 0.0, 30.0, 4.0);
    let radius = 0.2;
    let foot = project(&camera, v(0.0, 0.0, 0.08));
    // The floor 6 pole widths behind it, a few pixels beside its silhouette on screen (the 3x3
    // window stays off the pole's own pixels).
    let behind = project(&camera, v(0.15, 0.0, -1.2));
    let open = project(&camera, v(1.5, 0.0, -1.2));
    // The default thickness and reach, in radii, as the renderer derives them from a scene.
    let s = march(radius);
    let given = GivenLengths {
        thickness: Some(ssdo::render::THICKNESS_RADII * radius),
        reach: Some(ssdo::render::REACH_RADII * radius),
        ..s.given
    };
    let s = Settings { given, view: View::DoDirect, ..s };
    let d = directional(gpu, &scene, &sky, &camera, s, &[foot, behind, open]);
    let (foot, behind, open) = (d[0].x, d[1].x, d[2].x);
    eprintln!("pole: foot {foot:.4}, floor behind {behind:.4}, open floor {open:.4}");
    assert!(open > 0.97, "open floor sees the sky: {open}");
    assert!(foot < 0.93 * open, "the pole's foot is darker: {foot} vs {open}");
    // In truth the pole hides 0.6% of this point's cosine-weighted sky.
    assert!(behind > 0.97 * open, "the floor behind the pole is not shadowed: {behind} vs {open}");
}

#[test]
fn a_red_wall_beyond_the_radius_still_bounces_red_onto_the_floor() {
    let Some(gpu) = gpu() else { return };
    let v = Vec3::new;
    let (scene, sky, camera) = common::red_wall_view(Vec3::ZERO);
    // R = 0.1; the floor point lies 0.4 = 4R from the wall.
    let receiver = project(&camera, v(0.4, 0.0, 0.0));
    let s = march(0.1);
    let s = Settings { given: GivenLengths { reach: Some(3.0), thickness: Some(0.3), ..s.given }, ..s };
    let bounce = directional(gpu, &scene, &sky, &camera, s, &[receiver])[0];
    let points = Settings { knobs: Knobs { variant: Variant::Points, samples: 64, ..s.knobs }, ..s };
    let old = directional(gpu, &scene, &sky, &camera, points, &[receiver])[0];
    eprintln!("bounce at 4R from a red wall: march {bounce}, points {old}");
    assert!(bounce.x > 0.01 && bounce.x > 5.0 * bounce.y, "red bounce from beyond R: {bounce}");
    assert!(old.x < 0.1 * bounce.x, "the point estimator sees no wall beyond R: {old}");
}
