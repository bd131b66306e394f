// Test plugin GLSL with a compile error on line 4.
void tp_surface(inout SlSurface s) { }
vec3 tp_model(SlSurface s, vec3 l, vec3 E) {
    return s.base_color * undefined_identifier;
}
vec3 tp_view(SlSurface s) { return vec3(1.0); }
