use glam::Vec3;
use ssdo::reference::{self, ReferenceScene, TraceSettings};
use ssdo::render::capture::{capture, CAPTURE_FORMAT};
use ssdo::render::readback::{read_depth, read_rgba16f};
use ssdo::render::{Mode, Renderer, Settings, View};
use ssdo::scene::{OrbitCamera, Scene, Skybox};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let scene_name = args.get(1).cloned().unwrap_or("cornell".into());
    let lights: usize = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(8);
    let black = args.get(3).is_some_and(|s| s == "black");
    let slices: usize = args.get(4).map(|s| s.parse().unwrap()).unwrap_or(2);
    let steps: usize = args.get(5).map(|s| s.parse().unwrap()).unwrap_or(12);
    let gpu = ssdo::gpu::Gpu::headless().unwrap();
    let (model, sky_path) = ssdo::report::scenes::by_name(&scene_name).unwrap();
    let sky = if black { Skybox::constant(Vec3::ZERO) } else { match sky_path { Some(p) => Skybox::load(&p).unwrap(), None => ssdo::scene::load_skybox(None).unwrap() } };
    let scene = Scene::new(model, lights, 1);
    let camera = OrbitCamera::framing(&scene.model.bounds);
    let size = (320u32, 240u32);
    let s = Settings { mode: Mode::Ssdo, view: View::DoIndirect, ambient: 0.0, slices, steps, ..Settings::default() };
    let mut r = Renderer::new(&gpu, &scene, &sky, size, CAPTURE_FORMAT, s).unwrap();
    r.keep_hdr(&gpu, true);
    capture(&gpu, &mut r, &camera).unwrap();
    let depth = read_depth(&gpu, &r.targets().depth.texture).unwrap();
    let k = 1.0 / r.pre_exposure();
    let gpu_b: Vec<Vec3> = read_rgba16f(&gpu, &r.targets().occlusion().directional.as_ref().unwrap().texture).unwrap().iter().map(|p| Vec3::new(p[0], p[1], p[2]) * k).collect();
    let bvh = ReferenceScene::new(&scene.model);
    let ts = TraceSettings { samples_per_pixel: 512, seed: 1, radius: r.radius(), sky_scale: 1.0, ambient: 0.0 };
    let truth = reference::trace(&bvh, &scene.lights, &scene.rig, &sky, &camera, size, &depth, &ts, &|| {});
    let mut img = image::RgbImage::new(size.0 * 3, size.1);
    let (mut sg, mut st) = (0.0f64, 0.0f64);
    let peak = truth.bounce.iter().map(|b| reference::luminance(*b)).fold(0.0f32, f32::max) * 0.5;
    // regions: split by GPU bounce's truth luminance quartiles
    for y in 0..size.1 { for x in 0..size.0 {
        let i = (y * size.0 + x) as usize;
        if !truth.valid[i] { continue; }
        let (g, t) = (reference::luminance(gpu_b[i]), reference::luminance(truth.bounce[i]));
        sg += g as f64; st += t as f64;
        let c = |v: f32| ((v / peak).clamp(0.0, 1.0).sqrt() * 255.0) as u8;
        img.put_pixel(x, y, image::Rgb([c(g); 3]));
        img.put_pixel(x + size.0, y, image::Rgb([c(t); 3]));
        let ratio = if t > 1e-4 { g / t } else { 1.0 };
        let rr = ((ratio - 1.0).clamp(-1.0, 1.0) * 127.0 + 128.0) as u8;
        img.put_pixel(x + 2 * size.0, y, image::Rgb([rr, 128, 255 - rr]));
    }}
    println!("{scene_name} lights {lights} black {black} {slices}x{steps}: gpu mean {:.5} truth {:.5} ratio {:.3}", sg, st, sg / st);
    img.save(format!("/tmp/diag/{scene_name}_{lights}_{black}_{slices}x{steps}.png")).unwrap();
}
