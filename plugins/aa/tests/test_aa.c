/* aa: FXAA and TAA against the core's 8x8 supersampling on an edge scene (a lit square turned by
 * a few degrees on black), flat regions untouched by FXAA, a moving edge without ghosts after
 * taa_frames frames (its position per frame in closed form), and live switching equal to a fresh
 * start. Thresholds are the issue's: FXAA cuts the RMSE to the reference by >= 30 %, TAA after
 * taa_frames frames by >= 70 %. */
#include "check.h"
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 96
#define H 96
static float img[W * H * 4], ref[W * H * 4], base[W * H * 4];

/* A 1.2 x 1.2 square facing the camera, turned by `angle` degrees about the view axis; Lambert
 * base colour 0.8 under E = pi head-on: radiance 0.8 on the square, 0 around it. */
static void edge_scene(char *out, size_t n, double angle) {
    snprintf(out, n,
             "{\"plugins\": [\"aa\"],"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 3], \"target\": [0, 0, 0], \"fov_y\": 40}],"
             " \"materials\": [{\"name\": \"m\", \"base_color\": [0.8, 0.8, 0.8]}],"
             " \"nodes\": [{\"name\": \"sq\", \"rotate\": [90, 0, %.3f], \"mesh\": {\"primitive\": \"plane\", \"size\": 1.2},"
             "             \"material\": \"m\"}],"
             " \"environment\": {\"color\": [0, 0, 0], \"intensity\": 0},"
             " \"lights\": [{\"name\": \"l\", \"type\": \"directional\", \"direction\": [0, 0, -1], \"color\": [1, 1, 1],"
             "               \"intensity\": 3.14159265}]}",
             angle);
}

static sl_harness *open_json(const char *json, const char *const *settings) {
    char err[4096] = "";
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                         .scene_json = json, .settings = settings, .strict = true},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "harness: %s", err);
    return h;
}

/* One still: `frames` renders of frame index 0..frames-1 (the scene is static), the last kept. */
static bool render_still(const char *json, const char *const *settings, int frames, float *out) {
    sl_harness *h = open_json(json, settings);
    if (!h) return false;
    bool ok = true;
    for (int i = 0; i < frames && ok; i++) ok = sl_harness_render(h, out);
    CHECK(ok);
    sl_harness_destroy(h);
    return ok;
}

static double rmse(const float *a, const float *b) {
    sl_compare c;
    sl_harness_compare(a, b, W, H, 1e-6, &c);
    return c.rmse;
}

static void test_fxaa(void) {
    char json[2048];
    const double angles[] = {5, 17, 30};
    for (size_t k = 0; k < sizeof angles / sizeof *angles; k++) {
        edge_scene(json, sizeof json, angles[k]);
        const char *s_ref[] = {"aa.method=none", "core.ssaa=8", NULL};
        const char *s_none[] = {"aa.method=none", NULL};
        const char *s_fxaa[] = {"aa.method=fxaa", NULL};
        if (!render_still(json, s_ref, 1, ref) || !render_still(json, s_none, 1, base) ||
            !render_still(json, s_fxaa, 1, img))
            return;
        double e_none = rmse(base, ref), e_fxaa = rmse(img, ref);
        printf("edge %4.1f deg: RMSE to ssaa=8: none %.5f, fxaa %.5f (%.0f %% less)\n", angles[k], e_none, e_fxaa,
               100 * (1 - e_fxaa / e_none));
        CHECK_MSG(e_none > 0.01, "the edge scene does not alias (RMSE %g): the test cannot fail", e_none);
        CHECK_MSG(e_fxaa <= 0.7 * e_none, "edge %g deg: FXAA RMSE %.5f is not 30 %% below none's %.5f", angles[k],
                  e_fxaa, e_none);
        CHECK(sl_harness_count_nonfinite(img, W, H) == 0);
        /* flat regions: every pixel whose 5x5 neighbourhood is constant in the unfiltered image
         * comes out bit for bit the same */
        long flat = 0, changed = 0;
        for (int y = 2; y < H - 2; y++)
            for (int x = 2; x < W - 2; x++) {
                const float *c = base + (y * W + x) * 4;
                bool same = true;
                for (int j = -2; j <= 2 && same; j++)
                    for (int i = -2; i <= 2 && same; i++)
                        same = !memcmp(base + ((y + j) * W + x + i) * 4, c, 3 * sizeof(float));
                if (!same) continue;
                flat++;
                changed += memcmp(img + (y * W + x) * 4, c, 3 * sizeof(float)) != 0;
            }
        CHECK_MSG(flat > W * H / 2, "only %ld flat pixels", flat);
        CHECK_MSG(changed == 0, "edge %g deg: FXAA changed %ld of %ld pixels of flat regions", angles[k], changed, flat);
    }
}

/* TAA: a still after taa_frames frames (the documented headless still) against the reference. */
static void test_taa_still(void) {
    char json[2048];
    const double angles[] = {5, 17, 30};
    for (size_t k = 0; k < sizeof angles / sizeof *angles; k++) {
        edge_scene(json, sizeof json, angles[k]);
        const char *s_ref[] = {"aa.method=none", "core.ssaa=8", NULL};
        const char *s_none[] = {"aa.method=none", NULL};
        const char *s_taa[] = {"aa.method=taa", "aa.taa_frames=16", NULL};
        if (!render_still(json, s_ref, 1, ref) || !render_still(json, s_none, 1, base) ||
            !render_still(json, s_taa, 16, img))
            return;
        /* one frame (--frames 1, a single harness render): the pixel centre, no history = the
         * image without antialiasing, bit for bit */
        static float one[W * H * 4];
        if (!render_still(json, s_taa, 1, one)) return;
        long differ = 0;
        for (int i = 0; i < W * H; i++) differ += memcmp(one + i * 4, base + i * 4, 3 * sizeof(float)) != 0;
        CHECK_MSG(differ == 0, "edge %g deg: a single TAA frame differs from none in %ld pixels", angles[k], differ);
        /* a still keeps its 16-frame mean however long it is shown (the window = headless) */
        static float longer[W * H * 4];
        if (!render_still(json, s_taa, 40, longer)) return;
        differ = 0;
        for (int i = 0; i < W * H; i++) differ += memcmp(longer + i * 4, img + i * 4, 3 * sizeof(float)) != 0;
        CHECK_MSG(differ == 0, "edge %g deg: 40 frames of a still differ from its 16 in %ld pixels", angles[k], differ);
        double e_none = rmse(base, ref), e_taa = rmse(img, ref);
        printf("edge %4.1f deg: RMSE to ssaa=8: none %.5f, taa after 16 frames %.5f (%.0f %% less)\n", angles[k], e_none,
               e_taa, 100 * (1 - e_taa / e_none));
        CHECK_MSG(e_taa <= 0.3 * e_none, "edge %g deg: TAA RMSE %.5f is not 70 %% below none's %.5f", angles[k], e_taa,
                  e_none);
        CHECK(sl_harness_count_nonfinite(img, W, H) == 0);
    }
}

/* A still is the exact mean of its jittered frames: neither the neighbourhood clip nor the
 * disocclusion rejection may act on it (nothing moved). With rejection on in a still, silhouette
 * pixels of a sphere on an empty background lost their history whenever their last jittered
 * frame's surface point was not found again in the 3x3 neighbourhood, so their still was the mean
 * of its last frames only (found by envmap's bench/rim.sh --still against a C quadrature). */
static void test_taa_still_exact(void) {
    const char *json =
        "{\"plugins\": [\"aa\"],"
        " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 3.1], \"target\": [0, 0, 0], \"fov_y\": 40}],"
        " \"materials\": [{\"name\": \"m\", \"base_color\": [0.8, 0.8, 0.8]}],"
        " \"nodes\": [{\"name\": \"s\", \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"m\"}],"
        " \"environment\": {\"color\": [0, 0, 0], \"intensity\": 0},"
        " \"lights\": [{\"name\": \"l\", \"type\": \"directional\", \"direction\": [-0.3, -0.4, -1], \"color\": [1, 1, 1],"
        "               \"intensity\": 3}]}";
    const char *s_taa[] = {"aa.method=taa", "aa.taa_frames=16", NULL};
    const char *s_plain[] = {"aa.method=taa", "aa.taa_frames=16", "aa.taa_clamp=false", "aa.taa_reject=false", NULL};
    static float a[W * H * 4], b[W * H * 4];
    if (!render_still(json, s_taa, 16, a) || !render_still(json, s_plain, 16, b)) return;
    long differ = 0;
    double worst = 0;
    for (int i = 0; i < W * H * 4; i++) {
        if (i % 4 == 3) continue;
        double d = fabs((double)a[i] - b[i]);
        differ += d > 0, worst = d > worst ? d : worst;
    }
    printf("sphere still: with clip and rejection vs without, %ld channels differ (max %.4f)\n", differ, worst);
    CHECK_MSG(differ == 0, "a still with clip and rejection on differs from the plain mean of its frames in %ld channels", differ);
}

/* A square moving right (a VERTEX hook over sl_time, aa-test-mover): behind its left edge the
 * background is uncovered. After taa_frames frames of motion, no pixel farther than 1.5 px behind
 * the edge (its position per frame in closed form) may keep any of the square: the history there
 * must be dropped (disocclusion) or clipped (neighbourhood). With both off, the ghost must show. */
static double ghost(const char *clamp, const char *reject, double *edge_rmse) {
    const double v = 4.1, x0 = -0.45, half = 0.6, dist = 3.0, tan_half = tan(20.0 * M_PI / 180.0);
    const int frames = 12;
    char json[2048];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"aa\"],"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 3], \"target\": [0, 0, 0], \"fov_y\": 40}],"
             " \"materials\": [{\"name\": \"m\", \"base_color\": [0.8, 0.8, 0.8], \"aa_test_speed\": %g}],"
             " \"nodes\": [{\"name\": \"sq\", \"translate\": [%g, 0, 0], \"rotate\": [90, 0, 0],"
             "             \"mesh\": {\"primitive\": \"plane\", \"size\": 1.2}, \"material\": \"m\"}],"
             " \"environment\": {\"color\": [0, 0, 0], \"intensity\": 0},"
             " \"lights\": [{\"name\": \"l\", \"type\": \"directional\", \"direction\": [0, 0, -1],"
             "               \"color\": [1, 1, 1], \"intensity\": 3.14159265}]}",
             v, x0);
    const char *plugins[] = {AA_MOVER, NULL};
    const char *settings[] = {"aa.method=taa", "aa.taa_frames=8", clamp, reject, NULL};
    char err[4096] = "";
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                         .scene_json = json, .plugins = plugins, .settings = settings,
                                                         .strict = true},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "harness: %s", err);
    if (!h) return -1;
    for (int f = 0; f < frames; f++) CHECK(sl_harness_render(h, img));
    sl_harness_destroy(h);
    /* frame frames-1 at t = (frames-1)/60: the left edge's pixel column, from the left */
    double t = (frames - 1) / 60.0;
    double left = ((x0 - half + v * t) / (dist * tan_half) + 1) * 0.5 * W;
    double right = ((x0 + half + v * t) / (dist * tan_half) + 1) * 0.5 * W;
    double top = (1 - half / (dist * tan_half)) * 0.5 * H, bottom = (1 + half / (dist * tan_half)) * 0.5 * H;
    double worst = 0, se = 0;
    long n = 0;
    for (int y = (int)ceil(top) + 2; y < (int)floor(bottom) - 2; y++)
        for (int x = 0; x < W; x++) {
            double cx = x + 0.5;
            /* closed form: the box-filtered coverage of the pixel by [left, right] */
            double cover = fmax(0, fmin(x + 1.0, right) - fmax((double)x, left));
            double expect = 0.8 * fmin(cover, 1.0), got = img[(y * W + x) * 4 + 1];
            se += (got - expect) * (got - expect), n++;
            if (cx < left - 1.5) worst = fmax(worst, fabs(got));
        }
    *edge_rmse = sqrt(se / n);
    return worst;
}

static void test_taa_ghost(void) {
    double e1, e2, e3;
    double with = ghost("aa.taa_clamp=true", "aa.taa_reject=true", &e1);
    double reject_only = ghost("aa.taa_clamp=false", "aa.taa_reject=true", &e2);
    double without = ghost("aa.taa_clamp=false", "aa.taa_reject=false", &e3);
    printf("moving edge, 3.0 px/frame, after 12 frames: largest value behind the edge %.4f (clamp+reject), %.4f "
           "(reject only), %.4f (neither); RMSE to the closed-form coverage %.4f / %.4f / %.4f\n",
           with, reject_only, without, e1, e2, e3);
    CHECK_MSG(with >= 0 && with <= 0.01, "TAA leaves a ghost behind a moving edge: %g", with);
    /* rejection alone removes most of it; what it keeps is the band within a pixel of the edge
     * in the frame it was uncovered, which the neighbourhood clamp then removes */
    CHECK_MSG(reject_only >= 0 && reject_only <= 0.25 * without, "disocclusion rejection alone leaves a ghost of %g (%g "
              "without it)", reject_only, without);
    CHECK_MSG(without > 0.05, "without clamping and rejection no ghost shows (%g): the test cannot fail", without);
}

int main(void) {
    test_fxaa();
    test_taa_still();
    test_taa_still_exact();
    test_taa_ghost();
    return check_result();
}
