// GLSL helpers for tests/stability_core.c (evaluated through sl_harness_eval_glsl after the
// core's lights.glsl). The surface is at p facing +Y; the point light at lp.xyz has intensity lp.w.
// Returns (E·max(0, n·l), E, |l|, 1 if anything is NaN/Inf).
vec4 stability_point_light(vec4 p, vec4 lp) {
    SlLight L;
    L.position = vec4(lp.xyz, 1.0);
    L.direction = vec4(0.0, -1.0, 0.0, 0.0);
    L.color = vec4(vec3(lp.w), 0.0);
    L.params[0] = vec4(0.0);
    L.params[1] = vec4(0.0);
    SlSurface s;
    s.position = p.xyz;
    s.normal = vec3(0.0, 1.0, 0.0);
    s.geometric_normal = s.normal;
    s.tangent = vec3(1.0, 0.0, 0.0);
    s.bitangent = vec3(0.0, 0.0, 1.0);
    s.uv = vec2(0.0);
    s.view = s.normal;
    s.base_color = vec3(1.0);
    s.alpha = 1.0;
    s.specular = 1.0;
    s.ao = 1.0;
    s.opacity = 1.0;
    s.lod_bias = 0.0;
    vec3 l, E;
    sl_light_point(L, s, l, E);
    float c = E.x * max(0.0, dot(s.normal, l));
    bool bad = any(isnan(l)) || any(isinf(l)) || any(isnan(E)) || any(isinf(E));
    return vec4(c, E.x, length(l), bad ? 1.0 : 0.0);
}
