//! The `ssdo capture …` command that renders a given view: the viewer shows it and puts it on the
//! clipboard, so a view found by hand becomes a figure or a bug report. Every number is written
//! as the shortest text that reads back to the same float, so the command reproduces the camera
//! exactly; settings at their defaults are left out.

use std::path::Path;

use crate::render::{Settings, Variant, View, SAMPLES, SLICES, STEPS};
use crate::scene::{Layout, OrbitCamera};
use crate::spec::point;

/// Everything the command states.
pub struct ViewDescription<'a> {
    pub model: Option<&'a Path>,
    pub skybox: Option<&'a Path>,
    pub layout: Layout,
    pub triangles: Option<usize>,
    pub scale: f32,
    /// `--no-surface-maps` was given (for the first model).
    pub no_surface_maps: bool,
    pub lights: usize,
    pub seed: u64,
    pub camera: &'a OrbitCamera,
    /// Say the camera as the fly camera does (`--eye`, `--look-at`) rather than as an orbit.
    pub fly: bool,
    pub settings: &'a Settings,
    /// The 3D view's size in pixels.
    pub size: (u32, u32),
    /// The truth is on, with this many rays a pixel in each of its traces: `--truth --spp N`.
    pub truth_rays: Option<u32>,
}

/// The arguments after `ssdo`, one string each.
pub fn capture_arguments(view: &ViewDescription) -> Vec<String> {
    let mut args: Vec<String> = vec!["capture".into()];
    let mut flag = |name: &str, value: String| args.extend([format!("--{name}"), value]);
    if view.layout != Layout::Model {
        flag("scene", view.layout.name().into());
    }
    if let Some(triangles) = view.triangles {
        flag("triangles", triangles.to_string());
    }
    if let Some(model) = view.model {
        flag("model", model.display().to_string());
    }
    if let Some(sky) = view.skybox {
        flag("skybox", sky.display().to_string());
    }
    if view.scale != 1.0 {
        flag("scale", view.scale.to_string());
    }
    flag("lights", view.lights.to_string());
    flag("seed", view.seed.to_string());
    let camera = view.camera;
    if view.fly {
        flag("eye", point(camera.eye()));
        flag("look-at", point(camera.target));
    } else {
        flag("target", point(camera.target));
        flag("yaw", camera.yaw_deg.to_string());
        flag("pitch", camera.pitch_deg.to_string());
        flag("distance", camera.distance.to_string());
    }
    flag("near", camera.near.to_string());
    if let Some(far) = camera.far {
        flag("far", far.to_string());
    }
    settings_flags(view.settings, &mut flag);
    flag("size", format!("{}x{}", view.size.0, view.size.1));
    if let Some(rays) = view.truth_rays {
        // capture --truth takes at least 2 rays a trace.
        flag("spp", rays.max(2).to_string());
    }
    if view.no_surface_maps {
        args.push("--no-surface-maps".into());
    }
    // The switches turned from their defaults, each by its flag.
    let turned = crate::knobs::switches().filter(|k| k.is_on(&view.settings.knobs) != k.default_switch());
    args.extend(turned.map(|k| format!("--{}", k.flag)));
    if view.truth_rays.is_some() {
        args.push("--truth".into());
    }
    args
}

/// The valued flags of the settings that differ from the defaults of their variant.
fn settings_flags(s: &Settings, flag: &mut impl FnMut(&str, String)) {
    let base = Settings::for_variant(s.knobs.variant);
    flag("mode", s.mode.name().into());
    if s.knobs.variant != Variant::default() {
        flag("variant", s.knobs.variant.name().into());
    }
    for count in [SAMPLES, SLICES, STEPS] {
        if s.knobs.count(count.id) != base.knobs.count(count.id) {
            flag(count.flag, s.knobs.count(count.id).to_string());
        }
    }
    let lengths = [("reach", s.given.reach), ("thickness", s.given.thickness), ("radius", s.given.radius)];
    for (name, value) in lengths {
        if let Some(v) = value {
            flag(name, v.to_string());
        }
    }
    let numbers = [
        ("bias", s.given.bias, base.given.bias),
        ("ao-strength", s.ao_strength, base.ao_strength),
        ("ao-power", s.ao_power, base.ao_power),
        ("sky-strength", s.sky_strength, base.sky_strength),
        ("indirect-strength", s.knobs.indirect_strength, base.knobs.indirect_strength),
        ("exposure", s.exposure, base.exposure),
        ("ambient", s.ambient, base.ambient),
        ("sky-scale", s.sky_scale, base.sky_scale),
    ];
    for (name, value, default) in numbers {
        if value != default {
            flag(name, value.to_string());
        }
    }
    if s.knobs.sender_sky != base.knobs.sender_sky {
        flag("sender-sky", s.knobs.sender_sky.name().into());
    }
    if s.knobs.accumulate != base.knobs.accumulate {
        flag("accumulate", s.knobs.accumulate.to_string());
    }
    if s.view != View::Final {
        flag("view", s.view.name().into());
    }
}

/// The command as one line a shell reads back to the same arguments.
pub fn shell_line(arguments: &[String]) -> String {
    let quoted = arguments.iter().map(|a| {
        if !a.is_empty() && a.chars().all(|c| c.is_ascii_alphanumeric() || "-_./,=:+@%".contains(c)) {
            a.clone()
        } else {
            format!("'{}'", a.replace('\'', r"'\''"))
        }
    });
    std::iter::once("ssdo".to_string()).chain(quoted).collect::<Vec<_>>().join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::Mode;
    use crate::scene::Bounds;
    use glam::Vec3;

    fn description<'a>(camera: &'a OrbitCamera, settings: &'a Settings, fly: bool) -> ViewDescription<'a> {
        ViewDescription {
            model: Some(Path::new("my models/it's.glb")),
            skybox: None,
            layout: Layout::Model,
            triangles: None,
            scale: 1.0,
            no_surface_maps: false,
            lights: 3,
            seed: 9,
            camera,
            fly,
            settings,
            size: (320, 240),
            truth_rays: None,
        }
    }

    #[test]
    fn the_command_states_the_camera_and_what_differs_from_the_defaults() {
        let mut camera = OrbitCamera::framing(&Bounds { min: Vec3::splat(-1.0), max: Vec3::ONE });
        camera.target = Vec3::new(0.1, -0.2, 1.0 / 3.0);
        let mut settings = Settings { mode: Mode::Ssdo, exposure: 1.5, ..Settings::default() };
        settings.knobs.blur = false;
        let line = shell_line(&capture_arguments(&description(&camera, &settings, false)));
        assert!(line.starts_with("ssdo capture --model 'my models/it'\\''s.glb' --lights 3 --seed 9"), "{line}");
        assert!(line.contains(&format!("--target 0.1,-0.2,{}", 1.0f32 / 3.0)), "{line}");
        assert!(
            line.contains("--mode ssdo")
                && line.contains("--exposure 1.5")
                && line.ends_with("--size 320x240 --no-blur")
        );
        assert!(!line.contains("--slices") && !line.contains("--ambient") && !line.contains("--full-res"), "{line}");
        let fly = shell_line(&capture_arguments(&description(&camera, &settings, true)));
        assert!(fly.contains("--eye ") && fly.contains("--look-at ") && !fly.contains("--yaw"), "{fly}");
    }
}
