// The G-buffer's normal target packs a surface into one u32 (R32Uint, 4 bytes a pixel instead of
// the 8 of a half-float vec4):
//   bits  0-11  octahedral x of the unit view-space normal, 12-bit unorm over [-1, 1]
//   bits 12-23  octahedral y
//   bits 24-31  Blinn-Phong shininess s as round(log2(1 + s) · SHININESS_SCALE)
// The octahedral map spreads the 2^24 codes evenly over the sphere: the angle between a normal
// and its decoded value is below 0.06°. Shininess keeps about 3.6% relative precision up to 8191
// (log2 steps of 1/19.6), well under what a specular highlight's width shows.
// `src/render/targets.rs` holds the same code for reading the target back.

const SHININESS_SCALE: f32 = 19.615385; // 255 / log2(8192)

fn sign_not_zero(v: vec2<f32>) -> vec2<f32> {
    return select(vec2<f32>(-1.0), vec2<f32>(1.0), v >= vec2<f32>(0.0));
}

// The normal's 24 bits; the shininess's 8 (bits 24-31) are a material's, packed once on the CPU
// (`MaterialParams::shininess_bits`, src/render/targets.rs `shininess_bits`).
fn pack_normal(n: vec3<f32>) -> u32 {
    let m = n / max(abs(n.x) + abs(n.y) + abs(n.z), 1e-30);
    var e = m.xy;
    if m.z < 0.0 {
        e = (1.0 - abs(m.yx)) * sign_not_zero(m.xy);
    }
    let q = vec2<u32>(round(clamp(e * 0.5 + 0.5, vec2<f32>(0.0), vec2<f32>(1.0)) * 4095.0));
    return q.x | (q.y << 12u);
}

fn unpack_normal(bits: u32) -> vec3<f32> {
    let e = vec2<f32>(f32(bits & 0xfffu), f32((bits >> 12u) & 0xfffu)) * (2.0 / 4095.0) - 1.0;
    var n = vec3<f32>(e, 1.0 - abs(e.x) - abs(e.y));
    let fold = max(-n.z, 0.0);
    n = vec3<f32>(n.xy - fold * sign_not_zero(n.xy), n.z);
    return normalize(n);
}

// A sender of SSDO's bounce, as the lighting pass writes it and the sampling pass's gather reads
// it (the `bounce_radiance` target, Rg32Uint): its diffuse radiance as three halves, and in the
// top 16 bits its normal's octahedral code at 8 bits an axis (the G-buffer's 12-bit code, cut) —
// enough to tell which way it faces. One 8-byte load brings both: reading the radiance and the
// G-buffer normal separately was a quarter of the march's time on a CPU rasteriser.
fn pack_sender(radiance: vec3<f32>, normal_bits: u32) -> vec2<u32> {
    let code = ((normal_bits >> 4u) & 0xffu) | (((normal_bits >> 16u) & 0xffu) << 8u);
    let blue = pack2x16float(vec2<f32>(radiance.b, 0.0)) & 0xffffu;
    return vec2<u32>(pack2x16float(radiance.rg), blue | (code << 16u));
}

fn sender_radiance(texel: vec2<u32>) -> vec3<f32> {
    return vec3<f32>(unpack2x16float(texel.x), unpack2x16float(texel.y & 0xffffu).x);
}

// The sender's normal, not normalised: its direction is all a facing test needs.
fn sender_normal(texel: vec2<u32>) -> vec3<f32> {
    let code = texel.y >> 16u;
    // The centre of the 16 12-bit codes an 8-bit code stands for, over [-1, 1].
    let e = (vec2<f32>(f32(code & 0xffu), f32(code >> 8u)) + 0.5) * (32.0 / 4095.0) - 1.0;
    let n = vec3<f32>(e, 1.0 - abs(e.x) - abs(e.y));
    let fold = max(-n.z, 0.0);
    return vec3<f32>(n.xy - fold * sign_not_zero(n.xy), n.z);
}

// The packed normal's two octahedral coordinates, in codes (0-4095).
fn octahedral_code(bits: u32) -> vec2<f32> {
    return vec2<f32>(vec2<u32>(bits & 0xfffu, (bits >> 12u) & 0xfffu));
}

// The L1 distance between two normals' octahedral codes, in octahedral units: about the angle
// in radians between two normals that face the camera. What the blur and the upsample weigh
// normal agreement by, instead of decoding every neighbour's normal (decoding was a third of
// the blur's time and a quarter of the upsample's on a CPU rasteriser).
fn octahedral_distance(a: vec2<f32>, b: vec2<f32>) -> f32 {
    let e = abs(a - b) * (1.0 / 2047.5);
    return e.x + e.y;
}

fn unpack_shininess(bits: u32) -> f32 {
    return exp2(f32(bits >> 24u) / SHININESS_SCALE) - 1.0;
}
