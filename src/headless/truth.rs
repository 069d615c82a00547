//! The ray-traced truth of the view a capture renders, and each mode's error against it
//! (`ssdo capture --truth`). The truth and the errors are the report's own
//! (`report/measure.rs`): the mean of two traces of N rays a pixel on the surfaces the G-buffer
//! shows, HDR and DO RMSE on linear values with the pre-exposure divided out, FLIP on the
//! displayed images, over the pixels both renderers agree on, with the traces' own noise beside
//! them. Only the view is the caller's: any camera, model, sky and setting.

use glam::Vec3;
use image::RgbaImage;

use super::capture::capture;
use super::readback::read_depth;
use crate::gpu::Gpu;
use crate::reference::Reference;
use crate::render::{Mode, Renderer};
use crate::report::measure::{Frame, Truth, TruthSource};
use crate::report::metrics;
use crate::scene::{OrbitCamera, Scene, Skybox};
use crate::Result;

/// The truth of one view, traced.
pub struct ViewTruth {
    truth: Truth,
    /// The constant ambient radiance the truth and the frames share.
    ambient: f32,
    pub rays_per_pixel: u32,
    pub seconds: f64,
}

/// One mode's frame against the truth.
pub struct ModeError {
    pub mode: Mode,
    pub hdr_rmse: f64,
    /// `None` where the mode computes no directional occlusion.
    pub do_rmse: Option<f64>,
    pub flip: f64,
    /// Each pixel's error (the RMS of its three HDR channels against the truth's); `None` where
    /// nothing is measured (the sky, silhouettes, the lights' cubes).
    pub per_pixel: Vec<Option<f32>>,
}

impl ViewTruth {
    /// Traces the truth of `camera`'s view as `renderer` renders it (its size, lights, sky
    /// scale and ambient): one frame first for the G-buffer's depth, then two traces of
    /// `rays_per_pixel` rays a pixel, the first seeded with `seed`. `tick` is told of each row.
    pub fn trace(
        gpu: &Gpu,
        renderer: &mut Renderer,
        (scene, sky): (&Scene, &Skybox),
        camera: &OrbitCamera,
        (rays_per_pixel, seed): (u32, u64),
        tick: &(dyn Fn() + Sync),
    ) -> Result<Self> {
        let started = std::time::Instant::now();
        capture(gpu, renderer, camera)?;
        let depth = read_depth(gpu, &renderer.targets().depth().texture)?;
        let base = renderer.settings;
        let source = TruthSource::of_view(scene, (sky, &sky.name), renderer.size(), (rays_per_pixel, seed), &base);
        let truth = source.trace(camera, &depth, renderer.radius(), tick)?;
        Ok(Self { truth, ambient: base.ambient, rays_per_pixel, seconds: started.elapsed().as_secs_f64() })
    }

    /// The truth of two traces of `rays_per_pixel` rays each (`a`, `b`: the viewer's rounds),
    /// with `ambient`; `sky` names the sky and gives its peak for the error when the truth
    /// overflows.
    pub fn from_traces(
        (a, b): (&Reference, &Reference),
        ambient: f32,
        sky: &Skybox,
        rays_per_pixel: u32,
        seconds: f64,
    ) -> Result<Self> {
        let truth = Truth::from_traces(a, b, ambient, &sky.name, sky.max_value())?;
        Ok(Self { truth, ambient, rays_per_pixel, seconds })
    }

    /// The HDR RMSE between this truth and `other` (of the same view) over the pixels both
    /// measure: two estimates of one image differ by about √2 of their noise.
    pub fn rmse_against(&self, other: &ViewTruth) -> f64 {
        let (a, b) = (&self.truth.reference, &other.truth.reference);
        let both = self.truth.valid.iter().filter(|&&i| b.valid[i]);
        metrics::rmse(both.flat_map(|&i| {
            let (x, y) = (a.radiance(i, self.ambient), b.radiance(i, other.ambient));
            (0..3).map(move |c| (x[c], y[c]))
        }))
    }

    /// The truth's size.
    pub fn size(&self) -> (u32, u32) {
        (self.truth.reference.width, self.truth.reference.height)
    }

    /// The truth displayed at `exposure` where it is measured, transparent elsewhere (the view
    /// under it shows there: the sky, the lights' cubes, silhouettes).
    pub fn overlay(&self, exposure: f32) -> RgbaImage {
        let (w, h) = self.size();
        let mut image = RgbaImage::new(w, h);
        for &i in &self.truth.valid {
            let [r, g, b] = metrics::display(self.truth.reference.radiance(i, self.ambient), exposure);
            image.put_pixel(i as u32 % w, i as u32 / w, image::Rgba([r, g, b, 255]));
        }
        image
    }

    /// The truth's own noise: the HDR RMSE of the mean of its two traces (an error below it is
    /// not measured).
    pub fn noise_hdr(&self) -> f64 {
        self.truth.noise.hdr
    }

    /// The pixels measured, and all of the view's.
    pub fn pixels(&self) -> (usize, usize) {
        (self.truth.valid.len(), self.truth.reference.valid.len())
    }

    /// The truth displayed as `gpu_image` is (the same exposure and tone curve), the GPU's own
    /// pixels where nothing is measured.
    pub fn image(&self, gpu_image: &RgbaImage, exposure: f32) -> RgbaImage {
        crate::compare::overlay(gpu_image, &self.overlay(exposure))
    }

    /// The frame `renderer` has just drawn in `mode` (as `image`, displayed) against the truth,
    /// with the HDR image kept (`Renderer::keep_hdr`).
    pub fn measure(&self, gpu: &Gpu, renderer: &Renderer, mode: Mode, image: &RgbaImage) -> Result<ModeError> {
        let frame = Frame::read(gpu, renderer, mode)?;
        let errors = frame.errors(&self.truth, self.ambient);
        let gpu_rgb = image::DynamicImage::ImageRgba8(image.clone()).to_rgb8();
        let truth_rgb = self.truth.displayed(&gpu_rgb, self.ambient, renderer.settings.exposure);
        let (flip, _) = metrics::flip(&truth_rgb, &gpu_rgb, &self.truth.reference.valid);
        let mut per_pixel = vec![None; frame.hdr.len()];
        for &i in &self.truth.valid {
            let difference: Vec3 = frame.hdr[i] - self.truth.reference.radiance(i, self.ambient);
            per_pixel[i] = Some((difference.length_squared() / 3.0).sqrt());
        }
        Ok(ModeError { mode, hdr_rmse: errors.hdr_rmse, do_rmse: errors.do_rmse, flip, per_pixel })
    }
}

/// What `capture --truth` adds to a capture: the lines it prints, its figures as JSON, and the
/// truth's panel of `compare.png`.
pub struct Outputs {
    pub lines: Vec<String>,
    pub json: serde_json::Value,
    pub panel: (Vec<String>, RgbaImage),
}

impl ViewTruth {
    /// Stages `truth.png` (the truth over `image`, a mode's capture, at its `exposure`) and each
    /// of `errors`' map (`error_<mode>.png`) into `batch` in `out`; what to print and show.
    pub fn outputs(
        &self,
        errors: &[ModeError],
        (image, exposure): (&RgbaImage, f32),
        out: &std::path::Path,
        batch: &mut crate::output::Batch,
    ) -> Result<Outputs> {
        use crate::output::png_bytes;
        let path = out.join("truth.png");
        let truth = self.image(image, exposure);
        batch.stage(&path, &png_bytes(&path, &truth)?)?;
        for (error, map) in errors.iter().zip(error_maps(errors, self.size())) {
            let path = out.join(format!("error_{}.png", error.mode.name()));
            batch.stage(&path, &png_bytes(&path, &map)?)?;
        }
        let (measured, all) = self.pixels();
        let (rays, noise) = (self.rays_per_pixel, self.noise_hdr());
        let mut lines = vec![format!(
            "the truth: 2 × {rays} rays a pixel in {:.1} s, noise floor HDR {noise:.4}, {measured} of {all} pixels measured",
            self.seconds
        )];
        for e in errors {
            // An error within twice the truth's own noise is mostly the truth's.
            let noisy = if e.hdr_rmse < 2.0 * noise { " (within twice the truth's noise: raise --spp)" } else { "" };
            lines.push(format!("{:>5} against the truth: {}{noisy}", e.mode.name(), e.summary()));
        }
        let modes: serde_json::Map<String, serde_json::Value> =
            errors.iter().map(|e| (e.mode.name().to_string(), e.json())).collect();
        let json = serde_json::json!({
            "rays_per_pixel": rays, "noise_hdr": noise, "pixels_measured": measured, "modes": modes
        });
        Ok(Outputs { lines, json, panel: (self.caption(), truth) })
    }

    /// The truth's caption in a comparison.
    pub fn caption(&self) -> Vec<String> {
        let (rays, noise) = (self.rays_per_pixel, self.noise_hdr());
        vec!["Truth (ray traced)".to_string(), format!("2 × {rays} rays a pixel, noise floor HDR {noise:.4}")]
    }
}

impl ModeError {
    /// "HDR RMSE 0.0197, DO RMSE 0.0307, FLIP 0.0512".
    pub fn summary(&self) -> String {
        let directional = self.do_rmse.map_or_else(String::new, |d| format!(", DO RMSE {d:.4}"));
        format!("HDR RMSE {:.4}{directional}, FLIP {:.4}", self.hdr_rmse, self.flip)
    }

    pub fn json(&self) -> serde_json::Value {
        serde_json::json!({ "hdr_rmse": self.hdr_rmse, "do_rmse": self.do_rmse, "flip": self.flip })
    }
}

/// The error of each of `errors` as a heat map of `size` (magma, as FLIP's maps; dark grey where
/// nothing is measured) over one shared scale, the largest 99th percentile of the modes' pixel
/// errors, so the maps compare; a colour bar with the scale's numbers is drawn under each.
pub fn error_maps(errors: &[ModeError], size: (u32, u32)) -> Vec<RgbaImage> {
    let scale = error_scale(errors);
    errors.iter().map(|e| heat_map_with_bar(&e.per_pixel, size, scale)).collect()
}

/// The scale the maps of `errors` share: the largest 99th percentile of their pixel errors.
pub fn error_scale(errors: &[ModeError]) -> f32 {
    errors.iter().map(|e| percentile(&e.per_pixel, 0.99)).fold(0.0f32, f32::max).max(1e-6)
}

/// The `q` quantile of the measured values (0 without any).
fn percentile(values: &[Option<f32>], q: f64) -> f32 {
    let mut kept: Vec<f32> = values.iter().flatten().copied().filter(|v| v.is_finite()).collect();
    if kept.is_empty() {
        return 0.0;
    }
    kept.sort_by(f32::total_cmp);
    kept[((kept.len() - 1) as f64 * q).round() as usize]
}

/// `t` (each in [0, 1]) in magma, as FLIP's maps, `width` x `height`.
fn magma(t: &[f32], width: u32, height: u32) -> image::RgbImage {
    let mapped = nv_flip::FlipImageFloat::with_data(width, height, t).apply_color_lut(&nv_flip::magma_lut()).to_vec();
    image::RgbImage::from_raw(width, height, mapped).expect("the LUT keeps the image's size")
}

/// The errors `values` of a `w` x `h` view as a heat map: magma from 0 to `scale`, dark grey
/// where nothing is measured.
pub fn heat_map(values: &[Option<f32>], (w, h): (u32, u32), scale: f32) -> RgbaImage {
    let t: Vec<f32> = values.iter().map(|v| v.map_or(0.0, |e| (e / scale).clamp(0.0, 1.0))).collect();
    let map = magma(&t, w, h);
    RgbaImage::from_fn(w, h, |x, y| match values[(y * w + x) as usize] {
        Some(_) => {
            let p = map.get_pixel(x, y);
            image::Rgba([p[0], p[1], p[2], 255])
        }
        None => image::Rgba([40, 40, 40, 255]),
    })
}

/// The heat map's colour bar, `width` pixels from 0 to the scale.
pub fn colour_bar(width: u32) -> RgbaImage {
    let ramp: Vec<f32> = (0..width).map(|x| x as f32 / (width - 1).max(1) as f32).collect();
    image::DynamicImage::ImageRgb8(magma(&ramp, width, 1)).to_rgba8()
}

/// One heat map with its colour bar and the scale's numbers under it.
fn heat_map_with_bar(values: &[Option<f32>], (w, h): (u32, u32), scale: f32) -> RgbaImage {
    let bar = (h / 8).clamp(10, 40);
    let mut out = RgbaImage::from_pixel(w, h + bar, image::Rgba([24, 24, 28, 255]));
    image::imageops::replace(&mut out, &heat_map(values, (w, h), scale), 0, 0);
    // The ramp in the top half of the band, its ends' numbers under it.
    let ramp = colour_bar(w);
    for x in 0..w {
        for y in h + 1..h + bar / 2 {
            out.put_pixel(x, y, *ramp.get_pixel(x, 0));
        }
    }
    let text = (bar as f32 / 2.0).max(6.0);
    let label = format!("HDR error 0 … {scale:.3}");
    crate::compare::draw_text(&mut out, 2.0, (h + bar / 2) as f32, text, [220, 220, 220], &label);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_maps_share_one_scale_and_leave_what_is_not_measured_grey() {
        let error = |mode, values: Vec<Option<f32>>| ModeError {
            mode,
            hdr_rmse: 0.0,
            do_rmse: None,
            flip: 0.0,
            per_pixel: values,
        };
        let small = error(Mode::Off, vec![Some(0.0), Some(0.1), None, Some(0.1)]);
        let large = error(Mode::Ssdo, vec![Some(0.0), Some(0.4), None, Some(0.4)]);
        let maps = error_maps(&[small, large], (2, 2));
        assert_eq!(maps[0].dimensions(), (2, 2 + 10));
        // The same error is the same colour in both maps; a larger one is brighter.
        let luminance = |p: &image::Rgba<u8>| p[0] as u32 + p[1] as u32 + p[2] as u32;
        assert_eq!(maps[0].get_pixel(0, 0), maps[1].get_pixel(0, 0));
        assert!(luminance(maps[1].get_pixel(1, 0)) > luminance(maps[0].get_pixel(1, 0)));
        assert_eq!(maps[0].get_pixel(0, 1), &image::Rgba([40, 40, 40, 255]));
        assert!((percentile(&[Some(3.0), None, Some(1.0), Some(2.0)], 0.5) - 2.0).abs() < 1e-6);
    }
}
