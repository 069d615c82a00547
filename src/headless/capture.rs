//! Offscreen rendering to an image: the same renderer as the window, drawing into an sRGB
//! texture that is read back.

use super::readback::{output_texture_as, read_texture};
use crate::gpu::Gpu;
use crate::render::Renderer;
use crate::scene::OrbitCamera;
use crate::{Error, Result};

/// The output format of offscreen captures.
pub const CAPTURE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// An offscreen output texture of the renderer's size, in the capture format.
pub fn output_texture(gpu: &Gpu, size: (u32, u32)) -> wgpu::Texture {
    output_texture_as(gpu, size, CAPTURE_FORMAT)
}

/// Renders one frame of the current plan and returns it as an sRGB image. Works with any 8-bit
/// RGBA or BGRA output format (a window's surface format), so the viewer's renderer can capture.
pub fn capture(gpu: &Gpu, renderer: &mut Renderer, camera: &OrbitCamera) -> Result<image::RgbaImage> {
    let size = renderer.size();
    let format = renderer.output_format();
    let texture = output_texture_as(gpu, size, format);
    let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
    let mut encoder =
        gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("capture_encoder") });
    renderer.encode(gpu, &mut encoder, camera, &view);
    gpu.queue.submit([encoder.finish()]);
    let mut bytes = read_texture(gpu, &texture)?;
    match format {
        wgpu::TextureFormat::Rgba8UnormSrgb | wgpu::TextureFormat::Rgba8Unorm => {}
        wgpu::TextureFormat::Bgra8UnormSrgb | wgpu::TextureFormat::Bgra8Unorm => {
            bytes.chunks_exact_mut(4).for_each(|p| p.swap(0, 2))
        }
        other => return Err(Error::Gpu(format!("cannot capture from a {other:?} output"))),
    }
    image::RgbaImage::from_raw(size.0, size.1, bytes)
        .ok_or_else(|| Error::Gpu("readback returned the wrong number of bytes".into()))
}

/// Renders one frame for each camera without reading anything back: the frames an average
/// takes in before the one that is kept.
pub fn render_frames(gpu: &Gpu, renderer: &mut Renderer, cameras: impl IntoIterator<Item = OrbitCamera>) -> Result<()> {
    let texture = output_texture_as(gpu, renderer.size(), renderer.output_format());
    let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
    for camera in cameras {
        let mut encoder =
            gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("accumulate_encoder") });
        renderer.encode(gpu, &mut encoder, &camera, &view);
        gpu.queue.submit([encoder.finish()]);
    }
    gpu.check()
}

/// The converged image of a still camera: the average started anew, and every frame the plan
/// averages (`Renderer::accumulation`) rendered, the last one read back. One frame where the
/// plan does not accumulate.
pub fn capture_converged(gpu: &Gpu, renderer: &mut Renderer, camera: &OrbitCamera) -> Result<image::RgbaImage> {
    capture_path(gpu, renderer, |_| *camera)
}

/// Like [`capture_converged`], with the camera moving: `camera_at(k)` is the camera `k` frames
/// before the last (so `camera_at(0)` is the view of the image returned).
pub fn capture_path(
    gpu: &Gpu,
    renderer: &mut Renderer,
    camera_at: impl Fn(u32) -> OrbitCamera,
) -> Result<image::RgbaImage> {
    capture_path_from(gpu, renderer, 0, camera_at)
}

/// [`capture_path`] with `lead_in` frames more before those the average takes (`camera_at` goes
/// that much further back): where the camera was before a cut.
pub fn capture_path_from(
    gpu: &Gpu,
    renderer: &mut Renderer,
    lead_in: u32,
    camera_at: impl Fn(u32) -> OrbitCamera,
) -> Result<image::RgbaImage> {
    renderer.apply(gpu);
    renderer.reset_history();
    let frames = renderer.accumulation() + lead_in;
    // A frame that averages nothing may still read what the last frame left (the senders' sky
    // from its march): it follows one, as every frame but the viewer's first does.
    let primer = (frames == 1 && !renderer.plan().history.is_empty()).then(|| camera_at(1));
    render_frames(gpu, renderer, primer.into_iter().chain((1..frames).rev().map(&camera_at)))?;
    capture(gpu, renderer, &camera_at(0))
}

/// The still camera's converged image from where the average stands: the frames it still lacks
/// rendered first (the viewer's screenshot, after however many frames it has shown). An average
/// that began while the camera moved starts anew, so the image is [`capture_converged`]'s.
pub fn capture_settled(gpu: &Gpu, renderer: &mut Renderer, camera: &OrbitCamera) -> Result<image::RgbaImage> {
    renderer.apply(gpu);
    if renderer.plan().accumulates() && !renderer.still_average_is_clean(camera) {
        renderer.reset_history();
    }
    let missing = renderer.frames_to_settle(camera);
    render_frames(gpu, renderer, (0..missing).map(|_| *camera))?;
    capture(gpu, renderer, camera)
}
