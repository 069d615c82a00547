//! What every pass of the frame is made of (the passes themselves are `passes/`, one module
//! each, and their list in frame order). A pass has: its step and the rule for when a plan has
//! it, and what it reads and writes ([`io::PassIo`], the one declaration its bind group is built
//! from), all in its [`Entry`]; its struct and `new` — what lives as long as the renderer: shader
//! modules, samplers, pipelines that depend on nothing else; and [`Pass`]: `prepare` rebuilds what
//! depends on the targets and the plan — bind groups always, a pipeline specialised to a key
//! (`KeyedPipeline`, which keeps those built for earlier keys) when the plan, variant or view
//! asks for another — and `record` records it into a frame from one [`Recording`]. The helpers
//! below keep the pipeline and attachment boilerplate in one place; [`state::PassState`] is what
//! a full-screen pass keeps.

pub mod io;
mod keyed;
pub mod state;

pub use keyed::KeyedPipeline;

use super::history::{History, HistorySpec};
use super::modes::{Plan, PlanFacts, Step};
use super::resources::scene::SceneGpu;
use super::resources::sky::SkyGpu;
use super::settings::View;
use super::targets::Targets;
use super::variant::Variant;
use crate::Result;

/// One pass in the frame's list (`passes::PASSES`): its step, the rule for whether a plan has it, what
/// it reads and writes in a plan, the histories it keeps, and how it is built.
pub struct Entry {
    pub step: Step,
    pub runs: fn(&PlanFacts) -> bool,
    pub io: fn(&Plan) -> io::PassIo,
    pub histories: fn(&PlanFacts) -> Vec<HistorySpec>,
    /// The WGSL files whose bind group 1 is built from the pass's reads (none where the pass
    /// makes its own groups): a test holds the two against each other.
    pub group_shaders: &'static [&'static str],
    pub build: fn(&PassContext<'_>) -> Result<Box<dyn Pass>>,
    /// What the pass is for, as `bench` splits a frame.
    pub role: Role,
}

/// What a pass is for, as `bench` splits a frame's time: making the occlusion samples (the
/// sampling pass and what only it reads: the depth pyramid, the senders' sky), cleaning them
/// (blur, upsample, temporal accumulation), or the rest (geometry, lighting, compositing, display).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    Sampling,
    Denoise,
    Rest,
}

impl Role {
    pub const ALL: [Role; 3] = [Role::Sampling, Role::Denoise, Role::Rest];

    pub fn name(self) -> &'static str {
        match self {
            Role::Sampling => "sampling",
            Role::Denoise => "denoise",
            Role::Rest => "rest",
        }
    }
}

impl Entry {
    /// A pass's entry: its step, the rule for whether a plan has it, what it reads and writes,
    /// and how it is built; it keeps no history and binds no group 1 of its own unless
    /// [`Entry::binding`] and [`Entry::keeping`] say so.
    pub const fn new(
        step: Step,
        runs: fn(&PlanFacts) -> bool,
        io: fn(&Plan) -> io::PassIo,
        build: fn(&PassContext<'_>) -> Result<Box<dyn Pass>>,
    ) -> Self {
        Self { step, runs, io, histories: no_history, group_shaders: &[], build, role: Role::Rest }
    }

    /// What the pass is for, when it is not [`Role::Rest`].
    pub const fn role(self, role: Role) -> Self {
        Self { role, ..self }
    }

    /// The WGSL files whose bind group 1 is built from the pass's reads.
    pub const fn binding(self, shaders: &'static [&'static str]) -> Self {
        Self { group_shaders: shaders, ..self }
    }

    /// The histories the pass keeps in a plan.
    pub const fn keeping(self, histories: fn(&PlanFacts) -> Vec<HistorySpec>) -> Self {
        Self { histories, ..self }
    }
}

/// For an [`Entry`] of a pass that keeps no history.
pub fn no_history(_: &PlanFacts) -> Vec<HistorySpec> {
    Vec::new()
}

/// Everything a pass records one step of a frame from.
pub struct Recording<'a> {
    pub encoder: &'a mut wgpu::CommandEncoder,
    /// Where the step's GPU time is written (`None` when not timing).
    pub timestamps: Option<wgpu::RenderPassTimestampWrites<'a>>,
    pub targets: &'a Targets,
    pub plan: &'a Plan,
    /// Bind group 0: the frame uniforms and the lights.
    pub frame: &'a wgpu::BindGroup,
    pub sky: &'a SkyGpu,
    pub scene: &'a SceneGpu,
    pub lights: u32,
    /// The lights' indices, farthest first (an instance buffer of u32, for the light cubes).
    pub light_order: &'a wgpu::Buffer,
    /// What the frame is drawn into, and where the image starts in it (the viewer's panel is
    /// beside it).
    pub output: &'a wgpu::TextureView,
    pub origin: (u32, u32),
    /// The targets that survive frames: read the last frame's, write this one's.
    pub history: &'a History,
}

impl<'a> Recording<'a> {
    /// The viewport that places the image at its origin in the output.
    pub fn viewport(&self) -> [f32; 4] {
        let (w, h) = self.targets.size;
        [self.origin.0 as f32, self.origin.1 as f32, w as f32, h as f32]
    }

    /// Records a step that does no work this frame (the plan has it, the frame skips it): an
    /// empty render pass over `writes`, kept as they are, only where the step's time is
    /// measured, so its timestamps exist and read zero.
    pub fn skip(self, writes: &[super::targets::TargetId]) {
        let Some(timestamps) = self.timestamps else { return };
        let attachments = io::attachments(writes, self.targets, self.history, self.output, false);
        self.encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("skipped_step"),
            color_attachments: &attachments,
            depth_stencil_attachment: None,
            timestamp_writes: Some(timestamps),
            occlusion_query_set: None,
            multiview_mask: None,
        });
    }

    /// A colour attachment for each of `writes` (see [`io::attachments`]), cleared or kept.
    pub fn attachments(
        &self,
        writes: &[super::targets::TargetId],
        clear: bool,
    ) -> Vec<Option<wgpu::RenderPassColorAttachment<'a>>> {
        io::attachments(writes, self.targets, self.history, self.output, clear)
    }
}

/// What a pass's bind groups and pipeline are built for.
#[derive(Clone, Copy)]
pub struct Preparation<'a> {
    pub plan: &'a Plan,
    pub variant: Variant,
    pub view: View,
    /// What the passes' reads are bound to: the targets, the histories (made before the passes
    /// are prepared), the sampling parameters and the fallbacks.
    pub inputs: io::Inputs<'a>,
}

/// One pass of the frame (see the module's documentation).
pub trait Pass {
    /// Rebuilds what depends on the targets and the plan. Passes that hold nothing of the kind
    /// keep this default.
    fn prepare(&mut self, _device: &wgpu::Device, _p: &Preparation<'_>) {}

    /// Updates what the pass keeps from frame to frame (a jitter, a frame count), once a frame
    /// before any pass records, for every pass whether the plan runs it or not. Stateless
    /// passes keep this default.
    fn begin_frame(&mut self, _frame: &FrameState<'_>) {}

    /// Records the pass. Only steps of the plan are recorded, and only after `prepare`: a pass
    /// recorded otherwise is a bug, and says so.
    fn record(&self, rec: Recording<'_>);

    /// Uploads a model's geometry and materials, with each material's thickness code
    /// (`Model::thickness_codes`): the pass that draws the scene does, the others keep this
    /// default.
    fn upload_scene(
        &mut self,
        _gpu: &crate::gpu::Gpu,
        _model: &crate::scene::Model,
        _thickness: &[u32],
    ) -> Option<SceneGpu> {
        None
    }
}

/// What every pass is built from: the device, the layouts of bind groups 0 (frame) and 2 (sky)
/// that all passes share, and the format of the output a display plan draws into.
pub struct PassContext<'a> {
    pub gpu: &'a crate::gpu::Gpu,
    pub device: &'a wgpu::Device,
    pub frame_layout: &'a wgpu::BindGroupLayout,
    pub sky_layout: &'a wgpu::BindGroupLayout,
    pub output: wgpu::TextureFormat,
}

impl PassContext<'_> {
    /// A bind group layout named after its pass.
    pub fn layout(&self, name: &str, entries: &[wgpu::BindGroupLayoutEntry]) -> wgpu::BindGroupLayout {
        self.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(name), entries })
    }
}

/// What a pass may look at in [`Pass::begin_frame`].
pub struct FrameState<'a> {
    pub plan: &'a Plan,
    /// Counts frames since the renderer was made (wraps).
    pub frame_index: u32,
    /// The histories and how many frames each holds (0 after a reset).
    pub history: &'a History,
    /// The camera differs from the last frame's.
    pub camera_moved: bool,
    /// The samples are blurred this frame (`Renderer::blurs`): the plan blurs, and the view turns
    /// fast or its average is young. Where they are not, the temporal pass reads them raw.
    pub blur: bool,
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

/// A read-only test of the full-screen triangle, which lies at depth 0 (the reverse-Z far plane),
/// against the G-buffer's depth: `GreaterEqual` passes where nothing was drawn (the sky), `Less`
/// where a surface was.
pub fn fullscreen_depth_test(compare: wgpu::CompareFunction) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: crate::render::targets::DEPTH_FORMAT,
        depth_write_enabled: Some(false),
        depth_compare: Some(compare),
        stencil: wgpu::StencilState::default(),
        bias: wgpu::DepthBiasState::default(),
    }
}

/// A pipeline that draws the full-screen triangle of `common/fullscreen_triangle.wgsl` (the
/// module's `fullscreen_vs`: `common/fullscreen.wgsl`'s or `common/frame_varyings.wgsl`'s).
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

/// Records one full-screen pass: `attachments` as colour targets, an optional read-only depth
/// attachment (for the depth test of the skybox), the pipeline with its bind groups by index, and
/// the triangle of `common/fullscreen_triangle.wgsl` drawn into `viewport` (the whole target when `None`).
pub struct FullscreenPass<'a> {
    pub label: &'a str,
    pub attachments: &'a [Option<wgpu::RenderPassColorAttachment<'a>>],
    pub depth: Option<&'a wgpu::TextureView>,
    pub timestamps: Option<wgpu::RenderPassTimestampWrites<'a>>,
    pub pipeline: &'a wgpu::RenderPipeline,
    pub bind_groups: &'a [(u32, &'a wgpu::BindGroup)],
    pub viewport: Option<[f32; 4]>,
}

impl FullscreenPass<'_> {
    pub fn record(self, encoder: &mut wgpu::CommandEncoder) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(self.label),
            color_attachments: self.attachments,
            depth_stencil_attachment: self.depth.map(|view| wgpu::RenderPassDepthStencilAttachment {
                view,
                depth_ops: None,
                stencil_ops: None,
            }),
            timestamp_writes: self.timestamps,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let Some([x, y, w, h]) = self.viewport {
            pass.set_viewport(x, y, w, h, 0.0, 1.0);
        }
        pass.set_pipeline(self.pipeline);
        for (index, group) in self.bind_groups {
            pass.set_bind_group(*index, *group, &[]);
        }
        pass.draw(0..3, 0..1);
    }
}
