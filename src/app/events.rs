//! What the viewer does with the event loop: when to draw or wake next, each window event, and a
//! resize.

use std::time::{Duration, Instant};

use winit::dpi::PhysicalSize;
use winit::event::{ElementState, KeyEvent, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::keyboard::PhysicalKey;

use super::{Viewer, FRAME_POLL, LOAD_POLL};
use crate::Result;

impl Viewer {
    /// What the event loop does next. The viewer draws only when something changed: input (see
    /// `event`), a finished load, egui's own repaint request, or the one late timing refresh.
    pub(super) fn schedule(&mut self) -> ControlFlow {
        let now = Instant::now();
        let mut wake: Option<Instant> = None;
        // The pending frame is presented when the GPU is done with it; until then the loop
        // looks again shortly, handling input (Escape, closing) in between.
        if self.pending.is_some() {
            if self.present_when_done() {
                if std::mem::take(&mut self.redraw_wanted) {
                    self.window.request_redraw();
                }
            } else {
                wake = Some(now + FRAME_POLL);
            }
        }
        if self.loader.busy() {
            // A finished load, or once a second the panel's "loading… N s" line.
            if self.apply_loads() || now.duration_since(self.last_progress) >= Duration::from_secs(1) {
                self.last_progress = now;
                self.window.request_redraw();
            }
            let poll = now + LOAD_POLL;
            wake = Some(wake.map_or(poll, |w| w.min(poll)));
        }
        // A still view still averaging its frames draws the next one; so does a flying camera.
        if self.renderer.converging() || self.second_converging() || self.controls.flying() {
            self.window.request_redraw();
        }
        // The truth: started once a changed view settles, its rounds shown as they come.
        if let Some(next) = self.truth_tick() {
            wake = Some(wake.map_or(next, |w| w.min(next)));
        }
        // Each deadline that has come asks for a frame; the others say when to wake.
        let egui_due = self.egui_repaint.is_some_and(|t| t <= now);
        let timing_due = self.timing_refresh.is_some_and(|t| t <= now);
        if egui_due || timing_due {
            // A frame asked for by the timing refresh alone schedules no further refresh.
            self.refreshing = !egui_due;
            self.window.request_redraw();
        }
        if egui_due {
            self.egui_repaint = None;
        }
        if timing_due {
            self.timing_refresh = None;
        }
        let later = [self.egui_repaint, self.timing_refresh].into_iter().flatten();
        match later.chain(wake).min() {
            Some(t) => ControlFlow::WaitUntil(t),
            None => ControlFlow::Wait,
        }
    }

    pub(super) fn event(&mut self, event_loop: &ActiveEventLoop, event: WindowEvent) -> Result<()> {
        let response = self.egui.on_window_event(&self.window, &event);
        let panel = self.panel_pixels() as f64;
        let over_view = self.cursor.0 >= panel;
        // Input is what makes a frame: anything but a bare cursor move over the 3D view (the
        // panel needs its hover highlights; the view changes only while dragging).
        let redraw = match &event {
            WindowEvent::RedrawRequested => false,
            WindowEvent::CursorMoved { position, .. } => self.controls.dragging() || position.x < panel || !over_view,
            _ => true,
        };
        if redraw {
            self.refreshing = false;
            self.window.request_redraw();
        }
        if let WindowEvent::CursorMoved { position, .. } = &event {
            self.cursor = (position.x, position.y);
        }
        // A split's divider takes the mouse near it; the rest of the view turns the camera.
        if self.divider_event(&event, panel, over_view) {
            return Ok(());
        }
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => self.resize(size),
            WindowEvent::ScaleFactorChanged { .. } => self.resize(self.window_size),
            WindowEvent::RedrawRequested => self.redraw()?,
            WindowEvent::DroppedFile(path) => self.drop_file(path),
            WindowEvent::KeyboardInput {
                event: KeyEvent { physical_key: PhysicalKey::Code(key), state, repeat, .. },
                ..
            } if !self.egui.egui_ctx().text_edit_focused() => {
                // Every key goes through the fly controls first (they track what is held); the
                // rest act on a fresh press. Not a match guard: `fly_key` changes state.
                let taken = self.controls.fly_key(key, state);
                if !taken && state == ElementState::Pressed && !repeat {
                    self.key(event_loop, key);
                }
            }
            WindowEvent::CursorMoved { position, .. } => {
                let height = self.renderer.size().1;
                self.controls.moved(&mut self.camera, position.x, position.y, height);
            }
            WindowEvent::MouseInput { button, state, .. } => {
                self.controls.button(button, state, over_view && !response.consumed);
            }
            WindowEvent::MouseWheel { delta, .. } if over_view && !response.consumed => {
                self.controls.wheel(&mut self.camera, delta);
            }
            _ => {}
        }
        Ok(())
    }

    pub(super) fn resize(&mut self, size: PhysicalSize<u32>) {
        self.window_size = size;
        // A frame of the old size is dropped unseen: the surface is configured anew.
        if self.pending.take().is_some() {
            self.redraw_wanted = true;
        }
        // A minimised window is 0x0: keep everything as it is until it comes back.
        if size.width == 0 || size.height == 0 {
            return;
        }
        // A window larger than the adapter's largest texture draws into its top-left part, and
        // says so once, instead of failing every frame.
        let max = self.gpu.device.limits().max_texture_dimension_2d;
        let size = PhysicalSize::new(size.width.min(max), size.height.min(max));
        if (size.width == max || size.height == max) && !self.told_too_large {
            self.told_too_large = true;
            self.panel.say(
                format!(
                    "the window is larger than this adapter's largest texture ({max}); drawing {}x{} of it",
                    size.width, size.height
                ),
                true,
            );
        }
        self.config.width = size.width;
        self.config.height = size.height;
        self.surface.configure(&self.gpu.device, &self.config);
        let (w, h) = Self::view_size(size, self.window.scale_factor() as f32);
        if let Err(e) = self.renderer.resize(&self.gpu, w, h) {
            self.panel.say(e.to_string(), true);
        }
    }
}
