// What both sampling shaders (march.wgsl and points.wgsl) read beside the G-buffer: their
// parameters, the senders of the bounce, the sky, and which of AO and DO the mode computes.

@group(1) @binding(3) var<uniform> occ: SamplingParams;
// The senders: radiance and facing, packed (pack_sender in common/surface_pack.wgsl).
@group(1) @binding(4) var bounce_map: texture_2d<u32>;
#include "common/sky.wgsl"

// What the mode computes: AO, DO, or both (the composite and the tone mapper have the same two).
override HAS_AO: bool = true;
override HAS_DO: bool = true;
// The scene has point lights, so there is a bounce buffer to read.
override INDIRECT: bool = true;
