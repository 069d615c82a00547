//! One configuration measured against the truth: timed, rendered, read back and compared, pixel
//! for pixel on the surfaces both renderers see.

use glam::Vec3;

use super::sweep::Config;
use super::{metrics, plot, NoiseFloor, ReportOptions, Row};
use crate::gpu::Gpu;
use crate::headless::capture::capture_path;
use crate::headless::readback::{read_occlusion, read_rgba16f};
use crate::reference::{self, Reference};
use crate::render::{Mode, Renderer, View};
use crate::scene::OrbitCamera;
use crate::{Error, Result};

/// The truth at one radius: the mean of two independent traces, the pixels to measure, and the
/// traces' own noise.
pub(super) struct Truth {
    pub reference: Reference,
    /// The surface pixels both renderers see.
    pub valid: Vec<usize>,
    pub noise: NoiseFloor,
}

impl Truth {
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

/// What every measurement of one report shares.
pub(super) struct Bench<'a> {
    pub gpu: &'a Gpu,
    pub camera: &'a OrbitCamera,
    pub view: &'a wgpu::TextureView,
    pub options: &'a ReportOptions,
    pub ambient: f32,
}

impl Bench<'_> {
    /// Times `config` at `radius`, renders it, and measures it against `truth`. `maps`: write
    /// the error maps of this configuration.
    pub fn measure(
        &self,
        renderer: &mut Renderer,
        config: Config,
        radius: f32,
        truth: &Truth,
        maps: bool,
    ) -> Result<Row> {
        let (gpu, camera, ambient) = (self.gpu, self.camera, self.ambient);
        let (valid, truth) = (&truth.valid, &truth.reference);
        let Config { mode, variant, samples, steps, blur, pyramid, bounce, accumulate, orbit, half } = config;
        renderer.settings = config.settings(radius);
        let ms = crate::headless::bench::measure(gpu, renderer, camera, self.view, self.options.frames)?.frame_ms;
        // The frames averaged, turning `orbit` degrees each, ending in the truth's view.
        let camera_at = |k: u32| OrbitCamera { yaw_deg: camera.yaw_deg - orbit * k as f32, ..*camera };
        let image = capture_path(gpu, renderer, camera_at)?;
        let s = renderer.settings;
        // The half-float buffers hold radiance × pre-exposure: divided out here.
        let unexpose = 1.0 / renderer.pre_exposure();
        let values = read_occlusion(gpu, renderer.targets().occlusion(), mode.declaration().ambient_occlusion)?;
        let ao = values.ao;
        let directional = values.directional.map(|d| {
            d.into_iter().map(|p| [p[0] * unexpose, p[1] * unexpose, p[2] * unexpose, p[3]]).collect::<Vec<_>>()
        });
        let hdr: Vec<Vec3> = read_rgba16f(gpu, &renderer.targets().hdr()?.texture)?
            .into_iter()
            .map(|p| Vec3::new(p[0], p[1], p[2]) * unexpose)
            .collect();
        let against = |want: &dyn Fn(usize) -> Vec3| {
            metrics::rmse(valid.iter().flat_map(|&i| {
                let (got, want) = (hdr[i], want(i));
                (0..3).map(move |c| (got[c], want[c]))
            }))
        };
        let hdr_rmse = against(&|i| truth.radiance(i, ambient));
        let hdr_rmse_near = against(&|i| truth.radiance_near(i, ambient));
        let hdr_peak = valid.iter().map(|&i| truth.radiance(i, ambient).max_element()).fold(1e-6f32, f32::max) as f64;
        let ao_rmse = ao.as_ref().map(|ao| metrics::rmse(valid.iter().map(|&i| (ao[i], truth.ao[i]))));
        let do_against = |want: &dyn Fn(usize) -> Vec3| {
            directional.as_ref().map(|d| {
                metrics::rmse(valid.iter().flat_map(|&i| {
                    let w = want(i);
                    (0..3).map(move |c| (d[i][c], w[c]))
                }))
            })
        };
        let do_rmse = do_against(&|i| truth.directional(i));
        let do_rmse_near = do_against(&|i| truth.directional_near(i));
        // The bounce alone (the DO-indirect view zeroes the sky), against the truth's: a ratio
        // of means, so noise cancels and only the estimator's bias remains.
        let bounce_ratio = if directional.is_some() && bounce.is_some() {
            renderer.settings.view = View::DoIndirect;
            capture_path(gpu, renderer, camera_at)?;
            renderer.settings.view = s.view;
            let bounce = renderer.targets().occlusion().directional.map(|t| read_rgba16f(gpu, &t.texture));
            let bounce = bounce.transpose()?.unwrap_or_default();
            let mean =
                |f: &dyn Fn(usize) -> f32| valid.iter().map(|&i| f(i) as f64).sum::<f64>() / valid.len().max(1) as f64;
            let got = mean(&|i| reference::luminance(Vec3::new(bounce[i][0], bounce[i][1], bounce[i][2]) * unexpose));
            let want = mean(&|i| reference::luminance(truth.bounce[i]));
            (want > 0.0).then(|| got / want)
        } else {
            None
        };

        let gpu_image = image::DynamicImage::ImageRgba8(image).to_rgb8();
        let mut ref_image = gpu_image.clone();
        let width = self.options.size.0;
        for &i in valid {
            let (x, y) = ((i as u32) % width, (i as u32) / width);
            ref_image.put_pixel(x, y, image::Rgb(metrics::display(truth.radiance(i, ambient), s.exposure)));
        }
        let (flip, flip_map) = metrics::flip(&ref_image, &gpu_image, &truth.valid);
        if maps {
            plot::write_maps(&self.options.out, truth, &ao, &ref_image, &gpu_image, &flip_map)?;
        }
        Ok(Row {
            mode,
            variant,
            samples,
            steps,
            pyramid,
            blur,
            bounce: if mode.declaration().directional_occlusion { bounce } else { None },
            radius: if mode == Mode::Off { 0.0 } else { radius },
            accumulate,
            orbit,
            half,
            ms,
            ao_rmse,
            do_rmse,
            do_rmse_near,
            bounce_ratio,
            hdr_rmse,
            hdr_rmse_near,
            hdr_psnr: metrics::psnr(hdr_rmse, hdr_peak),
            flip,
            pareto: false,
        })
    }
}
