// phong: pure functions (no uniforms, no textures), used by the models in phong.glsl and
// evaluated directly by the GLSL unit tests (tests/test_phong_glsl.c compares them with C).
//
// Units follow the core: l points to the light, E is the light's irradiance at normal
// incidence, the result is outgoing radiance. The course formulas are written for a light of
// "intensity" I with Color = albedo·I·(n·l) + …; ours is the same with E = π·I, so every
// term below carries 1/π (Lambert is k_d/π).

const float PHONG_F0 = 0.04; // Schlick's F0 of the blinn-gloss model (dielectric, η ≈ 1.5)

// Schlick: F = F0 + (1 − F0)(1 − n·v)⁵, n·v clamped to [0, 1] (F ∈ [F0, 1]).
float phong_schlick(float ndv) {
    float m = 1.0 - clamp(ndv, 0.0, 1.0);
    float m2 = m * m;
    return PHONG_F0 + (1.0 - PHONG_F0) * m2 * m2 * m;
}

// SpecPower = 2^(12·gloss), gloss ∈ [0, 1] → [1, 4096]; gloss 0.5 → 64.
float phong_power_from_gloss(float gloss) { return exp2(12.0 * clamp(gloss, 0.0, 1.0)); }
float phong_gloss_from_power(float p) { return clamp(log2(max(p, 1.0)) / 12.0, 0.0, 1.0); }

// Blinn-Phong power ↔ the GGX-style α the surface record carries (s.alpha), by Walter et al.
// 2007's equivalence p = 2/α² − 2: the gloss map travels in s.alpha like any roughness.
float phong_alpha_from_power(float p) { return sqrt(2.0 / (max(p, 0.0) + 2.0)); }
float phong_power_from_alpha(float a) { return max(2.0 / max(a * a, 1e-8) - 2.0, 0.0); }

// The normalised Blinn-Phong lobe (p+1)/2 · (n·h)^p; 0 for n·h ≤ 0. Its integral over the
// hemisphere of h is exactly π for every p ≥ 0: ∫ (p+1)/2 cos^p θ dω = 2π·(p+1)/2 · 1/(p+1).
float phong_blinn_lobe(float ndh, float p) {
    return ndh > 0.0 ? (p + 1.0) * 0.5 * pow(ndh, max(p, 0.0)) : 0.0;
}

// Toksvig 2005: a mip level whose averaged (unnormalised) normal has length |N̄| < 1 behaves as
// a lobe of power ft·p, ft = |N̄| / (|N̄| + p(1 − |N̄|)).
float phong_toksvig_power(float p, float len) {
    len = clamp(len, 1e-4, 1.0);
    return p * len / (len + p * (1.0 - len));
}

// Half vector; l = −v (no half vector) falls back to n.
vec3 phong_half(vec3 l, vec3 v, vec3 n) {
    vec3 h = l + v;
    float hl = dot(h, h);
    return hl > 1e-12 ? h * inversesqrt(hl) : n;
}

// "blinn-gloss", one light: Color = mix(Ambient + Diffuse, Specular, F) split per light,
// exact because mix is linear and F depends on n·v only:
//   L = E/π · (n·l) · [(1 − F)·albedo + F·k_s·(p+1)/2·(n·h)^p]
vec3 phong_blinn_gloss(vec3 n, vec3 v, vec3 l, vec3 albedo, float p, float ks, vec3 E) {
    float ndl = dot(n, l);
    if (ndl <= 0.0) return vec3(0.0);
    float F = phong_schlick(dot(n, v));
    float spec = phong_blinn_lobe(dot(n, phong_half(l, v, n)), p);
    return E * SL_INV_PI * ndl * ((1.0 - F) * albedo + F * ks * spec);
}

// "blinn-gloss" for a prefiltered (Toksvig) texel: w = 1 − ft ∈ [0, 1] is how much the lobe was
// widened by the footprint's normal variance. The specular part of the footprint's average,
// Σ F(n_i·v)·lobe(n_i·h)·(n_i·l), comes from the microfacets with n_i ≈ h, so its Fresnel and
// cosine are F(h·v) and h·l, not F(N̄·v) and N̄·l of the averaged normal (at grazing angles
// F(N̄·v) overestimates a bumpy far field several times). w = 0 is exactly phong_blinn_gloss.
vec3 phong_blinn_gloss_filtered(vec3 n, vec3 v, vec3 l, vec3 albedo, float p, float ks, vec3 E, float w) {
    float ndl = dot(n, l);
    if (ndl <= 0.0) return vec3(0.0);
    vec3 h = phong_half(l, v, n);
    float Fn = phong_schlick(dot(n, v));
    float Fs = mix(Fn, phong_schlick(dot(h, v)), w);
    float cs = mix(ndl, max(dot(h, l), 0.0), w);
    return E * SL_INV_PI * ((1.0 - Fn) * ndl * albedo + Fs * cs * ks * phong_blinn_lobe(dot(n, h), p));
}

// "blinn-gloss", the ambient term outside the light loop: (1 − F)·albedo·AO·E_a/π
// (E_a = π × the constant environment radiance, so this is (1 − F)·albedo·AO·L_env).
vec3 phong_blinn_gloss_ambient(vec3 n, vec3 v, vec3 albedo, float ao, vec3 Ea) {
    return (1.0 - phong_schlick(dot(n, v))) * albedo * ao * Ea * SL_INV_PI;
}

// blinn-gloss as one lobe for light integrators (README, "Lobes"; derived by
// plugins/phong/lobe_fit.c): Blinn-Phong shaped (the contract's SL_LOBES_BLINN_PHONG), of the
// α whose power is the model's, sl_lobe_blinn_alpha(p) (Blinn's median: the GGX lobe closest to
// it for integrators that read every lobe as GGX). Its weight: the model's specular albedo over
// the lobe's (the contract gives a Blinn-Phong lobe the GGX lobe's albedo), so that a uniform
// environment gets the model's exact response at every n·v = μ:
//   R(μ, p) = ∫ (p+1)/(2π)(n·h)^p (n·l) dl,   E(μ, α) = ∫ D G₁(v)G₁(l)/(4 n·v) (n·l) dl,
// weight = R/E, fitted by least squares over p ∈ [0, 4095], μ ∈ [0.1, 1] (phong_lobe_fit weight:
// relative error ≤ 1.7 %, rms 0.7 %) as 4μ²/G₁(μ)² — its narrow-lobe limit, written
// (μ + √(μ² + α²(1 − μ²)))² to stay finite at μ → 0 — times exp(Σ c_ij α^i t^j), i + j ≤ 4,
// t = α/(max(μ, 0.1) + α) − α/(1 + α) (0 at μ = 1; grows where the lobe meets the horizon).
// α is sl_lobe_blinn_alpha(p). 0 for μ ≤ 0.
const float PHONG_LOBE_FIT[14] = float[](-0.46046, 4.39667, -0.01032, -3.45885, -0.13490, 12.44044, -22.01450, 6.06315, -2.31435, -10.56660, 13.49543, 2.38887, 0.95184, -0.84898);
float phong_lobe_weight(float mu, float alpha) {
    if (mu <= 0.0) return 0.0;
    float a = alpha, t = a / (max(mu, 0.1) + a) - a / (1.0 + a);
    const float c[14] = PHONG_LOBE_FIT;
    float e = t * (c[0] + t * (c[1] + t * (c[2] + t * c[3]))) +
              a * (c[4] + t * (c[5] + t * (c[6] + t * c[7])) +
              a * (c[8] + t * (c[9] + t * c[10]) +
              a * (c[11] + t * c[12] +
              a * c[13])));
    float g = mu + sqrt(mu * mu + a * a * (1.0 - mu * mu));
    return g * g * exp(e);
}

// Classic Phong, one light: L = E/π · (k_d·(n·l) + k_s·max(0, r·v)^shininess) for n·l > 0,
// r = reflect(−l, n). The specular term is not multiplied by n·l (the classic model), so it
// is cut at the terminator; 0 for light behind the surface.
vec3 phong_classic(vec3 n, vec3 v, vec3 l, vec3 kd, vec3 ks, float shininess, vec3 E) {
    float ndl = dot(n, l);
    if (ndl <= 0.0) return vec3(0.0);
    float rv = dot(reflect(-l, n), v);
    float spec = rv > 0.0 ? pow(rv, max(shininess, 0.0)) : 0.0;
    return E * SL_INV_PI * (kd * ndl + ks * spec);
}

// Classic Phong ambient: k_d·AO·E_a/π.
vec3 phong_classic_ambient(vec3 kd, float ao, vec3 Ea) { return kd * ao * Ea * SL_INV_PI; }
