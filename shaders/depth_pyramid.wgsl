// The depth pyramid for the march's far steps: mip k holds, for each 2^(k+1) × 2^(k+1) block of
// the depth buffer, the depth of the closest surface in it (reverse-Z: the largest value), as
// its bits in a u32 (integer targets render on every backend; positive floats order like their
// bits). A far step that reads a coarse level sees whatever lies in the pixels it skipped, so
// thin things between steps still occlude, and a GPU reads far fewer cache lines.
// An odd-sized level folds its last row and column into the texels beside them.

#include "common/fullscreen.wgsl"

// The full-resolution depth buffer (fs_first) or the level above (fs_next).
@group(0) @binding(0) var source_depth: texture_2d<f32>;
@group(0) @binding(1) var source_level: texture_2d<u32>;

// A source texel's depth bits: the depth buffer's (fs_first) or the level above's (fs_next).
fn depth_bits(texel: vec2<i32>, first: bool) -> u32 {
    if first {
        return bitcast<u32>(textureLoad(source_depth, texel, 0).r);
    }
    return textureLoad(source_level, texel, 0).r;
}

// The closest depth's bits among the source texels the destination texel at `position` folds:
// its 2x2 block, plus the extra row or column of an odd-sized source at the last row or column.
fn closest_in_block(position: vec2<f32>, first: bool) -> vec4<u32> {
    let pixel = vec2<i32>(position);
    let depth_size = vec2<i32>(textureDimensions(source_depth));
    let source = select(vec2<i32>(textureDimensions(source_level)), depth_size, first);
    let last = pixel == max(source / 2, vec2<i32>(1)) - vec2<i32>(1);
    let end = min(select(2 * pixel + 1, source - 1, last), source - 1);
    var closest = 0u;
    for (var y = 2 * pixel.y; y <= end.y; y += 1) {
        for (var x = 2 * pixel.x; x <= end.x; x += 1) {
            closest = max(closest, depth_bits(vec2<i32>(x, y), first));
        }
    }
    return vec4<u32>(closest, 0u, 0u, 1u);
}

@fragment
fn fs_first(in: FullscreenOut) -> @location(0) vec4<u32> {
    return closest_in_block(in.position.xy, true);
}

@fragment
fn fs_next(in: FullscreenOut) -> @location(0) vec4<u32> {
    return closest_in_block(in.position.xy, false);
}
