//! Winding that disagrees with the normals. The supplied normals say which side is out; the
//! loader turns each triangle to agree with them, and the G-buffer turns every normal to the side
//! the camera sees, so a mesh renders the same whichever way its faces are wound.

use crate::common;

use common::{gpu, looking, renderer, shoot, H, W};
use glam::Vec3;
use ssdo::gpu::Gpu;
use ssdo::headless::readback::read_rgba16f;
use ssdo::render::{Mode, Settings, View};
use ssdo::scene::builtin::MeshBuilder;
use ssdo::scene::model::{TextureImage, Vertex};
use ssdo::scene::obj_model::load_obj;
use ssdo::scene::{Material, Model, OrbitCamera, Scene, Skybox};

/// How each triangle of the sphere is wound, seen from outside.
#[derive(Clone, Copy, Debug)]
enum Winding {
    CounterClockwise,
    Clockwise,
    /// Every other triangle clockwise.
    Mixed,
}

/// A UV sphere of radius 1 at (0, 1.2, 0) over a floor quad, with outward vertex normals,
/// written as OBJ in the given winding and loaded back.
fn sphere_obj(dir: &std::path::Path, winding: Winding) -> Model {
    let mut b = MeshBuilder::default();
    let m = b.material(Material::plain("white", [0.8; 3]));
    b.sphere(m, Vec3::new(0.0, 1.2, 0.0), 1.0, 32, 16);
    let v = Vec3::new;
    b.quad(m, [v(-3.0, 0.0, 3.0), v(3.0, 0.0, 3.0), v(3.0, 0.0, -3.0), v(-3.0, 0.0, -3.0)]);
    let model = b.build("sphere").unwrap();
    let mut obj = String::new();
    for p in &model.vertices {
        obj += &format!(
            "v {} {} {}\nvn {} {} {}\n",
            p.position[0], p.position[1], p.position[2], p.normal[0], p.normal[1], p.normal[2]
        );
    }
    for (t, tri) in model.indices.chunks_exact(3).enumerate() {
        let reverse = match winding {
            Winding::CounterClockwise => false,
            Winding::Clockwise => true,
            Winding::Mixed => t % 2 == 1,
        };
        let [a, b, c] = [tri[0] + 1, tri[1] + 1, tri[2] + 1];
        let (b, c) = if reverse { (c, b) } else { (b, c) };
        obj += &format!("f {a}//{a} {b}//{b} {c}//{c}\n");
    }
    let path = dir.join(format!("sphere_{winding:?}.obj"));
    std::fs::write(&path, obj).unwrap();
    load_obj(&path).unwrap()
}

fn redblue() -> Skybox {
    Skybox::load(std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/skyboxes/redblue"))).unwrap()
}

/// HDR of the final image and of the DO-direct view, and the AO buffer, in one mode.
fn buffers(gpu: &Gpu, scene: &Scene, sky: &Skybox, camera: &OrbitCamera, mode: Mode, view: View) -> Vec<[f32; 4]> {
    let mut settings = Settings { mode, view, ambient: 0.05, ..Settings::default() };
    settings.knobs.blur = false;
    let mut r = renderer(gpu, scene, sky, (W, H), settings);
    shoot(gpu, &mut r, camera);
    let t = r.targets();
    match view {
        View::Ao => read_rgba16f(gpu, &t.occlusion().directional.unwrap().texture).unwrap(),
        _ => read_rgba16f(gpu, &t.hdr().unwrap().texture).unwrap(),
    }
}

fn max_difference(a: &[[f32; 4]], b: &[[f32; 4]]) -> f32 {
    a.iter().zip(b).flat_map(|(p, q)| (0..4).map(move |i| (p[i] - q[i]).abs())).fold(0.0, f32::max)
}

fn mean(a: &[[f32; 4]], channel: usize) -> f32 {
    a.iter().map(|p| p[channel]).sum::<f32>() / a.len() as f32
}

#[test]
fn loader_turns_triangles_to_agree_with_their_normals() {
    let dir = tempfile::tempdir().unwrap();
    for winding in [Winding::Clockwise, Winding::Mixed] {
        let model = sphere_obj(dir.path(), winding);
        assert!(
            model.warnings.iter().any(|w| w.contains("reversed the winding")),
            "{winding:?}: the repair is reported: {:?}",
            model.warnings
        );
        for t in 0..model.triangle_count() {
            let [a, b, c] = model.triangle(t);
            let g = (b - a).cross(c - a);
            if g.length() < 1e-4 * (b - a).length_squared().max((c - a).length_squared()) {
                continue; // the poles' slivers
            }
            let i = model.indices[3 * t] as usize;
            let n = Vec3::from(model.vertices[i].normal);
            assert!(g.dot(n) > 0.0, "{winding:?}: triangle {t} still wound against its normal");
        }
    }
    let model = sphere_obj(dir.path(), Winding::CounterClockwise);
    assert!(model.warnings.iter().all(|w| !w.contains("winding")), "nothing to repair: {:?}", model.warnings);
}

#[test]
fn both_windings_render_the_same_in_every_mode() {
    let Some((gpu, dir)) = common::gpu_and_folder() else { return };
    let sky = redblue();
    let camera = looking(Vec3::new(0.0, 1.0, 0.0), 20.0, 15.0, 5.0);
    let scenes: Vec<(Winding, Scene)> = [Winding::CounterClockwise, Winding::Clockwise, Winding::Mixed]
        .into_iter()
        .map(|w| (w, Scene::new(sphere_obj(dir.path(), w), 0, 1)))
        .collect();
    let cases = [
        (Mode::Off, View::Final),
        (Mode::Ssao, View::Final),
        (Mode::Ssdo, View::DoDirect),
        (Mode::Ssdo, View::Final),
        (Mode::Both, View::Ao),
        (Mode::Both, View::Final),
    ];
    for (mode, view) in cases {
        let reference = buffers(gpu, &scenes[0].1, &sky, &camera, mode, view);
        for (winding, scene) in &scenes[1..] {
            let other = buffers(gpu, scene, &sky, &camera, mode, view);
            let d = max_difference(&reference, &other);
            eprintln!("{mode} {}: {winding:?} vs counter-clockwise, max |Δ| {d:e}", view.name());
            assert!(d < 1e-3, "{mode} {}: {winding:?} differs from counter-clockwise by {d}", view.name());
        }
    }
    // And the sphere is sky-lit, not dark: blue from above, on average, in SSDO's sky light.
    let direct = buffers(gpu, &scenes[1].1, &sky, &camera, Mode::Ssdo, View::DoDirect);
    assert!(mean(&direct, 2) > 0.02, "clockwise sphere gets sky light: mean blue {}", mean(&direct, 2));
}

#[test]
fn a_single_quad_is_lit_from_whichever_side_the_camera_sees() {
    let Some(gpu) = gpu() else { return };
    let sky_radiance = Vec3::new(0.3, 0.6, 0.9);
    let sky = Skybox::constant(sky_radiance);
    let albedo = 0.5;
    // A material that reads a map draws the faces seen from behind in a second round of the
    // G-buffer pass; a plain one draws every face in the first: both are held to ρ·L here.
    let white = TextureImage { width: 1, height: 1, rgba: std::sync::Arc::new(vec![255; 4]) };
    let textured = Material { diffuse_map: Some(white), ..Material::plain("leaf", [albedo; 3]) };
    for (reversed, material) in
        [false, true].into_iter().flat_map(|r| [(r, Material::plain("leaf", [albedo; 3])), (r, textured.clone())])
    {
        // A lone quad whose vertex normals say +Y, wound counter-clockwise seen from above
        // (agreeing) or clockwise (against them).
        let v = Vec3::new;
        let mut c = [v(-50.0, 0.0, 50.0), v(50.0, 0.0, 50.0), v(50.0, 0.0, -50.0), v(-50.0, 0.0, -50.0)];
        if reversed {
            c.reverse();
        }
        let vertex = |p: Vec3| Vertex { position: p.into(), normal: [0.0, 1.0, 0.0], uv: [0.0, 0.0] };
        let group = [0, 1, 2, 0, 2, 3].map(|k| vertex(c[k])).to_vec();
        let maps = material.is_textured();
        let model = Model::from_groups("leaf", vec![material], vec![group]).unwrap();
        let scene = Scene::new(model, 0, 1);
        // From above and from below: the open sky on the seen side lights it as ρ·L.
        for pitch in [40.0, -40.0] {
            let camera = looking(Vec3::ZERO, 30.0, pitch, 4.0);
            let mut settings = Settings { mode: Mode::Ssdo, ambient: 0.0, ..Settings::default() };
            settings.knobs.blur = false;
            let mut r = renderer(gpu, &scene, &sky, (W, H), settings);
            shoot(gpu, &mut r, &camera);
            let hdr = read_rgba16f(gpu, &r.targets().hdr().unwrap().texture).unwrap();
            let p = hdr[(H as usize / 2) * W as usize + W as usize / 2];
            let got = Vec3::new(p[0], p[1], p[2]);
            let want = albedo * sky_radiance;
            assert!(
                (got - want).abs().max_element() < 0.02 * want.max_element(),
                "reversed {reversed}, maps {maps}, pitch {pitch}: {got} != ρ·L {want}"
            );
        }
    }
}
