//! Sample kernels and per-pixel rotations for the occlusion pass.
//!
//! Default: N directions spread evenly over the hemisphere by solid angle (a Fibonacci spiral in
//! cos θ and azimuth, so every N covers it without clumps), at distances spread evenly over
//! [0.1 R, R] (a low-discrepancy sequence). A point at distance t along a direction tests whether
//! that direction is blocked within t; the classic kernel puts most points within 0.3 R and so
//! misses occluders that a ray of length R (what AO of radius R means) would hit. The 16
//! rotations of a 4x4 tile are evenly spaced angles in Bayer order, so a 4x4 blur
//! window averages all of them. Deterministic: the same N gives the same kernel.
//!
//! Classic: the classic SSAO chapter's kernel (LearnOpenGL, "SSAO") — random points in the hemisphere's half cube,
//! normalised, scaled by a random length and by lerp(0.1, 1, (i/N)²) — and 16 random rotation
//! vectors in the tangent plane, from a fixed seed.

use glam::Vec3;
use rand::{rngs::StdRng, RngExt, SeedableRng};

pub use super::variant::Kernel;

/// The smallest cos θ of a default-kernel direction: directions within 3° of the tangent plane
/// only pick up the surface's own depth error (they carry 0.3% of the cosine weight).
const MIN_COS: f32 = 0.05;

fn lerp(a: f32, b: f32, t: f32) -> f32 {
    a + (b - a) * t
}

/// Radical inverse in base 3: a low-discrepancy sequence independent of the spiral's.
fn radical_inverse_3(mut i: u32) -> f32 {
    let (mut inv, mut f) = (0.0f32, 1.0 / 3.0);
    while i > 0 {
        inv += f * (i % 3) as f32;
        i /= 3;
        f /= 3.0;
    }
    inv
}

/// `n` tangent-space offsets for a unit radius.
pub fn kernel(kind: Kernel, n: usize) -> Vec<Vec3> {
    match kind {
        Kernel::Stratified => {
            let golden = std::f32::consts::PI * (3.0 - 5.0f32.sqrt());
            (0..n)
                .map(|i| {
                    let cos = lerp(1.0, MIN_COS, (i as f32 + 0.5) / n as f32);
                    let sin = (1.0 - cos * cos).max(0.0).sqrt();
                    let phi = golden * i as f32;
                    let length = lerp(0.1, 1.0, radical_inverse_3(i as u32 + 1));
                    Vec3::new(sin * phi.cos(), sin * phi.sin(), cos) * length
                })
                .collect()
        }
        Kernel::Classic => {
            let mut rng = StdRng::seed_from_u64(0x55A0);
            (0..n)
                .map(|i| {
                    let mut r = || rng.random::<f32>();
                    let v = Vec3::new(r() * 2.0 - 1.0, r() * 2.0 - 1.0, r());
                    let v = v.try_normalize().unwrap_or(Vec3::Z) * r();
                    let t = i as f32 / n as f32;
                    v * lerp(0.1, 1.0, t * t)
                })
                .collect()
        }
    }
}

/// The 16 entries of the 4x4 rotation tile, row by row.
pub fn rotations(kind: Kernel) -> [[f32; 4]; 16] {
    const BAYER: [u32; 16] = [0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5];
    let mut out = [[0.0; 4]; 16];
    match kind {
        Kernel::Stratified => {
            // xy: the points' rotation; z: the march's slice offset; w: its step offset (another
            // order of the same 16 values, so slices and steps do not jitter together).
            for (entry, b) in out.iter_mut().zip(BAYER) {
                let angle = std::f32::consts::TAU * (b as f32 + 0.5) / 16.0;
                let step = ((b * 7 + 3) % 16) as f32;
                *entry = [angle.cos(), angle.sin(), (b as f32 + 0.5) / 16.0, (step + 0.5) / 16.0];
            }
        }
        Kernel::Classic => {
            let mut rng = StdRng::seed_from_u64(0x4015E);
            for entry in &mut out {
                *entry = [rng.random::<f32>() * 2.0 - 1.0, rng.random::<f32>() * 2.0 - 1.0, 0.0, 0.0];
            }
        }
    }
    out
}

/// The additive recurrences of the sample schedule: steps whose multiples leave no gap wider than
/// 2/N among the first N (both have continued fractions of small terms): the golden ratio for
/// the march's slice offset and the points' rotation, √2 − 1 for the march's step offset.
const GOLDEN: f64 = 0.618_033_988_749_894_8;
const SILVER: f64 = std::f64::consts::SQRT_2 - 1.0;

/// The sample schedule of frame `index` of an accumulation (0 on its first frame): what every
/// pixel adds to its tile entry, xy to the march's slice and step offsets (mod 1) and zw the
/// (cos, sin) the points' rotation is turned by. Frame 0 adds nothing, so a frame that does not
/// accumulate samples exactly as before. The offsets are additive recurrences: each pixel's
/// offsets over N frames are N well-spread values of [0, 1) (a Weyl sequence), and so are the
/// 16 entries of a tile over N frames seen through the blur's 4x4 window, since an irrational
/// step never falls back onto the tile's sixteenths.
pub fn schedule(index: u32) -> [f32; 4] {
    let k = index as f64;
    let offset = |alpha: f64| (k * alpha).fract() as f32;
    let angle = std::f64::consts::TAU * (k * GOLDEN).fract();
    [offset(GOLDEN), offset(SILVER), angle.cos() as f32, angle.sin() as f32]
}

/// Mip level of a cube map of face size `size` whose texels cover the solid angle one of `n`
/// hemisphere samples stands for (2π/n); a texel at a face centre covers about (2/size)².
pub fn sky_mip_level(size: u32, n: usize) -> f32 {
    let per_sample = std::f32::consts::TAU / n.max(1) as f32;
    let texel = 4.0 / (size.max(1) as f32).powi(2);
    (0.5 * (per_sample / texel).log2()).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kernels_lie_in_the_unit_hemisphere_and_are_the_same_every_time() {
        for kind in [Kernel::Stratified, Kernel::Classic] {
            for n in [1, 16, 64, 256] {
                let k = kernel(kind, n);
                assert_eq!(k.len(), n);
                assert!(k.iter().all(|v| v.z >= 0.0 && v.length() <= 1.0 + 1e-6), "{kind:?} {n}");
                assert_eq!(k, kernel(kind, n), "{kind:?} {n}: deterministic");
            }
        }
        // The default kernel spreads its directions: their mean points up, not to one side.
        let mean = kernel(Kernel::Stratified, 64).iter().map(|v| v.normalize()).sum::<Vec3>() / 64.0;
        assert!(mean.x.abs() < 0.05 && mean.y.abs() < 0.05 && mean.z > 0.4, "{mean}");
    }

    #[test]
    fn rotations_are_unit_angles_and_slice_offsets_cover_the_tile() {
        let r = rotations(Kernel::Stratified);
        assert!(r.iter().all(|e| ((e[0] * e[0] + e[1] * e[1]) - 1.0).abs() < 1e-5));
        let mut offsets: Vec<f32> = r.iter().map(|e| e[2]).collect();
        offsets.sort_by(f32::total_cmp);
        for (i, o) in offsets.iter().enumerate() {
            assert!((o - (i as f32 + 0.5) / 16.0).abs() < 1e-6, "all 16 slice offsets once");
        }
    }

    #[test]
    fn the_schedule_adds_nothing_on_the_first_frame_and_spreads_every_later_one() {
        assert_eq!(schedule(0), [0.0, 0.0, 1.0, 0.0]);
        for frames in [4u32, 16, 64] {
            for dim in 0..2 {
                // N offsets of one pixel: no gap wider than 2/N, so N frames of one slice cover
                // the half circle about as evenly as N slices.
                let mut v: Vec<f32> = (0..frames).map(|k| schedule(k)[dim]).collect();
                v.sort_by(f32::total_cmp);
                v.push(v[0] + 1.0);
                let widest = v.windows(2).map(|w| w[1] - w[0]).fold(0.0, f32::max);
                assert!(widest < 2.0 / frames as f32, "dim {dim}, {frames} frames: gap {widest}");
            }
        }
        assert!((0..64).all(|k| {
            let s = schedule(k);
            (s[2] * s[2] + s[3] * s[3] - 1.0).abs() < 1e-5
        }));
    }

    #[test]
    fn more_samples_read_finer_sky_mips() {
        let levels: Vec<f32> = [1, 4, 16, 64, 256].iter().map(|&n| sky_mip_level(512, n)).collect();
        assert!(levels.windows(2).all(|w| w[1] <= w[0]), "{levels:?}");
        assert_eq!(sky_mip_level(1, 16), 0.0, "never below level 0");
    }
}
