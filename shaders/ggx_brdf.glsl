// GGX / Cook–Torrance microfacet BRDF (Walter, Marschner, Li, Torrance 2007, "Microfacet Models
// for Refraction through Rough Surfaces", eqs. 33–34) with exact dielectric Fresnel
// (Cook & Torrance 1982; Walter et al. eq. 22) and Schlick's approximation (Schlick 1994).
// Pure functions of their arguments, so the tests evaluate them directly.

// Smallest α used: the formulas become a delta at α = 0. At α = 2e-3 the peak D = 1/(π α²) ≈ 8e4
// stays far inside half-float range after multiplying by E and F.
const float GGX_MIN_ALPHA = 2e-3;

#ifndef SL_LIGHT_SPREAD_DECLARED // common.glsl's: the evaluated light's angular radius
#define SL_LIGHT_SPREAD_DECLARED 1
float sl_light_spread = 0.0;
#endif

// A light's disk of angular radius r reflects into half vectors within ρ = r/2 of the mirror one.
// The lobe widens to it, α'² = α² + ρ² (1 + 1.414 ρ²/(ρ² + α²)), which meets both ends: for
// α ≫ ρ the peak of D convolved with the disk, D(0)(1 − ρ²/α²) (α'² = α² + ρ²), and for α → 0
// GGX's half maximum (tan θ_h = 0.6436 α', where (α² + tan²θ)² doubles) at the disk image's edge
// (α' = 0.777 r). D stays normalised, so the highlight keeps its energy (a polished sphere shows a
// disk of radius R sin(r/2): test_ggx_render). A point light (r = 0) keeps α.
// ggx_disk_alpha: the same for a lobe whose half maximum sits elsewhere, given the ρ to widen by
// (blinn-gloss's, phong.glsl: its half maximum is at 0.8326 α, so ρ × 0.6436/0.8326).
float ggx_disk_alpha(float alpha, float rho) {
    float rho2 = rho * rho, a2 = alpha * alpha;
    return sqrt(a2 + rho2 * (1.0 + 1.414 * rho2 / max(rho2 + a2, 1e-20)));
}
float ggx_light_alpha(float alpha) {
    if (sl_light_spread <= 0.0) return alpha; // points: the same for every lane, so skipped
    return ggx_disk_alpha(alpha, 0.5 * sl_light_spread);
}

// Normal distribution D(n, h) = α² / (π cos⁴θ_h (α² + tan²θ_h)²) for n·h > 0, else 0.
// cos⁴θ (α² + tan²θ)² = (cos²θ (α² − 1) + 1)², which has no tan() blow-up at grazing angles.
float ggx_D(float n_dot_h, float alpha) {
    if (n_dot_h <= 0.0) return 0.0;
    float a2 = alpha * alpha;
    float c2 = n_dot_h * n_dot_h;
    float d = c2 * (a2 - 1.0) + 1.0;
#ifdef GGX_MUTATE_D
    return alpha / (SL_PI * d * d); // the test suite's mutant (α for α² in the numerator) must fail
#endif
    return a2 / (SL_PI * d * d);
}

// Smith masking G₁(x, h) = 2 / (1 + √(1 + α² tan²θ_x)), θ_x the angle between x and n, and 0 when
// (x·h)/(x·n) ≤ 0 (Walter et al. eq. 34). With GGX_G1_HALF_VECTOR θ_x is measured from h instead
// (the head assignment's wording; a documented variant).
float ggx_G1(vec3 x, vec3 n, vec3 h, float alpha) {
    float x_dot_n = dot(x, n);
    float x_dot_h = dot(x, h);
    if (x_dot_n == 0.0 || x_dot_h / x_dot_n <= 0.0) return 0.0;
#ifdef GGX_G1_HALF_VECTOR
    float c = clamp(abs(x_dot_h), 1e-6, 1.0);
#else
    float c = clamp(abs(x_dot_n), 1e-6, 1.0);
#endif
    float tan2 = (1.0 - c * c) / (c * c);
    return 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * tan2));
}

// Exact unpolarised Fresnel reflectance of a dielectric interface. c = l·h, eta = n₁/n₂:
// β = √(1/η² + c² − 1); R_s = ((c − β)/(c + β))², R_p = ((η²β − c)/(η²β + c))²; F = ½(R_s + R_p);
// F = 1 under total internal reflection (β² < 0).
float ggx_fresnel_exact(float c, float eta) {
    c = abs(c);
    float b2 = 1.0 / (eta * eta) + c * c - 1.0;
    if (b2 < 0.0) return 1.0;
    float b = sqrt(b2);
    float rs = (c - b) / (c + b);
    float rp = (eta * eta * b - c) / (eta * eta * b + c);
    return 0.5 * (rs * rs + rp * rp);
}

// Schlick: F0 + (1 − F0)(1 − c)⁵ with F0 = ((1 − η)/(1 + η))².
float ggx_f0_from_eta(float eta) {
    float r = (1.0 - eta) / (1.0 + eta);
    return r * r;
}
// glTF 2.0 metallic-roughness: the dielectric F0, 0.04 (ior 1.5), or ((ior − 1)/(ior + 1))² for a
// material carrying ior (KHR_materials_ior; ggx's key, whose uniform comes with SL_MAT_HAS_IOR).
#ifdef SL_MAT_HAS_IOR
float ggx_gltf_dielectric_f0() {
    float r = (sl_mat_ior - 1.0) / (sl_mat_ior + 1.0);
    return r * r;
}
#else
float ggx_gltf_dielectric_f0() { return 0.04; }
#endif
vec3 ggx_fresnel_schlick(float c, vec3 f0) {
    float m = clamp(1.0 - abs(c), 0.0, 1.0);
    float m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m);
}

// f_s = F·D·G / (4 |n·l| |n·v|) without F (callers multiply their Fresnel): D·G/(4|n·l||n·v|).
// Returns 0 when the light or the viewer is below the shading normal (n·l ≤ 0 or n·v ≤ 0, e.g.
// normal-mapped normals facing away). This is the per-light hot path of the light loop, so it
// is written with the divisions cancelled (issue 18): with c = n·x, Smith's
// G₁ = 2/(1 + √(1 + α² tan²θ)) = 2c / (c + √(α² + (1 − α²) c²)), hence
// G₁(l) G₁(v) / (4 c_l c_v) = 1 / ((c_l + √(α² + (1 − α²) c_l²)) (c_v + √(α² + (1 − α²) c_v²))),
// finite at grazing angles without a guard (the same closed form as ggx_D · ggx_G1 · ggx_G1 /
// (4 n·l n·v), checked by the ggx tests). Above the normal on both sides, h = (l + v)/|l + v|
// has n·h > 0, l·h = v·h > 0, so ggx_G1's sign test (χ⁺) and ggx_D's n·h ≤ 0 case cannot occur.
float ggx_DG_over_4(vec3 n, vec3 l, vec3 v, float alpha, out vec3 h) {
    float n_dot_l = dot(n, l), n_dot_v = dot(n, v);
    vec3 hv = l + v;
    float len2 = dot(hv, hv);
    h = len2 > 1e-16 ? hv * inversesqrt(len2) : n;
    if (n_dot_l <= 0.0 || n_dot_v <= 0.0) return 0.0;
    alpha = max(ggx_light_alpha(alpha), GGX_MIN_ALPHA);
#ifdef GGX_G1_HALF_VECTOR
    float D = ggx_D(dot(n, h), alpha);
    float G = ggx_G1(v, n, h, alpha) * ggx_G1(l, n, h, alpha);
    return D * G / (4.0 * max(n_dot_l, 1e-4) * max(n_dot_v, 1e-4));
#else
    float a2 = alpha * alpha, b = 1.0 - a2;
    float cl = min(n_dot_l, 1.0), cv = min(n_dot_v, 1.0);
    return ggx_D(dot(n, h), alpha) / ((cl + sqrt(a2 + b * cl * cl)) * (cv + sqrt(a2 + b * cv * cv)));
#endif
}
