/* The aa plugin's jitter of frame k of an n-frame TAA still, in pixels (its set_frame_jitter), for
 * the envmap tests and benches that recompute a still from its sub-pixel rays: 0 for k = 0,
 * Halton (2, 3) point k − ½ less the mean of points 1..n−1, so the n offsets average to the
 * pixel's centre. b: 2 for x, 3 for y. */
#ifndef ENVMAP_STILL_JITTER_H
#define ENVMAP_STILL_JITTER_H

static inline double still_halton(unsigned i, unsigned b) {
    double f = 1, r = 0;
    for (; i > 0; i /= b) f /= b, r += f * (i % b);
    return r;
}
static inline double still_jitter(unsigned k, unsigned n, unsigned b) {
    if (!k || n < 2) return 0;
    double mean = 0;
    for (unsigned i = 1; i < n; i++) mean += still_halton(i, b) - 0.5;
    return still_halton(k, b) - 0.5 - mean / (n - 1);
}
#endif
