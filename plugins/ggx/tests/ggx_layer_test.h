/* Shared by ggx's layer tests (test_ggx_layers.c, test_ggx_transmission.c,
 * test_ggx_iridescence.c): the GGX terms written in C from the formulas (Walter et al. 2007,
 * Smith's separable G), and one render of a scene into a float image, checked finite. */
#ifndef GGX_LAYER_TEST_H
#define GGX_LAYER_TEST_H
#include "check.h"
#include <math.h>
#include <shadelab/harness.h>
#include <stdbool.h>

static inline double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void normalize3(double v[3]) {
    double l = sqrt(dot3(v, v));
    for (int i = 0; i < 3; i++) v[i] /= l;
}
static inline double schlick(double c, double f0) { return f0 + (1 - f0) * pow(1 - fabs(c), 5); }
/* Smith's G1 for GGX; 0 on the wrong side of the microfacet */
static inline double g1(double xn, double xh, double a) {
    if (xn == 0 || xh / xn <= 0) return 0;
    return 2 / (1 + sqrt(1 + a * a * (1 - xn * xn) / (xn * xn)));
}
/* D·G/(4 n·l n·v) about n for unit v, l (0 when either is below the horizon) */
static inline double dg_over_4(const double n[3], const double v[3], const double l[3], double a) {
    double h[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
    normalize3(h);
    double nl = dot3(n, l), nv = dot3(n, v), nh = dot3(n, h);
    if (nl <= 0 || nv <= 0 || nh <= 0) return 0;
    double t2 = (1 - nh * nh) / (nh * nh), D = a * a / (M_PI * pow(nh, 4) * pow(a * a + t2, 2));
    return D * g1(nv, dot3(v, h), a) * g1(nl, dot3(l, h), a) / (4 * nl * nv);
}

/* A float32, strict harness of w × h for the scene json; NULL (and a failed check) on error. */
static inline sl_harness *ggx_test_harness(const char *json, int w, int h, const char *const *settings,
                                           const char *view) {
    char err[4096];
    sl_harness *hh = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = w,
                                                           .height = h, .scene_json = json, .settings = settings,
                                                           .debug_view = view, .float32 = true, .strict = true},
                                       err, sizeof err);
    CHECK_MSG(hh != NULL, "harness: %s", err);
    return hh;
}

/* Renders one frame into out and checks every pixel is finite; `what` names it in the message. */
static inline bool ggx_test_render(sl_harness *hh, int w, int h, float *out, const char *what) {
    bool ok = sl_harness_render(hh, out) && sl_harness_count_nonfinite(out, w, h) == 0;
    CHECK_MSG(ok, "render of %s failed or not finite", what);
    return ok;
}
#endif
