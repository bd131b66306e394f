/* Error metrics of shadelab-bench: how far a rendered image is from its reference.
 *
 * Images are linear HDR radiance, RGBA float, width*height*4, row 0 at the top (what
 * sl_app_read_color returns). Only R, G, B enter the metrics; alpha is ignored.
 *
 *   RMSE    sqrt(mean over pixels and RGB of (a - b)^2), linear radiance (sl_image_compare).
 *   relMSE  mean over pixels and RGB of (a - b)^2 / (b^2 + eps), b = the reference,
 *           eps = SL_RELMSE_EPSILON (0.01): the relative MSE common in Monte Carlo rendering
 *           and denoising papers; eps keeps dark reference pixels from dominating.
 *   PSNR    20 log10(1 / RMSE) dB, peak 1 on linear radiance (sl_image_compare's definition;
 *           +inf for identical images).
 *   SSIM    mean SSIM of Wang, Bovik, Sheikh, Simoncelli, "Image Quality Assessment: From Error
 *           Visibility to Structural Similarity", IEEE TIP 13(4), 2004, eqs. (13) and (17):
 *           11x11 circular-symmetric Gaussian window, sigma 1.5 samples, normalised to unit sum;
 *           K1 = 0.01, K2 = 0.03, dynamic range L = 1, so C1 = 1e-4, C2 = 9e-4; computed at every
 *           window position that lies wholly inside the image (no padding, no down-sampling) and
 *           averaged. Input: the luma Y' = 0.2126 R' + 0.7152 G' + 0.0722 B' of the
 *           display-encoded image (R' = sRGB OETF of the value clamped to [0,1], NaN -> 0: the
 *           core's display transform), in float (no 8-bit quantisation). DSSIM = 1 - SSIM is
 *           the lower-is-better form the charts and budgets use.
 *
 * Non-finite pixels (NaN/Inf in either image) are left out of RMSE/relMSE/PSNR and counted
 * (sl_bench_error.nonfinite): a setting that produces NaN is reported, never averaged in. */
#ifndef SL_BENCH_METRICS_H
#define SL_BENCH_METRICS_H
#include "autoquality.h"
#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SL_RELMSE_EPSILON 0.01
#define SL_SSIM_K1 0.01
#define SL_SSIM_K2 0.03
#define SL_SSIM_WINDOW 11
#define SL_SSIM_SIGMA 1.5

typedef struct sl_bench_error {
    double rmse, relmse, psnr, ssim, max_abs;
    long nonfinite;      /* pixels with a NaN/Inf channel in either image */
} sl_bench_error;

/* relMSE of a against the reference ref (RGB; non-finite pixels skipped; NaN if none left). */
double sl_metric_relmse(const float *a, const float *ref, int width, int height, double eps);
/* Luma of the display-encoded image, one float per pixel (see above). */
void sl_metric_display_luma(const float *rgba, int width, int height, float *luma);
/* Mean SSIM of two single-channel images with values in [0,1] (see above). Needs width and
 * height >= SL_SSIM_WINDOW; returns NaN otherwise. */
double sl_metric_ssim(const float *x, const float *y, int width, int height);
/* Every metric above at once: a = the image under test, ref = the reference. */
void sl_metric_all(const float *a, const float *ref, int width, int height, sl_bench_error *out);

/* sl_metric (the metrics by name: sl_metric_name, sl_metric_parse) is in autoquality.h, the
 * header of the library the viewer's --auto-quality shares with the bench. */
/* The error value of e under metric m, lower is better (PSNR: -psnr). */
double sl_metric_value(const sl_bench_error *e, sl_metric m);

#ifdef __cplusplus
}
#endif
#endif
