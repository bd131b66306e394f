// nod: SURFACE hook for materials carrying nod_color: base colour mixed toward it inside a
// sphere of the rest pose's world space (sl_model · SlSurface.object_position: the region stays
// on the surface while the vertex hook moves it), weight
//   strength · (1 − cos 2π f_c t)/2 · (1 − smoothstep(r/2, r, |p − centre|)).
#include "nod_motion.glsl" // nod_time()

float nod_color_weight(vec3 rest_position, float t) {
    float pulse = 0.5 - 0.5 * cos(2.0 * SL_PI * nod_color_frequency * t);
    float r = max(nod_color_radius, 1e-6);
    float inside = 1.0 - smoothstep(0.5 * r, r, length(rest_position - nod_color_center));
    return nod_color_strength * pulse * inside;
}

void nod_surface(inout SlSurface s) {
    s.base_color = mix(s.base_color, sl_mat_nod_color, nod_color_weight((sl_model * vec4(s.object_position, 1.0)).xyz, nod_time()));
}
