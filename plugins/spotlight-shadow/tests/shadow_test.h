/* Helpers shared by the spotlight-shadow tests: harness creation, ratios against the
 * unshadowed image, a few vector helpers. */
#ifndef SPOTLIGHT_SHADOW_TEST_H
#define SPOTLIGHT_SHADOW_TEST_H
#include "check.h"
#include "camera_rays.h"
#include <shadelab/harness.h>
#include <stdarg.h>
#include <stdlib.h>

__attribute__((unused)) static const char *const ss_filters[] = {"hard", "pcf", "poisson", "pcss"};

static inline sl_harness *ss_make(int w, int h, const char *json, const char *const *settings) {
    char err[8192];
    sl_harness *hh = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = w, .height = h,
                                                           .scene_json = json, .settings = settings, .float32 = true,
                                                           .strict = true,
                                                           .plugins = (const char *[]){"spotlight-shadow", NULL}},
                                       err, sizeof err);
    if (!hh) fprintf(stderr, "harness: %s\n", err);
    return hh;
}

static inline bool ss_set(sl_harness *h, const char *fmt, ...) {
    char a[512], err[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(a, sizeof a, fmt, ap);
    va_end(ap);
    bool ok = sl_harness_set(h, a, err, sizeof err);
    if (!ok) fprintf(stderr, "set %s: %s\n", a, err);
    return ok;
}

/* Renders with and without shadows (spotlight-shadow.shadows) into lit/unshadowed. */
static inline bool ss_render_pair(sl_harness *h, float *shadowed, float *unshadowed) {
    bool ok = ss_set(h, "spotlight-shadow.shadows=false") && sl_harness_render(h, unshadowed);
    ok = ok && ss_set(h, "spotlight-shadow.shadows=true") && sl_harness_render(h, shadowed);
    return ok;
}

/* Visibility of pixel i: shadowed / unshadowed red channel (1 where unlit either way). */
static inline double ss_ratio(const float *shadowed, const float *unshadowed, int i) {
    double u = unshadowed[i * 4], s = shadowed[i * 4];
    return u > 1e-7 ? s / u : 1.0;
}

static inline bool ss_has_pass(sl_harness *h, const char *name) {
    sl_harness_structure st;
    sl_harness_structure_of(h, &st);
    for (int i = 0; i < st.pass_count; i++)
        if (!strcmp(st.passes[i], name)) return true;
    return false;
}

static inline double ss_dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void ss_normalize(double *v) {
    double l = sqrt(ss_dot(v, v));
    for (int i = 0; i < 3; i++) v[i] /= l;
}

/* Distance from point c to the segment a-b. */
static inline double ss_segment_distance(const double *a, const double *b, const double *c) {
    double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double t = ss_dot(ac, ab) / ss_dot(ab, ab);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double d[3] = {a[0] + t * ab[0] - c[0], a[1] + t * ab[1] - c[1], a[2] + t * ab[2] - c[2]};
    return sqrt(ss_dot(d, d));
}

/* Does the camera ray of pixel (x, y) hit the sphere (center c, radius r) before t_max? */
static inline bool ss_ray_hits_sphere(const test_camera *cam, int x, int y, const double *c, double r) {
    float o[3], d[3];
    test_camera_ray(cam, x, y, o, d);
    double oc[3] = {o[0] - c[0], o[1] - c[1], o[2] - c[2]}, dd[3] = {d[0], d[1], d[2]};
    double b = ss_dot(oc, dd), q = ss_dot(oc, oc) - r * r;
    return b * b - q > 0 && -b + sqrt(b * b - q) > 0;
}
#endif
