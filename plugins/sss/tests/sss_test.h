/* Shared helpers of the sss plugin's render tests. */
#ifndef SSS_TEST_H
#define SSS_TEST_H
#include "check.h"
#include <shadelab/harness.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The published six-Gaussian skin profile (d'Eon & Luebke 2007, GPU Gems 3 ch. 14), typed in
 * here independently of the plugin's copy. */
static const double SSS_T_VAR[6] = {0.0064, 0.0484, 0.187, 0.567, 1.99, 7.41};
static const double SSS_T_W[6][3] = {{0.233, 0.455, 0.649}, {0.100, 0.336, 0.344}, {0.118, 0.198, 0.0},
                                     {0.113, 0.007, 0.007}, {0.358, 0.004, 0.0},   {0.078, 0.0, 0.0}};

/* Response of the profile at distance x (mm) from the centre of a stripe of width s (mm) and
 * unit value: Σ wᵢ [Φ((x + s/2)/σᵢ) − Φ((x − s/2)/σᵢ)]. */
static inline double sss_t_stripe(double x, double s, int c) {
    double r = 0;
    for (int i = 0; i < 6; i++) {
        double sg = sqrt(2 * SSS_T_VAR[i]);
        r += SSS_T_W[i][c] * 0.5 * (erf((x + s / 2) / sg) - erf((x - s / 2) / sg));
    }
    return r;
}

/* Transmittance through d mm: Σ wᵢ exp(−d²/2vᵢ). */
static inline double sss_t_transmittance(double d, int c) {
    double r = 0;
    for (int i = 0; i < 6; i++) r += SSS_T_W[i][c] * exp(-d * d / (2 * SSS_T_VAR[i]));
    return r;
}

/* The plugin's disk cache is off unless the settings name sss.cache: the tests run the blurs
 * (a result another test left in the shared test cache would be the same image, but the code
 * under test would not run). */
static inline sl_harness *sss_t_harness(const char *scene, int w, int h, const char *const *plugins,
                                        const char *const *settings) {
    char err[8192];
    const char *all[64];
    int n = 0;
    bool cache_named = false;
    for (; settings && settings[n] && n < 62; n++) {
        all[n] = settings[n];
        cache_named |= !strncmp(settings[n], "sss.cache=", 10);
    }
    bool has_sss = false;
    for (int i = 0; plugins && plugins[i]; i++) has_sss |= !strcmp(plugins[i], "sss");
    if (!cache_named && has_sss) all[n++] = "sss.cache=false";
    all[n] = NULL;
    sl_harness *hs = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = w, .height = h,
                                                          .scene_json = scene, .plugins = plugins, .settings = all,
                                                          .float32 = true},
                                       err, sizeof err);
    CHECK_MSG(hs != NULL, "%s", err);
    return hs;
}

static inline bool sss_t_set(sl_harness *h, const char *fmt, ...) {
    char a[512], err[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(a, sizeof a, fmt, ap);
    va_end(ap);
    bool ok = sl_harness_set(h, a, err, sizeof err);
    CHECK_MSG(ok, "%s: %s", a, err);
    return ok;
}

static inline const float *sss_t_px(const float *img, int w, int x, int y) { return img + 4 * ((size_t)y * w + x); }
#endif
