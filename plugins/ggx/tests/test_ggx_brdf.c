/* GLSL unit tests of the GGX BRDF terms the ggx plugin shades with (the SDK shader library's
 * shaders/ggx_brdf.glsl, `#include "sl:ggx_brdf.glsl"`, evaluated on the GL path),
 * against closed forms and numerical integration in C. */
#include "check.h"
#include <shadelab/harness.h>
#include <stdlib.h>

#define N 256
static sl_harness *h;
static float in0[N * N * 4], in1[N * N * 4], out[N * N * 4];

static bool eval(const char *expr, const char *defines) {
    char err[8192];
    const char *files[] = {"sl:ggx_brdf.glsl", NULL};
    sl_glsl_eval_desc d = {.struct_size = sizeof d, .plugin = "ggx", .files = files, .expression = expr,
                           .defines = defines, .width = N, .height = N, .in0 = in0, .in1 = in1};
    bool ok = sl_harness_eval_glsl(h, &d, out, err, sizeof err);
    if (!ok) fprintf(stderr, "eval %s: %s\n", expr, err);
    return ok;
}

/* ∫ D(h)(n·h) dω over the hemisphere, θ = (π/2)t² so samples concentrate near the peak. */
static double d_integral(float alpha, const char *defines) {
    for (int i = 0; i < N * N; i++) {
        double t = (i + 0.5) / (N * N);
        in0[i * 4 + 0] = (float)cos(M_PI / 2 * t * t);
        in0[i * 4 + 1] = alpha;
    }
    if (!eval("vec4(ggx_D(in0.x, in0.y))", defines)) return -1;
    double sum = 0, dt = 1.0 / (N * N);
    for (int i = 0; i < N * N; i++) {
        double t = (i + 0.5) / (N * N), th = M_PI / 2 * t * t;
        sum += out[i * 4] * cos(th) * sin(th) * (M_PI * t) * dt;
    }
    return 2 * M_PI * sum;
}

static double fresnel_exact_c(double c, double eta) {
    c = fabs(c);
    double b2 = 1 / (eta * eta) + c * c - 1;
    if (b2 < 0) return 1;
    double b = sqrt(b2), rs = (c - b) / (c + b), rp = (eta * eta * b - c) / (eta * eta * b + c);
    return 0.5 * (rs * rs + rp * rp);
}

static double d_c(double nh, double a) {
    if (nh <= 0) return 0;
    double t2 = (1 - nh * nh) / (nh * nh);
    return a * a / (M_PI * pow(nh, 4) * pow(a * a + t2, 2));
}

/* D over the pixel's footprint (ggx_D_footprint): GGX's slope density P(m) = α²/(π(α² + |m|²)²)
 * averaged over the disk of slopes of radius s (s² the footprint) centred at the half vector's
 * slope, tan θ_h away, by the midpoint rule in polar coordinates about the centre, over cos⁴θ_h. */
static double d_footprint_c(double nh, double a, double s2) {
    const int NR = 400, NA = 400;
    double t = sqrt(1 - nh * nh) / nh, s = sqrt(s2), sum = 0;
    for (int i = 0; i < NR; i++)
        for (int j = 0; j < NA; j++) {
            double r = s * (i + 0.5) / NR, ph = 2 * M_PI * (j + 0.5) / NA;
            double m2 = t * t + 2 * t * r * cos(ph) + r * r;
            sum += a * a / (M_PI * (a * a + m2) * (a * a + m2)) * r;
        }
    return sum * (s / NR) * (2 * M_PI / NA) / (M_PI * s2) / pow(nh, 4);
}

static double g1_c(const double x[3], const double n[3], const double hh[3], double a) {
    double xn = x[0] * n[0] + x[1] * n[1] + x[2] * n[2], xh = x[0] * hh[0] + x[1] * hh[1] + x[2] * hh[2];
    if (xn == 0 || xh / xn <= 0) return 0;
    double t2 = (1 - xn * xn) / (xn * xn);
    return 2 / (1 + sqrt(1 + a * a * t2));
}

int main(void) {
    char err[4096];
    h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 8, .height = 8,
                                             .plugins = (const char *[]){"ggx", NULL}, .strict = true},
                          err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return check_result();

    /* D is normalised: ∫ D (n·h) dω = 1 within 1% */
    const float alphas[] = {0.05f, 0.1f, 0.3f, 0.6f, 1.0f};
    for (int k = 0; k < 5; k++) {
        double I = d_integral(alphas[k], NULL);
        printf("alpha %.2f: integral of D(h)(n.h) = %.5f\n", alphas[k], I);
        CHECK_MSG(fabs(I - 1) < 0.01, "alpha %.2f: %.5f", alphas[k], I);
    }
    /* mutation: α in place of α² in the numerator must fail the same test */
    double mutant = d_integral(0.3f, "GGX_MUTATE_D 1");
    printf("mutant D (alpha for alpha^2), alpha 0.3: %.5f\n", mutant);
    CHECK_MSG(fabs(mutant - 1) > 0.05, "the normalisation test does not catch the mutant (%.5f)", mutant);

    /* D against the tan² form in C */
    for (int i = 0; i < N * N; i++) {
        in0[i * 4 + 0] = (float)(i + 0.5) / (N * N);
        in0[i * 4 + 1] = 0.02f + 0.98f * (float)(i % 97) / 96;
    }
    CHECK(eval("vec4(ggx_D(in0.x, in0.y))", NULL));
    double worst = 0;
    for (int i = 0; i < N * N; i++) {
        double e = d_c(in0[i * 4], in0[i * 4 + 1]);
        double rel = fabs(out[i * 4] - e) / (e + 1e-6);
        if (rel > worst) worst = rel;
    }
    CHECK_MSG(worst < 1e-3, "D vs C: relative %g", worst);

    /* D over the pixel's footprint (a point or spot light of the light loop) against the disk
     * average in C, on both sides of its two forms (the footprint narrower and wider than the lobe
     * at the half vector), and D itself where the footprint is negligible */
    const double fp_cases[][3] = {{0.999, 0.01, 1e-4}, {0.9999, 0.01, 1e-3}, {0.98, 0.05, 0.002}, {0.95, 0.3, 0.01},
                                  {0.7, 0.5, 0.05}, {0.999, 0.2, 0.3}, {0.6, 0.1, 0.2}, {0.9, 0.3, 1e-9}};
    const int nfp = (int)(sizeof fp_cases / sizeof *fp_cases);
    for (int i = 0; i < nfp; i++)
        for (int k = 0; k < 3; k++) in0[i * 4 + k] = (float)fp_cases[i][k];
    CHECK(eval("sl_normal_footprint = in0.z, vec4(ggx_D_footprint(in0.x, in0.y))", NULL));
    for (int i = 0; i < nfp; i++) {
        double e = d_footprint_c(fp_cases[i][0], fp_cases[i][1], fp_cases[i][2]);
        double plain = d_c(fp_cases[i][0], fp_cases[i][1]);
        printf("D over a footprint of %g, n.h %g, alpha %g: %.6g (C %.6g; D itself %.6g)\n", fp_cases[i][2],
               fp_cases[i][0], fp_cases[i][1], out[i * 4], e, plain);
        CHECK_MSG(fabs(out[i * 4] - e) < 2e-3 * e + 1e-6, "footprint %g, n.h %g, alpha %g: %g against %g",
                  fp_cases[i][2], fp_cases[i][0], fp_cases[i][1], out[i * 4], e);
    }

    /* Masking normalisation (Heitz 2014): ∫ G1(v,h) max(0, v·h) D(h) dω_h = n·v, within 2% */
    const float mask_alphas[] = {0.1f, 0.3f, 0.6f, 1.0f};
    const float view_deg[] = {0, 30, 60, 80};
    const int MT = 512, MP = 128; /* θ × φ samples = N*N */
    for (int a = 0; a < 4; a++)
        for (int v = 0; v < 4; v++) {
            double tv = view_deg[v] * M_PI / 180;
            for (int j = 0; j < MT; j++)
                for (int k = 0; k < MP; k++) {
                    int i = j * MP + k;
                    double t = (j + 0.5) / MT, th = M_PI / 2 * t * t, ph = 2 * M_PI * (k + 0.5) / MP;
                    in0[i * 4 + 0] = (float)(sin(th) * cos(ph));
                    in0[i * 4 + 1] = (float)(sin(th) * sin(ph));
                    in0[i * 4 + 2] = (float)cos(th);
                    in1[i * 4 + 0] = (float)sin(tv);
                    in1[i * 4 + 1] = 0;
                    in1[i * 4 + 2] = (float)cos(tv);
                    in1[i * 4 + 3] = mask_alphas[a];
                }
            CHECK(eval("vec4(ggx_G1(in1.xyz, vec3(0.0, 0.0, 1.0), in0.xyz, in1.w) * max(0.0, dot(in1.xyz, in0.xyz))"
                       " * ggx_D(in0.z, in1.w))", NULL));
            double sum = 0;
            for (int j = 0; j < MT; j++)
                for (int k = 0; k < MP; k++) {
                    double t = (j + 0.5) / MT, th = M_PI / 2 * t * t;
                    sum += out[(j * MP + k) * 4] * sin(th) * (M_PI * t / MT) * (2 * M_PI / MP);
                }
            double rel = fabs(sum - cos(tv)) / cos(tv);
            CHECK_MSG(rel < 0.02, "masking: alpha %.1f view %g deg: %.5f vs n.v %.5f", mask_alphas[a], view_deg[v], sum, cos(tv));
        }
    /* the same integral with the half-vector G1 variant is not normalised: the test can tell them apart */
    {
        double tv = 60 * M_PI / 180;
        CHECK(eval("vec4(ggx_G1(in1.xyz, vec3(0.0, 0.0, 1.0), in0.xyz, in1.w) * max(0.0, dot(in1.xyz, in0.xyz))"
                   " * ggx_D(in0.z, in1.w))", "GGX_G1_HALF_VECTOR 1"));
        double sum = 0;
        for (int j = 0; j < MT; j++)
            for (int k = 0; k < MP; k++) {
                double t = (j + 0.5) / MT, th = M_PI / 2 * t * t;
                sum += out[(j * MP + k) * 4] * sin(th) * (M_PI * t / MT) * (2 * M_PI / MP);
            }
        printf("half-vector G1 variant, alpha 1.0, view 60 deg: %.4f (n.v = %.4f)\n", sum, cos(tv));
        CHECK(fabs(sum - cos(tv)) / cos(tv) > 0.02);
    }

    /* G1 ≤ 1 and G1 against C on random directions */
    srand(7);
    for (int i = 0; i < N * N; i++) {
        double x[3], hh[3], n[3] = {0, 0, 1};
        for (int c = 0; c < 3; c++) { x[c] = rand() / (double)RAND_MAX * 2 - 1; hh[c] = rand() / (double)RAND_MAX * 2 - 1; }
        double lx = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), lh = sqrt(hh[0] * hh[0] + hh[1] * hh[1] + hh[2] * hh[2]);
        for (int c = 0; c < 3; c++) { x[c] /= lx; hh[c] /= lh; in0[i * 4 + c] = (float)x[c]; in1[i * 4 + c] = (float)hh[c]; }
        in0[i * 4 + 3] = 0.05f + 0.95f * (float)(i % 31) / 30;
        (void)n;
    }
    CHECK(eval("vec4(ggx_G1(in0.xyz, vec3(0.0, 0.0, 1.0), in1.xyz, in0.w))", NULL));
    worst = 0;
    double gmax = 0;
    for (int i = 0; i < N * N; i++) {
        double x[3] = {in0[i * 4], in0[i * 4 + 1], in0[i * 4 + 2]}, hh[3] = {in1[i * 4], in1[i * 4 + 1], in1[i * 4 + 2]};
        double n[3] = {0, 0, 1};
        double e = g1_c(x, n, hh, in0[i * 4 + 3]);
        if (fabs(out[i * 4] - e) > worst) worst = fabs(out[i * 4] - e);
        if (out[i * 4] > gmax) gmax = out[i * 4];
    }
    CHECK_MSG(worst < 1e-3, "G1 vs C: %g", worst);
    CHECK_MSG(gmax <= 1.0 + 1e-6, "G1 exceeds 1: %g", gmax);

    /* Fresnel: exact vs C; normal incidence; ≥ 0.9 at 89°; total internal reflection; Schlick error */
    const float etas[] = {1.0f / 1.5f, 1.0f / 1.33f, 1.5f};
    for (int e = 0; e < 3; e++) {
        for (int i = 0; i < N * N; i++) {
            in0[i * 4 + 0] = (float)(i + 1) / (N * N); /* c in (0, 1] */
            in0[i * 4 + 1] = etas[e];
        }
        CHECK(eval("vec4(ggx_fresnel_exact(in0.x, in0.y), ggx_fresnel_schlick(in0.x, vec3(ggx_f0_from_eta(in0.y))).x, 0.0, 0.0)", NULL));
        worst = 0;
        double schlick_err = 0;
        for (int i = 0; i < N * N; i++) {
            double c = in0[i * 4], ex = fresnel_exact_c(c, etas[e]);
            if (fabs(out[i * 4] - ex) > worst) worst = fabs(out[i * 4] - ex);
            if (fabs(out[i * 4 + 1] - ex) > schlick_err) schlick_err = fabs(out[i * 4 + 1] - ex);
        }
        CHECK_MSG(worst < 1e-4, "exact Fresnel vs C (eta %.3f): %g", etas[e], worst);
        double f0 = pow((1 - etas[e]) / (1 + etas[e]), 2);
        CHECK_NEAR(out[(N * N - 1) * 4], f0, 1e-5); /* c = 1 */
        if (e == 0) {
            printf("max |Schlick - exact| for eta = 1/1.5: %.4f\n", schlick_err);
            /* Schlick's known error for glass peaks near grazing incidence at ~0.036 */
            CHECK_MSG(schlick_err < 0.04, "Schlick error %.4f", schlick_err);
        }
        if (e == 2) { /* inside glass: TIR for c < sqrt(1 - 1/eta^2) */
            int tir = (int)(sqrt(1 - 1 / (1.5 * 1.5)) * N * N) - 10;
            CHECK_NEAR(out[tir * 4], 1.0, 0);
        }
    }
    in0[0] = (float)cos(89 * M_PI / 180);
    in0[1] = 1.0f / 1.5f;
    CHECK(eval("vec4(ggx_fresnel_exact(in0.x, in0.y))", NULL));
    printf("F at 89 degrees (eta 1/1.5): %.4f\n", out[0]);
    CHECK(out[0] >= 0.9f);

    /* the full specular term D G / (4 n.l n.v) against C, and its guards */
    srand(11);
    for (int i = 0; i < N * N; i++) {
        double th_l = acos(rand() / (double)RAND_MAX), th_v = acos(rand() / (double)RAND_MAX);
        double ph = rand() / (double)RAND_MAX * 2 * M_PI;
        in0[i * 4 + 0] = (float)sin(th_l); in0[i * 4 + 1] = 0; in0[i * 4 + 2] = (float)cos(th_l);
        in1[i * 4 + 0] = (float)(sin(th_v) * cos(ph)); in1[i * 4 + 1] = (float)(sin(th_v) * sin(ph)); in1[i * 4 + 2] = (float)cos(th_v);
        in0[i * 4 + 3] = in1[i * 4 + 3] = 0.1f + 0.9f * (float)(i % 19) / 18;
    }
    /* ggx_DG_over_4 has an out parameter: evaluated through a small wrapper */
    const char *files2[] = {"sl:ggx_brdf.glsl", SL_TEST_DATA_DIR "/glsl/ggx_wrappers.glsl", NULL};
    sl_glsl_eval_desc d = {.struct_size = sizeof d, .plugin = "ggx", .files = files2, .width = N, .height = N,
                           .in0 = in0, .in1 = in1, .expression = "vec4(test_ggx_dg(in0.xyz, in1.xyz, in0.w))"};
    CHECK_MSG(sl_harness_eval_glsl(h, &d, out, err, sizeof err), "%s", err);
    worst = 0;
    long bad = 0;
    for (int i = 0; i < N * N; i++) {
        double l[3] = {in0[i * 4], in0[i * 4 + 1], in0[i * 4 + 2]}, v[3] = {in1[i * 4], in1[i * 4 + 1], in1[i * 4 + 2]};
        double n[3] = {0, 0, 1}, hh[3] = {l[0] + v[0], l[1] + v[1], l[2] + v[2]};
        double hl = sqrt(hh[0] * hh[0] + hh[1] * hh[1] + hh[2] * hh[2]);
        for (int c = 0; c < 3; c++) hh[c] /= hl;
        double a = in0[i * 4 + 3];
        if (l[2] < 1e-3 || v[2] < 1e-3) continue; /* the guard region, checked below */
        double e = d_c(hh[2], a) * g1_c(v, n, hh, a) * g1_c(l, n, hh, a) / (4 * l[2] * v[2]);
        double rel = fabs(out[i * 4] - e) / (e + 1e-3);
        if (rel > worst) worst = rel;
        bad += !isfinite(out[i * 4]) || out[i * 4] < 0;
    }
    CHECK_MSG(worst < 2e-3, "DG/4 vs C: relative %g", worst);
    CHECK(bad == 0);

    /* stability grid: α 0 and 1, grazing, behind, facing away — finite, non-negative, non-trivial */
    const float cases[][7] = {
        /* l.xyz, v.xyz, alpha */
        {0, 0, 1, 0, 0, 1, 0.0f},            /* α = 0 (clamped), mirror direction: huge but finite */
        {0, 0, 1, 0, 0, 1, 1.0f},            /* α = 1 */
        {0.99999f, 0, 0.0044f, 0, 0, 1, 0.3f}, /* light grazing */
        {0, 0, -1, 0, 0, 1, 0.3f},           /* light behind */
        {0, 0, 1, 0.6f, 0, -0.8f, 0.3f},     /* viewer below the shading normal (normal map facing away) */
    };
    for (int i = 0; i < 5; i++) {
        for (int c = 0; c < 3; c++) { in0[i * 4 + c] = cases[i][c]; in1[i * 4 + c] = cases[i][3 + c]; }
        in0[i * 4 + 3] = cases[i][6];
    }
    d.width = 5;
    d.height = 1;
    CHECK_MSG(sl_harness_eval_glsl(h, &d, out, err, sizeof err), "%s", err);
    for (int i = 0; i < 5; i++) CHECK_MSG(isfinite(out[i * 4]) && out[i * 4] >= 0, "case %d: %g", i, out[i * 4]);
    printf("alpha 0 mirror peak D G/(4 n.l n.v) = %g (expected 1/(4 pi alpha_min^2) = %g)\n", out[0],
           1 / (4 * M_PI * 2e-3 * 2e-3));
    CHECK_NEAR(out[0] / (1 / (4 * M_PI * 2e-3 * 2e-3)), 1.0, 1e-3);
    CHECK_NEAR(out[4], 1 / (4 * M_PI), 1e-5); /* α = 1, normal incidence: D = 1/π, G = 1 */
    CHECK(out[8] >= 0 && out[8] < 1e3);
    CHECK(out[12] == 0 && out[16] == 0);
    sl_harness_destroy(h);
    return check_result();
}
