//! Denoise of the sampling pass's output (`shaders/blur.wgsl`): a 4x4 window, bilateral (plane
//! distance and normal agreement) in the default variant, the classic box blur otherwise.

use super::super::variant::Blur;
use super::occlusion::Outputs;
use super::{
    color_attachment, fullscreen_pipeline, gbuffer_entries, texture_entry, uniform_entry, FullscreenDesc,
    FullscreenPass, KeyedPipeline,
};
use super::{Pass, Preparation, Recording};
use crate::{shaders, Result};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Key {
    outputs: Outputs,
    bilateral: bool,
}

pub struct BlurPass {
    module: wgpu::ShaderModule,
    layout: wgpu::BindGroupLayout,
    frame_layout: wgpu::BindGroupLayout,
    pipeline: KeyedPipeline<Key>,
    bind_group: Option<wgpu::BindGroup>,
}

impl BlurPass {
    pub fn new(device: &wgpu::Device, frame_layout: &wgpu::BindGroupLayout) -> Result<Self> {
        let module = shaders::module(device, "blur.wgsl")?;
        let [a, n, d] = gbuffer_entries();
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("blur_layout"),
            entries: &[a, n, d, uniform_entry(3), texture_entry(4, false, wgpu::TextureViewDimension::D2)],
        });
        Ok(Self {
            module,
            layout,
            frame_layout: frame_layout.clone(),
            pipeline: KeyedPipeline::new(),
            bind_group: None,
        })
    }
}

impl Pass for BlurPass {
    /// Builds what the plan needs (nothing when it does not blur).
    fn prepare(&mut self, device: &wgpu::Device, p: &Preparation<'_>) {
        let Preparation { targets, plan, variant, data, .. } = *p;
        let Some(input) = targets.raw.output().filter(|_| plan.blur) else {
            self.pipeline.clear();
            self.bind_group = None;
            return;
        };
        let key = Key { outputs: Outputs::of(plan), bilateral: variant.decl().blur == Blur::Bilateral };
        let (module, frame_layout, layout) = (&self.module, &self.frame_layout, &self.layout);
        self.pipeline.ensure(key, |key| {
            let f = |b: bool| b as u8 as f64;
            fullscreen_pipeline(
                device,
                &FullscreenDesc {
                    label: "blur_pipeline",
                    module,
                    entry: "fs_main",
                    bind_group_layouts: &[Some(frame_layout), Some(layout)],
                    targets: &[Some(key.outputs.format().into())],
                    depth: None,
                    constants: &[("BILATERAL", f(key.bilateral)), ("AO_ONLY", f(!key.outputs.directional))],
                },
            )
        });
        let views = [&targets.albedo.view, &targets.normal.view, &targets.depth.view];
        let mut entries: Vec<wgpu::BindGroupEntry> = super::view_entries(&views);
        entries.push(wgpu::BindGroupEntry { binding: 3, resource: data.buffer.as_entire_binding() });
        entries.push(wgpu::BindGroupEntry { binding: 4, resource: wgpu::BindingResource::TextureView(&input.view) });
        self.bind_group = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("blur_bind_group"),
            layout: &self.layout,
            entries: &entries,
        }));
    }

    fn record(&self, rec: Recording<'_>) {
        let Recording { encoder, timestamps, targets, frame, .. } = rec;
        let output = targets.blurred.as_ref().and_then(|b| b.output());
        let (Some((_, pipeline)), Some(bind_group), Some(output)) = (self.pipeline.get(), &self.bind_group, output)
        else {
            unreachable!("the blur recorded before `prepare` or in a plan that does not blur")
        };
        FullscreenPass {
            label: "blur_pass",
            attachments: &[color_attachment(&output.view, true)],
            depth: None,
            timestamps,
            pipeline,
            bind_groups: &[(0, frame), (1, bind_group)],
            viewport: None,
        }
        .record(encoder);
    }
}
