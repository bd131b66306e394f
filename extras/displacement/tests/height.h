/* The height fields of displacement_height.glsl written again in C, for the meshes the tests and
 * tools displace on the CPU (the reference: independent of the tessellation path). */
#ifndef DISPLACEMENT_HEIGHT_H
#define DISPLACEMENT_HEIGHT_H
#include <math.h>

enum { HF_BUMP, HF_WAVES, HF_BARK, HF_RINGS };

static double hf_smoothstep(double a, double b, double x) {
    double t = (x - a) / (b - a);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return t * t * (3 - 2 * t);
}
static double hf_fract(double x) { return x - floor(x); }

/* H(u, v) in [0, 1] */
static double hf_H(int fn, double f, double u, double v) {
    const double pi = 3.14159265358979323846;
    double du = u - 0.5, dv = v - 0.5;
    switch (fn) {
    case HF_BUMP: return exp(-(du * du + dv * dv) * f * f);
    case HF_WAVES: return 0.5 + 0.5 * sin(2 * pi * f * u) * sin(2 * pi * f * v);
    case HF_BARK: {
        double x = f * u + 0.18 * sin(2 * pi * 2 * v) + 0.07 * sin(2 * pi * 7 * v + 3 * floor(f * u));
        double g = fabs(hf_fract(x) - 0.5) * 2;
        double H = 1 - hf_smoothstep(0.55, 0.95, g);
        double rim = hf_smoothstep(0, 0.04, v) * hf_smoothstep(0, 0.04, 1 - v);
        return 1 + (H - 1) * rim;
    }
    default: {
        double r = 2 * sqrt(du * du + dv * dv), phi = atan2(dv, du);
        double ring = hf_fract(f * r * (1 + 0.04 * sin(3 * phi)) + 0.1 * r);
        double H = 0.75 + 0.25 * hf_smoothstep(0, 0.3, ring) * (1 - hf_smoothstep(0.7, 1, ring));
        return H + (1 - H) * hf_smoothstep(0.9, 0.98, r);
    }
    }
}
/* h = scale·(H − 1) along the normal */
static double hf_h(int fn, double f, double scale, double u, double v) { return scale * (hf_H(fn, f, u, v) - 1); }
#endif
