// Test plugin GLSL: a surface hook, a vertex hook, a shading model, a debug view and a light that
// returns radiance (SL_CHUNK_LIGHT_RADIANCE): the material's model lit head-on by E = its colour,
// twice (two calls of sl_shading_model, so the test sees that the result is what is added).
#ifdef SL_MAT_HAS_TP_LIFT
void tp_vertex(inout SlVertex v) { v.position.y += sl_mat_tp_lift; }
#endif
#ifdef SL_MAT_HAS_TP_MARK // the hook is only called for such materials; tp-good's tint uniform
void tp_surface(inout SlSurface s) { s.base_color *= tp_good_tint; }
#endif
// tp_scale is a material key every variant declares (shared vocabulary): whichever plugin's
// model is used, its uniform must be declared.
vec3 tp_model(SlSurface s, vec3 l, vec3 E) { return s.base_color * E * max(0.0, dot(s.normal, l)) * sl_mat_tp_scale; }
vec3 tp_view(SlSurface s) { return vec3(0.25, 0.5, 0.75); }
#ifdef SL_FRAGMENT_STAGE // this file is also the vertex hook's: sl_shading_model is fragment-only
vec3 tp_glow(SlLight L, SlSurface s) {
    return sl_shading_model(s, s.normal, 0.5 * L.color.rgb) + sl_shading_model(s, s.normal, 0.5 * L.color.rgb);
}
#endif
