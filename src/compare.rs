//! The labelled comparison image: the four modes side by side (2x2), each with a caption band
//! naming the mode and its key settings. Text is drawn with egui's bundled Ubuntu font.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use image::{Rgba, RgbaImage};

use crate::render::Renderer;

/// The caption of the panel `renderer` just rendered: the mode and its key, then the settings and
/// the plan that shaped it.
pub fn caption(renderer: &Renderer, sky: &str, lights: usize) -> Vec<String> {
    let (s, radius) = (&renderer.settings, renderer.radius());
    let mut lines = vec![format!("{}  [{}]", s.mode.title(), s.mode.key())];
    if !s.mode.declaration().runs_sampling() {
        let light = s.knobs.variant.decl().composite.label();
        lines.push(format!("{light} + point lights, no occlusion"));
    } else {
        let blur = if s.knobs.blur { "blurred" } else { "no blur" };
        let half = if s.knobs.half_resolution { " at half res" } else { "" };
        let frames = if s.accumulates() { format!(", {} frames", s.knobs.accumulate) } else { String::new() };
        lines.push(format!("{}, {}{half}, radius {radius:.3}, {blur}{frames}", s.knobs.variant, s.knobs.count_label()));
    }
    // The far side layer, where the plan draws it, and its sky.
    let plan = renderer.plan();
    let far = match (plan.far_side, plan.has(crate::render::modes::Step::FAR_SKY)) {
        (true, true) => ", far side and its sky",
        (true, false) => ", far side",
        _ => "",
    };
    lines.push(format!("sky {sky}, {lights} lights, ambient {}{far}", s.ambient));
    lines
}

/// Writes `text` into `image` with its top-left corner at (`x`, `y`), `size` pixels high.
pub fn draw_text(image: &mut RgbaImage, x: f32, y: f32, size: f32, color: [u8; 3], text: &str) {
    draw_text_within(image, (x, y), f32::INFINITY, (size, color), text);
}

/// The width `text` takes at `size` pixels high.
fn text_width(size: f32, text: &str) -> f32 {
    let font = FontRef::try_from_slice(epaint_default_fonts::UBUNTU_LIGHT).expect("egui's bundled font parses");
    let scaled = font.as_scaled(PxScale::from(size));
    let mut previous = None;
    let mut width = 0.0;
    for ch in text.chars() {
        let id = font.glyph_id(ch);
        if let Some(prev) = previous {
            width += scaled.kern(prev, id);
        }
        width += scaled.h_advance(id);
        previous = Some(id);
    }
    width
}

/// [`draw_text`] cut to `width` pixels: a line wider than that ends with "…" where it fits, so
/// a caption never runs into its neighbour's.
pub fn draw_text_within(
    image: &mut RgbaImage,
    (x, y): (f32, f32),
    width: f32,
    (size, color): (f32, [u8; 3]),
    text: &str,
) {
    let mut shown = text.to_owned();
    if text_width(size, text) > width {
        let mut kept: Vec<char> = text.chars().collect();
        shown.clear();
        while !kept.is_empty() {
            kept.pop();
            let candidate: String = kept.iter().collect::<String>().trim_end().to_owned() + "…";
            if text_width(size, &candidate) <= width {
                shown = candidate;
                break;
            }
        }
    }
    let font = FontRef::try_from_slice(epaint_default_fonts::UBUNTU_LIGHT).expect("egui's bundled font parses");
    let scaled = font.as_scaled(PxScale::from(size));
    let mut caret = x;
    let mut previous = None;
    for ch in shown.chars() {
        let id = font.glyph_id(ch);
        if let Some(prev) = previous {
            caret += scaled.kern(prev, id);
        }
        let glyph = id.with_scale_and_position(PxScale::from(size), ab_glyph::point(caret, y + scaled.ascent()));
        caret += scaled.h_advance(id);
        previous = Some(id);
        let Some(outline) = font.outline_glyph(glyph) else { continue };
        let bounds = outline.px_bounds();
        outline.draw(|gx, gy, coverage| {
            let (px, py) = (bounds.min.x as i64 + gx as i64, bounds.min.y as i64 + gy as i64);
            if px < 0 || py < 0 || px >= image.width() as i64 || py >= image.height() as i64 {
                return;
            }
            let pixel = image.get_pixel_mut(px as u32, py as u32);
            for (channel, &ink) in pixel.0.iter_mut().zip(&color) {
                *channel = (*channel as f32 * (1.0 - coverage) + ink as f32 * coverage).round() as u8;
            }
        });
    }
}

/// A 2x2 grid of equally sized `panels`, each captioned with its lines of text below it.
pub fn grid(panels: &[(Vec<String>, RgbaImage)]) -> RgbaImage {
    let (w, h) = panels.first().map_or((1, 1), |(_, img)| img.dimensions());
    let text_size = (h as f32 / 22.0).clamp(11.0, 28.0);
    let caption =
        (text_size * 1.25 * panels.iter().map(|(l, _)| l.len()).max().unwrap_or(1) as f32 + text_size * 0.6) as u32;
    let gap = 4;
    let columns = 2u32.min(panels.len() as u32).max(1);
    let rows = (panels.len() as u32).div_ceil(columns);
    let mut out = RgbaImage::from_pixel(
        columns * w + (columns + 1) * gap,
        rows * (h + caption) + (rows + 1) * gap,
        Rgba([24, 24, 28, 255]),
    );
    for (i, (lines, image)) in panels.iter().enumerate() {
        let (col, row) = (i as u32 % columns, i as u32 / columns);
        let (x, y) = (gap + col * (w + gap), gap + row * (h + caption + gap));
        image::imageops::replace(&mut out, image, x as i64, y as i64);
        for (k, line) in lines.iter().enumerate() {
            let (size, color) =
                if k == 0 { (text_size * 1.1, [255, 255, 255]) } else { (text_size * 0.9, [190, 190, 200]) };
            let at = (x as f32 + 6.0, (y + h) as f32 + 3.0 + k as f32 * text_size * 1.25);
            draw_text_within(&mut out, at, w as f32 - 12.0, (size, color), line);
        }
    }
    out
}

/// `top` over `base`, where `top` is opaque: `top` scaled to `base`'s size first (each pixel of
/// `base` takes the `top` pixel under its centre). The viewer's truth and error views on a frame.
pub fn overlay(base: &RgbaImage, top: &RgbaImage) -> RgbaImage {
    let (w, h) = base.dimensions();
    let (tw, th) = top.dimensions();
    RgbaImage::from_fn(w, h, |x, y| {
        let tx = (((x as u64 * 2 + 1) * tw as u64) / (2 * w as u64)).min(tw as u64 - 1) as u32;
        let ty = (((y as u64 * 2 + 1) * th as u64) / (2 * h as u64)).min(th as u64 - 1) as u32;
        let t = *top.get_pixel(tx, ty);
        if t[3] == 255 {
            t
        } else {
            *base.get_pixel(x, y)
        }
    })
}

/// `left`'s pixels left of the divider at `divider` (a share of the width, the column
/// `round(divider · width)` the first of the right) and `right`'s from there on.
pub fn split(left: &RgbaImage, right: &RgbaImage, divider: f32) -> RgbaImage {
    let (w, h) = left.dimensions();
    let column = (divider.clamp(0.0, 1.0) * w as f32).round() as u32;
    RgbaImage::from_fn(w, h, |x, y| if x < column { *left.get_pixel(x, y) } else { *right.get_pixel(x, y) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_split_is_each_image_on_its_side_and_an_overlay_covers_only_where_it_is_opaque() {
        let (red, blue) = (
            RgbaImage::from_pixel(10, 4, Rgba([255, 0, 0, 255])),
            RgbaImage::from_pixel(10, 4, Rgba([0, 0, 255, 255])),
        );
        let both = split(&red, &blue, 0.3);
        assert!((0..4).all(|y| (0..3).all(|x| both.get_pixel(x, y) == red.get_pixel(x, y))));
        assert!((0..4).all(|y| (3..10).all(|x| both.get_pixel(x, y) == blue.get_pixel(x, y))));
        // A 5x2 overlay, opaque in its left half, over a 10x4 image.
        let top = RgbaImage::from_fn(5, 2, |x, _| if x < 2 { Rgba([0, 255, 0, 255]) } else { Rgba([0, 0, 0, 0]) });
        let over = overlay(&red, &top);
        assert_eq!(over.get_pixel(0, 0), &Rgba([0, 255, 0, 255]));
        assert_eq!(over.get_pixel(3, 3), &Rgba([0, 255, 0, 255]));
        assert_eq!(over.get_pixel(4, 0), red.get_pixel(4, 0));
        assert_eq!(over.get_pixel(9, 3), red.get_pixel(9, 3));
    }

    #[test]
    fn a_caption_wider_than_its_panel_ends_within_it() {
        let line = "march, 2 slices × 16 steps at half res, radius 0.303, blurred, 16 frames";
        let inked = |width: f32| {
            let mut image = RgbaImage::from_pixel(400, 20, Rgba([0, 0, 0, 255]));
            draw_text_within(&mut image, (2.0, 2.0), width, (12.0, [255, 255, 255]), line);
            (0..400).filter(|&x| (0..20).any(|y| image.get_pixel(x, y).0[0] > 0)).max().unwrap_or(0)
        };
        // Unbounded, the line runs to about 350 pixels; within 100 it stops there, with its "…".
        assert!(inked(f32::INFINITY) > 300);
        let cut = inked(100.0);
        assert!((80..=102).contains(&cut), "ink to x = {cut}");
    }
}
