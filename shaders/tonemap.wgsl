// HDR to display: exposure, the ACES filmic curve (Narkowicz's fit), then sRGB. When the target
// format is an sRGB format the hardware encodes; otherwise the shader does.

#include "common/uniforms.wgsl"
#include "common/fullscreen.wgsl"

@group(1) @binding(0) var hdr: texture_2d<f32>;

// True when the output format does the sRGB encoding itself.
override OUTPUT_SRGB: bool = true;

fn aces(x: vec3<f32>) -> vec3<f32> {
    let y = max(x, vec3<f32>(0.0));
    return clamp((y * (2.51 * y + 0.03)) / (y * (2.43 * y + 0.59) + 0.14), vec3<f32>(0.0), vec3<f32>(1.0));
}

fn linear_to_srgb(c: vec3<f32>) -> vec3<f32> {
    let low = c * 12.92;
    let high = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(high, low, c <= vec3<f32>(0.0031308));
}

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4<f32> {
    let radiance = textureLoad(hdr, vec2<i32>(in.position.xy), 0).rgb * frame.camera.z;
    // A huge value maps to white; the curve's rational form would give inf/inf = NaN.
    var mapped = select(aces(radiance), vec3<f32>(1.0), radiance > vec3<f32>(1e4));
    if !OUTPUT_SRGB {
        mapped = linear_to_srgb(mapped);
    }
    return vec4<f32>(mapped, 1.0);
}
