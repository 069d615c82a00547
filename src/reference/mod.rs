//! CPU ray-traced ground truth: one physical image for every mode. The same triangles, camera and
//! pixels as the GPU, with exact visibility at any distance.
//!
//! For each pixel the primary ray finds the visible surface (checked against the GPU's depth; a
//! pixel where the two disagree, on a silhouette, is left out). From it, `spp` cosine-distributed
//! rays (pdf cos/π, so a mean over rays is E/π) each answer, at once:
//!
//! * **Sky light**: the ray hits nothing at all and brings the sky's radiance in its direction
//!   (the same cube map).
//! * **One bounce**: the ray hits a surface, at any distance, which sends its diffuse radiance
//!   under the point lights — unshadowed, exactly what the GPU's `bounce` buffer holds. Senders
//!   are lit by the point lights only, not by the sky (a sky-lit bounce would need a second ray
//!   per hit).
//! * **Openness**: the share of rays that escape, which occludes the constant ambient (a uniform
//!   environment of radiance A).
//!
//! The truth at a pixel is ρ·(sky + bounce + A·openness) + direct point light, the same for every
//! mode and variant. Beside it, **within-R diagnostics** with the sampling radius R: occluders
//! and senders beyond R ignored (AO = 1 − share of rays hitting within R; sky where no hit within
//! R; bounce from hits within R). The gap between a mode's error against the truth and against
//! the within-R image is what its reach costs.
//!
//! Deterministic: each pixel draws from a generator seeded by the seed and the pixel index, and
//! pixels run in parallel. [`trace_pair`] traces twice with independent seeds, for the truth (their
//! mean) and its noise floor (their difference).

use glam::{Vec3, Vec3A, Vec4Swizzles};
use obvhs::cwbvh::{builder::build_cwbvh_from_tris, CwBvh};
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;
use rand::{rngs::StdRng, RngExt, SeedableRng};
use rayon::prelude::*;

use crate::scene::{LightRig, Material, Model, OrbitCamera, PointLight, Skybox};

/// The model's triangles in a BVH, with what shading needs per triangle.
pub struct ReferenceScene {
    bvh: CwBvh,
    triangles: Vec<Triangle>,
    normals: Vec<[Vec3; 3]>,
    uvs: Vec<[[f32; 2]; 3]>,
    material: Vec<usize>,
    materials: Vec<Material>,
    /// Offset of secondary rays along the normal, against self-intersection.
    epsilon: f32,
}

/// A surface point the tracer found.
#[derive(Clone, Copy, Debug)]
pub struct Surface {
    pub position: Vec3,
    /// Interpolated shading normal, turned towards the incoming ray (faces are two-sided).
    pub normal: Vec3,
    pub albedo: Vec3,
    pub specular: f32,
    pub shininess: f32,
    pub distance: f32,
}

fn srgb_to_linear(c: u8) -> f32 {
    let c = c as f32 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

impl ReferenceScene {
    pub fn new(model: &Model) -> Self {
        let mut material = vec![0; model.triangle_count()];
        for part in &model.parts {
            let first = part.first_index as usize / 3;
            for m in &mut material[first..first + part.index_count as usize / 3] {
                *m = part.material;
            }
        }
        let vertex = |i: usize, k: usize| model.vertices[model.indices[3 * i + k] as usize];
        let triangles: Vec<Triangle> = (0..model.triangle_count())
            .map(|i| {
                let p = model.triangle(i);
                Triangle { v0: p[0].into(), v1: p[1].into(), v2: p[2].into() }
            })
            .collect();
        let normals = (0..model.triangle_count()).map(|i| [0, 1, 2].map(|k| Vec3::from(vertex(i, k).normal))).collect();
        let uvs = (0..model.triangle_count()).map(|i| [0, 1, 2].map(|k| vertex(i, k).uv)).collect();
        let bvh =
            build_cwbvh_from_tris(&triangles, BvhBuildParams::medium_build(), &mut std::time::Duration::default());
        Self {
            bvh,
            triangles,
            normals,
            uvs,
            material,
            materials: model.materials.clone(),
            epsilon: 1e-4 * model.bounds.radius(),
        }
    }

    /// The closest surface along the ray within `t_max`.
    pub fn trace(&self, origin: Vec3, direction: Vec3, t_max: f32) -> Option<Surface> {
        let ray = Ray::new(Vec3A::from(origin), Vec3A::from(direction), 0.0, t_max);
        let mut hit = RayHit::none();
        let found = self.bvh.ray_traverse(ray, &mut hit, |ray, id| {
            self.triangles[self.bvh.primitive_indices[id] as usize].intersect(ray)
        });
        if !found {
            return None;
        }
        let index = self.bvh.primitive_indices[hit.primitive_id as usize] as usize;
        let position = origin + direction * hit.t;
        let tri = &self.triangles[index];
        let (a, b, c) = (Vec3::from(tri.v0), Vec3::from(tri.v1), Vec3::from(tri.v2));
        // Barycentric coordinates of the hit, for the interpolated normal and texture coordinate.
        let (e1, e2, ep) = (b - a, c - a, position - a);
        let (d11, d12, d22, dp1, dp2) = (e1.dot(e1), e1.dot(e2), e2.dot(e2), ep.dot(e1), ep.dot(e2));
        let det = d11 * d22 - d12 * d12;
        let (v, w) = if det.abs() > f32::MIN_POSITIVE {
            ((d22 * dp1 - d12 * dp2) / det, (d11 * dp2 - d12 * dp1) / det)
        } else {
            (0.0, 0.0)
        };
        let weights = [1.0 - v - w, v, w];
        let n = self.normals[index];
        // The side of the triangle the ray arrives on, whatever its winding; the shading normal
        // is turned to that side, as the G-buffer does (shaders/gbuffer.wgsl, `camera_side`).
        let mut geometric = e1.cross(e2).try_normalize().unwrap_or(-direction);
        if geometric.dot(direction) > 0.0 {
            geometric = -geometric;
        }
        let mut normal =
            (n[0] * weights[0] + n[1] * weights[1] + n[2] * weights[2]).try_normalize().unwrap_or(geometric);
        if normal.dot(geometric) < 0.0 {
            normal = -normal;
        }
        let m = &self.materials[self.material[index]];
        let uv = self.uvs[index];
        let uv = [0, 1].map(|k| uv[0][k] * weights[0] + uv[1][k] * weights[1] + uv[2][k] * weights[2]);
        let texel = |image: &crate::scene::model::TextureImage| {
            let x = ((uv[0].rem_euclid(1.0) * image.width as f32) as u32).min(image.width - 1);
            let y = ((uv[1].rem_euclid(1.0) * image.height as f32) as u32).min(image.height - 1);
            let i = 4 * (y * image.width + x) as usize;
            [image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]]
        };
        let mut albedo = Vec3::from(m.diffuse);
        if let Some(map) = &m.diffuse_map {
            albedo *= Vec3::from(texel(map).map(srgb_to_linear));
        }
        let mut specular = m.specular.iter().sum::<f32>() / 3.0;
        if let Some(map) = &m.specular_map {
            specular *= texel(map)[0] as f32 / 255.0;
        }
        Some(Surface { position, normal, albedo, specular, shininess: m.shininess, distance: hit.t })
    }
}

/// The reference's estimates at one surface point, each with its Monte Carlo standard error.
#[derive(Clone, Copy, Debug)]
pub struct Estimate {
    pub ao: f32,
    pub ao_error: f32,
    /// Sky light with full visibility, E/π.
    pub sky: Vec3,
    /// Standard error of the sky light's luminance.
    pub sky_error: f32,
    /// One bounce from a sender at any distance, E/π.
    pub bounce: Vec3,
    pub bounce_error: f32,
    /// Share of the cosine-weighted rays that escape (occludes the constant ambient).
    pub open: f32,
    /// Sky light where no occluder lies within the radius (occluders beyond R ignored), E/π.
    pub sky_near: Vec3,
    /// One bounce from senders within the radius, E/π.
    pub bounce_near: Vec3,
}

impl ReferenceScene {
    /// Sky light, one bounce and openness at `surface` with exact visibility, and the within-R
    /// AO, sky and bounce, from `spp` cosine-distributed rays.
    pub fn estimate(
        &self,
        surface: &Surface,
        lights: &[PointLight],
        rig: &LightRig,
        sky: &Skybox,
        settings: &TraceSettings,
        rng: &mut StdRng,
    ) -> Estimate {
        let n = settings.samples_per_pixel.max(1);
        let origin = surface.position + surface.normal * self.epsilon;
        let (mut ao_sum, mut ao_sq) = (0.0f32, 0.0f32);
        let (mut sky_sum, mut sky_sq) = (Vec3::ZERO, 0.0f32);
        let (mut bounce_sum, mut bounce_sq) = (Vec3::ZERO, 0.0f32);
        let (mut open, mut sky_near, mut bounce_near) = (0.0f32, Vec3::ZERO, Vec3::ZERO);
        for _ in 0..n {
            let dir = cosine_direction(surface.normal, rng.random(), rng.random());
            match self.trace(origin, dir, f32::INFINITY) {
                None => {
                    let l = sky.sample(dir) * settings.sky_scale;
                    sky_sum += l;
                    sky_sq += luminance(l).powi(2);
                    sky_near += l;
                    open += 1.0;
                }
                Some(sender) => {
                    let (diffuse, _) = point_lighting(&sender, -dir, lights, rig);
                    bounce_sum += diffuse;
                    bounce_sq += luminance(diffuse).powi(2);
                    if sender.distance < settings.radius {
                        ao_sum += 1.0;
                        ao_sq += 1.0;
                        bounce_near += diffuse;
                    } else {
                        sky_near += sky.sample(dir) * settings.sky_scale;
                    }
                }
            }
        }
        let nf = n as f32;
        let standard_error = |sum: f32, sq: f32| ((sq / nf - (sum / nf).powi(2)).max(0.0) / nf).sqrt();
        Estimate {
            ao: 1.0 - ao_sum / nf,
            ao_error: standard_error(ao_sum, ao_sq),
            sky: sky_sum / nf,
            sky_error: standard_error(luminance(sky_sum), sky_sq),
            bounce: bounce_sum / nf,
            bounce_error: standard_error(luminance(bounce_sum), bounce_sq),
            open: open / nf,
            sky_near: sky_near / nf,
            bounce_near: bounce_near / nf,
        }
    }
}

/// Outgoing radiance of the point lights at a surface, split like the GPU's `point_lighting`
/// (shaders/common/point_lights.wgsl): unshadowed, Lambert + normalised Blinn-Phong.
pub fn point_lighting(surface: &Surface, to_eye: Vec3, lights: &[PointLight], rig: &LightRig) -> (Vec3, Vec3) {
    let n = surface.normal;
    let spec_norm = (surface.shininess + 8.0) / (8.0 * std::f32::consts::PI);
    let (mut diffuse, mut specular) = (Vec3::ZERO, Vec3::ZERO);
    for light in lights {
        let to_light = light.position - surface.position;
        let d2 = to_light.length_squared();
        let l = to_light.try_normalize().unwrap_or(n);
        let n_dot_l = n.dot(l).max(0.0);
        let irradiance = light.color * (light.intensity / d2.max(rig.min_distance * rig.min_distance)) * n_dot_l;
        let h = (l + to_eye).try_normalize().unwrap_or(n);
        diffuse += irradiance * surface.albedo / std::f32::consts::PI;
        specular += irradiance * surface.specular * spec_norm * n.dot(h).max(0.0).powf(surface.shininess);
    }
    (diffuse, specular)
}

/// What the reference computes per pixel (linear, before albedo where the GPU's buffers are too).
pub struct Reference {
    pub width: u32,
    pub height: u32,
    /// A surface is visible and the GPU's depth agrees with the traced one.
    pub valid: Vec<bool>,
    pub albedo: Vec<Vec3>,
    /// AO within the radius (a diagnostic: what AO estimates by definition).
    pub ao: Vec<f32>,
    /// Sky light with full visibility, E/π.
    pub sky: Vec<Vec3>,
    /// One bounce from any distance, E/π.
    pub bounce: Vec<Vec3>,
    /// Share of rays that escape: the constant ambient's visibility.
    pub open: Vec<f32>,
    /// Within-R sky and bounce (diagnostics), E/π.
    pub sky_near: Vec<Vec3>,
    pub bounce_near: Vec<Vec3>,
    /// Direct point lighting (diffuse + specular), as displayed.
    pub direct: Vec<Vec3>,
    /// Mean Monte Carlo standard errors over the valid pixels.
    pub ao_error: f64,
    pub sky_error: f64,
    pub bounce_error: f64,
    /// Pixels left out: a surface on one side only, or at a different depth (silhouettes).
    pub mismatched: usize,
    /// Pixels left out because a light's emissive cube covers the surface.
    pub covered: usize,
}

/// Parameters of a reference render.
#[derive(Clone, Copy, Debug)]
pub struct TraceSettings {
    pub samples_per_pixel: u32,
    pub seed: u64,
    pub radius: f32,
    /// Multiplies the sky (the renderer's sky scale).
    pub sky_scale: f32,
}

/// A direction around `n` with density cos θ / π.
fn cosine_direction(n: Vec3, u1: f32, u2: f32) -> Vec3 {
    let r = u1.sqrt();
    let phi = std::f32::consts::TAU * u2;
    let local = Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u1).max(0.0).sqrt());
    let (t, b) = n.any_orthonormal_pair();
    (t * local.x + b * local.y + n * local.z).normalize()
}

struct PixelResult {
    valid: bool,
    /// A light's cube is in front of the surface.
    covered: bool,
    albedo: Vec3,
    ao: (f32, f32),
    sky: (Vec3, f32),
    bounce: (Vec3, f32),
    open: f32,
    sky_near: Vec3,
    bounce_near: Vec3,
    direct: Vec3,
}

/// Traces the reference for `camera` at `size`. `gpu_depth` is the G-buffer's reverse-Z depth
/// (row by row), against which each pixel's visible surface is checked; `progress` is called
/// once per finished row.
#[allow(clippy::too_many_arguments)]
pub fn trace(
    scene: &ReferenceScene,
    lights: &[PointLight],
    rig: &LightRig,
    sky: &Skybox,
    camera: &OrbitCamera,
    size: (u32, u32),
    gpu_depth: &[f32],
    settings: &TraceSettings,
    progress: &(dyn Fn() + Sync),
) -> Reference {
    let (w, h) = size;
    let view_to_world = camera.world_to_view().inverse();
    let projection = camera.view_to_clip(w as f32 / h as f32);
    let eye = camera.eye();
    let rows: Vec<Vec<PixelResult>> = (0..h)
        .into_par_iter()
        .map(|y| {
            let row = (0..w)
                .map(|x| {
                    let index = (y * w + x) as usize;
                    let ndc = ((x as f32 + 0.5) / w as f32 * 2.0 - 1.0, 1.0 - (y as f32 + 0.5) / h as f32 * 2.0);
                    let view_dir = Vec3::new(ndc.0 / projection.x_axis.x, ndc.1 / projection.y_axis.y, -1.0);
                    let direction = (view_to_world * view_dir.extend(0.0)).xyz().normalize();
                    let empty = PixelResult {
                        valid: false,
                        covered: false,
                        albedo: Vec3::ZERO,
                        ao: (1.0, 0.0),
                        sky: (Vec3::ZERO, 0.0),
                        bounce: (Vec3::ZERO, 0.0),
                        open: 1.0,
                        sky_near: Vec3::ZERO,
                        bounce_near: Vec3::ZERO,
                        direct: Vec3::ZERO,
                    };
                    let Some(surface) = scene.trace(eye, direction, f32::INFINITY) else { return empty };
                    // The lights' emissive cubes cover the surface here on the GPU's image (and its
                    // depth); the reference has no such cubes, so the pixel measures nothing.
                    let cube = lights.iter().any(|l| {
                        ray_box(eye, direction, l.position, rig.cube_half_size).is_some_and(|t| t < surface.distance)
                    });
                    if cube {
                        return PixelResult { covered: true, ..empty };
                    }
                    // The GPU's depth at this pixel as a distance along the same view axis.
                    let depth = gpu_depth[index];
                    let view_z = surface.distance * direction.dot((view_to_world * Vec3::NEG_Z.extend(0.0)).xyz());
                    let gpu_z =
                        if depth > 0.0 { (projection.w_axis.z) / (depth + projection.z_axis.z) } else { f32::INFINITY };
                    if !((view_z - gpu_z).abs() <= 1e-3 * view_z) {
                        return empty;
                    }
                    let mut rng =
                        StdRng::seed_from_u64(settings.seed ^ (index as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
                    let e = scene.estimate(&surface, lights, rig, sky, settings, &mut rng);
                    let (diffuse, specular) = point_lighting(&surface, -direction, lights, rig);
                    PixelResult {
                        valid: true,
                        covered: false,
                        albedo: surface.albedo,
                        ao: (e.ao, e.ao_error),
                        sky: (e.sky, e.sky_error),
                        bounce: (e.bounce, e.bounce_error),
                        open: e.open,
                        sky_near: e.sky_near,
                        bounce_near: e.bounce_near,
                        direct: diffuse + specular,
                    }
                })
                .collect();
            progress();
            row
        })
        .collect();
    let pixels: Vec<PixelResult> = rows.into_iter().flatten().collect();
    let valid_count = pixels.iter().filter(|p| p.valid).count().max(1) as f64;
    let mean_error = |f: &dyn Fn(&PixelResult) -> f32| {
        pixels.iter().filter(|p| p.valid).map(|p| f(p) as f64).sum::<f64>() / valid_count
    };
    let surfaces = gpu_depth.iter().filter(|d| **d > 0.0).count();
    Reference {
        width: w,
        height: h,
        ao_error: mean_error(&|p| p.ao.1),
        sky_error: mean_error(&|p| p.sky.1),
        bounce_error: mean_error(&|p| p.bounce.1),
        covered: pixels.iter().filter(|p| p.covered).count(),
        mismatched: surfaces.saturating_sub(pixels.iter().filter(|p| p.valid || p.covered).count()),
        valid: pixels.iter().map(|p| p.valid).collect(),
        albedo: pixels.iter().map(|p| p.albedo).collect(),
        ao: pixels.iter().map(|p| p.ao.0).collect(),
        sky: pixels.iter().map(|p| p.sky.0).collect(),
        bounce: pixels.iter().map(|p| p.bounce.0).collect(),
        open: pixels.iter().map(|p| p.open).collect(),
        sky_near: pixels.iter().map(|p| p.sky_near).collect(),
        bounce_near: pixels.iter().map(|p| p.bounce_near).collect(),
        direct: pixels.iter().map(|p| p.direct).collect(),
    }
}

impl Reference {
    /// The truth at pixel `i`: linear radiance with exact visibility under the sky, one bounce,
    /// the constant ambient `ambient` and the point lights — the same image for every mode.
    pub fn radiance(&self, i: usize, ambient: f32) -> Vec3 {
        self.albedo[i] * (self.sky[i] + self.bounce[i] + Vec3::splat(ambient * self.open[i])) + self.direct[i]
    }

    /// The within-R diagnostic image at pixel `i`: the same lighting with every occluder and
    /// sender beyond the radius removed.
    pub fn radiance_near(&self, i: usize, ambient: f32) -> Vec3 {
        self.albedo[i] * (self.sky_near[i] + self.bounce_near[i] + Vec3::splat(ambient * self.ao[i])) + self.direct[i]
    }

    /// DO's truth at pixel `i` (sky light + bounce, before albedo), and its within-R diagnostic.
    pub fn directional(&self, i: usize) -> Vec3 {
        self.sky[i] + self.bounce[i]
    }

    pub fn directional_near(&self, i: usize) -> Vec3 {
        self.sky_near[i] + self.bounce_near[i]
    }

    /// The mean of two independent traces of the same view (the truth with half the noise).
    pub fn mean(a: &Reference, b: &Reference) -> Reference {
        let avg3 = |x: &[Vec3], y: &[Vec3]| x.iter().zip(y).map(|(p, q)| 0.5 * (*p + *q)).collect();
        let avg1 = |x: &[f32], y: &[f32]| x.iter().zip(y).map(|(p, q)| 0.5 * (p + q)).collect();
        Reference {
            width: a.width,
            height: a.height,
            valid: a.valid.iter().zip(&b.valid).map(|(p, q)| *p && *q).collect(),
            albedo: a.albedo.clone(),
            ao: avg1(&a.ao, &b.ao),
            sky: avg3(&a.sky, &b.sky),
            bounce: avg3(&a.bounce, &b.bounce),
            open: avg1(&a.open, &b.open),
            sky_near: avg3(&a.sky_near, &b.sky_near),
            bounce_near: avg3(&a.bounce_near, &b.bounce_near),
            direct: a.direct.clone(),
            ao_error: 0.5 * (a.ao_error + b.ao_error) / std::f64::consts::SQRT_2,
            sky_error: 0.5 * (a.sky_error + b.sky_error) / std::f64::consts::SQRT_2,
            bounce_error: 0.5 * (a.bounce_error + b.bounce_error) / std::f64::consts::SQRT_2,
            mismatched: a.mismatched.max(b.mismatched),
            covered: a.covered,
        }
    }
}

/// Distance along the ray (unit `direction`) to an axis-aligned cube of half edge `half` around
/// `center`, if it is hit in front of `origin`.
fn ray_box(origin: Vec3, direction: Vec3, center: Vec3, half: f32) -> Option<f32> {
    let inv = direction.recip();
    let t0 = (center - Vec3::splat(half) - origin) * inv;
    let t1 = (center + Vec3::splat(half) - origin) * inv;
    let (near, far) = (t0.min(t1).max_element(), t0.max(t1).min_element());
    (near <= far && far > 0.0).then_some(near.max(0.0))
}

/// Rec. 709 luminance.
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}
