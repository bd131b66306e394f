// envmap's forward chunks: the "mirror" and "environment" shading models and the AMBIENT hook
// that lights every material from the environment. The hook specialises on the material's model
// (SL_MODEL_<NAME>, defined by the composer):
//   ggx         split sum: diffuse irradiance (SH or convolved cube) + prefiltered specular chain
//               × environment BRDF (F0·A + B); or, with envmap.mode = reference, Monte Carlo
//               integration of the source environment with the ggx plugin's exact BRDF
//   mirror      L(reflect(−v, n)), tinted by base_color when the material gives one
//   environment L(n), likewise
//   any other   Lambert: base_color × E(n)/π × ao (reference: cosine-sampled)
#include "envmap_common.glsl"
#include "sl:ggx_brdf.glsl"

uniform sampler2D envmap_src2d;   // the source as loaded (lat-long) …
uniform samplerCube envmap_srccube; // … or as a cube; envmap_is_cube says which
uniform bool envmap_is_cube;
uniform vec2 envmap_src_size;     // lat-long (w, h) or (face size, face size)
uniform samplerCube envmap_spec;  // prefiltered specular chain
uniform float envmap_spec_lod_max;// its last level (roughness 1)
uniform samplerCube envmap_irr;   // convolved irradiance (E/π)
uniform vec3 envmap_sh[9];        // SH irradiance (E/π), coefficients × Â_l/π × basis norm
uniform sampler2D envmap_lut;     // environment BRDF (A, B), envmap_lut_size² (the parameter's uniform)
uniform mat3 envmap_rot;          // world → map: R_y(−yaw)
uniform float envmap_scale;       // the scene environment's intensity

// Radiance arriving from world direction d.
vec3 envmap_source(vec3 d, float lod) {
    vec3 m = envmap_rot * d;
    vec3 c = envmap_is_cube ? textureLod(envmap_srccube, m, lod).rgb
                            : textureLod(envmap_src2d, envmap_dir_latlong(m), lod).rgb;
    return c * envmap_scale;
}
// Mip level for a lookup `angle` radians wide (a lat-long's u seam has no usable derivatives,
// so levels are chosen from the direction's own screen-space change).
float envmap_source_lod(float angle) {
    float texel = envmap_is_cube ? 0.5 * ENVMAP_PI / envmap_src_size.x : ENVMAP_PI / envmap_src_size.y;
    return max(0.0, log2(max(angle, 1e-8) / texel));
}

vec3 envmap_diffuse(vec3 n) { // E(n)/π: the outgoing radiance of a white Lambert surface
    vec3 m = envmap_rot * n;
#if defined(ENVMAP_IRRADIANCE) && ENVMAP_IRRADIANCE == ENVMAP_IRRADIANCE_CONVOLVED
    vec3 e = textureLod(envmap_irr, m, 0.0).rgb;
#else
    float x = m.x, y = m.y, z = m.z;
    vec3 e = envmap_sh[0] + envmap_sh[1] * y + envmap_sh[2] * z + envmap_sh[3] * x + envmap_sh[4] * (x * y) +
             envmap_sh[5] * (y * z) + envmap_sh[6] * (3.0 * z * z - 1.0) + envmap_sh[7] * (x * z) +
             envmap_sh[8] * (x * x - y * y);
    e = max(e, vec3(0.0)); // order-2 SH rings negative opposite a strong sun: clamp
#endif
    return e * envmap_scale;
}

vec3 envmap_specular(vec3 r, float alpha) {
    return textureLod(envmap_spec, envmap_rot * r, sqrt(alpha) * envmap_spec_lod_max).rgb * envmap_scale;
}

vec2 envmap_brdf(float mu, float alpha) { // texel i ↔ n·v = i/(n−1), j ↔ r = j/(n−1)
    vec2 x = vec2(mu, sqrt(alpha));
    float n = float(envmap_lut_size);
    return texture(envmap_lut, (x * (n - 1.0) + 0.5) / n).rg;
}

// Per-sample random numbers for the reference: an R2 sequence continued across accumulated
// frames (sl_frame_index), rotated per pixel.
vec2 envmap_xi(uint i, vec2 rot) {
    uint k = uint(envmap_reference_samples);
    return fract(envmap_r2(uint(sl_frame_index) * k + i) + rot);
}

vec3 envmap_lambert_reference(SlSurface s) {
    vec3 t, b;
    envmap_frame(s.normal, t, b);
    vec2 rot = envmap_hash2(uvec2(gl_FragCoord.xy));
    vec3 sum = vec3(0.0);
    for (int i = 0; i < envmap_reference_samples; i++) {
        vec3 l = envmap_sample_cosine(envmap_xi(uint(i), rot));
        sum += envmap_source(t * l.x + b * l.y + s.normal * l.z, 0.0);
    }
    return s.base_color * s.ao * sum / float(envmap_reference_samples);
}

#if defined(SL_MODEL_GGX)
float envmap_zero_specular() {
#if defined(GGX_ZERO_SPECULAR) && GGX_ZERO_SPECULAR
    return 0.0;
#else
    return 1.0;
#endif
}

vec3 envmap_ggx_split_sum(SlSurface s) {
    vec3 n = s.normal, v = s.view;
    float mu = clamp(dot(n, v), 1e-4, 1.0);
    float alpha = max(s.alpha, GGX_MIN_ALPHA);
    vec2 ab = envmap_brdf(mu, alpha);
#if SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS
    vec3 f0 = mix(vec3(0.04), s.base_color, sl_mat_metallic);
    float ks = 1.0;
    // the diffuse weight (1 − F)(1 − metallic) with F at the view angle
    vec3 kd = (1.0 - ggx_fresnel_schlick(mu, f0)) * (1.0 - sl_mat_metallic) * s.base_color;
#else
    // exact dielectric Fresnel is approximated by Schlick with the same F0 (a split-sum error)
    vec3 f0 = vec3(ggx_f0_from_eta(sl_mat_eta));
    float ks = s.specular;
    vec3 kd = s.base_color;
#endif
    vec3 spec = f0 * ab.x + ab.y;
    if (envmap_multiscatter) // Fdez-Agüera 2019: the energy single scattering loses, F0-tinted
        spec *= 1.0 + f0 * (1.0 / max(ab.x + ab.y, 1e-3) - 1.0);
    vec3 r = reflect(-v, n);
    // a (normal-mapped) normal facing away from the viewer is masked, G1(v) = 0: no specular,
    // as in the reference below and in ggx's direct term (ggx leaves such normals unbent)
    float visible = dot(n, v) > 0.0 ? 1.0 : 0.0;
    return kd * envmap_diffuse(n) * s.ao + ks * envmap_zero_specular() * visible * spec * envmap_specular(r, alpha);
}

// Monte Carlo with the exact BRDF: specular by GGX visible-normal sampling (f·cos/pdf =
// F·G(v,l)/G1(v)), diffuse by cosine sampling; the source map read at full resolution.
vec3 envmap_ggx_reference(SlSurface s) {
    vec3 n = s.normal, v = s.view;
    vec3 t, b;
    envmap_frame(n, t, b);
    vec3 vl = vec3(dot(v, t), dot(v, b), dot(v, n));
    float alpha = max(s.alpha, GGX_MIN_ALPHA);
    vec2 rot = envmap_hash2(uvec2(gl_FragCoord.xy));
#if SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS
    float ks = 1.0;
#else
    float ks = s.specular;
#endif
    ks *= envmap_zero_specular();
    vec3 spec = vec3(0.0), diff = vec3(0.0);
    for (int i = 0; i < envmap_reference_samples; i++) {
        vec2 xi = envmap_xi(uint(i), rot);
        if (vl.z > 0.0) {
            vec3 hl = envmap_sample_vndf(vl, alpha, xi);
            vec3 ll = 2.0 * dot(vl, hl) * hl - vl;
            if (ll.z > 0.0) {
                vec3 h = t * hl.x + b * hl.y + n * hl.z, l = t * ll.x + b * ll.y + n * ll.z;
                float g = ggx_G1(v, n, h, alpha) * ggx_G1(l, n, h, alpha) / envmap_smith_g1(vl.z, alpha);
                spec += ggx_fresnel(dot(l, h), s) * g * envmap_source(l, 0.0);
            }
        }
        vec3 lc = envmap_sample_cosine(fract(xi + vec2(0.5, 0.25)));
        vec3 l = t * lc.x + b * lc.y + n * lc.z;
#if SL_MAT_FRESNEL == SL_MAT_FRESNEL_METALLIC_ROUGHNESS
        vec3 h = normalize(l + v);
        vec3 kd = (1.0 - ggx_fresnel(dot(l, h), s)) * (1.0 - sl_mat_metallic) * s.base_color;
#else
        vec3 kd = s.base_color;
#endif
        diff += kd * envmap_source(l, 0.0);
    }
    return (ks * spec + diff * s.ao) / float(envmap_reference_samples);
}
#endif

vec3 envmap_tint(SlSurface s) {
#if defined(SL_MAT_HAS_BASE_COLOR) || defined(SL_MAT_HAS_BASE_COLOR_MAP)
    return s.base_color;
#else
    return vec3(1.0);
#endif
}

// The per-light part of "mirror" and "environment": a perfect mirror sees a punctual light only
// as a delta, and "environment" shows the map along n; neither reacts to lights.
vec3 envmap_model_none(SlSurface s, vec3 l, vec3 E) { return vec3(0.0); }

vec3 envmap_ambient(SlSurface s) {
    // screen-space footprint of the lookup direction, before any branch (derivatives)
#if defined(SL_MODEL_MIRROR)
    vec3 d = reflect(-s.view, s.normal);
#else
    vec3 d = s.normal;
#endif
    float footprint = max(length(dFdx(d)), length(dFdy(d)));
#if defined(SL_MODEL_MIRROR) || defined(SL_MODEL_ENVIRONMENT)
    return envmap_tint(s) * envmap_source(d, envmap_source_lod(footprint));
#elif defined(SL_MODEL_GGX)
#if ENVMAP_MODE == ENVMAP_MODE_REFERENCE
    return envmap_ggx_reference(s);
#else
    return envmap_ggx_split_sum(s);
#endif
#else
#if ENVMAP_MODE == ENVMAP_MODE_REFERENCE
    return envmap_lambert_reference(s);
#else
    return s.base_color * envmap_diffuse(s.normal) * s.ao;
#endif
#endif
}
