// cascades: the debug view "cascades" (sdk shader.h DEBUG_VIEW): the cascade each pixel reads,
// from the same practical splits as cascades.c (Zhang et al. 2006) and the same selection as
// spotlight-shadow's hook (camera depth; fading into the next cascade over the blend band).
// Colours: red, green, blue, yellow = cascade 0..3; grey beyond the last split. Shaded by the
// normal against the view direction so the geometry stays readable.

float cascades_split(int i, int n, float zn, float zf) {
    float x = float(i) / float(n);
    return cascades_lambda * zn * pow(zf / zn, x) + (1.0 - cascades_lambda) * (zn + (zf - zn) * x);
}

vec3 cascades_debug(SlSurface s) {
    const vec3 colors[4] = vec3[4](vec3(0.9, 0.15, 0.1), vec3(0.15, 0.8, 0.15), vec3(0.15, 0.3, 0.95),
                                   vec3(0.95, 0.85, 0.1));
    float zn = sl_proj[3][2] / (sl_proj[2][2] - 1.0), zf = sl_proj[3][2] / (sl_proj[2][2] + 1.0);
    if (cascades_max_distance > 0.0) zf = min(zf, cascades_max_distance);
    int n = clamp(cascades_count, 1, 4);
    float z = -(sl_view * vec4(s.position, 1.0)).z;
    float shade = 0.45 + 0.55 * abs(dot(s.normal, s.view));
    vec3 c = vec3(0.5);
    for (int k = 0; k < n; ++k) {
        float s0 = cascades_split(k, n, zn, zf), s1 = cascades_split(k + 1, n, zn, zf);
        if (z >= s1) continue;
        float b = k + 1 < n ? clamp(cascades_blend, 0.0, 0.5) * (s1 - s0) : 0.0;
        float t = b > 0.0 ? (z - (s1 - b)) / b : -1.0;
        c = t > 0.0 ? mix(colors[k], colors[k + 1], t) : colors[k];
        break;
    }
    return c * shade;
}
