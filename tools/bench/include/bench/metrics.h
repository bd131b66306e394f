/* Error metrics of shadelab-bench: how far a rendered image is from its reference. The public
 * header of the library shadelab_metrics (tools/bench/metrics.c), which other tools link too
 * (shadelab-xcheck's FLIP).
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
 *   FLIP    LDR-FLIP of Andersson et al., "FLIP: A Difference Evaluator for Alternating Images",
 *           Proc. ACM CGIT 3(2), 2020, written from the paper's formulas: a perceptual error per
 *           pixel in [0,1] and its mean over the image (the pooled value the authors recommend).
 *           Input: the display image, each channel of the linear image clamped to [0,1] (NaN ->
 *           0), i.e. what the core's display pass encodes, without 8-bit quantisation. Colour:
 *           sRGB primaries -> XYZ (white = RGB 1,1,1) -> YyCxCz; each channel filtered by the
 *           paper's contrast sensitivity kernel sum_k a_k sqrt(pi/b_k) exp(-pi^2 x^2/b_k) (x in
 *           degrees, unit sum, radius ceil(3 sqrt(0.04/(2 pi^2)) ppd)); back to linear RGB
 *           clamped to [0,1]; L*a*b* with the Hunt adjustment a,b *= L/100; HyAB distance
 *           |dL| + |(da,db)|, raised to 0.7 and compressed (knee 0.4 of the Hunt-adjusted
 *           green-blue distance -> 0.95). Features: on Y/Yn, the magnitudes of the first and
 *           second derivatives of a Gaussian (sigma = 0.5 * 0.082 deg * ppd pixels, radius
 *           ceil(3 sigma), positive weights summing to 1 and negative to -1); feature error =
 *           (max(|d edge|, |d point|) / sqrt 2)^0.5. Per pixel: colour^(1 - feature). Image
 *           borders: clamp to edge. ppd: pixels per degree of visual angle; the paper's default
 *           67 (a 0.7 m wide 3840-pixel monitor seen from 0.7 m). HDR-FLIP (several exposures of
 *           an HDR pair) is not implemented: the bench compares images after tone mapping.
 *
 *   noise   How much a setting's frames scatter around their mean: the per-pixel sample standard
 *           deviation, over the frames k = 0..n-1 of an n-frame still (sl_frame.sample_index k
 *           of n, n = SL_NOISE_SAMPLES unless told), of the display-encoded value (sRGB of the
 *           value clamped to [0,1]), root-mean-square over pixels and R, G, B. Each frame is
 *           rendered on its own (sl_tool_render_sample: a fresh start, no TAA history, no
 *           accumulation), so it is what a TAA still or an accumulation has to average away, the
 *           sparkle while a still settles. 0 exactly for a method whose frames do not depend on
 *           the sample index (deterministic). A setting whose noise exceeds the limit
 *           (SL_NOISE_VISIBLE unless told) is "noisy": it is left off every Pareto front and
 *           --auto-quality does not choose it, whatever its mean error. Noise fixed in screen
 *           space (the same speckle in every frame) does not scatter: FLIP against the
 *           reference sees it.
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
/* 0.7 m * (3840 px / 0.7 m) * pi / 180: the paper's observer (section 5). */
#define SL_FLIP_PPD_DEFAULT 67.0206
#define SL_FLIP_PPD_MIN 1.0     /* below this the feature kernels underflow */
#define SL_FLIP_PPD_MAX 1000.0
#define SL_NOISE_SAMPLES 16     /* the frames of the still whose spread is the noise (TAA's default) */
#define SL_NOISE_VISIBLE 0.002  /* noise limit: half an 8-bit code value, RMS (issue 42's target) */

typedef struct sl_bench_error {
    double rmse, relmse, psnr, ssim, max_abs;
    double flip;         /* mean LDR-FLIP at SL_FLIP_PPD_DEFAULT */
    double noise;        /* NaN when not measured */
    long nonfinite;      /* pixels with a NaN/Inf channel in either image */
} sl_bench_error;

/* relMSE of a against the reference ref (RGB; non-finite pixels skipped; NaN if none left). */
double sl_metric_relmse(const float *a, const float *ref, int width, int height, double eps);
/* Luma of the display-encoded image, one float per pixel (see above). */
void sl_metric_display_luma(const float *rgba, int width, int height, float *luma);
/* Mean SSIM of two single-channel images with values in [0,1] (see above). Needs width and
 * height >= SL_SSIM_WINDOW; returns NaN otherwise. */
double sl_metric_ssim(const float *x, const float *y, int width, int height);
/* Mean LDR-FLIP of test against ref (RGBA float, w*h*4, see above); ppd <= 0 means
 * SL_FLIP_PPD_DEFAULT. error_map: NULL, or w*h floats that receive the per-pixel error.
 * NaN when w or h <= 0, ppd is outside [SL_FLIP_PPD_MIN, SL_FLIP_PPD_MAX] or memory runs out. */
double sl_metric_flip(const float *test_rgba, const float *ref_rgba, int w, int h, double ppd, float *error_map);
/* The noise measure, one frame at a time (Welford's running mean and variance per value). */
typedef struct sl_noise_acc { int width, height, count; double *mean, *m2; } sl_noise_acc;
bool sl_noise_begin(sl_noise_acc *acc, int width, int height);
void sl_noise_add(sl_noise_acc *acc, const float *rgba);
/* The noise of the frames added (0 for fewer than 2); sigma_map: NULL, or width*height floats
 * that receive each pixel's standard deviation (RMS over R, G, B). Frees the accumulator. */
double sl_noise_end(sl_noise_acc *acc, float *sigma_map);
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
