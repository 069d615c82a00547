//! Screen-sized textures. `Targets` owns them and is rebuilt as a whole on resize or when the
//! plan needs a different set; passes own pipelines and rebuild only their bind groups. A target
//! that the current plan does not read or write is not allocated at all.

pub const ALBEDO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// View-space normal and shininess packed in one u32 (`shaders/common/surface_pack.wgsl`).
pub const NORMAL_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
pub const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Log2 steps per unit of the packed shininess (`shaders/common/surface_pack.wgsl`).
const SHININESS_SCALE: f32 = 255.0 / 13.0;

/// The G-buffer's packed surface: the unit normal in two 12-bit octahedral coordinates and the
/// shininess in 8 log-encoded bits, exactly as `pack_surface` in `surface_pack.wgsl` writes it.
pub fn pack_surface(n: glam::Vec3, shininess: f32) -> u32 {
    let sign = |v: f32| if v >= 0.0 { 1.0 } else { -1.0 };
    let m = n / (n.x.abs() + n.y.abs() + n.z.abs()).max(1e-30);
    let (x, y) = if m.z < 0.0 { ((1.0 - m.y.abs()) * sign(m.x), (1.0 - m.x.abs()) * sign(m.y)) } else { (m.x, m.y) };
    let q = |e: f32| ((e * 0.5 + 0.5).clamp(0.0, 1.0) * 4095.0).round() as u32;
    let s = ((1.0 + shininess.max(0.0)).log2() * SHININESS_SCALE).clamp(0.0, 255.0).round() as u32;
    q(x) | (q(y) << 12) | (s << 24)
}

/// The normal and shininess of a packed surface (the inverse of [`pack_surface`]).
pub fn unpack_surface(bits: u32) -> (glam::Vec3, f32) {
    let e = |v: u32| (v & 0xfff) as f32 * (2.0 / 4095.0) - 1.0;
    let (x, y) = (e(bits), e(bits >> 12));
    let z = 1.0 - x.abs() - y.abs();
    let fold = (-z).max(0.0);
    let sign = |v: f32| if v >= 0.0 { 1.0 } else { -1.0 };
    let n = glam::Vec3::new(x - fold * sign(x), y - fold * sign(y), z).normalize();
    (n, ((bits >> 24) as f32 / SHININESS_SCALE).exp2() - 1.0)
}

/// One texture with its default view and its size in bytes.
pub struct Target {
    pub name: &'static str,
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
    pub bytes: u64,
}

impl Target {
    pub fn new(device: &wgpu::Device, name: &'static str, size: (u32, u32), format: wgpu::TextureFormat) -> Self {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(name),
            size: wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        Self { name, texture, view, bytes: texel_bytes(size, format) }
    }
}

/// The bytes of a `size` texture of `format`.
pub(crate) fn texel_bytes(size: (u32, u32), format: wgpu::TextureFormat) -> u64 {
    size.0 as u64 * size.1 as u64 * format.block_copy_size(None).unwrap_or(4) as u64
}

/// The depth pyramid: closest depth per block, as f32 bits (see `shaders/depth_pyramid.wgsl`).
pub const PYRAMID_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;
/// Levels of the pyramid at most: level k covers 2^(k+1) pixels, so 7 levels serve steps up
/// to 256 pixels apart.
pub const PYRAMID_LEVELS: u32 = 7;

/// The depth pyramid: half the screen at level 0, halving down to 1x1 or `PYRAMID_LEVELS`.
pub struct Pyramid {
    pub texture: wgpu::Texture,
    /// Every level, for the march.
    pub view: wgpu::TextureView,
    /// One view per level, for building it.
    pub levels: Vec<wgpu::TextureView>,
    pub bytes: u64,
}

impl Pyramid {
    /// Level 0's size and the number of levels for a screen of `size`.
    fn shape(size: (u32, u32)) -> ((u32, u32), u32) {
        let base = ((size.0 / 2).max(1), (size.1 / 2).max(1));
        (base, (32 - base.0.max(base.1).leading_zeros()).clamp(1, PYRAMID_LEVELS))
    }

    /// The bytes of a pyramid for a screen of `size`.
    fn bytes_for(size: (u32, u32)) -> u64 {
        let (base, count) = Self::shape(size);
        (0..count).map(|l| ((base.0 >> l).max(1) as u64) * ((base.1 >> l).max(1) as u64) * 4).sum()
    }

    fn new(device: &wgpu::Device, size: (u32, u32)) -> Self {
        let (base, count) = Self::shape(size);
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("depth_pyramid"),
            size: wgpu::Extent3d { width: base.0, height: base.1, depth_or_array_layers: 1 },
            mip_level_count: count,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: PYRAMID_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let levels = (0..count)
            .map(|level| {
                texture.create_view(&wgpu::TextureViewDescriptor {
                    base_mip_level: level,
                    mip_level_count: Some(1),
                    ..Default::default()
                })
            })
            .collect();
        Self { texture, view, levels, bytes: Self::bytes_for(size) }
    }
}

pub const AO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R16Float;
pub const DO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
pub const BOUNCE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Which screen targets a plan allocates besides the G-buffer (formats below).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TargetSet {
    /// Linear HDR radiance (`hdr_color`).
    pub hdr: bool,
    /// The diffuse radiance SSDO bounces (`bounce_radiance`): the senders' direct light.
    pub bounce: bool,
    /// AO alone (`ao_raw`): SSAO.
    pub ao: bool,
    /// DO + AO (`do_raw`): SSDO and SSAO+SSDO.
    pub directional: bool,
    /// A blurred copy of whichever of the two the plan has.
    pub blurred: bool,
    /// Its average over frames (`ao_accumulated` / `do_accumulated`), the temporal pass's output.
    pub accumulated: bool,
    /// The sampling pass's output at half resolution (`ao_half` / `do_half`), before the upsample.
    pub half: bool,
    /// The closest-depth pyramid of the march's far steps.
    pub pyramid: bool,
    /// The sky each sender sees, at half resolution (`sender_sky`).
    pub sender_sky: bool,
}

/// The view of an optional target.
pub fn view_of(target: &Option<Target>) -> Option<&wgpu::TextureView> {
    target.as_ref().map(|t| &t.view)
}

/// Half of `size`, rounded up: the sender-sky march's resolution (its pixel (x, y) is the
/// full-resolution pixel (2x, 2y)).
pub fn half_size(size: (u32, u32)) -> (u32, u32) {
    (size.0.div_ceil(2).max(1), size.1.div_ceil(2).max(1))
}

/// The view of an optional target, or `unused` where it does not exist.
pub fn view_or<'a>(target: &'a Option<Target>, unused: &'a wgpu::TextureView) -> &'a wgpu::TextureView {
    view_of(target).unwrap_or(unused)
}

/// Which output of the sampling chain a set of [`OcclusionTargets`] holds.
#[derive(Clone, Copy)]
enum Stage {
    Raw,
    Blurred,
    Accumulated,
    Half,
}

/// The sampling pass's outputs (raw, blurred or accumulated): whichever the plan computes.
pub struct OcclusionTargets {
    /// Ambient occlusion in [0, 1] (SSAO only).
    pub ao: Option<Target>,
    /// SSDO and SSAO+SSDO: rgb = sky light + indirect bounce (before albedo), a = AO.
    pub directional: Option<Target>,
}

impl OcclusionTargets {
    /// The pair named `ao_<stage>` and `do_<stage>`: `raw`, `blurred` or `accumulated`.
    fn new(device: &wgpu::Device, set: &TargetSet, size: (u32, u32), stage: Stage) -> Self {
        let (ao, directional) = match stage {
            Stage::Raw => ("ao_raw", "do_raw"),
            Stage::Blurred => ("ao_blurred", "do_blurred"),
            Stage::Accumulated => ("ao_accumulated", "do_accumulated"),
            Stage::Half => ("ao_half", "do_half"),
        };
        let size = if let Stage::Half = stage { half_size(size) } else { size };
        let make = |wanted: bool, name: &'static str, format| wanted.then(|| Target::new(device, name, size, format));
        Self { ao: make(set.ao, ao, AO_FORMAT), directional: make(set.directional, directional, DO_FORMAT) }
    }

    /// The one target the sampling pass (and the blur) writes.
    pub fn output(&self) -> Option<&Target> {
        self.ao.as_ref().or(self.directional.as_ref())
    }

    pub fn all(&self) -> impl Iterator<Item = &Target> {
        [&self.ao, &self.directional].into_iter().flatten()
    }
}

/// The G-buffer and the intermediate buffers of the current plan. A buffer the plan does not
/// use is `None`, not allocated.
pub struct Targets {
    pub size: (u32, u32),
    /// rgb albedo, a specular strength
    pub albedo: Target,
    /// View-space normal and shininess, packed (`pack_surface`)
    pub normal: Target,
    pub depth: Target,
    /// Linear HDR radiance before tone mapping (not in a display plan without a lighting pass).
    pub hdr: Option<Target>,
    /// The diffuse radiance of each surface under its direct light: SSDO's bounce source.
    pub bounce: Option<Target>,
    /// The sky each sender of the bounce sees (rgb, E/π before albedo) and its open share (a),
    /// at half resolution: the sender-sky march's output, read by the lighting pass.
    pub sender_sky: Option<Target>,
    /// What the sampling pass writes.
    pub raw: OcclusionTargets,
    /// What the blur writes (when the plan blurs).
    pub blurred: Option<OcclusionTargets>,
    /// What the temporal pass writes (when the plan accumulates).
    pub accumulated: Option<OcclusionTargets>,
    /// What a half-resolution sampling pass writes (the upsample then writes `raw`).
    pub half: Option<OcclusionTargets>,
    /// The closest-depth pyramid the march reads (when the plan builds one).
    pub pyramid: Option<Pyramid>,
}

impl Targets {
    /// Allocates the G-buffer and the targets of `set` (a plan's [`TargetSet`]).
    pub fn new(device: &wgpu::Device, size: (u32, u32), set: &TargetSet) -> Self {
        Self {
            size,
            albedo: Target::new(device, "gbuffer_albedo", size, ALBEDO_FORMAT),
            normal: Target::new(device, "gbuffer_normal", size, NORMAL_FORMAT),
            depth: Target::new(device, "gbuffer_depth", size, DEPTH_FORMAT),
            hdr: set.hdr.then(|| Target::new(device, "hdr_color", size, HDR_FORMAT)),
            bounce: set.bounce.then(|| Target::new(device, "bounce_radiance", size, BOUNCE_FORMAT)),
            sender_sky: set.sender_sky.then(|| Target::new(device, "sender_sky", half_size(size), DO_FORMAT)),
            raw: OcclusionTargets::new(device, set, size, Stage::Raw),
            blurred: set.blurred.then(|| OcclusionTargets::new(device, set, size, Stage::Blurred)),
            accumulated: set.accumulated.then(|| OcclusionTargets::new(device, set, size, Stage::Accumulated)),
            half: set.half.then(|| OcclusionTargets::new(device, set, size, Stage::Half)),
            pyramid: set.pyramid.then(|| Pyramid::new(device, size)),
        }
    }

    /// The bytes [`Targets::new`] allocates for `set` at `size`, known before anything is
    /// allocated (the memory budget is checked with it).
    pub fn bytes_for(size: (u32, u32), set: &TargetSet) -> u64 {
        let when = |wanted: bool, bytes: u64| if wanted { bytes } else { 0 };
        let occlusion =
            when(set.ao, texel_bytes(size, AO_FORMAT)) + when(set.directional, texel_bytes(size, DO_FORMAT));
        [ALBEDO_FORMAT, NORMAL_FORMAT, DEPTH_FORMAT].map(|f| texel_bytes(size, f)).iter().sum::<u64>()
            + when(set.hdr, texel_bytes(size, HDR_FORMAT))
            + when(set.bounce, texel_bytes(size, BOUNCE_FORMAT))
            + when(set.sender_sky, texel_bytes(half_size(size), DO_FORMAT))
            + occlusion * (1 + set.blurred as u64 + set.accumulated as u64)
            + when(set.half, {
                let half = half_size(size);
                when(set.ao, texel_bytes(half, AO_FORMAT)) + when(set.directional, texel_bytes(half, DO_FORMAT))
            })
            + when(set.pyramid, Pyramid::bytes_for(size))
    }

    /// The HDR target, where the plan keeps one (see `Renderer::keep_hdr`).
    pub fn hdr(&self) -> crate::Result<&Target> {
        self.hdr.as_ref().ok_or_else(|| {
            crate::Error::Gpu("this frame kept no HDR image: call Renderer::keep_hdr(true) before rendering".into())
        })
    }

    /// The AO/DO buffers the composite reads: accumulated when the plan accumulates, otherwise
    /// blurred when it blurs.
    pub fn occlusion(&self) -> &OcclusionTargets {
        self.accumulated.as_ref().or(self.blurred.as_ref()).unwrap_or(&self.raw)
    }

    /// What the temporal pass reads: the blurred output when the plan blurs, else the raw one.
    pub fn filtered(&self) -> &OcclusionTargets {
        self.blurred.as_ref().unwrap_or(&self.raw)
    }

    /// Every allocated target with its size in bytes.
    pub fn allocations(&self) -> Vec<(&'static str, u64)> {
        let fixed = [&self.albedo, &self.normal, &self.depth].into_iter();
        let optional = self
            .hdr
            .iter()
            .chain(self.bounce.iter())
            .chain(self.sender_sky.iter())
            .chain(self.raw.all())
            .chain(self.blurred.iter().flat_map(|b| b.all()))
            .chain(self.accumulated.iter().flat_map(|b| b.all()))
            .chain(self.half.iter().flat_map(|b| b.all()));
        let mut list: Vec<(&'static str, u64)> = fixed.chain(optional).map(|t| (t.name, t.bytes)).collect();
        if let Some(p) = &self.pyramid {
            list.push(("depth_pyramid", p.bytes));
        }
        list
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn packed_normals_come_back_within_seven_hundredths_of_a_degree() {
        let mut worst = 0.0f32;
        // A spiral over the whole sphere, plus the axes and the octahedron's folds.
        let mut normals: Vec<Vec3> = (0..20_000)
            .map(|i| {
                let z = 1.0 - 2.0 * (i as f32 + 0.5) / 20_000.0;
                let phi = i as f32 * 2.399_963;
                let r = (1.0 - z * z).sqrt();
                Vec3::new(r * phi.cos(), r * phi.sin(), z)
            })
            .collect();
        normals.extend([Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z, Vec3::new(1.0, 1.0, 0.0).normalize()]);
        for n in normals {
            let (back, _) = unpack_surface(pack_surface(n, 32.0));
            worst = worst.max(n.dot(back).clamp(-1.0, 1.0).acos().to_degrees());
        }
        assert!(worst < 0.07, "worst angle {worst}°");
    }

    #[test]
    fn packed_shininess_keeps_four_percent() {
        for s in [0.0f32, 1.0, 8.0, 32.0, 100.0, 1000.0, 8000.0] {
            let (_, back) = unpack_surface(pack_surface(Vec3::Z, s));
            assert!((back - s).abs() <= 0.04 * s + 0.03, "{s} came back as {back}");
        }
    }
}
