// One triangle that covers the screen, at depth 0 (the reverse-Z far plane, where the skybox
// lives): vertex `index`'s uv, (0,0) at the top-left of the target, and its clip position.
// Each full-screen shader's vertex stage `fullscreen_vs` places it: common/fullscreen.wgsl's, or
// common/frame_varyings.wgsl's, which also hands the frame's constants down.

fn fullscreen_uv(index: u32) -> vec2<f32> {
    return vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
}

fn fullscreen_clip(uv: vec2<f32>) -> vec4<f32> {
    return vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
}
