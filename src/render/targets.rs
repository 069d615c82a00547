//! Screen-sized textures. `Targets` owns them and is rebuilt as a whole on resize or when the
//! plan needs a different set; passes own pipelines and rebuild only their bind groups. A target
//! that the current plan does not read or write is not allocated at all.

use super::modes::Plan;

pub const ALBEDO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
pub const NORMAL_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
pub const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// One texture with its default view and its size in bytes.
pub struct Target {
    pub name: &'static str,
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
    pub bytes: u64,
}

impl Target {
    pub fn new(device: &wgpu::Device, name: &'static str, size: (u32, u32), format: wgpu::TextureFormat) -> Self {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(name),
            size: wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let bytes = size.0 as u64 * size.1 as u64 * format.block_copy_size(None).unwrap_or(4) as u64;
        Self { name, texture, view, bytes }
    }
}

/// The G-buffer and the intermediate buffers of the current plan.
pub struct Targets {
    pub size: (u32, u32),
    /// rgb albedo, a specular strength
    pub albedo: Target,
    /// xyz view-space normal, w shininess
    pub normal: Target,
    pub depth: Target,
    /// Linear HDR radiance before tone mapping.
    pub hdr: Target,
}

impl Targets {
    pub fn new(device: &wgpu::Device, size: (u32, u32), _plan: &Plan) -> Self {
        Self {
            size,
            albedo: Target::new(device, "gbuffer_albedo", size, ALBEDO_FORMAT),
            normal: Target::new(device, "gbuffer_normal", size, NORMAL_FORMAT),
            depth: Target::new(device, "gbuffer_depth", size, DEPTH_FORMAT),
            hdr: Target::new(device, "hdr_color", size, HDR_FORMAT),
        }
    }

    /// Every allocated target with its size in bytes.
    pub fn allocations(&self) -> Vec<(&'static str, u64)> {
        [&self.albedo, &self.normal, &self.depth, &self.hdr].iter().map(|t| (t.name, t.bytes)).collect()
    }
}
