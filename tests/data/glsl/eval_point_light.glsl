// Test helper: evaluates the core's point light at position p for a light of intensity 10 at
// (0.5, 1.5, -0.3); returns (l.xyz, E.r).
#include "sl:lights.glsl"
vec4 test_point_light(vec3 p) {
    SlLight L = SlLight(vec4(0.5, 1.5, -0.3, 1.0), vec4(0.0, -1.0, 0.0, 0.0), vec4(10.0), vec4[2](vec4(0.0), vec4(0.0)));
    SlSurface s;
    s.position = p;
    vec3 l, E;
    sl_light_point(L, s, l, E);
    return vec4(l, E.r);
}
