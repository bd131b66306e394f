// ss-wrap-lit (test plugin): wrap lighting with w = 1, k_d/π · E · (1 + n·l)/2.
vec3 ss_wrap_lit_model(SlSurface s, vec3 l, vec3 E) { return s.base_color * SL_INV_PI * E * 0.5 * (1.0 + dot(s.normal, l)); }
