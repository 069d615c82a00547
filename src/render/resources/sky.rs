//! The sky on the GPU: uploaded once per sky as an Rgba16Float cube map with a full mip chain
//! (SSDO and the march read coarser levels to filter the sky over a sample's solid angle). Half
//! floats end at 65504, so a brighter sky is stored divided by a scale that the shaders multiply
//! back in f32. Bind group 2 of the passes that read it.

use crate::gpu::Gpu;
use crate::render::bindings::{sampler_entry, texture_entry};
use crate::scene::Skybox;
use crate::Result;

/// Largest value stored in the half-float cube map.
const HALF_LIMIT: f32 = 60000.0;

/// The sky on the GPU (bind group 2 of the passes that read it).
pub struct SkyGpu {
    pub bind_group: wgpu::BindGroup,
    /// Multiply stored values by this to get radiance.
    pub encode_scale: f32,
    pub mip_levels: u32,
    /// Face size of mip 0.
    pub size: u32,
    pub bytes: u64,
    pub mean: glam::Vec3,
    /// Largest radiance on the sky (before any user scale).
    pub peak: f32,
}

pub fn sky_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("sky_layout"),
        entries: &[texture_entry(0, true, wgpu::TextureViewDimension::Cube), sampler_entry(1)],
    })
}

impl SkyGpu {
    pub fn upload(gpu: &Gpu, layout: &wgpu::BindGroupLayout, sky: &Skybox) -> Result<Self> {
        let max = gpu.device.limits().max_texture_dimension_2d;
        if sky.size > max {
            return Err(crate::Error::Setting(format!(
                "skybox '{}': faces of {0}x{0} exceed this adapter's limit of {max}",
                sky.size
            )));
        }
        let peak = sky.max_value();
        let encode_scale = if peak > HALF_LIMIT { peak / HALF_LIMIT } else { 1.0 };
        let levels = sky.mip_chain();
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("sky_cubemap"),
            size: wgpu::Extent3d { width: sky.size, height: sky.size, depth_or_array_layers: 6 },
            mip_level_count: levels.len() as u32,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba16Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let mut bytes = 0;
        for (level, faces) in levels.iter().enumerate() {
            let size = (sky.size >> level).max(1);
            for (face, texels) in faces.iter().enumerate() {
                let data: Vec<half::f16> = texels
                    .iter()
                    .flat_map(|t| [t[0], t[1], t[2], 1.0])
                    .map(|c| half::f16::from_f32((c / encode_scale).min(HALF_LIMIT)))
                    .collect();
                let data: &[u8] = bytemuck::cast_slice(&data);
                bytes += data.len() as u64;
                gpu.queue.write_texture(
                    wgpu::TexelCopyTextureInfo {
                        texture: &texture,
                        mip_level: level as u32,
                        origin: wgpu::Origin3d { x: 0, y: 0, z: face as u32 },
                        aspect: wgpu::TextureAspect::All,
                    },
                    data,
                    wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(size * 8),
                        rows_per_image: Some(size),
                    },
                    wgpu::Extent3d { width: size, height: size, depth_or_array_layers: 1 },
                );
            }
        }
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("sky_cubemap_view"),
            dimension: Some(wgpu::TextureViewDimension::Cube),
            ..Default::default()
        });
        let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("sky_sampler"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Nearest,
            ..Default::default()
        });
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sky_bind_group"),
            layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&view) },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::Sampler(&sampler) },
            ],
        });
        Ok(Self {
            bind_group,
            encode_scale,
            mip_levels: levels.len() as u32,
            size: sky.size,
            bytes,
            mean: sky.mean(),
            peak,
        })
    }
}
