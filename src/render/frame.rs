//! Bind group 0: the per-frame uniforms and the light array, shared by every pass.

use glam::{Mat3, Vec3, Vec4Swizzles};

use super::uniforms::{mat, FrameUniforms, GpuLight, UNIFORM_LIGHTS};
use crate::scene::irradiance::irradiance_quadratic;
use crate::scene::{LightRig, OrbitCamera, PointLight};

/// What the frame uniforms are computed from, besides the camera and the scene.
#[derive(Clone, Copy, Debug)]
pub struct FrameInputs {
    pub size: (u32, u32),
    pub exposure: f32,
    pub ambient: Vec3,
    pub sky_scale: f32,
    pub sky_mips: u32,
    /// Radiance in the half-float buffers is radiance × this (see `Renderer::pre_exposure`).
    pub pre_exposure: f32,
    pub ao_strength: f32,
    pub ao_power: f32,
    /// The sky's E(n)/π as spherical harmonics, in radiance (scaled, not yet pre-exposed).
    pub sky_sh: [Vec3; 9],
    /// Where the image starts in the output target (the viewer's panel is beside it).
    pub output_origin: (u32, u32),
    /// The scene's default march thickness (`Lengths::default_thickness`).
    pub default_thickness: f32,
}

pub struct FrameData {
    pub layout: wgpu::BindGroupLayout,
    pub bind_group: wgpu::BindGroup,
    uniforms: wgpu::Buffer,
    lights: wgpu::Buffer,
    /// The lights' indices, farthest from the camera first: the order the light cubes are drawn
    /// in (an instance buffer), so that where a display plan draws them without a depth buffer of
    /// their own, a nearer cube still covers a farther one.
    pub cube_order: wgpu::Buffer,
    light_capacity: usize,
    frame_index: u32,
    /// The last frame's camera: its world-to-clip and world-to-view transforms; `None` on a
    /// first frame and after a reset.
    previous_camera: Option<(glam::Mat4, glam::Mat4)>,
    /// What the last `update` wrote (for tests and diagnostics).
    last: FrameUniforms,
    /// Whether the last frame's camera differs from the frame's before it (false on a first
    /// frame and after a reset).
    pub camera_moved: bool,
}

impl FrameData {
    pub fn new(device: &wgpu::Device) -> Self {
        let stages = wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("frame_layout"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: stages,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: stages,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: true },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
            ],
        });
        let uniforms = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("frame_uniforms"),
            size: std::mem::size_of::<FrameUniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let (lights, bind_group) = Self::light_buffer(device, &layout, &uniforms, 1);
        let cube_order = Self::order_buffer(device, 1);
        let (light_capacity, frame_index, previous_camera) = (1, 0, None);
        let last = bytemuck::Zeroable::zeroed();
        let camera_moved = false;
        Self {
            layout,
            bind_group,
            uniforms,
            lights,
            cube_order,
            light_capacity,
            frame_index,
            previous_camera,
            last,
            camera_moved,
        }
    }

    fn order_buffer(device: &wgpu::Device, capacity: usize) -> wgpu::Buffer {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("frame_cube_order"),
            size: (capacity.max(1) * std::mem::size_of::<u32>()) as u64,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// A light array for `capacity` lights (at least one: a storage binding cannot be empty).
    fn light_buffer(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        uniforms: &wgpu::Buffer,
        capacity: usize,
    ) -> (wgpu::Buffer, wgpu::BindGroup) {
        let lights = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("frame_lights"),
            size: (capacity.max(1) * std::mem::size_of::<GpuLight>()) as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("frame_bind_group"),
            layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: uniforms.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: lights.as_entire_binding() },
            ],
        });
        (lights, bind_group)
    }

    /// The uniforms of the last frame written.
    pub fn uniforms(&self) -> &FrameUniforms {
        &self.last
    }

    /// The next frame has no previous one: its previous camera is its own.
    pub fn forget_previous(&mut self) {
        self.previous_camera = None;
    }

    /// Bytes held by the frame buffers.
    pub fn bytes(&self) -> u64 {
        self.uniforms.size() + self.lights.size() + self.cube_order.size()
    }

    /// Writes this frame's uniforms and lights; grows the light array when needed.
    pub fn update(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        camera: &OrbitCamera,
        lights: &[PointLight],
        rig: &LightRig,
        inputs: &FrameInputs,
    ) {
        let (w, h) = inputs.size;
        let world_to_view = camera.world_to_view();
        let view_to_clip = camera.view_to_clip(w as f32 / h as f32);
        let world_to_clip = view_to_clip * world_to_view;
        let this_camera = (world_to_clip, world_to_view);
        let (previous, previous_world_to_view) = self.previous_camera.replace(this_camera).unwrap_or(this_camera);
        self.camera_moved = previous != world_to_clip;
        let gpu_lights: Vec<GpuLight> = lights
            .iter()
            .map(|l| GpuLight {
                world_position: l.position.into(),
                intensity: l.intensity,
                view_position: (world_to_view * l.position.extend(1.0)).xyz().into(),
                _pad0: 0.0,
                color: l.color.into(),
                cube_half_size: rig.cube_half_size,
            })
            .collect();
        let mut first_lights = [GpuLight::default(); UNIFORM_LIGHTS];
        for (slot, light) in first_lights.iter_mut().zip(&gpu_lights) {
            *slot = *light;
        }
        let uniforms = FrameUniforms {
            world_to_view: mat(world_to_view),
            view_to_clip: mat(view_to_clip),
            view_to_world: mat(world_to_view.inverse()),
            viewport: [w as f32, h as f32, 1.0 / w as f32, 1.0 / h as f32],
            near: camera.near,
            far: camera.far.unwrap_or(0.0),
            display_scale: inputs.exposure / inputs.pre_exposure,
            min_light_distance2: rig.min_distance.powi(2),
            ambient: inputs.ambient.into(),
            orbit_distance: camera.distance,
            sky_scale: inputs.sky_scale * inputs.pre_exposure,
            sky_mips: inputs.sky_mips as f32,
            pre_exposure: inputs.pre_exposure,
            ao_strength: inputs.ao_strength,
            ao_power: inputs.ao_power,
            light_count: lights.len() as u32,
            frame_index: self.frame_index,
            default_thickness: inputs.default_thickness,
            output_origin: [inputs.output_origin.0 as f32, inputs.output_origin.1 as f32],
            _pad1: [0.0; 2],
            sky_irradiance: irradiance_quadratic(&inputs.sky_sh, Mat3::from_mat4(world_to_view.inverse()))
                .map(|c| (c * inputs.pre_exposure).extend(0.0).into()),
            previous_world_to_clip: mat(previous),
            previous_projection: projection_terms(previous * previous_world_to_view.inverse()),
            view_to_previous_view: mat(previous_world_to_view * world_to_view.inverse()),
            previous_eye: (world_to_view * previous_world_to_view.inverse()).transform_point3(Vec3::ZERO).into(),
            _pad2: 0.0,
            first_lights,
        };
        queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(&uniforms));
        self.last = uniforms;

        if lights.len() > self.light_capacity {
            self.light_capacity = lights.len().next_power_of_two();
            (self.lights, self.bind_group) =
                Self::light_buffer(device, &self.layout, &self.uniforms, self.light_capacity);
            self.cube_order = Self::order_buffer(device, self.light_capacity);
        }
        if !gpu_lights.is_empty() {
            queue.write_buffer(&self.lights, 0, bytemuck::cast_slice(&gpu_lights));
            let order = far_to_near(gpu_lights.iter().map(|l| Vec3::from(l.view_position)));
            queue.write_buffer(&self.cube_order, 0, bytemuck::cast_slice(&order));
        }
        self.frame_index = self.frame_index.wrapping_add(1);
    }
}

/// What a pass needs of a projection to take a pixel and its depth to view space: 1 / its x and y
/// scales, and a, b of its reverse-Z depth (depth = -a - b / z).
fn projection_terms(view_to_clip: glam::Mat4) -> [f32; 4] {
    let m = view_to_clip;
    [1.0 / m.x_axis.x, 1.0 / m.y_axis.y, m.z_axis.z, m.w_axis.z]
}

/// The pre-exposure for a frame whose brightest radiance is at most `peak`: 1 up to 4096, then
/// 4096 / peak, so the half-float buffers (largest value 65504) keep 16× headroom.
pub fn pre_exposure_for(peak: f32) -> f32 {
    if peak.is_finite() && peak > 4096.0 {
        4096.0 / peak
    } else {
        1.0
    }
}

/// Indices of view-space points, farthest from the camera first (ties in index order). For
/// equal non-intersecting spheres this is the painter's order that is right at every pixel; the
/// light cubes, all of one size, are close to that.
pub fn far_to_near(view_positions: impl Iterator<Item = Vec3>) -> Vec<u32> {
    let d: Vec<f32> = view_positions.map(|p| p.length_squared()).collect();
    let mut order: Vec<u32> = (0..d.len() as u32).collect();
    order.sort_by(|&a, &b| d[b as usize].total_cmp(&d[a as usize]).then(a.cmp(&b)));
    order
}

#[cfg(test)]
mod tests {
    use super::{far_to_near, pre_exposure_for};
    use glam::Vec3;

    #[test]
    fn pre_exposure_keeps_the_brightest_radiance_at_4096() {
        assert_eq!(pre_exposure_for(0.0), 1.0);
        assert_eq!(pre_exposure_for(4096.0), 1.0);
        assert_eq!(pre_exposure_for(1e5) * 1e5, 4096.0);
        assert!((pre_exposure_for(1e30) * 1e30 - 4096.0).abs() < 1.0);
        assert_eq!(pre_exposure_for(f32::INFINITY), 1.0, "a non-finite peak scales nothing");
        assert_eq!(pre_exposure_for(f32::NAN), 1.0);
    }

    #[test]
    fn cubes_are_drawn_farthest_first() {
        let points =
            [Vec3::new(0.0, 0.0, -2.0), Vec3::new(3.0, 0.0, -1.0), Vec3::new(0.0, 0.0, -5.0), Vec3::new(0.0, 2.0, 0.0)];
        assert_eq!(far_to_near(points.into_iter()), vec![2, 1, 0, 3]);
        assert_eq!(far_to_near([Vec3::X, Vec3::Y].into_iter()), vec![0, 1], "ties keep their order");
        assert!(far_to_near(std::iter::empty()).is_empty());
    }
}
