//! The split view's second renderer: the mode right of the divider drawn live, with the same
//! settings and camera as the view, into a texture the panel shows there; and the divider the
//! mouse drags.

use winit::event::{ElementState, MouseButton, WindowEvent};

use super::truth_ui::{Display, Side};
use super::view_state::SecondView;
use super::Viewer;
use crate::headless::capture::capture_settled;
use crate::render::Renderer;
use crate::scene::OrbitCamera;
use crate::Result;

impl Viewer {
    /// Draws the image right of a split's divider into its texture, in `encoder`, when the split
    /// is between two modes (the second renderer made, or made anew, as needed).
    pub(super) fn encode_second(&mut self, encoder: &mut wgpu::CommandEncoder) -> Result<()> {
        let camera = self.view_camera();
        if self.second_for_display()? {
            let second = self.split.second.as_mut().expect("the display's second renderer");
            second.renderer.encode(&self.gpu, encoder, &camera, &second.view);
        }
        Ok(())
    }

    /// The second renderer as the display wants it now: made (or made anew at the view's size)
    /// where the split is between two modes, with the view's settings in the right side's mode;
    /// forgotten otherwise. Drawing and F12 both take it from here, so a screenshot taken before
    /// the next frame is drawn already shows the side just chosen. Whether there is one.
    fn second_for_display(&mut self) -> Result<bool> {
        let Display::Split(Side::Mode(mode)) = self.panel.truth.display else {
            self.drop_second();
            return Ok(false);
        };
        let size = self.renderer.size();
        let settings = crate::render::Settings { mode, ..self.renderer.settings };
        if self.split.second.as_ref().is_none_or(|s| s.renderer.size() != size) {
            self.drop_second();
            let renderer = Renderer::new(&self.gpu, &self.scene, &self.sky, size, self.config.format, settings)?;
            let texture = self.gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some("viewer_split_right"),
                size: wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: self.config.format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            });
            let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
            let id = self.egui_renderer.register_native_texture(&self.gpu.device, &view, wgpu::FilterMode::Nearest);
            self.split.second = Some(SecondView { renderer, view, id });
        }
        if let Some(second) = &mut self.split.second {
            second.renderer.settings = settings;
        }
        Ok(true)
    }

    /// Forgets the second renderer (its scene, sky or lights are no longer the view's).
    pub(super) fn drop_second(&mut self) {
        if let Some(second) = self.split.second.take() {
            self.egui_renderer.free_texture(&second.id);
        }
    }

    /// Whether the second renderer still averages frames of a still view.
    pub(super) fn second_converging(&self) -> bool {
        self.split.second.as_ref().is_some_and(|s| s.renderer.converging())
    }

    /// The right side's mode as a settled image of the view, where the split is between two
    /// modes: the side chosen now, even if no frame has drawn it yet.
    pub(super) fn capture_second(&mut self, camera: &OrbitCamera) -> Result<Option<image::RgbaImage>> {
        if !self.second_for_display()? {
            return Ok(None);
        }
        let second = self.split.second.as_mut().expect("the display's second renderer");
        capture_settled(&self.gpu, &mut second.renderer, camera).map(Some)
    }

    /// The divider's share of the mouse: a press within a few pixels of it takes it, a move then
    /// drags it, the release lets go. Whether `event` was the divider's.
    pub(super) fn divider_event(&mut self, event: &WindowEvent, panel: f64, over_view: bool) -> bool {
        let width = self.renderer.size().0.max(1) as f64;
        match event {
            WindowEvent::CursorMoved { position, .. } if self.split.dragging => {
                self.panel.truth.divider = ((position.x - panel) / width).clamp(0.0, 1.0) as f32;
                true
            }
            WindowEvent::MouseInput { button: MouseButton::Left, state: ElementState::Pressed, .. } => {
                let x = panel + self.panel.truth.divider as f64 * width;
                let near = (self.cursor.0 - x).abs() <= 6.0 * self.window.scale_factor();
                self.split.dragging = matches!(self.panel.truth.display, Display::Split(_)) && near && over_view;
                self.split.dragging
            }
            WindowEvent::MouseInput { state: ElementState::Released, .. } => std::mem::take(&mut self.split.dragging),
            _ => false,
        }
    }
}
