//! The memory budget, measured: this test binary counts every byte the Rust allocator hands
//! out, so the peak of a load is a figure the test checks (the GPU driver's own memory is not
//! counted; `tests/resources.rs` watches that). One test at a time: the counter is the process's.

#[path = "it/common.rs"]
mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use std::sync::Mutex;

use ssdo::render::{Mode, Renderer, SceneFeatures, Settings};

struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

// SAFETY: every call is passed to the system allocator unchanged; the counters only add up sizes.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = LIVE.fetch_add(layout.size(), Relaxed) + layout.size();
            PEAK.fetch_max(now, Relaxed);
        }
        p
    }

    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        unsafe { System.dealloc(p, layout) };
        LIVE.fetch_sub(layout.size(), Relaxed);
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// What `work` returns, and the most bytes it held at once beyond what was live before.
fn peak_during<T>(work: impl FnOnce() -> T) -> (T, usize) {
    let base = LIVE.load(Relaxed);
    PEAK.store(base, Relaxed);
    let out = work();
    (out, PEAK.load(Relaxed).saturating_sub(base))
}

const MIB: usize = 1 << 20;

/// One test at a time (the allocator's counts are the process's), and the process's memory
/// budget, set to `bytes` while the guard lives and to the default again when it drops (even when
/// the test fails).
struct Alone {
    _lock: std::sync::MutexGuard<'static, ()>,
    budget_set: bool,
}

fn alone() -> Alone {
    Alone { _lock: ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner()), budget_set: false }
}

fn alone_within(bytes: u64) -> Alone {
    let mut one = alone();
    ssdo::budget::set(bytes).unwrap();
    one.budget_set = true;
    one
}

impl Drop for Alone {
    fn drop(&mut self) {
        if self.budget_set {
            ssdo::budget::set(ssdo::budget::machine_bytes() / 2).unwrap();
        }
    }
}

fn write_quad(dir: &Path, map: &str) -> std::path::PathBuf {
    std::fs::write(dir.join("m.mtl"), format!("newmtl m\nKd 1 1 1\nmap_Kd {map}\n")).unwrap();
    let obj = "mtllib m.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
               usemtl m\nf 1/1 2/2 3/3 4/4\n";
    std::fs::write(dir.join("quad.obj"), obj).unwrap();
    dir.join("quad.obj")
}

/// The quad textured with `map`, loaded within `budget` bytes of textures: its diffuse map's
/// size, its warnings, and the most bytes the load held at once.
fn load_quad(dir: &Path, map: &str, budget: u64) -> ((u32, u32), Vec<String>, usize) {
    let quad = write_quad(dir, map);
    let (model, peak) = peak_during(|| ssdo::scene::obj_model::load_obj_with_budget(&quad, budget).unwrap());
    let map = model.materials[0].diffuse_map.as_ref().unwrap();
    ((map.width, map.height), model.warnings, peak)
}

#[test]
fn a_decompression_bomb_is_sized_from_its_header_and_never_expanded_whole() {
    let _one = alone();
    let dir = tempfile::tempdir().unwrap();
    // 8192² grey texels of one value: a 0.2 MB file that is 256 MiB as RGBA8.
    image::GrayImage::from_pixel(8192, 8192, image::Luma([85])).save(dir.path().join("bomb.png")).unwrap();
    assert!(std::fs::metadata(dir.path().join("bomb.png")).unwrap().len() < MIB as u64);

    let (size, warnings, peak) = load_quad(dir.path(), "bomb.png", 16 << 20);
    assert_eq!(size, (2048, 2048), "halved until 16 MiB of RGBA8 holds it");
    assert!(warnings.iter().any(|w| w.contains("downscaled from 8192x8192 to 2048x2048")), "{warnings:?}");
    // The grey decode (64 MiB) and the result (16 MiB) at most; decoding to RGBA8 first would
    // have held 256 MiB, and a float resize of that twice as much again.
    assert!(peak < 100 * MIB, "the load peaked at {} MiB", peak / MIB);
}

#[test]
fn textures_share_the_room_fairly_and_a_decode_beyond_it_is_a_checker() {
    let _one = alone();
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Eight distinct 512² maps (8 MiB of RGBA8) in 2 MiB: each ends at 256², none below.
    let mut mtl = String::new();
    let mut obj = String::from("mtllib m.mtl\n");
    for i in 0..8u32 {
        image::RgbImage::from_pixel(512, 512, image::Rgb([i as u8 * 30, 100, 50]))
            .save(d.join(format!("t{i}.png")))
            .unwrap();
        mtl += &format!("newmtl m{i}\nKd 1 1 1\nmap_Kd t{i}.png\n");
        obj +=
            &format!("v {i} 0 0\nv {i} 0 1\nv {i}.5 0 0\nusemtl m{i}\nf {} {} {}\n", 3 * i + 1, 3 * i + 2, 3 * i + 3);
    }
    std::fs::write(d.join("m.mtl"), mtl).unwrap();
    std::fs::write(d.join("m.obj"), obj).unwrap();
    let model = ssdo::scene::obj_model::load_obj_with_budget(&d.join("m.obj"), 2 << 20).unwrap();
    let sizes: Vec<(u32, u32)> =
        model.materials.iter().filter_map(|m| m.diffuse_map.as_ref()).map(|t| (t.width, t.height)).collect();
    assert_eq!(sizes.len(), 8);
    assert!(sizes.iter().all(|&s| s == (256, 256)), "{sizes:?}");

    // A picture whose decode alone is beyond the room (and beyond the 64 MiB any decode may
    // take): 16-bit RGBA of 4096x2304 is 72 MiB before any resize. It becomes the checker.
    let big = image::ImageBuffer::<image::Rgba<u16>, _>::from_pixel(4096, 2304, image::Rgba([9000u16; 4]));
    big.save(d.join("deep.png")).unwrap();
    drop(big);
    let (size, warnings, peak) = load_quad(d, "deep.png", 3 << 20);
    assert_eq!(size, (8, 8), "the checker");
    assert!(warnings.iter().any(|w| w.contains("deep.png") && w.contains("decodes to 72 MiB")), "{warnings:?}");
    assert!(peak < 8 * MIB, "refused from the header, yet {} MiB were held", peak / MIB);
}

#[test]
fn a_model_and_targets_beyond_the_budget_are_refused_before_they_are_built() {
    let _one = alone_within(256 << 20);
    let dir = tempfile::tempdir().unwrap();
    // One polygon of a million corners (a 2 MB file): 999,998 fan triangles, 610 MiB to build,
    // over the 96 MiB geometry share of a 256 MiB budget.
    let path = dir.path().join("polygon.obj");
    let corners: Vec<String> = (0..1_000_000).map(|i| (i % 9 + 1).to_string()).collect();
    let vertices: String = (0..9).map(|i| format!("v {} 0 {}\n", (i as f32).cos(), (i as f32).sin())).collect();
    std::fs::write(&path, format!("{vertices}f {}\n", corners.join(" "))).unwrap();
    let (result, peak) = peak_during(|| ssdo::scene::obj_model::load_obj(&path));
    let message = result.unwrap_err().to_string();
    assert!(message.contains("polygon.obj") && message.contains("999998 triangles would need"), "{message}");
    assert!(message.contains("memory budget for geometry") && message.contains("--memory-budget"), "{message}");
    assert!(peak < MIB, "sized from a stream of the file, yet {} KiB were held", peak >> 10);

    // 64 MiB of zero bytes (a sparse file, as a disk full of nothing gives): refused by name
    // from the same stream, never read whole.
    let zeros = dir.path().join("zeros.obj");
    std::fs::File::create(&zeros).unwrap().set_len(64 << 20).unwrap();
    let (result, peak) = peak_during(|| ssdo::scene::obj_model::load_obj(&zeros));
    let message = result.unwrap_err().to_string();
    assert!(message.contains("zeros.obj") && message.contains("holds only zero bytes"), "{message}");
    assert!(peak < MIB, "a file of zeros was held: {} KiB", peak >> 10);

    // Targets: refused from the plan, before a device exists; what fits passes.
    let settings = Settings::default();
    let features = SceneFeatures::lit(8);
    let error = Renderer::check_memory((8192, 8192), &settings, features, false, &Mode::ALL).unwrap_err();
    assert!(error.to_string().contains("8192x8192 in Off would need"), "{error}");
    Renderer::check_memory((160, 120), &settings, features, true, &Mode::ALL).unwrap();
}

#[test]
fn every_input_a_gltf_or_a_sky_names_is_sized_before_it_is_read() {
    use serde_json::json;
    let _one = alone_within(64 << 20);
    let dir = tempfile::tempdir().unwrap();
    // Eight images naming one file of 1000 MiB (sparse: nothing to read but its size). Read once
    // at most, and not at all when it cannot fit: each image is the checker, and the warning
    // names the budget.
    let big = dir.path().join("big.png");
    std::fs::File::create(&big).unwrap().set_len(1000 << 20).unwrap();
    std::fs::write(dir.path().join("quad.bin"), common::quad_buffer()).unwrap();
    let textured = json!({ "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } });
    let buffer = json!({ "uri": "quad.bin", "byteLength": 144 });
    let mut document = common::quad_gltf(buffer.clone(), common::one_node(), textured.clone());
    document["materials"] = json!(vec![textured; 8]);
    document["textures"] = json!((0..8).map(|i| json!({ "source": i })).collect::<Vec<_>>());
    document["images"] = json!(vec![json!({ "uri": "big.png" }); 8]);
    let path = dir.path().join("eight.gltf");
    std::fs::write(&path, document.to_string()).unwrap();
    let (result, peak) = peak_during(|| ssdo::scene::load_model_file(&path));
    let model = result.unwrap();
    assert!(
        model.warnings.iter().any(|w| w.contains("big.png") && w.contains("memory budget for textures")),
        "{:?}",
        model.warnings
    );
    assert!(peak < 8 * MIB, "the image file was read: {} MiB held", peak / MIB);
    // A buffer of 2 GiB (sparse): refused from its declared length before a byte is read.
    let huge = dir.path().join("huge.bin");
    std::fs::File::create(&huge).unwrap().set_len(2 << 30).unwrap();
    let document =
        common::quad_gltf(json!({ "uri": "huge.bin", "byteLength": 1u64 << 31 }), common::one_node(), json!({}));
    let path = dir.path().join("huge.gltf");
    std::fs::write(&path, document.to_string()).unwrap();
    let (result, peak) = peak_during(|| ssdo::scene::load_model_file(&path));
    let message = result.unwrap_err().to_string();
    assert!(
        message.contains("huge.gltf")
            && (message.contains("memory budget for geometry") || message.contains("over 1024 MiB")),
        "{message}"
    );
    assert!(peak < 2 * MIB, "{} MiB held", peak / MIB);
    // A panorama of 16384x8192 (its header, then nothing): refused from the header, within the
    // sky's share, before its 1.5 GiB decode.
    let panorama = dir.path().join("big.hdr");
    std::fs::write(&panorama, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 16384\n").unwrap();
    let (result, peak) = peak_during(|| ssdo::scene::Skybox::load(&panorama));
    let message = result.unwrap_err().to_string();
    assert!(message.contains("16384x8192") && message.contains("memory budget for the sky"), "{message}");
    assert!(peak < 2 * MIB, "{} MiB held", peak / MIB);
    // The room's built-in figure counts against the same share.
    let (result, peak) = peak_during(|| ssdo::scene::Layout::Room.load(None, 1.0, Some(10_000_000)));
    let message = result.unwrap_err().to_string();
    assert!(message.contains("--triangles 10000000") && message.contains("memory budget for geometry"), "{message}");
    assert!(peak < MIB, "the figure was built: {} MiB held", peak / MIB);
}

#[test]
fn the_targets_counted_before_allocation_are_the_targets_allocated() {
    let _one = alone();
    let Some(gpu) = common::gpu() else { return };
    let scene = ssdo::scene::Scene::new(ssdo::scene::builtin::cornell().unwrap(), 8, 1);
    let sky = ssdo::scene::Skybox::constant(glam::Vec3::ONE);
    for mode in Mode::ALL {
        for keep_hdr in [false, true] {
            let settings = Settings { mode, ..Settings::default() };
            let mut renderer = common::renderer(gpu, &scene, &sky, (97, 61), settings);
            renderer.keep_hdr(gpu, keep_hdr);
            let allocated: u64 = renderer.targets().allocations().iter().map(|(_, b)| b).sum();
            let counted = ssdo::render::targets::Targets::bytes_for((97, 61), &renderer.plan().targets());
            assert_eq!(counted, allocated, "{mode:?}, HDR kept: {keep_hdr}");
        }
    }
}
