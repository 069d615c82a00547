//! The renderer: screen targets, the passes, and the plan for the current mode.
//!
//! A frame is the plan's steps in order (see [`modes::Step`]); [`Renderer::encode`] reads like
//! that list. Switching mode or light count rebuilds the plan and only what the new plan needs
//! differently; resizing rebuilds the targets and the passes' bind groups.

pub mod capture;
pub mod frame;
pub mod modes;
pub mod passes;
pub mod readback;
pub mod targets;
pub mod timing;
pub mod uniforms;

use glam::Vec3;

use crate::gpu::Gpu;
use crate::scene::{LightRig, OrbitCamera, PointLight, Scene, Skybox};
use crate::Result;
use frame::{FrameData, FrameInputs};
pub use modes::{Mode, Plan, SceneFeatures, Step};
use passes::composite::CompositePass;
use passes::gbuffer::{GBufferPass, SceneGpu};
use passes::light_cubes::LightCubesPass;
use passes::skybox::{sky_layout, SkyGpu, SkyboxPass};
use passes::tonemap::TonemapPass;
use targets::Targets;
use timing::GpuTimer;

/// What the user can change without reloading anything.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    pub mode: Mode,
    /// Multiplies HDR radiance before tone mapping.
    pub exposure: f32,
    /// Constant ambient radiance (grey), multiplied by albedo and AO.
    pub ambient: f32,
    /// Multiplies the sky's radiance (the background and, in SSDO, the sky light).
    pub sky_scale: f32,
}

impl Default for Settings {
    fn default() -> Self {
        Self { mode: Mode::Off, exposure: 1.0, ambient: 0.25, sky_scale: 1.0 }
    }
}

pub struct Renderer {
    pub settings: Settings,
    plan: Plan,
    lights: Vec<PointLight>,
    rig: LightRig,
    frame: FrameData,
    sky_layout: wgpu::BindGroupLayout,
    targets: Targets,
    scene: SceneGpu,
    sky: SkyGpu,
    gbuffer: GBufferPass,
    composite: CompositePass,
    skybox: SkyboxPass,
    light_cubes: LightCubesPass,
    tonemap: TonemapPass,
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
        let plan = Plan::new(settings.mode, SceneFeatures { lights: scene.lights.len() })?;
        let frame = FrameData::new(device);
        let sky_layout = sky_layout(device);
        let targets = Targets::new(device, size, &plan);
        let mut gbuffer = GBufferPass::new(gpu, &frame.layout)?;
        let scene_gpu = gbuffer.upload(gpu, &scene.model);
        let sky_gpu = SkyGpu::upload(gpu, &sky_layout, sky)?;
        let composite = CompositePass::new(device, &frame.layout, &targets, &plan)?;
        let skybox = SkyboxPass::new(device, &frame.layout, &sky_layout)?;
        let light_cubes = LightCubesPass::new(device, &frame.layout)?;
        let tonemap = TonemapPass::new(device, &frame.layout, &targets, output)?;
        gpu.check()?;
        Ok(Self {
            settings,
            plan,
            lights: scene.lights.clone(),
            rig: scene.rig,
            frame,
            sky_layout,
            targets,
            scene: scene_gpu,
            sky: sky_gpu,
            gbuffer,
            composite,
            skybox,
            light_cubes,
            tonemap,
            timer: None,
        })
    }

    pub fn plan(&self) -> &Plan {
        &self.plan
    }

    pub fn size(&self) -> (u32, u32) {
        self.targets.size
    }

    pub fn targets(&self) -> &Targets {
        &self.targets
    }

    /// Rebuilds the plan (and what depends on it) after a mode or light-count change.
    fn replan(&mut self, gpu: &Gpu) -> Result<()> {
        let plan = Plan::new(self.settings.mode, SceneFeatures { lights: self.lights.len() })?;
        if plan != self.plan {
            self.plan = plan;
            self.rebuild_targets(gpu);
        }
        Ok(())
    }

    fn rebuild_targets(&mut self, gpu: &Gpu) {
        self.targets = Targets::new(&gpu.device, self.targets.size, &self.plan);
        self.composite.resize(&gpu.device, &self.targets, &self.plan);
        self.tonemap.resize(&gpu.device, &self.targets);
        self.timer = self.timer.as_ref().map(|_| GpuTimer::new(gpu, &self.plan));
    }

    pub fn set_mode(&mut self, gpu: &Gpu, mode: Mode) -> Result<()> {
        let previous = self.settings.mode;
        self.settings.mode = mode;
        self.replan(gpu).inspect_err(|_| self.settings.mode = previous)
    }

    pub fn set_lights(&mut self, gpu: &Gpu, lights: Vec<PointLight>) -> Result<()> {
        self.lights = lights;
        self.replan(gpu)
    }

    /// Replaces the model and lights.
    pub fn set_scene(&mut self, gpu: &Gpu, scene: &Scene) -> Result<()> {
        self.scene = self.gbuffer.upload(gpu, &scene.model);
        self.rig = scene.rig;
        self.set_lights(gpu, scene.lights.clone())
    }

    /// Replaces the sky; on error the old sky stays.
    pub fn set_sky(&mut self, gpu: &Gpu, sky: &Skybox) -> Result<()> {
        self.sky = SkyGpu::upload(gpu, &self.sky_layout, sky)?;
        Ok(())
    }

    /// Resizes the screen targets; a zero size (a minimised window) is ignored.
    pub fn resize(&mut self, gpu: &Gpu, width: u32, height: u32) -> Result<()> {
        if width == 0 || height == 0 || (width, height) == self.targets.size {
            return Ok(());
        }
        gpu.check_size(width, height)?;
        self.targets.size = (width, height);
        self.rebuild_targets(gpu);
        Ok(())
    }

    /// Starts recording per-step GPU times (needs timestamp queries on the device).
    pub fn enable_timing(&mut self, gpu: &Gpu) -> bool {
        if gpu.timestamps && self.timer.is_none() {
            self.timer = Some(GpuTimer::new(gpu, &self.plan));
        }
        self.timer.is_some()
    }

    /// Per-step GPU milliseconds of the last frame submitted and waited for.
    pub fn read_timings(&self, gpu: &Gpu) -> Result<Option<Vec<(Step, f64)>>> {
        self.timer.as_ref().map(|t| t.read(gpu, &self.plan)).transpose()
    }

    /// Bytes allocated on the GPU, by name: screen targets first, then scene, sky and frame data.
    pub fn allocations(&self) -> Vec<(String, u64)> {
        let mut list: Vec<(String, u64)> =
            self.targets.allocations().into_iter().map(|(n, b)| (n.to_string(), b)).collect();
        list.push(("scene_geometry_and_materials".into(), self.scene.bytes));
        list.push(("sky_cubemap".into(), self.sky.bytes));
        list.push(("frame_uniforms_and_lights".into(), self.frame.bytes()));
        list
    }

    /// Records one frame of the current plan into `encoder`, drawing into `output`.
    pub fn encode(
        &mut self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        camera: &OrbitCamera,
        output: &wgpu::TextureView,
    ) {
        let scene = (&self.lights, &self.rig);
        let ambient = Vec3::splat(self.settings.ambient);
        let inputs = FrameInputs {
            size: self.targets.size,
            exposure: self.settings.exposure,
            ambient,
            sky_scale: self.settings.sky_scale * self.sky.encode_scale,
            sky_mips: self.sky.mip_levels,
        };
        self.frame.update(&gpu.device, &gpu.queue, camera, scene.0, scene.1, &inputs);
        let frame = &self.frame.bind_group;
        let t = &self.targets;
        for (index, step) in self.plan.steps.iter().enumerate() {
            let ts = self.timer.as_ref().map(|timer| timer.writes(index));
            encoder.push_debug_group(step.name());
            match step {
                // Geometry once: albedo, normal, depth.
                Step::GBuffer => self.gbuffer.encode(encoder, ts, t, frame, &self.scene),
                // Ambient, occlusion and direct light into HDR.
                Step::Composite => self.composite.encode(encoder, ts, t, frame),
                // Sky behind everything.
                Step::Skybox => self.skybox.encode(encoder, ts, t, frame, &self.sky),
                // Lights as emissive cubes.
                Step::LightCubes => self.light_cubes.encode(encoder, ts, t, frame, self.lights.len() as u32),
                // HDR to display.
                Step::Tonemap => self.tonemap.encode(encoder, ts, frame, output),
            }
            encoder.pop_debug_group();
        }
        if let Some(timer) = &self.timer {
            timer.resolve(encoder);
        }
    }
}
