// toon: a cel-shading model (sdk/example/toon), written against the public SDK only.
// For one light from l with irradiance E at normal incidence, where n·l > 0:
//   f(s, l, E) = E/π ⊙ [ base · q(n·l)                          N flat bands of the Lambert term
//                      + rim_color       · [n·v < rim]           a rim on the lit side
//                      + highlight_color · [n·h ≥ highlight] ]   a hard highlight
//   q(t) = ceil(t·N)/N (N = toon_bands): 1/N for the first sliver of light, 1 where t > (N−1)/N.
// 0 where n·l ≤ 0. Its lobes ask integrators not to integrate it (an environment or an area
// light would blur the bands): SL_LOBES_MODEL_AT_DOMINANT_LIGHT (ABI 1.16), so they evaluate this f
// at their light's dominant direction and give the diffuse albedo the rest.

float toon_band(float t) {
    float n = float(max(sl_mat_toon_bands, 1));
    return ceil(t * n) / n;
}

vec3 toon_model(SlSurface s, vec3 l, vec3 E) {
    float nl = dot(s.normal, l);
    if (!(nl > 0.0)) return vec3(0.0);
    vec3 c = s.base_color * toon_band(min(nl, 1.0));
    if (dot(s.normal, s.view) < sl_mat_toon_rim) c += sl_mat_toon_rim_color;
    if (dot(s.normal, normalize(l + s.view)) >= sl_mat_toon_highlight) c += sl_mat_toon_highlight_color;
    return c * E * SL_INV_PI;
}

// How integrators see it: evaluate toon_model at the dominant direction; the rest of the light
// (an environment's light from other directions) falls on a plain Lambert surface of base_color.
SlLobes toon_lobes(SlSurface s) {
    SlLobes L = sl_lobes_none();
    L.diffuse = s.base_color;
    L.flags = SL_LOBES_MODEL_AT_DOMINANT_LIGHT;
    return L;
}
