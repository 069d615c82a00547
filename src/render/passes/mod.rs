//! The passes of a frame, one module each (what a pass is made of is `graph/`), and their list in
//! frame order — the frame's table of contents — with what follows from their declarations: the
//! plan for a mode (each pass's own rule says whether it runs), what each step of it reads and
//! writes, the targets it allocates, and the passes themselves, built together, prepared together
//! and found by their step. Adding a pass is its WGSL, its module here, and its two lines in this
//! file: `mod` and its [`Entry`] in [`PASSES`].

pub mod blur;
pub mod composite;
pub mod depth_pyramid;
pub mod far_side;
pub mod far_sky;
pub mod gbuffer;
pub mod light_cubes;
pub mod lighting;
pub mod sampling;
pub mod sender_sky;
pub mod skybox;
pub mod temporal;
pub mod tonemap;
pub mod upsample;

use crate::gpu::Gpu;
use crate::render::graph::io::PassIo;
use crate::render::graph::{Entry, Pass, PassContext, Preparation, Recording, Role};
use crate::render::modes::{Mode, Plan, PlanFacts, PlanOptions, SceneFeatures, Step};
use crate::render::resources::scene::SceneGpu;
use crate::render::targets::TargetId;
use crate::scene::Model;
use crate::Result;

/// Every pass, in the order a frame runs them.
pub const PASSES: [Entry; 14] = [
    // Geometry once: albedo, normal, depth.
    gbuffer::ENTRY,
    // The nearest surfaces turned away from the eye, lit as senders (`--far-side`).
    far_side::ENTRY,
    // The closest depth per block, for the march's far steps.
    depth_pyramid::ENTRY,
    // The sky each sender sees, at half resolution.
    sender_sky::ENTRY,
    // The sky each far side surface sees, at quarter resolution (`--far-sky`).
    far_sky::ENTRY,
    // Each surface's direct light: the radiance SSDO bounces, and the point lights' light.
    lighting::ENTRY,
    // AO and/or DO from one set of samples.
    sampling::ENTRY,
    // Denoise AO/DO, where the samples are (at half resolution when they were taken there).
    blur::ENTRY,
    // Average AO/DO over frames, where the same surface was (at the samples' size).
    temporal::ENTRY,
    // A full-size copy of a half-size chain for an HDR plan's readers (the composite upsamples
    // as it reads), each pixel from the samples on its own surface.
    upsample::ENTRY,
    // The sky and ambient terms with AO/DO, direct light (and, in a display plan, the sky behind
    // and the tone curve, into the output).
    composite::ENTRY,
    // Sky behind everything (HDR plans).
    skybox::ENTRY,
    // Lights as emissive cubes.
    light_cubes::ENTRY,
    // HDR to display (HDR plans).
    tonemap::ENTRY,
];

/// What `step`'s pass is for, as `bench` splits a frame.
pub fn role(step: Step) -> Role {
    entry(step).role
}

fn entry(step: Step) -> &'static Entry {
    PASSES.iter().find(|e| e.step == step).unwrap_or_else(|| panic!("no pass for step {}", step.name()))
}

/// A step's reads (the targets the plan has, bound or attached) and writes in one plan.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StepIo {
    pub reads: Vec<TargetId>,
    pub writes: Vec<TargetId>,
}

impl Step {
    /// What this step reads and writes in `plan`, as its pass declares them.
    pub fn io(self, plan: &Plan) -> StepIo {
        let io: PassIo = (entry(self).io)(plan);
        StepIo { reads: io.targets_read(), writes: io.writes }
    }
}

impl Plan {
    /// The steps of `mode` for a scene with `features` and the options `o`: every pass whose
    /// rule says it runs, in frame order.
    pub fn new(mode: Mode, features: SceneFeatures, o: PlanOptions) -> Self {
        let facts = PlanFacts { decl: *mode.declaration(), features, options: o };
        let steps: Vec<Step> = PASSES.iter().filter(|e| (e.runs)(&facts)).map(|e| e.step).collect();
        let has = |step: Step| steps.contains(&step);
        let history = PASSES.iter().filter(|e| has(e.step)).flat_map(|e| (e.histories)(&facts)).collect();
        Self {
            mode,
            decl: facts.decl,
            features,
            blur: has(Step::BLUR) || (has(Step::TEMPORAL) && facts.temporal_blurs()),
            temporal_blurs: has(Step::TEMPORAL) && facts.temporal_blurs(),
            display: o.display,
            sender_sky: facts.sender_sky(),
            // The sampling pass runs at half size, and so do its blur and the temporal pass;
            // the composite upsamples as it reads.
            half_resolution: facts.half_resolution(),
            accumulates: has(Step::TEMPORAL),
            lighting: has(Step::LIGHTING),
            pyramid: has(Step::DEPTH_PYRAMID),
            sender_march: has(Step::SENDER_SKY),
            thickness_layer: features.thin_materials && o.material_thickness,
            far_side: has(Step::FAR_SIDE),
            extent_layer: has(Step::FAR_SIDE) && o.material_thickness,
            steps,
            history,
        }
    }

    /// Every step's inputs and outputs, in order.
    pub fn io(&self) -> Vec<(Step, StepIo)> {
        self.steps.iter().map(|&s| (s, s.io(self))).collect()
    }

    /// Whether a step of this plan writes `target`.
    pub fn writes(&self, target: TargetId) -> bool {
        self.steps.iter().any(|s| s.io(self).writes.contains(&target))
    }

    /// The screen targets this plan allocates: those its steps write, in the order they are
    /// first written (the G-buffer's three first).
    pub fn targets(&self) -> Vec<TargetId> {
        let mut out: Vec<TargetId> = Vec::new();
        for write in self.steps.iter().flat_map(|s| s.io(self).writes) {
            if write.allocated() && !out.contains(&write) {
                out.push(write);
            }
        }
        out
    }

    /// Whether the plan allocates `target`.
    pub fn allocates(&self, target: TargetId) -> bool {
        self.targets().contains(&target)
    }
}

/// Every pass of the renderer, built once, in the order of [`PASSES`].
pub struct PassSet {
    passes: Vec<(Step, Box<dyn Pass>)>,
}

impl PassSet {
    /// Builds every pass: what lives as long as the renderer (shaders, samplers, pipelines that
    /// depend on nothing else). `frame` and `sky` are the layouts of bind groups 0 and 2.
    pub fn new(
        gpu: &Gpu,
        frame: &wgpu::BindGroupLayout,
        sky: &wgpu::BindGroupLayout,
        output: wgpu::TextureFormat,
    ) -> Result<Self> {
        let cx = PassContext { gpu, device: &gpu.device, frame_layout: frame, sky_layout: sky, output };
        let passes = PASSES.iter().map(|e| Ok((e.step, (e.build)(&cx)?))).collect::<Result<_>>()?;
        Ok(Self { passes })
    }

    /// Rebuilds every pass's bind groups and pipelines for `p`, whether the plan runs it or not
    /// (a pass the plan lacks drops what it held).
    pub fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        for (_, pass) in &mut self.passes {
            pass.prepare(device, p);
        }
    }

    /// Calls `f` on every pass, whether the plan runs it or not.
    pub fn each(&mut self, mut f: impl FnMut(&mut dyn Pass)) {
        for (_, pass) in &mut self.passes {
            f(pass.as_mut());
        }
    }

    /// Records `step` (a step of the plan).
    pub fn record(&self, step: Step, rec: Recording<'_>) {
        let pass = self.passes.iter().find(|(s, _)| *s == step).map(|(_, p)| p);
        pass.unwrap_or_else(|| panic!("no pass for step {}", step.name())).record(rec);
    }

    /// Uploads `model` through the pass that draws it, with its materials' thickness codes.
    pub fn upload_scene(&mut self, gpu: &Gpu, model: &Model, thickness: &[u32]) -> SceneGpu {
        // Every pass sees the model (the far side builds its pipelines for its materials); the
        // G-buffer pass uploads it.
        let mut uploaded = None;
        for (_, pass) in &mut self.passes {
            if let Some(scene) = pass.upload_scene(gpu, model, thickness) {
                uploaded.get_or_insert(scene);
            }
        }
        uploaded.expect("the G-buffer pass draws the scene")
    }
}

#[cfg(test)]
mod tests;
