//! The viewer's actions and frames: what a key, a button or a finished load does, the comparison
//! of the four modes, and drawing a frame (the 3D view, then the panel over it).

use std::path::PathBuf;
use std::time::{Duration, Instant};

use super::loader::Loaded;
use super::panel_state::Action;
use super::{timestamp, ui, Viewer, TIMING_REFRESH};
use crate::headless::capture::capture_converged;
use crate::render::{Canvas, Mode};
use crate::scene::Scene;
use crate::{compare, output, Result};

impl Viewer {
    pub(super) fn act(&mut self, action: Action) {
        match action {
            Action::Mode(mode) => {
                self.renderer.settings.mode = mode;
                self.window.set_title(&format!("ssdo — {}", mode.title()));
            }
            Action::LoadSky(path) => {
                self.panel.say(format!("loading sky {}", path.display()), false);
                self.loader.sky(path);
            }
            Action::LoadModel(path) => {
                self.panel.say(format!("loading model {}", path.display()), false);
                self.loader.model(path);
            }
            Action::Relight { lights, seed } => {
                self.scene.relight(lights, seed);
                self.renderer.set_lights(&self.gpu, self.scene.lights.clone());
                self.scene_changed();
            }
            Action::ToggleAccumulation => {
                let s = &mut self.renderer.settings;
                s.knobs.accumulate = if s.accumulates() { 1 } else { self.panel.accumulate.max(2) };
            }
            Action::ResetCamera => {
                self.camera = self.home;
                // A jump, not a move: nothing of the last view is kept.
                self.renderer.reset_history();
            }
            Action::Screenshot => {
                let path = self.screenshot_dir.join(format!(
                    "screenshot-{}-{}.png",
                    timestamp(),
                    self.renderer.settings.mode.name()
                ));
                // What is on screen: the frame, or the truth, the error map or the split over it.
                let result = self.screen_image().and_then(|image| output::save_png(&path, &image));
                match result {
                    Ok(()) => {
                        self.panel.say(format!("saved {}", path.display()), false);
                        log::info!("{}: the same view headless: {}", path.display(), self.command());
                    }
                    Err(e) => self.panel.say(format!("screenshot failed: {e}"), true),
                }
            }
            Action::Compare => match self.compare() {
                Ok(path) => self.panel.say(format!("saved {}", path.display()), false),
                Err(e) => self.panel.say(format!("comparison failed: {e}"), true),
            },
            Action::ToggleFly => {
                self.controls.set_fly(!self.controls.fly);
                self.panel.fly = self.controls.fly;
                log::info!("fly camera {}", if self.controls.fly { "on" } else { "off" });
            }
            Action::LoadPreset(path) => match crate::preset::Preset::load(&path) {
                Ok(preset) => {
                    self.renderer.settings = self.renderer.settings.with_knobs(preset.knobs);
                    self.panel.say(format!("preset '{}': {}", preset.name, preset.knobs.label()), false);
                    if let Some(warning) = preset.elsewhere(&self.panel.adapter, self.renderer.size()) {
                        self.panel.say(warning, true);
                    }
                    self.panel.preset = Some(preset);
                }
                // The settings stay as they were.
                Err(e) => self.panel.say(format!("preset not loaded: {e}"), true),
            },
            Action::CopyCommand => {
                let command = self.command();
                self.egui.egui_ctx().copy_text(command.clone());
                self.panel.say(format!("copied: {command}"), false);
            }
        }
    }

    /// The camera the view is drawn with. The fly camera is drawn as `--eye` and `--look-at`
    /// build it from the command's numbers (which read back to the same floats), so the command
    /// renders the very same pixels; an orbit camera is its own numbers already.
    pub(super) fn view_camera(&self) -> crate::scene::OrbitCamera {
        if self.controls.fly {
            self.camera.looking(self.camera.eye(), self.camera.target).unwrap_or(self.camera)
        } else {
            self.camera
        }
    }

    /// The `ssdo capture` command that renders what the 3D view shows.
    pub(super) fn command(&self) -> String {
        // The lengths a preset gives as multiples, stated as this scene's.
        let settings = &self.renderer.settings;
        let settings = settings.resolved(self.scene.default_radius());
        let view = crate::reproduce::ViewDescription {
            model: self.model_path.as_deref(),
            skybox: self.sky_path.as_deref(),
            layout: self.layout,
            triangles: self.triangles,
            scale: self.scale,
            no_surface_maps: self.no_surface_maps,
            lights: self.scene.lights.len(),
            seed: self.panel.seed,
            camera: &self.camera,
            fly: self.controls.fly,
            settings: &settings,
            size: self.renderer.size(),
            truth_rays: self.truth_rays(),
        };
        crate::reproduce::shell_line(&crate::reproduce::capture_arguments(&view))
    }

    /// The four modes of the current view, rendered offscreen at the 3D view's size; with the
    /// truth of this view traced, the truth and each mode's error map too (on one scale).
    fn compare(&mut self) -> Result<PathBuf> {
        let (mode, hdr) = (self.renderer.settings.mode, self.renderer.keeps_hdr());
        let with_truth = self.truth_for_compare().is_some();
        if with_truth {
            self.renderer.keep_hdr(&self.gpu, true);
        }
        let panels = self.compare_panels();
        self.renderer.set_mode(&self.gpu, mode);
        self.renderer.keep_hdr(&self.gpu, hdr);
        let path = self.screenshot_dir.join(format!("compare-{}.png", timestamp()));
        output::save_png(&path, &compare::grid(&panels?))?;
        Ok(path)
    }

    /// The comparison's panels: each mode's image, then the truth and the modes' error maps
    /// where the truth of this view is traced.
    fn compare_panels(&mut self) -> Result<Vec<(Vec<String>, image::RgbaImage)>> {
        let mut panels = Vec::new();
        let mut errors = Vec::new();
        let camera = self.view_camera();
        for m in Mode::ALL {
            self.renderer.set_mode(&self.gpu, m);
            let image = capture_converged(&self.gpu, &mut self.renderer, &camera)?;
            if let Some(truth) = self.truth_for_compare() {
                errors.push(truth.measure(&self.gpu, &self.renderer, m, &image)?);
            }
            let caption = compare::caption(&self.renderer, &self.panel.sky_name, self.scene.lights.len());
            panels.push((caption, image));
        }
        if let Some(truth) = self.truth_for_compare() {
            let image = truth.image(&panels[0].1, self.renderer.settings.exposure);
            panels.push((truth.caption(), image));
            let maps = crate::headless::truth::error_maps(&errors, self.renderer.size());
            for (e, map) in errors.iter().zip(maps) {
                panels.push((vec![format!("{} error", e.mode.title()), e.summary()], map));
            }
        }
        Ok(panels)
    }

    /// The model, the sky or the lights changed: the truth is traced anew, and a split's second
    /// renderer is made anew with them.
    fn scene_changed(&mut self) {
        self.scene_number += 1;
        self.drop_second();
    }

    /// Applies finished loads: the old sky or model stays unless the new one is complete.
    /// Returns whether anything arrived.
    pub(super) fn apply_loads(&mut self) -> bool {
        let finished = self.loader.finished();
        let arrived = !finished.is_empty();
        for loaded in finished {
            match loaded {
                Loaded::Sky(path, Ok(sky)) => match self.renderer.set_sky(&self.gpu, &sky) {
                    Ok(()) => {
                        self.panel.sky_name = sky.name.clone();
                        self.sky_path = Some(path.clone());
                        self.panel.say(format!("sky {} loaded", path.display()), false);
                        self.sky = std::sync::Arc::new(sky);
                        self.scene_changed();
                    }
                    Err(e) => self.panel.say(format!("{e}; keeping sky {}", self.panel.sky_name), true),
                },
                Loaded::Model(path, Ok(model)) => {
                    let warnings = model.warnings.len();
                    let model = match self.layout.arrange(model) {
                        Ok(model) => model,
                        Err(e) => {
                            self.panel.say(format!("{e}; keeping model {}", self.panel.model_name), true);
                            continue;
                        }
                    };
                    self.scene = Scene::new(model, self.panel.lights, self.panel.seed);
                    self.renderer.set_scene(&self.gpu, &self.scene);
                    self.scene_changed();
                    self.home = self.layout.camera(&self.scene.model.bounds);
                    self.camera = self.home;
                    self.panel.model_name = self.scene.model.name.clone();
                    // A model loaded here is not scaled (`--scale` applied to the first).
                    self.model_path = Some(path.clone());
                    (self.scale, self.triangles, self.no_surface_maps) = (1.0, None, false);
                    self.panel
                        .say(format!("model {} loaded ({warnings} warnings, see the log)", path.display()), false);
                    if let Some(note) = self.scene.model.cut_away() {
                        self.panel.say(format!("{}: {note}", path.display()), true);
                    }
                }
                Loaded::Sky(_, Err(e)) => self.panel.say(format!("{e}; keeping sky {}", self.panel.sky_name), true),
                Loaded::Model(_, Err(e)) => {
                    self.panel.say(format!("{e}; keeping model {}", self.panel.model_name), true)
                }
            }
        }
        self.panel.loading = self.loader.progress();
        arrived
    }

    /// egui's input for this frame: what `egui_winit::State::take_egui_input` gathers, with the
    /// size from the last `Resized` instead of asking the window (see `Viewer::window_size`). The
    /// scale factor is winit's cached value, no round trip to the server.
    fn egui_input(&mut self) -> egui::RawInput {
        let native = self.window.scale_factor() as f32;
        let points_per_pixel = 1.0 / (native * self.egui.egui_ctx().zoom_factor());
        let size = egui::vec2(self.window_size.width as f32, self.window_size.height as f32) * points_per_pixel;
        let input = self.egui.egui_input_mut();
        input.time = Some(self.started.elapsed().as_secs_f64());
        input.screen_rect = (size.x > 0.0 && size.y > 0.0).then(|| egui::Rect::from_min_size(egui::Pos2::ZERO, size));
        input.viewport_id = egui::ViewportId::ROOT;
        input.viewports.entry(egui::ViewportId::ROOT).or_default().native_pixels_per_point = Some(native);
        input.take()
    }

    /// Presents the pending frame if the GPU has finished it; returns whether none is pending
    /// now. Never waits: a frame that takes seconds on a software rasteriser leaves the event
    /// loop free for Escape and the close button.
    pub(super) fn present_when_done(&mut self) -> bool {
        if self.pending.is_none() {
            return true;
        }
        let _ = self.gpu.device.poll(wgpu::PollType::Poll);
        if self.gpu_busy.load(std::sync::atomic::Ordering::Acquire) {
            return false;
        }
        let Some((frame, started)) = self.pending.take() else { return true };
        self.gpu.queue.present(frame);
        let elapsed = started.elapsed().as_secs_f64() * 1e3;
        self.panel.frame_ms =
            if self.panel.frame_ms == 0.0 { elapsed } else { 0.8 * self.panel.frame_ms + 0.2 * elapsed };
        true
    }

    pub(super) fn redraw(&mut self) -> Result<()> {
        // One frame at a time: the next is drawn once the pending one is on screen.
        if !self.present_when_done() {
            self.redraw_wanted = true;
            return Ok(());
        }
        let started = Instant::now();
        self.apply_loads();
        let Some(frame) = self.acquire() else { return Ok(()) };
        let target = frame.texture.create_view(&wgpu::TextureViewDescriptor::default());
        // The fly camera's step, then the panel: it may change settings for this frame.
        self.controls.step(&mut self.camera, self.scene.model.bounds.radius(), Instant::now());
        // Wherever flying, panning and zooming led, within what `capture` takes back.
        self.camera.keep_in_range(&self.scene.model.bounds);
        let panel = self.run_panel();
        let mut encoder =
            self.gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("viewer_frame") });
        let camera = self.view_camera();
        if let Err(e) = self.encode_second(&mut encoder) {
            self.panel.say(format!("the split's right side cannot be drawn: {e}"), true);
            self.panel.truth.display = super::truth_ui::Display::Live;
        }
        let canvas = Canvas { view: &target, origin: (self.panel_pixels(), 0) };
        self.renderer.encode(&self.gpu, &mut encoder, &camera, canvas);
        self.drawn_camera = Some(camera);
        self.submit_with_panel(encoder, panel, &target);
        self.pending = Some((frame, started));
        // Timestamps of a frame or two ago, never waited for.
        if let Some(steps) = self.renderer.poll_timings(&self.gpu)? {
            let names: Vec<(&'static str, f64)> =
                steps.iter().map(|(step, ms)| (step.name_in(self.renderer.plan().mode), *ms)).collect();
            self.panel.record_timings(&names);
        }
        if !self.refreshing {
            self.timing_refresh = Some(Instant::now() + TIMING_REFRESH);
        }
        self.refreshing = false;
        if let Err(e) = self.gpu.check() {
            self.panel.say(e.to_string(), true);
        }
        Ok(())
    }

    /// The window's next image, or `None` for no frame now (minimised, occluded, or a surface
    /// that had to be configured anew).
    fn acquire(&mut self) -> Option<wgpu::SurfaceTexture> {
        if self.window_size.width == 0 || self.window_size.height == 0 {
            return None;
        }
        match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame) | wgpu::CurrentSurfaceTexture::Suboptimal(frame) => Some(frame),
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => None,
            wgpu::CurrentSurfaceTexture::Outdated
            | wgpu::CurrentSurfaceTexture::Lost
            | wgpu::CurrentSurfaceTexture::Validation => {
                self.surface.configure(&self.gpu.device, &self.config);
                None
            }
        }
    }

    /// Runs the panel for this frame, carrying out what was clicked; its output to draw.
    fn run_panel(&mut self) -> egui::FullOutput {
        self.panel.still_frames = self.renderer.still_frames();
        self.panel.command = self.command();
        let input = self.egui_input();
        let default_radius = self.scene.default_radius();
        let ctx = self.egui.egui_ctx().clone();
        let mut actions = Vec::new();
        let scale = self.window.scale_factor() as f32;
        let (w, h) = self.renderer.size();
        let view = egui::Rect::from_min_size(
            egui::pos2(self.panel_pixels() as f32 / scale, 0.0),
            egui::vec2(w as f32 / scale, h as f32 / scale),
        );
        let mut full = ctx.run_ui(input, |ui| {
            actions = ui::panel(ui, &mut self.panel, &mut self.renderer.settings, default_radius);
            self.paint_view(ui.ctx(), view);
        });
        let delay = full.viewport_output.get(&egui::ViewportId::ROOT).map_or(Duration::MAX, |v| v.repaint_delay);
        self.egui_repaint = Instant::now().checked_add(delay);
        self.egui.handle_platform_output(&self.window, std::mem::take(&mut full.platform_output));
        for action in actions {
            self.act(action);
        }
        full
    }

    /// Draws the panel over `target` after the frame in `encoder`, and submits both; the GPU's
    /// work is watched so the frame is presented once done.
    fn submit_with_panel(
        &mut self,
        mut encoder: wgpu::CommandEncoder,
        mut panel: egui::FullOutput,
        target: &wgpu::TextureView,
    ) {
        let pixels_per_point = panel.pixels_per_point;
        let jobs = self.egui.egui_ctx().tessellate(std::mem::take(&mut panel.shapes), pixels_per_point);
        for (id, deltas) in panel.textures_delta.set.drain() {
            for delta in &deltas {
                self.egui_renderer.update_texture(&self.gpu.device, &self.gpu.queue, id, delta);
            }
        }
        let screen =
            egui_wgpu::ScreenDescriptor { size_in_pixels: [self.config.width, self.config.height], pixels_per_point };
        let extra = self.egui_renderer.update_buffers(&self.gpu.device, &self.gpu.queue, &mut encoder, &jobs, &screen);
        {
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("egui_pass"),
                color_attachments: &[crate::render::graph::io::color_attachment(target, false)],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            self.egui_renderer.render(&mut pass.forget_lifetime(), &jobs, &screen);
        }
        self.gpu_busy.store(true, std::sync::atomic::Ordering::Release);
        self.gpu.queue.submit(extra.into_iter().chain([encoder.finish()]));
        let busy = self.gpu_busy.clone();
        self.gpu.queue.on_submitted_work_done(move || busy.store(false, std::sync::atomic::Ordering::Release));
        self.renderer.timings_submitted();
        for id in panel.textures_delta.free.drain() {
            self.egui_renderer.free_texture(&id);
        }
    }
}
