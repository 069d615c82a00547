//! The G-buffer's packed surface on the CPU, exactly as the shaders pack and unpack it
//! (`shaders/common/surface_pack.wgsl`): the tests read the normal target back through it, and
//! the G-buffer pass packs each material's shininess once.

/// Log2 steps per unit of the packed shininess (`shaders/common/surface_pack.wgsl`).
const SHININESS_SCALE: f32 = 255.0 / 13.0;

/// The G-buffer's packed surface: the unit normal in two 12-bit octahedral coordinates and the
/// shininess in 8 log-encoded bits, exactly as the G-buffer pass writes it (`pack_normal` in
/// `surface_pack.wgsl`, ORed with the material's [`shininess_bits`]).
pub fn pack_surface(n: glam::Vec3, shininess: f32) -> u32 {
    pack_normal(n) | shininess_bits(shininess)
}

/// The packed surface's normal bits (0-23), as `pack_normal` in `surface_pack.wgsl` writes them.
pub fn pack_normal(n: glam::Vec3) -> u32 {
    let sign = |v: f32| if v >= 0.0 { 1.0 } else { -1.0 };
    let m = n / (n.x.abs() + n.y.abs() + n.z.abs()).max(1e-30);
    let (x, y) = if m.z < 0.0 { ((1.0 - m.y.abs()) * sign(m.x), (1.0 - m.x.abs()) * sign(m.y)) } else { (m.x, m.y) };
    let q = |e: f32| ((e * 0.5 + 0.5).clamp(0.0, 1.0) * 4095.0).round() as u32;
    q(x) | (q(y) << 12)
}

/// The packed surface's shininess bits (24-31): a material's, computed once for its draws (the
/// G-buffer pass ORs them onto the normal's).
pub fn shininess_bits(shininess: f32) -> u32 {
    let s = ((1.0 + shininess.max(0.0)).log2() * SHININESS_SCALE).clamp(0.0, 255.0).round() as u32;
    s << 24
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
