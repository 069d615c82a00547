//! The truth's bounce split by where its senders lie for the camera, and the sky its occluders
//! block by where they lie: a wall beside the view sends its whole bounce, and blocks all the
//! sky it blocks, from off the screen, the same wall in view from what the screen shows; a
//! fin's far face, whose light falls on the floor behind it, is the second surface on its eye
//! ray, and behind a nearer fin it is deeper.

use glam::Vec3;
use ssdo::reference::{self, ReferenceScene, SenderPlace, TraceSettings};
use ssdo::scene::{LightRig, OrbitCamera, Skybox};

const SIZE: (u32, u32) = (64, 48);

/// A black floor (it sends nothing: the wall is the only sender) and, at x = 1.5, a red wall 2
/// wide and 1.5 high facing -x.
fn floor_and_wall() -> ReferenceScene {
    let v = Vec3::new;
    let (mut b, wall) = crate::common::on_floor([0.0; 3], 10.0, "wall", [0.8, 0.1, 0.1]);
    b.quad(wall, [v(1.5, 0.0, 1.0), v(1.5, 0.0, -1.0), v(1.5, 1.5, -1.0), v(1.5, 1.5, 1.0)]);
    ReferenceScene::new(&b.build("wall").unwrap())
}

/// The shares of the truth's bounce by place, seen from `camera`, with the depth buffer the
/// truth's own first hits would give, and the shares of the sky its occluders block.
fn shares(scene: &ReferenceScene, camera: &OrbitCamera) -> ([f64; 4], [f64; 4]) {
    let (bounce, _, blocked) = placed(scene, camera);
    (bounce, blocked)
}

/// The bounce's shares, the shares of each place the first two surfaces on the senders' eye rays
/// hold, and the blocked sky's shares.
fn placed(scene: &ReferenceScene, camera: &OrbitCamera) -> ([f64; 4], [f64; 4], [f64; 4]) {
    let (w, h) = SIZE;
    let projection = camera.view_to_clip(w as f32 / h as f32);
    let world_to_clip = projection * camera.world_to_view();
    let depth: Vec<f32> = (0..w * h)
        .map(|i| {
            let (eye, dir) = crate::common::eye_ray_in(camera, SIZE, ((i % w) as usize, (i / w) as usize));
            scene.trace(eye, dir, f32::INFINITY).map_or(0.0, |s| {
                let clip = world_to_clip * s.position.extend(1.0);
                clip.z / clip.w
            })
        })
        .collect();
    let settings = TraceSettings { samples_per_pixel: 64, seed: 1, radius: 0.5, sky_scale: 1.0, ambient: 0.0 };
    let rig = LightRig { strength: 1.0, min_distance: 0.01, cube_half_size: 0.01 };
    let sky = Skybox::constant(Vec3::ONE);
    let truth = reference::trace(scene, &[], &rig, &sky, camera, SIZE, &depth, &settings, &|| {});
    assert!(truth.valid.iter().filter(|v| **v).count() > (w * h / 2) as usize, "the floor fills the view");
    let shares = truth.bounce_shares().expect("the wall bounces light onto the floor");
    let blocked = truth.blocked_shares().expect("the wall blocks sky");
    (shares, truth.two_layer_shares().expect("with its places"), blocked)
}

#[test]
fn a_wall_beside_the_view_sends_its_bounce_from_off_screen_and_in_view_from_the_screen() {
    let scene = floor_and_wall();
    let (seen, off) = (SenderPlace::Seen as usize, SenderPlace::OffScreen as usize);
    // Straight down from 2 above the origin: the view reaches x = ±0.55 on the floor and never
    // the wall, which stands at x = 1.5 lower than the eye.
    let above = OrbitCamera {
        target: Vec3::ZERO,
        yaw_deg: 0.0,
        pitch_deg: 89.0,
        distance: 2.0,
        fov_y_deg: 45.0,
        near: 0.01,
        far: None,
    };
    let (s, blocked) = shares(&scene, &above);
    eprintln!("wall beside the view: {s:?}, blocked sky {blocked:?}");
    assert!(s[off] > 0.99, "all the bounce comes from off the screen: {s:?}");
    assert!(blocked[off] > 0.99, "all the blocked sky is blocked from off the screen: {blocked:?}");
    // From the floor's open side, looking at the wall's face: what bounces is on the screen.
    let facing =
        OrbitCamera { target: Vec3::new(0.9, 0.5, 0.0), yaw_deg: -90.0, pitch_deg: 35.0, distance: 3.0, ..above };
    let (s, blocked) = shares(&scene, &facing);
    eprintln!("wall in view: {s:?}, blocked sky {blocked:?}");
    assert!(s[seen] > 0.85, "most of the bounce comes from the wall the screen shows: {s:?}");
    // The floor's receivers are blocked by the wall the screen shows; the wall's own, facing the
    // floor, by the floor out to 5 away, most of it beyond the view's edges (black: no bounce).
    assert!(blocked[seen] > 0.5 && blocked[off] > 0.1, "{blocked:?}");
    assert!((blocked.iter().sum::<f64>() - 1.0).abs() < 1e-9, "the blocked shares add up: {blocked:?}");
    // The floor seen beyond the wall's top gets its bounce from the wall's back, which faces away.
    let away = SenderPlace::FacingAway as usize;
    assert!(s[away] > 0.02 && s[SenderPlace::OffScreen as usize] == 0.0, "{s:?}");
    assert!((s.iter().sum::<f64>() - 1.0).abs() < 1e-9, "the shares add up: {s:?}");
}

/// A black floor and red closed fins 0.1 thick, 1.5 high and 2 wide, their near faces at each
/// of `xs`.
fn floor_and_fins(xs: &[f32]) -> ReferenceScene {
    let v = Vec3::new;
    let (mut b, fin) = crate::common::on_floor([0.0; 3], 10.0, "fin", [0.8, 0.1, 0.1]);
    for &x in xs {
        b.cuboid(fin, v(x, 0.0, -1.0), v(x + 0.1, 1.5, 1.0), false);
    }
    ReferenceScene::new(&b.build("fins").unwrap())
}

#[test]
fn a_fins_far_face_is_within_two_layers_and_behind_a_nearer_fin_deeper() {
    let away = SenderPlace::FacingAway as usize;
    let camera = OrbitCamera {
        target: Vec3::new(2.2, 0.3, 0.0),
        yaw_deg: -90.0,
        pitch_deg: 50.0,
        distance: 4.0,
        fov_y_deg: 45.0,
        near: 0.01,
        far: None,
    };
    // One fin: the floor behind it is lit by its far face, which the eye's ray meets second.
    let (s, layered, _) = placed(&floor_and_fins(&[1.4]), &camera);
    eprintln!("one fin: {s:?} {layered:?}");
    assert!(s[away] > 0.1, "the far face sends a good part of the bounce: {s:?}");
    assert!(layered[away] > 0.95 * s[away], "a second layer holds it: {s:?} {layered:?}");
    // A second fin in front: the far face the floor behind the first sees lies behind the
    // nearer fin's two faces where the eye looks through both.
    let (s, layered, _) = placed(&floor_and_fins(&[1.0, 1.4]), &camera);
    eprintln!("two fins: {s:?} {layered:?}");
    assert!(s[away] - layered[away] > 0.05, "part of it (over 5% of the bounce) lies deeper: {s:?} {layered:?}");
    assert!(layered.iter().zip(&s).all(|(l, s)| l <= s), "{s:?} {layered:?}");
}
