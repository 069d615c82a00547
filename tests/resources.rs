//! Resource stability: 1,000 resizes (0x0 and 1x1 among them) and 200 sky swaps, each followed by
//! a frame. The renderer's own byte accounting must come back to the same total at the same size,
//! and the process's resident memory must stay flat (within ±5% of what it was after a warm-up
//! round of the same work).

#[path = "it/common.rs"]
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
        common::renderer(gpu, &scene, &skies[0], (64, 48), Settings { mode: Mode::Both, ..Settings::default() });
    let camera = ssdo::scene::OrbitCamera::framing(&scene.model.bounds);
    let sizes = [(0, 0), (1, 1), (64, 48), (3, 2), (97, 61), (0, 0), (40, 30), (64, 48)];
    let total = |r: &ssdo::render::Renderer| r.allocations().iter().map(|(_, b)| b).sum::<u64>();
    let output = ssdo::headless::capture::output_texture(gpu, (128, 96));
    let view = output.create_view(&wgpu::TextureViewDescriptor::default());

    let mut round = |resizes: usize, swaps: usize| {
        for i in 0..resizes {
            let (w, h) = sizes[i % sizes.len()];
            renderer.resize(gpu, w, h).unwrap();
            let mut encoder =
                gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("resource_test") });
            renderer.encode(gpu, &mut encoder, &camera, &view);
            gpu.queue.submit([encoder.finish()]);
            gpu.wait().unwrap();
        }
        for i in 0..swaps {
            renderer.set_sky(gpu, &skies[i % 2]).unwrap();
            let mut encoder =
                gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("resource_test") });
            renderer.encode(gpu, &mut encoder, &camera, &view);
            gpu.queue.submit([encoder.finish()]);
            gpu.wait().unwrap();
        }
        renderer.set_sky(gpu, &skies[0]).unwrap();
        renderer.resize(gpu, 64, 48).unwrap();
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

#[test]
fn a_history_survives_re_plans_that_do_not_concern_it_and_is_dropped_on_resize() {
    use ssdo::render::history::{History, HistorySpec};
    let Some(gpu) = common::gpu() else { return };
    let spec = HistorySpec { name: "accumulated", format: wgpu::TextureFormat::Rgba16Float, key: 7 };
    let other = HistorySpec { name: "other", key: 1, ..spec };
    let mut history = History::default();
    history.ensure(&gpu.device, (32, 24), &[spec]);
    let get = |h: &History| {
        let p = h.get("accumulated").expect("kept");
        (p.generation, p.frames)
    };
    let made = get(&history).0;
    assert_eq!(history.bytes(), 2 * 32 * 24 * 8, "two Rgba16Float textures");
    // Ping-pong: what a frame writes is what the next one reads.
    for frame in 1..=3 {
        let written: *const _ = history.get("accumulated").unwrap().write();
        history.advance();
        let pair = history.get("accumulated").unwrap();
        assert!(std::ptr::eq(pair.read(), written), "frame {frame} reads what the last one wrote");
        assert!(!std::ptr::eq(pair.write(), written));
    }
    assert_eq!(get(&history), (made, 3));
    // A re-plan that still asks for it (and for something else) keeps it, frames and all.
    history.ensure(&gpu.device, (32, 24), &[other, spec]);
    assert_eq!(get(&history), (made, 3));
    assert_eq!(history.get("other").unwrap().frames, 0);
    // A reset keeps the textures and forgets the frames.
    history.reset();
    assert_eq!(get(&history), (made, 0));
    // Another key (its inputs changed) or another size makes it anew; what no spec names goes.
    history.advance();
    history.ensure(&gpu.device, (32, 24), &[HistorySpec { key: 8, ..spec }]);
    let rekeyed = get(&history);
    assert!(rekeyed.0 != made && rekeyed.1 == 0, "{rekeyed:?}");
    assert!(history.get("other").is_none());
    history.advance();
    history.ensure(&gpu.device, (33, 24), &[HistorySpec { key: 8, ..spec }]);
    let resized = get(&history);
    assert!(resized.0 != rekeyed.0 && resized.1 == 0, "dropped on resize: {resized:?}");
    assert_eq!(history.get("accumulated").unwrap().size, (33, 24));
    history.ensure(&gpu.device, (33, 24), &[]);
    assert_eq!((history.bytes(), history.all().count()), (0, 0));
}

#[test]
fn the_frame_uniforms_carry_the_previous_camera_and_only_an_accumulating_plan_allocates_history() {
    let Some(gpu) = common::gpu() else { return };
    let scene = Scene::new(builtin::cornell().unwrap(), 8, 1);
    let sky = Skybox::constant(Vec3::ONE);
    let size = (40, 30);
    let mut renderer = common::renderer(gpu, &scene, &sky, size, Settings { mode: Mode::Both, ..Settings::default() });
    let a = ssdo::scene::OrbitCamera::framing(&scene.model.bounds);
    let b = ssdo::scene::OrbitCamera { yaw_deg: a.yaw_deg + 10.0, ..a };
    let clip = |c: &ssdo::scene::OrbitCamera| {
        (c.view_to_clip(size.0 as f32 / size.1 as f32) * c.world_to_view()).to_cols_array_2d()
    };
    let previous = |r: &ssdo::render::Renderer| r.frame_uniforms().previous_world_to_clip;
    common::shoot(gpu, &mut renderer, &a);
    assert_eq!(previous(&renderer), clip(&a), "a first frame's previous camera is its own");
    common::shoot(gpu, &mut renderer, &b);
    assert_eq!(previous(&renderer), clip(&a), "the second frame remembers the first's camera");
    assert_ne!(previous(&renderer), clip(&b));
    renderer.reset_history();
    common::shoot(gpu, &mut renderer, &b);
    assert_eq!(previous(&renderer), clip(&b), "after a reset the previous camera is the frame's own");
    // A plan that accumulates keeps the temporal pass's two pairs, counted among the
    // allocations; one that does not (Off, or one frame) allocates none of them. A DO mode keeps
    // the sky its march saw for the next frame's senders either way.
    for accumulate in [1, 16] {
        renderer.settings.knobs.accumulate = accumulate;
        for mode in Mode::ALL {
            renderer.set_mode(gpu, mode);
            renderer.resize(gpu, 41, 30).unwrap();
            common::shoot(gpu, &mut renderer, &a);
            let kept = accumulate > 1 && mode != Mode::Off;
            let senders = mode.declaration().directional_occlusion;
            let names: Vec<String> = renderer.allocations().into_iter().map(|(n, _)| n).collect();
            let mut histories: Vec<&String> = names.iter().filter(|n| n.starts_with("history_")).collect();
            histories.sort();
            let mut want = if kept { vec!["history_occlusion", "history_surface"] } else { vec![] };
            want.extend(senders.then_some("history_sender_sky"));
            want.sort();
            assert_eq!(histories, want, "{mode}");
            // Two textures each, at the half-size samples' size (21x15): the average (8 or 2
            // bytes a texel) and the surface (8 bytes); the senders' sky (8 bytes).
            let per_texel = if mode == Mode::Ssao { 2 + 8 } else { 8 + 8 };
            let want = (if kept { per_texel } else { 0 } + if senders { 8 } else { 0 }) * 2 * 21 * 15;
            assert_eq!(renderer.history().bytes(), want, "{mode}, {accumulate} frames");
            renderer.resize(gpu, 40, 30).unwrap();
        }
    }
}
