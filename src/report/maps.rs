//! The report's error maps of the default configuration, beside the truth's and the GPU's images.

use std::path::Path;

use crate::{output, reference, Result};

/// Error maps of the default Both configuration: AO error, DO error, the two displayed images,
/// FLIP, as PNG files by name (written with the tables, in one set). `buffers`: the AO and the DO
/// (rgb, linear) the GPU read back.
pub(super) fn encode(
    out: &Path,
    reference: &reference::Reference,
    (ao, directional): (Option<&[f32]>, Option<&[[f32; 4]]>),
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
        // AO is a fraction: a quarter of it off is the full colour.
        save("error_ao_both_default.png", &signed_map((w, h), &reference.valid, |i| 4.0 * (ao[i] - reference.ao[i])))?;
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
    if let Some(d) = directional {
        // DO is light (sky and bounce, before albedo): its luminance against the truth's, half the
        // truth's mean off the full colour, so the map reads alike under any sky.
        let luminance = |i: usize| reference::luminance(glam::Vec3::new(d[i][0], d[i][1], d[i][2]));
        let valid = (0..reference.valid.len()).filter(|&i| reference.valid[i]);
        let (sum, count) =
            valid.fold((0.0, 0usize), |(s, n), i| (s + reference::luminance(reference.directional(i)), n + 1));
        let scale = 2.0 / (sum / count.max(1) as f32).max(1e-6);
        let error = |i| scale * (luminance(i) - reference::luminance(reference.directional(i)));
        save("error_do_both_default.png", &signed_map((w, h), &reference.valid, error))?;
    }
    save("reference_both_default.png", ref_image)?;
    save("gpu_both_default.png", gpu_image)?;
    save("error_flip_both_default.png", flip_map)?;
    Ok(files)
}

/// A signed error as colour: red where the GPU is darker than the truth, blue where lighter,
/// white where they agree (`error` of a pixel's index, ±1 the full colour); dark grey where no
/// surface is measured (not `valid`).
fn signed_map((w, h): (u32, u32), valid: &[bool], error: impl Fn(usize) -> f32) -> image::RgbImage {
    image::RgbImage::from_fn(w, h, |x, y| {
        let i = (y * w + x) as usize;
        if !valid[i] {
            return image::Rgb([40, 40, 40]);
        }
        let e = error(i).clamp(-1.0, 1.0);
        let v = (255.0 * e.abs()) as u8;
        if e < 0.0 {
            image::Rgb([255, 255 - v, 255 - v])
        } else {
            image::Rgb([255 - v, 255 - v, 255])
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn darker_is_red_lighter_is_blue_and_beyond_one_is_the_full_colour() {
        let errors = [0.0, -0.5, 3.0, f32::NAN];
        let map = signed_map((4, 1), &[true, true, true, false], |i| errors[i]);
        let colours: Vec<[u8; 3]> = map.pixels().map(|p| p.0).collect();
        assert_eq!(colours, [[255, 255, 255], [255, 128, 128], [0, 0, 255], [40, 40, 40]]);
    }
}
