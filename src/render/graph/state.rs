//! What every full-screen pass with a bind group of its own keeps: its shader, the layout of its
//! group 1 (built from its declared reads, `io.rs`), the layouts its pipelines are built with, its
//! pipeline for the current key, and its bind group for the current targets. `new` loads the
//! shader; `prepare` binds the pass's reads (making the layout the first time) and fills the
//! pipeline, or clears both where the plan has no such step; `record` takes them ready.

use super::io::{Inputs, Kind, PassIo};
use super::{
    fullscreen_depth_test, fullscreen_pipeline, FullscreenDesc, FullscreenPass, KeyedPipeline, PassContext,
    Preparation, Recording,
};
use crate::render::history::PingPong;
use crate::render::modes::{Plan, Step};
use crate::render::targets::TargetId;
use crate::{shaders, Result};

/// Override constants, by name (booleans as 0 or 1).
pub type Constants = Vec<(&'static str, f64)>;

/// What a pass's pipeline for one key is: its fragment entry point, colour targets and override
/// constants (booleans as 0 or 1).
pub struct PipelineSpec {
    pub entry: &'static str,
    pub targets: Vec<Option<wgpu::ColorTargetState>>,
    pub constants: Constants,
}

/// An override constant's value for a flag.
pub fn flag(b: bool) -> f64 {
    b as u8 as f64
}

/// The override the framework sets from the plan in every pipeline whose shader declares it, so
/// no pass's key carries it: the sampling chain runs at half width and height
/// (`common/sample_grid.wgsl`).
const SAMPLE_SCALE: &str = "HALF_RESOLUTION";

pub struct PassState<K> {
    /// The pass's name: its labels and its messages.
    pub name: &'static str,
    /// The render pass's label (`<name>_pass`), made once rather than every frame.
    pass_label: String,
    pub module: wgpu::ShaderModule,
    /// Group 1, the pass's own inputs, with the kinds of its bindings it was made for.
    layout: Option<(Vec<Kind>, wgpu::BindGroupLayout)>,
    /// Group 0, the frame uniforms and lights.
    frame_layout: wgpu::BindGroupLayout,
    /// Group 2, the sky, for the passes that read it.
    sky_layout: Option<wgpu::BindGroupLayout>,
    /// The pipeline for a key, and the plan's `SAMPLE_SCALE` it was built with.
    pub pipeline: KeyedPipeline<(K, bool)>,
    /// The shader declares `SAMPLE_SCALE`.
    scaled: bool,
    pub bind_group: Option<wgpu::BindGroup>,
    /// The targets the pass writes in the plan it was last bound for, so a frame's `record`
    /// does not build its declaration again.
    writes: Vec<TargetId>,
    /// Draws only where the G-buffer has a surface (`surfaces_only`).
    surfaces_only: bool,
}

/// A pass's group 1 for a frame of either history parity ([`PassState::parity_groups`]).
pub struct ParityGroups([wgpu::BindGroup; 2]);

impl ParityGroups {
    /// The group for the frame whose side of `history` stands as it does now.
    pub fn of(&self, history: &PingPong) -> &wgpu::BindGroup {
        &self.0[history.parity()]
    }
}

impl<K: PartialEq + Copy> PassState<K> {
    /// Loads `shaders/<shader>`; `sky` says whether group 2 (the sky) follows group 1.
    pub fn new(cx: &PassContext<'_>, name: &'static str, shader: &str, sky: bool) -> Result<Self> {
        Ok(Self {
            name,
            pass_label: format!("{name}_pass"),
            module: shaders::module(cx.device, shader)?,
            scaled: shaders::resolve(shader)?.contains(&format!("override {SAMPLE_SCALE}")),
            layout: None,
            frame_layout: cx.frame_layout.clone(),
            sky_layout: sky.then(|| cx.sky_layout.clone()),
            pipeline: KeyedPipeline::new(),
            bind_group: None,
            writes: Vec::new(),
            surfaces_only: false,
        })
    }

    /// The pass draws only where the G-buffer has a surface: its pipelines test the fragment
    /// against the depth buffer (read-only), so the sky's pixels keep the cleared value without
    /// running the shader. For a pass whose shader returns zero there anyway: a branch does not
    /// spare a CPU rasteriser the work it skips (both sides run), the depth test does. Only where
    /// the adapter lets a read-only depth attachment be read as a texture in the same pass (not
    /// wgpu's GL backend); elsewhere the shader's own test stands.
    pub fn surfaces_only(mut self, cx: &PassContext<'_>) -> Self {
        let flags = cx.gpu.adapter.get_downlevel_capabilities().flags;
        self.surfaces_only = flags.contains(wgpu::DownlevelFlags::READ_ONLY_DEPTH_STENCIL);
        self
    }

    /// Another state of the same shader and layouts, named `name`, with a pipeline of its own: a
    /// pass that switches between two pipelines frame by frame (the temporal pass's still and
    /// moving ones) without compiling its shader twice.
    pub fn sibling(&self, name: &'static str) -> Self {
        Self {
            name,
            pass_label: format!("{name}_pass"),
            module: self.module.clone(),
            scaled: self.scaled,
            layout: self.layout.clone(),
            frame_layout: self.frame_layout.clone(),
            sky_layout: self.sky_layout.clone(),
            pipeline: KeyedPipeline::new(),
            bind_group: None,
            writes: Vec::new(),
            surfaces_only: self.surfaces_only,
        }
    }

    /// Group 1's layout for `io`'s reads, made when their kinds first come (or, which no pass
    /// does, change: the pipelines built with the old one are dropped then).
    pub fn layout_for(&mut self, device: &wgpu::Device, io: &PassIo) -> &wgpu::BindGroupLayout {
        let kinds = io.kinds();
        if self.layout.as_ref().is_none_or(|(k, _)| *k != kinds) {
            let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(&format!("{}_layout", self.name)),
                entries: &io.layout_entries(),
            });
            self.layout = Some((kinds, layout));
            self.pipeline.clear();
        }
        &self.layout.as_ref().expect("made above").1
    }

    /// Group 1 with `io`'s reads bound to `inputs` (for a history, the side a frame of `parity`
    /// reads).
    pub fn group(&mut self, device: &wgpu::Device, io: &PassIo, inputs: &Inputs<'_>, parity: usize) -> wgpu::BindGroup {
        let label = format!("{}_bind_group", self.name);
        self.writes.clone_from(&io.writes);
        let layout = self.layout_for(device, io);
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&label),
            layout,
            entries: &io.entries(inputs, parity),
        })
    }

    /// Group 1 for each parity of the histories `io` binds: a pass that reads (or writes) a side
    /// of a history makes both on a re-plan and draws each frame with the one its parity picks.
    pub fn parity_groups(&mut self, device: &wgpu::Device, io: &PassIo, inputs: &Inputs<'_>) -> ParityGroups {
        ParityGroups([0, 1].map(|parity| self.group(device, io, inputs, parity)))
    }

    /// Binds `io`'s reads as the pass's group 1.
    pub fn bind(&mut self, device: &wgpu::Device, io: &PassIo, inputs: &Inputs<'_>) {
        self.bind_group = Some(self.group(device, io, inputs, 0));
    }

    /// The pipeline for `key` in `plan`: `build` makes it (from the key, the shader, groups 0, 1
    /// and, with the sky, 2, and the constants the framework sets from the plan, which it adds to
    /// its own) when the current one is for another key or plan. Group 1's layout comes from the
    /// pass's reads: bind them first.
    pub fn ensure(
        &mut self,
        plan: &Plan,
        key: K,
        build: impl FnOnce(K, &wgpu::ShaderModule, &[Option<&wgpu::BindGroupLayout>], Constants) -> wgpu::RenderPipeline,
    ) {
        let Some((_, own)) = &self.layout else {
            unreachable!("the {} pass built a pipeline before binding its reads", self.name)
        };
        let mut layouts = vec![Some(&self.frame_layout), Some(own)];
        layouts.extend(self.sky_layout.as_ref().map(Some));
        let module = &self.module;
        let scaled = plan.half_resolution && self.scaled;
        let shared = self.scaled.then_some((SAMPLE_SCALE, flag(scaled)));
        self.pipeline.ensure((key, scaled), |(key, _)| build(key, module, &layouts, shared.into_iter().collect()));
    }

    /// [`PassState::ensure`] for the usual case: a full-screen pipeline of this pass's own shader
    /// and groups, labelled after the pass, with what `spec` gives for the key.
    pub fn ensure_fullscreen(
        &mut self,
        device: &wgpu::Device,
        plan: &Plan,
        key: K,
        spec: impl FnOnce(K) -> PipelineSpec,
    ) {
        let label = format!("{}_pipeline", self.name);
        let depth = self.surfaces_only.then(|| fullscreen_depth_test(wgpu::CompareFunction::Less));
        self.ensure(plan, key, |key, module, layouts, shared| {
            let spec = spec(key);
            let desc = FullscreenDesc {
                label: &label,
                module,
                entry: spec.entry,
                bind_group_layouts: layouts,
                targets: &spec.targets,
                depth,
                constants: &[spec.constants, shared].concat(),
            };
            fullscreen_pipeline(device, &desc)
        });
    }

    /// A full-screen pass's whole `prepare`: nothing kept where the plan has no `step`;
    /// otherwise the reads `io` declares bound as group 1 and the pipeline for the plan's key.
    pub fn prepare_fullscreen(
        &mut self,
        device: &wgpu::Device,
        p: &Preparation<'_>,
        (step, io): (Step, fn(&Plan) -> PassIo),
        key: impl FnOnce() -> K,
        spec: impl FnOnce(K) -> PipelineSpec,
    ) {
        if !self.runs(p.plan.has(step)) {
            return;
        }
        self.bind(device, &io(p.plan), &p.inputs);
        self.ensure_fullscreen(device, p.plan, key(), spec);
    }

    /// Drops the bind group, and the pipeline from use (it is kept for a plan that has the pass
    /// again): the plan has no step for this pass.
    pub fn clear(&mut self) {
        self.pipeline.park();
        self.bind_group = None;
        self.writes.clear();
    }

    /// The targets the pass writes, as declared when its reads were last bound.
    pub fn writes(&self) -> &[TargetId] {
        &self.writes
    }

    /// Whether the plan runs the pass: `runs`, with the pipeline and bind group dropped first
    /// where it does not. A pass's `prepare` starts `if !self.state.runs(...) { return; }`.
    pub fn runs(&mut self, runs: bool) -> bool {
        if !runs {
            self.clear();
        }
        runs
    }

    /// Records the pass (a full-screen triangle) into `attachments`, with `frame` as group 0,
    /// its own group 1, and `sky` as group 2 where the pass reads it; `viewport` places the image
    /// in a larger output.
    pub fn draw<'a>(
        &'a self,
        rec: (&mut wgpu::CommandEncoder, Option<wgpu::RenderPassTimestampWrites<'a>>),
        attachments: &'a [Option<wgpu::RenderPassColorAttachment<'a>>],
        groups: (&'a wgpu::BindGroup, Option<&'a wgpu::BindGroup>),
        viewport: Option<[f32; 4]>,
    ) {
        let (_, _, own) = self.ready();
        self.draw_with(rec, attachments, (groups.0, own, groups.1), viewport);
    }

    /// A full-screen pass's whole `record`: drawn over all of the targets it writes (cleared),
    /// with the sky as group 2 where the pass was made with it.
    pub fn record(&self, rec: Recording<'_>) {
        let (_, _, own) = self.ready();
        self.record_with(rec, &self.writes, own);
    }

    /// [`PassState::record`] into `writes` with group 1 given: a pass that keeps one group per
    /// history parity, or a sibling drawing with its parent's targets and groups.
    pub fn record_with(&self, rec: Recording<'_>, writes: &[TargetId], own: &wgpu::BindGroup) {
        let attachments = rec.attachments(writes, true);
        let sky = self.sky_layout.is_some().then_some(&rec.sky.bind_group);
        let depth = self.surfaces_only.then(|| &rec.targets.depth().view);
        self.draw_inner((rec.encoder, rec.timestamps), &attachments, (rec.frame, own, sky), depth, None);
    }

    /// [`PassState::draw`] with group 1 given: a pass that keeps one group per history parity.
    pub fn draw_with<'a>(
        &'a self,
        rec: (&mut wgpu::CommandEncoder, Option<wgpu::RenderPassTimestampWrites<'a>>),
        attachments: &'a [Option<wgpu::RenderPassColorAttachment<'a>>],
        groups: (&'a wgpu::BindGroup, &'a wgpu::BindGroup, Option<&'a wgpu::BindGroup>),
        viewport: Option<[f32; 4]>,
    ) {
        debug_assert!(!self.surfaces_only, "the {} pass draws only on surfaces: record it with `record`", self.name);
        self.draw_inner(rec, attachments, groups, None, viewport);
    }

    fn draw_inner<'a>(
        &'a self,
        rec: (&mut wgpu::CommandEncoder, Option<wgpu::RenderPassTimestampWrites<'a>>),
        attachments: &'a [Option<wgpu::RenderPassColorAttachment<'a>>],
        groups: (&'a wgpu::BindGroup, &'a wgpu::BindGroup, Option<&'a wgpu::BindGroup>),
        depth: Option<&'a wgpu::TextureView>,
        viewport: Option<[f32; 4]>,
    ) {
        let (encoder, timestamps) = rec;
        let Some((_, pipeline)) = self.pipeline.get() else {
            unreachable!("the {} pass recorded before `prepare`, or in a plan without it", self.name)
        };
        let (frame, own, sky) = groups;
        let all = [(0, frame), (1, own)];
        let with_sky;
        let bind_groups: &[(u32, &wgpu::BindGroup)] = match sky {
            Some(sky) => {
                with_sky = [(0, frame), (1, own), (2, sky)];
                &with_sky
            }
            None => &all,
        };
        FullscreenPass { label: &self.pass_label, attachments, depth, timestamps, pipeline, bind_groups, viewport }
            .record(encoder);
    }

    /// The pipeline (with its key) and the bind group. A pass recorded before `prepare`, or in a
    /// plan without it, is a bug, and says so.
    pub fn ready(&self) -> (&K, &wgpu::RenderPipeline, &wgpu::BindGroup) {
        match (self.pipeline.get(), &self.bind_group) {
            (Some(((key, _), pipeline)), Some(group)) => (key, pipeline, group),
            _ => unreachable!("the {} pass recorded before `prepare`, or in a plan without it", self.name),
        }
    }
}
