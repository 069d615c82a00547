//! Error metrics: RMSE and PSNR on linear values, FLIP (NVIDIA's perceptual metric) on the
//! displayed image, and the tone curve that turns linear radiance into displayed pixels exactly as
//! the tone-map pass does.

use glam::Vec3;

/// Root mean square of the differences.
pub fn rmse(pairs: impl Iterator<Item = (f32, f32)>) -> f64 {
    let (mut sum, mut n) = (0.0f64, 0usize);
    for (a, b) in pairs {
        sum += (a as f64 - b as f64).powi(2);
        n += 1;
    }
    if n == 0 {
        0.0
    } else {
        (sum / n as f64).sqrt()
    }
}

/// Peak signal-to-noise ratio in dB for an error of `rmse` against a signal peaking at `peak`.
pub fn psnr(rmse: f64, peak: f64) -> f64 {
    if rmse <= 0.0 {
        f64::INFINITY
    } else {
        20.0 * (peak / rmse).log10()
    }
}

/// Linear radiance to a displayed sRGB pixel: exposure, the ACES fit, sRGB (as tonemap.wgsl).
pub fn display(radiance: Vec3, exposure: f32) -> [u8; 3] {
    let aces = |x: f32| {
        let x = (x * exposure).max(0.0);
        if x > 1e4 {
            1.0
        } else {
            ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0)
        }
    };
    let srgb = |c: f32| if c <= 0.0031308 { 12.92 * c } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
    radiance.to_array().map(|c| (srgb(aces(c)) * 255.0 + 0.5).clamp(0.0, 255.0) as u8)
}

/// FLIP between two sRGB images of the same size: the mean error over the pixels `mask` keeps
/// (the surfaces both renderers see; the rest would add zeros) and the error map (magma).
pub fn flip(reference: &image::RgbImage, test: &image::RgbImage, mask: &[bool]) -> (f64, image::RgbImage) {
    let (w, h) = reference.dimensions();
    let reference = nv_flip::FlipImageRgb8::with_data(w, h, reference.as_raw());
    let test = nv_flip::FlipImageRgb8::with_data(w, h, test.as_raw());
    // 67 pixels per degree: a 0.7 m viewing distance from a 0.3 mm-pixel monitor, FLIP's default.
    let error = nv_flip::flip(reference, test, 67.0);
    let values = error.to_vec();
    let (sum, count) = values
        .iter()
        .zip(mask)
        .filter(|(_, keep)| **keep)
        .fold((0.0f64, 0usize), |(s, n), (v, _)| (s + *v as f64, n + 1));
    let mean = if count == 0 { 0.0 } else { sum / count as f64 };
    let map = error.apply_color_lut(&nv_flip::magma_lut());
    (mean, image::RgbImage::from_raw(w, h, map.to_vec()).expect("FLIP map has the image's size"))
}
