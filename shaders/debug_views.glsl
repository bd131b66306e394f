// The core's debug views.
vec3 sl_debug_diffuse_texture(SlSurface s) { return s.base_color; }
vec3 sl_debug_normal(SlSurface s) { return s.normal * 0.5 + 0.5; }
vec3 sl_debug_uv(SlSurface s) { return vec3(fract(s.uv), 0.0); }
