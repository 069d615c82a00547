//! The report's error maps of the default configuration, beside the truth's and the GPU's images.

use std::path::Path;

use crate::{output, reference, Result};

/// Error maps of the default Both configuration: AO error, the two displayed images, FLIP, as
/// PNG files by name (written with the tables, in one set).
pub(super) fn encode(
    out: &Path,
    reference: &reference::Reference,
    ao: &Option<Vec<f32>>,
    ref_image: &image::RgbImage,
    gpu_image: &image::RgbImage,
    flip_map: &image::RgbImage,
) -> Result<Vec<(String, Vec<u8>)>> {
    let (w, h) = (reference.width, reference.height);
    let mut files = Vec::new();
    let mut save = |name: &str, img: &image::RgbImage| -> Result<()> {
        let rgba = image::DynamicImage::ImageRgb8(img.clone()).to_rgba8();
        files.push((name.to_string(), output::png_bytes(&out.join(name), &rgba)?));
        Ok(())
    };
    if let Some(ao) = ao {
        // Signed AO error: red where the GPU is darker than the truth, blue where lighter.
        let map = image::RgbImage::from_fn(w, h, |x, y| {
            let i = (y * w + x) as usize;
            if !reference.valid[i] {
                return image::Rgb([40, 40, 40]);
            }
            let e = ((ao[i] - reference.ao[i]) * 4.0).clamp(-1.0, 1.0);
            let v = (255.0 * e.abs()) as u8;
            if e < 0.0 {
                image::Rgb([255, 255 - v, 255 - v])
            } else {
                image::Rgb([255 - v, 255 - v, 255])
            }
        });
        save("error_ao_both_default.png", &map)?;
        let reference_ao = image::RgbImage::from_fn(w, h, |x, y| {
            let i = (y * w + x) as usize;
            let v = (reference.ao[i].clamp(0.0, 1.0) * 255.0) as u8;
            if reference.valid[i] {
                image::Rgb([v, v, v])
            } else {
                image::Rgb([40, 40, 40])
            }
        });
        save("reference_ao.png", &reference_ao)?;
    }
    save("reference_both_default.png", ref_image)?;
    save("gpu_both_default.png", gpu_image)?;
    save("error_flip_both_default.png", flip_map)?;
    Ok(files)
}
