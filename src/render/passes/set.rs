//! Every pass of the renderer in one place: built together, prepared together, and found by the
//! step they record. Adding a pass is a field here, its line in [`PassSet::new`], [`PassSet::each`]
//! and [`PassSet::get`], and its [`Step`] in the plan.

use super::blur::BlurPass;
use super::composite::CompositePass;
use super::depth_pyramid::DepthPyramidPass;
use super::gbuffer::GBufferPass;
use super::light_cubes::LightCubesPass;
use super::lighting::LightingPass;
use super::occlusion::OcclusionPass;
use super::sender_sky::SenderSkyPass;
use super::skybox::SkyboxPass;
use super::temporal::TemporalPass;
use super::tonemap::TonemapPass;
use super::upsample::UpsamplePass;
use super::{Pass, PassContext};
use crate::gpu::Gpu;
use crate::render::modes::Step;
use crate::Result;

pub struct PassSet {
    pub gbuffer: GBufferPass,
    pub pyramid: DepthPyramidPass,
    pub sender_sky: SenderSkyPass,
    pub lighting: LightingPass,
    pub occlusion: OcclusionPass,
    pub upsample: UpsamplePass,
    pub blur: BlurPass,
    pub temporal: TemporalPass,
    pub composite: CompositePass,
    pub skybox: SkyboxPass,
    pub light_cubes: LightCubesPass,
    pub tonemap: TonemapPass,
}

impl PassSet {
    /// Builds every pass: what lives as long as the renderer (layouts, shaders, pipelines that
    /// depend on nothing else). `frame` and `sky` are the layouts of bind groups 0 and 2.
    pub fn new(
        gpu: &Gpu,
        frame: &wgpu::BindGroupLayout,
        sky: &wgpu::BindGroupLayout,
        output: wgpu::TextureFormat,
    ) -> Result<Self> {
        let cx = PassContext { gpu, device: &gpu.device, frame_layout: frame, sky_layout: sky, output };
        Ok(Self {
            gbuffer: GBufferPass::new(&cx)?,
            pyramid: DepthPyramidPass::new(&cx)?,
            sender_sky: SenderSkyPass::new(&cx)?,
            lighting: LightingPass::new(&cx)?,
            occlusion: OcclusionPass::new(&cx)?,
            upsample: UpsamplePass::new(&cx)?,
            blur: BlurPass::new(&cx)?,
            temporal: TemporalPass::new(&cx)?,
            composite: CompositePass::new(&cx)?,
            skybox: SkyboxPass::new(&cx)?,
            light_cubes: LightCubesPass::new(&cx)?,
            tonemap: TonemapPass::new(&cx)?,
        })
    }

    /// Calls `f` on every pass, whether the plan runs it or not.
    pub fn each(&mut self, mut f: impl FnMut(&mut dyn Pass)) {
        let passes: [&mut dyn Pass; 12] = [
            &mut self.gbuffer,
            &mut self.pyramid,
            &mut self.sender_sky,
            &mut self.lighting,
            &mut self.occlusion,
            &mut self.upsample,
            &mut self.blur,
            &mut self.temporal,
            &mut self.composite,
            &mut self.skybox,
            &mut self.light_cubes,
            &mut self.tonemap,
        ];
        for pass in passes {
            f(pass);
        }
    }

    /// The pass that records `step`: the frame's table of contents.
    pub fn get(&self, step: Step) -> &dyn Pass {
        match step {
            // Geometry once: albedo, normal, depth.
            Step::GBuffer => &self.gbuffer,
            // The closest depth per block, for the march's far steps.
            Step::DepthPyramid => &self.pyramid,
            // The sky each sender sees, at half resolution.
            Step::SenderSky => &self.sender_sky,
            // Each surface's direct light: the radiance SSDO bounces, and the point lights' light.
            Step::Lighting => &self.lighting,
            // AO and/or DO from one set of samples.
            Step::Occlusion => &self.occlusion,
            // Half-resolution AO/DO to full resolution, on each pixel's own surface.
            Step::Upsample => &self.upsample,
            // Denoise AO/DO.
            Step::Blur => &self.blur,
            // Average AO/DO over frames, where the same surface was.
            Step::Temporal => &self.temporal,
            // The sky and ambient terms with AO/DO, direct light (and, in a display plan, the sky
            // behind and the tone curve, into the output).
            Step::Composite => &self.composite,
            // Sky behind everything (HDR plans).
            Step::Skybox => &self.skybox,
            // Lights as emissive cubes.
            Step::LightCubes => &self.light_cubes,
            // HDR to display (HDR plans).
            Step::Tonemap => &self.tonemap,
        }
    }
}
