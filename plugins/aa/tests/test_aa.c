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

/* TAA over supersampling (core.ssaa = k): each frame's pixel is already the box mean of its k × k
 * samples, so the still's jitter spreads each sample over its own cell (the core divides the
 * jitter by k) and the still is the pixel's box filter sampled 16·k² times. A jitter of a whole
 * pixel moved the k × k grid across the pixel's neighbours: the still was a box filtered again by
 * a box, a tent two pixels wide, further from the 8x8 reference than supersampling alone. */
static void test_taa_over_ssaa(void) {
    char json[2048];
    edge_scene(json, sizeof json, 17);
    const char *s_ref[] = {"aa.method=none", "core.ssaa=8", NULL};
    const char *s_ssaa[] = {"aa.method=none", "core.ssaa=2", NULL};
    const char *s_both[] = {"aa.method=taa", "aa.taa_frames=16", "core.ssaa=2", NULL};
    if (!render_still(json, s_ref, 1, ref) || !render_still(json, s_ssaa, 1, base) || !render_still(json, s_both, 16, img))
        return;
    double e_ssaa = rmse(base, ref), e_both = rmse(img, ref);
    printf("edge 17 deg: RMSE to ssaa=8: ssaa=2 %.5f, ssaa=2 with a 16-frame TAA still %.5f\n", e_ssaa, e_both);
    CHECK_MSG(e_both <= 0.5 * e_ssaa, "TAA over core.ssaa=2: RMSE %.5f is not half of supersampling's alone (%.5f)",
              e_both, e_ssaa);
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

/* Texture detail in a still (taa_lod_bias): a fine checker on a plane tilted away from the camera.
 * The 8x8 supersampled reference box-filters the texture over each pixel; a still whose jittered
 * frames each sample the mip level of the whole pixel filters it twice (the mip's box, then the
 * pixel's), and the LOD bias -0.5 log2(16) = -2 removes the first. The still with the bias is
 * closer to the reference (RMSE at least 30 % lower), and a single frame (the pixel centre) is the
 * same with the bias on or off: only the jittered frames of a still are biased. */
static void test_taa_texture_still(void) {
    const char *json =
        "{\"plugins\": [\"aa\"],"
        " \"cameras\": [{\"name\": \"c\", \"position\": [0, 1.2, 2.2], \"target\": [0, 0, 0], \"fov_y\": 40}],"
        " \"materials\": [{\"name\": \"m\", \"base_color_map\": \"checker:48:0.9,0.9,0.9:0.1,0.1,0.1\"}],"
        " \"nodes\": [{\"name\": \"p\", \"mesh\": {\"primitive\": \"plane\", \"size\": 2}, \"material\": \"m\"}],"
        " \"environment\": {\"color\": [0, 0, 0], \"intensity\": 0},"
        " \"lights\": [{\"name\": \"l\", \"type\": \"directional\", \"direction\": [0, -1, 0], \"color\": [1, 1, 1],"
        "               \"intensity\": 3.14159265}]}";
    const char *s_ref[] = {"aa.method=none", "core.ssaa=8", NULL};
    const char *s_bias[] = {"aa.method=taa", "aa.taa_frames=16", NULL};
    const char *s_plain[] = {"aa.method=taa", "aa.taa_frames=16", "aa.taa_lod_bias=false", NULL};
    static float plain[W * H * 4], one_bias[W * H * 4], one_plain[W * H * 4];
    if (!render_still(json, s_ref, 1, ref) || !render_still(json, s_bias, 16, img) || !render_still(json, s_plain, 16, plain) ||
        !render_still(json, s_bias, 1, one_bias) || !render_still(json, s_plain, 1, one_plain))
        return;
    double e_bias = rmse(img, ref), e_plain = rmse(plain, ref), e_one = rmse(one_plain, ref);
    printf("checker plane, still of 16 frames: RMSE to ssaa=8 with the LOD bias %.5f, without %.5f (one frame %.5f)\n",
           e_bias, e_plain, e_one);
    CHECK_MSG(e_bias <= 0.7 * e_plain, "the still with the texture LOD bias (RMSE %.5f) is not 30 %% closer to ssaa=8 "
              "than without (%.5f)", e_bias, e_plain);
    long differ = 0;
    for (int i = 0; i < W * H; i++) differ += memcmp(one_bias + i * 4, one_plain + i * 4, 3 * sizeof(float)) != 0;
    CHECK_MSG(differ == 0, "a single frame differs with the LOD bias on and off in %ld pixels", differ);
}

/* A square moving right (a VERTEX hook over sl_time, aa-test-mover): behind its left edge the
 * background is uncovered. After `frames` frames of motion (`then`, if any, set before the last),
 * no pixel farther than `behind` px behind the edge (its position per frame in closed form) may keep
 * any of the square: the history there must be dropped (disocclusion) or clipped (neighbourhood).
 * Returns the largest value there; *edge_rmse: the RMSE to the box-filtered coverage in closed form
 * over the rows the square covers. */
static double moving_edge(const char *const *settings, int frames, const char *then, double behind, double *edge_rmse) {
    const double v = 4.1, x0 = -0.45, half = 0.6, dist = 3.0, tan_half = tan(20.0 * M_PI / 180.0);
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
    char err[4096] = "";
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                         .scene_json = json, .plugins = plugins, .settings = settings,
                                                         .strict = true},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "harness: %s", err);
    if (!h) return -1;
    if (frames == 1) sl_harness_set_frame(h, 11); /* a first frame at the time of the others' last */
    for (int f = 0; f < frames; f++) {
        if (then && f == frames - 1) CHECK_MSG(sl_harness_set(h, then, err, sizeof err), "%s", err);
        CHECK(sl_harness_render(h, img));
    }
    sl_harness_destroy(h);
    /* the last frame, at t = 11/60: the left edge's pixel column, from the left */
    double t = 11 / 60.0;
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
            if (cx < left - behind) worst = fmax(worst, fabs(got));
        }
    *edge_rmse = sqrt(se / n);
    return worst;
}

static double ghost(const char *clamp, const char *reject, double *edge_rmse) {
    const char *settings[] = {"aa.method=taa", "aa.taa_frames=8", clamp, reject, NULL};
    return moving_edge(settings, 12, NULL, 1.5, edge_rmse);
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

/* TAAU (render scale 0.5, taau.frag): a still converges towards the full-size still closer than
 * TAA at the render size scaled up bilinearly does, and closer to the 8x8 supersampled truth. */
static void test_taau_still(void) {
    char json[2048];
    edge_scene(json, sizeof json, 17);
    static float full[W * H * 4], up[W * H * 4], bilinear[W * H * 4];
    const char *s_ref[] = {"aa.method=none", "core.ssaa=8", NULL};
    const char *s_full[] = {"aa.taa_frames=16", NULL};
    const char *s_up[] = {"aa.taa_frames=16", "core.render_scale=0.5", "aa.taa_upscale=true", NULL};
    const char *s_bilinear[] = {"aa.taa_frames=16", "core.render_scale=0.5", NULL}; /* the default */
    /* the still of a TAAU at scale 0.5 is 4x as long: its frames bring a quarter of the samples */
    if (!render_still(json, s_ref, 1, ref) || !render_still(json, s_full, 16, full) || !render_still(json, s_up, 64, up) ||
        !render_still(json, s_bilinear, 16, bilinear))
        return;
    double up_full = rmse(up, full), bilinear_full = rmse(bilinear, full);
    double up_ref = rmse(up, ref), bilinear_ref = rmse(bilinear, ref), full_ref = rmse(full, ref);
    printf("edge 17 deg, still at render scale 0.5: RMSE to the full-size still: taau %.5f, bilinear %.5f; to ssaa=8: "
           "taau %.5f, bilinear %.5f (full size %.5f)\n", up_full, bilinear_full, up_ref, bilinear_ref, full_ref);
    CHECK(sl_harness_count_nonfinite(up, W, H) == 0);
    CHECK_MSG(up_full <= 0.6 * bilinear_full, "TAAU's still (RMSE %.5f to the full-size still) is not 40 %% closer than "
              "the bilinear scale-up's (%.5f)", up_full, bilinear_full);
    CHECK_MSG(up_ref < bilinear_ref, "TAAU's still is farther from the truth (%.5f) than bilinear (%.5f)", up_ref,
              bilinear_ref);
}

/* The edge scene with the camera set again before every frame (the view counts as moving: the
 * resolve in motion runs, with reprojection and clip, not a still) for `frames` frames; `then`, if
 * any, set before the last. The last frame's RMSE to the 8x8 supersampled truth (in ref). */
static double moving_view(const char *const *settings, int frames, const char *then) {
    char json[2048], err[256];
    edge_scene(json, sizeof json, 17);
    sl_harness *h = open_json(json, settings);
    if (!h) return -1;
    const float eye[3] = {0, 0, 3}, target[3] = {0, 0, 0};
    for (int f = 0; f < frames; f++) {
        if (then && f == frames - 1) CHECK_MSG(sl_harness_set(h, then, err, sizeof err), "%s", err);
        CHECK(sl_harness_set_camera(h, eye, target) && sl_harness_render(h, img));
    }
    sl_harness_destroy(h);
    return rmse(img, ref);
}

/* TAAU in motion: no ghost behind a moving edge (beyond the 3x3 render-size box, 4 px), and a new
 * render scale keeps the history at the output size: with the view moving (but for its jitter, in
 * place), the frame after a switch from 0.5 to 0.6 stays as close to the truth as its history was,
 * not as far as a first frame at 0.6; TAA at the render size restarts there. */
static void test_taau_motion(void) {
    double e_moving;
    const char *s_up[] = {"aa.taa_frames=8", "core.render_scale=0.5", "aa.taa_upscale=true", NULL};
    double ghost_up = moving_edge(s_up, 12, NULL, 4.0, &e_moving);
    printf("moving edge at render scale 0.5, TAAU: largest value 4 px behind the edge %.4f, edge RMSE %.4f\n", ghost_up,
           e_moving);
    CHECK_MSG(ghost_up >= 0 && ghost_up <= 0.01, "TAAU leaves a ghost behind a moving edge: %g", ghost_up);

    char json[2048];
    edge_scene(json, sizeof json, 17);
    const char *s_ref[] = {"aa.method=none", "core.ssaa=8", NULL};
    if (!render_still(json, s_ref, 1, ref)) return;
    const char *s_taau[] = {"aa.taa_frames=16", "core.render_scale=0.5", "aa.taa_upscale=true", NULL};
    const char *s_first[] = {"aa.taa_frames=16", "core.render_scale=0.6", "aa.taa_upscale=true", NULL};
    const char *s_bilinear[] = {"aa.taa_frames=16", "core.render_scale=0.5", NULL};
    double before = moving_view(s_taau, 24, NULL), after = moving_view(s_taau, 25, "core.render_scale=0.6");
    double first = moving_view(s_first, 1, NULL), restarted = moving_view(s_bilinear, 25, "core.render_scale=0.6");
    printf("edge 17 deg, view moving in place: RMSE to ssaa=8 after 24 frames at render scale 0.5 %.5f, one frame after "
           "a switch to 0.6 %.5f, a first frame at 0.6 %.5f; TAA at the render size after the switch %.5f\n", before,
           after, first, restarted);
    CHECK_MSG(after <= 0.7 * first, "after a new render scale TAAU's frame (RMSE %.5f) is not closer to the truth than a "
              "first frame (%.5f): its history was not kept", after, first);
    CHECK_MSG(after <= 1.25 * before, "a new render scale lost TAAU's history: RMSE %.5f after, %.5f before", after, before);
}

/* Without TAA nothing upscales (taa_upscale on or not): FXAA runs at the render size and the image
 * is scaled up bilinearly, as a render at the render size scaled up here. */
static void test_fxaa_not_upscaled(void) {
    char json[2048];
    edge_scene(json, sizeof json, 17);
    static float small[(W / 2) * (H / 2) * 4];
    const char *s_small[] = {"aa.method=fxaa", "aa.taa_upscale=true", NULL};
    const char *s_scaled[] = {"aa.method=fxaa", "core.render_scale=0.5", "aa.taa_upscale=true", NULL};
    char err[4096] = "";
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W / 2,
                                                         .height = H / 2, .scene_json = json, .settings = s_small,
                                                         .strict = true},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "harness: %s", err);
    if (!h) return;
    CHECK(sl_harness_render(h, small));
    sl_harness_destroy(h);
    if (!render_still(json, s_scaled, 1, img)) return;
    double worst = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            /* bilinear at pixel centres, clamped at the edges (the window's present) */
            double fy = fmin(fmax((y + 0.5) / 2 - 0.5, 0), H / 2 - 1), fx = fmin(fmax((x + 0.5) / 2 - 0.5, 0), W / 2 - 1);
            int y0 = (int)fy, x0 = (int)fx, y1 = y0 + 1 < H / 2 ? y0 + 1 : y0, x1 = x0 + 1 < W / 2 ? x0 + 1 : x0;
            double ay = fy - y0, ax = fx - x0;
            const float *s00 = small + (y0 * (W / 2) + x0) * 4, *s01 = small + (y0 * (W / 2) + x1) * 4;
            const float *s10 = small + (y1 * (W / 2) + x0) * 4, *s11 = small + (y1 * (W / 2) + x1) * 4;
            double expect = (s00[1] * (1 - ax) + s01[1] * ax) * (1 - ay) + (s10[1] * (1 - ax) + s11[1] * ax) * ay;
            worst = fmax(worst, fabs(img[(y * W + x) * 4 + 1] - expect));
        }
    printf("fxaa at render scale 0.5 against a render at half size scaled up bilinearly: largest difference %.2g\n", worst);
    CHECK_MSG(worst <= 1e-3, "FXAA at render scale 0.5 is not the half-size FXAA image scaled up bilinearly (%g)", worst);
}

/* "still": the still tests alone (ctest aa_no_fbfetch runs them with Mesa's framebuffer fetch
 * hidden, MESA_EXTENSION_OVERRIDE: a still then reads its history as a texture, ping-pong, in
 * the colour target's format, where it otherwise updates an RGBA32F history in place) */
int main(int argc, char **argv) {
    test_taa_still();
    test_taa_still_exact();
    test_taa_over_ssaa();
    test_taa_texture_still();
    if (argc > 1 && !strcmp(argv[1], "still")) return check_result();
    test_fxaa();
    test_taa_ghost();
    test_taau_still();
    test_taau_motion();
    test_fxaa_not_upscaled();
    return check_result();
}
