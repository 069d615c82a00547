//! Bind-group-layout entries and bind-group entries as the passes (and the sky's bind group) use
//! them: fragment-stage textures, samplers and uniforms, and the G-buffer's three inputs.

/// A bind-group-layout entry for a float texture read by fragment shaders.
pub fn texture_entry(
    binding: u32,
    filterable: bool,
    dimension: wgpu::TextureViewDimension,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable },
            view_dimension: dimension,
            multisampled: false,
        },
        count: None,
    }
}

/// A bind-group-layout entry for the depth buffer read with `textureLoad`. It is bound as an
/// unfilterable float texture (`texture_2d<f32>` in WGSL), which WebGPU allows for `depth32float`:
/// wgpu's GL backend cannot translate `textureLoad` from a `texture_depth_2d`, and on Vulkan the
/// two compile to the same image read.
pub fn depth_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    texture_entry(binding, false, wgpu::TextureViewDimension::D2)
}

pub fn sampler_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
        count: None,
    }
}

/// Layout entries 0-2 of the full-screen passes: albedo (unfilterable float), the packed normal
/// (u32), depth.
pub fn gbuffer_entries() -> [wgpu::BindGroupLayoutEntry; 3] {
    [texture_entry(0, false, wgpu::TextureViewDimension::D2), normal_entry(1), depth_entry(2)]
}

/// A layout entry for the G-buffer's packed normal target (`u32`, read with `textureLoad`).
pub fn normal_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    uint_entry(binding)
}

/// A layout entry for an unsigned-integer texture read with `textureLoad` (the packed normal, the
/// depth pyramid's levels).
pub fn uint_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Uint,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// A layout entry for a uniform buffer read by fragment shaders.
pub fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// Bind group entries for a list of texture views, numbered from 0.
pub fn view_entries<'a>(views: &[&'a wgpu::TextureView]) -> Vec<wgpu::BindGroupEntry<'a>> {
    views
        .iter()
        .enumerate()
        .map(|(i, view)| wgpu::BindGroupEntry { binding: i as u32, resource: wgpu::BindingResource::TextureView(view) })
        .collect()
}

/// The layout of a pass that filters one sampling output by the G-buffer (the blur and the
/// upsample): the G-buffer at 0-2, the sampling parameters at 3, the input at 4.
pub fn filter_layout(cx: &super::PassContext<'_>, label: &str) -> wgpu::BindGroupLayout {
    let [a, n, d] = gbuffer_entries();
    cx.layout(label, &[a, n, d, uniform_entry(3), texture_entry(4, false, wgpu::TextureViewDimension::D2)])
}

/// Bind group 1 of such a pass, filtering `input`.
pub fn filter_entries<'a>(
    targets: &'a crate::render::targets::Targets,
    data: &'a crate::render::resources::sampling::OcclusionData,
    input: &'a wgpu::TextureView,
) -> Vec<wgpu::BindGroupEntry<'a>> {
    let mut entries = view_entries(&[&targets.albedo.view, &targets.normal.view, &targets.depth.view]);
    entries.push(wgpu::BindGroupEntry { binding: 3, resource: data.buffer.as_entire_binding() });
    entries.push(wgpu::BindGroupEntry { binding: 4, resource: wgpu::BindingResource::TextureView(input) });
    entries
}
