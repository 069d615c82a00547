//! The model on the GPU: vertex and index buffers, one draw a material with its bind group and
//! what its pipeline reads (`Features`), and the material maps with their mip chains. The G-buffer pass fills it (`GBufferPass::upload`,
//! which owns the material layout and sampler) and draws it.

use rayon::prelude::*;

use crate::gpu::Gpu;
use crate::scene::model::TextureImage;

/// One draw: a range of indices with a material bind group.
pub(crate) struct Draw {
    pub first_index: u32,
    pub index_count: u32,
    pub bind_group: wgpu::BindGroup,
    /// The pipeline it draws with.
    pub features: Features,
}

/// What a material's pipeline reads besides its constants (the shader's overrides).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Features {
    /// Colour maps (diffuse, specular).
    pub textured: bool,
    /// Where the specular strength's map is: none, its own, or the diffuse map's alpha.
    pub specular: SpecularMap,
    pub normal_mapped: bool,
    pub cut_out: bool,
    /// The scene has the thickness layer's third target (the same for every material of a
    /// scene that has it: the G-buffer pass's attachments are one set).
    pub thickness_layer: bool,
    /// The material is thinner than the scene's default thickness: with the thickness layer, its
    /// fragments write their class and tilt (the others, the default class alone).
    pub thin: bool,
}

/// Where a material's specular map is read from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SpecularMap {
    /// No map: the material's constant strength.
    #[default]
    None,
    /// A texture of its own.
    Own,
    /// The diffuse map's alpha (the specular map's red, packed there at upload: one sample
    /// for both maps, with the same texels and the same mips, since the alpha of an sRGB texture
    /// is linear like the specular map's own format).
    DiffuseAlpha,
}

impl SpecularMap {
    /// Where material `m`'s specular map goes: into its diffuse map's alpha when the two maps
    /// are one size.
    pub fn of(m: &crate::scene::Material) -> Self {
        match (&m.diffuse_map, &m.specular_map) {
            (_, None) => SpecularMap::None,
            (Some(d), Some(s)) if (d.width, d.height) == (s.width, s.height) => SpecularMap::DiffuseAlpha,
            (_, Some(_)) => SpecularMap::Own,
        }
    }

    /// The value of the G-buffer shader's `SPECULAR_MAP` constant.
    pub(crate) fn shader_code(self) -> f64 {
        match self {
            SpecularMap::None => 0.0,
            SpecularMap::Own => 1.0,
            SpecularMap::DiffuseAlpha => 2.0,
        }
    }
}

impl Features {
    /// What material `m` of a model reads; its normal map only where the model has tangents.
    pub fn of(m: &crate::scene::Material, has_tangents: bool) -> Self {
        Self {
            textured: m.is_textured(),
            specular: SpecularMap::of(m),
            normal_mapped: m.normal_map.is_some() && has_tangents,
            cut_out: m.cutout.is_some(),
            thickness_layer: false,
            thin: false,
        }
    }

    /// The pipeline's features with the thickness layer or without it (a thin material's tilt
    /// only with it).
    pub fn with_layer(self, thickness_layer: bool) -> Self {
        Self { thickness_layer, thin: self.thin && thickness_layer, ..self }
    }
}

/// The model on the GPU.
pub struct SceneGpu {
    pub(crate) vertices: wgpu::Buffer,
    pub(crate) indices: wgpu::Buffer,
    /// One per vertex, only where a material has a normal map.
    pub(crate) tangents: Option<wgpu::Buffer>,
    pub(crate) draws: Vec<Draw>,
    /// A material reads colour maps.
    pub textured: bool,
    /// A material reads a normal map: the G-buffer's normals are not the geometry's.
    pub normal_mapped: bool,
    /// A material is thinner than the scene's default thickness (`scene/thickness.rs`).
    pub thin_materials: bool,
    /// The model is smooth-shaded somewhere (`Model::has_smooth_normals`).
    pub smooth_normals: bool,
    pub bytes: u64,
}

/// An upload at least this large is waited for before the next is made.
const LARGE_UPLOAD: usize = 16 << 20;

pub(crate) fn upload_texture(
    gpu: &Gpu,
    label: &str,
    image: &TextureImage,
    format: wgpu::TextureFormat,
) -> (wgpu::TextureView, u64) {
    let max = gpu.device.limits().max_texture_dimension_2d;
    let shrunk;
    let image = if image.width > max || image.height > max {
        log::warn!("{label}: {}x{} exceeds the adapter's {max}; downscaling", image.width, image.height);
        let src = image::RgbaImage::from_raw(image.width, image.height, image.rgba.to_vec())
            .expect("texture size matches its data");
        let scale = max as f32 / image.width.max(image.height) as f32;
        let (w, h) = (((image.width as f32 * scale) as u32).max(1), ((image.height as f32 * scale) as u32).max(1));
        let small = image::imageops::resize(&src, w, h, image::imageops::FilterType::Triangle);
        shrunk = TextureImage { width: w, height: h, rgba: std::sync::Arc::new(small.into_raw()) };
        &shrunk
    } else {
        image
    };
    let level_count = 32 - image.width.max(image.height).leading_zeros();
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d { width: image.width, height: image.height, depth_or_array_layers: 1 },
        mip_level_count: level_count,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    // Level by level, each made from the one above and written before the next is made: the
    // image is never copied whole, and a large level's upload copy is freed before the next is
    // made (on a software adapter the texture, the copies and the model's pixels share the RAM).
    let write = |level: u32, (w, h): (u32, u32), texels: &[u8]| {
        let origin = wgpu::Origin3d::ZERO;
        gpu.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: level,
                origin,
                aspect: wgpu::TextureAspect::All,
            },
            texels,
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(4 * w), rows_per_image: Some(h) },
            wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        );
        if texels.len() >= LARGE_UPLOAD {
            gpu.queue.submit([]);
            // A failed wait only keeps the copy alive longer; errors surface at the next check.
            let _ = gpu.device.poll(wgpu::PollType::wait_indefinitely());
        }
    };
    let mut size = (image.width, image.height);
    let mut bytes = image.rgba.len() as u64;
    write(0, size, &image.rgba);
    let mut level = next_level(&image.rgba, size, format.is_srgb());
    for index in 1..level_count {
        size = ((size.0 / 2).max(1), (size.1 / 2).max(1));
        write(index, size, &level);
        bytes += level.len() as u64;
        if index + 1 < level_count {
            level = next_level(&level, size, format.is_srgb());
        }
    }
    (texture.create_view(&wgpu::TextureViewDescriptor::default()), bytes)
}

/// The full mip chain of an RGBA8 image, level 0 first, down to 1x1: each level the 2x2 box
/// average of the one above (the last row or column repeated where a side is odd), averaged in
/// linear light when the texels are sRGB-encoded (so a minified checker keeps its brightness).
/// Minified textures then read a level of about their on-screen size: no aliasing, and a few
/// cache lines per pixel instead of texels scattered over the whole image.
pub fn mip_chain(image: &TextureImage, srgb: bool) -> Vec<Vec<u8>> {
    let mut levels = vec![image.rgba.to_vec()];
    let (mut w, mut h) = (image.width, image.height);
    while w > 1 || h > 1 {
        let next = next_level(levels.last().expect("level 0 is there"), (w, h), srgb);
        levels.push(next);
        (w, h) = ((w / 2).max(1), (h / 2).max(1));
    }
    levels
}

/// The level below `src` (RGBA8, `w` x `h`) in the chain of [`mip_chain`].
fn next_level(src: &[u8], (w, h): (u32, u32), srgb: bool) -> Vec<u8> {
    let decode: Vec<f32> = (0..256)
        .map(|v| {
            let c = v as f32 / 255.0;
            match srgb {
                false => c,
                true if c <= 0.04045 => c / 12.92,
                true => ((c + 0.055) / 1.055).powf(2.4),
            }
        })
        .collect();
    let encode = |c: f32| -> u8 {
        let c = c.clamp(0.0, 1.0);
        let e = match srgb {
            false => c,
            true if c <= 0.0031308 => c * 12.92,
            true => 1.055 * c.powf(1.0 / 2.4) - 0.055,
        };
        (e * 255.0).round() as u8
    };
    let (w, h) = (w as usize, h as usize);
    let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
    let mut dst = vec![0u8; nw * nh * 4];
    // Rows in parallel: a 8192² map's chain is a quarter of a billion texels.
    dst.par_chunks_mut(nw * 4).enumerate().for_each(|(y, row)| {
        let rows = [(2 * y).min(h - 1), (2 * y + 1).min(h - 1)];
        for x in 0..nw {
            let cols = [(2 * x).min(w - 1), (2 * x + 1).min(w - 1)];
            for c in 0..4 {
                let texel = |yy: usize, xx: usize| src[(yy * w + xx) * 4 + c];
                let sum: f32 = rows
                    .iter()
                    .flat_map(|&yy| cols.iter().map(move |&xx| (yy, xx)))
                    .map(|(yy, xx)| {
                        // Alpha (specular strength) is linear in either format.
                        if c == 3 {
                            texel(yy, xx) as f32 / 255.0
                        } else {
                            decode[texel(yy, xx) as usize]
                        }
                    })
                    .sum();
                let mean = 0.25 * sum;
                row[x * 4 + c] = if c == 3 { (mean * 255.0).round() as u8 } else { encode(mean) };
            }
        }
    });
    dst
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(width: u32, height: u32, texel: impl Fn(u32, u32) -> [u8; 4]) -> TextureImage {
        let mut bytes = Vec::new();
        for y in 0..height {
            for x in 0..width {
                bytes.extend_from_slice(&texel(x, y));
            }
        }
        TextureImage { width, height, rgba: std::sync::Arc::new(bytes) }
    }

    #[test]
    fn the_mip_chain_halves_down_to_one_texel_and_averages_in_linear_light() {
        let checker = image(8, 2, |x, y| if (x + y) % 2 == 0 { [255, 255, 255, 255] } else { [0, 0, 0, 0] });
        let srgb = mip_chain(&checker, true);
        let sizes: Vec<usize> = srgb.iter().map(|l| l.len() / 4).collect();
        assert_eq!(sizes, vec![16, 4, 2, 1], "8x2, 4x1, 2x1, 1x1");
        // Half white, half black is linear 0.5: sRGB 188, not 128; alpha (linear) 128.
        assert_eq!(&srgb[1][..4], &[188, 188, 188, 128]);
        assert_eq!(&srgb[3][..], &[188, 188, 188, 128]);
        let linear = mip_chain(&checker, false);
        assert_eq!(&linear[3][..], &[128, 128, 128, 128]);
        // An odd side repeats its last row and column.
        let odd = mip_chain(&image(3, 3, |x, _| [(x * 100) as u8, 0, 0, 255]), false);
        assert_eq!(odd.len(), 2);
        assert_eq!(&odd[1][..], &[50, 0, 0, 255]);
    }
}
