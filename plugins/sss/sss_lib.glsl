// sss: pure functions (no uniforms), so the GLSL unit tests evaluate exactly this code.
// Lengths in millimetres of the skin profile unless stated; see sss_profile.h for the profile
// (d'Eon & Luebke 2007, GPU Gems 3 ch. 14, six Gaussians).

const float SSS_VARIANCE[6] = float[6](0.0064, 0.0484, 0.187, 0.567, 1.99, 7.41);
const vec3 SSS_WEIGHT[6] = vec3[6](vec3(0.233, 0.455, 0.649), vec3(0.100, 0.336, 0.344), vec3(0.118, 0.198, 0.0),
                                   vec3(0.113, 0.007, 0.007), vec3(0.358, 0.004, 0.0), vec3(0.078, 0.0, 0.0));

// Transmittance through d mm of skin lit uniformly from behind: Σ wᵢ exp(−d²/2vᵢ) (d'Eon &
// Luebke, GPU Gems 3 ch. 14). 1 at d = 0; d < 0 (depth-map noise in front of the first surface) counts as 0.
vec3 sss_slab_transmittance(float d_mm) {
    float d2 = max(d_mm, 0.0);
    d2 *= d2;
    vec3 t = vec3(0.0);
    for (int i = 0; i < 6; ++i) t += SSS_WEIGHT[i] * exp(-d2 / (2.0 * SSS_VARIANCE[i]));
    return t;
}

// Wrap lighting with a scatter band (Green, "Real-Time Approximations to Subsurface
// Scattering", GPU Gems 1 ch. 16, first method). Returns (wrapped diffuse factor, scatter
// factor): diffuse = max(0, (n·l + w)/(1 + w)); the scatter term is a band just inside the
// terminator, smoothstep(0, s, diffuse)·smoothstep(2s, s, diffuse) with s = scatter width.
// w = 0 and s → 0 give max(0, n·l) and no band. Guards: w clamped to [0, 1], s ≥ 1e-4.
vec2 sss_wrap_factors(float n_dot_l, float wrap, float scatter_width) {
    float w = clamp(wrap, 0.0, 1.0);
    float s = max(scatter_width, 1e-4);
    float diffuse = max(0.0, (n_dot_l + w) / (1.0 + w));
    float band = smoothstep(0.0, s, diffuse) * smoothstep(2.0 * s, s, diffuse);
    return vec2(diffuse, band);
}

// A premultiplied, coverage-carrying texel (rgb·a, a) → the covered average; 0 where nothing is
// covered. The texture-space and screen-space buffers store coverage in alpha so that bilinear
// filtering at chart edges and seams averages only covered texels.
vec3 sss_unpremultiply(vec4 t) { return t.a > 1e-6 ? t.rgb / t.a : vec3(0.0); }

// How much of the blurred result to use at a texel with coverage a: full from a = 0.25 on
// (a quarter of the bilinear footprint covered), fading to the unscattered Lambert term below.
float sss_coverage_weight(float a) { return smoothstep(0.0, 0.25, a); }

// Window depth d ∈ [0, 1] of a perspective projection (GL conventions) → distance in front of
// the camera: D = P[3][2] / ((2d − 1) + P[2][2]) with P[2][2] = −(f+n)/(f−n), P[3][2] = −2fn/(f−n).
float sss_linear_depth(float d, float p22, float p32) { return p32 / ((2.0 * d - 1.0) + p22); }

// Light-space depth d of a shadow map (extension shadow_maps.h) → metres along its axis.
float sss_map_linear_depth(float d, float n, float f, bool perspective) {
    return perspective ? 2.0 * n * f / (f + n - (2.0 * d - 1.0) * (f - n)) : n + d * (f - n);
}
