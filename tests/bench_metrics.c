/* shadelab-bench's numbers on inputs whose answers are known by hand: RMSE/PSNR/relMSE of
 * constant offsets, SSIM = 1 for identical images, the closed forms of SSIM for constant
 * images and for checkerboards, SSIM against a direct (non-separable) evaluation of Wang et
 * al.'s formula, FLIP on pairs derived by hand from Andersson et al.'s formulas, the Pareto
 * front of a hand-made point set, and the --auto-quality choice. */
#include "autoquality.h"
#include "bench.h"
#include "check.h"
#include "image/image.h"
#include "bench/metrics.h"
#include "orbit.h"
#include "test_tmp.h"
#include <math.h>
#include <stdlib.h>
#include <unistd.h>

static float *image(int w, int h, float r, float g, float b) {
    float *p = malloc(sizeof(float) * 4 * w * h);
    for (int i = 0; i < w * h; i++) { p[4 * i] = r; p[4 * i + 1] = g; p[4 * i + 2] = b; p[4 * i + 3] = 1; }
    return p;
}

static unsigned rng = 12345;
static float rnd(void) { rng = rng * 1664525u + 1013904223u; return (rng >> 8) / 16777216.0f; }

/* Wang et al. 2004 eq. (13)-(17) evaluated directly: a 2D 11x11 Gaussian window at every
 * valid position, means/variances/covariance by their definitions (x - mu), no separability. */
static double ssim_direct(const float *x, const float *y, int w, int h) {
    double win[11][11], sum = 0;
    for (int j = 0; j < 11; j++)
        for (int i = 0; i < 11; i++) sum += win[j][i] = exp(-((i - 5) * (i - 5) + (j - 5) * (j - 5)) / (2 * 1.5 * 1.5));
    double C1 = 0.01 * 0.01, C2 = 0.03 * 0.03, total = 0;
    int count = 0;
    for (int oy = 0; oy + 11 <= h; oy++)
        for (int ox = 0; ox + 11 <= w; ox++) {
            double mx = 0, my = 0;
            for (int j = 0; j < 11; j++)
                for (int i = 0; i < 11; i++) {
                    mx += win[j][i] / sum * x[(oy + j) * w + ox + i];
                    my += win[j][i] / sum * y[(oy + j) * w + ox + i];
                }
            double vx = 0, vy = 0, cxy = 0;
            for (int j = 0; j < 11; j++)
                for (int i = 0; i < 11; i++) {
                    double a = x[(oy + j) * w + ox + i] - mx, b = y[(oy + j) * w + ox + i] - my;
                    vx += win[j][i] / sum * a * a;
                    vy += win[j][i] / sum * b * b;
                    cxy += win[j][i] / sum * a * b;
                }
            total += (2 * mx * my + C1) * (2 * cxy + C2) / ((mx * mx + my * my + C1) * (vx + vy + C2));
            count++;
        }
    return total / count;
}

static void test_rmse_psnr_relmse(void) {
    const int w = 16, h = 12;
    float *ref = image(w, h, 0.5f, 0.5f, 0.5f), *a = image(w, h, 0.6f, 0.6f, 0.6f);
    sl_bench_error e;
    sl_metric_all(a, ref, w, h, &e);
    /* constant offset d = 0.1 on every channel: RMSE = d, PSNR = 20 log10(1/d) = 20 dB,
     * relMSE = d^2 / (b^2 + eps) = 0.01 / 0.26 */
    CHECK_NEAR(e.rmse, 0.1, 1e-6);
    CHECK_NEAR(e.psnr, 20.0, 1e-4);
    CHECK_NEAR(e.relmse, 0.01 / 0.26, 1e-6);
    CHECK_NEAR(e.max_abs, 0.1, 1e-6);
    CHECK(e.nonfinite == 0);
    /* offset 0.3 in red only: RMSE = sqrt(0.09 / 3) = 0.173205, PSNR = 15.2288 dB */
    float *r = image(w, h, 0.8f, 0.5f, 0.5f);
    sl_metric_all(r, ref, w, h, &e);
    CHECK_NEAR(e.rmse, 0.1732051, 1e-6);
    CHECK_NEAR(e.psnr, 15.2287875, 1e-4);
    CHECK_NEAR(e.relmse, 0.09 / 0.26 / 3, 1e-6);
    /* identical: zero error, PSNR = inf, SSIM = 1 */
    sl_metric_all(ref, ref, w, h, &e);
    CHECK(e.rmse == 0 && e.relmse == 0 && isinf(e.psnr) && e.psnr > 0);
    CHECK_NEAR(e.ssim, 1.0, 1e-12);
    /* black reference: eps keeps relMSE finite, 0.1^2 / (0 + 0.01) = 1 */
    float *black = image(w, h, 0, 0, 0), *dim = image(w, h, 0.1f, 0.1f, 0.1f);
    CHECK_NEAR(sl_metric_relmse(dim, black, w, h, SL_RELMSE_EPSILON), 1.0, 1e-5);
    /* a NaN pixel is counted and left out, not averaged in */
    a[4 * 5 + 1] = NAN;
    sl_metric_all(a, ref, w, h, &e);
    CHECK(e.nonfinite == 1);
    CHECK_NEAR(e.rmse, 0.1, 1e-6);
    CHECK(isfinite(e.relmse) && isfinite(e.ssim));
    free(ref); free(a); free(r); free(black); free(dim);
}

static void test_ssim(void) {
    const int w = 24, h = 20;
    float *x = malloc(sizeof(float) * w * h), *y = malloc(sizeof(float) * w * h);
    /* two constant images: variances are zero, so SSIM = (2 mx my + C1) / (mx^2 + my^2 + C1) */
    for (int i = 0; i < w * h; i++) { x[i] = 0.5f; y[i] = 0.6f; }
    CHECK_NEAR(sl_metric_ssim(x, y, w, h), (2 * 0.5 * 0.6 + 1e-4) / (0.25 + 0.36 + 1e-4), 1e-6);
    CHECK_NEAR(sl_metric_ssim(x, y, w, h), 0.98360924, 1e-6); /* the same, by hand */
    /* checkerboards m ± A and m ± B in phase: the window's mean is m (the alternating sum of
     * the Gaussian weights is ~1e-9), variances A^2 and B^2, covariance AB, so
     * SSIM = (2AB + C2) / (A^2 + B^2 + C2) = 0.0409 / 0.0509 for A = 0.2, B = 0.1 */
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            float s = (i + j) % 2 ? 1.0f : -1.0f;
            x[j * w + i] = 0.5f + 0.2f * s;
            y[j * w + i] = 0.5f + 0.1f * s;
        }
    CHECK_NEAR(sl_metric_ssim(x, y, w, h), 0.0409 / 0.0509, 1e-5);
    /* in opposite phase the structure term is negative: (-2AB + C2) / (A^2 + B^2 + C2) */
    for (int i = 0; i < w * h; i++) y[i] = 1.0f - y[i];
    CHECK_NEAR(sl_metric_ssim(x, y, w, h), (-0.04 + 0.0009) / 0.0509, 1e-5);
    /* random images: the separable implementation equals the direct formula */
    for (int i = 0; i < w * h; i++) { x[i] = rnd(); y[i] = 0.7f * x[i] + 0.3f * rnd(); }
    double s = sl_metric_ssim(x, y, w, h), d = ssim_direct(x, y, w, h);
    CHECK_NEAR(s, d, 1e-9);
    CHECK(s > 0.2 && s < 0.99);
    /* more noise, lower SSIM */
    for (int i = 0; i < w * h; i++) y[i] = 0.4f * x[i] + 0.6f * rnd();
    CHECK(sl_metric_ssim(x, y, w, h) < s);
    /* identical: exactly 1 */
    CHECK_NEAR(sl_metric_ssim(x, x, w, h), 1.0, 1e-12);
    /* too small for an 11x11 window: NaN, not garbage */
    CHECK(isnan(sl_metric_ssim(x, y, 10, 30)));
    free(x);
    free(y);
}

static void test_display_luma(void) {
    /* linear 0.214 grey encodes to ~0.5; luma of grey is the encoded value; pure red is 0.2126 */
    float px[3 * 4] = {0.214f, 0.214f, 0.214f, 1, 1, 0, 0, 1, NAN, 5.0f, -1.0f, 1};
    float l[3];
    sl_metric_display_luma(px, 3, 1, l);
    CHECK_NEAR(l[0], 0.49994, 2e-4);
    CHECK_NEAR(l[1], 0.2126, 1e-6);
    CHECK_NEAR(l[2], 0.7152, 1e-6); /* NaN -> 0, 5 -> 1 (clamped), -1 -> 0 */
}

/* FLIP on pairs whose value follows by hand from the paper's formulas (Andersson et al. 2020).
 *
 * Shared constants. sRGB->XYZ matrix M (IEC 61966-2-1), white W = M (1,1,1) =
 * (0.95047, 1.0000001, 1.08883). CIE L*a*b* of the primaries with that white, f(t) = cbrt(t):
 *   green (0,1,0): L 87.734719, a -86.182702, b  83.179315
 *   blue  (0,0,1): L 32.297009, a  79.187527, b -107.860165
 *   red   (1,0,0): L 53.240792, a  80.092470, b  67.203193
 * Hunt adjustment a_H = a L/100, b_H = b L/100:
 *   green (87.734719, -75.612151, 72.977138), blue (32.297009, 25.575203, -34.835607),
 *   red (53.240792, 42.641865, 35.779512).
 * HyAB(green, blue) = |87.734719 - 32.297009| + |(-101.187354, 107.812745)| = 55.437710 +
 * 147.859624 = 203.297334; cmax = 203.297334^0.7 = 41.275484; knee pc cmax = 16.510194.
 * Compression: e = HyAB^0.7; e < 16.510194: 0.95 e / 16.510194; else
 * 0.95 + (e - 16.510194) / (41.275484 - 16.510194) * 0.05.
 *
 * Uniform images: every filter has unit sum (CSF) or zero sum (edge, point) and borders are
 * clamped, so the CSF leaves each colour unchanged and the feature error is 0: the FLIP of
 * every pixel, and the mean, is the compressed colour error, at any ppd. */
static void test_flip_uniform(void) {
    const int w = 24, h = 18;
    float *black = image(w, h, 0, 0, 0), *white = image(w, h, 1, 1, 1);
    float *red = image(w, h, 1, 0, 0), *green = image(w, h, 0, 1, 0);
    /* identical images: 0 everywhere */
    float *map = malloc(sizeof(float) * w * h);
    CHECK(sl_metric_flip(red, red, w, h, 0, map) == 0.0);
    /* black vs white: L 0 vs 100, a = b = 0: HyAB 100, e = 100^0.7 = 25.118864 > knee:
     * 0.95 + (25.118864 - 16.510194) / 24.765290 * 0.05 = 0.967381 */
    CHECK_NEAR(sl_metric_flip(black, white, w, h, 0, map), 0.967381, 2e-5);
    CHECK_NEAR(map[0], 0.967381, 2e-5);
    CHECK_NEAR(map[w * h - 1], 0.967381, 2e-5);
    /* red vs green: |53.240792 - 87.734719| + |(118.254016, -37.197626)| = 34.493927 +
     * 123.966430 = 158.460357; e = 158.460357^0.7 = 34.669249 > knee:
     * 0.95 + (34.669249 - 16.510194) / 24.765290 * 0.05 = 0.986662 */
    CHECK_NEAR(sl_metric_flip(red, green, w, h, 0, NULL), 0.986662, 2e-5);
    /* symmetric in its arguments; non-finite values are displayed as 0 (NaN) or 1 (+Inf) */
    CHECK_NEAR(sl_metric_flip(green, red, w, h, 0, NULL), 0.986662, 2e-5);
    for (int i = 0; i < w * h; i++) { black[4 * i] = NAN; white[4 * i + 1] = INFINITY; }
    CHECK_NEAR(sl_metric_flip(black, white, w, h, 0, NULL), 0.967381, 2e-5);
    /* invalid arguments: NaN, not garbage */
    CHECK(isnan(sl_metric_flip(red, green, 0, h, 0, NULL)));
    CHECK(isnan(sl_metric_flip(red, green, w, h, 0.5, NULL)));
    free(black); free(white); free(red); free(green); free(map);
}

/* A vertical step edge at ppd = 2 (half a degree per pixel), where both pipelines reduce to
 * sums a hand can do:
 * - CSF: radius ceil(3 sqrt(0.04 / (2 pi^2)) 2) = 1; the neighbours' weights relative to the
 *   centre are exp(-pi^2 0.5^2 / b) <= exp(-61.7) ~ 1.6e-27, so each pixel keeps its colour.
 * - Features: sigma = 0.5 * 0.082 * 2 = 0.082 px, radius 1. The 1D edge kernel -x g(x) is
 *   (+, 0, -) and normalised to (1, 0, -1); the point kernel (x^2/sigma^2 - 1) g(x) is
 *   (+, -, +), normalised to (0.5, -1, 0.5); across the edge the unit-sum Gaussian (with
 *   clamped borders on a vertically constant image) changes nothing and the y responses are 0.
 *   Reference: columns 0-3 black (Y^ = 0), 4-7 white (Y^ = 1). Test: columns 4-7 grey 0.8
 *   (Y^ = 0.8). At columns 3 and 4 the edge response is |0 - Y^right| (1 vs 0.8), the point
 *   response half that (0.5 vs 0.4); elsewhere both are 0. Feature error at columns 3, 4:
 *   (max(0.2, 0.1) / sqrt 2)^0.5 = 0.376060.
 * - Colour: columns 0-3 black vs black: 0, so FLIP 0 (0^(1 - f) = 0). Columns 4-7: white vs
 *   grey 0.8: L* = 116 * 0.8^(1/3) - 16 = 91.684861, a = b = 0; HyAB = 8.315139,
 *   e = 8.315139^0.7 = 4.404622 < knee: 0.95 * 4.404622 / 16.510194 = 0.253443.
 * - Column 4: 0.253443^(1 - 0.376060) = 0.424675; columns 5-7: 0.253443.
 * Mean over the 8 columns: (3 * 0.253443 + 0.424675) / 8 = 0.148126. */
static void test_flip_step_edge(void) {
    const int w = 8, h = 5;
    float *ref = image(w, h, 0, 0, 0), *test = image(w, h, 0, 0, 0), map[8 * 5];
    for (int y = 0; y < h; y++)
        for (int x = 4; x < w; x++)
            for (int c = 0; c < 3; c++) {
                ref[4 * (y * w + x) + c] = 1.0f;
                test[4 * (y * w + x) + c] = 0.8f;
            }
    CHECK_NEAR(sl_metric_flip(test, ref, w, h, 2.0, map), 0.148126, 1e-5);
    for (int y = 0; y < h; y++) {
        CHECK(map[y * w + 0] == 0 && map[y * w + 3] == 0);
        CHECK_NEAR(map[y * w + 4], 0.424675, 1e-5);
        CHECK_NEAR(map[y * w + 5], 0.253443, 1e-5);
        CHECK_NEAR(map[y * w + 7], 0.253443, 1e-5);
    }
    free(ref); free(test);
}

/* What the CSF is for: a one-pixel blue/yellow checkerboard against its mean colour (the
 * average of yellow and blue in XYZ is grey 0.5) is plain at 8 pixels per degree and all but
 * invisible at 64, where the filters average it out (borders excepted); a firefly is an error
 * at any distance. */
static void test_flip_viewing_distance(void) {
    const int w = 64, h = 64;
    float *checker = image(w, h, 0, 0, 0), *mean = image(w, h, 0.5f, 0.5f, 0.5f), *noisy = image(w, h, 0.5f, 0.5f, 0.5f);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            bool odd = (x + y) % 2;
            float *p = checker + 4 * (y * w + x);
            p[0] = p[1] = odd ? 1.0f : 0.0f; /* yellow */
            p[2] = odd ? 0.0f : 1.0f;        /* blue */
        }
    noisy[4 * (16 * w + 16)] = noisy[4 * (16 * w + 16) + 1] = noisy[4 * (16 * w + 16) + 2] = 1.0f;
    double near = sl_metric_flip(checker, mean, w, h, 8, NULL), far = sl_metric_flip(checker, mean, w, h, 64, NULL);
    CHECK(near > 0.9 && far < 0.05 && far > 0);
    float *map = malloc(sizeof(float) * w * h);
    double firefly = sl_metric_flip(noisy, mean, w, h, 0, map);
    CHECK(firefly > 0 && map[16 * w + 16] > 0.2f && map[0] == 0);
    double sum = 0;
    for (int i = 0; i < w * h; i++) sum += map[i];
    CHECK_NEAR(firefly, sum / (w * h), 1e-9);
    free(checker); free(mean); free(noisy); free(map);
}

/* The noise measure on frames whose spread is known: identical frames 0; black and white in turn
 * (sRGB 0 and 1): sample variance ((0 - 1/2)^2 + (1 - 1/2)^2) / (2 - 1) = 1/2, sigma = 0.707107;
 * on one pixel of four only: RMS over pixels sqrt(0.5 / 4) = 0.353553. */
static void test_noise(void) {
    const int w = 2, h = 2;
    float *grey = image(w, h, 0.3f, 0.3f, 0.3f), *black = image(w, h, 0, 0, 0), *white = image(w, h, 1, 1, 1);
    float sigma[4];
    sl_noise_acc acc;
    CHECK(sl_noise_begin(&acc, w, h));
    for (int i = 0; i < 5; i++) sl_noise_add(&acc, grey);
    CHECK(sl_noise_end(&acc, sigma) == 0.0 && sigma[3] == 0);
    CHECK(sl_noise_begin(&acc, w, h));
    sl_noise_add(&acc, black);
    sl_noise_add(&acc, white);
    CHECK_NEAR(sl_noise_end(&acc, sigma), 0.707107, 1e-6);
    CHECK_NEAR(sigma[0], 0.707107, 1e-6);
    /* four frames, pixel 0 alternating, the others constant; linear 2 and -1 display as 1 and 0 */
    float *alt = image(w, h, 0, 0, 0);
    CHECK(sl_noise_begin(&acc, w, h));
    for (int k = 0; k < 4; k++) {
        for (int c = 0; c < 3; c++) alt[c] = k % 2 ? 2.0f : -1.0f;
        sl_noise_add(&acc, alt);
    }
    /* sample variance of 0,1,0,1: (4 * 1/4) / 3 = 1/3; RMS over 4 pixels sqrt(1/12) = 0.288675 */
    CHECK_NEAR(sl_noise_end(&acc, sigma), 0.288675, 1e-6);
    CHECK(sigma[1] == 0 && sigma[2] == 0);
    CHECK(sl_noise_begin(&acc, w, h));
    sl_noise_add(&acc, white);
    CHECK(sl_noise_end(&acc, NULL) == 0.0); /* one frame: no spread */
    free(grey); free(black); free(white); free(alt);
}

/* --orbit's statistics: quantiles by interpolation between order statistics, and flicker, the
 * frame-to-frame change of the error against the truth. */
static void test_orbit_numbers(void) {
    double v[] = {5, 1, 4, 2, 3}; /* sorted 1..5: q 0.5 -> 3; q 0.95 -> index 3.8 -> 4.8 */
    CHECK(sl_orbit_quantile(v, 5, 0.5) == 3);
    CHECK_NEAR(sl_orbit_quantile(v, 5, 0.95), 4.8, 1e-12);
    CHECK(sl_orbit_quantile(v, 5, 1) == 5 && sl_orbit_quantile(v, 5, 0) == 1);
    CHECK(isnan(sl_orbit_quantile(v, 0, 0.5)));
    const int w = 4, h = 2;
    float *h0 = image(w, h, 0.2f, 0.2f, 0.2f), *h1 = image(w, h, 0.2f, 0.2f, 0.2f);
    float *f0 = image(w, h, 0.2f, 0.2f, 0.2f), *f1 = image(w, h, 0.2f, 0.2f, 0.2f);
    /* the truth changes between the cameras (motion) and the frames change with it: 0 */
    for (int c = 0; c < 3; c++) h1[c] = f1[c] = 1.0f;
    CHECK(sl_orbit_flicker(f0, f1, h0, h1, w, h) == 0.0);
    /* a steady error (the same in both frames, pixels 1-7) does not flicker: 0 */
    for (int i = 1; i < w * h; i++) f0[4 * i + 1] = f1[4 * i + 1] = 0.5f;
    CHECK(sl_orbit_flicker(f0, f1, h0, h1, w, h) == 0.0);
    /* one pixel's red goes black -> white in the frames while its truth stays black: the
     * display changes by 1 in one of 3 x 8 values, sqrt(1 / 24) = 0.204124 */
    for (int i = 1; i < w * h; i++) f0[4 * i + 1] = f1[4 * i + 1] = 0.2f;
    for (int c = 0; c < 3; c++) h1[c] = f1[c] = 0.2f;
    f0[4 * 5] = 0, f1[4 * 5] = 1, h0[4 * 5] = h1[4 * 5] = 0;
    CHECK_NEAR(sl_orbit_flicker(f0, f1, h0, h1, w, h), 0.204124, 1e-6);
    free(h0); free(h1); free(f0); free(f1);
}

static void test_pareto(void) {
    /*            A     B    C    D    E    F    G    H */
    double c[] = {1,    2,   3,   4,   2,   5,   NAN, 0.5};
    double e[] = {10,   5,   6,   1,   5,   1,   0,   20};
    bool f[8];
    CHECK(sl_pareto_front(c, e, 8, f) == 5);
    /* C is dominated by B, F by D (same error, dearer), G has no cost; E duplicates B */
    bool expect[8] = {true, true, false, true, true, false, false, true};
    for (int i = 0; i < 8; i++) CHECK_MSG(f[i] == expect[i], "point %d", i);
    CHECK(sl_pareto_cheapest_within(c, e, 8, 5) == 1);   /* B (E ties; the lower index) */
    CHECK(sl_pareto_cheapest_within(c, e, 8, 100) == 7); /* H */
    CHECK(sl_pareto_cheapest_within(c, e, 8, 1) == 3);   /* D, not the dearer F */
    CHECK(sl_pareto_cheapest_within(c, e, 8, 0.5) == -1);
    CHECK(sl_pareto_most_accurate(c, e, 8) == 3);
    /* one point is its own front; an empty set has none */
    CHECK(sl_pareto_front(c, e, 1, f) == 1 && f[0]);
    CHECK(sl_pareto_front(c, e, 0, f) == 0);
    /* random sets: the cheapest point within any budget is on the front, and every point off
     * the front is dominated by one on it */
    for (int t = 0; t < 200; t++) {
        double rc[12], re[12];
        bool rf[12];
        for (int i = 0; i < 12; i++) { rc[i] = (int)(rnd() * 6); re[i] = (int)(rnd() * 6); }
        sl_pareto_front(rc, re, 12, rf);
        int k = sl_pareto_cheapest_within(rc, re, 12, rnd() * 6);
        CHECK(k < 0 || rf[k]);
        for (int i = 0; i < 12; i++) {
            if (rf[i]) continue;
            bool dominated = false;
            for (int j = 0; j < 12; j++)
                dominated |= rf[j] && rc[j] <= rc[i] && re[j] <= re[i] && (rc[j] < rc[i] || re[j] < re[i]);
            CHECK(dominated);
        }
    }
}

static const char *front_json =
    "{\"format\": \"shadelab-bench/1\", \"plugin\": \"core\", \"primary_metric\": \"rmse\", \"scene\": \"s.json\","
    " \"width\": 64, \"height\": 32, \"backend\": \"osmesa\", \"renderer\": \"llvmpipe\", \"settings\": ["
    " {\"settings\": \"core.ssaa=1\", \"ok\": true, \"frame_ms\": {\"median\": 1.0},"
    "  \"passes\": [{\"name\": \"forward\", \"median_ms\": 0.8}], \"error\": {\"rmse\": 0.02, \"ssim\": 0.98, \"psnr\": 34,"
    "   \"flip\": 0.1, \"noise\": 0}},"
    " {\"settings\": \"core.ssaa=2\", \"ok\": true, \"frame_ms\": {\"median\": 3.0},"
    "  \"error\": {\"rmse\": 0.007, \"ssim\": 0.997, \"psnr\": 43, \"flip\": 0.05, \"noise\": 0}},"
    " {\"settings\": \"core.ssaa=3\", \"ok\": false, \"failure\": \"x\"},"
    " {\"settings\": \"core.ssaa=4\", \"ok\": true, \"frame_ms\": {\"median\": 9.0},"
    "  \"error\": {\"rmse\": 0.003, \"ssim\": 0.9995, \"psnr\": 50}},"
    " {\"settings\": \"core.ssaa=5\", \"ok\": true, \"frame_ms\": {\"median\": 12.0},"
    "  \"error\": {\"rmse\": 0.004, \"ssim\": 0.999, \"psnr\": 48}},"
    /* the cheapest and most accurate on every metric, but its frames scatter: never chosen */
    " {\"settings\": \"core.ssaa=6\", \"ok\": true, \"frame_ms\": {\"median\": 0.5},"
    "  \"error\": {\"rmse\": 0.001, \"ssim\": 0.9999, \"psnr\": 60, \"flip\": 0.01, \"noise\": 0.03, \"noisy\": true}}]}";

/* only noisy settings: the most accurate of them is chosen, and flagged */
static const char *noisy_json =
    "{\"format\": \"shadelab-bench/1\", \"plugin\": \"core\", \"primary_metric\": \"flip\", \"settings\": ["
    " {\"settings\": \"core.ssaa=1\", \"ok\": true, \"frame_ms\": {\"median\": 1.0},"
    "  \"error\": {\"rmse\": 0.02, \"flip\": 0.2, \"noise\": 0.01, \"noisy\": true}},"
    " {\"settings\": \"core.ssaa=2\", \"ok\": true, \"frame_ms\": {\"median\": 2.0},"
    "  \"error\": {\"rmse\": 0.01, \"flip\": 0.1, \"noise\": 0.01, \"noisy\": true}}]}";

static void test_choose(void) {
    sl_aq_choice c;
    char err[512];
    CHECK(sl_autoquality_choose(front_json, NULL, 0.01, &c, err, sizeof err));
    CHECK(!strcmp(c.settings, "core.ssaa=2") && c.within_budget && c.frame_ms == 3.0 && !strcmp(c.metric, "rmse"));
    CHECK(sl_autoquality_choose(front_json, NULL, 0.05, &c, err, sizeof err) && !strcmp(c.settings, "core.ssaa=1"));
    CHECK_CONTAINS(c.passes, "forward 0.800 ms");
    CHECK(sl_autoquality_choose(front_json, NULL, 0.0035, &c, err, sizeof err) && !strcmp(c.settings, "core.ssaa=4"));
    /* nothing meets the budget: the most accurate, flagged */
    CHECK(sl_autoquality_choose(front_json, NULL, 0.001, &c, err, sizeof err));
    CHECK(!strcmp(c.settings, "core.ssaa=4") && !c.within_budget);
    /* psnr: the budget is a floor in dB; dssim = 1 - ssim */
    CHECK(sl_autoquality_choose(front_json, "psnr", 40, &c, err, sizeof err) && !strcmp(c.settings, "core.ssaa=2"));
    CHECK(c.error == 43);
    CHECK(sl_autoquality_choose(front_json, "dssim", 0.002, &c, err, sizeof err) && !strcmp(c.settings, "core.ssaa=4"));
    CHECK(!sl_autoquality_choose("{\"format\": \"other\"}", NULL, 1, &c, err, sizeof err));
    CHECK_CONTAINS(err, "not a shadelab-bench result");
    CHECK(!sl_autoquality_choose("{ nope", NULL, 1, &c, err, sizeof err));
    CHECK_CONTAINS(err, "malformed JSON");
    CHECK(!sl_autoquality_choose(front_json, "nope", 1, &c, err, sizeof err));
    CHECK_CONTAINS(err, "unknown metric");
    /* flip and noise budgets; the noisy ssaa=6 would win every one of them on its numbers */
    CHECK(sl_autoquality_choose(front_json, "flip", 0.06, &c, err, sizeof err) && !strcmp(c.settings, "core.ssaa=2"));
    CHECK(c.error == 0.05 && !c.noisy);
    CHECK(sl_autoquality_choose(front_json, "noise", 0.001, &c, err, sizeof err) && !strcmp(c.settings, "core.ssaa=1"));
    CHECK(sl_autoquality_choose(noisy_json, NULL, 0.15, &c, err, sizeof err) && !strcmp(c.settings, "core.ssaa=2"));
    CHECK(c.noisy && c.within_budget && !strcmp(c.metric, "flip"));
}

/* The writers on a synthetic result: one dominated setting, one identical to the reference. */
static void test_outputs(void) {
    sl_bench_result r = {0};
    r.scene = strdup("synthetic");
    r.plugin = strdup("core");
    r.backend = strdup("none");
    r.renderer = strdup("test");
    r.timing_mode = strdup("glfinish");
    r.width = 64;
    r.height = 32;
    r.frames = 30;
    r.warmup = 5;
    r.rounds = 1;
    r.reference.settings = strdup("core.ssaa=8");
    r.reference.accumulate = 1;
    strcpy(r.created, "2024-01-01T00:00:00Z");
    const double ms[] = {1, 4, 3, 9}, rmse[] = {0.02, 0.004, 0.006, 0}, psnr[] = {34, 48, 44, INFINITY};
    r.row_count = 4;
    r.rows = calloc(4, sizeof *r.rows);
    for (int i = 0; i < 4; i++) {
        char s[32];
        snprintf(s, sizeof s, "core.ssaa=%d", i + 1);
        r.rows[i] = (sl_bench_row){.settings = strdup(s), .label = sl_bench_label(s, "core"), .ok = true, .frames = 30,
                                   .frame_ms_median = ms[i], .error = {.rmse = rmse[i], .psnr = psnr[i], .ssim = 1 - rmse[i]}};
    }
    sl_bench_mark_fronts(&r);
    /* (3 ms, 0.006) lies between (1 ms, 0.02) and (4 ms, 0.004): on the front. At 5 ms it is
     * dearer and worse than (4 ms, 0.004): dominated. */
    CHECK(r.rows[2].front[SL_METRIC_RMSE] && r.rows[0].front[SL_METRIC_RMSE] && r.rows[1].front[SL_METRIC_RMSE] && r.rows[3].front[SL_METRIC_RMSE]);
    r.rows[2].frame_ms_median = 5;
    sl_bench_mark_fronts(&r);
    CHECK(!r.rows[2].front[SL_METRIC_RMSE] && r.rows[1].front[SL_METRIC_RMSE]);
    /* a noisy setting is on no front: here the cheapest is, until its frames scatter */
    r.noise_limit = 0.002;
    r.rows[0].error.noise = 0.0021;
    sl_bench_mark_fronts(&r);
    CHECK(r.rows[0].noisy && !r.rows[0].front[SL_METRIC_RMSE] && !r.rows[0].front[SL_METRIC_FLIP]);
    r.rows[0].error.noise = 0.002;
    sl_bench_mark_fronts(&r);
    CHECK(!r.rows[0].noisy && r.rows[0].front[SL_METRIC_RMSE]);
    CHECK(!strcmp(r.rows[2].label, "ssaa=3"));
    /* a peer renderer (EEVEE against a Cycles reference): in the JSON, on no front even when it
     * beats every setting's error */
    r.peer_count = 1;
    r.peers = calloc(1, sizeof *r.peers);
    r.peers[0] = (sl_bench_peer){.label = strdup("EEVEE 16 spp"), .ms = 20000, .error = {.rmse = 0.001, .psnr = 60, .ssim = 0.999}};
    sl_bench_mark_fronts(&r);
    char dir[512], path[600], err[1024];
    snprintf(dir, sizeof dir, "%s/bench-metrics", sl_test_dir());
    CHECK(sl_bench_mkdirs(dir, err, sizeof err));
    snprintf(path, sizeof path, "%s/synthetic.json", dir);
    CHECK(sl_bench_write_json(&r, path, SL_METRIC_RMSE, err, sizeof err));
    FILE *f = fopen(path, "rb");
    char text[20000] = "";
    if (f) { text[fread(text, 1, sizeof text - 1, f)] = 0; fclose(f); }
    CHECK_CONTAINS(text, "\"front\":\t[\"core.ssaa=1\", \"core.ssaa=2\", \"core.ssaa=4\"]");
    CHECK_CONTAINS(text, "\"psnr\":\t\"inf\"");
    CHECK_CONTAINS(text, "\"peers\":\t[{\n\t\t\t\"label\":\t\"EEVEE 16 spp\",\n\t\t\t\"ms_per_render\":\t20000,\n\t\t\t\"error\":\t{\n\t\t\t\t\"rmse\":\t0.001");
    sl_aq_choice c;
    CHECK(sl_autoquality_choose(text, NULL, 0.005, &c, err, sizeof err) && !strcmp(c.settings, "core.ssaa=2"));
    CHECK(sl_autoquality_choose(text, "psnr", 100, &c, err, sizeof err) && !strcmp(c.settings, "core.ssaa=4"));
    snprintf(path, sizeof path, "%s/synthetic.csv", dir);
    CHECK(sl_bench_write_csv(&r, path, SL_METRIC_RMSE, err, sizeof err));
    for (int m = 0; m < 2; m++) {
        snprintf(path, sizeof path, "%s/synthetic-%s.png", dir, m ? "psnr" : "rmse");
        int w = sl_bench_write_chart(&r, path, m ? SL_METRIC_PSNR : SL_METRIC_RMSE, err, sizeof err);
        CHECK_MSG(w == 1 || (w == 0 && strstr(err, "gnuplot not found")), "%d: %s", w, err);
    }
    /* no gnuplot: the chart is skipped with a message that says how to get it */
    setenv("SHADELAB_GNUPLOT", "/nonexistent/gnuplot", 1);
    snprintf(path, sizeof path, "%s/skipped.png", dir);
    CHECK(sl_bench_write_chart(&r, path, SL_METRIC_RMSE, err, sizeof err) == 0);
    CHECK_CONTAINS(err, "gnuplot not found");
    CHECK_CONTAINS(err, "gnuplot-nox");
    CHECK(access(path, F_OK) != 0);
    unsetenv("SHADELAB_GNUPLOT");
    sl_bench_result_free(&r);
}

/* The chart keeps everything inside the picture: a long title (reference settings) wraps, and
 * long labels of the slowest settings are written left of their points. Nothing may be drawn in
 * the 8 px next to the left and right edges (the plot's border is 25 px from the right edge). */
static void test_chart_edges(void) {
    sl_bench_result r = {0};
    r.scene = strdup("scenes/a-scene-with-a-rather-long-name.json");
    r.plugin = strdup("core");
    r.backend = strdup("osmesa");
    r.renderer = strdup("llvmpipe (LLVM 15.0.6, 256 bits)");
    r.timing_mode = strdup("glfinish");
    r.width = 320;
    r.height = 180;
    r.frames = 30;
    r.warmup = 5;
    r.rounds = 1;
    char ref[600] = "";
    for (int i = 0; i < 12; i++) snprintf(ref + strlen(ref), sizeof ref - strlen(ref), "%score.setting_number_%d=%d", i ? " " : "", i, i);
    r.reference.settings = strdup(ref);
    r.reference.accumulate = 1;
    r.reference.scale = 2;
    strcpy(r.created, "2024-01-01T00:00:00Z");
    const double ms[] = {1, 6, 9.5, 10}, rmse[] = {0.02, 0.006, 0.004, 0};
    r.row_count = 4;
    r.rows = calloc(4, sizeof *r.rows);
    for (int i = 0; i < 4; i++) {
        char s[200];
        snprintf(s, sizeof s, "core.ssaa=%d core.anisotropy=%d core.a_long_knob_name=a-long-value-%d", i + 1, 1 << i, i);
        r.rows[i] = (sl_bench_row){.settings = strdup(s), .label = sl_bench_label(s, "core"), .ok = true, .frames = 30,
                                   .frame_ms_median = ms[i], .error = {.rmse = rmse[i], .psnr = 30 + i, .ssim = 1 - rmse[i]}};
    }
    /* a peer seconds away on the log axis that --reference cycles draws: its label goes left too */
    r.peer_count = 1;
    r.peers = calloc(1, sizeof *r.peers);
    r.peers[0] = (sl_bench_peer){.label = strdup("EEVEE 16 spp (a peer renderer with a long label)"), .ms = 20000,
                                 .error = {.rmse = 0.005, .psnr = 40, .ssim = 0.995}};
    sl_bench_mark_fronts(&r);
    char dir[] = "/tmp/shadelab-chart-edges-XXXXXX", path[600], err[1024];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/edges.png", dir);
    int w = sl_bench_write_chart(&r, path, SL_METRIC_RMSE, err, sizeof err);
    CHECK_MSG(w == 1 || (w == 0 && strstr(err, "gnuplot not found")), "%d: %s", w, err);
    sl_image img = {0};
    if (w == 1 && sl_image_load(&img, path, err, sizeof err)) {
        int ink_left = 0, ink_right = 0;
        for (int y = 0; y < img.height; y++)
            for (int x = 0; x < 8; x++)
                for (int c = 0; c < 3; c++) {
                    ink_left += img.pixels[((size_t)y * img.width + x) * 4 + c] < 0.9f;
                    ink_right += img.pixels[((size_t)y * img.width + img.width - 1 - x) * 4 + c] < 0.9f;
                }
        CHECK_MSG(ink_left == 0 && ink_right == 0, "%s: %d / %d dark samples within 8 px of the left / right edge", path,
                  ink_left, ink_right);
        sl_image_free(&img);
    } else if (w == 1) {
        CHECK_MSG(false, "%s", err);
    } else {
        printf("test_chart_edges: %s (skipped)\n", err);
    }
    unlink(path);
    rmdir(dir);
    sl_bench_result_free(&r);
}

int main(void) {
    test_rmse_psnr_relmse();
    test_ssim();
    test_display_luma();
    test_flip_uniform();
    test_flip_step_edge();
    test_flip_viewing_distance();
    test_noise();
    test_orbit_numbers();
    test_pareto();
    test_choose();
    test_outputs();
    test_chart_edges();
    return check_result();
}
