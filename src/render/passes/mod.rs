//! The passes of a frame. Each has the same shape: `new` builds layouts, pipelines and samplers
//! once; `resize` rebuilds only what depends on the targets (bind groups); `encode` records one
//! labelled pass. The helpers here keep the pipeline and attachment boilerplate in one place.

pub mod composite;
pub mod gbuffer;
pub mod light_cubes;
pub mod skybox;
pub mod tonemap;

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

/// A bind-group-layout entry for the depth buffer read with `textureLoad`.
pub fn depth_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Depth,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

pub fn sampler_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
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

/// A colour attachment that either clears to black or keeps what is there.
pub fn color_attachment(view: &wgpu::TextureView, clear: bool) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations {
            load: if clear { wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT) } else { wgpu::LoadOp::Load },
            store: wgpu::StoreOp::Store,
        },
    })
}

/// Everything that distinguishes one full-screen pipeline from another.
pub struct FullscreenDesc<'a> {
    pub label: &'a str,
    pub module: &'a wgpu::ShaderModule,
    pub bind_group_layouts: &'a [Option<&'a wgpu::BindGroupLayout>],
    pub format: wgpu::TextureFormat,
    pub depth: Option<wgpu::DepthStencilState>,
    pub constants: &'a [(&'a str, f64)],
}

/// A pipeline that draws the full-screen triangle of `common/fullscreen.wgsl` with `fs_main`.
pub fn fullscreen_pipeline(device: &wgpu::Device, desc: &FullscreenDesc<'_>) -> wgpu::RenderPipeline {
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(&format!("{}_layout", desc.label)),
        bind_group_layouts: desc.bind_group_layouts,
        immediate_size: 0,
    });
    let options = wgpu::PipelineCompilationOptions { constants: desc.constants, ..Default::default() };
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(desc.label),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: desc.module,
            entry_point: Some("fullscreen_vs"),
            compilation_options: options.clone(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: desc.depth.clone(),
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: desc.module,
            entry_point: Some("fs_main"),
            compilation_options: options,
            targets: &[Some(desc.format.into())],
        }),
        multiview_mask: None,
        cache: None,
    })
}
