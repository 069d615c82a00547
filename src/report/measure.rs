//! One configuration measured against the truth: timed, rendered, read back and compared, pixel
//! for pixel on the surfaces both renderers see.

use glam::Vec3;

use super::options::ReportOptions;
use super::row::{NoiseFloor, Row};
use super::sweep::{Config, CUT_DEG};
use super::{maps, metrics};
use crate::gpu::Gpu;
use crate::headless::capture::capture_path_from;
use crate::headless::readback::{read_occlusion, read_rgba16f};
use crate::knobs::Knobs;
use crate::reference::{self, Reference};
use crate::render::{Mode, Renderer, View};
use crate::scene::OrbitCamera;
use crate::{Error, Result};

/// The truth at one radius: the mean of two independent traces, the pixels to measure, and the
/// traces' own noise.
pub(crate) struct Truth {
    pub reference: Reference,
    /// The surface pixels both renderers see.
    pub valid: Vec<usize>,
    pub noise: NoiseFloor,
}

/// What a truth is traced from: the scene, its sky and the settings every row renders with.
pub(crate) struct TruthSource<'a> {
    pub bvh: crate::reference::ReferenceScene,
    pub scene: &'a crate::scene::Scene,
    pub sky: &'a crate::scene::Skybox,
    pub sky_name: &'a str,
    pub size: (u32, u32),
    /// Rays per pixel in each of the two traces, and the first trace's seed.
    pub samples_per_pixel: u32,
    pub seed: u64,
    pub sky_scale: f32,
    pub ambient: f32,
}

impl<'a> TruthSource<'a> {
    /// The truth of `scene` under `sky` as the report's `options` ask for it (size, rays, seed),
    /// lit as `base` lights the GPU's frames.
    pub fn new(
        scene: &'a crate::scene::Scene,
        sky: &'a crate::scene::Skybox,
        sky_name: &'a str,
        options: &ReportOptions,
        base: &crate::render::Settings,
    ) -> Self {
        Self::of_view(scene, (sky, sky_name), options.on.size, (options.samples_per_pixel, options.on.seed), base)
    }

    /// The truth of `scene` under `sky` (and its name) at `size`, with `rays` (rays per pixel in
    /// each of the two traces, the first trace's seed), lit as `base` lights the GPU's frames.
    pub fn of_view(
        scene: &'a crate::scene::Scene,
        (sky, sky_name): (&'a crate::scene::Skybox, &'a str),
        size: (u32, u32),
        (samples_per_pixel, seed): (u32, u64),
        base: &crate::render::Settings,
    ) -> Self {
        Self {
            bvh: crate::reference::ReferenceScene::new(&scene.model),
            scene,
            sky,
            sky_name,
            size,
            samples_per_pixel,
            seed,
            sky_scale: base.sky_scale,
            ambient: base.ambient,
        }
    }

    /// The truth in `camera`'s view, at `radius` (for the within-R images), on the surfaces of
    /// `depth` (the G-buffer's, read back): the mean of two traces with independent seeds.
    pub fn trace(&self, camera: &OrbitCamera, depth: &[f32], radius: f32, tick: &(dyn Fn() + Sync)) -> Result<Truth> {
        let trace = |seed: u64| {
            let settings = crate::reference::TraceSettings {
                samples_per_pixel: self.samples_per_pixel,
                seed,
                radius,
                sky_scale: self.sky_scale,
                ambient: self.ambient,
            };
            let (lights, rig) = (&self.scene.lights, &self.scene.rig);
            reference::trace(&self.bvh, lights, rig, self.sky, camera, self.size, depth, &settings, tick)
        };
        let (a, b) = (trace(self.seed), trace(self.seed ^ 0x5DEE_CE66_D1CE_4E5B));
        Truth::from_traces(&a, &b, self.ambient, self.sky_name, self.sky.max_value())
    }
}

impl Truth {
    /// The truth as the GPU's `gpu_image` displays (the same exposure and tone map): its
    /// radiance where it is measured, the GPU's pixels elsewhere (the sky, the lights' cubes,
    /// silhouettes).
    pub fn displayed(&self, gpu_image: &image::RgbImage, ambient: f32, exposure: f32) -> image::RgbImage {
        let mut image = gpu_image.clone();
        let width = image.width();
        for &i in &self.valid {
            let (x, y) = ((i as u32) % width, (i as u32) / width);
            image.put_pixel(x, y, image::Rgb(metrics::display(self.reference.radiance(i, ambient), exposure)));
        }
        image
    }

    /// Joins two traces; nothing to measure, or a truth beyond 32-bit floats, is an error.
    pub fn from_traces(a: &Reference, b: &Reference, ambient: f32, sky_name: &str, sky_peak: f32) -> Result<Self> {
        let truth = Reference::mean(a, b);
        let valid: Vec<usize> = (0..truth.valid.len()).filter(|&i| truth.valid[i]).collect();
        // Nothing to measure is an error, not a table of zeros and infinite PSNRs.
        if valid.is_empty() {
            return Err(Error::Setting(format!(
                "the view shows no surface pixel that the ray tracer and the GPU agree on ({} background, {} \
                 silhouette, {} under a light's cube): nothing to measure",
                truth.valid.len() - truth.mismatched - truth.covered,
                truth.mismatched,
                truth.covered
            )));
        }
        // A sky so bright that the truth overflows 32-bit floats gives no number worth a row.
        if valid.iter().any(|&i| !truth.radiance(i, ambient).is_finite()) {
            return Err(Error::Setting(format!(
                "{sky_name}: the ray-traced truth overflows 32-bit floats under this sky (radiance up to {sky_peak:e}); \
                 scale the sky down"
            )));
        }
        let half_difference = |f: &dyn Fn(&Reference, usize) -> Vec3| {
            metrics::rmse(valid.iter().flat_map(|&i| {
                let (x, y) = (f(a, i), f(b, i));
                (0..3).map(move |c| (0.5 * x[c], 0.5 * y[c]))
            }))
        };
        let noise = NoiseFloor {
            hdr: half_difference(&|r, i| r.radiance(i, ambient)),
            directional: half_difference(&|r, i| r.directional(i)),
            ao: half_difference(&|r, i| Vec3::splat(r.ao[i])),
        };
        Ok(Self { reference: truth, valid, noise })
    }
}

/// Error maps as PNG files by name.
pub(crate) type MapFiles = Vec<(String, Vec<u8>)>;

/// What every measurement of one report shares.
pub(crate) struct Bench<'a> {
    pub gpu: &'a Gpu,
    pub camera: &'a OrbitCamera,
    pub view: &'a wgpu::TextureView,
    pub options: &'a ReportOptions,
    pub ambient: f32,
    /// Measure the bounce's ratio to the truth's too (one more capture a row).
    pub diagnostics: bool,
    /// Time the frame (`false`: the row's `ms` is 0, for a view whose time another view gives).
    pub timed: bool,
}

impl Bench<'_> {
    /// Times `config` at `radius`, renders it, and measures it against `truth`. `maps`: where
    /// to keep this configuration's error maps (PNG files by name), if they are wanted.
    pub fn measure(
        &self,
        renderer: &mut Renderer,
        config: Config,
        radius: f32,
        truth: &Truth,
        maps: Option<&mut MapFiles>,
    ) -> Result<Row> {
        let (gpu, camera) = (self.gpu, self.camera);
        let (mode, orbit, cut, bounce) = (config.mode, config.orbit, config.cut, config.bounce());
        renderer.settings = config.settings(radius);
        let ms = if self.timed {
            crate::headless::bench::measure(gpu, renderer, camera, self.view, self.options.frames)?.frame_ms
        } else {
            0.0
        };
        // The frames averaged, turning `orbit` degrees each, ending in the truth's view; after a
        // cut, as many before them from CUT_DEG around.
        let lead_in = if cut { config.knobs.accumulate as u32 } else { 0 };
        let camera_at = |k: u32| {
            let turn = if cut && k >= lead_in { CUT_DEG } else { orbit * k as f32 };
            OrbitCamera { yaw_deg: camera.yaw_deg - turn, ..*camera }
        };
        let image = capture_path_from(gpu, renderer, lead_in, camera_at)?;
        let frame = Frame::read(gpu, renderer, mode)?;
        let errors = frame.errors(truth, self.ambient);
        let (bounce_ratio, bounce_seen_ratio) = if self.diagnostics && frame.directional.is_some() && bounce.is_some() {
            self.bounce_ratios(renderer, (lead_in, &camera_at), truth, frame.unexpose)?
        } else {
            (None, None)
        };
        let flip = self.flip(image, truth, renderer.settings.exposure, maps.map(|m| (m, &frame)))?;
        let Errors { hdr_rmse, hdr_rmse_near, hdr_peak, ao_rmse, do_rmse, do_rmse_near } = errors;
        // (The far side is drawn only where the scene has point lights to light it.)
        let plan = renderer.plan();
        let drawn = Knobs {
            far_side: config.far_side() && plan.far_side,
            far_sky: config.far_sky() && plan.has(crate::render::modes::Step::FAR_SKY),
            ..config.knobs
        };
        Ok(Row {
            config: Config { knobs: drawn, ..config },
            radius: if mode == Mode::Off { 0.0 } else { radius },
            ms,
            ao_rmse,
            do_rmse,
            do_rmse_near,
            bounce_ratio,
            bounce_seen_ratio,
            hdr_rmse,
            hdr_rmse_near,
            hdr_psnr: metrics::psnr(hdr_rmse, hdr_peak),
            flip,
            pareto: false,
            preset: None,
        })
    }

    /// The bounce alone (the DO-indirect view zeroes the sky), against the truth's and against
    /// the truth's from the senders the camera sees: ratios of means, so noise cancels and only
    /// the estimator's bias remains.
    fn bounce_ratios(
        &self,
        renderer: &mut Renderer,
        (lead_in, camera_at): (u32, &dyn Fn(u32) -> OrbitCamera),
        truth: &Truth,
        unexpose: f32,
    ) -> Result<(Option<f64>, Option<f64>)> {
        let view = renderer.settings.view;
        renderer.settings.view = View::DoIndirect;
        capture_path_from(self.gpu, renderer, lead_in, camera_at)?;
        renderer.settings.view = view;
        let bounce = renderer.targets().occlusion().directional.map(|t| read_rgba16f(self.gpu, &t.texture));
        let bounce = bounce.transpose()?.unwrap_or_default();
        let valid = &truth.valid;
        let mean =
            |f: &dyn Fn(usize) -> f32| valid.iter().map(|&i| f(i) as f64).sum::<f64>() / valid.len().max(1) as f64;
        let got = mean(&|i| reference::luminance(Vec3::new(bounce[i][0], bounce[i][1], bounce[i][2]) * unexpose));
        let want = mean(&|i| reference::luminance(truth.reference.bounce[i]));
        let seen = truth.reference.seen_bounce(valid);
        Ok(((want > 0.0).then(|| got / want), (seen > 0.0).then(|| got / seen)))
    }

    /// FLIP between the displayed GPU image and the truth displayed alike; with `maps` (where
    /// to keep them, and the frame's buffers read back), the error maps are made too.
    fn flip(
        &self,
        image: image::RgbaImage,
        truth: &Truth,
        exposure: f32,
        maps: Option<(&mut MapFiles, &Frame)>,
    ) -> Result<f64> {
        let gpu_image = image::DynamicImage::ImageRgba8(image).to_rgb8();
        let ref_image = truth.displayed(&gpu_image, self.ambient, exposure);
        let (flip, flip_map) = metrics::flip(&ref_image, &gpu_image, &truth.reference.valid);
        if let Some((kept, frame)) = maps {
            let buffers = (frame.ao.as_deref(), frame.directional.as_deref());
            kept.extend(maps::encode(&self.options.out, &truth.reference, buffers, &ref_image, &gpu_image, &flip_map)?);
        }
        Ok(flip)
    }
}

/// A frame's linear buffers as read back, pre-exposure divided out.
pub(crate) struct Frame {
    ao: Option<Vec<f32>>,
    directional: Option<Vec<[f32; 4]>>,
    pub hdr: Vec<Vec3>,
    /// 1 / the pre-exposure the half-float buffers hold radiance at.
    unexpose: f32,
}

/// A frame's errors against the truth, over its valid pixels.
pub(crate) struct Errors {
    pub hdr_rmse: f64,
    pub hdr_rmse_near: f64,
    /// The truth's brightest channel (PSNR's peak).
    pub hdr_peak: f64,
    pub ao_rmse: Option<f64>,
    pub do_rmse: Option<f64>,
    pub do_rmse_near: Option<f64>,
}

impl Frame {
    pub fn read(gpu: &Gpu, renderer: &Renderer, mode: Mode) -> Result<Self> {
        // The half-float buffers hold radiance × pre-exposure: divided out here.
        let unexpose = 1.0 / renderer.pre_exposure();
        let values = read_occlusion(gpu, renderer.targets().occlusion(), mode.declaration().ambient_occlusion)?;
        let directional = values.directional.map(|d| {
            d.into_iter().map(|p| [p[0] * unexpose, p[1] * unexpose, p[2] * unexpose, p[3]]).collect::<Vec<_>>()
        });
        let hdr: Vec<Vec3> = read_rgba16f(gpu, &renderer.targets().hdr()?.texture)?
            .into_iter()
            .map(|p| Vec3::new(p[0], p[1], p[2]) * unexpose)
            .collect();
        Ok(Self { ao: values.ao, directional, hdr, unexpose })
    }

    pub fn errors(&self, truth: &Truth, ambient: f32) -> Errors {
        let (valid, truth) = (&truth.valid, &truth.reference);
        let against = |want: &dyn Fn(usize) -> Vec3| {
            metrics::rmse(valid.iter().flat_map(|&i| {
                let (got, want) = (self.hdr[i], want(i));
                (0..3).map(move |c| (got[c], want[c]))
            }))
        };
        let do_against = |want: &dyn Fn(usize) -> Vec3| {
            self.directional.as_ref().map(|d| {
                metrics::rmse(valid.iter().flat_map(|&i| {
                    let w = want(i);
                    (0..3).map(move |c| (d[i][c], w[c]))
                }))
            })
        };
        Errors {
            hdr_rmse: against(&|i| truth.radiance(i, ambient)),
            hdr_rmse_near: against(&|i| truth.radiance_near(i, ambient)),
            hdr_peak: valid.iter().map(|&i| truth.radiance(i, ambient).max_element()).fold(1e-6f32, f32::max) as f64,
            ao_rmse: self.ao.as_ref().map(|ao| metrics::rmse(valid.iter().map(|&i| (ao[i], truth.ao[i])))),
            do_rmse: do_against(&|i| truth.directional(i)),
            do_rmse_near: do_against(&|i| truth.directional_near(i)),
        }
    }
}
