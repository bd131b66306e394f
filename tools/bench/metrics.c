/* Error metrics (see metrics.h for the exact definitions). RMSE and PSNR come from the core's
 * image comparison; relMSE and SSIM are here. */
#include "bench/metrics.h"
#include "toolkit.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

static bool finite3(const float *p) { return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]); }

double sl_metric_relmse(const float *a, const float *ref, int w, int h, double eps) {
    double sum = 0;
    long n = 0;
    for (long i = 0; i < (long)w * h; i++) {
        const float *p = a + 4 * i, *q = ref + 4 * i;
        if (!finite3(p) || !finite3(q)) continue;
        for (int c = 0; c < 3; c++) {
            double d = (double)p[c] - q[c];
            sum += d * d / ((double)q[c] * q[c] + eps);
        }
        n++;
    }
    return n ? sum / (3.0 * n) : NAN;
}

void sl_metric_display_luma(const float *rgba, int w, int h, float *luma) {
    for (long i = 0; i < (long)w * h; i++) {
        const float *p = rgba + 4 * i;
        /* sl_srgb_encode clamps to [0,1] and maps NaN to 0, as the display pass does */
        luma[i] = (float)(0.2126 * sl_srgb_encode(p[0]) + 0.7152 * sl_srgb_encode(p[1]) +
                          0.0722 * sl_srgb_encode(p[2]));
    }
}

/* Separable Gaussian filtering over the 'valid' region: out is (w-10)x(h-10). */
static void filter_valid(const double *in, int w, int h, const double *k, double *tmp, double *out) {
    const int r = SL_SSIM_WINDOW / 2, ow = w - 2 * r, oh = h - 2 * r;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < ow; x++) {
            double s = 0;
            for (int i = 0; i < SL_SSIM_WINDOW; i++) s += k[i] * in[(size_t)y * w + x + i];
            tmp[(size_t)y * ow + x] = s;
        }
    for (int y = 0; y < oh; y++)
        for (int x = 0; x < ow; x++) {
            double s = 0;
            for (int i = 0; i < SL_SSIM_WINDOW; i++) s += k[i] * tmp[(size_t)(y + i) * ow + x];
            out[(size_t)y * ow + x] = s;
        }
}

double sl_metric_ssim(const float *x, const float *y, int w, int h) {
    if (w < SL_SSIM_WINDOW || h < SL_SSIM_WINDOW) return NAN;
    /* The 2D window w(i,j) = g(i)g(j) / (sum g)^2 is separable: the circular-symmetric
     * Gaussian of the paper, normalised to unit sum. */
    double k[SL_SSIM_WINDOW], ksum = 0;
    for (int i = 0; i < SL_SSIM_WINDOW; i++) {
        double d = i - SL_SSIM_WINDOW / 2;
        k[i] = exp(-d * d / (2 * SL_SSIM_SIGMA * SL_SSIM_SIGMA));
        ksum += k[i];
    }
    for (int i = 0; i < SL_SSIM_WINDOW; i++) k[i] /= ksum;
    const size_t n = (size_t)w * h;
    const int ow = w - (SL_SSIM_WINDOW - 1), oh = h - (SL_SSIM_WINDOW - 1);
    const size_t on = (size_t)ow * oh;
    double *buf = malloc(sizeof(double) * (5 * n + (size_t)ow * h + 5 * on));
    if (!buf) return NAN;
    double *X = buf, *Y = X + n, *XX = Y + n, *YY = XX + n, *XY = YY + n, *tmp = XY + n;
    double *mx = tmp + (size_t)ow * h, *my = mx + on, *sxx = my + on, *syy = sxx + on, *sxy = syy + on;
    for (size_t i = 0; i < n; i++) {
        X[i] = x[i];
        Y[i] = y[i];
        XX[i] = X[i] * X[i];
        YY[i] = Y[i] * Y[i];
        XY[i] = X[i] * Y[i];
    }
    filter_valid(X, w, h, k, tmp, mx);
    filter_valid(Y, w, h, k, tmp, my);
    filter_valid(XX, w, h, k, tmp, sxx);
    filter_valid(YY, w, h, k, tmp, syy);
    filter_valid(XY, w, h, k, tmp, sxy);
    const double C1 = (SL_SSIM_K1 * 1.0) * (SL_SSIM_K1 * 1.0), C2 = (SL_SSIM_K2 * 1.0) * (SL_SSIM_K2 * 1.0);
    double sum = 0;
    for (size_t i = 0; i < on; i++) {
        /* eq. (14)-(16): sigma^2 = E[x^2] - mu^2 under the window weights (eq. 14 with w_i) */
        double ux = mx[i], uy = my[i];
        double vx = sxx[i] - ux * ux, vy = syy[i] - uy * uy, cxy = sxy[i] - ux * uy;
        sum += ((2 * ux * uy + C1) * (2 * cxy + C2)) / ((ux * ux + uy * uy + C1) * (vx + vy + C2));
    }
    free(buf);
    return sum / (double)on;
}

void sl_metric_all(const float *a, const float *ref, int w, int h, sl_bench_error *out) {
    memset(out, 0, sizeof *out);
    sl_image_diff d;
    sl_image_compare(a, ref, w, h, 4, INFINITY, &d);
    out->rmse = d.rmse;
    out->psnr = d.psnr;
    out->max_abs = d.max_abs;
    out->nonfinite = (long)w * h - d.pixels_compared;
    out->relmse = sl_metric_relmse(a, ref, w, h, SL_RELMSE_EPSILON);
    float *la = malloc(sizeof(float) * (size_t)w * h * 2);
    if (!la) { out->ssim = NAN; return; }
    float *lb = la + (size_t)w * h;
    sl_metric_display_luma(a, w, h, la);
    sl_metric_display_luma(ref, w, h, lb);
    out->ssim = sl_metric_ssim(la, lb, w, h);
    free(la);
    out->flip = sl_metric_flip(a, ref, w, h, SL_FLIP_PPD_DEFAULT, NULL);
    out->noise = NAN;
}

bool sl_noise_begin(sl_noise_acc *acc, int w, int h) {
    memset(acc, 0, sizeof *acc);
    size_t n = (size_t)w * h * 3;
    acc->mean = calloc(2 * n, sizeof(double));
    if (!acc->mean) return false;
    acc->m2 = acc->mean + n;
    acc->width = w, acc->height = h;
    return true;
}

void sl_noise_add(sl_noise_acc *acc, const float *rgba) {
    acc->count++;
    for (size_t i = 0; i < (size_t)acc->width * acc->height; i++)
        for (int c = 0; c < 3; c++) {
            double x = sl_srgb_encode(rgba[4 * i + c]), *mean = &acc->mean[3 * i + c];
            double d = x - *mean;
            *mean += d / acc->count;
            acc->m2[3 * i + c] += d * (x - *mean);
        }
}

double sl_noise_end(sl_noise_acc *acc, float *sigma_map) {
    size_t n = (size_t)acc->width * acc->height;
    double sum = 0;
    for (size_t i = 0; i < n; i++) {
        double v = 0;
        for (int c = 0; c < 3 && acc->count > 1; c++) v += acc->m2[3 * i + c] / (acc->count - 1);
        if (sigma_map) sigma_map[i] = (float)sqrt(v / 3);
        sum += v;
    }
    free(acc->mean);
    memset(acc, 0, sizeof *acc);
    return n ? sqrt(sum / (3.0 * n)) : NAN;
}

/* sl_metric_name, sl_metric_parse: core/quality/results.c (autoquality.h). */
double sl_metric_value(const sl_bench_error *e, sl_metric m) {
    switch (m) {
    case SL_METRIC_RMSE: return e->rmse;
    case SL_METRIC_RELMSE: return e->relmse;
    case SL_METRIC_DSSIM: return 1.0 - e->ssim;
    case SL_METRIC_PSNR: return -e->psnr;
    case SL_METRIC_FLIP: return e->flip;
    case SL_METRIC_NOISE: return e->noise;
    default: return NAN;
    }
}

/* ------------------------------------------------------------------ FLIP ---------------- */
/* LDR-FLIP, Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström, Fairchild, "FLIP: A
 * Difference Evaluator for Alternating Images", Proc. ACM Comput. Graph. Interact. Tech. 3(2),
 * 2020, sections 4.1 (colour), 4.2 (features), 4.3 (combination); the errata's "division by
 * 116" for the feature pipeline's normalised luminance. Written from the paper's formulas. */
#define FLIP_QC 0.7        /* exponent of the colour difference */
#define FLIP_PC 0.4        /* compression knee, fraction of the largest difference */
#define FLIP_PT 0.95       /* value at the knee */
#define FLIP_QF 0.5        /* exponent of the feature difference */
#define FLIP_EDGE_W 0.082  /* degrees: distance between the edge filter's extrema is w */

/* sRGB primaries (D65) to CIE XYZ, IEC 61966-2-1. White = the row sums (RGB 1,1,1). */
static const double flip_rgb2xyz[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                                          {0.2126729, 0.7151522, 0.0721750},
                                          {0.0193339, 0.1191920, 0.9503041}};

/* The contrast sensitivity of each YCxCz channel as a sum of two Gaussians in frequency,
 * a_k exp(-b_k f^2), whose spatial kernel is sum_k a_k sqrt(pi/b_k) exp(-pi^2 x^2 / b_k),
 * x in degrees (the paper's section 4.1, table of a1 b1 a2 b2). */
static const double flip_csf_a[3][2] = {{1, 0}, {1, 0}, {34.1, 13.5}};
static const double flip_csf_b[3][2] = {{0.0047, 1e-5}, {0.0053, 1e-5}, {0.04, 0.025}};

typedef struct flip_kernels {
    int csf_r;              /* CSF radius in pixels: ceil(3 sqrt(b_max / (2 pi^2)) ppd) */
    double *csf[3][2];      /* per channel and term: the 1D factor exp(-pi^2 (i/ppd)^2 / b) */
    double csf_weight[3][2];/* the term's weight in the unit-sum 2D kernel */
    int feat_r;             /* ceil(3 sigma), sigma = 0.5 w ppd pixels */
    double *gauss, *edge, *point; /* unit-sum Gaussian; its 1st and 2nd derivative, +-1 sums */
    double xyz2rgb[3][3], white[3];
    double *mem;
} flip_kernels;

static void invert3(const double m[3][3], double out[3][3]) {
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            /* cofactor of m[j][i] (the adjugate is the transposed cofactor matrix) */
            int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            out[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
        }
}

/* Scales the positive entries of k to sum to 1 and the negative ones to -1 (section 4.2). */
static void normalise_signed(double *k, int len) {
    double pos = 0, neg = 0;
    for (int i = 0; i < len; i++) {
        if (k[i] > 0) pos += k[i];
        else neg -= k[i];
    }
    for (int i = 0; i < len; i++) k[i] = k[i] > 0 ? k[i] / pos : neg > 0 ? k[i] / neg : 0;
}

static bool flip_kernels_make(flip_kernels *k, double ppd) {
    memset(k, 0, sizeof *k);
    k->csf_r = (int)ceil(3.0 * sqrt(0.04 / (2 * M_PI * M_PI)) * ppd); /* b_max = 0.04 */
    double sigma = 0.5 * FLIP_EDGE_W * ppd;
    k->feat_r = (int)ceil(3.0 * sigma);
    int cl = 2 * k->csf_r + 1, fl = 2 * k->feat_r + 1;
    k->mem = malloc(sizeof(double) * (6 * (size_t)cl + 3 * (size_t)fl));
    if (!k->mem) return false;
    double *p = k->mem;
    for (int c = 0; c < 3; c++) {
        double total = 0; /* sum of the 2D kernel: sum_k A_k (sum_i e_k(i))^2 */
        for (int t = 0; t < 2; t++, p += cl) {
            k->csf[c][t] = p;
            double s = 0, b = flip_csf_b[c][t];
            for (int i = -k->csf_r; i <= k->csf_r; i++) s += p[i + k->csf_r] = exp(-M_PI * M_PI * (i / ppd) * (i / ppd) / b);
            k->csf_weight[c][t] = flip_csf_a[c][t] * sqrt(M_PI / b);
            total += k->csf_weight[c][t] * s * s;
        }
        for (int t = 0; t < 2; t++) k->csf_weight[c][t] /= total;
    }
    k->gauss = p, k->edge = p + fl, k->point = p + 2 * fl;
    double gs = 0;
    for (int i = -k->feat_r; i <= k->feat_r; i++) gs += k->gauss[i + k->feat_r] = exp(-i * i / (2 * sigma * sigma));
    for (int i = -k->feat_r; i <= k->feat_r; i++) {
        double g = k->gauss[i + k->feat_r] /= gs;
        k->edge[i + k->feat_r] = -i * g;
        k->point[i + k->feat_r] = (i * i / (sigma * sigma) - 1) * g;
    }
    /* 2D: edge_x(x,y) = edge(x) gauss(y); its positive part sums to (sum edge+)(sum gauss) = 1 */
    normalise_signed(k->edge, fl);
    normalise_signed(k->point, fl);
    invert3(flip_rgb2xyz, k->xyz2rgb);
    for (int i = 0; i < 3; i++) k->white[i] = flip_rgb2xyz[i][0] + flip_rgb2xyz[i][1] + flip_rgb2xyz[i][2];
    return true;
}

/* out = in filtered by kx along rows then ky along columns (radius r), edges clamped. */
static void convolve2(const float *in, int w, int h, const double *kx, const double *ky, int r, float *tmp, float *out) {
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double s = 0;
            for (int i = -r; i <= r; i++) {
                int xi = x + i < 0 ? 0 : x + i >= w ? w - 1 : x + i;
                s += kx[i + r] * in[(size_t)y * w + xi];
            }
            tmp[(size_t)y * w + x] = (float)s;
        }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double s = 0;
            for (int i = -r; i <= r; i++) {
                int yi = y + i < 0 ? 0 : y + i >= h ? h - 1 : y + i;
                s += ky[i + r] * tmp[(size_t)yi * w + x];
            }
            out[(size_t)y * w + x] = (float)s;
        }
}

/* What the display shows, as linear light: clamped to [0,1], NaN -> 0. */
static double display_linear(float v) { return v > 0 ? (v < 1 ? v : 1) : 0; }

static double lab_f(double t) {
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

/* Linear RGB in [0,1] -> CIE L*a*b* (white: RGB 1,1,1) with the Hunt adjustment a, b *= L/100. */
static void rgb_to_hunt_lab(const flip_kernels *k, const double rgb[3], float lab[3]) {
    double f[3];
    for (int i = 0; i < 3; i++)
        f[i] = lab_f((flip_rgb2xyz[i][0] * rgb[0] + flip_rgb2xyz[i][1] * rgb[1] + flip_rgb2xyz[i][2] * rgb[2]) / k->white[i]);
    double L = 116 * f[1] - 16;
    lab[0] = (float)L;
    lab[1] = (float)(0.01 * L * 500 * (f[0] - f[1]));
    lab[2] = (float)(0.01 * L * 200 * (f[1] - f[2]));
}

/* The colour pipeline of one image (section 4.1): YCxCz, CSF filtering, back to linear RGB
 * clamped to [0,1], Hunt-adjusted L*a*b* into lab[0..2]. work: 3 planes of w*h. */
static void flip_color(const flip_kernels *k, const float *rgba, int w, int h, float *work, float *lab[3]) {
    size_t n = (size_t)w * h;
    float *tmp = work, *term = work + n, *in = work + 2 * n;
    for (size_t i = 0; i < n; i++) {
        double rgb[3] = {display_linear(rgba[4 * i]), display_linear(rgba[4 * i + 1]), display_linear(rgba[4 * i + 2])};
        double v[3];
        for (int j = 0; j < 3; j++)
            v[j] = (flip_rgb2xyz[j][0] * rgb[0] + flip_rgb2xyz[j][1] * rgb[1] + flip_rgb2xyz[j][2] * rgb[2]) / k->white[j];
        /* YyCxCz: Yy = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn) */
        lab[0][i] = (float)(116 * v[1] - 16);
        lab[1][i] = (float)(500 * (v[0] - v[1]));
        lab[2][i] = (float)(200 * (v[1] - v[2]));
    }
    for (int c = 0; c < 3; c++) {
        memcpy(in, lab[c], sizeof(float) * n);
        memset(lab[c], 0, sizeof(float) * n);
        for (int t = 0; t < 2; t++) {
            if (flip_csf_a[c][t] == 0) continue;
            convolve2(in, w, h, k->csf[c][t], k->csf[c][t], k->csf_r, tmp, term);
            for (size_t i = 0; i < n; i++) lab[c][i] += (float)(k->csf_weight[c][t] * term[i]);
        }
    }
    for (size_t i = 0; i < n; i++) {
        double y = (lab[0][i] + 16) / 116.0, x = lab[1][i] / 500.0 + y, z = y - lab[2][i] / 200.0;
        double xyz[3] = {x * k->white[0], y * k->white[1], z * k->white[2]}, rgb[3];
        for (int j = 0; j < 3; j++) {
            double v = k->xyz2rgb[j][0] * xyz[0] + k->xyz2rgb[j][1] * xyz[1] + k->xyz2rgb[j][2] * xyz[2];
            rgb[j] = v < 0 ? 0 : v > 1 ? 1 : v;
        }
        float out[3];
        rgb_to_hunt_lab(k, rgb, out);
        for (int j = 0; j < 3; j++) lab[j][i] = out[j];
    }
}

/* The feature pipeline of one image (section 4.2): on the normalised luminance
 * Y^ = (Yy + 16) / 116 = Y / Yn, the magnitudes of the edge (first-derivative) and point
 * (second-derivative) responses, |(Y^ * Gx, Y^ * Gy)|, into edge and point. work: 4 planes. */
static void flip_features(const flip_kernels *k, const float *rgba, int w, int h, float *work, float *edge, float *point) {
    size_t n = (size_t)w * h;
    float *yhat = work, *tmp = work + n, *gx = work + 2 * n, *gy = work + 3 * n;
    for (size_t i = 0; i < n; i++)
        yhat[i] = (float)((flip_rgb2xyz[1][0] * display_linear(rgba[4 * i]) + flip_rgb2xyz[1][1] * display_linear(rgba[4 * i + 1]) +
                           flip_rgb2xyz[1][2] * display_linear(rgba[4 * i + 2])) / k->white[1]);
    const double *kernel[2] = {k->edge, k->point};
    float *out[2] = {edge, point};
    for (int f = 0; f < 2; f++) {
        convolve2(yhat, w, h, kernel[f], k->gauss, k->feat_r, tmp, gx);
        convolve2(yhat, w, h, k->gauss, kernel[f], k->feat_r, tmp, gy);
        for (size_t i = 0; i < n; i++) out[f][i] = hypotf(gx[i], gy[i]);
    }
}

/* Section 4.1: the HyAB distance raised to qc, compressed against the largest one, the
 * distance of Hunt-adjusted green and blue (raised to qc too). */
static double flip_color_error(double hyab, double cmax) {
    double e = pow(hyab, FLIP_QC);
    if (e < FLIP_PC * cmax) return FLIP_PT / (FLIP_PC * cmax) * e;
    return FLIP_PT + (e - FLIP_PC * cmax) / (cmax - FLIP_PC * cmax) * (1 - FLIP_PT);
}

static double hyab(const float p[3], const float q[3]) {
    return fabs((double)p[0] - q[0]) + hypot((double)p[1] - q[1], (double)p[2] - q[2]);
}

double sl_metric_flip(const float *test_rgba, const float *ref_rgba, int w, int h, double ppd, float *error_map) {
    if (w <= 0 || h <= 0) return NAN;
    if (ppd <= 0) ppd = SL_FLIP_PPD_DEFAULT;
    if (!(ppd >= SL_FLIP_PPD_MIN && ppd <= SL_FLIP_PPD_MAX)) return NAN;
    flip_kernels k;
    size_t n = (size_t)w * h;
    float *buf = malloc(sizeof(float) * n * 14);
    if (!buf || !flip_kernels_make(&k, ppd)) {
        free(buf);
        free(k.mem);
        return NAN;
    }
    float *lt[3] = {buf, buf + n, buf + 2 * n}, *lr[3] = {buf + 3 * n, buf + 4 * n, buf + 5 * n};
    float *et = buf + 6 * n, *pt = buf + 7 * n, *er = buf + 8 * n, *pr = buf + 9 * n, *work = buf + 10 * n;
    flip_color(&k, test_rgba, w, h, work, lt);
    flip_color(&k, ref_rgba, w, h, work, lr);
    flip_features(&k, test_rgba, w, h, work, et, pt);
    flip_features(&k, ref_rgba, w, h, work, er, pr);
    float green[3], blue[3];
    rgb_to_hunt_lab(&k, (const double[3]){0, 1, 0}, green);
    rgb_to_hunt_lab(&k, (const double[3]){0, 0, 1}, blue);
    double cmax = pow(hyab(green, blue), FLIP_QC), sum = 0;
    for (size_t i = 0; i < n; i++) {
        float a[3] = {lt[0][i], lt[1][i], lt[2][i]}, b[3] = {lr[0][i], lr[1][i], lr[2][i]};
        double color = flip_color_error(hyab(a, b), cmax);
        /* section 4.2: the larger of the edge and point differences, / sqrt 2, raised to qf */
        double feature = pow(fmax(fabs(er[i] - et[i]), fabs(pr[i] - pt[i])) / M_SQRT2, FLIP_QF);
        double e = pow(color, 1 - feature); /* section 4.3 */
        if (error_map) error_map[i] = (float)e;
        sum += e;
    }
    free(buf);
    free(k.mem);
    return sum / (double)n;
}
