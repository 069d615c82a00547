//! The passes of a frame. Each has the same shape: `new` builds layouts, pipelines and samplers
//! once; `resize` rebuilds only what depends on the targets (bind groups); `encode` records one
//! labelled pass. The helpers here keep the pipeline and attachment boilerplate in one place.

pub mod blur;
pub mod composite;
pub mod gbuffer;
pub mod light_cubes;
pub mod lighting;
pub mod occlusion;
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

/// Layout entries 0-2 of the full-screen passes: albedo, normal (unfilterable floats), depth.
pub fn gbuffer_entries() -> [wgpu::BindGroupLayoutEntry; 3] {
    [
        texture_entry(0, false, wgpu::TextureViewDimension::D2),
        texture_entry(1, false, wgpu::TextureViewDimension::D2),
        depth_entry(2),
    ]
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

/// Colour attachments for views that may be absent, all cleared.
pub fn cleared_attachments<'a>(
    views: &[Option<&'a wgpu::TextureView>],
) -> Vec<Option<wgpu::RenderPassColorAttachment<'a>>> {
    views.iter().map(|v| v.and_then(|view| color_attachment(view, true))).collect()
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
    /// Fragment entry point.
    pub entry: &'a str,
    pub bind_group_layouts: &'a [Option<&'a wgpu::BindGroupLayout>],
    /// One per fragment output; `None` discards that output.
    pub targets: &'a [Option<wgpu::ColorTargetState>],
    pub depth: Option<wgpu::DepthStencilState>,
    pub constants: &'a [(&'a str, f64)],
}

/// Colour target states for formats that may be absent (an output the plan does not keep).
pub fn color_targets(formats: &[Option<wgpu::TextureFormat>]) -> Vec<Option<wgpu::ColorTargetState>> {
    formats.iter().map(|f| f.map(Into::into)).collect()
}

/// A pipeline that draws the full-screen triangle of `common/fullscreen.wgsl`.
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
            entry_point: Some(desc.entry),
            compilation_options: options,
            targets: desc.targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}
