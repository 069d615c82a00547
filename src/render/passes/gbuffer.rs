//! G-buffer pass: the deferred renderer's geometry pass. It rasterises every face of the model
//! once, two-sided, into albedo + specular strength, view-space normal + shininess, and reverse-Z
//! depth (cleared to 0, compared with `Greater`). Every mode reads these; position is
//! reconstructed from depth. A material that reads maps draws its faces seen from the front in a
//! first round and those seen from behind in a second (`Sides`).
//!
//! Each material draws with the pipeline of what it reads ([`Features`]: colour maps, a normal
//! map, a cutout), built when a model first needs it: untextured opaque materials use the plain
//! one, which never samples or discards. Tangents are a second vertex buffer, which only a model
//! with a normal map has.
//!
//! In a display plan the pass then draws the sky, as it will be displayed, into the albedo of
//! the pixels no geometry covered (a full-screen triangle at the far plane behind a depth test,
//! so a covered pixel costs its depth test alone); the composite shows those pixels as they are.
//! A frame the model fills pays nothing for the sky (the composite evaluating it for every pixel
//! was 2.9 of its 17 ms in the classic program's room, lavapipe: a shader there costs both sides
//! of every branch).

use wgpu::util::DeviceExt;

use crate::gpu::Gpu;
use crate::render::bindings::{sampler_entry, texture_entry, uniform_entry};
use crate::render::graph::io::PassIo;
use crate::render::graph::{Entry, Pass, PassContext, Recording};
use crate::render::modes::{Plan, Step};
use crate::render::resources::maps::MaterialMaps;
use crate::render::resources::scene::{Draw, Features, SceneGpu};
use crate::render::surface_pack::shininess_bits;
use crate::render::targets::{ALBEDO, ALBEDO_FORMAT, DEPTH, DEPTH_FORMAT, NORMAL, NORMAL_FORMAT};
use crate::render::targets::{THICKNESS, THICKNESS_FORMAT};
use crate::render::uniforms::MaterialParams;
use crate::scene::model::Material;
use crate::scene::thickness::FULL_THICKNESS;
use crate::scene::{Model, Vertex};
use crate::{shaders, Result};

impl Step {
    pub const GBUFFER: Step = Step::new("gbuffer");
}

pub const ENTRY: Entry = Entry::new(Step::GBUFFER, |_| true, GBufferPass::io, |cx| Ok(Box::new(GBufferPass::new(cx)?)));

/// How a material's faces are drawn; every face is drawn, two-sided, in one of two rounds. A
/// material that reads maps draws the faces the camera sees from the side their normals point to
/// in the first round (back faces culled) and the faces it sees from behind in the second (front
/// faces culled): a closed surface's far side then fails the depth test before its fragments
/// read the maps, where in the model's own order it was shaded and then covered about half the
/// time. (Of two faces at one depth, the one facing the camera now wins.) A plain material draws
/// all its faces in the first round: its fragments cost less than setting its triangles up twice
/// (docs/performance.md).
struct Sides {
    first: wgpu::RenderPipeline,
    second: Option<wgpu::RenderPipeline>,
}

impl Sides {
    fn new(
        device: &wgpu::Device,
        layout: &wgpu::PipelineLayout,
        module: &wgpu::ShaderModule,
        features: Features,
    ) -> Self {
        let pipeline = |culled| GBufferPass::pipeline(device, layout, module, features, culled);
        if features.with_layer(false) == Features::default() {
            Self { first: pipeline(None), second: None }
        } else {
            Self { first: pipeline(Some(wgpu::Face::Back)), second: Some(pipeline(Some(wgpu::Face::Front))) }
        }
    }

    /// The pipeline of the first round or of the second (none: the material has no second).
    fn round(&self, second: bool) -> Option<&wgpu::RenderPipeline> {
        if second {
            self.second.as_ref()
        } else {
            Some(&self.first)
        }
    }
}

pub struct GBufferPass {
    pub material_layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    /// The pipelines of each set of features a model has needed (the plain one from the start).
    pipelines: std::collections::HashMap<Features, Sides>,
    pipeline_layout: wgpu::PipelineLayout,
    module: wgpu::ShaderModule,
    /// The displayed sky behind the geometry (display plans), without the thickness layer and
    /// with it.
    sky: [wgpu::RenderPipeline; 2],
}

impl GBufferPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        let (device, frame_layout) = (cx.device, cx.frame_layout);
        let module = shaders::module(device, "gbuffer.wgsl")?;
        let material_layout = cx.layout("gbuffer_material_layout", &material_entries());
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("gbuffer_pipeline_layout"),
            bind_group_layouts: &[Some(frame_layout), Some(&material_layout)],
            immediate_size: 0,
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("gbuffer_material_sampler"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        let plain = Sides::new(device, &pipeline_layout, &module, Features::default());
        let pipelines = [(Features::default(), plain)].into_iter().collect();
        // The albedo alone; the normal (and the thickness layer) are left as cleared.
        let kept = |format| wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::empty() };
        let targets = [Some(ALBEDO_FORMAT.into()), Some(kept(NORMAL_FORMAT)), Some(kept(THICKNESS_FORMAT))];
        let sky = [
            super::skybox::behind_geometry(cx, "gbuffer_sky_pipeline", "fs_display", &targets[..2])?,
            super::skybox::behind_geometry(cx, "gbuffer_sky_thickness_pipeline", "fs_display", &targets)?,
        ];
        Ok(Self { material_layout, sampler, pipelines, pipeline_layout, module, sky })
    }

    /// The model and its materials (its own bind groups); the G-buffer, depth last, and the
    /// thickness layer where the plan has it.
    pub fn io(plan: &Plan) -> PassIo {
        let mut writes = vec![ALBEDO, NORMAL, DEPTH];
        if plan.thickness_layer {
            writes.push(THICKNESS);
        }
        PassIo { reads: vec![], attached: vec![], writes }
    }

    /// The pipeline of a material with `features`, culling the faces whose `culled` side is
    /// towards the camera.
    fn pipeline(
        device: &wgpu::Device,
        layout: &wgpu::PipelineLayout,
        module: &wgpu::ShaderModule,
        features: Features,
        culled: Option<wgpu::Face>,
    ) -> wgpu::RenderPipeline {
        let fragment = if features.thickness_layer {
            (
                "fs_thickness",
                &[Some(ALBEDO_FORMAT.into()), Some(NORMAL_FORMAT.into()), Some(THICKNESS_FORMAT.into())][..],
            )
        } else {
            ("fs_main", &[Some(ALBEDO_FORMAT.into()), Some(NORMAL_FORMAT.into())][..])
        };
        model_pipeline(device, layout, module, features, culled, fragment)
    }

    /// Uploads `model` and builds its material bind groups (and the pipelines its materials need
    /// that do not exist yet).
    fn upload(&mut self, gpu: &Gpu, model: &Model, thickness: &[u32]) -> SceneGpu {
        let device = &gpu.device;
        let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("scene_vertices"),
            contents: bytemuck::cast_slice(&model.vertices),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("scene_indices"),
            contents: bytemuck::cast_slice(&model.indices),
            usage: wgpu::BufferUsages::INDEX,
        });
        // Only a model with a normal map has tangents (one per vertex).
        let tangents = model.has_tangents().then(|| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("scene_tangents"),
                contents: bytemuck::cast_slice(&model.tangents),
                usage: wgpu::BufferUsages::VERTEX,
            })
        });
        let mut maps = MaterialMaps::new(gpu);
        maps.bytes = vertices.size() + indices.size() + tangents.as_ref().map_or(0, wgpu::Buffer::size);
        let draws: Vec<Draw> = model
            .parts
            .iter()
            .map(|part| {
                let m = &model.materials[part.material];
                let code = thickness.get(part.material).copied().unwrap_or(FULL_THICKNESS);
                let bind_group = self.material_bind_group(gpu, m, code, &mut maps);
                let features = Features { thin: code < FULL_THICKNESS, ..Features::of(m, tangents.is_some()) };
                Draw { first_index: part.first_index, index_count: part.index_count, bind_group, features }
            })
            .collect();
        // A scene with a thin material draws with the thickness layer where the plan has it, and
        // without it where not: both sets of its pipelines.
        let thin_materials = thickness.iter().any(|&c| c < FULL_THICKNESS);
        for draw in &draws {
            for thickness_layer in [false, thin_materials] {
                let features = draw.features.with_layer(thickness_layer);
                if !self.pipelines.contains_key(&features) {
                    let sides = Sides::new(device, &self.pipeline_layout, &self.module, features);
                    self.pipelines.insert(features, sides);
                }
            }
        }
        let textured = draws.iter().any(|d| d.features.textured);
        let normal_mapped = draws.iter().any(|d| d.features.normal_mapped);
        let smooth_normals = model.has_smooth_normals();
        SceneGpu {
            vertices,
            indices,
            tangents,
            draws,
            textured,
            normal_mapped,
            thin_materials,
            smooth_normals,
            bytes: maps.bytes,
        }
    }

    /// Material `m`'s bind group: its parameters, and its maps uploaded through `maps` (or the
    /// white stand-ins).
    fn material_bind_group(
        &self,
        gpu: &Gpu,
        m: &Material,
        thickness_code: u32,
        maps: &mut MaterialMaps,
    ) -> wgpu::BindGroup {
        let params = MaterialParams {
            albedo: m.diffuse,
            specular: m.specular.iter().sum::<f32>() / 3.0,
            shininess_bits: shininess_bits(m.shininess),
            normal_scale: m.normal_map.as_ref().map_or(1.0, |n| n.scale),
            alpha_cutoff: m.cutout.as_ref().map_or(0.0, |c| c.cutoff),
            alpha_factor: m.cutout.as_ref().map_or(1.0, |c| c.factor),
            thickness_code,
            ..Default::default()
        };
        let uniform = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(&format!("material_{}_params", m.name)),
            contents: bytemuck::bytes_of(&params),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        maps.bytes += uniform.size();
        let [diffuse, specular, normals, coverage] = maps.of(gpu, m);
        gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&format!("material_{}_bind_group", m.name)),
            layout: &self.material_layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: uniform.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(&diffuse) },
                wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::TextureView(&specular) },
                wgpu::BindGroupEntry { binding: 3, resource: wgpu::BindingResource::Sampler(&self.sampler) },
                wgpu::BindGroupEntry { binding: 4, resource: wgpu::BindingResource::TextureView(&normals) },
                wgpu::BindGroupEntry { binding: 5, resource: wgpu::BindingResource::TextureView(&coverage) },
            ],
        })
    }
}

/// The layout of a material's bind group (`gbuffer.wgsl` group 1): its parameters, its maps and
/// their sampler. The far side layer binds the scene's material groups too.
pub(super) fn material_entries() -> [wgpu::BindGroupLayoutEntry; 6] {
    let map = |binding| texture_entry(binding, true, wgpu::TextureViewDimension::D2);
    [uniform_entry(0), map(1), map(2), sampler_entry(3), map(4), map(5)]
}

/// A pipeline that draws the faces of a material with `features` (`gbuffer.wgsl`'s vertex
/// stages) through the fragment entry and targets of `fragment`, behind the reverse-Z depth
/// test, culling the faces whose `culled` side is towards the camera: the G-buffer's pipelines
/// and the far side layer's.
pub(super) fn model_pipeline(
    device: &wgpu::Device,
    layout: &wgpu::PipelineLayout,
    module: &wgpu::ShaderModule,
    features: Features,
    culled: Option<wgpu::Face>,
    (entry, targets): (&str, &[Option<wgpu::ColorTargetState>]),
) -> wgpu::RenderPipeline {
    let flag = |on: bool| if on { 1.0 } else { 0.0 };
    let constants = [
        ("TEXTURED", flag(features.textured)),
        ("SPECULAR_MAP", features.specular.shader_code()),
        ("NORMAL_MAPPED", flag(features.normal_mapped)),
        ("CUT_OUT", flag(features.cut_out)),
        ("THIN", flag(features.thin)),
    ];
    let options = wgpu::PipelineCompilationOptions { constants: &constants, ..Default::default() };
    let vertex = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Vertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2],
    };
    let tangent = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<[f32; 4]>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &wgpu::vertex_attr_array![3 => Float32x4],
    };
    let buffers = [Some(vertex), Some(tangent)];
    let buffers = if features.normal_mapped { &buffers[..] } else { &buffers[..1] };
    let label = format!("{entry}_pipeline_{features:?}_{culled:?}_culled");
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(&label),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(if features.normal_mapped { "vs_mapped" } else { "vs_main" }),
            compilation_options: options.clone(),
            buffers,
        },
        primitive: wgpu::PrimitiveState { cull_mode: culled, ..Default::default() },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Greater),
            stencil: wgpu::StencilState::default(),
            bias: wgpu::DepthBiasState::default(),
        }),
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState { module, entry_point: Some(entry), compilation_options: options, targets }),
        multiview_mask: None,
        cache: None,
    })
}

/// A render pass that draws the model into `colors` and the depth target of `depth` (cleared to
/// the far plane, then stored or not), with the frame's bind group and the model's buffers set:
/// the G-buffer's, and the far side layer's.
pub(super) fn begin_model_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    colors: &[Option<wgpu::RenderPassColorAttachment<'_>>],
    (depth, store): (&wgpu::TextureView, wgpu::StoreOp),
    timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
    frame: &wgpu::BindGroup,
    scene: &SceneGpu,
) -> wgpu::RenderPass<'e> {
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: colors,
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: depth,
            depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(0.0), store }),
            stencil_ops: None,
        }),
        timestamp_writes: timestamps,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_bind_group(0, frame, &[]);
    pass.set_vertex_buffer(0, scene.vertices.slice(..));
    if let Some(tangents) = &scene.tangents {
        pass.set_vertex_buffer(1, tangents.slice(..));
    }
    pass.set_index_buffer(scene.indices.slice(..), wgpu::IndexFormat::Uint32);
    pass
}

impl Pass for GBufferPass {
    fn upload_scene(&mut self, gpu: &Gpu, model: &Model, thickness: &[u32]) -> Option<SceneGpu> {
        Some(self.upload(gpu, model, thickness))
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, scene, plan, sky, .. } = rec;
        let attachment = crate::render::graph::io::color_attachment;
        let layer = plan.thickness_layer.then(|| attachment(&targets.expect(THICKNESS).view, true));
        let colors = [attachment(&targets.albedo().view, true), attachment(&targets.normal().view, true)];
        let colors: Vec<_> = colors.into_iter().chain(layer).collect();
        let depth = (&targets.depth().view, wgpu::StoreOp::Store);
        let mut pass = begin_model_pass(encoder, "gbuffer_pass", &colors, depth, timestamps, frame, scene);
        // Two rounds (`Sides`): every material's faces seen from the front (a plain material's
        // every face), then the faces of those that read maps seen from behind.
        for second in [false, true] {
            for draw in &scene.draws {
                let features = draw.features.with_layer(plan.thickness_layer);
                let Some(pipeline) = self.pipelines[&features].round(second) else { continue };
                pass.set_pipeline(pipeline);
                pass.set_bind_group(1, &draw.bind_group, &[]);
                pass.draw_indexed(draw.first_index..draw.first_index + draw.index_count, 0, 0..1);
            }
        }
        if plan.display {
            pass.set_pipeline(&self.sky[usize::from(plan.thickness_layer)]);
            pass.set_bind_group(1, None, &[]);
            pass.set_bind_group(2, &sky.bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
    }
}
