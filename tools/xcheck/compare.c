#include "compare.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench/metrics.h"
#include "toolkit.h"

double xc_luminance(const float *rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

long xc_region_mask(const float *index_rgba, int w, int h, int index, unsigned char *mask) {
    long count = 0;
#define IDX(x, y) ((int)lroundf(index_rgba[((size_t)(y) * w + (x)) * 4]))
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            bool in = IDX(x, y) == index;
            if (in && index != 0)
                in = x > 0 && y > 0 && x < w - 1 && y < h - 1 && IDX(x - 1, y) == index && IDX(x + 1, y) == index &&
                     IDX(x, y - 1) == index && IDX(x, y + 1) == index;
            mask[(size_t)y * w + x] = in;
            count += in;
        }
#undef IDX
    return count;
}

long xc_interior_mask(const float *index_rgba, int w, int h, unsigned char *mask) {
    long count = 0;
#define IDX(x, y) ((int)lroundf(index_rgba[((size_t)(y) * w + (x)) * 4]))
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int i = IDX(x, y);
            bool in = x > 0 && y > 0 && x < w - 1 && y < h - 1 && IDX(x - 1, y) == i && IDX(x + 1, y) == i &&
                      IDX(x, y - 1) == i && IDX(x, y + 1) == i;
            mask[(size_t)y * w + x] = in;
            count += in;
        }
#undef IDX
    return count;
}

void xc_region_stats(const float *test, const float *ref, const unsigned char *mask, int w, int h, xc_stats *s) {
    double diff2 = 0, ref2 = 0, lt = 0, lr = 0;
    long count = 0;
    for (size_t p = 0; p < (size_t)w * h; p++) {
        if (mask && !mask[p]) continue;
        const float *t = test + p * 4, *r = ref + p * 4;
        if (!isfinite(t[0] + t[1] + t[2]) || !isfinite(r[0] + r[1] + r[2])) {
            diff2 += INFINITY; /* a NaN or Inf in shadelab's image is an error, not a pixel to skip */
            count++;
            continue;
        }
        for (int c = 0; c < 3; c++) diff2 += (double)(t[c] - r[c]) * (t[c] - r[c]), ref2 += (double)r[c] * r[c];
        lt += xc_luminance(t);
        lr += xc_luminance(r);
        count++;
    }
    s->pixels = count;
    s->rel_rms = ref2 > 0 ? sqrt(diff2 / ref2) : (diff2 > 0 ? INFINITY : 0);
    s->mean_ratio = lr > 0 ? lt / lr : (lt > 0 ? INFINITY : 1);
    s->mean_test = count ? lt / count : 0;
    s->mean_ref = count ? lr / count : 0;
    s->flip = NAN;
    s->noise = NAN;
}

void xc_error_map(const float *test, const float *ref, int w, int h, float *out) {
    double mean = 0;
    for (size_t p = 0; p < (size_t)w * h; p++) mean += xc_luminance(ref + p * 4);
    mean /= (double)w * h;
    double floor = fmax(0.02 * mean, 1e-6); /* keeps near-black pixels from reading as huge ratios */
    for (size_t p = 0; p < (size_t)w * h; p++) {
        double t = xc_luminance(test + p * 4), r = xc_luminance(ref + p * 4);
        double e = isfinite(t) ? log2((fmax(t, 0) + floor) / (fmax(r, 0) + floor)) : 1;
        double a = fmin(fabs(e), 1.0);
        float *o = out + p * 4;
        o[0] = e > 0 ? (float)a : 0;
        o[1] = (float)(a > 0.5 ? (a - 0.5) : 0); /* beyond 1.4× the colour lightens */
        o[2] = e < 0 ? (float)a : 0;
        o[3] = 1;
        if (!isfinite(t)) o[0] = o[1] = o[2] = 1; /* NaN/Inf: white */
    }
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

double xc_display_scale(const float *ref, int w, int h) {
    size_t n = (size_t)w * h;
    double *lum = malloc(n * sizeof *lum), scale = 1;
    if (!lum) return 1;
    for (size_t p = 0; p < n; p++) lum[p] = xc_luminance(ref + p * 4);
    qsort(lum, n, sizeof *lum, cmp_double);
    double p99 = lum[(size_t)(0.99 * (n - 1))];
    if (p99 > 0 && isfinite(p99)) scale = 1 / p99;
    free(lum);
    return scale;
}

double xc_flip_map(const float *test, const float *ref, int w, int h, double scale, float *map) {
    size_t n = (size_t)w * h * 4;
    float *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    double mean = NAN;
    if (a && b) {
        for (size_t i = 0; i < n; i++) a[i] = (float)(test[i] * scale), b[i] = (float)(ref[i] * scale);
        mean = sl_metric_flip(a, b, w, h, 0, map);
    }
    free(a);
    free(b);
    return mean;
}

double xc_masked_mean(const float *map, const unsigned char *mask, int w, int h) {
    double sum = 0;
    long count = 0;
    for (size_t p = 0; p < (size_t)w * h; p++)
        if (!mask || mask[p]) sum += map[p], count++;
    return count ? sum / count : NAN;
}

void xc_side_by_side(const float *test, const float *ref, const float *error_map, int w, int h, float *out) {
    double scale = xc_display_scale(ref, w, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t p = (size_t)y * w + x;
            const float *src[3] = {test + p * 4, ref + p * 4, error_map + p * 4};
            for (int k = 0; k < 3; k++) {
                float *o = out + ((size_t)y * 3 * w + (size_t)k * w + x) * 4;
                for (int c = 0; c < 3; c++) {
                    double v = k < 2 ? src[k][c] * scale : src[k][c];
                    v = isfinite(v) ? fmin(fmax(v, 0), 1) : 1;
                    /* the images are linear: encode them; the error map is a display colour already */
                    if (k < 2) v = sl_srgb_encode((float)v);
                    o[c] = (float)v;
                }
                o[3] = 1;
            }
        }
}
