//! Statistics of the linear buffers a frame produces — AO, DO direct, DO indirect and HDR colour
//! — for `capture --stats` and the stability suite: min, max, mean and the count of non-finite
//! values. DO direct and indirect share one buffer (sky·strength + bounce·strength); each is
//! measured by rendering with the other's strength at 0 (the debug views).

use super::capture::capture_converged;
use super::readback::{read_occlusion, read_rgba16f};
use crate::gpu::Gpu;
use crate::render::{Renderer, View};
use crate::scene::OrbitCamera;
use crate::Result;

#[derive(Clone, Debug, PartialEq)]
pub struct BufferStats {
    pub name: &'static str,
    pub min: f32,
    pub max: f32,
    pub mean: f64,
    pub non_finite: usize,
    pub count: usize,
}

impl BufferStats {
    fn of(name: &'static str, values: impl Iterator<Item = f32>) -> Self {
        let (mut min, mut max, mut sum, mut non_finite, mut count, mut finite) =
            (f32::INFINITY, f32::NEG_INFINITY, 0.0f64, 0, 0, 0);
        for v in values {
            count += 1;
            if v.is_finite() {
                min = min.min(v);
                max = max.max(v);
                sum += v as f64;
                finite += 1;
            } else {
                non_finite += 1;
            }
        }
        let mean = if finite > 0 { sum / finite as f64 } else { 0.0 };
        if finite == 0 {
            (min, max) = (0.0, 0.0);
        }
        Self { name, min, max, mean, non_finite, count }
    }

    pub fn json(&self) -> serde_json::Value {
        serde_json::json!({ "min": self.min, "max": self.max, "mean": self.mean, "non_finite": self.non_finite, "count": self.count })
    }
}

/// Renders the current settings and measures every linear buffer the mode produces, in radiance
/// units (the pre-exposure divided out). The renderer's view is restored afterwards.
pub fn frame_stats(gpu: &Gpu, renderer: &mut Renderer, camera: &OrbitCamera) -> Result<Vec<BufferStats>> {
    let view = renderer.settings.view;
    let result = measure(gpu, renderer, camera);
    renderer.settings.view = view;
    result
}

fn measure(gpu: &Gpu, renderer: &mut Renderer, camera: &OrbitCamera) -> Result<Vec<BufferStats>> {
    let mut stats = Vec::new();
    renderer.settings.view = View::Final;
    capture_converged(gpu, renderer, camera)?;
    let pre = renderer.pre_exposure();
    let decl = *renderer.plan().mode.declaration();
    if let Some(ao) = read_occlusion(gpu, renderer.targets().occlusion(), decl.ambient_occlusion)?.ao {
        stats.push(BufferStats::of("ao", ao.into_iter()));
    }
    let hdr = read_rgba16f(gpu, &renderer.targets().hdr()?.texture)?;
    let hdr_stats = BufferStats::of("hdr", hdr.iter().flat_map(|p| [p[0], p[1], p[2]]).map(|v| v / pre));
    if decl.directional_occlusion {
        for (view, name) in [(View::DoDirect, "do_direct"), (View::DoIndirect, "do_indirect")] {
            renderer.settings.view = view;
            capture_converged(gpu, renderer, camera)?;
            let target = renderer.targets().occlusion().directional.expect("a DO mode has a DO target");
            let values = read_rgba16f(gpu, &target.texture)?;
            stats.push(BufferStats::of(name, values.iter().flat_map(|p| [p[0], p[1], p[2]]).map(|v| v / pre)));
        }
    }
    stats.push(hdr_stats);
    Ok(stats)
}

/// The linear HDR image of the last frame, in radiance units, as 32-bit float RGBA.
pub fn hdr_image(gpu: &Gpu, renderer: &Renderer) -> Result<image::Rgba32FImage> {
    let (w, h) = renderer.size();
    let pre = renderer.pre_exposure();
    let hdr = read_rgba16f(gpu, &renderer.targets().hdr()?.texture)?;
    let data: Vec<f32> = hdr.iter().flat_map(|p| [p[0] / pre, p[1] / pre, p[2] / pre, 1.0]).collect();
    Ok(image::Rgba32FImage::from_raw(w, h, data).expect("HDR readback has the renderer's size"))
}
