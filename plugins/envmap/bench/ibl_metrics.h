/* FLIP and noise over a bench sphere's pixels (bench/ibl_methods.c, bench/ibl_still.c):
 * shadelab-bench's measures (tools/bench/include/bench/metrics.h, library shadelab_metrics)
 * restricted to the pixels of `mask` (the sphere).
 *   ibl_flip_over   the mean over the mask of the per-pixel LDR-FLIP map of x against ref (the
 *                   whole images enter the filters)
 *   ibl_noise_over  samples k = 0 … n−1 of an n-frame still of h's current setting, each rendered
 *                   on its own (sl_harness_render_sample: nothing accumulated, TAA restarted, so
 *                   each is a pixel-centre frame); the RMS over the mask of each pixel's spread
 *                   (RMS over R, G, B) of the sRGB-encoded value. Above SL_NOISE_VISIBLE a setting
 *                   is noisy. */
#ifndef ENVMAP_BENCH_IBL_METRICS_H
#define ENVMAP_BENCH_IBL_METRICS_H
#include "bench/metrics.h"
#include <shadelab/harness.h>
#include <math.h>

/* map: size² floats of scratch */
static inline double ibl_flip_over(const float *x, const float *ref, const unsigned char *mask, int size, float *map) {
    if (isnan(sl_metric_flip(x, ref, size, size, 0, map))) return NAN;
    double s = 0;
    long count = 0;
    for (int i = 0; i < size * size; i++)
        if (mask[i]) s += map[i], count++;
    return count ? s / count : NAN;
}

/* img: size² RGBA floats, sigma: size² floats of scratch; NaN when a frame fails */
static inline double ibl_noise_over(sl_harness *h, int n, const unsigned char *mask, int size, float *img, float *sigma) {
    sl_noise_acc acc;
    if (!sl_noise_begin(&acc, size, size)) return NAN;
    for (int k = 0; k < n; k++) {
        if (!sl_harness_render_sample(h, k, n, img)) {
            sl_noise_end(&acc, NULL);
            return NAN;
        }
        sl_noise_add(&acc, img);
    }
    sl_noise_end(&acc, sigma);
    double s = 0;
    long count = 0;
    for (int i = 0; i < size * size; i++)
        if (mask[i]) s += (double)sigma[i] * sigma[i], count++;
    return count ? sqrt(s / count) : NAN;
}
#endif
