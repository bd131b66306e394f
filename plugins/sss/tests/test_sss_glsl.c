/* sss: GLSL unit tests of sss_lib.glsl (evaluated on the GL path) against closed forms written
 * here, and checks of the CPU-side profile code (sss_profile.c) against the published table and
 * independent numerical integration. */
#include "check.h"
#include "../sss_profile.h"
#include <shadelab/harness.h>
#include <stdlib.h>

#define N 64
static sl_harness *h;
static float in0[N * N * 4], in1[N * N * 4], out[N * N * 4];

static bool eval(const char *expr) {
    char err[8192];
    const char *files[] = {"sss_lib.glsl", NULL};
    sl_glsl_eval_desc d = {.struct_size = sizeof d, .plugin = "sss", .files = files, .expression = expr,
                           .width = N, .height = N, .in0 = in0, .in1 = in1};
    bool ok = sl_harness_eval_glsl(h, &d, out, err, sizeof err);
    if (!ok) fprintf(stderr, "eval %s: %s\n", expr, err);
    return ok;
}

/* The published six-Gaussian fit (d'Eon & Luebke 2007, GPU Gems 3 ch. 14), typed in again here
 * so the test does not read the plugin's copy. */
static const double VAR[6] = {0.0064, 0.0484, 0.187, 0.567, 1.99, 7.41};
static const double W[6][3] = {{0.233, 0.455, 0.649}, {0.100, 0.336, 0.344}, {0.118, 0.198, 0.0},
                               {0.113, 0.007, 0.007}, {0.358, 0.004, 0.0},   {0.078, 0.0, 0.0}};

static double smoothstep(double a, double b, double x) {
    double t = (x - a) / (b - a);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return t * t * (3 - 2 * t);
}

int main(void) {
    char err[4096];
    h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 8, .height = 8,
                                             .plugins = (const char *[]){"sss", NULL}, .strict = true},
                          err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return check_result();

    /* slab transmittance Σ wᵢ exp(−d²/2vᵢ): d from −1 (clamped to 0) to 20 mm */
    for (int i = 0; i < N * N; i++) in0[i * 4] = -1.0f + 21.0f * i / (N * N);
    CHECK(eval("vec4(sss_slab_transmittance(in0.x), 0.0)"));
    double worst = 0;
    for (int i = 0; i < N * N; i++) {
        double d = in0[i * 4] < 0 ? 0 : in0[i * 4];
        for (int c = 0; c < 3; c++) {
            double t = 0;
            for (int k = 0; k < 6; k++) t += W[k][c] * exp(-d * d / (2 * VAR[k]));
            worst = fmax(worst, fabs(out[i * 4 + c] - t));
        }
    }
    printf("transmittance: max |GLSL - C| = %.3g\n", worst);
    CHECK(worst < 1e-5);
    CHECK_NEAR(out[0], 1.0, 1e-6); /* d ≤ 0: everything gets through (weights sum to 1) */

    /* wrap lighting factors against Green's formulas */
    for (int i = 0; i < N * N; i++) {
        in0[i * 4] = -1.0f + 2.0f * (i % N) / (N - 1);
        in0[i * 4 + 1] = (float)(i / N) / (N - 1);         /* wrap 0..1 */
        in0[i * 4 + 2] = 0.05f + 0.5f * (i / N) / (N - 1); /* scatter width */
    }
    CHECK(eval("vec4(sss_wrap_factors(in0.x, in0.y, in0.z), 0.0, 0.0)"));
    worst = 0;
    for (int i = 0; i < N * N; i++) {
        double ndl = in0[i * 4], w = in0[i * 4 + 1], sw = in0[i * 4 + 2];
        double diff = fmax(0, (ndl + w) / (1 + w));
        double band = smoothstep(0, sw, diff) * smoothstep(2 * sw, sw, diff);
        worst = fmax(worst, fmax(fabs(out[i * 4] - diff), fabs(out[i * 4 + 1] - band)));
        if (w == 0 && ndl >= 0) CHECK_NEAR(out[i * 4], ndl, 1e-6); /* no wrap: Lambert's cosine */
    }
    printf("wrap: max |GLSL - C| = %.3g\n", worst);
    CHECK(worst < 1e-5);

    /* perspective depth linearisation round trip (n = 0.1, f = 100) */
    {
        double n = 0.1, f = 100, p22 = -(f + n) / (f - n), p32 = -2 * f * n / (f - n);
        for (int i = 0; i < N * N; i++) {
            double D = 0.1 + 99.8 * i / (N * N);
            double ndc = (p22 * -D + p32) / D;
            in0[i * 4] = (float)(0.5 * ndc + 0.5);
            in0[i * 4 + 1] = (float)p22;
            in0[i * 4 + 2] = (float)p32;
            in1[i * 4] = (float)D;
        }
        CHECK(eval("vec4(sss_linear_depth(in0.x, in0.y, in0.z), sss_map_linear_depth(in0.x, 0.1, 100.0, true), 0.0, 0.0)"));
        double rel = 0;
        for (int i = 0; i < N * N; i++) {
            if (in1[i * 4] > 20) continue; /* float depth resolution far away */
            rel = fmax(rel, fabs(out[i * 4] - in1[i * 4]) / in1[i * 4]);
            rel = fmax(rel, fabs(out[i * 4 + 1] - in1[i * 4]) / in1[i * 4]);
        }
        printf("linear depth: max relative error %.3g (D <= 20)\n", rel);
        CHECK(rel < 1e-3);
    }
    sl_harness_destroy(h);

    /* ---- CPU side (sss_profile.c) ---- */
    /* full profile and its line response against ∫ R(√(x²+y²)) dy integrated numerically */
    sss_gaussians full;
    sss_profile_reduce(6, &full);
    CHECK(full.n == 6);
    for (int k = 0; k < 6; k++) {
        CHECK(full.variance[k] == VAR[k]);
        for (int c = 0; c < 3; c++) CHECK(full.weight[k][c] == W[k][c]);
    }
    for (int c = 0; c < 3; c++) {
        double sum = 0;
        for (int k = 0; k < 6; k++) sum += W[k][c];
        CHECK_NEAR(sum, 1.0, 1e-9); /* white profile */
    }
    worst = 0;
    for (double x = 0.25; x < 8; x += 0.5)
        for (int c = 0; c < 3; c++) {
            double line = 0, dy = 0.001;
            for (double y = -30; y < 30; y += dy) {
                double r2 = x * x + y * y, R = 0;
                for (int k = 0; k < 6; k++) R += W[k][c] * exp(-r2 / (2 * VAR[k])) / (2 * M_PI * VAR[k]);
                line += R * dy;
            }
            worst = fmax(worst, fabs(sss_line_response(&full, c, x) - line) / fmax(line, 1e-6));
        }
    printf("line response vs 2D profile integrated along the line: max relative error %.3g\n", worst);
    CHECK(worst < 1e-3);

    /* reduced profiles keep each channel's total weight (white) and get closer with k */
    double previous = INFINITY;
    for (int k = 1; k <= 6; k++) {
        sss_gaussians g;
        sss_profile_reduce(k, &g);
        CHECK(g.n == k);
        double e = 0;
        for (int c = 0; c < 3; c++) {
            double sum = 0;
            for (int i = 0; i < g.n; i++) sum += g.weight[i][c];
            CHECK_NEAR(sum, 1.0, 1e-9);
            for (double x = 0; x < 15; x += 0.01) {
                double d = sss_line_response(&g, c, x) - sss_line_response(&full, c, x);
                e += d * d * 0.01;
            }
        }
        printf("%d Gaussians: L2 error of the line response %.4g\n", k, sqrt(e));
        CHECK(e <= previous + 1e-12);
        previous = e;
    }
    CHECK(previous < 1e-20);

    /* blur taps: 7 reproduce d'Eon & Luebke's 0.006, 0.061, 0.242, 0.383; all sum to 1 */
    float off[SSS_MAX_TS_TAPS], wt[SSS_MAX_TS_TAPS];
    sss_blur_taps(7, off, wt);
    const double published[7] = {0.006, 0.061, 0.242, 0.383, 0.242, 0.061, 0.006};
    for (int t = 0; t < 7; t++) {
        CHECK_NEAR(off[t], t - 3, 1e-6);
        CHECK_NEAR(wt[t], published[t], 6e-4);
    }
    for (int taps = 3; taps <= SSS_MAX_TS_TAPS; taps += 2) {
        sss_blur_taps(taps, off, wt);
        double sum = 0, var = 0;
        for (int t = 0; t < taps; t++) sum += wt[t], var += wt[t] * off[t] * off[t];
        CHECK_NEAR(sum, 1.0, 1e-6);
        if (taps >= 13) CHECK_NEAR(var, 1.0, 0.03); /* the taps' variance is σ² = 1 */
    }

    /* screen-space kernel: sums to 1 per channel; offsets symmetric and increasing */
    for (int taps = 3; taps <= SSS_MAX_SS_TAPS; taps += 10) {
        float *k = calloc((size_t)taps * 6 * 4, sizeof(float));
        sss_ss_kernel(&full, taps, 8.0, k);
        for (int c = 0; c < 3; c++) {
            double sum = 0;
            for (int i = 0; i < 6 * taps; i++) sum += k[i * 4 + c];
            CHECK_NEAR(sum, 1.0, 1e-5);
        }
        for (int t = 0; t < taps; t++) {
            CHECK_NEAR(k[t * 4 + 3], -k[(taps - 1 - t) * 4 + 3], 1e-6);
            if (t) CHECK(k[t * 4 + 3] > k[(t - 1) * 4 + 3]);
        }
        CHECK_NEAR(k[3], -8.0, 1e-6);
        free(k);
    }

    /* pre-integrated LUT: row 0 is max(0, n·l); every entry in [0, 1]; at n·l = 1 scattering
     * darkens (light moves to the dark side), at n·l = 0 it brightens (wrap-like), and more so
     * for higher curvature; red, which scatters furthest, is affected most */
    enum { LW = 64, LH = 32 };
    float *lut = malloc(sizeof(float) * 4 * LW * LH);
    sss_preintegrated_lut(LW, LH, 0.5, lut);
    bool in_range = true;
    for (int i = 0; i < LW * LH * 4; i++) in_range &= lut[i] >= 0 && lut[i] <= 1.0f + 1e-6f && isfinite(lut[i]);
    CHECK(in_range);
    for (int i = 0; i < LW; i++) CHECK_NEAR(lut[i * 4], fmax(0, 2.0 * i / (LW - 1) - 1), 1e-6);
    int mid = LW / 2; /* n·l ≈ 0 */
    const float *top = lut + 4 * ((LH - 1) * LW + mid), *lower = lut + 4 * ((LH / 2) * LW + mid);
    printf("LUT at n.l = %.3f: kappa max %.3f %.3f %.3f, kappa max/2 %.3f %.3f %.3f\n", 2.0 * mid / (LW - 1) - 1, top[0],
           top[1], top[2], lower[0], lower[1], lower[2]);
    CHECK(top[0] > lower[0] && lower[0] > lut[4 * mid] + 0.01);
    CHECK(top[0] > top[1] && top[1] >= top[2]);
    const float *lit = lut + 4 * ((LH - 1) * LW + LW - 1);
    CHECK(lit[0] < 1.0f && lit[0] > 0.5f);
    /* a mid row against a direct numerical integration of Penner's ring integral (red) */
    {
        int j = LH / 2, i = LW / 3;
        double kappa = 0.5 * j / (LH - 1), r = 1 / kappa, ndl = 2.0 * i / (LW - 1) - 1, th = acos(ndl);
        double num = 0, den = 0, dx = 2 * M_PI / 200000;
        for (double x = -M_PI + dx / 2; x < M_PI; x += dx) {
            double d = 2 * r * sin(x / 2), R = 0;
            for (int k = 0; k < 6; k++) R += W[k][0] * exp(-d * d / (2 * VAR[k])) / sqrt(2 * M_PI * VAR[k]);
            num += fmax(0, cos(th + x)) * R;
            den += R;
        }
        printf("LUT (n.l %.3f, kappa %.3f) red: %.5f, direct integration %.5f\n", ndl, kappa, lut[4 * (j * LW + i)],
               num / den);
        CHECK_NEAR(lut[4 * (j * LW + i)], num / den, 2e-3);
    }
    free(lut);
    return check_result();
}
