// The core's Lambert shading model: f = k_d/π, L_o = f·E·max(0, n·l).
vec3 sl_model_lambert(SlSurface s, vec3 l, vec3 E) {
    return s.base_color * SL_INV_PI * E * max(0.0, dot(s.normal, l));
}

// Uniform ambient irradiance E_a (π × constant environment radiance) → outgoing radiance.
vec3 sl_model_lambert_ambient(SlSurface s, vec3 E_ambient) {
    return s.base_color * SL_INV_PI * E_ambient * s.ao;
}

// Its lobes (ABI 1.14): the diffuse albedo alone.
SlLobes sl_model_lambert_lobes(SlSurface s) {
    SlLobes L = sl_lobes_none();
    L.diffuse = s.base_color;
    return L;
}
