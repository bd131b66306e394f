/* Error metrics (see metrics.h for the exact definitions). RMSE and PSNR come from the core's
 * image comparison; relMSE and SSIM are here. */
#include "metrics.h"
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
}

/* sl_metric_name, sl_metric_parse: core/quality/results.c (autoquality.h). */
double sl_metric_value(const sl_bench_error *e, sl_metric m) {
    switch (m) {
    case SL_METRIC_RMSE: return e->rmse;
    case SL_METRIC_RELMSE: return e->relmse;
    case SL_METRIC_DSSIM: return 1.0 - e->ssim;
    case SL_METRIC_PSNR: return -e->psnr;
    default: return NAN;
    }
}
