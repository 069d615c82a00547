//! CPU ray-traced ground truth: one physical image for every mode. The same triangles, camera and
//! pixels as the GPU, with exact visibility at any distance.
//!
//! For each pixel the primary ray finds the visible surface (checked against the GPU's depth; a
//! pixel where the two disagree, on a silhouette, is left out). From it, `spp` cosine-distributed
//! rays (pdf cos/π, so a mean over rays is E/π) each answer, at once:
//!
//! * **Sky light**: the ray hits nothing at all and brings the sky's radiance in its direction
//!   (the same cube map).
//! * **One bounce**: the ray hits a surface, at any distance, which sends its diffuse radiance
//!   under its own *direct* light: the point lights (unshadowed, as on the GPU), the sky it sees
//!   with its own visibility, and the constant ambient A with its own openness. The sender's sky
//!   and openness come from one cosine-distributed ray of its own per hit (an unbiased estimate of
//!   its E/π, noisier than the receiver's). The sender's own bounce is left out: one bounce, on
//!   both sides.
//! * **Openness**: the share of rays that escape, which occludes the constant ambient (a uniform
//!   environment of radiance A).
//!
//! The truth at a pixel is ρ·(sky + bounce + A·openness) + direct point light, the same for every
//! mode and variant.
//!
//! **Surfaces as the G-buffer draws them.** The cosines at receivers and senders are the shading
//! normal's: the interpolated vertex normal, or the normal map's in the tangent frame (nearest
//! texel), turned with its frame to the side the ray arrives from. The hemisphere a surface
//! gathers from is cut at its triangle's own plane: rays are drawn cosine-distributed about the
//! shading normal, and those below the plane are drawn again, so the weights are normalised over
//! what remains and an open surface under a constant sky gets exactly albedo × sky whatever its
//! normal map (the GPU does the same, with the plane from the depth buffer). A ray's hit on a
//! cut-out texel (coverage below the material's cutoff, read at the hit's texture coordinate) is
//! a miss, as the G-buffer discards that texel: the truth sees through the same holes. Beside it, **within-R diagnostics** with the sampling radius R: occluders
//! and senders beyond R ignored (AO = 1 − share of rays hitting within R; sky where no hit within
//! R; bounce from hits within R, the senders lit as above). The gap between a mode's error against
//! the truth and against the within-R image is what its reach costs.
//!
//! Deterministic: each pixel draws from a generator seeded by the seed and the pixel index, and
//! pixels run in parallel. The report traces twice with independent seeds, for the truth (their
//! mean, [`Reference::mean`]) and its noise floor (their difference).

mod image;
mod layers;
mod place;
mod scene;
mod shares;

pub use image::*;
pub use place::*;
pub use scene::*;
