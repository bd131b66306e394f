/* See sss_profile.h. */
#include "sss_profile.h"
#include <math.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* d'Eon & Luebke 2007, GPU Gems 3 ch. 14 (the six-Gaussian fit of the three-layer skin
 * profile): variance (mm²) and blur weights (R, G, B). */
const double sss_skin_variance[SSS_MAX_GAUSSIANS] = {0.0064, 0.0484, 0.187, 0.567, 1.99, 7.41};
const double sss_skin_weight[SSS_MAX_GAUSSIANS][3] = {
    {0.233, 0.455, 0.649}, {0.100, 0.336, 0.344}, {0.118, 0.198, 0.0},
    {0.113, 0.007, 0.007}, {0.358, 0.004, 0.0},   {0.078, 0.0, 0.0},
};

static double g1(double v, double x) { return exp(-x * x / (2 * v)) / sqrt(2 * M_PI * v); }

/* ∫_a^b g(v, x) dx */
static double g1_integral(double v, double a, double b) {
    double s = sqrt(2 * v);
    return 0.5 * (erf(b / s) - erf(a / s));
}

double sss_line_response(const sss_gaussians *g, int c, double x) {
    double r = 0;
    for (int i = 0; i < g->n; i++) r += g->weight[i][c] * g1(g->variance[i], x);
    return r;
}

void sss_transmittance(const sss_gaussians *g, double d, double rgb[3]) {
    for (int c = 0; c < 3; c++) {
        rgb[c] = 0;
        for (int i = 0; i < g->n; i++) rgb[c] += g->weight[i][c] * exp(-d * d / (2 * g->variance[i]));
    }
}

static void full_profile(sss_gaussians *g) {
    g->n = SSS_MAX_GAUSSIANS;
    memcpy(g->variance, sss_skin_variance, sizeof g->variance);
    memcpy(g->weight, sss_skin_weight, sizeof g->weight);
}

/* cuts: bit i set = a run ends after Gaussian i (i = 0..4). */
static void grouped(unsigned cuts, sss_gaussians *out) {
    memset(out, 0, sizeof *out);
    int start = 0;
    for (int i = 0; i < SSS_MAX_GAUSSIANS; i++) {
        if (i < SSS_MAX_GAUSSIANS - 1 && !(cuts & (1u << i))) continue;
        double sum = 0, moment = 0, w[3] = {0, 0, 0};
        for (int j = start; j <= i; j++) {
            double t = 0;
            for (int c = 0; c < 3; c++) w[c] += sss_skin_weight[j][c], t += sss_skin_weight[j][c];
            sum += t;
            moment += t * sss_skin_variance[j];
        }
        int k = out->n++;
        out->variance[k] = sum > 0 ? moment / sum : sss_skin_variance[start];
        memcpy(out->weight[k], w, sizeof w);
        start = i + 1;
    }
}

static double line_error(const sss_gaussians *a, const sss_gaussians *b) {
    double e = 0;
    for (int s = 0; s < 1500; s++) {
        double x = (s + 0.5) * 0.01; /* 0 … 15 mm */
        for (int c = 0; c < 3; c++) {
            double d = sss_line_response(a, c, x) - sss_line_response(b, c, x);
            e += d * d;
        }
    }
    return e;
}

void sss_profile_reduce(int k, sss_gaussians *out) {
    sss_gaussians full;
    full_profile(&full);
    if (k >= SSS_MAX_GAUSSIANS || k < 1) {
        *out = full;
        if (k < 1) grouped(0, out); /* k ≤ 0: one Gaussian */
        return;
    }
    double best = INFINITY;
    for (unsigned cuts = 0; cuts < 32; cuts++) {
        if (__builtin_popcount(cuts) != k - 1) continue;
        sss_gaussians g;
        grouped(cuts, &g);
        double e = line_error(&g, &full);
        if (e < best) best = e, *out = g;
    }
}

void sss_blur_taps(int taps, float *offsets, float *weights) {
    if (taps < 1) taps = 1;
    if (taps > SSS_MAX_TS_TAPS) taps = SSS_MAX_TS_TAPS;
    if (taps == 1) { offsets[0] = 0, weights[0] = 1; return; }
    int half = taps / 2;
    double h = 3.0 / half; /* ±3σ */
    for (int t = 0; t < taps; t++) {
        double x = (t - half) * h;
        double a = t == 0 ? -INFINITY : x - h / 2, b = t == taps - 1 ? INFINITY : x + h / 2;
        offsets[t] = (float)x;
        weights[t] = (float)g1_integral(1.0, a, b);
    }
}

void sss_ss_kernel(const sss_gaussians *g, int taps, double range, float *rgba) {
    if (taps < 1) taps = 1;
    int half = taps / 2;
    double x[SSS_MAX_SS_TAPS];
    for (int t = 0; t < taps; t++) {
        double u = half ? (double)(t - half) / half : 0;
        x[t] = range * u * fabs(u);
    }
    for (int i = 0; i < g->n; i++)
        for (int t = 0; t < taps; t++) {
            double a = t == 0 ? -INFINITY : 0.5 * (x[t - 1] + x[t]);
            double b = t == taps - 1 ? INFINITY : 0.5 * (x[t] + x[t + 1]);
            double area = g1_integral(g->variance[i], a, b);
            float *p = rgba + 4 * (i * taps + t);
            for (int c = 0; c < 3; c++) p[c] = (float)(g->weight[i][c] * area);
            p[3] = (float)x[t];
        }
}

/* ∫ f(x) over the ring for one Gaussian, on the arc where its chord distance 2r·sin(x/2) stays
 * within 6σ (the rest is < 1e-8 of the peak): midpoint rule, 128 samples. */
static void ring_integrals(double v, double r, double theta, double *num, double *den) {
    double sigma = sqrt(v), reach = 6 * sigma / (2 * r);
    double xmax = reach >= 1 ? M_PI : 2 * asin(reach);
    const int n = 128;
    double dx = 2 * xmax / n;
    *num = *den = 0;
    for (int s = 0; s < n; s++) {
        double x = -xmax + (s + 0.5) * dx;
        double d = 2 * r * sin(0.5 * x);
        double w = g1(v, d) * dx;
        double c = cos(theta + x);
        *num += (c > 0 ? c : 0) * w;
        *den += w;
    }
}

void sss_preintegrated_lut(int width, int height, double kappa_max, float *rgba) {
    for (int j = 0; j < height; j++) {
        double kappa = height > 1 ? kappa_max * j / (height - 1) : 0;
        for (int i = 0; i < width; i++) {
            double ndl = width > 1 ? 2.0 * i / (width - 1) - 1.0 : 1.0;
            float *p = rgba + 4 * ((size_t)j * width + i);
            p[3] = 1;
            if (kappa <= 0) {
                for (int c = 0; c < 3; c++) p[c] = (float)(ndl > 0 ? ndl : 0);
                continue;
            }
            double r = 1.0 / kappa, theta = acos(ndl < -1 ? -1 : ndl > 1 ? 1 : ndl);
            double num[SSS_MAX_GAUSSIANS], den[SSS_MAX_GAUSSIANS];
            for (int k = 0; k < SSS_MAX_GAUSSIANS; k++) ring_integrals(sss_skin_variance[k], r, theta, &num[k], &den[k]);
            for (int c = 0; c < 3; c++) {
                double a = 0, b = 0;
                for (int k = 0; k < SSS_MAX_GAUSSIANS; k++) a += sss_skin_weight[k][c] * num[k], b += sss_skin_weight[k][c] * den[k];
                p[c] = (float)(b > 0 ? a / b : (ndl > 0 ? ndl : 0));
            }
        }
    }
}
