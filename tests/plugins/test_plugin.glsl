// Test plugin GLSL: a surface hook, a shading model and a debug view.
void tp_surface(inout SlSurface s) { s.base_color *= tp_good_tint; }
vec3 tp_model(SlSurface s, vec3 l, vec3 E) { return s.base_color * E * max(0.0, dot(s.normal, l)); }
vec3 tp_view(SlSurface s) { return vec3(0.25, 0.5, 0.75); }
