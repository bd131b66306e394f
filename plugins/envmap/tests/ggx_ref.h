/* Closed forms and numerical integrals in C (double precision) for the envmap tests: the GGX
 * terms exactly as shaders/ggx_brdf.glsl defines them, the split-sum BRDF integrals
 * (A, B) and the prefilter kernel. Independent of the GLSL they check. */
#ifndef ENVMAP_TEST_GGX_REF_H
#define ENVMAP_TEST_GGX_REF_H
#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static inline double ref_ggx_D(double nh, double a) {
    if (nh <= 0) return 0;
    double a2 = a * a, d = nh * nh * (a2 - 1) + 1;
    return a2 / (M_PI * d * d);
}

/* Smith G1 measured from the normal, 0 when (x·h)/(x·n) ≤ 0 (ggx_G1). */
static inline double ref_ggx_G1(double xn, double xh, double a) {
    if (xn == 0 || xh / xn <= 0) return 0;
    double c = fabs(xn);
    if (c < 1e-6) c = 1e-6;
    if (c > 1) c = 1;
    double t2 = (1 - c * c) / (c * c);
    return 2 / (1 + sqrt(1 + a * a * t2));
}

/* ∫ f_s cos dl = F0·A + B for the separable-Smith GGX BRDF with Schlick's Fresnel, n·v = mu.
 * Integrated over the half-vector with u = CDF of D(h)(n·h), so narrow lobes are resolved:
 * D(h)(n·h) dω_h = du dφ/2π, and ∫ f cos dl = ∫ D G F (v·h)/(mu) dω_h. Midpoint rule. v lies in
 * the xz plane, so the integrand at φ equals the one at 2π − φ (h_y changes sign, nothing it
 * enters does): the nodes j and nphi − 1 − j are mirrors, and each pair is evaluated once with
 * weight 2 (the node at φ = π, odd nphi, is its own mirror: weight 1) — the same sum in a
 * quarter of the time (these integrals were most of the envmap tests' time). */
static inline void ref_brdf_ab(double mu, double a, int nu, int nphi, double *A, double *B) {
    double v[3] = {sqrt(1 - mu * mu), 0, mu};
    double sa = 0, sb = 0;
    for (int j = 0; j < (nphi + 1) / 2; j++) { /* φ outside: cos φ once per node */
        double cphi = cos(2 * M_PI * (j + 0.5) / nphi), weight = 2 * j + 1 == nphi ? 1 : 2;
        for (int i = 0; i < nu; i++) {
            double u = (i + 0.5) / nu;
            double c2 = (1 - u) / (1 + (a * a - 1) * u), ch = sqrt(c2), sh = sqrt(fmax(0, 1 - c2));
            double vh = v[0] * sh * cphi + v[2] * ch;
            if (vh <= 0) continue;
            double lz = 2 * vh * ch - v[2];
            if (lz <= 0) continue;
            double G = ref_ggx_G1(mu, vh, a) * ref_ggx_G1(lz, vh, a);
            /* D(h) dω_h = du dφ/(2π ch): integrand D G F vh / mu → G F vh/(mu ch) du dφ/2π */
            double w = weight * G * vh / (mu * ch);
            double m = 1 - vh, fc = m * m * m * m * m;
            sa += w * (1 - fc);
            sb += w * fc;
        }
    }
    *A = sa / ((double)nu * nphi);
    *B = sb / ((double)nu * nphi);
}

/* The diffuse Fresnel weight C(mu) = ∫ (1 − v·h)^5 cos θ_l/π dl over the hemisphere, h the
 * half-vector of l and v: glTF's diffuse (1 − F(v·h)) c/π with Schlick's F integrates to
 * (1 − F0)(1 − C(mu)) c. Midpoint rule in (cos² θ_l, φ), where cos/π dl = d(cos²θ) dφ/2π. */
static inline double ref_diffuse_fresnel(double mu, int n) {
    double v[3] = {sqrt(fmax(0, 1 - mu * mu)), 0, mu}, s = 0;
    for (int i = 0; i < n; i++) {
        double c2 = (i + 0.5) / n, ct = sqrt(c2), st = sqrt(1 - c2);
        for (int j = 0; j < n; j++) {
            double phi = 2 * M_PI * (j + 0.5) / n;
            double h[3] = {st * cos(phi) + v[0], st * sin(phi) + v[1], ct + v[2]};
            double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
            s += pow(1 - (v[0] * h[0] + v[1] * h[1] + v[2] * h[2]) / hl, 5);
        }
    }
    return s / ((double)n * n);
}

/* Directional albedo E(mu, α) with F = 1. */
static inline double ref_albedo(double mu, double a) {
    double A, B;
    ref_brdf_ab(mu, a, 1200, 96, &A, &B);
    return A + B;
}

/* The split-sum prefilter kernel with n = v: k(θ) = (n·l) D(n·h)/4, θ the angle between n and l
 * (n·h = cos θ/2); the prefiltered value is ∫ L k / ∫ k over n·l > 0. */
static inline double ref_prefilter_kernel(double cos_theta, double a) {
    if (cos_theta <= 0) return 0;
    double nh = sqrt(0.5 * (1 + cos_theta));
    return cos_theta * ref_ggx_D(nh, a) * 0.25;
}
static inline double ref_prefilter_norm(double a) {
    int n = 20000;
    double s = 0;
    for (int i = 0; i < n; i++) {
        double t = (i + 0.5) / n * (M_PI / 2);
        s += ref_prefilter_kernel(cos(t), a) * sin(t);
    }
    return s * 2 * M_PI * (M_PI / 2) / n;
}
#endif
