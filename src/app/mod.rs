//! The interactive viewer: a winit window with the renderer on the right and an egui panel on the
//! left. Keys 1-4 switch modes, F12 writes a screenshot of the 3D view, C a labelled comparison
//! of the four modes, F toggles the fly camera, P copies the command of the view, R resets the
//! camera, Escape quits. Skies and models load off the render
//! thread; a failed load shows its message and keeps what was on screen.

mod controls;
mod events;
mod frame;
mod keys;
mod loader;
mod panel_state;
mod split;
pub mod truth;
mod truth_ui;
mod truth_view;
mod ui;
mod view_state;

use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::window::{Window, WindowId};

use crate::gpu::{instance_descriptor, Gpu};
use crate::render::{Renderer, Settings};
use crate::scene::{self, OrbitCamera, Scene, Skybox};
use crate::spec::SceneArgs;
use crate::{Error, Result};
use controls::CameraControls;
use loader::Loader;
use panel_state::{PanelState, PANEL_WIDTH};

/// What the viewer starts with.
pub struct ViewerOptions {
    /// The model, sky, lights, layout and camera asked for (the same flags as `capture`). The
    /// layout also places every model loaded later.
    pub scene: SceneArgs,
    pub settings: Settings,
    /// The preset or quality level the settings came from (`--preset`, `--quality`): the panel
    /// shows its expected time and error.
    pub preset: Option<crate::preset::Preset>,
    /// Window size in physical pixels (panel included).
    pub size: (u32, u32),
    pub screenshot_dir: PathBuf,
}

/// Opens the window and runs until it is closed.
pub fn run(options: ViewerOptions) -> Result<()> {
    // Load before opening the window: a bad file is an error on the command line, not a window.
    let (scene, sky) = options.scene.load()?;
    let camera = options.scene.camera(&scene)?;
    // No display is a setting of the environment, not a GPU fault.
    let event_loop = EventLoop::new().map_err(|e| {
        Error::Setting(format!(
            "cannot open a window ({e}): the viewer needs a display (DISPLAY or WAYLAND_DISPLAY); \
             `ssdo capture` renders without one"
        ))
    })?;
    // Sleep until something happens: an idle viewer draws nothing (see `Viewer::schedule`).
    event_loop.set_control_flow(ControlFlow::Wait);
    let mut app = App { options, start: Some((scene, sky, camera)), viewer: None, failure: None };
    event_loop.run_app(&mut app).map_err(|e| Error::Gpu(format!("window event loop: {e}")))?;
    // Closing does not wait for a frame still on the GPU (seconds, for a heavy scene on a
    // software rasteriser): the process is ending, and the system takes back what it held.
    std::mem::forget(app.viewer.take());
    app.failure.map_or(Ok(()), Err)
}

struct App {
    options: ViewerOptions,
    start: Option<(Scene, Skybox, OrbitCamera)>,
    viewer: Option<Viewer>,
    failure: Option<Error>,
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        let Some((scene, sky, camera)) = self.start.take() else { return };
        match Viewer::new(event_loop, &self.options, scene, sky, camera) {
            Ok(viewer) => self.viewer = Some(viewer),
            Err(e) => {
                self.failure = Some(e);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        // The window was destroyed from outside (its X11 drawable is gone): touch nothing of it
        // again, and quit as if it had been closed.
        if matches!(event, WindowEvent::Destroyed) {
            // As on closing: the frame on the GPU is not waited for.
            std::mem::forget(self.viewer.take());
            event_loop.exit();
            return;
        }
        let Some(viewer) = &mut self.viewer else { return };
        if let Err(e) = viewer.event(event_loop, event) {
            self.failure = Some(e);
            event_loop.exit();
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(viewer) = &mut self.viewer {
            event_loop.set_control_flow(viewer.schedule());
        }
    }
}

struct Viewer {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    gpu: Gpu,
    renderer: Renderer,
    scene: Scene,
    camera: OrbitCamera,
    home: OrbitCamera,
    controls: CameraControls,
    loader: Loader,
    egui: egui_winit::State,
    egui_renderer: egui_wgpu::Renderer,
    panel: PanelState,
    screenshot_dir: PathBuf,
    /// Where models are placed (`--scene`), the first and every one loaded later.
    layout: scene::Layout,
    /// The files on screen (`None`: the defaults) and the scene flags, for the command that
    /// reproduces the view.
    model_path: Option<PathBuf>,
    sky_path: Option<PathBuf>,
    triangles: Option<usize>,
    scale: f32,
    no_surface_maps: bool,
    /// Cursor position in physical pixels.
    cursor: (f64, f64),
    /// When egui asked to be drawn again (an animation, a tooltip's delay).
    egui_repaint: Option<Instant>,
    /// When to draw once more to show the timings of the last frames, which arrive a frame or
    /// two late; a frame drawn for that reason schedules no further one.
    timing_refresh: Option<Instant>,
    /// The frame being drawn was asked for by `timing_refresh` alone.
    refreshing: bool,
    /// The window outgrew the adapter once already (said once, not every frame).
    told_too_large: bool,
    /// When the loading line was last redrawn.
    last_progress: Instant,
    /// The window's size as the last `Resized` said (0x0 while minimised). A frame reads this, never
    /// the window: winit asks the X server for the size and panics if the window was destroyed from
    /// outside while its `Destroyed` event is still queued.
    window_size: PhysicalSize<u32>,
    /// egui's clock (its input is built here, not by `egui_winit`, which asks the window its size).
    started: Instant,
    /// The frame submitted and not yet presented, with when it began: it is presented once the
    /// GPU has finished it (`gpu_busy` false), so the event loop never waits on a slow frame.
    pending: Option<(wgpu::SurfaceTexture, Instant)>,
    /// Whether the GPU is still working on the pending frame (cleared by the queue's callback).
    gpu_busy: Arc<std::sync::atomic::AtomicBool>,
    /// A frame was asked for while one was pending: drawn once that one is presented.
    redraw_wanted: bool,
    /// The sky on screen as the truth traces it.
    sky: Arc<Skybox>,
    /// Bumped whenever the model, the sky or the lights change: the truth is then traced anew.
    scene_number: u64,
    /// The camera of the last frame drawn (its G-buffer's depth is what the truth checks).
    drawn_camera: Option<OrbitCamera>,
    /// The truth of the view (`truth_view.rs`), and the split's right side and divider.
    truth: view_state::TruthState,
    split: view_state::SplitState,
}

/// How often the viewer looks for finished loads while one runs.
const LOAD_POLL: Duration = Duration::from_millis(100);
/// How often the loop looks whether the GPU has finished the pending frame.
const FRAME_POLL: Duration = Duration::from_millis(4);
/// How long after the last frame the timings are shown settled.
const TIMING_REFRESH: Duration = Duration::from_millis(250);

fn timestamp() -> String {
    let now = jiff::Timestamp::now();
    let zoned = now.to_zoned(jiff::tz::TimeZone::UTC);
    format!("{}-{:03}", zoned.strftime("%Y%m%d-%H%M%S"), zoned.millisecond())
}

/// Opens the window at `size`, the device that draws into it, and its surface, configured for
/// the window (at most the adapter's largest texture).
fn open_window(
    event_loop: &ActiveEventLoop,
    size: (u32, u32),
) -> Result<(Arc<Window>, wgpu::Surface<'static>, Gpu, wgpu::SurfaceConfiguration)> {
    let attributes = Window::default_attributes()
        .with_title("ssdo — screen-space directional occlusion")
        .with_inner_size(PhysicalSize::new(size.0, size.1));
    let window =
        Arc::new(event_loop.create_window(attributes).map_err(|e| Error::Gpu(format!("cannot open a window: {e}")))?);
    let descriptor =
        wgpu::InstanceDescriptor::new_with_display_handle_from_env(Box::new(event_loop.owned_display_handle()));
    let instance = wgpu::Instance::new(instance_descriptor(descriptor));
    let surface =
        instance.create_surface(window.clone()).map_err(|e| Error::Gpu(format!("cannot draw into the window: {e}")))?;
    let gpu = Gpu::from_instance(instance, Some(&surface))?;
    let caps = surface.get_capabilities(&gpu.adapter);
    // egui blends in gamma space and wants a non-sRGB target; the tone-map pass then does the
    // sRGB encoding itself (OUTPUT_SRGB = false).
    let format = caps
        .formats
        .iter()
        .copied()
        .find(|f| matches!(f, wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm))
        .or(caps.formats.first().copied())
        .ok_or_else(|| Error::Gpu("the window offers no surface format".into()))?;
    let max = gpu.device.limits().max_texture_dimension_2d;
    let inner = window.inner_size();
    let config = wgpu::SurfaceConfiguration {
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        format,
        width: inner.width.min(max).max(1),
        height: inner.height.min(max).max(1),
        present_mode: wgpu::PresentMode::AutoVsync,
        desired_maximum_frame_latency: 2,
        alpha_mode: caps.alpha_modes.first().copied().unwrap_or(wgpu::CompositeAlphaMode::Auto),
        view_formats: vec![],
        color_space: wgpu::SurfaceColorSpace::Auto,
    };
    surface.configure(&gpu.device, &config);
    Ok((window, surface, gpu, config))
}

impl Drop for Viewer {
    fn drop(&mut self) {
        // Before the surface: it cannot be let go while one of its frames is held.
        drop(self.pending.take());
    }
}

impl Viewer {
    fn new(
        event_loop: &ActiveEventLoop,
        options: &ViewerOptions,
        scene: Scene,
        sky: Skybox,
        camera: OrbitCamera,
    ) -> Result<Self> {
        let (window, surface, gpu, config) = open_window(event_loop, options.size)?;
        let (format, window_size) = (config.format, window.inner_size());
        let size = PhysicalSize::new(config.width, config.height);
        let scale = window.scale_factor() as f32;
        let view = Self::view_size(size, scale);
        let mut renderer = Renderer::new(&gpu, &scene, &sky, view, format, options.settings)?;
        let timing = renderer.enable_timing(&gpu);

        let egui_ctx = egui::Context::default();
        let max_texture = gpu.device.limits().max_texture_dimension_2d as usize;
        let egui =
            egui_winit::State::new(egui_ctx, egui::ViewportId::ROOT, &window, Some(scale), None, Some(max_texture));
        let egui_renderer = egui_wgpu::Renderer::new(&gpu.device, format, egui_wgpu::RendererOptions::default());
        let mut panel = PanelState::new((&options.scene, &options.settings), &gpu, (&scene, &sky), timing);
        if let Some(note) = scene.model.cut_away() {
            panel.say(format!("model {}: {note}", scene.model.name), true);
        }
        if let Some(preset) = &options.preset {
            if let Some(warning) = preset.elsewhere(&panel.adapter, view) {
                panel.say(warning, true);
            }
            panel.preset = Some(preset.clone());
        }
        Ok(Self {
            window,
            surface,
            config,
            gpu,
            renderer,
            scene,
            home: camera,
            camera,
            controls: CameraControls::flying_from_start(options.scene.eye.is_some()),
            loader: Loader::default(),
            egui,
            egui_renderer,
            panel,
            screenshot_dir: options.screenshot_dir.clone(),
            layout: options.scene.layout,
            model_path: options.scene.model.clone(),
            sky_path: options.scene.skybox.clone(),
            triangles: options.scene.triangles,
            scale: options.scene.scale,
            no_surface_maps: options.scene.no_surface_maps,
            cursor: (0.0, 0.0),
            egui_repaint: None,
            timing_refresh: None,
            refreshing: false,
            told_too_large: false,
            last_progress: Instant::now(),
            window_size,
            started: Instant::now(),
            pending: None,
            gpu_busy: Arc::new(std::sync::atomic::AtomicBool::new(false)),
            redraw_wanted: false,
            sky: Arc::new(sky),
            scene_number: 0,
            drawn_camera: None,
            truth: view_state::TruthState::default(),
            split: view_state::SplitState::default(),
        })
    }

    /// The 3D view's size: the window less the panel, at least one pixel each way.
    fn view_size(window: PhysicalSize<u32>, scale: f32) -> (u32, u32) {
        let panel = (PANEL_WIDTH * scale).round() as u32;
        (window.width.saturating_sub(panel).max(1), window.height.max(1))
    }

    fn panel_pixels(&self) -> u32 {
        (PANEL_WIDTH * self.window.scale_factor() as f32).round() as u32
    }
}
