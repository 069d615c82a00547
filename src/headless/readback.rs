//! Copying a texture back to the CPU. Rows of a texture-to-buffer copy must be padded to 256
//! bytes; the padding is removed after mapping, so any size works (the tests use 161x97).

use crate::gpu::Gpu;
use crate::{Error, Result};

/// The texture's pixels (mip 0, layer 0), rows tightly packed, in its own format.
pub fn read_texture(gpu: &Gpu, texture: &wgpu::Texture) -> Result<Vec<u8>> {
    let (width, height) = (texture.width(), texture.height());
    let aspect = if texture.format().is_depth_stencil_format() {
        wgpu::TextureAspect::DepthOnly
    } else {
        wgpu::TextureAspect::All
    };
    let pixel = texture
        .format()
        .block_copy_size(Some(aspect))
        .ok_or_else(|| Error::Gpu(format!("cannot read back {:?}", texture.format())))?;
    let row = width * pixel;
    let padded = row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback_buffer"),
        size: padded as u64 * height as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder =
        gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback_encoder") });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo { texture, mip_level: 0, origin: wgpu::Origin3d::ZERO, aspect },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
    );
    gpu.queue.submit([encoder.finish()]);
    let slice = buffer.slice(..);
    slice.map_async(wgpu::MapMode::Read, |_| {});
    gpu.wait()?;
    gpu.check()?;
    let mut out = Vec::with_capacity((row * height) as usize);
    {
        let view = slice.get_mapped_range().map_err(|e| Error::Gpu(format!("reading back a texture: {e}")))?;
        for y in 0..height as usize {
            out.extend_from_slice(&view[y * padded as usize..y * padded as usize + row as usize]);
        }
    }
    buffer.unmap();
    Ok(out)
}

/// A texture of four half floats per pixel, as f32.
pub fn read_rgba16f(gpu: &Gpu, texture: &wgpu::Texture) -> Result<Vec<[f32; 4]>> {
    let bytes = read_texture(gpu, texture)?;
    let halves: &[half::f16] = bytemuck::cast_slice(&bytes);
    Ok(halves.chunks_exact(4).map(|c| [c[0].to_f32(), c[1].to_f32(), c[2].to_f32(), c[3].to_f32()]).collect())
}

/// The G-buffer's packed normal target as view-space normal (xyz) and shininess (w).
pub fn read_surfaces(gpu: &Gpu, texture: &wgpu::Texture) -> Result<Vec<[f32; 4]>> {
    let bytes = read_texture(gpu, texture)?;
    Ok(bytemuck::cast_slice::<u8, u32>(&bytes)
        .iter()
        .map(|&bits| {
            let (n, shininess) = crate::render::surface_pack::unpack_surface(bits);
            [n.x, n.y, n.z, shininess]
        })
        .collect())
}

/// A texture of one half float per pixel (AO), as f32.
pub fn read_r16f(gpu: &Gpu, texture: &wgpu::Texture) -> Result<Vec<f32>> {
    let bytes = read_texture(gpu, texture)?;
    Ok(bytemuck::cast_slice::<u8, half::f16>(&bytes).iter().map(|h| h.to_f32()).collect())
}

/// A depth texture as f32. Where the device cannot copy depth to a buffer (wgpu's GL backend),
/// a full-screen pass first writes its bits into an `R32Uint` target.
pub fn read_depth(gpu: &Gpu, texture: &wgpu::Texture) -> Result<Vec<f32>> {
    let copyable =
        gpu.adapter.get_downlevel_capabilities().flags.contains(wgpu::DownlevelFlags::DEPTH_TEXTURE_AND_BUFFER_COPIES);
    let bytes = if copyable { read_texture(gpu, texture)? } else { read_texture(gpu, &depth_to_bits(gpu, texture)?)? };
    Ok(bytemuck::cast_slice(&bytes).to_vec())
}

/// A texture the renderer (or a copy pass) draws into and readback copies from.
pub fn output_texture_as(gpu: &Gpu, size: (u32, u32), format: wgpu::TextureFormat) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("capture_output"),
        size: wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

fn depth_to_bits(gpu: &Gpu, depth: &wgpu::Texture) -> Result<wgpu::Texture> {
    use crate::render::bindings::texture_entry;
    use crate::render::graph::io::color_attachment;
    use crate::render::graph::{fullscreen_pipeline, FullscreenDesc, FullscreenPass};
    let device = &gpu.device;
    let format = wgpu::TextureFormat::R32Uint;
    let size = depth.size();
    let target = output_texture_as(gpu, (size.width, size.height), format);
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("depth_copy_layout"),
        entries: &[texture_entry(0, false, wgpu::TextureViewDimension::D2)],
    });
    let module = crate::shaders::module(device, "depth_copy.wgsl")?;
    let pipeline = fullscreen_pipeline(
        device,
        &FullscreenDesc {
            label: "depth_copy",
            module: &module,
            entry: "fs_main",
            bind_group_layouts: &[Some(&layout)],
            targets: &[Some(format.into())],
            depth: None,
            constants: &[],
        },
    );
    let source = depth
        .create_view(&wgpu::TextureViewDescriptor { aspect: wgpu::TextureAspect::DepthOnly, ..Default::default() });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("depth_copy_group"),
        layout: &layout,
        entries: &[wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&source) }],
    });
    let view = target.create_view(&wgpu::TextureViewDescriptor::default());
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("depth_copy") });
    FullscreenPass {
        label: "depth_copy",
        attachments: &[color_attachment(&view, true)],
        depth: None,
        timestamps: None,
        pipeline: &pipeline,
        bind_groups: &[(0, &group)],
        viewport: None,
    }
    .record(&mut encoder);
    gpu.queue.submit([encoder.finish()]);
    Ok(target)
}

/// A set of sampling outputs read back (`Targets::occlusion`, `raw`, `half`...).
pub struct OcclusionValues {
    /// AO: its own target (SSAO), or DO's alpha where the mode computes AO beside DO.
    pub ao: Option<Vec<f32>>,
    /// DO (rgb, pre-exposed) and its alpha (AO in SSAO+SSDO, the open share in SSDO).
    pub directional: Option<Vec<[f32; 4]>>,
}

/// Reads `set`; `with_ao` says whether DO's alpha is AO (the mode computes AO).
pub fn read_occlusion(
    gpu: &Gpu,
    set: crate::render::targets::OcclusionTargets<'_>,
    with_ao: bool,
) -> Result<OcclusionValues> {
    let directional = set.directional.map(|t| read_rgba16f(gpu, &t.texture)).transpose()?;
    let ao = match (set.ao, &directional) {
        (Some(t), _) => Some(read_r16f(gpu, &t.texture)?),
        (None, Some(d)) if with_ao => Some(d.iter().map(|p| p[3]).collect()),
        _ => None,
    };
    Ok(OcclusionValues { ao, directional })
}
