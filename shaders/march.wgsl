// The marched sampling pass's entry points (sampling.rs); the march itself, and the sums it
// takes over a pixel's hemisphere, are common/march.wgsl.

#include "common/march.wgsl"

// SSAO: AO alone, into a one-channel target.
@fragment
fn fs_ao(in: FullscreenOut) -> @location(0) vec4<f32> {
    return vec4<f32>(evaluate_pixel(in.position.xy).ao, 0.0, 0.0, 1.0);
}

// SSDO and SSAO+SSDO: DO in rgb; in a, AO (SSAO+SSDO) or, in SSDO, the open share: the constant
// ambient is a uniform sky, and SSDO sees it through the same open sectors as the sky.
fn do_value(o: Occlusion) -> vec4<f32> {
    return vec4<f32>(o.direct * occ.sky_strength + o.indirect * occ.indirect_strength, select(o.open, o.ao, HAS_AO));
}

@fragment
fn fs_do(in: FullscreenOut) -> @location(0) vec4<f32> {
    return stored_do(do_value(evaluate_pixel(in.position.xy)), surface_pixel(vec2<i32>(in.position.xy)));
}

struct DoAndSky {
    @location(0) occlusion: vec4<f32>,
    // `sender_value` of this pixel's surface, as `fs_sender` writes it: the next frame's lighting
    // pass reads it as the sky this surface sends in the bounce (`--sender-sky last-frame`).
    @location(1) sky: vec4<f32>,
}

// fs_do, and the sky this pixel sees for the next frame's senders: the same march's visible sky
// and open share (all its slices, where the sender-sky pass marches one).
@fragment
fn fs_do_senders(in: FullscreenOut) -> DoAndSky {
    let o = evaluate_pixel(in.position.xy);
    return DoAndSky(stored_do(do_value(o), surface_pixel(vec2<i32>(in.position.xy))), sender_value(o));
}
