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

// A light's disk of angular radius r reflects into half vectors within about ρ = r/2 of the mirror
// one. ggx_DG_over_4 convolves D with that disk (ggx_D_disk, below). ggx_disk_alpha widens
// a lobe instead, α'² = α² + ρ² (1 + 1.414 ρ²/(ρ² + α²)), which meets both ends in the peak's width
// (for α ≫ ρ the peak of the convolution, α'² = α² + ρ²; for α → 0 GGX's half maximum, tan θ_h =
// 0.6436 α', at the disk image's edge, α' = 0.777 r) but not in shape: a widened GGX keeps its
// long tails (71 % of its energy outside the disk's image as α → 0). Blinn-gloss (phong.glsl, its
// half maximum at 0.8326 α: ρ × 0.6436/0.8326) uses it.
float ggx_disk_alpha(float alpha, float rho) {
    float rho2 = rho * rho, a2 = alpha * alpha;
    return sqrt(a2 + rho2 * (1.0 + 1.414 * rho2 / max(rho2 + a2, 1e-20)));
}

// D seen through the light's disk (sl_light_spread = r > 0), in slope space: D = P(m)/cos⁴θ_h with
// m = (h − n cos θ_h)/cos θ_h and GGX's slope density P(m) = α²/(π (α² + |m|²)²) — the kernel of the
// form factor from a point at height α to a plane. So P's mean over a disk of slopes of radius s
// whose centre is |m| = t away is the form factor of a parallel disk offset by t, over π s² (the
// differential element to a parallel disk: F = ½ (1 − (α² + t² − s²)/√((α² + t² + s²)² − 4t²s²))):
// ggx_slope_disk = 2α²/(π y (y + x)), x = α² + t² − s², y = √(x² + 4α²s²), as (y − x)/(2π y s²)
// where x < 0 (no cancellation). Normalised for any α and s, and P itself as s → 0.
float ggx_slope_disk(float t2, float s2, float a2) {
    float x = a2 + t2 - s2;
    float y = sqrt((t2 - s2) * (t2 - s2) + a2 * (a2 + 2.0 * (t2 + s2)));
    return x >= 0.0 ? 2.0 * a2 / (SL_PI * y * (y + x)) : (y - x) / (2.0 * SL_PI * y * s2);
}

// The pixel's footprint of normals (sl_normal_footprint, common.glsl, ABI 1.23; declared here too
// for programs that include this file alone): D is filtered over it, as a disk of its area,
// together with the light's disk (their areas add), so a sun's glint smaller than a pixel lights the
// pixels round it by their share of it rather than the samples that happen to hit it. For every
// light the light loop evaluates (sl_light_in_loop, ABI 1.25; a point or spot light, without a
// disk: the footprint alone, ggx_D_footprint), not for the directions an integrator samples
// (envmap's reference: it sees D itself, whose importance sampling it is).
// Where the filter sits in a TAA still's jittered frames (ggx_footprint_normal): a disk of a pixel's
// area does not tile the pixels, so a glint far narrower than a pixel keeps its energy only as the
// jitter moves the disk over the pixel (the still's filter then that disk moved over the pixel,
// about two pixels wide); a lobe about a pixel wide needs no such help and is box-filtered
// closest to what a path tracer's pixel gives (Cycles' 1-pixel box) by the disk at the pixel's
// centre in every frame. The normal moves from the sample towards the pixel's centre
// (sl_normal_to_centre, ABI 1.28) by 4g/(s² + 4g), g the lobe's own slope area (α² and the
// light's disk). Modelled for a 4-frame still against the box filter: a lobe of 0.53 pixel (the
// default scene's gold under its sun) 0.163 → 0.035 relative RMS, 0.3 pixel 0.22 → 0.10, a
// 0.03-pixel glint as before (1 % of the way); a share of the footprint instead, sharper, left
// the glint's energy 0.82-1.28 of itself by position. test_ggx_render measures it against
// supersampling.
#ifndef SL_NORMAL_FOOTPRINT_DECLARED
#define SL_NORMAL_FOOTPRINT_DECLARED 1
float sl_normal_footprint = 0.0;
vec3 sl_normal_to_centre = vec3(0.0);
#endif
vec3 ggx_footprint_normal(vec3 n, float alpha2) {
    float g = alpha2 + 0.25 * sl_light_spread * sl_light_spread, s2 = sl_normal_footprint;
    return normalize(n + sl_normal_to_centre * (4.0 * g / max(s2 + 4.0 * g, 1e-20)));
}
#ifndef SL_LIGHT_IN_LOOP_DECLARED // common.glsl's: the light loop's own evaluations
#define SL_LIGHT_IN_LOOP_DECLARED 1
bool sl_light_in_loop = false;
#endif

// The disk of half vectors is an ellipse: r/2 in the plane of l and v, r/(2 cos θ_d) across it
// (θ_d: l·h), and its slopes wider off the normal (s² = (r/2)²/cos³θ_h, area-matched; short of
// the normal's slope 0 unless it is within r/2 of h: s ≤ 0.9 tan θ_h once that exceeds r/2, for
// near the horizon the linear map of angles to slopes would reach back to the lobe's peak):
// ggx_disk_light. Squeezing slopes across the plane by k = cos θ_d makes it a disk (the density ×
// k), but squeezes the lobe as well, so k blends from 1 (the lobe wider than the disk: GGX's shape
// kept) to cos θ_d (the disk wider: its image kept) by w = s²/(s² + α² + footprint); the lobe keeps
// its α in the squeezed slopes (measured closer to the integral than α√k, the squeezed lobe's mean,
// or w² or √w: test_ggx_render). Returns k; m becomes the squeezed slope, s2 the disk's with the
// footprint's.
float ggx_disk_light(float c, vec3 m) {
    float rho = 0.5 * sl_light_spread;
    return min(rho * rho / (c * c * c), max(rho * rho, 0.81 * dot(m, m)));
}
float ggx_disk_squeeze(vec3 l, vec3 v, vec3 h, float light, float a2, inout vec3 m, out float s2) {
    s2 = light + sl_normal_footprint;
    float k = 1.0 - (1.0 - clamp(dot(l, h), 0.0, 1.0)) * light / max(s2 + a2, 1e-20);
    vec3 across = cross(l, v);
    across *= inversesqrt(max(dot(across, across), 1e-20));
    m -= (1.0 - k) * dot(m, across) * across;
    return k;
}
// Whether this evaluation convolves D with a disk (ggx_D_disk, ggx_layers.glsl's ggx_aniso_D_disk):
// under a light's disk, its area and the pixel's footprint together. Uniform per light.
bool ggx_D_disk_filtered() { return sl_light_spread > 0.0; }
// For a light of the light loop without a disk (a point or spot light), D over the pixel's
// footprint alone: ggx_slope_disk(tan²θ_h, footprint, α²)/cos⁴θ_h (ggx_D_disk without a light's
// disk to squeeze), with both brought over u = cos²θ_h, X = u(α² − s²) + 1 − u and
// Y = √((1 − u − u s²)² + α²u(α²u + 2(1 − u) + 2u s²)): D = 2α²/(π Y (Y + X)) where X ≥ 0, else
// (Y − X)/(2π Y s² u²), as one division, (X ≥ 0 ? 4α²s²u² : (Y + |X|)²)/(2π Y (Y + |X|) s² u²) —
// a square root more than D itself, where ggx_D_disk's path took 64 point lights' forward pass to
// 1.6× plain D's (ratio_sphere at 256²; this form 1.1×). s² = 0 gives D (X = Y). Integrators' directions
// (sl_light_in_loop false) see D itself.
bool ggx_D_footprint_filtered() { return sl_light_in_loop && sl_normal_footprint > 0.0; }
float ggx_D_footprint(float n_dot_h, float alpha) {
    float u = max(n_dot_h * n_dot_h, 1e-8), a2 = alpha * alpha, s2 = max(sl_normal_footprint, 1e-12), w = 1.0 - u;
    float X = u * (a2 - s2) + w, e = w - u * s2;
    float Y = sqrt(e * e + a2 * u * (a2 * u + 2.0 * w + 2.0 * u * s2)), q = Y + abs(X), k = s2 * u * u;
    return (X >= 0.0 ? 4.0 * a2 * k : q * q) / (2.0 * SL_PI * Y * q * k);
}
float ggx_D_disk(vec3 n, vec3 h, vec3 l, vec3 v, float alpha) {
    float c = max(dot(n, h), 1e-4), c2 = c * c, a2 = alpha * alpha, s2;
    vec3 m = (h - n * c) / c;
    float k = ggx_disk_squeeze(l, v, h, ggx_disk_light(c, m), a2, m, s2);
    return k * ggx_slope_disk(dot(m, m), s2, a2) / (c2 * c2);
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
    alpha = max(alpha, GGX_MIN_ALPHA);
    float D; // a light of the light loop (uniform per light): its disk and the pixel's footprint
    if (ggx_D_disk_filtered()) D = ggx_D_disk(ggx_footprint_normal(n, alpha * alpha), h, l, v, alpha);
    else if (ggx_D_footprint_filtered()) D = ggx_D_footprint(dot(ggx_footprint_normal(n, alpha * alpha), h), alpha);
    else D = ggx_D(dot(n, h), alpha);
#ifdef GGX_G1_HALF_VECTOR
    float G = ggx_G1(v, n, h, alpha) * ggx_G1(l, n, h, alpha);
    return D * G / (4.0 * max(n_dot_l, 1e-4) * max(n_dot_v, 1e-4));
#else
    float a2 = alpha * alpha, b = 1.0 - a2;
    float cl = min(n_dot_l, 1.0), cv = min(n_dot_v, 1.0);
    return D / ((cl + sqrt(a2 + b * cl * cl)) * (cv + sqrt(a2 + b * cv * cv)));
#endif
}
