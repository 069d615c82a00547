//! Shared helpers for the tests that render on a GPU adapter (lavapipe in CI).

#![allow(dead_code)]

use glam::{Vec3, Vec4Swizzles};
use ssdo::gpu::{Gpu, NO_ADAPTER_HELP};
use ssdo::headless::capture::{capture, CAPTURE_FORMAT};
use ssdo::render::{Renderer, Settings};
use ssdo::scene::builtin::MeshBuilder;
use ssdo::scene::{Material, OrbitCamera, PointLight, Scene, Skybox};

/// The process's headless device, or `None` (test skipped) when there is no adapter outside CI.
/// Under `CI=true` a missing adapter fails the test with the install hint.
///
/// One device serves every test of the process: the adapter is probed once, and lavapipe is
/// never asked to open devices from several threads at once. Sharing is safe with the error
/// checks because no test provokes a GPU error on purpose (sizes beyond the adapter are refused
/// before anything reaches wgpu): any error in the shared log is a failure, though
/// [`Gpu::check`] may report it from the test that looks next rather than the one that caused
/// it. Two tests keep the old isolation by living in their own processes (tests/memory.rs and
/// tests/resources.rs).
pub fn gpu() -> Option<&'static Gpu> {
    static GPU: std::sync::OnceLock<Option<Gpu>> = std::sync::OnceLock::new();
    GPU.get_or_init(|| match Gpu::headless() {
        Ok(gpu) => Some(gpu),
        Err(e) if std::env::var("CI").is_ok_and(|v| v == "true") => panic!("{e}\n{NO_ADAPTER_HELP}"),
        Err(e) => {
            eprintln!("skipping: {e}");
            None
        }
    })
    .as_ref()
}

/// The size the rendering tests draw at: small enough for a CPU rasteriser.
pub const W: u32 = 160;
pub const H: u32 = 120;

/// Pixel coordinates of world point `p` in a test-sized image from `camera`.
pub fn project(camera: &OrbitCamera, p: Vec3) -> (usize, usize) {
    project_to(camera, (W, H), p)
}

/// The white-furnace set-up: an open plane of albedo `ALBEDO` under a constant sky of
/// `radiance`, seen from above; every receiver should return albedo × sky.
pub struct Furnace {
    pub scene: Scene,
    pub sky: Skybox,
    pub radiance: Vec3,
    pub camera: OrbitCamera,
}

impl Furnace {
    pub const ALBEDO: f32 = 0.5;
    /// Pixels of a test-sized image that see the plane: the centre and two lower corners.
    pub const PIXELS: [(usize, usize); 3] = [(80, 60), (20, 100), (140, 100)];

    pub fn new() -> Self {
        let radiance = Vec3::new(0.3, 0.6, 0.9);
        Self {
            scene: Scene::new(ssdo::scene::builtin::plane(100.0, [Self::ALBEDO; 3]).unwrap(), 0, 1),
            sky: Skybox::constant(radiance),
            radiance,
            camera: looking(Vec3::ZERO, 10.0, 40.0, 3.0),
        }
    }
}

pub fn renderer(gpu: &Gpu, scene: &Scene, sky: &Skybox, size: (u32, u32), settings: Settings) -> Renderer {
    let mut r = Renderer::new(gpu, scene, sky, size, CAPTURE_FORMAT, settings).expect("renderer builds");
    // The tests read the linear HDR image back.
    r.keep_hdr(gpu, true);
    r
}

pub fn shoot(gpu: &Gpu, renderer: &mut Renderer, camera: &OrbitCamera) -> image::RgbaImage {
    capture(gpu, renderer, camera).expect("capture succeeds")
}

/// A camera at `eye` looking at `target`, expressed as an orbit.
pub fn looking(target: Vec3, yaw_deg: f32, pitch_deg: f32, distance: f32) -> OrbitCamera {
    OrbitCamera { target, yaw_deg, pitch_deg, distance, fov_y_deg: 45.0, near: distance * 1e-3, far: None }
}

/// The displayed value of linear radiance `x` (exposure 1): ACES fit, then sRGB, 0-255.
pub fn displayed(x: f32) -> f32 {
    let y = ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0);
    let s = if y <= 0.0031308 { 12.92 * y } else { 1.055 * y.powf(1.0 / 2.4) - 0.055 };
    s * 255.0
}

/// Mean RGB (0-255) of a rectangle of an image.
pub fn mean_rgb(image: &image::RgbaImage, x0: u32, y0: u32, w: u32, h: u32) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for y in y0..y0 + h {
        for x in x0..x0 + w {
            let p = image.get_pixel(x, y).0;
            sum += Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32);
        }
    }
    sum / (w * h) as f32
}

/// Mean rgb over the (2r+1)² window around `(x, y)` of a test-sized, row-major buffer.
pub fn window_mean(buffer: &[[f32; 4]], (x, y): (usize, usize), r: usize) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for yy in y - r..=y + r {
        for xx in x - r..=x + r {
            let p = buffer[yy * W as usize + xx];
            sum += Vec3::new(p[0], p[1], p[2]);
        }
    }
    sum / ((2 * r + 1) * (2 * r + 1)) as f32
}

/// Pixel coordinates of world point `p` in a `size` image from `camera`; it must lie well inside.
pub fn project_to(camera: &OrbitCamera, size: (u32, u32), p: Vec3) -> (usize, usize) {
    let (w, h) = (size.0 as f32, size.1 as f32);
    let clip = camera.view_to_clip(w / h) * camera.world_to_view() * p.extend(1.0);
    let ndc = clip.xy() / clip.w;
    assert!(clip.w > 0.0 && ndc.abs().max_element() < 0.95, "{p} is not well inside the view");
    (((ndc.x * 0.5 + 0.5) * w) as usize, ((0.5 - ndc.y * 0.5) * h) as usize)
}

/// A builder holding a square floor of `floor`'s albedo (`half` either way from the origin) and
/// a second material, `name` of `albedo`, for what stands on it; the second's index.
pub fn on_floor(floor: [f32; 3], half: f32, name: &str, albedo: [f32; 3]) -> (MeshBuilder, usize) {
    let mut b = MeshBuilder::default();
    let floor = b.material(Material::plain("floor", floor));
    let other = b.material(Material::plain(name, albedo));
    b.floor(floor, half);
    (b, other)
}

/// A white floor beside a red wall (the plane x = 0) lit by one white light, under a constant sky
/// of `sky`, and a camera facing the wall (their corner a horizontal line across the middle of
/// the view): the colour-bleeding scene.
pub fn red_wall_view(sky: Vec3) -> (Scene, Skybox, OrbitCamera) {
    let v = Vec3::new;
    let mut b = MeshBuilder::default();
    let floor = b.material(Material::plain("floor", [0.8; 3]));
    let wall = b.material(Material::plain("wall", [0.9, 0.05, 0.05]));
    b.quad(floor, [v(0.0, 0.0, 2.0), v(4.0, 0.0, 2.0), v(4.0, 0.0, -2.0), v(0.0, 0.0, -2.0)]);
    b.quad(wall, [v(0.0, 0.0, -2.0), v(0.0, 0.0, 2.0), v(0.0, 2.0, 2.0), v(0.0, 2.0, -2.0)]);
    let mut scene = Scene::new(b.build("red_wall").unwrap(), 0, 1);
    scene.lights = vec![PointLight { position: v(1.2, 1.0, 0.0), color: Vec3::ONE, intensity: 2.0 }];
    (scene, Skybox::constant(sky), looking(v(1.0, 0.3, 0.0), 90.0, 35.0, 3.5))
}

/// Runs the `ssdo` binary from the repository root with `args`, on the backend the test run asks
/// for (`WGPU_BACKEND`, Vulkan by default).
pub fn run_ssdo(args: &[&str]) -> std::process::Output {
    run_ssdo_in(std::path::Path::new(env!("CARGO_MANIFEST_DIR")), args)
}

/// [`run_ssdo`] from the folder `dir`.
pub fn run_ssdo_in(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_ssdo"))
        .args(args)
        .current_dir(dir)
        .env("WGPU_BACKEND", std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "vulkan".into()))
        .output()
        .expect("the binary runs")
}

/// What the binary wrote to standard error.
pub fn stderr(output: &std::process::Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// The binary's `ssdo: error:` line (empty when there is none).
pub fn error_line(output: &std::process::Output) -> String {
    stderr(output).lines().find(|l| l.starts_with("ssdo: error:")).unwrap_or_default().to_owned()
}

/// Runs the binary with `args`, which must exit with `code` and an error line containing
/// `needle`; returns that line.
pub fn refused(args: &[&str], code: i32, needle: &str) -> String {
    let result = run_ssdo(args);
    assert_eq!(result.status.code(), Some(code), "{args:?}: {}", stderr(&result));
    let line = error_line(&result);
    assert!(line.contains(needle), "{args:?}: {}", stderr(&result));
    line
}

/// The process's device and a temporary folder, or `None` (the test skipped) as [`gpu`] says.
pub fn gpu_and_folder() -> Option<(&'static Gpu, tempfile::TempDir)> {
    gpu().map(|gpu| (gpu, tempfile::tempdir().unwrap()))
}

/// The names of the files in `dir`, sorted.
pub fn file_names(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> =
        std::fs::read_dir(dir).unwrap().flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    names
}

/// A temporary folder for a test that renders with the binary, or `None` (the test skipped) where
/// there is no adapter; under `CI=true` a missing one fails the test with the install hint.
pub fn folder_if_adapter() -> Option<tempfile::TempDir> {
    has_adapter().then(|| tempfile::tempdir().unwrap())
}

/// Whether there is an adapter to render on (the binary opens its own); under `CI=true` a
/// missing one fails the test with the install hint.
pub fn has_adapter() -> bool {
    gpu().is_some()
}

/// A unit quad on y = 0 facing up (u along +x, v along +z): its positions, normals and UVs, then
/// `extra` (more vertex data, such as tangents), then its 16-bit indices.
pub fn quad_bytes(extra: &[u8]) -> Vec<u8> {
    let positions: [[f32; 3]; 4] = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [1.0, 0.0, 1.0]];
    let normals = [[0.0f32, 1.0, 0.0]; 4];
    let uvs: [[f32; 2]; 4] = [[0.0, 0.0], [0.0, 1.0], [1.0, 0.0], [1.0, 1.0]];
    let indices: [u16; 6] = [0, 1, 3, 0, 3, 2];
    let mut bytes: Vec<u8> = Vec::new();
    for part in [bytemuck::cast_slice(&positions), bytemuck::cast_slice(&normals), bytemuck::cast_slice(&uvs), extra] {
        bytes.extend_from_slice(part);
    }
    bytes.extend_from_slice(bytemuck::cast_slice(&indices));
    bytes
}

/// The bytes of buffer 0: [`quad_bytes`] with nothing between the UVs and the indices, padded to
/// 144 bytes.
pub fn quad_buffer() -> Vec<u8> {
    let mut bytes = quad_bytes(&[]);
    bytes.resize(144, 0);
    bytes
}

/// A glTF document for [`quad_buffer`]: `buffer` is the buffer's JSON (its URI or none), `nodes`
/// the node list and `material` the first material.
pub fn quad_gltf(
    buffer: serde_json::Value,
    nodes: serde_json::Value,
    material: serde_json::Value,
) -> serde_json::Value {
    let view =
        |offset: usize, length: usize| serde_json::json!({ "buffer": 0, "byteOffset": offset, "byteLength": length });
    let node_count = nodes.as_array().map_or(0, Vec::len);
    let roots: Vec<usize> = (0..node_count)
        .filter(|i| {
            !nodes
                .as_array()
                .unwrap()
                .iter()
                .any(|n| n["children"].as_array().is_some_and(|c| c.contains(&serde_json::json!(i))))
        })
        .collect();
    serde_json::json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": roots }],
        "nodes": nodes,
        "meshes": [{ "primitives": [{
            "attributes": { "POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2 },
            "indices": 3,
            "material": 0
        }] }],
        "materials": [material],
        "buffers": [buffer],
        "bufferViews": [view(0, 48), view(48, 48), view(96, 32), view(128, 12)],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 0.0, 1.0] },
            { "bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3" },
            { "bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2" },
            { "bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR" }
        ]
    })
}

pub fn plain_material() -> serde_json::Value {
    serde_json::json!({ "name": "paint", "pbrMetallicRoughness": { "baseColorFactor": [0.2, 0.4, 0.6, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.5 } })
}

pub fn one_node() -> serde_json::Value {
    serde_json::json!([{ "mesh": 0 }])
}

/// Writes a `.glb`: the JSON chunk and the binary chunk, each padded to 4 bytes.
pub fn write_glb(path: &std::path::Path, document: &serde_json::Value, bin: &[u8]) {
    let mut json = serde_json::to_vec(document).unwrap();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::new();
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(&json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    std::fs::write(path, out).unwrap();
}

/// The eye ray (origin, unit direction) through the centre of pixel `(x, y)` of a `size` image
/// from `camera`.
pub fn eye_ray_in(camera: &OrbitCamera, size: (u32, u32), (x, y): (usize, usize)) -> (Vec3, Vec3) {
    let (w, h) = (size.0 as f32, size.1 as f32);
    let to_world = (camera.view_to_clip(w / h) * camera.world_to_view()).inverse();
    let ndc = Vec3::new((x as f32 + 0.5) / w * 2.0 - 1.0, 1.0 - (y as f32 + 0.5) / h * 2.0, 0.5);
    let eye = camera.eye();
    (eye, (to_world.project_point3(ndc) - eye).normalize())
}
