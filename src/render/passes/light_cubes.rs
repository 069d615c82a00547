//! The point lights as small emissive cubes in their own colours: one instanced draw, depth
//! tested (reverse-Z, `GreaterEqual`) against the G-buffer depth — by the depth attachment when
//! they are drawn into HDR, by the shader (`fs_display`) when a display plan draws them
//! tone-mapped straight into the output, which can be larger than the G-buffer. Not in the plan
//! when the scene has no lights.

use wgpu::util::DeviceExt;

use crate::render::graph::io::color_attachment;
use crate::render::graph::io::{PassIo, Read};
use crate::render::graph::Entry;
use crate::render::graph::{Pass, PassContext, Preparation, Recording};
use crate::render::modes::{Plan, Step};
use crate::render::targets::{DEPTH, DEPTH_FORMAT, HDR, HDR_FORMAT, OUTPUT};
use crate::{shaders, Result};

impl Step {
    pub const LIGHT_CUBES: Step = Step::new("light_cubes");
}

pub const ENTRY: Entry =
    Entry::new(Step::LIGHT_CUBES, |f| f.lights(), LightCubesPass::io, |cx| Ok(Box::new(LightCubesPass::new(cx)?)))
        .binding(&["light_cubes.wgsl"]);

/// The 36 corners of a unit cube's 12 triangles (±1 on each axis).
fn cube_corners() -> Vec<[f32; 3]> {
    let faces: [[[f32; 3]; 4]; 6] = [
        [[1., -1., -1.], [1., 1., -1.], [1., 1., 1.], [1., -1., 1.]],
        [[-1., -1., 1.], [-1., 1., 1.], [-1., 1., -1.], [-1., -1., -1.]],
        [[-1., 1., -1.], [-1., 1., 1.], [1., 1., 1.], [1., 1., -1.]],
        [[-1., -1., 1.], [-1., -1., -1.], [1., -1., -1.], [1., -1., 1.]],
        [[-1., -1., 1.], [1., -1., 1.], [1., 1., 1.], [-1., 1., 1.]],
        [[1., -1., -1.], [-1., -1., -1.], [-1., 1., -1.], [1., 1., -1.]],
    ];
    faces.iter().flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]]).collect()
}

pub struct LightCubesPass {
    /// Into HDR, with the depth attachment.
    pipeline: wgpu::RenderPipeline,
    /// Into the output, tone-mapped, testing depth in the shader.
    display: wgpu::RenderPipeline,
    depth_layout: wgpu::BindGroupLayout,
    /// The G-buffer depth for `display`, rebuilt with the targets.
    depth_group: Option<wgpu::BindGroup>,
    corners: wgpu::Buffer,
}

impl LightCubesPass {
    pub fn new(cx: &PassContext<'_>) -> Result<Self> {
        let (device, frame_layout, output) = (cx.device, cx.frame_layout, cx.output);
        let module = shaders::module(device, "light_cubes.wgsl")?;
        let depth_layout = cx.layout("light_cubes_depth_layout", &Self::display_io().layout_entries());
        let pipeline = Self::pipeline(device, &module, &[Some(frame_layout)], HDR_FORMAT, None);
        let display = Self::pipeline(device, &module, &[Some(frame_layout), Some(&depth_layout)], output, Some(()));
        let corners = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("light_cubes_corners"),
            contents: bytemuck::cast_slice(&cube_corners()),
            usage: wgpu::BufferUsages::VERTEX,
        });
        Ok(Self { pipeline, display, depth_layout, depth_group: None, corners })
    }

    /// A display plan's: the depth, bound (the shader tests it); the output.
    fn display_io() -> PassIo {
        PassIo { reads: vec![Read::Target(DEPTH)], attached: vec![], writes: vec![OUTPUT] }
    }

    /// The depth, bound in a display plan and attached (tested and written) otherwise; the
    /// output or HDR.
    pub fn io(plan: &Plan) -> PassIo {
        if plan.display {
            Self::display_io()
        } else {
            PassIo { reads: vec![], attached: vec![DEPTH], writes: vec![HDR] }
        }
    }

    /// `display`: the pipeline that draws into the output and tests depth itself.
    fn pipeline(
        device: &wgpu::Device,
        module: &wgpu::ShaderModule,
        layouts: &[Option<&wgpu::BindGroupLayout>],
        format: wgpu::TextureFormat,
        display: Option<()>,
    ) -> wgpu::RenderPipeline {
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("light_cubes_pipeline_layout"),
            bind_group_layouts: layouts,
            immediate_size: 0,
        });
        let constants = [("OUTPUT_SRGB", if format.is_srgb() { 1.0 } else { 0.0 })];
        let fragment_options = wgpu::PipelineCompilationOptions {
            constants: if display.is_some() { &constants } else { &[] },
            ..Default::default()
        };
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(if display.is_some() { "light_cubes_display_pipeline" } else { "light_cubes_pipeline" }),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[
                    Some(wgpu::VertexBufferLayout {
                        array_stride: 12,
                        step_mode: wgpu::VertexStepMode::Vertex,
                        attributes: &wgpu::vertex_attr_array![0 => Float32x3],
                    }),
                    // Which light each instance draws, farthest first (`FrameData::cube_order`).
                    Some(wgpu::VertexBufferLayout {
                        array_stride: 4,
                        step_mode: wgpu::VertexStepMode::Instance,
                        attributes: &wgpu::vertex_attr_array![1 => Uint32],
                    }),
                ],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: display.is_none().then(|| wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::GreaterEqual),
                stencil: wgpu::StencilState::default(),
                bias: wgpu::DepthBiasState::default(),
            }),
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module,
                entry_point: Some(if display.is_some() { "fs_display" } else { "fs_main" }),
                compilation_options: fragment_options,
                targets: &[Some(format.into())],
            }),
            multiview_mask: None,
            cache: None,
        })
    }
}

impl Pass for LightCubesPass {
    /// Binds the G-buffer depth for the display pipeline.
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        self.depth_group = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("light_cubes_depth_bind_group"),
            layout: &self.depth_layout,
            entries: &Self::display_io().entries(&p.inputs, 0),
        }));
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, lights, light_order, plan, output, origin, .. } = rec;
        let display = plan.display.then_some((output, origin));
        // `display`: a display plan's output and the image's origin in it; otherwise into HDR.
        let (color, depth) = match (display, targets.get(HDR)) {
            (None, Some(hdr)) => (
                &hdr.view,
                Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &targets.depth().view,
                    depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store }),
                    stencil_ops: None,
                }),
            ),
            (Some((output, _)), _) => (output, None),
            (None, None) => panic!("light cubes drawn into HDR in a plan that has no HDR target"),
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("light_cubes_pass"),
            color_attachments: &[color_attachment(color, false)],
            depth_stencil_attachment: depth,
            timestamp_writes: timestamps,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        match (display, &self.depth_group) {
            (None, _) => pass.set_pipeline(&self.pipeline),
            (Some((_, origin)), Some(group)) => {
                let (w, h) = targets.size;
                pass.set_viewport(origin.0 as f32, origin.1 as f32, w as f32, h as f32, 0.0, 1.0);
                pass.set_pipeline(&self.display);
                pass.set_bind_group(1, group, &[]);
            }
            (Some(_), None) => panic!("light cubes drawn into the output before `prepare` bound the depth"),
        }
        pass.set_bind_group(0, frame, &[]);
        pass.set_vertex_buffer(0, self.corners.slice(..));
        pass.set_vertex_buffer(1, light_order.slice(..));
        pass.draw(0..36, 0..lights);
    }
}
