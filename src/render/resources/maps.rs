//! The materials' maps as the G-buffer pass binds them: each image uploaded once, a diffuse
//! map with its specular map packed into its alpha, and white stand-ins for a missing map.

use std::sync::Arc;

use super::scene::{upload_texture, SpecularMap};
use crate::gpu::Gpu;
use crate::scene::model::{Material, TextureImage};

/// The diffuse map's colour with the specular map's red as its alpha (two maps of one size).
fn pack_specular(diffuse: &TextureImage, specular: &TextureImage) -> TextureImage {
    let mut rgba = diffuse.rgba.to_vec();
    for (texel, spec) in rgba.chunks_exact_mut(4).zip(specular.rgba.chunks_exact(4)) {
        texel[3] = spec[0];
    }
    TextureImage { width: diffuse.width, height: diffuse.height, rgba: Arc::new(rgba) }
}

/// The materials' maps as a scene's upload makes them: each image uploaded once (by its pixels'
/// identity and format), the diffuse maps with a specular map packed in (by the two maps'
/// identities), the white stand-ins of a missing map, and the bytes uploaded so far.
pub struct MaterialMaps {
    uploaded: std::collections::HashMap<(usize, wgpu::TextureFormat), wgpu::TextureView>,
    packed: std::collections::HashMap<(usize, usize), TextureImage>,
    white_srgb: wgpu::TextureView,
    white_linear: wgpu::TextureView,
    /// The bytes uploaded so far (maps and, as the G-buffer pass adds them, parameters).
    pub bytes: u64,
}

impl MaterialMaps {
    pub fn new(gpu: &Gpu) -> Self {
        let white = TextureImage { width: 1, height: 1, rgba: Arc::new(vec![255; 4]) };
        let (white_srgb, _) =
            upload_texture(gpu, "material_default_diffuse", &white, wgpu::TextureFormat::Rgba8UnormSrgb);
        let (white_linear, _) =
            upload_texture(gpu, "material_default_specular", &white, wgpu::TextureFormat::Rgba8Unorm);
        let (uploaded, packed) = Default::default();
        Self { uploaded, packed, white_srgb, white_linear, bytes: 0 }
    }

    /// The view of `image` in `format` (material `name`'s `kind` of map), uploaded unless it was;
    /// the white stand-in of that format without one.
    fn view(
        &mut self,
        gpu: &Gpu,
        name: &str,
        image: Option<&TextureImage>,
        kind: &str,
        format: wgpu::TextureFormat,
    ) -> wgpu::TextureView {
        let Some(image) = image else {
            return if format == wgpu::TextureFormat::Rgba8UnormSrgb { &self.white_srgb } else { &self.white_linear }
                .clone();
        };
        let key = (std::sync::Arc::as_ptr(&image.rgba) as usize, format);
        if let Some(view) = self.uploaded.get(&key) {
            return view.clone();
        }
        let (view, size) = upload_texture(gpu, &format!("material_{name}_{kind}"), image, format);
        self.bytes += size;
        self.uploaded.insert(key, view.clone());
        view
    }

    /// Material `m`'s four maps: diffuse (with the specular map in its alpha where the two are
    /// one size), specular, normals and coverage, each uploaded once or a white stand-in.
    pub fn of(&mut self, gpu: &Gpu, m: &Material) -> [wgpu::TextureView; 4] {
        let (srgb, linear) = (wgpu::TextureFormat::Rgba8UnormSrgb, wgpu::TextureFormat::Rgba8Unorm);
        let (diffuse, specular) = match (&m.diffuse_map, &m.specular_map, SpecularMap::of(m)) {
            (Some(d), Some(s), SpecularMap::DiffuseAlpha) => {
                let key = (Arc::as_ptr(&d.rgba) as usize, Arc::as_ptr(&s.rgba) as usize);
                let both = self.packed.entry(key).or_insert_with(|| pack_specular(d, s)).clone();
                (
                    self.view(gpu, &m.name, Some(&both), "diffuse_specular", srgb),
                    self.view(gpu, &m.name, None, "", linear),
                )
            }
            _ => (
                self.view(gpu, &m.name, m.diffuse_map.as_ref(), "diffuse", srgb),
                self.view(gpu, &m.name, m.specular_map.as_ref(), "specular", linear),
            ),
        };
        let normals = self.view(gpu, &m.name, m.normal_map.as_ref().map(|n| &n.image), "normals", linear);
        // sRGB like the colour map it often is (alpha is linear in either), so the two share one
        // upload.
        let mask = m.cutout.as_ref().and_then(|c| c.mask.as_ref());
        let coverage = self.view(gpu, &m.name, mask, "coverage", srgb);
        [diffuse, specular, normals, coverage]
    }
}
