//! The reference image: every pixel's primary ray, its cosine-distributed secondary rays and what
//! they bring (sky, bounce, openness, within-R diagnostics), traced in parallel and seeded per
//! pixel, with where each bounce's sender lies for the camera; and the two-seed pair whose mean is
//! the truth and whose difference is its noise floor.

use glam::{Vec3, Vec4Swizzles};
use rand::{rngs::StdRng, SeedableRng};
use rayon::prelude::*;

use super::layers::within_two_surfaces;
use super::place::{Placement, Places, SenderPlace};
use super::scene::{point_lighting, ray_box, ReferenceScene, Surface, TraceSettings};
use crate::scene::{LightRig, OrbitCamera, PointLight, Skybox};

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
    /// The bounce's luminance by where its sender lies for the camera ([`Placement::index`]).
    pub bounce_by_place: Vec<Places>,
    /// The sky the occluders block, by where they lie ([`Placement::index`]).
    pub blocked_by_place: Vec<Places>,
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
    bounce_by_place: Places,
    blocked_by_place: Places,
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
    let go_on = || {
        progress();
        true
    };
    let traced = trace_while(scene, (lights, rig), sky, camera, (size, gpu_depth), settings, &go_on);
    traced.expect("a trace that is never stopped ends")
}

/// [`trace`], stopped as soon as `go_on` (called once per finished row) says no: `None` then.
/// The viewer's truth stops a trace whose view has changed without waiting for its rows.
pub fn trace_while(
    scene: &ReferenceScene,
    (lights, rig): (&[PointLight], &LightRig),
    sky: &Skybox,
    camera: &OrbitCamera,
    (size, gpu_depth): ((u32, u32), &[f32]),
    settings: &TraceSettings,
    go_on: &(dyn Fn() -> bool + Sync),
) -> Option<Reference> {
    use std::sync::atomic::{AtomicBool, Ordering};
    let (w, h) = size;
    let stopped = AtomicBool::new(false);
    let tracer = Tracer {
        scene,
        lights,
        rig,
        sky,
        settings,
        gpu_depth,
        size,
        eye: camera.eye(),
        world_to_view: camera.world_to_view(),
        view_to_world: camera.world_to_view().inverse(),
        projection: camera.view_to_clip(w as f32 / h as f32),
    };
    let rows: Vec<Vec<PixelResult>> = (0..h)
        .into_par_iter()
        .map(|y| {
            if stopped.load(Ordering::Relaxed) {
                return Vec::new();
            }
            let row = (0..w).map(|x| tracer.pixel(x, y)).collect();
            if !go_on() {
                stopped.store(true, Ordering::Relaxed);
            }
            row
        })
        .collect();
    if stopped.load(Ordering::Relaxed) {
        return None;
    }
    Some(Reference::from_pixels(rows.into_iter().flatten().collect(), gpu_depth, size))
}

/// What every pixel of one trace shares.
struct Tracer<'a> {
    scene: &'a ReferenceScene,
    lights: &'a [PointLight],
    rig: &'a LightRig,
    sky: &'a Skybox,
    settings: &'a TraceSettings,
    gpu_depth: &'a [f32],
    size: (u32, u32),
    eye: Vec3,
    world_to_view: glam::Mat4,
    view_to_world: glam::Mat4,
    projection: glam::Mat4,
}

/// How far a sender may lie from the depth buffer's surface at its pixel and still be the
/// surface the screen shows: this share of its distance, plus the depth its tilt spans over one
/// pixel.
const SEEN_DEPTH_SHARE: f32 = 0.02;

impl Tracer<'_> {
    /// Pixel (x, y): the surface its centre's ray hits, if the GPU sees the same one there, and
    /// the estimates at it.
    fn pixel(&self, x: u32, y: u32) -> PixelResult {
        let (w, h) = self.size;
        let (scene, lights, rig) = (self.scene, self.lights, self.rig);
        let (eye, projection, view_to_world) = (self.eye, self.projection, self.view_to_world);
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
            bounce_by_place: [0.0; Placement::COUNT],
            blocked_by_place: [0.0; Placement::COUNT],
            direct: Vec3::ZERO,
        };
        let Some(surface) = scene.trace(eye, direction, f32::INFINITY) else { return empty };
        // The lights' emissive cubes cover the surface here on the GPU's image (and its depth);
        // the reference has no such cubes, so the pixel measures nothing.
        let cube = lights
            .iter()
            .any(|l| ray_box(eye, direction, l.position, rig.cube_half_size).is_some_and(|t| t < surface.distance));
        if cube {
            return PixelResult { covered: true, ..empty };
        }
        // The GPU's depth at this pixel as a distance along the same view axis.
        let depth = self.gpu_depth[index];
        let view_z = surface.distance * direction.dot((view_to_world * Vec3::NEG_Z.extend(0.0)).xyz());
        let gpu_z = if depth > 0.0 { (projection.w_axis.z) / (depth + projection.z_axis.z) } else { f32::INFINITY };
        if !((view_z - gpu_z).abs() <= 1e-3 * view_z) {
            return empty;
        }
        let mut rng = StdRng::seed_from_u64(self.settings.seed ^ (index as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let e = scene.estimate_placed(&surface, (lights, rig), self.sky, self.settings, &mut rng, &|s| self.place(s));
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
            bounce_by_place: e.bounce_by_place,
            blocked_by_place: e.blocked_by_place,
            direct: diffuse + specular,
        }
    }

    /// Where `sender` lies for this camera and its depth buffer: off screen (outside the view),
    /// facing away (the side that lights the receiver turned from the eye), seen (where the
    /// depth buffer is, at its pixel), or hidden (behind what the depth buffer holds there); and
    /// for the hidden and the facing away, whether the first two surfaces on its eye ray hold it.
    fn place(&self, sender: &Surface) -> Placement {
        let place = self.place_alone(sender);
        let in_two_layers = match place {
            SenderPlace::Seen => true,
            SenderPlace::OffScreen => false,
            SenderPlace::Hidden | SenderPlace::FacingAway => within_two_surfaces(self.scene, self.eye, sender.position),
        };
        Placement { place, in_two_layers }
    }

    /// Where `sender` lies for this camera and its depth buffer, alone.
    fn place_alone(&self, sender: &Surface) -> SenderPlace {
        let (w, h) = self.size;
        let view = self.world_to_view.transform_point3(sender.position);
        let clip = self.projection * view.extend(1.0);
        if !(clip.w > 0.0) {
            return SenderPlace::OffScreen;
        }
        let ndc = clip.xy() / clip.w;
        if !(ndc.abs().max_element() < 1.0) {
            return SenderPlace::OffScreen;
        }
        let to_eye = self.eye - sender.position;
        let facing = sender.geometric.dot(to_eye) / to_eye.length().max(1e-30);
        if !(facing > 0.0) {
            return SenderPlace::FacingAway;
        }
        let x = (((ndc.x * 0.5 + 0.5) * w as f32) as u32).min(w - 1);
        let y = (((0.5 - ndc.y * 0.5) * h as f32) as u32).min(h - 1);
        let depth = self.gpu_depth[(y * w + x) as usize];
        if !(depth > 0.0) {
            return SenderPlace::Hidden;
        }
        let shown = self.projection.w_axis.z / (depth + self.projection.z_axis.z);
        let z = -view.z;
        // One pixel's width at the sender's distance, and the depth the sender's tilt spans
        // over it.
        let pixel = 2.0 * z / (h as f32 * self.projection.y_axis.y);
        let tilt = (1.0 - facing * facing).max(0.0).sqrt() / facing.max(0.02);
        if (z - shown).abs() <= SEEN_DEPTH_SHARE * z + pixel * tilt {
            SenderPlace::Seen
        } else {
            SenderPlace::Hidden
        }
    }
}

impl Reference {
    /// The reference of a trace's pixels, row by row, for a screen of `size` whose G-buffer
    /// depth is `gpu_depth`.
    fn from_pixels(pixels: Vec<PixelResult>, gpu_depth: &[f32], size: (u32, u32)) -> Self {
        let valid_count = pixels.iter().filter(|p| p.valid).count().max(1) as f64;
        let mean_error = |f: &dyn Fn(&PixelResult) -> f32| {
            pixels.iter().filter(|p| p.valid).map(|p| f(p) as f64).sum::<f64>() / valid_count
        };
        let surfaces = gpu_depth.iter().filter(|d| **d > 0.0).count();
        Reference {
            width: size.0,
            height: size.1,
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
            bounce_by_place: pixels.iter().map(|p| p.bounce_by_place).collect(),
            blocked_by_place: pixels.iter().map(|p| p.blocked_by_place).collect(),
            direct: pixels.iter().map(|p| p.direct).collect(),
        }
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
        Self::weighted_mean((a, 1.0), (b, 1.0))
    }

    /// The mean of two independent traces of the same view with `wa` and `wb` rays a pixel: one
    /// trace of `wa + wb` rays, as the viewer's truth adds its passes up.
    pub fn weighted_mean((a, wa): (&Reference, f64), (b, wb): (&Reference, f64)) -> Reference {
        let (ka, kb) = ((wa / (wa + wb)) as f32, (wb / (wa + wb)) as f32);
        let avg3 = |x: &[Vec3], y: &[Vec3]| x.iter().zip(y).map(|(p, q)| ka * *p + kb * *q).collect();
        let avg1 = |x: &[f32], y: &[f32]| x.iter().zip(y).map(|(p, q)| ka * p + kb * q).collect();
        let avg_places = |x: &[Places], y: &[Places]| {
            x.iter().zip(y).map(|(p, q)| std::array::from_fn(|k| ka * p[k] + kb * q[k])).collect()
        };
        // Independent errors: their weighted sum's standard error.
        let error = |ea: f64, eb: f64| ((ka as f64 * ea).powi(2) + (kb as f64 * eb).powi(2)).sqrt();
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
            bounce_by_place: avg_places(&a.bounce_by_place, &b.bounce_by_place),
            blocked_by_place: avg_places(&a.blocked_by_place, &b.blocked_by_place),
            direct: a.direct.clone(),
            ao_error: error(a.ao_error, b.ao_error),
            sky_error: error(a.sky_error, b.sky_error),
            bounce_error: error(a.bounce_error, b.bounce_error),
            mismatched: a.mismatched.max(b.mismatched),
            covered: a.covered,
        }
    }
}
