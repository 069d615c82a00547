//! What a pass reads and writes, declared once: its bind group 1 is built from its reads, in
//! binding order, and its colour attachments from its writes, so the declaration cannot drift
//! from what the shader is given. The plan's reads and writes, the targets it allocates, their
//! bytes and `--print-plan` are derived from the same lists (`passes/mod.rs`), and a test holds
//! each list against the bindings its WGSL declares (`tests/it/cpu/shaders.rs`).

use crate::render::history::{History, PingPong};
use crate::render::targets::{Place, TargetId, Targets};

/// One binding of a pass's group 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Read {
    /// A target the plan has; for a history, the side this frame reads.
    Target(TargetId),
    /// A target the plan lacks: the fallback of its kind is bound, and nothing is read.
    Absent(TargetId),
    /// The side of a history this frame writes, read by a later pass of the same frame.
    Written(TargetId),
    /// The sampling passes' parameters (`SamplingParams`, a uniform).
    Sampling,
    /// What the filters of the samples read (`FilterParams`, a uniform).
    Filter,
}

impl Read {
    /// `id` where the plan has it (`present`), else its fallback.
    pub fn target_if(present: bool, id: TargetId) -> Self {
        if present {
            Read::Target(id)
        } else {
            Read::Absent(id)
        }
    }

    /// The target read, if this reads one.
    pub fn target(self) -> Option<TargetId> {
        match self {
            Read::Target(id) | Read::Written(id) => Some(id),
            Read::Absent(_) | Read::Sampling | Read::Filter => None,
        }
    }

    /// How the shader sees this binding.
    pub fn kind(self) -> Kind {
        match self {
            Read::Target(id) | Read::Absent(id) | Read::Written(id) => Kind::of(id.format),
            Read::Sampling | Read::Filter => Kind::Uniform,
        }
    }
}

/// How a shader reads a binding of group 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `texture_2d<f32>`, unfilterable (read with `textureLoad`); the depth buffer too, which
    /// wgpu's GL backend cannot read with `textureLoad` as a `texture_depth_2d`.
    Float,
    /// `texture_2d<u32>` (the packed normal, the pyramid, the surface history).
    Uint,
    /// A uniform buffer.
    Uniform,
}

impl Kind {
    pub fn of(format: wgpu::TextureFormat) -> Self {
        match format.sample_type(None, None) {
            Some(wgpu::TextureSampleType::Uint) => Kind::Uint,
            _ => Kind::Float,
        }
    }

    fn layout_entry(self, binding: u32) -> wgpu::BindGroupLayoutEntry {
        let texture = |sample_type| wgpu::BindingType::Texture {
            sample_type,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        };
        let ty = match self {
            Kind::Float => texture(wgpu::TextureSampleType::Float { filterable: false }),
            Kind::Uint => texture(wgpu::TextureSampleType::Uint),
            Kind::Uniform => wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
        };
        wgpu::BindGroupLayoutEntry { binding, visibility: wgpu::ShaderStages::FRAGMENT, ty, count: None }
    }
}

/// What a pass reads and writes in one plan.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PassIo {
    /// Group 1's bindings, in binding order.
    pub reads: Vec<Read>,
    /// Targets read otherwise: through the depth attachment, or by bind groups of the pass's own
    /// making (the pyramid's levels).
    pub attached: Vec<TargetId>,
    /// Colour attachments, in order (a depth attachment the pass writes comes last).
    pub writes: Vec<TargetId>,
}

impl PassIo {
    /// Every target read, bound or attached, that the plan has.
    pub fn targets_read(&self) -> Vec<TargetId> {
        self.reads.iter().filter_map(|r| r.target()).chain(self.attached.iter().copied()).collect()
    }

    /// The layout of group 1: one entry a read, numbered in order.
    pub fn layout_entries(&self) -> Vec<wgpu::BindGroupLayoutEntry> {
        self.kinds().iter().enumerate().map(|(i, kind)| kind.layout_entry(i as u32)).collect()
    }

    /// What each binding is, in order: the layout's key.
    pub fn kinds(&self) -> Vec<Kind> {
        self.reads.iter().map(|r| r.kind()).collect()
    }

    /// Group 1's entries, each read bound to what `inputs` holds for it; a history's side is the
    /// one a frame of `parity` reads (or, [`Read::Written`], writes).
    pub fn entries<'a>(&self, inputs: &Inputs<'a>, parity: usize) -> Vec<wgpu::BindGroupEntry<'a>> {
        let view = |view| wgpu::BindingResource::TextureView(view);
        self.reads
            .iter()
            .enumerate()
            .map(|(i, read)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: match *read {
                    Read::Sampling => inputs.sampling.as_entire_binding(),
                    Read::Filter => inputs.filter.as_entire_binding(),
                    Read::Absent(id) => view(inputs.fallbacks.of(Kind::of(id.format))),
                    Read::Target(id) if id.place == Place::History => view(&inputs.pair(id).read_side(parity).view),
                    Read::Written(id) => view(&inputs.pair(id).write_side(parity).view),
                    Read::Target(id) => view(&inputs.targets.expect(id).view),
                },
            })
            .collect()
    }
}

/// What a pass's reads are bound to.
#[derive(Clone, Copy)]
pub struct Inputs<'a> {
    pub targets: &'a Targets,
    pub history: &'a History,
    /// `SamplingParams`, for [`Read::Sampling`].
    pub sampling: &'a wgpu::Buffer,
    /// `FilterParams`, for [`Read::Filter`].
    pub filter: &'a wgpu::Buffer,
    pub fallbacks: &'a Fallbacks,
}

impl<'a> Inputs<'a> {
    /// The history `id`, which the plan keeps.
    fn pair(&self, id: TargetId) -> &'a PingPong {
        self.history.get(id).unwrap_or_else(|| panic!("the plan has no {}", id.name))
    }
}

/// What is bound where a plan lacks an input: one texture of each kind, 1x1, never read (the
/// shader's override constants skip the code that would). Kept in one place, the renderer's.
pub struct Fallbacks {
    /// For a float input: a missing sampling output, HDR image or senders' sky.
    pub absent_float: wgpu::TextureView,
    /// For an integer input: a missing bounce (`Rg32Uint`) or depth pyramid.
    pub absent_uint: wgpu::TextureView,
}

impl Fallbacks {
    pub fn new(device: &wgpu::Device) -> Self {
        let texture = |label, format| {
            device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: 1 },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage: wgpu::TextureUsages::TEXTURE_BINDING,
                    view_formats: &[],
                })
                .create_view(&wgpu::TextureViewDescriptor::default())
        };
        Self {
            absent_float: texture("absent_float_input", wgpu::TextureFormat::Rgba16Float),
            absent_uint: texture("absent_uint_input", wgpu::TextureFormat::R32Uint),
        }
    }

    /// The fallback for a texture input of `kind`.
    pub fn of(&self, kind: Kind) -> &wgpu::TextureView {
        match kind {
            Kind::Uint => &self.absent_uint,
            Kind::Float | Kind::Uniform => &self.absent_float,
        }
    }
}

/// A colour attachment for each write, cleared or kept (`clear`): a target of the plan, the
/// side of a history this frame writes, or the frame's output.
pub fn attachments<'a>(
    writes: &[TargetId],
    targets: &'a Targets,
    history: &'a History,
    output: &'a wgpu::TextureView,
    clear: bool,
) -> Vec<Option<wgpu::RenderPassColorAttachment<'a>>> {
    writes
        .iter()
        .map(|&id| {
            let view = match id.place {
                Place::Output => output,
                Place::History => {
                    &history.get(id).unwrap_or_else(|| panic!("the plan has no {}", id.name)).write().view
                }
                _ => &targets.expect(id).view,
            };
            color_attachment(view, clear)
        })
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
