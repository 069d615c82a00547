//! Render modes, and what a frame of one is: the modes' table ([`MODES`]), the facts a plan is
//! made from ([`PlanFacts`]: the mode's declaration, the scene, the options) and the plan itself
//! ([`Plan`]: the steps in order, and what follows from them). Which steps a plan has is each
//! pass's own rule, beside its code (`passes/<pass>.rs`); `passes/mod.rs` lists the passes in
//! frame order and builds the plan from their rules (`Plan::new`). What each step reads and
//! writes is the pass's declaration too, and the plan's targets are the ones its steps write:
//! nothing a mode or a scene does not need is in the plan, and so nothing for it is allocated or
//! run. `--print-plan` prints both.
//!
//! | mode | steps (the defaults: lights, half resolution, blur, accumulation, display plan) | targets besides the G-buffer and histories |
//! |---|---|---|
//! | Off | gbuffer, composite, light_cubes | — |
//! | SSAO | gbuffer, ssao, temporal, composite, light_cubes | `ao_half`, `ao_half_accumulated` |
//! | SSDO | gbuffer, sender_sky, lighting, ssdo, temporal, composite, light_cubes | `hdr_color`, `bounce_radiance`, `sender_sky`, `do_half`, `do_half_accumulated` |
//! | SSAO+SSDO | gbuffer, sender_sky, lighting, ssao_ssdo, temporal, composite, light_cubes | as SSDO (AO travels in the DO target's alpha) |
//!
//! The sampling pass and the temporal pass run at half size, over the samples, and the temporal
//! pass blurs them as it reads them ([`PlanFacts::temporal_blurs`]); the composite upsamples the
//! average as it reads it, so no full-screen pass lies between the samples and the composite.
//!
//! By default (`--sender-sky last-frame`) the march of the sampling pass writes the sky each
//! pixel sees into a history the next frame's lighting pass reads, and the sender-sky step runs
//! only on a frame with no last frame; `--sender-sky march` runs it every frame.
//!
//! Without lights there are no light cubes and the lighting pass writes the bounce alone (the
//! senders' sky and ambient light; no HDR target in a display plan); `--sender-sky march-quarter`
//! marches the senders' sky into `sender_sky_quarter` instead; with `--sender-sky off` and
//! no lights, or with `--indirect-strength 0`, there is no lighting pass and no bounce target at
//! all (the composite then runs the light loop). An HDR plan (the report, `--raw`, `--stats`, a
//! debug view) adds `hdr_color`, the skybox and the tone map, and after a half-size chain the
//! upsample pass with the full-size copy of its last stage (`ao_accumulated` / `do_accumulated`),
//! which the debug views and the report read; the classic variant (a box blur) keeps a blur pass
//! and its half-size target (`ao_half_blurred` / `do_half_blurred`); `--accumulate 1` drops the
//! temporal pass, its target and its two histories, and blurs in a pass of its own (the
//! composite then upsamples `ao_half_blurred` / `do_half_blurred`; an HDR plan's copy is
//! `ao_blurred` / `do_blurred`); `--full-res` the half-size targets (the blur then reads `ao_raw`
//! / `do_raw` and writes `ao_blurred` / `do_blurred`, the temporal pass `ao_accumulated` /
//! `do_accumulated`); the march with `--depth-pyramid` adds the pyramid in the DO modes.

pub mod table;

pub use table::{Mode, ModeDecl, MODES};

use super::history::HistorySpec;
use super::senders::SenderSky;
use super::settings::{Settings, View};
use super::targets::{half_size, Place, Stage, TargetId, DO_FORMAT};
use super::uniforms::{UNIFORM_LIGHTS, UNROLLED_LIGHTS};
use super::variant::Blur;

/// What the scene brings that changes the plan.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SceneFeatures {
    pub lights: usize,
    /// A material has a normal map: the G-buffer's normals are not the surfaces' own, and the
    /// sampling passes take the geometry's from the depth (see `shaders/common/march.wgsl`).
    pub normal_mapped: bool,
    /// A material is thinner than the scene's default thickness (`scene/thickness.rs`): the
    /// march can take each depth sample's thickness from the G-buffer's thickness layer.
    pub thin_materials: bool,
    /// The model is smooth-shaded somewhere (`Model::has_smooth_normals`): its normals turn
    /// from pixel to pixel, as a normal map's do.
    pub smooth_normals: bool,
}

impl SceneFeatures {
    /// A scene with `lights` point lights, flat-shaded, no normal maps and no thin materials.
    pub fn lit(lights: usize) -> Self {
        Self { lights, normal_mapped: false, thin_materials: false, smooth_normals: false }
    }
}

/// The settings that shape a plan besides the mode, by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlanOptions {
    /// Denoise the sampling output.
    pub blur: bool,
    /// The blur is the bilateral tent (every variant's but the classic one's box): the temporal
    /// pass can run it as it reads the samples (see [`PlanFacts::temporal_blurs`]).
    pub bilateral: bool,
    /// The sampling pass marches the depth buffer and its far steps, taken only where DO is
    /// computed, read a depth pyramid (the march variant with `depth_pyramid` on).
    pub pyramid: bool,
    /// See [`Plan::display`].
    pub display: bool,
    /// SSDO's one bounce is on (its strength is above 0).
    pub indirect: bool,
    /// What lights the bounce's senders besides the point lights (`Settings::sender_sky`).
    pub sender_sky: SenderSky,
    /// The sampling pass runs at half resolution, and the chain after it.
    pub half_resolution: bool,
    /// The sampling output is averaged over frames (`Settings::accumulates`): a temporal pass
    /// and its history.
    pub accumulate: bool,
    /// Each depth sample may take its material's thickness (the march variant, no `--thickness`
    /// given, and a mode that samples or the thickness view): the G-buffer writes the thickness
    /// layer where the scene has a thin material.
    pub material_thickness: bool,
    /// The far side layer: the nearest surfaces turned away from the eye, lit, for the bounce.
    pub far_side: bool,
    /// ... and its surfaces' sky from a march of their own (`--far-sky`).
    pub far_sky: bool,
}

impl PlanOptions {
    /// The options `settings` give: a display plan (no HDR after the frame) unless HDR is kept
    /// (`keep_hdr`) or a debug view needs the tone-map pass.
    pub fn of(settings: &Settings, keep_hdr: bool) -> Self {
        let variant = settings.knobs.variant;
        Self {
            blur: settings.knobs.blur,
            bilateral: variant.decl().blur == Blur::Bilateral,
            pyramid: settings.knobs.reads_pyramid(),
            display: !keep_hdr && settings.view == View::Final,
            indirect: settings.knobs.indirect_strength > 0.0,
            sender_sky: settings.knobs.sender_sky.for_variant(variant),
            accumulate: settings.accumulates(),
            half_resolution: settings.knobs.half_resolution,
            material_thickness: settings.material_thickness()
                && (settings.mode.declaration().runs_sampling() || settings.view == View::Thickness),
            far_side: settings.knobs.far_side,
            far_sky: settings.knobs.far_sky,
        }
    }
}

impl Default for PlanOptions {
    /// The default settings' plan in a mode that samples: a display plan with half-resolution
    /// sampling, blur and accumulation, no pyramid, and the bounce lit by the sky and the lights.
    fn default() -> Self {
        Self::of(&Settings { mode: Mode::Ssdo, ..Settings::default() }, false)
    }
}

/// What a plan is made from; each pass's rule for whether it runs reads these.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlanFacts {
    pub decl: ModeDecl,
    pub features: SceneFeatures,
    pub options: PlanOptions,
}

impl PlanFacts {
    /// Whether there are point lights.
    pub fn lights(&self) -> bool {
        self.features.lights > 0
    }

    /// Whether the mode bounces light (a DO mode with its bounce on).
    pub fn bounces(&self) -> bool {
        self.decl.directional_occlusion && self.options.indirect
    }

    /// What lights the bounce's senders besides the point lights; `Off` where nothing bounces.
    pub fn sender_sky(&self) -> SenderSky {
        if self.bounces() {
            self.options.sender_sky
        } else {
            SenderSky::Off
        }
    }

    /// Whether the mode samples at all (every mode but Off).
    pub fn samples(&self) -> bool {
        self.decl.runs_sampling()
    }

    /// Whether the mode samples at half resolution.
    pub fn half_resolution(&self) -> bool {
        self.samples() && self.options.half_resolution
    }

    /// Whether the temporal pass blurs the samples as it reads them, and no blur pass runs: the
    /// bilateral tent at half resolution covers the 3x3 texels whose range a moving view's
    /// history is clamped to, so one pass reads them once (a moving view's blur and temporal
    /// pass 14.7 → 11.6 ms, docs/performance.md). The classic box and a full-resolution blur
    /// (a 4x4 window) keep their pass.
    pub fn temporal_blurs(&self) -> bool {
        let o = &self.options;
        self.half_resolution() && o.blur && o.bilateral && o.accumulate
    }
}

/// One step of a frame: a pass, by name. Each pass declares its step beside its code
/// (`Step::BLUR` in `passes/blur.rs`), with its rule and its reads and writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Step {
    name: &'static str,
    /// The step is named after what the mode computes (the sampling pass: `ssao`, `ssdo`...).
    named_by_mode: bool,
}

impl Step {
    pub const fn new(name: &'static str) -> Self {
        Self { name, named_by_mode: false }
    }

    /// A step that takes the name of what the mode computes (`ModeDecl::sampling_step`).
    pub const fn named_by_mode(name: &'static str) -> Self {
        Self { name, named_by_mode: true }
    }

    /// The step's name in a plan of `mode`.
    pub fn name_in(self, mode: Mode) -> &'static str {
        if self.named_by_mode {
            mode.declaration().sampling_step
        } else {
            self.name
        }
    }

    pub fn name(self) -> &'static str {
        self.name
    }
}

/// The steps of one frame for a mode and a scene (built by `Plan::new` in `passes/mod.rs`), and
/// what follows from them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plan {
    pub mode: Mode,
    pub decl: ModeDecl,
    pub features: SceneFeatures,
    /// The sampling output is blurred: by the blur pass, or by the temporal pass as it reads it
    /// ([`Plan::temporal_blurs`]).
    pub blur: bool,
    /// The temporal pass blurs the samples ([`PlanFacts::temporal_blurs`]): no blur pass.
    pub temporal_blurs: bool,
    /// Nothing reads HDR after the frame (the final image is shown or saved as it is): the
    /// G-buffer pass draws the displayed sky behind the geometry, the composite tone-maps
    /// straight into the output, and there is no skybox or tone-map pass, and no HDR target
    /// unless a lighting pass writes its direct light there.
    pub display: bool,
    /// What lights the bounce's senders besides the point lights; `Off` wherever the plan has no
    /// bounce.
    pub sender_sky: SenderSky,
    /// The sampling pass runs at half resolution, and so do the blur and the temporal pass after
    /// it: the composite upsamples as it reads (the upsample pass makes a full-size copy only
    /// where something else reads one).
    pub half_resolution: bool,
    /// The sampling output is averaged over frames (a temporal pass and its histories).
    pub accumulates: bool,
    /// A lighting pass writes each surface's direct light (the bounce's source).
    pub lighting: bool,
    /// The march's far steps read a depth pyramid, which a step builds.
    pub pyramid: bool,
    /// The senders' sky comes from their own march, which a step runs.
    pub sender_march: bool,
    /// The G-buffer writes the thickness layer (depth with each surface's thickness code), which
    /// the marches and the thickness view read: a thin material, and the options allow it.
    pub thickness_layer: bool,
    /// A pass draws the far side layer (the surfaces turned from the eye, lit as senders), which
    /// the march's bounce reads.
    pub far_side: bool,
    /// With the far side, and no thickness given: the lighting pass writes the depth with each
    /// surface's extent behind it (to the far side's face there), which the march reads in place
    /// of the thickness layer.
    pub extent_layer: bool,
    pub steps: Vec<Step>,
    /// The targets kept across frames (see `history.rs`): the temporal pass's, where it runs.
    pub history: Vec<HistorySpec>,
}

impl Plan {
    /// Whether the plan averages the sampling output over frames.
    pub fn accumulates(&self) -> bool {
        self.accumulates
    }

    /// The sampling chain's last stage at half size (`half`: where the samples are, in a
    /// half-resolution plan) or at full size (the upsample's copy, or the samples themselves).
    pub fn chain_end(&self, half: bool) -> Stage {
        Stage::last(self.accumulates, self.blur, half)
    }

    /// The stage of the chain, where the samples are (at half size in a half-resolution plan),
    /// that holds them averaged over frames (`accumulated`), else blurred (`blurred`), else as
    /// they were taken.
    pub fn sampled(&self, accumulated: bool, blurred: bool) -> Stage {
        Stage::last(accumulated, blurred, self.half_resolution)
    }

    /// The size of the histories' textures for a screen of `screen`: where the samples are.
    pub fn history_size(&self, screen: (u32, u32)) -> (u32, u32) {
        if self.half_resolution {
            half_size(screen)
        } else {
            screen
        }
    }

    /// The names of the steps, in order.
    pub fn step_names(&self) -> Vec<&'static str> {
        self.steps.iter().map(|s| s.name_in(self.mode)).collect()
    }

    /// Whether the HDR target exists: an HDR plan, or a lighting pass writing its direct light.
    pub fn keeps_hdr(&self) -> bool {
        !self.display || self.lighting_writes_direct()
    }

    /// Whether the lighting pass writes the point lights' displayed light (it runs and there are
    /// lights), which the composite then adds instead of running the light loop.
    pub fn lighting_writes_direct(&self) -> bool {
        self.lighting && self.features.lights > 0
    }

    /// The target the lighting pass writes the bounce's senders into: with the far side
    /// layer's beside them where the plan draws it.
    pub fn bounce_target(&self) -> TargetId {
        super::targets::bounce_target(self.far_side)
    }

    pub fn has(&self, step: Step) -> bool {
        self.steps.contains(&step)
    }

    /// Whether the sampling chain holds its DO over the sky's unoccluded irradiance at each
    /// sample's normal, which the upsample multiplies by that at each pixel's own
    /// (`DO_OVER_IRRADIANCE` in `shaders/common/upsample.wgsl`): under a normal map or smooth
    /// shading the normal turns between pixels that share half-size samples. A flat-shaded
    /// scene's normals turn only at edges, where the upsample takes no sample across.
    pub fn do_over_irradiance(&self) -> bool {
        let turning = self.features.normal_mapped || self.features.smooth_normals;
        self.half_resolution && self.decl.directional_occlusion && turning
    }

    /// Whether the composite runs the point-light loop itself (lights, but no lighting pass).
    pub fn light_loop(&self) -> bool {
        self.features.lights > 0 && !self.lighting
    }

    /// The light count a pipeline's light loop is built for: the scene's, where it has at most
    /// [`UNROLLED_LIGHTS`] (the shader compiler unrolls a loop of known length), else 0, and the
    /// loop reads the frame's count.
    pub fn unrolled_lights(&self) -> u32 {
        match self.features.lights {
            n @ 1..=UNROLLED_LIGHTS => n as u32,
            _ => 0,
        }
    }

    /// Whether the light loops read the frame uniforms' copy of the lights (the scene has at
    /// most [`UNIFORM_LIGHTS`]) rather than the storage array.
    pub fn uniform_lights(&self) -> bool {
        self.features.lights <= UNIFORM_LIGHTS
    }

    /// How every pipeline with a light loop (the composite's, the lighting pass's) reads the
    /// lights.
    pub fn light_reads(&self) -> LightReads {
        LightReads { count: self.unrolled_lights(), uniform: self.uniform_lights() }
    }
}

/// How a pipeline's point-light loop (`common/point_lights.wgsl`) reads the lights: part of the
/// key of each pass that runs one, and the override constants it is built with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightReads {
    /// The count the loop is built for ([`Plan::unrolled_lights`]), or 0: the frame's count.
    pub count: u32,
    /// From the frame uniforms' copy ([`Plan::uniform_lights`]), not the storage array.
    pub uniform: bool,
}

impl LightReads {
    /// `LIGHT_COUNT` and `UNIFORM_LIGHT_READS`.
    pub fn constants(self) -> [(&'static str, f64); 2] {
        [("LIGHT_COUNT", f64::from(self.count)), ("UNIFORM_LIGHT_READS", f64::from(u8::from(self.uniform)))]
    }
}

/// The temporal pass's history of the averaged AO or DO + AO (in the sampling output's
/// format; a float texture for binding).
pub const OCCLUSION_HISTORY: TargetId = TargetId::new("history_occlusion", DO_FORMAT, Place::History);
/// The temporal pass's history of each pixel's surface: its depth (f32 bits), and its world
/// normal (two 12-bit octahedral codes) with the frames it holds (8 bits).
pub const SURFACE_HISTORY: TargetId = TargetId::new("history_surface", SURFACE_HISTORY_FORMAT, Place::History);
pub const SURFACE_HISTORY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rg32Uint;
