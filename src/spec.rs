//! What a run asks for — the scene (model, sky, lights, layout), the camera and the render
//! settings — as command-line flags, with their defaults, the range each is refused outside of
//! (the range in the message) and the loading they lead to. The command line, the viewer and the
//! bench share it; `src/cli.rs` only adds the commands around it.

use std::path::PathBuf;

use clap::Args;

use crate::knobs::{Knobs, SwitchFlags, KNOBS};
use crate::preset::Preset;
use crate::render::sampling::DEFAULT_BIAS;
use crate::render::{GivenLengths, Mode, SenderSky, Settings, Variant, View};
use crate::scene::camera::{DISTANCE_RADII, REACH_RADII};
use crate::scene::{self, OrbitCamera, Scene};
use crate::{Error, Result};

#[derive(Args)]
pub struct SceneArgs {
    /// model: the model framed by the orbit camera; room: the model lying on the floor of a closed
    /// room that fills the screen, seen by a fixed camera (the classic SSAO chapter's set-up);
    /// crevices, fence, open, stairs: the report's scenes, framed as the report sees them (open
    /// under skyboxes/redblue unless --skybox is given)
    #[arg(long = "scene", default_value = "model")]
    pub layout: scene::Layout,
    /// With --scene room and no --model: the built-in figure's triangle count [default: 50000]
    #[arg(long)]
    pub triangles: Option<usize>,
    /// Model to load: OBJ (.obj) or glTF 2.0 (.gltf, .glb) [default: models/cornell/cornell.obj]
    #[arg(long)]
    pub model: Option<PathBuf>,
    /// Sky: a folder of six faces, or an equirectangular panorama (.hdr, .exr, .png, .jpg)
    /// [default: skyboxes/day]
    #[arg(long)]
    pub skybox: Option<PathBuf>,
    /// Number of random point lights, 0-4096
    #[arg(long, default_value_t = scene::DEFAULT_LIGHTS, value_parser = parse_lights)]
    pub lights: usize,
    /// Seed for the lights' colours and positions
    #[arg(long, default_value_t = 1, value_parser = parse_seed)]
    pub seed: u64,
    /// The point the orbit camera turns about, X,Y,Z [default: the model's centre]
    #[arg(long, value_parser = parse_point, allow_hyphen_values = true)]
    pub target: Option<glam::Vec3>,
    /// The fly camera: where the eye is, X,Y,Z (with --look-at; instead of --target, --yaw,
    /// --pitch and --distance)
    #[arg(long, value_parser = parse_point, allow_hyphen_values = true, requires = "look_at",
          conflicts_with_all = ["target", "yaw", "pitch", "distance"])]
    pub eye: Option<glam::Vec3>,
    /// The fly camera: the point the eye looks at, X,Y,Z (with --eye)
    #[arg(long, value_parser = parse_point, allow_hyphen_values = true, requires = "eye")]
    pub look_at: Option<glam::Vec3>,
    /// Camera yaw around the model in degrees [default: 35]
    #[arg(long, allow_hyphen_values = true)]
    pub yaw: Option<f32>,
    /// Camera elevation in degrees [default: 22]
    #[arg(long, allow_hyphen_values = true)]
    pub pitch: Option<f32>,
    /// Camera distance from the model's centre [default: frames the model]
    #[arg(long, allow_hyphen_values = true)]
    pub distance: Option<f32>,
    /// Near plane distance [default: a thousandth of the camera distance]
    #[arg(long, allow_hyphen_values = true)]
    pub near: Option<f32>,
    /// Far plane distance, or inf [default: inf]
    #[arg(long, value_parser = parse_far)]
    pub far: Option<f32>,
    /// Scale the model by this factor (defaults scale with it)
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub scale: f32,
    /// Draw the model without its normal maps and alpha cutouts (in the truth too), to see what
    /// they bring
    #[arg(long)]
    pub no_surface_maps: bool,
}

/// The most point lights a run takes: every pixel loops over all of them (unshadowed), so beyond
/// this the light loop alone costs more than every other pass together, and the light buffer
/// (48 bytes a light) stays far inside any adapter's storage-buffer limit.
pub const MAX_LIGHTS: usize = 4096;

/// A whole number in `min..=max`, with the range in the message (the parser names the flag).
pub fn count_in(s: &str, min: u64, max: u64) -> std::result::Result<u64, String> {
    let bad = || format!("must be a whole number between {min} and {max}");
    let n: u64 = s.trim().parse().map_err(|_| bad())?;
    if (min..=max).contains(&n) {
        Ok(n)
    } else {
        Err(bad())
    }
}

/// A seed: any whole number from 0 to 2^64 - 1 (a negative one is refused by its flag).
pub fn parse_seed(s: &str) -> std::result::Result<u64, String> {
    count_in(s, 0, u64::MAX)
}

/// A whole number for a count whose range the setting checks once it is read: what is no
/// whole number at all (-1, 2.5, abc) is refused here, saying what is accepted.
pub fn whole_number(s: &str, (min, max): (usize, usize)) -> std::result::Result<usize, String> {
    s.trim().parse().map_err(|_| format!("must be a whole number between {min} and {max}"))
}

pub fn parse_lights(s: &str) -> std::result::Result<usize, String> {
    count_in(s, 0, MAX_LIGHTS as u64).map(|n| n as usize)
}

/// A point as X,Y,Z: three finite numbers within the largest length setting.
pub fn parse_point(s: &str) -> std::result::Result<glam::Vec3, String> {
    let bad = || format!("'{s}' is not a point X,Y,Z of three finite numbers (each within ±{MAX_LENGTH:e})");
    let parts: Vec<f32> =
        s.split(',').map(|p| p.trim().parse::<f32>()).collect::<std::result::Result<_, _>>().map_err(|_| bad())?;
    match parts[..] {
        [x, y, z] if parts.iter().all(|v| v.is_finite() && v.abs() <= MAX_LENGTH) => Ok(glam::Vec3::new(x, y, z)),
        _ => Err(bad()),
    }
}

pub fn parse_far(s: &str) -> std::result::Result<f32, String> {
    if s.eq_ignore_ascii_case("inf") {
        return Ok(f32::INFINITY);
    }
    s.parse::<f32>().map_err(|_| format!("'{s}' is not a number or inf"))
}

#[derive(Args)]
pub struct RenderArgs {
    /// Settings from a preset file (as `ssdo tune` writes): its knobs (variant, counts, radius, reach
    /// and thickness as multiples of the scene's, blur, resolution, accumulation, the bounce and its
    /// senders); flags given beside it override it
    #[arg(long, conflicts_with = "quality")]
    pub preset: Option<PathBuf>,
    /// A built-in quality level: low, medium, high (the default settings) or ultra, each tune's
    /// pick on the default scene at a multiple of the Off frame's time (docs/quality.md); flags
    /// given beside it override it
    #[arg(long)]
    pub quality: Option<crate::preset::Quality>,
    /// Algorithm family: march (the default), points (the paper's point sampling) or classic (the classic SSAO chapter and the SSDO course project)
    #[arg(long)]
    pub variant: Option<Variant>,
    /// Samples per pixel of the points and classic variants (the help states the range from
    /// `render::SAMPLES`)
    #[arg(long)]
    pub samples: Option<usize>,
    /// The march: slices per pixel (range: `render::SLICES`)
    #[arg(long)]
    pub slices: Option<usize>,
    /// The march: steps along each side of a slice (range: `render::STEPS`)
    #[arg(long)]
    pub steps: Option<usize>,
    /// The march's reach, in model units [default: 24 radii, or the preset's multiple of it]
    #[arg(long, allow_hyphen_values = true)]
    pub reach: Option<f32>,
    /// The march's surface thickness, in model units [default: 1 radius, or the preset's multiple of it]
    #[arg(long, allow_hyphen_values = true)]
    pub thickness: Option<f32>,
    /// Sampling radius in model units [default: a tenth of the scene's bounding radius]
    #[arg(long, allow_hyphen_values = true)]
    pub radius: Option<f32>,
    /// Depth bias of the occlusion test, as a fraction of the radius
    #[arg(long, default_value_t = DEFAULT_BIAS, allow_hyphen_values = true)]
    pub bias: f32,
    /// How much of the AO is applied (0 to 1)
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub ao_strength: f32,
    /// AO is raised to this power
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub ao_power: f32,
    /// Multiplier on SSDO's sky light
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub sky_strength: f32,
    /// Multiplier on SSDO's indirect bounce [default: 1]
    #[arg(long, allow_hyphen_values = true)]
    pub indirect_strength: Option<f32>,
    /// What lights the bounce's senders besides the point lights: last-frame (the sky each saw
    /// in the last frame's march), march (the sky each sender sees, from a half-resolution march
    /// of its own), march-quarter (the same march at quarter resolution), irradiance (the sky's
    /// unoccluded irradiance for its normal) or off (the point lights only); all but off add the
    /// ambient [default: last-frame]
    #[arg(long)]
    pub sender_sky: Option<SenderSky>,
    /// The switches (`--no-blur`, `--full-res`, `--depth-pyramid`, `--far-side`), declared by
    /// their knobs (`knobs::switches`)
    #[command(flatten)]
    pub switches: SwitchFlags,
    /// Frames averaged with the camera still (range: `render::ACCUMULATE`; 1: none): headless
    /// commands render this many frames of the still camera and keep the last
    #[arg(long)]
    pub accumulate: Option<usize>,
    /// Exposure applied before tone mapping
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub exposure: f32,
    /// Constant ambient radiance, on top of the sky [default: 0.1; classic 0.5]
    #[arg(long, allow_hyphen_values = true)]
    pub ambient: Option<f32>,
    /// Multiplier on the sky's radiance
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub sky_scale: f32,
    /// What to show: final, albedo, normals, depth, ao, do-direct, do-indirect, lighting, thickness
    #[arg(long, default_value = "final")]
    pub view: View,
}

pub use crate::knobs::MAX_GAIN;
/// The largest length setting (radius, reach, thickness), in model units.
pub const MAX_LENGTH: f32 = 1e9;

pub fn non_negative(name: &str, value: f32) -> Result<f32> {
    in_range(name, value, 0.0, MAX_LENGTH)
}

pub use crate::error::in_range;

/// A point as the command line takes it: X,Y,Z, each number as short as round-trips exactly.
pub fn point(p: glam::Vec3) -> String {
    format!("{},{},{}", p.x, p.y, p.z)
}

pub use crate::text::num;

impl SceneArgs {
    /// The model: the file (or the default scene) scaled and placed by the layout, or the room's
    /// built-in figure.
    pub fn load_model(&self) -> Result<scene::Model> {
        // Beyond these, positions lose the precision the depth buffer and the march need.
        in_range("scale", self.scale, 1e-6, 1e6)?;
        let mut model = self.layout.load(self.model.as_deref(), self.scale, self.triangles)?;
        if self.no_surface_maps {
            model.drop_surface_maps();
        }
        Ok(model)
    }

    /// The sky folder, or the scene's own (open's), or the default sky.
    pub fn load_sky(&self) -> Result<scene::Skybox> {
        match (&self.skybox, self.layout.sky()) {
            (None, Some(own)) => scene::Skybox::load(&own),
            (given, _) => scene::load_skybox(given.as_deref()),
        }
    }

    /// `model` with this run's lights.
    pub fn scene(&self, model: scene::Model) -> Scene {
        Scene::new(model, self.lights, self.seed)
    }

    /// The scene and its sky.
    pub fn load(&self) -> Result<(Scene, scene::Skybox)> {
        Ok((self.scene(self.load_model()?), self.load_sky()?))
    }

    pub fn camera(&self, scene: &Scene) -> Result<OrbitCamera> {
        let bounds = &scene.model.bounds;
        let r = bounds.radius().max(f32::MIN_POSITIVE);
        // A camera point far from the model leaves 32-bit view maths too few bits for it.
        let points = [("target", self.target), ("eye", self.eye), ("look-at", self.look_at)];
        for (flag, p) in points.into_iter().filter_map(|(flag, p)| Some((flag, p?))) {
            let reach = REACH_RADII * r;
            if (p - bounds.center()).length() > reach {
                return Err(Error::Setting(format!(
                    "--{flag} {}: must lie within {reach:.3e} of the model's centre {} ({REACH_RADII:e} of its bounding radius)",
                    point(p),
                    point(bounds.center())
                )));
            }
        }
        let mut camera = self.layout.camera(bounds);
        if let Some(target) = self.target {
            camera.target = target;
        }
        if let (Some(eye), Some(look_at)) = (self.eye, self.look_at) {
            camera = camera.looking(eye, look_at).ok_or_else(|| {
                Error::Setting(format!(
                    "--eye {} --look-at {}: the eye must be away from the point it looks at, and not straight above or below it",
                    point(eye),
                    point(look_at)
                ))
            })?;
            camera.near = camera.distance * 1e-3;
        }
        if let Some(yaw) = self.yaw {
            camera.yaw_deg = in_range("yaw", yaw, -36000.0, 36000.0)?;
        }
        if let Some(pitch) = self.pitch {
            // ±90 would look along the orbit's up axis, where the view has no defined roll.
            camera.pitch_deg = in_range("pitch", pitch, -89.0, 89.0)?;
        }
        if let Some(distance) = self.distance {
            // From inside the model out to where it is a speck, in the model's own size.
            let (lo, hi) = (DISTANCE_RADII.0 * r, DISTANCE_RADII.1 * r);
            if !(distance.is_finite() && (lo..=hi).contains(&distance)) {
                return Err(Error::Setting(format!(
                    "--distance {}: must be from {lo:.3e} to {hi:.3e} for this model ({:e} to {:e} of its bounding radius)",
                    num(distance),
                    DISTANCE_RADII.0,
                    DISTANCE_RADII.1
                )));
            }
            camera.distance = distance;
            camera.near = camera.near.min(distance * 1e-3);
        }
        if let Some(near) = self.near {
            // Reverse-Z keeps precision down to a tiny near plane, but not to a denormal one.
            let lo = camera.distance * 1e-9;
            if !(near.is_finite() && near >= lo) {
                return Err(Error::Setting(format!(
                    "--near {}: must be a finite number of at least {lo:.3e} (1e-9 of the camera distance)",
                    num(near)
                )));
            }
            camera.near = near;
        }
        if let Some(far) = self.far {
            if !(far > camera.near) {
                return Err(Error::Setting(format!("--far {far}: must be beyond the near plane ({})", camera.near)));
            }
            camera.far = far.is_finite().then_some(far);
        }
        Ok(camera)
    }
}

impl RenderArgs {
    /// The preset these flags name: `--preset FILE` or a `--quality` level.
    pub fn preset(&self) -> Result<Option<Preset>> {
        Preset::chosen(self.preset.as_deref(), self.quality)
    }

    /// The knobs: a preset's (or the defaults), with each flag given beside it taking its place.
    /// A variant other than the preset's brings its own sample count unless `--samples` is given.
    fn knobs(&self, preset: Option<&Preset>) -> Knobs {
        let from = preset.map(|p| p.knobs);
        let variant = self.variant.or(from.map(|k| k.variant)).unwrap_or_default();
        let mut k = match from {
            Some(k) if k.variant == variant => k,
            Some(k) => Knobs { variant, samples: variant.decl().default_samples, ..k },
            None => Knobs::for_variant(variant),
        };
        k.samples = self.samples.unwrap_or(k.samples);
        k.slices = self.slices.unwrap_or(k.slices);
        k.steps = self.steps.unwrap_or(k.steps);
        self.switches.apply(&mut k);
        k.accumulate = self.accumulate.unwrap_or(k.accumulate);
        k.sender_sky = self.sender_sky.unwrap_or(k.sender_sky);
        k.indirect_strength = self.indirect_strength.unwrap_or(k.indirect_strength);
        k
    }

    /// The settings of these flags over `preset` (see [`RenderArgs::preset`]), each checked
    /// against its range.
    pub fn settings_with(&self, mode: Mode, preset: Option<&Preset>) -> Result<Settings> {
        let k = self.knobs(preset);
        KNOBS.iter().try_for_each(|knob| knob.check_flag(&k))?;
        let base = Settings::for_variant(k.variant);
        let length = |name: &str, v: Option<f32>| v.map(|r| non_negative(name, r)).transpose();
        let mut s = Settings {
            mode,
            knobs: k,
            given: GivenLengths { bias: non_negative("bias", self.bias)?, ..base.given },
            ao_strength: in_range("ao-strength", self.ao_strength, 0.0, 1.0)?,
            ao_power: in_range("ao-power", self.ao_power, 0.0, 100.0)?,
            sky_strength: in_range("sky-strength", self.sky_strength, 0.0, MAX_GAIN)?,
            exposure: in_range("exposure", self.exposure, 0.0, MAX_GAIN)?,
            ambient: in_range("ambient", self.ambient.unwrap_or(base.ambient), 0.0, MAX_GAIN)?,
            sky_scale: in_range("sky-scale", self.sky_scale, 0.0, MAX_GAIN)?,
            view: self.view,
        };
        // Lengths given as flags win over the knobs' multiples of the scene's.
        s.given.radius = length("radius", self.radius)?;
        s.given.reach = length("reach", self.reach)?;
        s.given.thickness = length("thickness", self.thickness)?;
        Ok(s)
    }

    /// The settings of these flags (over their preset or quality level, if any).
    pub fn settings(&self, mode: Mode) -> Result<Settings> {
        self.settings_with(mode, self.preset()?.as_ref())
    }
}
