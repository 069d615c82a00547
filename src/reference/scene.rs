//! The traced scene: the model's triangles in a BVH with their materials, a surface a ray finds,
//! and the estimates at it (sky light, one bounce, openness, within-R diagnostics), with the
//! point lights' direct light.

use glam::{Vec3, Vec3A};
use obvhs::cwbvh::{builder::build_cwbvh_from_tris, CwBvh};
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;
use rand::{rngs::StdRng, RngExt};

use super::place::{Placement, Places};
use crate::scene::model::NormalMap;
use crate::scene::{LightRig, Material, Model, PointLight, Skybox};

/// A direction around `n` with density cos θ / π.
fn cosine_direction(n: Vec3, u1: f32, u2: f32) -> Vec3 {
    let r = u1.sqrt();
    let phi = std::f32::consts::TAU * u2;
    let local = Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u1).max(0.0).sqrt());
    let (t, b) = n.any_orthonormal_pair();
    (t * local.x + b * local.y + n * local.z).normalize()
}

/// Parameters of a reference render.
#[derive(Clone, Copy, Debug)]
pub struct TraceSettings {
    pub samples_per_pixel: u32,
    pub seed: u64,
    pub radius: f32,
    /// Multiplies the sky (the renderer's sky scale).
    pub sky_scale: f32,
    /// The constant ambient radiance A: the senders of the bounce are lit by it through their
    /// own openness, as receivers are (the receiver's own A·openness is applied in
    /// `Reference::radiance`, so it stays a parameter there).
    pub ambient: f32,
}

/// The model's triangles in a BVH, with what shading needs per triangle.
pub struct ReferenceScene {
    bvh: CwBvh,
    triangles: Vec<Triangle>,
    normals: Vec<[Vec3; 3]>,
    uvs: Vec<[[f32; 2]; 3]>,
    /// Per triangle where the model has tangents (a normal map), else empty.
    tangents: Vec<[[f32; 4]; 3]>,
    material: Vec<usize>,
    materials: Vec<Material>,
    /// Offset of secondary rays along the normal, against self-intersection.
    epsilon: f32,
}

/// A surface point the tracer found.
#[derive(Clone, Copy, Debug)]
pub struct Surface {
    pub position: Vec3,
    /// The shading normal (interpolated, then the normal map's where the material has one),
    /// turned with its frame towards the incoming ray (faces are two-sided).
    pub normal: Vec3,
    /// The triangle's own normal, on the side the ray arrives from: the hemisphere is cut at
    /// its plane (see [`ReferenceScene::hemisphere_direction`]).
    pub geometric: Vec3,
    pub albedo: Vec3,
    pub specular: f32,
    pub shininess: f32,
    pub distance: f32,
}

/// The linear value of an 8-bit sRGB code.
pub fn srgb_to_linear(c: u8) -> f32 {
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
        let tangents = match model.has_tangents() {
            true => (0..model.triangle_count())
                .map(|i| [0, 1, 2].map(|k| model.tangents[model.indices[3 * i + k] as usize]))
                .collect(),
            false => Vec::new(),
        };
        let bvh =
            build_cwbvh_from_tris(&triangles, BvhBuildParams::medium_build(), &mut std::time::Duration::default());
        Self {
            bvh,
            triangles,
            normals,
            uvs,
            tangents,
            material,
            materials: model.materials.clone(),
            epsilon: 1e-4 * model.bounds.radius(),
        }
    }

    /// Barycentric weights of `position` (on or near the plane of triangle `index`).
    fn barycentric(&self, index: usize, position: Vec3) -> [f32; 3] {
        let tri = &self.triangles[index];
        let (a, b, c) = (Vec3::from(tri.v0), Vec3::from(tri.v1), Vec3::from(tri.v2));
        let (e1, e2, ep) = (b - a, c - a, position - a);
        let (d11, d12, d22, dp1, dp2) = (e1.dot(e1), e1.dot(e2), e2.dot(e2), ep.dot(e1), ep.dot(e2));
        let det = d11 * d22 - d12 * d12;
        let (v, w) = if det.abs() > f32::MIN_POSITIVE {
            ((d22 * dp1 - d12 * dp2) / det, (d11 * dp2 - d12 * dp1) / det)
        } else {
            (0.0, 0.0)
        };
        [1.0 - v - w, v, w]
    }

    /// The texture coordinate at barycentric `weights` of triangle `index`.
    fn uv(&self, index: usize, weights: [f32; 3]) -> [f32; 2] {
        let uv = self.uvs[index];
        [0, 1].map(|k| uv[0][k] * weights[0] + uv[1][k] * weights[1] + uv[2][k] * weights[2])
    }

    /// Whether the ray's hit at `t` on triangle `index` lands on a cut-out texel (the any-hit
    /// test: such a hit is a miss, as the G-buffer discards it).
    fn is_hole(&self, index: usize, ray: &Ray, t: f32) -> bool {
        let Some(cutout) = &self.materials[self.material[index]].cutout else { return false };
        let position = Vec3::from(ray.origin + ray.direction * t);
        cutout.coverage_at(self.uv(index, self.barycentric(index, position))) < cutout.cutoff
    }

    /// The closest surface along the ray within `t_max` (cut-out texels let it through).
    pub fn trace(&self, origin: Vec3, direction: Vec3, t_max: f32) -> Option<Surface> {
        let ray = Ray::new(Vec3A::from(origin), Vec3A::from(direction), 0.0, t_max);
        let mut hit = RayHit::none();
        let found = self.bvh.ray_traverse(ray, &mut hit, |ray, id| {
            let index = self.bvh.primitive_indices[id] as usize;
            let t = self.triangles[index].intersect(ray);
            if t < f32::INFINITY && self.is_hole(index, ray, t) {
                return f32::INFINITY;
            }
            t
        });
        if !found {
            return None;
        }
        let index = self.bvh.primitive_indices[hit.primitive_id as usize] as usize;
        let position = origin + direction * hit.t;
        let tri = &self.triangles[index];
        let (a, b, c) = (Vec3::from(tri.v0), Vec3::from(tri.v1), Vec3::from(tri.v2));
        // Barycentric coordinates of the hit, for the interpolated normal and texture coordinate.
        let weights = self.barycentric(index, position);
        let n = self.normals[index];
        // The side of the triangle the ray arrives on, whatever its winding; the shading normal
        // is turned to that side, as the G-buffer does (shaders/gbuffer.wgsl, `camera_side`).
        let mut geometric = (b - a).cross(c - a).try_normalize().unwrap_or(-direction);
        if geometric.dot(direction) > 0.0 {
            geometric = -geometric;
        }
        let vertex_normal =
            (n[0] * weights[0] + n[1] * weights[1] + n[2] * weights[2]).try_normalize().unwrap_or(geometric);
        let m = &self.materials[self.material[index]];
        let uv = self.uv(index, weights);
        let mut normal = match (&m.normal_map, self.tangents.get(index)) {
            (Some(map), Some(t)) => mapped_normal(vertex_normal, t, weights, map, uv),
            _ => vertex_normal,
        };
        // The side is the vertex normal's: a mapped normal turns with its whole frame.
        if vertex_normal.dot(geometric) < 0.0 {
            normal = -normal;
        }
        let texel = |image: &crate::scene::model::TextureImage| image.texel(uv);
        let mut albedo = Vec3::from(m.diffuse);
        if let Some(map) = &m.diffuse_map {
            let [r, g, b, _] = texel(map);
            albedo *= Vec3::from([r, g, b].map(srgb_to_linear));
        }
        let mut specular = m.specular.iter().sum::<f32>() / 3.0;
        if let Some(map) = &m.specular_map {
            specular *= texel(map)[0] as f32 / 255.0;
        }
        Some(Surface { position, normal, geometric, albedo, specular, shininess: m.shininess, distance: hit.t })
    }

    /// A direction from `surface` with density proportional to the cosine at its shading normal
    /// over the directions above its own plane (those below are drawn again): the hemisphere of
    /// a normal-mapped surface is cut where the surface itself is, and its cosine weights are
    /// normalised over what remains, so an open surface under a constant sky gets exactly
    /// albedo × sky whatever its normal map, as on the GPU (`NORMAL_MAPPED` in
    /// shaders/common/sampling_params.wgsl). Where the shading normal is the triangle's, nothing
    /// is drawn again.
    fn hemisphere_direction(surface: &Surface, rng: &mut StdRng) -> Vec3 {
        // At least half the shading normal's lobe lies above the plane (it is turned to the
        // plane's side), so 32 draws all fail with a chance below 2^-32.
        for _ in 0..32 {
            let dir = cosine_direction(surface.normal, rng.random(), rng.random());
            if dir.dot(surface.geometric) > 0.0 {
                return dir;
            }
        }
        cosine_direction(surface.geometric, rng.random(), rng.random())
    }
}

/// The normal map's normal at `uv` in the frame of unit `n` and the triangle's tangents `t`
/// (interpolated with `weights`), as `mapped_normal` in shaders/gbuffer.wgsl: nearest texel.
fn mapped_normal(n: Vec3, t: &[[f32; 4]; 3], weights: [f32; 3], map: &NormalMap, uv: [f32; 2]) -> Vec3 {
    let tangent: Vec3 = (0..3).map(|k| Vec3::from_slice(&t[k][..3]) * weights[k]).sum();
    let sign = t.iter().map(|t| t[3]).find(|w| *w != 0.0).unwrap_or(0.0);
    let Some(tu) = (tangent - n * n.dot(tangent)).try_normalize().filter(|_| sign != 0.0) else { return n };
    let bv = n.cross(tu) * sign.signum();
    let [r, g, b, _] = map.image.texel(uv);
    let m = Vec3::new(r as f32, g as f32, b as f32) / 255.0 * 2.0 - 1.0;
    let m = Vec3::new(m.x * map.scale, m.y * map.scale, m.z.max(0.0));
    (tu * m.x + bv * m.y + n * m.z).try_normalize().unwrap_or(n)
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
    /// The bounce's luminance by where its sender lies ([`Placement::index`]): they add up to
    /// the bounce's.
    pub bounce_by_place: Places,
    /// The sky's luminance the occluders block (what each ray that hits something would have
    /// brought from the sky), by where the occluder lies: what the screen can block and what not.
    pub blocked_by_place: Places,
}

impl ReferenceScene {
    /// Sky light, one bounce and openness at `surface` with exact visibility, and the within-R
    /// AO, sky and bounce, from `spp` cosine-distributed rays (every sender counted as seen).
    pub fn estimate(
        &self,
        surface: &Surface,
        lights: &[PointLight],
        rig: &LightRig,
        sky: &Skybox,
        settings: &TraceSettings,
        rng: &mut StdRng,
    ) -> Estimate {
        self.estimate_placed(surface, (lights, rig), sky, settings, rng, &|_| Placement::seen())
    }

    /// [`ReferenceScene::estimate`], with the bounce split by where `place` says each sender lies.
    pub fn estimate_placed(
        &self,
        surface: &Surface,
        (lights, rig): (&[PointLight], &LightRig),
        sky: &Skybox,
        settings: &TraceSettings,
        rng: &mut StdRng,
        place: &dyn Fn(&Surface) -> Placement,
    ) -> Estimate {
        let n = settings.samples_per_pixel.max(1);
        let origin = surface.position + surface.geometric * self.epsilon;
        let (mut ao_sum, mut ao_sq) = (0.0f32, 0.0f32);
        let (mut sky_sum, mut sky_sq) = (Vec3::ZERO, 0.0f32);
        let (mut bounce_sum, mut bounce_sq) = (Vec3::ZERO, 0.0f32);
        let (mut open, mut sky_near, mut bounce_near) = (0.0f32, Vec3::ZERO, Vec3::ZERO);
        let (mut by_place, mut blocked): (Places, Places) = Default::default();
        for _ in 0..n {
            let dir = Self::hemisphere_direction(surface, rng);
            match self.trace(origin, dir, f32::INFINITY) {
                None => {
                    let l = sky.sample(dir) * settings.sky_scale;
                    sky_sum += l;
                    sky_sq += luminance(l).powi(2);
                    sky_near += l;
                    open += 1.0;
                }
                Some(sender) => {
                    let diffuse = self.sender_radiance(&sender, -dir, lights, rig, sky, settings, rng);
                    bounce_sum += diffuse;
                    bounce_sq += luminance(diffuse).powi(2);
                    // The sky this occluder blocks: the within-R image's beyond R.
                    let blocked_sky = sky.sample(dir) * settings.sky_scale;
                    let at = place(&sender).index();
                    by_place[at] += luminance(diffuse);
                    blocked[at] += luminance(blocked_sky);
                    if sender.distance < settings.radius {
                        ao_sum += 1.0;
                        ao_sq += 1.0;
                        bounce_near += diffuse;
                    } else {
                        sky_near += blocked_sky;
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
            bounce_by_place: by_place.map(|b| b / nf),
            blocked_by_place: blocked.map(|b| b / nf),
        }
    }

    /// The diffuse radiance a sender sends towards `to_receiver`: ρ/π times its direct
    /// irradiance — the point lights (unshadowed, as the GPU's lighting pass), and the sky and the
    /// constant ambient through what the sender itself sees, estimated with one cosine-distributed
    /// ray (unbiased: its mean over rays is the sender's visible E/π).
    #[allow(clippy::too_many_arguments)]
    fn sender_radiance(
        &self,
        sender: &Surface,
        to_receiver: Vec3,
        lights: &[PointLight],
        rig: &LightRig,
        sky: &Skybox,
        settings: &TraceSettings,
        rng: &mut StdRng,
    ) -> Vec3 {
        let (points, _) = point_lighting(sender, to_receiver, lights, rig);
        let dir = Self::hemisphere_direction(sender, rng);
        let origin = sender.position + sender.geometric * self.epsilon;
        let environment = match self.trace(origin, dir, f32::INFINITY) {
            None => sky.sample(dir) * settings.sky_scale + Vec3::splat(settings.ambient),
            Some(_) => Vec3::ZERO,
        };
        points + sender.albedo * environment
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

/// Distance along the ray (unit `direction`) to an axis-aligned cube of half edge `half` around
/// `center`, if it is hit in front of `origin`.
pub(super) fn ray_box(origin: Vec3, direction: Vec3, center: Vec3, half: f32) -> Option<f32> {
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
