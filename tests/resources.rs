//! Resource stability: 1,000 resizes (0x0 and 1x1 among them) and 200 sky swaps, each followed by
//! a frame. The renderer's own byte accounting must come back to the same total at the same size,
//! and the process's resident memory must stay flat (within ±5% of what it was after a warm-up
//! round of the same work).

mod common;

use glam::Vec3;
use ssdo::render::{Mode, Settings};
use ssdo::scene::{builtin, Scene, Skybox};

fn resident_bytes() -> u64 {
    let statm = std::fs::read_to_string("/proc/self/statm").unwrap_or_default();
    let pages: u64 = statm.split_whitespace().nth(1).and_then(|p| p.parse().ok()).unwrap_or(0);
    pages * 4096
}

#[test]
fn resizes_and_sky_swaps_leave_memory_flat() {
    let Some(gpu) = common::gpu() else { return };
    if !std::path::Path::new("/proc/self/statm").exists() {
        eprintln!("skipping: no /proc/self/statm on this system");
        return;
    }
    let scene = Scene::new(builtin::cornell().unwrap(), 8, 1);
    let skies = [Skybox::from_fn("day", 32, builtin::day_sky), Skybox::constant(Vec3::new(0.2, 0.3, 0.9))];
    let mut renderer =
        common::renderer(&gpu, &scene, &skies[0], (64, 48), Settings { mode: Mode::Both, ..Settings::default() });
    let camera = ssdo::scene::OrbitCamera::framing(&scene.model.bounds);
    let sizes = [(0, 0), (1, 1), (64, 48), (3, 2), (97, 61), (0, 0), (40, 30), (64, 48)];
    let total = |r: &ssdo::render::Renderer| r.allocations().iter().map(|(_, b)| b).sum::<u64>();
    let output = ssdo::render::capture::output_texture(&gpu, (128, 96));
    let view = output.create_view(&wgpu::TextureViewDescriptor::default());

    let mut round = |resizes: usize, swaps: usize| {
        for i in 0..resizes {
            let (w, h) = sizes[i % sizes.len()];
            renderer.resize(&gpu, w, h).unwrap();
            let mut encoder =
                gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("resource_test") });
            renderer.encode(&gpu, &mut encoder, &camera, &view);
            gpu.queue.submit([encoder.finish()]);
            gpu.wait().unwrap();
        }
        for i in 0..swaps {
            renderer.set_sky(&gpu, &skies[i % 2]).unwrap();
            let mut encoder =
                gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("resource_test") });
            renderer.encode(&gpu, &mut encoder, &camera, &view);
            gpu.queue.submit([encoder.finish()]);
            gpu.wait().unwrap();
        }
        renderer.set_sky(&gpu, &skies[0]).unwrap();
        renderer.resize(&gpu, 64, 48).unwrap();
        gpu.wait().unwrap();
        (total(&renderer), resident_bytes())
    };
    // Warm-up: allocators and driver caches reach their working size.
    let (bytes_before, rss_before) = round(200, 40);
    let (bytes_after, rss_after) = round(1000, 200);
    gpu.check().unwrap();
    println!(
        "renderer bytes {bytes_before} -> {bytes_after}; resident {:.1} MiB -> {:.1} MiB",
        rss_before as f64 / 1048576.0,
        rss_after as f64 / 1048576.0
    );
    assert_eq!(bytes_after, bytes_before, "the renderer's own accounting is the same at the same size");
    let change = (rss_after as f64 - rss_before as f64) / rss_before as f64;
    assert!(change.abs() <= 0.05, "resident memory changed by {:.1}%", change * 100.0);
}
