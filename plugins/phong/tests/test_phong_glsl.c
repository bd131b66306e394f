/* GLSL unit tests of phong_brdf.glsl, evaluated from the plugin's own file and compared with C:
 * Schlick (0.04 at normal incidence, 1 at grazing), SpecPower = 2^(12·gloss), the α ↔ power
 * equivalence, the lobe's normalisation (∫ (p+1)/2·cos^p θ_h dω_h = π for every p, with a
 * mutant that must fail), Toksvig, both models over random grids, and their stability (gloss 0
 * and 1, grazing light, light behind, normals facing away, l = −v): no NaN/Inf, no negative
 * radiance, and stated values. The lobe description (README, "Lobes"): α with Blinn's median and
 * the weight that carries the model's directional albedo, against quadratures in C. */
#include "check.h"
#include <shadelab/harness.h>
#include <stdlib.h>

static const char *const PH[] = {"phong", NULL};
static const char *files[] = {"phong_brdf.glsl", NULL};
static sl_harness *h;
static char err[8192];

#define G 64
static float in0[G * G * 4], in1[G * G * 4], out[G * G * 4];
#define NL 4096
static float lin0[NL * 8 * 4], lout[NL * 8 * 4];

static unsigned rng = 777u;
static double frand(void) { rng = rng * 1664525u + 1013904223u; return (rng >> 8) / 16777216.0; }

static bool eval(const char *expr, int w, int hh, const float *a, const float *b, float *o) {
    sl_glsl_eval_desc d = {.struct_size = sizeof d, .plugin = "phong", .files = files, .width = w, .height = hh,
                           .in0 = a, .in1 = b, .expression = expr};
    bool ok = sl_harness_eval_glsl(h, &d, o, err, sizeof err);
    if (!ok) fprintf(stderr, "eval %s: %s\n", expr, err);
    return ok;
}

static double schlick(double c) {
    double m = 1 - (c < 0 ? 0 : c > 1 ? 1 : c);
    return 0.04 + 0.96 * m * m * m * m * m;
}

static void unit_random(double v[3], bool upper) {
    double a = 2 * M_PI * frand(), z = upper ? frand() : 2 * frand() - 1, r = sqrt(1 - z * z);
    v[0] = r * cos(a), v[1] = r * sin(a), v[2] = z;
}
static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* C versions of the two models (n = +Z frame-free: vectors as given). */
static double c_blinn(const double n[3], const double v[3], const double l[3], double albedo, double p, double ks, double E,
                      double w) {
    double ndl = dot3(n, l);
    if (ndl <= 0) return 0;
    double hv[3] = {l[0] + v[0], l[1] + v[1], l[2] + v[2]}, hl = sqrt(dot3(hv, hv));
    for (int i = 0; i < 3; i++) hv[i] = hl > 1e-6 ? hv[i] / hl : n[i];
    double ndh = dot3(n, hv), Fn = schlick(dot3(n, v));
    double Fs = (1 - w) * Fn + w * schlick(dot3(hv, v)), cs = (1 - w) * ndl + w * fmax(dot3(hv, l), 0);
    double lobe = ndh > 0 ? (p + 1) / 2 * pow(ndh, p) : 0;
    return E / M_PI * ((1 - Fn) * ndl * albedo + Fs * cs * ks * lobe);
}

static double c_classic(const double n[3], const double v[3], const double l[3], double kd, double ks, double s, double E) {
    double ndl = dot3(n, l);
    if (ndl <= 0) return 0;
    double r[3];
    for (int i = 0; i < 3; i++) r[i] = 2 * ndl * n[i] - l[i];
    double rv = dot3(r, v);
    return E / M_PI * (kd * ndl + ks * (rv > 0 ? pow(rv, s) : 0));
}

static void test_fresnel_and_gloss(void) {
    for (int i = 0; i < G * G; i++) in0[i * 4] = (float)(-0.5 + 1.7 * i / (G * G - 1)); /* n·v in [−0.5, 1.2] */
    CHECK(eval("vec4(phong_schlick(in0.x), phong_power_from_gloss(in0.x), phong_gloss_from_power(phong_power_from_gloss(in0.x)), 0.0)",
               G, G, in0, NULL, out));
    double worst_f = 0, worst_p = 0, worst_g = 0;
    for (int i = 0; i < G * G; i++) {
        double x = in0[i * 4], g = x < 0 ? 0 : x > 1 ? 1 : x;
        worst_f = fmax(worst_f, fabs(out[i * 4] - schlick(x)));
        worst_p = fmax(worst_p, fabs(out[i * 4 + 1] - pow(2, 12 * g)) / pow(2, 12 * g));
        worst_g = fmax(worst_g, fabs(out[i * 4 + 2] - g));
    }
    CHECK_MSG(worst_f < 1e-6, "Schlick differs from C by %g", worst_f);
    CHECK_MSG(worst_p < 1e-5, "2^(12 gloss) differs from C by %g (relative)", worst_p);
    CHECK_MSG(worst_g < 1e-5, "gloss round trip off by %g", worst_g);
    /* stated values: F(1) = F0 = 0.04 exactly, F(0) = F(−x) = 1; gloss 0.5 → 64, 0 → 1, 1 → 4096 */
    float pts[4 * 4] = {1, 0.5f, 0, 0, 0, 0, 0, 0, -0.3f, 1, 0, 0, 0.5f, 0, 0, 0};
    CHECK(eval("vec4(phong_schlick(in0.x), phong_power_from_gloss(in0.y), 0.0, 0.0)", 4, 1, pts, NULL, out));
    CHECK_NEAR(out[0], 0.04, 1e-7);
    CHECK_NEAR(out[1], 64, 1e-4);
    CHECK_NEAR(out[4], 1, 1e-7);
    CHECK_NEAR(out[5], 1, 1e-6);
    CHECK_NEAR(out[8], 1, 1e-7);
    CHECK_NEAR(out[9], 4096, 1e-2);
    printf("Schlick: F(n.v = 1) = %.7f, F(0) = %.7f; SpecPower(gloss 0.5) = %.4f\n", out[0], out[4], out[1]);

    /* α ↔ power (Walter 2007): round trip over p ∈ [1, 4096] */
    for (int i = 0; i < G * G; i++) in0[i * 4] = (float)pow(2, 12.0 * i / (G * G - 1));
    CHECK(eval("vec4(phong_power_from_alpha(phong_alpha_from_power(in0.x)), phong_alpha_from_power(in0.x), 0.0, 0.0)", G, G,
               in0, NULL, out));
    double worst = 0;
    for (int i = 0; i < G * G; i++) {
        worst = fmax(worst, fabs(out[i * 4] - in0[i * 4]) / in0[i * 4]);
        CHECK(fabs(out[i * 4 + 1] - sqrt(2 / (in0[i * 4] + 2.0))) < 1e-6);
    }
    CHECK_MSG(worst < 1e-4, "power -> alpha -> power off by %g (relative)", worst);

    /* Toksvig: ft·p with ft = |N|/(|N| + p(1 − |N|)); |N| = 1 leaves p unchanged */
    for (int i = 0; i < G * G; i++) in0[i * 4] = (float)pow(2, 12 * frand()), in0[i * 4 + 1] = (float)(0.5 + 0.5 * frand());
    in0[1] = 1;
    CHECK(eval("vec4(phong_toksvig_power(in0.x, in0.y), 0.0, 0.0, 0.0)", G, G, in0, NULL, out));
    worst = 0;
    for (int i = 0; i < G * G; i++) {
        double p = in0[i * 4], len = in0[i * 4 + 1], e = p * len / (len + p * (1 - len));
        worst = fmax(worst, fabs(out[i * 4] - e) / e);
    }
    CHECK_MSG(worst < 1e-5, "Toksvig differs from C by %g (relative)", worst);
    CHECK_NEAR(out[0], in0[0], 1e-3 * in0[0]);
}

/* ∫ over the hemisphere of h of (p+1)/2·cos^p θ dω = 2π ∫_0^1 (p+1)/2 μ^p dμ = π. Evaluated on a
 * grid of μ = 1 − x⁴ (dense near 1, where high powers live), integrated in C (trapezoid in x). */
static double lobe_integral(int row) {
    double sum = 0;
    for (int i = 0; i < NL; i++) {
        double x0 = (double)i / (NL - 1);
        double f = lout[(row * NL + i) * 4] * 4 * x0 * x0 * x0; /* dμ = 4x³ dx */
        sum += (i == 0 || i == NL - 1) ? 0.5 * f : f;
    }
    return 2 * M_PI * sum / (NL - 1);
}

static void test_normalisation(void) {
    const double powers[8] = {0, 1, 2, 8, 64, 256, 1024, 4096};
    for (int r = 0; r < 8; r++)
        for (int i = 0; i < NL; i++) {
            double x = (double)i / (NL - 1);
            lin0[(r * NL + i) * 4] = (float)(1 - x * x * x * x);
            lin0[(r * NL + i) * 4 + 1] = (float)powers[r];
        }
    CHECK(eval("vec4(phong_blinn_lobe(in0.x, in0.y), 0.0, 0.0, 0.0)", NL, 8, lin0, NULL, lout));
    for (int r = 0; r < 8; r++) {
        double I = lobe_integral(r);
        CHECK_MSG(fabs(I - M_PI) / M_PI < 2e-3, "p = %g: integral of the lobe over the hemisphere %.6f != pi", powers[r], I);
        printf("p = %6g: integral of (p+1)/2 cos^p over the hemisphere of h = %.6f (pi = %.6f)\n", powers[r], I, M_PI);
    }
    /* mutant: the (p+2)/2 normalisation (the one for ∫ D (n·h) dω = 1) must fail the test */
    CHECK(eval("vec4((in0.y + 2.0) * 0.5 * pow(in0.x, in0.y), 0.0, 0.0, 0.0)", NL, 8, lin0, NULL, lout));
    int failing = 0;
    for (int r = 0; r < 8; r++) failing += fabs(lobe_integral(r) - M_PI) / M_PI >= 2e-3;
    CHECK_MSG(failing >= 6, "the mutant (p+2)/2 lobe passes the normalisation test for %d of 8 powers", 8 - failing);
}

/* Both models over random configurations. They only use dot products and normalised sums, so
 * n = +Z is general: v and l range over the whole sphere (normals facing away from the viewer,
 * light behind the surface included). in0 = (v, gloss), in1 = (l, albedo). */
static void test_models(void) {
    for (int i = 0; i < G * G; i++) {
        double v[3], l[3];
        unit_random(v, false), unit_random(l, false);
        if (i % 3 == 0) { /* near-mirror configurations, where high powers are non-zero */
            double jitter[3];
            unit_random(jitter, false);
            l[0] = -v[0] + 0.05 * jitter[0], l[1] = -v[1] + 0.05 * jitter[1], l[2] = v[2] + 0.05 * jitter[2];
            double ll = sqrt(dot3(l, l));
            for (int c = 0; c < 3; c++) l[c] /= ll;
        }
        for (int c = 0; c < 3; c++) in0[i * 4 + c] = (float)v[c], in1[i * 4 + c] = (float)l[c];
        in0[i * 4 + 3] = (float)frand();
        in1[i * 4 + 3] = (float)(0.05 + 0.9 * frand());
    }
    CHECK(eval("vec4(phong_blinn_gloss(vec3(0,0,1), in0.xyz, in1.xyz, vec3(in1.w), phong_power_from_gloss(in0.w), 0.7, vec3(2.0)).x,"
               " phong_classic(vec3(0,0,1), in0.xyz, in1.xyz, vec3(in1.w), vec3(0.6), 1.0 + 99.0 * in0.w, vec3(2.0)).x,"
               " phong_blinn_gloss_filtered(vec3(0,0,1), in0.xyz, in1.xyz, vec3(in1.w), phong_power_from_gloss(in0.w), 0.7,"
               " vec3(2.0), fract(in0.w * 7.0)).x,"
               " phong_blinn_gloss_filtered(vec3(0,0,1), in0.xyz, in1.xyz, vec3(in1.w), phong_power_from_gloss(in0.w), 0.7,"
               " vec3(2.0), 0.0).x - phong_blinn_gloss(vec3(0,0,1), in0.xyz, in1.xyz, vec3(in1.w), phong_power_from_gloss(in0.w),"
               " 0.7, vec3(2.0)).x)", G, G, in0, in1, out));
    const double n[3] = {0, 0, 1};
    double worst[3] = {0, 0, 0};
    long nonfinite = 0, negative = 0, lit = 0, away = 0, w0_diff = 0;
    for (int i = 0; i < G * G; i++) {
        double v[3] = {in0[i * 4], in0[i * 4 + 1], in0[i * 4 + 2]}, l[3] = {in1[i * 4], in1[i * 4 + 1], in1[i * 4 + 2]};
        double g = in0[i * 4 + 3], a = in1[i * 4 + 3], p = pow(2, 12 * g);
        double w = 7 * g - floor(7 * g);
        double e[3] = {c_blinn(n, v, l, a, p, 0.7, 2, 0), c_classic(n, v, l, a, 0.6, 1 + 99 * g, 2), c_blinn(n, v, l, a, p, 0.7, 2, w)};
        for (int k = 0; k < 3; k++) {
            float o = out[i * 4 + k];
            nonfinite += !isfinite(o);
            negative += o < 0;
            /* float rounding of n·h (a few 1e-8) is amplified by the power: relative tolerance
             * 1e-4 + 3e-7·p, i.e. 1.3e-3 at p = 4096 */
            double p_k = k == 1 ? 1 + 99 * g : p;
            worst[k] = fmax(worst[k], fabs(o - e[k]) / fmax(e[k], 1e-2) / (1e-4 + 3e-7 * p_k));
        }
        w0_diff += fabs(out[i * 4 + 3]) > 1e-6 * fmax(e[0], 1e-2); /* w = 0: the assignment's formula */
        lit += e[0] > 0;
        away += v[2] < 0;
    }
    CHECK(nonfinite == 0);
    CHECK(negative == 0);
    CHECK(w0_diff == 0);
    CHECK_MSG(lit > G * G / 4 && away > G * G / 4, "grid too easy: %ld lit, %ld facing away", lit, away);
    CHECK_MSG(worst[0] <= 1, "blinn-gloss differs from C by %g x the tolerance", worst[0]);
    CHECK_MSG(worst[1] <= 1, "classic Phong differs from C by %g x the tolerance", worst[1]);
    CHECK_MSG(worst[2] <= 1, "filtered blinn-gloss differs from C by %g x the tolerance", worst[2]);
    printf("models over %d random configurations (%ld lit, %ld facing away): worst error / tolerance (1e-4 + 3e-7 p, "
           "relative): blinn %.2f, classic %.2f, filtered %.2f\n", G * G, lit, away, worst[0], worst[1], worst[2]);
}

/* Stability: gloss 0 and 1, grazing light, light behind, v below the surface, l = −v (no half
 * vector), l = v; each with a stated value computed in C, none NaN/Inf or negative. */
static void test_stability(void) {
    typedef struct { const char *what; double v[3], l[3], gloss; } cfg;
    const double s45 = sqrt(0.5);
    const cfg cases[] = {
        {"gloss 1 (SpecPower 4096), mirror", {0, s45, s45}, {0, -s45, s45}, 1.0},
        {"gloss 0 (SpecPower 1), mirror", {0, s45, s45}, {0, -s45, s45}, 0.0},
        {"gloss 1, 2 deg off the mirror", {0, s45, s45}, {0, -0.731354, 0.681998}, 1.0},
        {"grazing light (n.l = 1e-4)", {0, s45, s45}, {0, -0.99999999, 1e-4}, 0.5},
        {"light behind (n.l = -0.3)", {0, s45, s45}, {0, 0.953939, -0.3}, 0.5},
        {"view below the surface (n.v = -0.2)", {0, 0.979796, -0.2}, {0, -s45, s45}, 0.5},
        {"l = -v (no half vector)", {0, 0.6, 0.8}, {0, -0.6, -0.8}, 0.5},
        {"l = v, grazing (n.v = 1e-3)", {0, 0.9999995, 1e-3}, {0, 0.9999995, 1e-3}, 1.0},
    };
    int nc = sizeof cases / sizeof *cases;
    for (int i = 0; i < nc; i++) {
        for (int c = 0; c < 3; c++) in0[i * 4 + c] = (float)cases[i].v[c], in1[i * 4 + c] = (float)cases[i].l[c];
        in0[i * 4 + 3] = (float)cases[i].gloss, in1[i * 4 + 3] = 0.5f;
    }
    CHECK(eval("vec4(phong_blinn_gloss(vec3(0,0,1), in0.xyz, in1.xyz, vec3(in1.w), phong_power_from_gloss(in0.w), 1.0, vec3(3.14159265)).x,"
               " phong_classic(vec3(0,0,1), in0.xyz, in1.xyz, vec3(in1.w), vec3(0.5), 1.0 + 4095.0 * in0.w, vec3(3.14159265)).x,"
               " phong_blinn_gloss_ambient(vec3(0,0,1), in0.xyz, vec3(in1.w), 0.4, vec3(3.14159265)).x,"
               " phong_blinn_gloss_filtered(vec3(0,0,1), in0.xyz, in1.xyz, vec3(in1.w), phong_power_from_gloss(in0.w), 1.0, vec3(3.14159265), 1.0).x)",
               nc, 1, in0, in1, out));
    const double n[3] = {0, 0, 1};
    for (int i = 0; i < nc; i++) {
        const cfg *k = &cases[i];
        double p = pow(2, 12 * k->gloss);
        double eb = c_blinn(n, k->v, k->l, 0.5, p, 1, M_PI, 0), ec = c_classic(n, k->v, k->l, 0.5, 0.5, 1 + 4095 * k->gloss, M_PI);
        double ea = (1 - schlick(k->v[2])) * 0.5 * 0.4, ef = c_blinn(n, k->v, k->l, 0.5, p, 1, M_PI, 1);
        for (int c = 0; c < 4; c++) {
            CHECK_MSG(isfinite(out[i * 4 + c]) && out[i * 4 + c] >= 0, "%s: component %d = %g", k->what, c, out[i * 4 + c]);
        }
        double tol = 1e-4 + 3e-7 * p;
        CHECK_MSG(fabs(out[i * 4] - eb) <= tol * fmax(eb, 1), "%s: blinn %g, C %g", k->what, out[i * 4], eb);
        CHECK_MSG(fabs(out[i * 4 + 1] - ec) <= tol * fmax(ec, 1), "%s: classic %g, C %g", k->what, out[i * 4 + 1], ec);
        CHECK_MSG(fabs(out[i * 4 + 2] - ea) <= 1e-5, "%s: ambient %g, C %g", k->what, out[i * 4 + 2], ea);
        CHECK_MSG(fabs(out[i * 4 + 3] - ef) <= tol * fmax(ef, 1), "%s: filtered %g, C %g", k->what, out[i * 4 + 3], ef);
        printf("%-38s blinn %10.5f  classic %9.5f  ambient %.5f  (stated: C values)\n", k->what, out[i * 4], out[i * 4 + 1],
               out[i * 4 + 2]);
    }
    /* stated non-trivial values: the mirror peaks (E = π, albedo 0.5, k_s 1): gloss 1 gives
     * (1−F)·0.5·cos45° + F·2048.5·cos45°, F = Schlick(cos 45°) */
    double F = schlick(s45);
    CHECK_NEAR(out[0], ((1 - F) * 0.5 + F * 2048.5) * s45, 2e-3 * 2048 * s45 * F);
    CHECK_NEAR(out[4], ((1 - F) * 0.5 + F * 1.0) * s45, 1e-5); /* gloss 0: lobe (1+1)/2·1 */
    CHECK(out[0] > 100 * out[4]);
    /* behind / no half vector / below: 0 direct light but the ambient term is (1−F)·albedo·AO > 0 */
    CHECK(out[4 * 4] == 0 && out[4 * 4 + 2] > 0.05);
    CHECK(out[6 * 4] == 0); /* l = −v: n·l < 0 here */
    CHECK(out[5 * 4 + 2] == 0); /* n·v < 0: F = 1, (1−F)·ambient = 0 (the formula's own limit) */
}

/* ---- the lobe description: one GGX lobe for light integrators --------------------------- */
static double ggx_d(double c, double a) {
    if (c <= 0) return 0;
    double d = c * c * (a * a - 1) + 1;
    return a * a / (M_PI * d * d);
}
static double smith_g1(double c, double a) { return c > 0 ? 2 / (1 + sqrt(1 + a * a * (1 - c * c) / (c * c))) : 0; }
static double median_alpha(double p) { return sqrt(expm1(M_LN2 * 2 / (p + 2))); }
/* ∫ f cos θ_l dl of blinn-gloss's specular lobe (ggx = false: (p+1)/(2π)(n·h)^p, per unit F·k_s)
 * or of a GGX lobe (D G₁(v)G₁(l)/(4 n·v)) at n·v = μ: midpoint quadrature over l in polar
 * coordinates about the mirror direction r, ψ = 2 atan(k x/(1 − x)) crowding the nodes into
 * the lobe (k its width), cut at the horizon */
static double lobe_albedo(bool ggx, double mu, double p, double a) {
    const int nt = 500, np = 128;
    double v[3] = {sqrt(1 - mu * mu), 0, mu}, r[3] = {-v[0], 0, mu}, t1[3] = {mu, 0, v[0]}, k = sqrt(2 / (p + 2)), sum = 0;
    for (int i = 0; i < nt; i++) {
        double x = (i + 0.5) / nt, u = x / (1 - x), psi = 2 * atan(k * u);
        double dpsi = 2 * k / (1 + k * k * u * u) / ((1 - x) * (1 - x)) / nt;
        for (int j = 0; j < np; j++) {
            double ph = (j + 0.5) / np * 2 * M_PI, cs = cos(psi), sn = sin(psi);
            double l[3] = {cs * r[0] + sn * cos(ph) * t1[0], sn * sin(ph), cs * r[2] + sn * cos(ph) * t1[2]};
            if (l[2] <= 0) continue;
            double hv[3] = {l[0] + v[0], l[1] + v[1], l[2] + v[2]}, ndh = hv[2] / sqrt(dot3(hv, hv));
            double f = ggx ? ggx_d(ndh, a) * smith_g1(mu, a) * smith_g1(l[2], a) / (4 * mu)
                           : (p + 1) / (2 * M_PI) * pow(fmax(ndh, 0), p) * l[2];
            sum += f * sn * dpsi * (2 * M_PI / np);
        }
    }
    return sum;
}
static void test_lobe_description(void) {
    /* α: Blinn's median, √(2^(2/(p+2)) − 1), p from 0 to 10⁵ (past gloss 1, through s.alpha) */
    for (int i = 0; i < G; i++) in0[i * 4] = (float)(exp2(17.0 * i / (G - 1)) - 1);
    CHECK(eval("vec4(sl_lobe_blinn_alpha(in0.x), 0.0, 0.0, 0.0)", G, 1, in0, NULL, out));
    double worst = 0;
    for (int i = 0; i < G; i++) worst = fmax(worst, fabs(out[i * 4] / median_alpha(in0[i * 4]) - 1));
    CHECK_MSG(worst < 2e-5, "sl_lobe_blinn_alpha differs from sqrt(2^(2/(p+2)) - 1) by %g (relative)", worst);
    /* the contract's inverse (ABI 1.19, what integrators read a Blinn-Phong lobe's power from):
     * p = 2/log2(1 + α²) − 2 against C, and the round trip p → α → p, p from 1 to 10⁵ */
    for (int i = 0; i < G; i++) in0[i * 4] = (float)exp2(17.0 * i / (G - 1)), in0[i * 4 + 1] = (float)median_alpha(in0[i * 4]);
    CHECK(eval("vec4(sl_lobe_blinn_power(in0.y), sl_lobe_blinn_power(sl_lobe_blinn_alpha(in0.x)), 0.0, 0.0)", G, 1, in0, NULL,
               out));
    double worst_p = 0, worst_trip = 0;
    for (int i = 0; i < G; i++) {
        double a = in0[i * 4 + 1], want = 2 / log2(1 + a * a) - 2;
        worst_p = fmax(worst_p, fabs(out[i * 4] / want - 1));
        worst_trip = fmax(worst_trip, fabs(out[i * 4 + 1] / in0[i * 4] - 1));
    }
    CHECK_MSG(worst_p < 1e-4, "sl_lobe_blinn_power differs from 2/log2(1 + a^2) - 2 by %g (relative)", worst_p);
    CHECK_MSG(worst_trip < 1e-3, "sl_lobe_blinn_power(sl_lobe_blinn_alpha(p)) differs from p by %g (relative)", worst_trip);
    /* … which is the median: half of GGX's projected area within θ½, where Blinn's CDF
     * 1 − cos^(p+2) θ is ½ (trapezoid over θ of D_GGX cos θ sin θ 2π) */
    const double pm[3] = {1, 64, 2000};
    for (int k = 0; k < 3; k++) {
        double a = median_alpha(pm[k]), th = acos(exp2(-1 / (pm[k] + 2))), sum = 0;
        for (int i = 0; i < 20000; i++) {
            double t = (i + 0.5) / 20000 * th;
            sum += ggx_d(cos(t), a) * cos(t) * sin(t) * 2 * M_PI * th / 20000;
        }
        CHECK_MSG(fabs(sum - 0.5) < 1e-4, "p = %g: GGX's projected area within Blinn's median angle %.6f", pm[k], sum);
    }
    /* weight: the model's specular albedo over the lobe's, R(μ, p)/E(μ, α), at gloss 0 … 1 and
     * μ = 0.1 … 1 (the fit's domain); the old centre-of-lobe weight 4μ²(p+1)/((p+2)G₁(μ)²) at
     * Walter's α must fail the same bound */
    enum { NG = 9, NM = 7 };
    for (int g = 0; g < NG; g++)
        for (int m = 0; m < NM; m++) {
            int i = g * NM + m;
            in0[i * 4] = (float)(0.1 + 0.9 * m / (NM - 1)), in0[i * 4 + 1] = (float)exp2(12.0 * g / (NG - 1));
        }
    CHECK(eval("vec4(phong_lobe_weight(in0.x, sl_lobe_blinn_alpha(in0.y)), sl_lobe_blinn_alpha(in0.y), 0.0, 0.0)", NG * NM, 1, in0,
               NULL, out));
    double worst_w = 0, worst_old = 0;
    for (int i = 0; i < NG * NM; i++) {
        double mu = in0[i * 4], p = in0[i * 4 + 1], a = out[i * 4 + 1], R = lobe_albedo(false, mu, p, 0);
        double want = R / lobe_albedo(true, mu, p, a), aw = sqrt(2 / (p + 2)), g1 = smith_g1(mu, aw);
        double old = 4 * mu * mu * (p + 1) / ((p + 2) * g1 * g1) * lobe_albedo(true, mu, p, aw) / R;
        worst_w = fmax(worst_w, fabs(out[i * 4] / want - 1));
        worst_old = fmax(worst_old, fabs(old - 1));
    }
    printf("lobe weight over %d (gloss, n.v): worst relative error %.4f (the centre-of-lobe weight: %.4f)\n", NG * NM,
           worst_w, worst_old);
    CHECK_MSG(worst_w < 0.025, "phong_lobe_weight is %.4f off the ratio of the albedos", worst_w);
    CHECK_MSG(worst_old >= 0.025, "the mutant (centre-of-lobe weight) passes: %.4f", worst_old);
    /* stability: μ ≤ 0 → 0; μ → 0, p = 0 and p = 10⁶: finite, ≥ 0 */
    float edge[6 * 4] = {0, 64, 0, 0, -0.3f, 64, 0, 0, 1e-4f, 64, 0, 0, 0.02f, 0, 0, 0, 1e-4f, 1e6f, 0, 0, 1, 1e6f, 0, 0};
    CHECK(eval("vec4(phong_lobe_weight(in0.x, sl_lobe_blinn_alpha(in0.y)), 0.0, 0.0, 0.0)", 6, 1, edge, NULL, out));
    CHECK(out[0] == 0 && out[4] == 0);
    for (int i = 2; i < 6; i++) CHECK_MSG(isfinite(out[i * 4]) && out[i * 4] >= 0, "edge %d: weight %g", i, out[i * 4]);
    CHECK_NEAR(out[5 * 4], 4.0, 0.02); /* a mirror-sharp lobe at μ = 1: 4μ²/G₁² = 4 */
}

int main(void) {
    h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 8, .height = 8, .plugins = PH,
                                             .strict = true},
                          err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return check_result();
    test_fresnel_and_gloss();
    test_normalisation();
    test_models();
    test_stability();
    test_lobe_description();
    sl_harness_destroy(h);
    return check_result();
}
