// HDR to display: exposure is applied by the caller; the ACES filmic curve (Narkowicz's fit) and
// the sRGB encoding for outputs whose format does not encode. Used by the tone-map pass and, when
// nothing reads HDR after it, by the composite and the light cubes drawing straight to the output.

fn aces(x: vec3<f32>) -> vec3<f32> {
    let y = max(x, vec3<f32>(0.0));
    return clamp((y * (2.51 * y + 0.03)) / (y * (2.43 * y + 0.59) + 0.14), vec3<f32>(0.0), vec3<f32>(1.0));
}

fn linear_to_srgb(c: vec3<f32>) -> vec3<f32> {
    let low = c * 12.92;
    let high = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(high, low, c <= vec3<f32>(0.0031308));
}

fn tone_map(radiance: vec3<f32>) -> vec3<f32> {
    // A huge value maps to white; the curve's rational form would give inf/inf = NaN.
    return select(aces(radiance), vec3<f32>(1.0), radiance > vec3<f32>(1e4));
}
