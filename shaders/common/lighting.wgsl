// Direct lighting by the point lights: Lambert diffuse plus normalised Blinn-Phong specular,
// inverse-square falloff with the distance clamped from below (a light on a surface stays
// finite). Returns outgoing radiance towards the camera at view-space `p`.

fn point_lighting(p: vec3<f32>, n: vec3<f32>, albedo: vec3<f32>, specular: f32, shininess: f32) -> vec3<f32> {
    let to_eye = safe_normalize(-p, vec3<f32>(0.0, 0.0, 1.0));
    let min_d2 = frame.camera.w;
    let spec_norm = (shininess + 8.0) / (8.0 * PI);
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < frame.counts.x; i += 1u) {
        let light = lights[i];
        let to_light = light.view_position.xyz - p;
        let d2 = dot(to_light, to_light);
        let l = safe_normalize(to_light, n);
        let n_dot_l = max(dot(n, l), 0.0);
        let irradiance = light.color.rgb * (light.world_position.w / max(d2, min_d2)) * n_dot_l;
        let h = safe_normalize(l + to_eye, n);
        let highlight = specular * spec_norm * pow(max(dot(n, h), 0.0), shininess);
        sum += irradiance * (albedo / PI + vec3<f32>(highlight));
    }
    return sum;
}
