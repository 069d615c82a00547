//! Screen-sized textures. Each is a [`TargetId`] (name, format, size), declared once; `Targets`
//! owns the ones the current plan's steps write and is rebuilt as a whole on resize or when the
//! plan needs a different set; passes own pipelines and rebuild only their bind groups. A target
//! that the current plan does not write is not allocated at all.

pub const ALBEDO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// View-space normal and shininess packed in one u32 (`shaders/common/surface_pack.wgsl`).
pub const NORMAL_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
pub const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Where a target lives, and so how large it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Place {
    /// A screen texture of the screen's size.
    Screen,
    /// A screen texture of half the screen's size, rounded up ([`half_size`]).
    HalfScreen,
    /// A screen texture of a quarter of the screen's width and height, rounded up
    /// ([`quarter_size`]).
    QuarterScreen,
    /// The closest-depth pyramid: half the screen at level 0, halving down (see [`Target`]).
    Pyramid,
    /// A texture that outlives the frame (`history.rs`): read as the last frame left it.
    History,
    /// What the frame is drawn into (the window or the capture); not allocated here.
    Output,
}

/// A texture a pass reads or writes, declared once: by the pass that writes it
/// (`passes/<pass>.rs`), or below for the G-buffer and the targets several passes share. Two
/// ids are the same target when their names are.
#[derive(Clone, Copy, Debug)]
pub struct TargetId {
    pub name: &'static str,
    pub format: wgpu::TextureFormat,
    pub place: Place,
}

impl PartialEq for TargetId {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl Eq for TargetId {}

impl std::hash::Hash for TargetId {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.name.hash(state);
    }
}

impl AsRef<str> for TargetId {
    fn as_ref(&self) -> &str {
        self.name
    }
}

impl TargetId {
    pub const fn new(name: &'static str, format: wgpu::TextureFormat, place: Place) -> Self {
        Self { name, format, place }
    }

    pub fn name(self) -> &'static str {
        self.name
    }

    /// Whether the target is a history: it outlives the frame, and a step may read it before any
    /// step of this frame writes it.
    pub fn persistent(self) -> bool {
        self.place == Place::History
    }

    /// Whether the target is one of the G-buffer's three, which every plan has.
    pub fn in_gbuffer(self) -> bool {
        [ALBEDO, NORMAL, DEPTH].contains(&self)
    }

    /// Whether [`Targets`] allocates it (the histories and the output live elsewhere).
    pub fn allocated(self) -> bool {
        matches!(self.place, Place::Screen | Place::HalfScreen | Place::QuarterScreen | Place::Pyramid)
    }

    /// The bytes it takes for a screen of `size`.
    pub fn bytes(self, size: (u32, u32)) -> u64 {
        match self.place {
            Place::Screen => texel_bytes(size, self.format),
            Place::HalfScreen => texel_bytes(half_size(size), self.format),
            Place::QuarterScreen => texel_bytes(quarter_size(size), self.format),
            Place::Pyramid => {
                let (base, count) = pyramid_shape(size);
                (0..count).map(|l| texel_bytes(((base.0 >> l).max(1), (base.1 >> l).max(1)), self.format)).sum()
            }
            Place::History | Place::Output => 0,
        }
    }
}

pub const AO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R16Float;
pub const DO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// The G-buffer: rgb albedo and a specular strength; the view-space normal and shininess,
/// packed (`surface_pack::pack_surface`); depth (reverse-Z). Every plan has them.
pub const ALBEDO: TargetId = TargetId::new("gbuffer_albedo", ALBEDO_FORMAT, Place::Screen);
pub const NORMAL: TargetId = TargetId::new("gbuffer_normal", NORMAL_FORMAT, Place::Screen);
pub const DEPTH: TargetId = TargetId::new("gbuffer_depth", DEPTH_FORMAT, Place::Screen);
/// The thickness layer: each pixel's depth bits with, in their low 6 bits, its material's
/// thickness code (`scene/thickness.rs`; the depth moves by at most 2^-17 of itself). Written by
/// the G-buffer pass where the plan has it (a thin material in the scene), read by the marches
/// in place of the depth, and by the thickness view.
pub const THICKNESS: TargetId = TargetId::new("gbuffer_thickness", THICKNESS_FORMAT, Place::Screen);
pub const THICKNESS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;
/// Linear HDR radiance before tone mapping: written by the lighting pass, the composite, the
/// skybox and the light cubes, read by the tone map.
pub const HDR: TargetId = TargetId::new("hdr_color", HDR_FORMAT, Place::Screen);
/// The diffuse radiance of each surface under its direct light, SSDO's bounce source, and which
/// way the surface faces: written by the lighting pass, read by the sampling pass. Three halves
/// and a 16-bit normal code in two u32s (`pack_sender` in shaders/common/surface_pack.wgsl), so
/// the march's gather reads a sender in one 8-byte load instead of two.
pub const BOUNCE: TargetId = TargetId::new("bounce_radiance", BOUNCE_FORMAT, Place::Screen);
pub const BOUNCE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rg32Uint;
/// [`BOUNCE`] with, in its second pair, the sender the far side layer holds behind each pixel
/// (`--far-side`; none: zero), lit the same way: a march step reads both in one 16-byte load.
pub const BOUNCE_WITH_FAR: TargetId =
    TargetId::new("bounce_radiance_with_far", wgpu::TextureFormat::Rgba32Uint, Place::Screen);

/// The bounce's senders' target: with the far side layer's beside them where `far_side`.
pub fn bounce_target(far_side: bool) -> TargetId {
    if far_side {
        BOUNCE_WITH_FAR
    } else {
        BOUNCE
    }
}
/// What the frame is drawn into.
pub const OUTPUT: TargetId = TargetId::new("output", ALBEDO_FORMAT, Place::Output);

/// A stage of the sampling chain. Each has two targets, one for AO alone (SSAO) and one for DO +
/// AO (SSDO and SSAO+SSDO: rgb sky light and bounce before albedo, a AO): what the sampling pass
/// (or the upsample) writes, what a half-resolution sampling pass writes and its blurred copy,
/// the blurred copy at full resolution (the blur's, or the upsample's of the half-size one) and
/// the average over frames (at half size where the samples are: the composite upsamples it as
/// it reads; the full-size copy is the upsample's, made only where something else reads it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    Raw,
    Half,
    /// The half-size samples blurred where they were taken (half-resolution plans that blur).
    HalfBlurred,
    Blurred,
    Accumulated,
    /// The average over frames where the samples are (half-resolution plans that accumulate).
    HalfAccumulated,
}

impl Stage {
    /// The last stage of a chain: the average over frames where it accumulates, else the
    /// samples blurred where it blurs, else as they were taken; at half size (`half`) or full.
    pub fn last(accumulated: bool, blurred: bool, half: bool) -> Stage {
        match (accumulated, blurred, half) {
            (true, _, true) => Stage::HalfAccumulated,
            (true, _, false) => Stage::Accumulated,
            (false, true, true) => Stage::HalfBlurred,
            (false, true, false) => Stage::Blurred,
            (false, false, true) => Stage::Half,
            (false, false, false) => Stage::Raw,
        }
    }

    /// The stage's target for a mode that computes DO (`directional`) or AO alone.
    pub const fn target(self, directional: bool) -> TargetId {
        let (ao, directional_name, place) = match self {
            Stage::Raw => ("ao_raw", "do_raw", Place::Screen),
            Stage::Half => ("ao_half", "do_half", Place::HalfScreen),
            Stage::HalfBlurred => ("ao_half_blurred", "do_half_blurred", Place::HalfScreen),
            Stage::Blurred => ("ao_blurred", "do_blurred", Place::Screen),
            Stage::Accumulated => ("ao_accumulated", "do_accumulated", Place::Screen),
            Stage::HalfAccumulated => ("ao_half_accumulated", "do_half_accumulated", Place::HalfScreen),
        };
        if directional {
            TargetId::new(directional_name, DO_FORMAT, place)
        } else {
            TargetId::new(ao, AO_FORMAT, place)
        }
    }

    /// Both of the stage's targets: AO alone's and DO + AO's.
    pub const fn targets(self) -> [TargetId; 2] {
        [self.target(false), self.target(true)]
    }
}

/// One texture with its default view, its mip levels' views where it has several (the pyramid),
/// and its size in bytes.
pub struct Target {
    pub name: &'static str,
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
    /// One view per mip level (the pyramid's, for building it); empty for one level.
    pub levels: Vec<wgpu::TextureView>,
    pub bytes: u64,
}

impl Target {
    pub fn new(device: &wgpu::Device, name: &'static str, size: (u32, u32), format: wgpu::TextureFormat) -> Self {
        Self::with_levels(device, name, size, format, None)
    }

    /// A target of `levels` mips with a view of each (`None`: one level, no level views, and
    /// readable back).
    fn with_levels(
        device: &wgpu::Device,
        name: &'static str,
        size: (u32, u32),
        format: wgpu::TextureFormat,
        mips: Option<u32>,
    ) -> Self {
        let copy = if mips.is_none() { wgpu::TextureUsages::COPY_SRC } else { wgpu::TextureUsages::empty() };
        let levels = mips.unwrap_or(1);
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(name),
            size: wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: 1 },
            mip_level_count: levels,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING | copy,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let levels = if mips.is_none() {
            Vec::new()
        } else {
            (0..levels)
                .map(|level| {
                    texture.create_view(&wgpu::TextureViewDescriptor {
                        base_mip_level: level,
                        mip_level_count: Some(1),
                        ..Default::default()
                    })
                })
                .collect()
        };
        let bytes = (0..texture.mip_level_count())
            .map(|l| texel_bytes(((size.0 >> l).max(1), (size.1 >> l).max(1)), format))
            .sum();
        Self { name, texture, view, levels, bytes }
    }

    /// The target `id` for a screen of `size`.
    fn of(device: &wgpu::Device, id: TargetId, size: (u32, u32)) -> Self {
        match id.place {
            Place::HalfScreen => Self::new(device, id.name, half_size(size), id.format),
            Place::QuarterScreen => Self::new(device, id.name, quarter_size(size), id.format),
            Place::Pyramid => {
                let (base, count) = pyramid_shape(size);
                Self::with_levels(device, id.name, base, id.format, Some(count))
            }
            _ => Self::new(device, id.name, size, id.format),
        }
    }
}

/// The bytes of a `size` texture of `format`.
pub(crate) fn texel_bytes(size: (u32, u32), format: wgpu::TextureFormat) -> u64 {
    size.0 as u64 * size.1 as u64 * format.block_copy_size(None).unwrap_or(4) as u64
}

/// Levels of the depth pyramid at most: level k covers 2^(k+1) pixels, so 7 levels serve steps
/// up to 256 pixels apart.
pub const PYRAMID_LEVELS: u32 = 7;

/// The pyramid's level 0 size and number of levels for a screen of `size`: half the screen,
/// halving down to 1x1 or [`PYRAMID_LEVELS`].
fn pyramid_shape(size: (u32, u32)) -> ((u32, u32), u32) {
    let base = ((size.0 / 2).max(1), (size.1 / 2).max(1));
    (base, (32 - base.0.max(base.1).leading_zeros()).clamp(1, PYRAMID_LEVELS))
}

/// Half of `size`, rounded up: the half-resolution passes' size (their pixel (x, y) is the
/// full-resolution pixel (2x, 2y)).
pub fn half_size(size: (u32, u32)) -> (u32, u32) {
    (size.0.div_ceil(2).max(1), size.1.div_ceil(2).max(1))
}

/// A quarter of `size`'s width and height, rounded up: the quarter-resolution sender sky's size
/// (its pixel (x, y) is the full-resolution pixel (4x + 1, 4y + 1), about its 4x4 block's middle).
pub fn quarter_size(size: (u32, u32)) -> (u32, u32) {
    (size.0.div_ceil(4).max(1), size.1.div_ceil(4).max(1))
}

/// A stage of the sampling chain as it exists in a plan: AO alone, or DO + AO, or neither.
#[derive(Clone, Copy)]
pub struct OcclusionTargets<'a> {
    /// Ambient occlusion in [0, 1] (SSAO only).
    pub ao: Option<&'a Target>,
    /// SSDO and SSAO+SSDO: rgb = sky light + indirect bounce (before albedo), a = AO.
    pub directional: Option<&'a Target>,
}

impl<'a> OcclusionTargets<'a> {
    /// The one target of the stage.
    pub fn output(&self) -> Option<&'a Target> {
        self.ao.or(self.directional)
    }
}

/// The screen targets of the current plan: the G-buffer and exactly the targets its steps
/// write (`Plan::targets`). A target the plan does not write is not allocated at all.
pub struct Targets {
    pub size: (u32, u32),
    list: Vec<(TargetId, Target)>,
}

impl Targets {
    /// Allocates `ids` (a plan's targets, the G-buffer among them) for a screen of `size`.
    pub fn new(device: &wgpu::Device, size: (u32, u32), ids: &[TargetId]) -> Self {
        let list = ids.iter().filter(|id| id.allocated()).map(|&id| (id, Target::of(device, id, size))).collect();
        Self { size, list }
    }

    /// The bytes [`Targets::new`] allocates for `ids` at `size`, known before anything is
    /// allocated (the memory budget is checked with it).
    pub fn bytes_for(size: (u32, u32), ids: &[TargetId]) -> u64 {
        ids.iter().filter(|id| id.allocated()).map(|id| id.bytes(size)).sum()
    }

    /// The target `id`, where the plan has it.
    pub fn get(&self, id: TargetId) -> Option<&Target> {
        self.list.iter().find(|(i, _)| *i == id).map(|(_, t)| t)
    }

    /// The target `id`, which the plan must have (a pass asks for what it declared).
    pub fn expect(&self, id: TargetId) -> &Target {
        self.get(id).unwrap_or_else(|| panic!("the plan has no target {}", id.name))
    }

    pub fn albedo(&self) -> &Target {
        self.expect(ALBEDO)
    }

    pub fn normal(&self) -> &Target {
        self.expect(NORMAL)
    }

    pub fn depth(&self) -> &Target {
        self.expect(DEPTH)
    }

    /// The HDR target, where the plan keeps one (see `Renderer::keep_hdr`).
    pub fn hdr(&self) -> crate::Result<&Target> {
        self.get(HDR).ok_or_else(|| {
            crate::Error::Gpu("this frame kept no HDR image: call Renderer::keep_hdr(true) before rendering".into())
        })
    }

    /// A stage of the sampling chain, as the plan has it.
    pub fn stage(&self, stage: Stage) -> OcclusionTargets<'_> {
        OcclusionTargets { ao: self.get(stage.target(false)), directional: self.get(stage.target(true)) }
    }

    /// What the sampling pass (or the upsample) writes.
    pub fn raw(&self) -> OcclusionTargets<'_> {
        self.stage(Stage::Raw)
    }

    /// The AO/DO buffers the composite reads: accumulated when the plan accumulates, otherwise
    /// blurred when it blurs, else raw.
    pub fn occlusion(&self) -> OcclusionTargets<'_> {
        [Stage::Accumulated, Stage::Blurred, Stage::Raw]
            .map(|s| self.stage(s))
            .into_iter()
            .find(|t| t.output().is_some())
            .unwrap_or(OcclusionTargets { ao: None, directional: None })
    }

    /// Every allocated target with its size in bytes.
    pub fn allocations(&self) -> Vec<(&'static str, u64)> {
        self.list.iter().map(|(_, t)| (t.name, t.bytes)).collect()
    }
}
