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

/// A texture of one half float per pixel (AO), as f32.
pub fn read_r16f(gpu: &Gpu, texture: &wgpu::Texture) -> Result<Vec<f32>> {
    let bytes = read_texture(gpu, texture)?;
    Ok(bytemuck::cast_slice::<u8, half::f16>(&bytes).iter().map(|h| h.to_f32()).collect())
}

/// A depth texture as f32.
pub fn read_depth(gpu: &Gpu, texture: &wgpu::Texture) -> Result<Vec<f32>> {
    let bytes = read_texture(gpu, texture)?;
    Ok(bytemuck::cast_slice(&bytes).to_vec())
}
