//! The far side layer (`--far-side`): a second geometry pass that draws the model with the faces
//! towards the camera culled, so each pixel holds the nearest surface turned away from the eye —
//! a closed fin's or box's far face, an underside, the other side of a sheet seen from behind
//! (`gbuffer.wgsl`, `fs_far_side`): its normal, albedo and depth. The lighting pass lights it as
//! a sender of SSDO's bounce beside the surface the screen shows, and the march takes its light
//! where that surface faces away from the receiver: the senders the G-buffer cannot hold because
//! they face away from the camera. Its fragments only store: lit here, the point lights' loop
//! ran for every face drawn over another (25.6 ms against 9.1 for the pass in the room at
//! 800x600, lavapipe).

use super::gbuffer::{begin_model_pass, material_entries, model_pipeline};
use crate::gpu::Gpu;
use crate::render::graph::io::PassIo;
use crate::render::graph::{Entry, Pass, PassContext, Recording};
use crate::render::modes::{Plan, PlanFacts, Step};
use crate::render::resources::scene::{Features, SceneGpu};
use crate::render::targets::{Place, TargetId, DEPTH_FORMAT};
use crate::scene::Model;
use crate::{shaders, Result};

impl Step {
    pub const FAR_SIDE: Step = Step::new("far_side");
}

pub const ENTRY: Entry = Entry::new(Step::FAR_SIDE, runs, FarSidePass::io, |cx| Ok(Box::new(FarSidePass::new(cx)?)));

/// Where a DO mode bounces light, the far side is asked for, and there is light to light it:
/// point lights, or the sky its own march measures (`--far-sky`, `far_sky.rs`).
pub fn runs(f: &PlanFacts) -> bool {
    f.bounces() && f.options.far_side && (f.lights() || sky(f))
}

/// Whether the far side's surfaces take the sky they see (`far_sky.rs`): asked for, and the
/// senders take the sky at all.
pub fn sky(f: &PlanFacts) -> bool {
    f.options.far_sky && f.sender_sky() != crate::render::SenderSky::Off
}

/// The far side's surfaces: the packed normal and shininess as the G-buffer packs them (x), the
/// albedo (y, four 8-bit channels) and the depth's bits (z; 0 where there is none).
pub const FAR_SURFACE: TargetId = TargetId::new("far_surface", wgpu::TextureFormat::Rgba32Uint, Place::Screen);
/// The depth the sampling pass marches where there is a far side (written by the lighting pass):
/// the G-buffer's depth bits, the low nine replaced by each surface's extent behind it, the
/// distance to the far side's face behind it where there is one (`common/thickness.wgsl`
/// `extent_code`), else its thickness layer's code.
pub const EXTENT_LAYER: TargetId =
    TargetId::new("depth_extent", crate::render::targets::THICKNESS_FORMAT, Place::Screen);
/// The far side's own depth test (reverse-Z: the nearest of the faces turned away wins).
pub const FAR_DEPTH: TargetId = TargetId::new("far_side_depth", DEPTH_FORMAT, Place::Screen);

pub struct FarSidePass {
    pipeline_layout: wgpu::PipelineLayout,
    module: wgpu::ShaderModule,
    /// The pipelines of each set of material features a model has needed.
    pipelines: std::collections::HashMap<Features, wgpu::RenderPipeline>,
}

impl FarSidePass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        let module = shaders::module(cx.device, "gbuffer.wgsl")?;
        // The G-buffer's material layout, entry for entry: the scene's material bind groups,
        // made for that pass, bind here too.
        let material_layout = cx.layout("gbuffer_material_layout", &material_entries());
        let pipeline_layout = cx.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("far_side_pipeline_layout"),
            bind_group_layouts: &[Some(cx.frame_layout), Some(&material_layout)],
            immediate_size: 0,
        });
        Ok(Self { pipeline_layout, module, pipelines: Default::default() })
    }

    /// The model and its materials; the far side's surfaces and its depth.
    pub fn io(_plan: &Plan) -> PassIo {
        PassIo { reads: vec![], attached: vec![], writes: vec![FAR_SURFACE, FAR_DEPTH] }
    }

    fn pipeline(&self, device: &wgpu::Device, features: Features) -> wgpu::RenderPipeline {
        let fragment = ("fs_far_side", &[Some(FAR_SURFACE.format.into())][..]);
        model_pipeline(device, &self.pipeline_layout, &self.module, features, Some(wgpu::Face::Front), fragment)
    }
}

impl Pass for FarSidePass {
    /// Builds the pipelines the model's materials need (the G-buffer pass uploads the model).
    fn upload_scene(&mut self, gpu: &Gpu, model: &Model, _thickness: &[u32]) -> Option<SceneGpu> {
        for part in &model.parts {
            let features = Features::of(&model.materials[part.material], model.has_tangents());
            if !self.pipelines.contains_key(&features) {
                let pipeline = self.pipeline(&gpu.device, features);
                self.pipelines.insert(features, pipeline);
            }
        }
        None
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, scene, .. } = rec;
        let attachment = crate::render::graph::io::color_attachment;
        let colors = [attachment(&targets.expect(FAR_SURFACE).view, true)];
        let depth = (&targets.expect(FAR_DEPTH).view, wgpu::StoreOp::Discard);
        let mut pass = begin_model_pass(encoder, "far_side_pass", &colors, depth, timestamps, frame, scene);
        for draw in &scene.draws {
            pass.set_pipeline(&self.pipelines[&draw.features.with_layer(false)]);
            pass.set_bind_group(1, &draw.bind_group, &[]);
            pass.draw_indexed(draw.first_index..draw.first_index + draw.index_count, 0, 0..1);
        }
    }
}
