//! The stability suite: extreme cases in every mode and variant. Each must render without a
//! panic with every value finite, AO in [0, 1] and DO ≥ 0. The table of results is printed
//! (`cargo test --test it gpu::stability -- --nocapture`); every case is reachable from the
//! command line (the `cli` column). Every case renders the frames it averages (16 by default)
//! before it is read; accumulation also runs at 1x1 and odd sizes, turning the camera and
//! resizing mid-average.

use crate::common;

use glam::Vec3;
use ssdo::gpu::Gpu;
use ssdo::headless::capture::CAPTURE_FORMAT;
use ssdo::headless::stats::frame_stats;
use ssdo::render::{Mode, Renderer, Settings, Variant};
use ssdo::scene::{builtin, obj_model::load_obj, OrbitCamera, PointLight, Scene, Skybox};

const SIZE: (u32, u32) = (48, 36);

struct Case {
    name: &'static str,
    cli: &'static str,
    scene: Scene,
    sky: Skybox,
    camera: OrbitCamera,
    size: (u32, u32),
    settings: Settings,
}

fn base(name: &'static str, cli: &'static str) -> Case {
    let scene = Scene::new(builtin::cornell().unwrap(), 8, 1);
    let camera = OrbitCamera::framing(&scene.model.bounds);
    Case {
        name,
        cli,
        scene,
        sky: Skybox::from_fn("day", 16, builtin::day_sky),
        camera,
        size: SIZE,
        settings: Settings::default(),
    }
}

fn with_model(name: &'static str, cli: &'static str, model: ssdo::scene::Model) -> Case {
    let scene = Scene::new(model, 8, 1);
    let camera = OrbitCamera::framing(&scene.model.bounds);
    Case { scene, camera, ..base(name, cli) }
}

/// The default scene written as OBJ with extra zero-area and NaN-vertex faces, and without normals.
fn messy_obj(dir: &std::path::Path, normals: bool) -> ssdo::scene::Model {
    let model = builtin::cornell().unwrap();
    let mut obj = String::new();
    for v in &model.vertices {
        obj += &format!("v {} {} {}\n", v.position[0], v.position[1], v.position[2]);
        if normals {
            obj += &format!("vn {} {} {}\n", v.normal[0], v.normal[1], v.normal[2]);
        }
    }
    for tri in model.indices.chunks_exact(3) {
        let f: Vec<String> =
            tri.iter().map(|i| if normals { format!("{0}//{0}", i + 1) } else { format!("{}", i + 1) }).collect();
        obj += &format!("f {}\n", f.join(" "));
    }
    let n = model.vertices.len();
    obj += "v 0.5 0.5 0.5\nv 0.5 0.5 0.5\nv 1 1 1\nv nan 0 0\nv 0 inf 0\n";
    obj += &format!("f {} {} {}\nf {} {} {}\nf {} {} {}\n", n + 1, n + 2, n + 3, n + 3, n + 4, n + 5, 1, 2, n + 4);
    let name = if normals { "degenerate.obj" } else { "no_normals.obj" };
    std::fs::write(dir.join(name), obj).unwrap();
    load_obj(&dir.join(name)).unwrap()
}

/// The default scene written as OBJ with every other triangle wound against its normals.
fn rewound_obj(dir: &std::path::Path) -> ssdo::scene::Model {
    let model = builtin::cornell().unwrap();
    let mut obj = String::new();
    for v in &model.vertices {
        obj += &format!("v {} {} {}\n", v.position[0], v.position[1], v.position[2]);
        obj += &format!("vn {} {} {}\n", v.normal[0], v.normal[1], v.normal[2]);
    }
    for (t, tri) in model.indices.chunks_exact(3).enumerate() {
        let [a, b, c] = [tri[0] + 1, tri[1] + 1, tri[2] + 1];
        let (b, c) = if t % 2 == 1 { (c, b) } else { (b, c) };
        obj += &format!("f {a}//{a} {b}//{b} {c}//{c}\n");
    }
    std::fs::write(dir.join("rewound.obj"), obj).unwrap();
    load_obj(&dir.join("rewound.obj")).unwrap()
}

/// The default scene written as OBJ in coordinates f32 cannot shade as they are: `scale` times
/// its size, `offset` model radii from the origin (f64 in the file). The loader fits it.
fn placed_obj(dir: &std::path::Path, name: &str, scale: f64, offset: f64) -> ssdo::scene::Model {
    let model = builtin::cornell().unwrap();
    let shift = offset * model.bounds.radius() as f64 * scale;
    let mut obj = String::new();
    for v in &model.vertices {
        let p = v.position.map(|c| c as f64 * scale);
        obj += &format!("v {:e} {:e} {:e}\n", p[0] + shift, p[1], p[2]);
    }
    for tri in model.indices.chunks_exact(3) {
        obj += &format!("f {} {} {}\n", tri[0] + 1, tri[1] + 1, tri[2] + 1);
    }
    std::fs::write(dir.join(name), obj).unwrap();
    let fitted = load_obj(&dir.join(name)).unwrap();
    assert!(!fitted.warnings.is_empty() || (scale == 1.0 && offset < 1e3), "{name}: fitted without a word");
    fitted
}

/// The default scene with a normal map of zero, axis-aligned and straight texels at a scale of
/// 1e6 on every material, and a cutout of a quarter of each texture tile.
fn extreme_maps() -> ssdo::scene::Model {
    use ssdo::scene::model::{Cutout, NormalMap, TextureImage};
    let mut model = builtin::cornell().unwrap();
    let texels = vec![128, 128, 128, 255, 255, 0, 0, 255, 0, 0, 0, 255, 128, 128, 255, 0];
    let image = TextureImage { width: 2, height: 2, rgba: std::sync::Arc::new(texels) };
    for m in &mut model.materials {
        m.normal_map = Some(NormalMap { image: image.clone(), scale: 1e6 });
        m.cutout = Some(Cutout { mask: Some(image.clone()), factor: 1.0, cutoff: 0.5 });
    }
    model.generate_tangents(None);
    model
}

fn cases(gpu: &Gpu, dir: &std::path::Path) -> Vec<Case> {
    let mut list = Vec::new();
    let mut c = base("near 1e-6, far inf", "--near 1e-6 --far inf");
    c.camera.near = 1e-6;
    list.push(c);
    list.push(with_model("model × 1e-3", "--scale 1e-3", builtin::cornell().unwrap().scaled(1e-3)));
    list.push(with_model("model × 1e4", "--scale 1e4", builtin::cornell().unwrap().scaled(1e4)));
    let mut c = base("grazing the floor at 0.5°", "--pitch 0.5 --distance 3");
    c.camera.target = Vec3::new(0.0, 0.02, 0.0);
    c.camera.pitch_deg = 0.5;
    c.camera.distance = 3.0;
    list.push(c);
    let mut c = base("camera inside the model", "--yaw 0 --pitch 0 --distance 0.05 (target in the sphere)");
    c.camera.target = Vec3::new(-0.95, 0.38, 0.95);
    c.camera.distance = 0.05;
    c.camera.near = 1e-4;
    list.push(c);
    list.push(with_model("zero-area and NaN-vertex faces", "--model degenerate.obj", messy_obj(dir, true)));
    list.push(with_model("missing normals", "--model no_normals.obj", messy_obj(dir, false)));
    list.push(with_model("half the faces wound against their normals", "--model rewound.obj", rewound_obj(dir)));
    let mut c = base("radius 0", "--radius 0");
    c.settings.given.radius = Some(0.0);
    list.push(c);
    let mut c = base("radius 1e6", "--radius 1e6");
    c.settings.given.radius = Some(1e6);
    list.push(c);
    let mut c = base("1 sample", "--samples 1");
    c.settings.knobs.samples = 1;
    list.push(c);
    let mut c = base("256 samples", "--samples 256");
    c.settings.knobs.samples = 256;
    list.push(c);
    let mut c = base("1x1 target", "--size 1x1");
    c.size = (1, 1);
    list.push(c);
    let mut c = base("3x2 target", "--size 3x2");
    c.size = (3, 2);
    list.push(c);
    let mut c = base("depth pyramid, 37x23 (odd sizes down the chain)", "--depth-pyramid --size 37x23");
    c.size = (37, 23);
    c.settings.knobs.depth_pyramid = true;
    list.push(c);
    let mut c = base("depth pyramid, 1x1", "--depth-pyramid --size 1x1");
    c.size = (1, 1);
    c.settings.knobs.depth_pyramid = true;
    list.push(c);
    let mut c = base("far side layer, 37x23", "--far-side --size 37x23");
    c.size = (37, 23);
    c.settings.knobs.far_side = true;
    list.push(c);
    // The far sky's quarter-size cells scan blocks that run past the screen's edge.
    for (size, label, line) in [
        ((37, 23), "far side and its sky, 37x23", "--far-side --far-sky --size 37x23"),
        ((1, 1), "far side and its sky, 1x1", "--far-side --far-sky --size 1x1"),
    ] {
        let mut c = base(label, line);
        c.size = size;
        (c.settings.knobs.far_side, c.settings.knobs.far_sky) = (true, true);
        list.push(c);
    }
    let max = gpu.device.limits().max_texture_dimension_2d;
    let mut c = base("largest 2D size (width)", "--size <max>x2");
    c.size = (max, 2);
    list.push(c);
    let mut c = base("0 lights", "--lights 0");
    c.scene.relight(0, 1);
    list.push(c);
    let mut c = base("1024 lights", "--lights 1024");
    c.scene.relight(1024, 1);
    list.push(c);
    let mut c = base("light exactly on a surface", "(a light at the floor's and a wall's surface)");
    c.scene.lights = vec![
        PointLight { position: Vec3::new(0.5, 0.0, 0.5), color: Vec3::ONE, intensity: 1.0 },
        PointLight { position: Vec3::new(-2.0, 1.0, 0.0), color: Vec3::X, intensity: 1.0 },
    ];
    list.push(c);
    let mut c = base("sky of 0", "--sky-scale 0");
    c.sky = Skybox::constant(Vec3::ZERO);
    list.push(c);
    let mut c = base("sky of 1e5 (beyond half float)", "--sky-scale 1e5");
    c.sky = Skybox::constant(Vec3::splat(1e5));
    list.push(c);
    // The edges of the ranges the command line accepts (beyond them it refuses, with the range).
    list.push(with_model(
        "model × 1e-6 (the smallest scale taken)",
        "--scale 1e-6",
        builtin::cornell().unwrap().scaled(1e-6),
    ));
    list.push(with_model(
        "model × 1e6 (the largest scale taken)",
        "--scale 1e6",
        builtin::cornell().unwrap().scaled(1e6),
    ));
    let mut c = base(
        "ambient, sky and indirect strength 1e6 (the largest taken)",
        "--ambient 1e6 --sky-strength 1e6 --indirect-strength 1e6",
    );
    c.settings.ambient = 1e6;
    c.settings.sky_strength = 1e6;
    c.settings.knobs.indirect_strength = 1e6;
    list.push(c);
    // Scales and offsets in the file's own coordinates, beyond what --scale takes: scaled to a
    // unit radius or moved to the origin at load (with a warning), then like any model.
    list.push(with_model(
        "1e-20 across in its own coordinates",
        "--model tiny.obj",
        placed_obj(dir, "tiny.obj", 1e-20, 0.0),
    ));
    list.push(with_model(
        "1e12 across in its own coordinates",
        "--model huge.obj",
        placed_obj(dir, "huge.obj", 1e12, 0.0),
    ));
    list.push(with_model("1e4 radii from the origin", "--model offset.obj", placed_obj(dir, "offset.obj", 1.0, 1e4)));
    list.push(with_model(
        "1e-9 across, 1e5 radii from the origin",
        "--model tiny_far.obj",
        placed_obj(dir, "tiny_far.obj", 1e-9, 1e5),
    ));
    list.push(with_model(
        "normal maps of zero and extreme texels at scale 1e6, cut-outs",
        "(built in code)",
        extreme_maps(),
    ));
    let mut c = base("near plane at 1e-9 of the distance (the smallest taken)", "--near <1e-9 × distance>");
    c.camera.near = c.camera.distance * 1e-9;
    list.push(c);
    list
}

#[test]
fn every_extreme_case_renders_finite_in_every_mode_and_variant() {
    let Some((gpu, dir)) = common::gpu_and_folder() else { return };
    let mut failures = Vec::new();
    println!("| case | cli | mode | variant | AO min..max | DO min..max | HDR min..max | non-finite |");
    println!("|---|---|---|---|---|---|---|---|");
    for case in cases(gpu, dir.path()) {
        let mut renderer =
            Renderer::new(gpu, &case.scene, &case.sky, case.size, CAPTURE_FORMAT, case.settings).unwrap();
        renderer.keep_hdr(gpu, true);
        for variant in Variant::ALL {
            for mode in Mode::ALL {
                renderer.settings = case.settings;
                (renderer.settings.mode, renderer.settings.knobs.variant) = (mode, variant);
                let stats =
                    frame_stats(gpu, &mut renderer, &case.camera).unwrap_or_else(|e| panic!("{}: {e}", case.name));
                let find = |n: &str| stats.iter().find(|s| s.name == n);
                let range = |n: &str| find(n).map_or("—".to_string(), |s| format!("{:.3e}..{:.3e}", s.min, s.max));
                let non_finite: usize = stats.iter().map(|s| s.non_finite).sum();
                let do_min =
                    ["do_direct", "do_indirect"].iter().filter_map(|n| find(n)).map(|s| s.min).fold(0.0f32, f32::min);
                let (ao_min, ao_max) = find("ao").map_or((0.0, 1.0), |s| (s.min, s.max));
                let ok = non_finite == 0 && ao_min >= 0.0 && ao_max <= 1.0 && do_min >= 0.0;
                let do_range = match (find("do_direct"), find("do_indirect")) {
                    (Some(d), Some(i)) => format!("{:.3e}..{:.3e}", d.min.min(i.min), d.max.max(i.max)),
                    _ => "—".into(),
                };
                println!(
                    "| {} | `{}` | {} | {} | {} | {} | {} | {} |",
                    case.name,
                    case.cli,
                    mode,
                    variant,
                    range("ao"),
                    do_range,
                    range("hdr"),
                    non_finite
                );
                if !ok {
                    failures.push(format!("{} / {mode} / {variant}: {stats:?}", case.name));
                }
            }
        }
        gpu.check().unwrap_or_else(|e| panic!("{}: {e}", case.name));
    }
    assert!(failures.is_empty(), "unstable cases:\n{}", failures.join("\n"));
}

#[test]
fn sizes_beyond_the_adapter_are_a_clear_error() {
    let Some(gpu) = common::gpu() else { return };
    let max = gpu.device.limits().max_texture_dimension_2d;
    let scene = Scene::new(builtin::plane(1.0, builtin::WHITE).unwrap(), 0, 1);
    let error =
        Renderer::new(gpu, &scene, &Skybox::constant(Vec3::ONE), (max + 1, 2), CAPTURE_FORMAT, Settings::default())
            .err()
            .expect("too large");
    assert!(error.to_string().contains("exceeds") && error.exit_code() == 2, "{error}");
    let mut renderer =
        Renderer::new(gpu, &scene, &Skybox::constant(Vec3::ONE), (8, 8), CAPTURE_FORMAT, Settings::default()).unwrap();
    assert!(renderer.resize(gpu, max + 1, 8).is_err());
    assert_eq!(renderer.size(), (8, 8), "a refused resize keeps the old size");
    renderer.resize(gpu, 0, 0).unwrap();
    assert_eq!(renderer.size(), (8, 8), "0x0 (minimised) is ignored");
}

/// Every value of the frame's AO/DO (what the composite read) and HDR: finite, AO in [0, 1] and
/// DO ≥ 0, or what is wrong.
fn check_frame(gpu: &Gpu, r: &Renderer) -> Result<(), String> {
    use ssdo::headless::readback::{read_occlusion, read_rgba16f};
    let values = read_occlusion(gpu, r.targets().occlusion(), r.plan().decl.ambient_occlusion).unwrap();
    let ao = values.ao.unwrap_or_default();
    if let Some(bad) = ao.iter().find(|v| !(v.is_finite() && (0.0..=1.0).contains(*v))) {
        return Err(format!("AO {bad}"));
    }
    if let Some(d) = values.directional {
        if let Some(bad) = d.iter().find(|p| p[..3].iter().any(|v| !(v.is_finite() && *v >= 0.0))) {
            return Err(format!("DO {bad:?}"));
        }
    }
    let hdr = read_rgba16f(gpu, &r.targets().hdr().unwrap().texture).unwrap();
    match hdr.iter().find(|p| p.iter().any(|v| !v.is_finite())) {
        Some(bad) => Err(format!("HDR {bad:?}")),
        None => Ok(()),
    }
}

#[test]
fn accumulation_stays_finite_at_any_size_while_moving_and_across_a_resize() {
    let Some(gpu) = common::gpu() else { return };
    let scene = Scene::new(builtin::cornell().unwrap(), 8, 1);
    let sky = Skybox::from_fn("day", 16, builtin::day_sky);
    let camera = OrbitCamera::framing(&scene.model.bounds);
    let mut failures = Vec::new();
    for size in [(1, 1), (2, 3), (33, 17), (48, 36)] {
        let mut settings = Settings::default();
        settings.knobs.accumulate = 16;
        let mut r = Renderer::new(gpu, &scene, &sky, size, CAPTURE_FORMAT, settings).unwrap();
        r.keep_hdr(gpu, true);
        for variant in Variant::ALL {
            for mode in Mode::sampled() {
                r.settings = settings;
                (r.settings.mode, r.settings.knobs.variant) = (mode, variant);
                r.resize(gpu, size.0, size.1).unwrap();
                // Twelve frames turning 5° and tilting; half way through the window grows.
                for k in 0..12 {
                    if k == 6 {
                        r.resize(gpu, size.0 + 7, size.1 + 5).unwrap();
                    }
                    let turned = OrbitCamera {
                        yaw_deg: camera.yaw_deg + 5.0 * k as f32,
                        pitch_deg: camera.pitch_deg + 2.0 * (k % 3) as f32,
                        ..camera
                    };
                    ssdo::headless::capture::render_frames(gpu, &mut r, [turned]).unwrap();
                    if let Err(e) = check_frame(gpu, &r) {
                        failures.push(format!("{size:?} {mode} {variant} frame {k}: {e}"));
                    }
                }
                assert_eq!(r.size(), (size.0 + 7, size.1 + 5));
                assert_eq!(r.frames_accumulated(), 6, "the resize started the average anew");
            }
        }
        gpu.check().unwrap();
    }
    assert!(failures.is_empty(), "unstable accumulation:\n{}", failures.join("\n"));
}
