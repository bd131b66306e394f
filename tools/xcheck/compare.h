/* shadelab-xcheck's comparison of a test image (shadelab) with a reference (Cycles), both linear
 * RGBA floats, rows top to bottom, over regions given by the reference's object-index pass. */
#ifndef XCHECK_COMPARE_H
#define XCHECK_COMPARE_H
#include <stdbool.h>
#include <stddef.h>

typedef struct xc_stats {
    long pixels;        /* pixels compared */
    double rel_rms;     /* sqrt(Σ (t − r)²) / sqrt(Σ r²) over RGB */
    double mean_ratio;  /* Σ lum(t) / Σ lum(r): 1 = the same mean brightness */
    double mean_test, mean_ref; /* mean luminance */
    double flip;        /* mean LDR-FLIP over the region (xc_flip_map), NaN when not computed */
    double noise;       /* RMS over the region of the per-pixel spread of --noise's frames (NaN: not measured) */
} xc_stats;

/* The pixels whose object index is `index` (rounded) and whose four neighbours have it too: the
 * object's interior, where antialiasing of silhouettes plays no part. mask: w*h bytes. Returns the
 * count. index_rgba: the index pass (R channel). */
long xc_region_mask(const float *index_rgba, int w, int h, int index, unsigned char *mask);

/* Every pixel whose four neighbours have its object index (the background's included): the image
 * less its silhouettes. Returns the count. */
long xc_interior_mask(const float *index_rgba, int w, int h, unsigned char *mask);

/* Statistics over the masked pixels (mask NULL: every pixel). */
void xc_region_stats(const float *test, const float *ref, const unsigned char *mask, int w, int h, xc_stats *s);

/* The error map, display-encoded RGBA floats: black where the two agree, red where the test is
 * brighter, blue where it is darker, full colour at a luminance ratio of 2 (or ½). */
void xc_error_map(const float *test, const float *ref, int w, int h, float *out);

/* Test, reference and error map side by side (3w × h display-encoded RGBA); both images scaled by
 * one exposure that puts the reference's 99th-percentile luminance at 1, then clamped. */
void xc_side_by_side(const float *test, const float *ref, const float *error_map, int w, int h, float *out);

/* The exposure both images are shown and judged at: 1 / the reference's 99th-percentile luminance
 * (1 when that is not positive). */
double xc_display_scale(const float *ref, int w, int h);

/* Per-pixel LDR-FLIP (Andersson et al. 2020; sl_metric_flip of tools/bench) of test against ref,
 * both multiplied by `scale` first (FLIP reads the display range [0, 1]): w*h floats into map.
 * Returns the mean, NaN on failure. */
double xc_flip_map(const float *test, const float *ref, int w, int h, double scale, float *map);

/* The mean of map over the masked pixels (NaN when none). */
double xc_masked_mean(const float *map, const unsigned char *mask, int w, int h);

/* Rec. 709 luminance of a linear RGB pixel. */
double xc_luminance(const float *rgb);
#endif
