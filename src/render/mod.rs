//! The renderer: screen targets, the passes, and the plan for the current mode.
//!
//! A frame is the plan's steps in order (see [`modes::Step`]); [`Renderer::encode`] reads like
//! that list. Switching mode or light count rebuilds the plan and only what the new plan needs
//! differently; resizing rebuilds the targets and the passes' bind groups.

mod accumulation;
pub mod bindings;
mod derived;
pub mod frame;
pub mod graph;
pub mod history;
mod inspect;
pub mod kernel;
pub mod modes;
pub mod passes;
pub mod resources;
pub mod sampling;
pub mod senders;
pub mod settings;
pub mod surface_pack;
pub mod targets;
pub mod timer;
pub mod uniforms;
pub mod variant;

use glam::Vec3;

use crate::budget::{self, Share};
use crate::gpu::Gpu;
use crate::scene::thickness::FULL_THICKNESS;
use crate::scene::{LightRig, OrbitCamera, PointLight, Scene, Skybox};
use crate::{Error, Result};
pub use accumulation::{BLURRED_FRAMES, CUT_TURN_DEG, SLOW_TURN_DEG};
use frame::FrameData;
use graph::io::{Fallbacks, Inputs};
use graph::{FrameState, Preparation, Recording};
use history::{History, StillView};
pub use modes::{Mode, Plan, PlanOptions, SceneFeatures, Step};
use passes::PassSet;
pub use passes::StepIo;
use resources::sampling::SamplingData;
use resources::scene::SceneGpu;
use resources::sky::{sky_layout, SkyGpu};
pub use sampling::{GivenLengths, Lengths, REACH_RADII, THICKNESS_RADII};
pub use senders::SenderSky;
pub use settings::{motion_accumulate, Settings, View};
pub use targets::TargetId;
use targets::Targets;
use timer::GpuTimer;
pub use uniforms::{UNIFORM_LIGHTS, UNROLLED_LIGHTS};
pub use variant::{Count, Variant, VariantDecl, ACCUMULATE, SAMPLES, SLICES, STEPS};

/// Where a frame is drawn: a view of the output, and the image's top-left corner in it (the
/// viewer draws beside its panel).
#[derive(Clone, Copy)]
pub struct Canvas<'a> {
    pub view: &'a wgpu::TextureView,
    pub origin: (u32, u32),
}

impl<'a> From<&'a wgpu::TextureView> for Canvas<'a> {
    fn from(view: &'a wgpu::TextureView) -> Self {
        Self { view, origin: (0, 0) }
    }
}

pub struct Renderer {
    pub settings: Settings,
    plan: Plan,
    /// The variant and view the passes were last prepared for.
    prepared: (Variant, View),
    lights: Vec<PointLight>,
    rig: LightRig,
    /// Default sampling radius of the current scene.
    scene_radius: f32,
    /// The sky's E(n)/π as spherical harmonics (`Skybox::irradiance`), in its own radiance.
    sky_sh: [Vec3; 9],
    frame: FrameData,
    sampling_data: SamplingData,
    sky_layout: wgpu::BindGroupLayout,
    /// Bound where a pass's input does not exist in the current plan.
    fallbacks: Fallbacks,
    targets: Targets,
    /// Targets that survive frames and re-plans (the temporal pass's).
    history: History,
    /// The settings the history was accumulated under: another meaning starts it anew.
    history_settings: Settings,
    /// Frames recorded since the camera last moved, counting the one it moved in (0 before a
    /// first frame and after a reset), with that frame's camera and the history it went into.
    still: StillView,
    /// The entry of the sample schedule a history's first frame takes (0, but where the report
    /// measures a single frame under each entry: [`Renderer::start_schedule_at`]).
    schedule_start: u32,
    scene: SceneGpu,
    sky: SkyGpu,
    passes: PassSet,
    /// Format of what `encode` draws into.
    output: wgpu::TextureFormat,
    /// Keep the HDR image for reading back after the frame (see [`Renderer::keep_hdr`]).
    keep_hdr: bool,
    timer: Option<GpuTimer>,
}

impl Renderer {
    /// Builds everything for `scene` under `sky` at `size`, drawing into `output` format.
    pub fn new(
        gpu: &Gpu,
        scene: &Scene,
        sky: &Skybox,
        size: (u32, u32),
        output: wgpu::TextureFormat,
        settings: Settings,
    ) -> Result<Self> {
        gpu.check_size(size.0, size.1)?;
        let device = &gpu.device;
        // As the G-buffer's upload decides (`GBufferPass::upload`).
        let normal_mapped = scene.model.is_normal_mapped() && scene.model.has_tangents();
        let thickness = scene.model.thickness_codes();
        let thin_materials = thickness.iter().any(|&c| c < FULL_THICKNESS);
        let smooth_normals = scene.model.has_smooth_normals();
        let features = SceneFeatures { lights: scene.lights.len(), normal_mapped, thin_materials, smooth_normals };
        Self::check_memory(size, &settings, features, false, &[settings.mode])?;
        let plan = Self::plan_for(&settings, features, false);
        let frame = FrameData::new(device);
        let sky_layout = sky_layout(device);
        let targets = Targets::new(device, size, &plan.targets());
        let mut history = History::default();
        history.ensure(device, plan.history_size(size), &plan.history);
        let mut passes = PassSet::new(gpu, &frame.layout, &sky_layout, output)?;
        let scene_gpu = passes.upload_scene(gpu, &scene.model, &thickness);
        let sky_gpu = SkyGpu::upload(gpu, &sky_layout, sky)?;
        let mut renderer = Self {
            settings,
            prepared: (settings.knobs.variant, settings.view),
            lights: scene.lights.clone(),
            rig: scene.rig,
            scene_radius: scene.default_radius(),
            sky_sh: sky.irradiance,
            sampling_data: SamplingData::new(device),
            output,
            keep_hdr: false,
            plan,
            frame,
            sky_layout,
            fallbacks: Fallbacks::new(device),
            targets,
            history,
            history_settings: settings,
            still: StillView::default(),
            schedule_start: 0,
            scene: scene_gpu,
            sky: sky_gpu,
            passes,
            timer: None,
        };
        renderer.prepare_passes(gpu);
        gpu.check()?;
        Ok(renderer)
    }

    pub fn plan(&self) -> &Plan {
        &self.plan
    }

    pub fn size(&self) -> (u32, u32) {
        self.targets.size
    }

    /// The format `encode` draws into.
    pub fn output_format(&self) -> wgpu::TextureFormat {
        self.output
    }

    pub fn targets(&self) -> &Targets {
        &self.targets
    }

    /// Brings the plan, targets and pipelines in line with the settings and lights: only what a
    /// change affects is rebuilt. Called by [`Renderer::encode`]; call it to read the new plan.
    pub fn apply(&mut self, gpu: &Gpu) {
        // A setting that changes what is averaged starts the average anew.
        if !self.settings.same_history(&self.history_settings) {
            self.history.reset();
            self.history_settings = self.settings;
        }
        let plan = Self::plan_for(&self.settings, self.features(), self.keep_hdr);
        if plan != self.plan {
            self.plan = plan;
            self.rebuild_targets(gpu);
        } else if (self.settings.knobs.variant, self.settings.view) != self.prepared {
            self.prepare_passes(gpu);
        }
    }

    /// What the current scene brings to the plan.
    fn features(&self) -> SceneFeatures {
        let (normal_mapped, thin_materials) = (self.scene.normal_mapped, self.scene.thin_materials);
        let smooth_normals = self.scene.smooth_normals;
        SceneFeatures { lights: self.lights.len(), normal_mapped, thin_materials, smooth_normals }
    }

    /// The plan of `settings` for a scene with `features`: a display plan (no HDR after the
    /// frame) unless HDR is kept or a debug view needs the tone-map pass.
    fn plan_for(settings: &Settings, features: SceneFeatures, keep_hdr: bool) -> Plan {
        let options = PlanOptions::of(settings, keep_hdr);
        Plan::new(settings.mode, features, options)
    }

    /// Keeps the linear HDR image of each frame in `targets().hdr` for reading back (the report,
    /// `--raw`, `--stats`, tests). Off by default: the final image is then tone-mapped by the
    /// composite straight into the output, with no HDR write, skybox or tone-map pass.
    pub fn keep_hdr(&mut self, gpu: &Gpu, keep: bool) {
        self.keep_hdr = keep;
        self.apply(gpu);
    }

    /// Whether the HDR image is kept ([`Renderer::keep_hdr`]).
    pub fn keeps_hdr(&self) -> bool {
        self.keep_hdr
    }

    fn rebuild_targets(&mut self, gpu: &Gpu) {
        self.targets = Targets::new(&gpu.device, self.targets.size, &self.plan.targets());
        // A history outlives the re-plan unless its size or its own inputs changed.
        self.history.ensure(&gpu.device, self.plan.history_size(self.targets.size), &self.plan.history);
        self.prepare_passes(gpu);
        self.timer = self.timer.as_ref().map(|_| GpuTimer::new(gpu, &self.plan));
    }

    /// Rebuilds the passes' bind groups for the targets, and their pipelines where the plan or
    /// variant asks for a different one.
    fn prepare_passes(&mut self, gpu: &Gpu) {
        let (variant, view) = (self.settings.knobs.variant, self.settings.view);
        let inputs = Inputs {
            targets: &self.targets,
            history: &self.history,
            sampling: &self.sampling_data.buffer,
            filter: &self.sampling_data.filter_buffer,
            fallbacks: &self.fallbacks,
        };
        let preparation = Preparation { plan: &self.plan, variant, view, inputs };
        self.passes.prepare(&gpu.device, &preparation);
        self.prepared = (variant, view);
    }

    /// The frame uniforms of the last frame recorded.
    pub fn frame_uniforms(&self) -> &uniforms::FrameUniforms {
        self.frame.uniforms()
    }

    pub fn set_mode(&mut self, gpu: &Gpu, mode: Mode) {
        self.settings.mode = mode;
        self.apply(gpu);
    }

    pub fn set_lights(&mut self, gpu: &Gpu, lights: Vec<PointLight>) {
        self.lights = lights;
        self.history.reset();
        self.apply(gpu);
    }

    /// Replaces the model and lights.
    pub fn set_scene(&mut self, gpu: &Gpu, scene: &Scene) {
        self.scene = self.passes.upload_scene(gpu, &scene.model, &scene.model.thickness_codes());
        self.rig = scene.rig;
        self.scene_radius = scene.default_radius();
        self.set_lights(gpu, scene.lights.clone());
    }

    /// Whether the current model needs the textured G-buffer pipeline.
    pub fn uses_texture_path(&self) -> bool {
        self.scene.textured
    }

    /// Fails before anything is allocated when the targets of any of `modes` at `size`, with
    /// the output image and its readback copy, would not fit the memory budget's share for
    /// render targets.
    pub fn check_memory(
        size: (u32, u32),
        settings: &Settings,
        features: SceneFeatures,
        keep_hdr: bool,
        modes: &[Mode],
    ) -> Result<()> {
        let pixels = size.0 as u64 * size.1 as u64;
        for &mode in modes {
            let plan = Self::plan_for(&Settings { mode, ..*settings }, features, keep_hdr);
            // The 8-bit output and its readback; with the HDR image kept, its f32 readback too.
            let output = pixels * (8 + if keep_hdr { 16 } else { 0 });
            let history: u64 = plan.history.iter().map(|h| h.bytes(plan.history_size(size))).sum();
            let bytes = Targets::bytes_for(size, &plan.targets()) + history + output;
            budget::check(Share::Targets, bytes, || format!("{}x{} in {}", size.0, size.1, mode.title()))
                .map_err(Error::Setting)?;
        }
        Ok(())
    }

    /// Replaces the sky; on error the old sky stays.
    pub fn set_sky(&mut self, gpu: &Gpu, sky: &Skybox) -> Result<()> {
        self.sky = SkyGpu::upload(gpu, &self.sky_layout, sky)?;
        self.sky_sh = sky.irradiance;
        self.history.reset();
        Ok(())
    }

    /// Resizes the screen targets; a zero size (a minimised window) is ignored.
    pub fn resize(&mut self, gpu: &Gpu, width: u32, height: u32) -> Result<()> {
        if width == 0 || height == 0 || (width, height) == self.targets.size {
            return Ok(());
        }
        gpu.check_size(width, height)?;
        let features = self.features();
        Self::check_memory((width, height), &self.settings, features, self.keep_hdr, &[self.settings.mode])?;
        self.targets.size = (width, height);
        // The plan of the settings as they are now (the variant decides what lights the senders).
        self.plan = Self::plan_for(&self.settings, features, self.keep_hdr);
        self.rebuild_targets(gpu);
        Ok(())
    }

    /// Records one frame of the current plan into `encoder`, drawing into `canvas`: a view of
    /// the output (the image at its top-left corner), or a [`Canvas`] that places it.
    pub fn encode<'a>(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        camera: &OrbitCamera,
        canvas: impl Into<Canvas<'a>>,
    ) {
        let Canvas { view: output, origin } = canvas.into();
        self.apply(gpu);
        if self.cuts_to(camera) {
            self.reset_history();
        }
        self.still.count(camera, self.history.get(modes::OCCLUSION_HISTORY));
        self.upload_frame(gpu, camera, origin);
        let frame_index = self.frame.uniforms().frame_index;
        let camera_moved = self.frame.camera_moved;
        let blur = self.blurs();
        let state = FrameState { plan: &self.plan, frame_index, history: &self.history, camera_moved, blur };
        self.passes.each(|pass| pass.begin_frame(&state));
        for (index, &step) in self.plan.steps.iter().enumerate() {
            encoder.push_debug_group(step.name_in(self.plan.mode));
            self.passes.record(
                step,
                Recording {
                    encoder,
                    timestamps: self.timer.as_ref().map(|timer| timer.writes(index)),
                    targets: &self.targets,
                    plan: &self.plan,
                    frame: &self.frame.bind_group,
                    sky: &self.sky,
                    scene: &self.scene,
                    lights: self.lights.len() as u32,
                    light_order: &self.frame.cube_order,
                    output,
                    origin,
                    history: &self.history,
                },
            );
            encoder.pop_debug_group();
        }
        // What this frame wrote is what the next one reads.
        self.history.advance();
        if let Some(timer) = &mut self.timer {
            timer.resolve(encoder);
        }
    }
}
