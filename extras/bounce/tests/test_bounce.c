/* bounce tests (headless, llvmpipe), on scenes/bounce_wall.json: a Lambert floor under a sun
 * straight down and a block floating above it whose vertical sides the sun does not light.
 *   - the block's +x side against the floor's form factor, integrated here (midpoint rule): its
 *     radiance is ρ_block/π × ∫ ρ_floor E/π · cos θ_floor cos θ_side / r² dA over the floor, per
 *     channel (the floor's colour carried over), at three heights; closer with more probes and
 *     virtual lights. What the method gives up (README "Accuracy"): order-2 harmonics read this
 *     floor 1.2-2.8 % dark, and the lookup half a cell out of the surface 0.8-4.4 % more;
 *   - the floor does not light itself: its radiance stays ρ/π × E within 2 % (order-2 harmonics
 *     give a light along the surface's plane 0.094 of its irradiance instead of 0);
 *   - switched off: no pass, no light: the side is black;
 *   - hostile scenes (flat, lit from below, a 10¹⁰ sun, five suns, a huge ground, the camera
 *     inside): finite.
 * Live switching equals a fresh start: the toggle matrix (tests/test_toggle_matrix.c in shadelab)
 * runs this scene. */
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures;
#define CHECK(c, ...) do { if (!(c)) { failures++; printf("FAIL %s:%d: ", __FILE__, __LINE__); printf(__VA_ARGS__); printf("\n"); } } while (0)

enum { W = 160, H = 96 };
/* bounce_wall.json, as written there */
static const double FLOOR_HALF = 4, FLOOR_RHO[3] = {0.5, 0.25, 0.1}, BLOCK_RHO = 0.8, SIDE_X = 0.2, SUN_E = 1;
static const double CAM[3] = {6, 1.5, 0}, FOV_Y = 40;

/* The side's irradiance at (SIDE_X, h, z), normal +x, from the floor of unit radiosity, by the
 * midpoint rule on a 1600² grid (the floor behind the side, x < SIDE_X, sends it nothing). */
static double side_irradiance(double h, double z) {
    const int N = 1600;
    double step = 2 * FLOOR_HALF / N, sum = 0;
    for (int i = 0; i < N; i++) {
        double x = -FLOOR_HALF + (i + 0.5) * step - SIDE_X;
        if (x <= 0) continue;
        for (int k = 0; k < N; k++) {
            double dz = -FLOOR_HALF + (k + 0.5) * step - z, r2 = x * x + h * h + dz * dz;
            sum += h * x / (r2 * r2);
        }
    }
    return sum * step * step / M_PI;
}

/* The pixel where world point p lands (the scene's camera looks along −x, up +y, so +z is left). */
static void pixel_of(const double p[3], int *col, int *row) {
    double d = CAM[0] - p[0], t = tan(FOV_Y * M_PI / 360), aspect = (double)W / H;
    double nx = -(p[2] - CAM[2]) / (d * t * aspect), ny = (p[1] - CAM[1]) / (d * t);
    *col = (int)((nx + 1) / 2 * W), *row = (int)((1 - ny) / 2 * H);
}

static void mean3x3(const float *img, const double p[3], double out[3]) {
    int c, r;
    pixel_of(p, &c, &r);
    out[0] = out[1] = out[2] = 0;
    for (int y = r - 1; y <= r + 1; y++)
        for (int x = c - 1; x <= c + 1; x++)
            for (int k = 0; k < 3; k++) out[k] += img[((size_t)y * W + x) * 4 + k] / 9;
}

static sl_harness *open_scene(const char *const *settings) {
    char err[2048];
    const char *plugins[] = {BOUNCE_PLUGIN, NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
        .scene_file = BOUNCE_SCENES "/bounce_wall.json", .plugins = plugins, .settings = settings, .float32 = true,
        .strict = true}, err, sizeof err);
    CHECK(h, "harness: %s", err);
    return h;
}

/* The side's largest relative error (over heights and channels) at these settings; -1 on failure. */
static double side_error(const char *const *settings, const char *what) {
    sl_harness *h = open_scene(settings);
    if (!h) return -1;
    float *img = malloc(sizeof(float) * 4 * W * H);
    bool ok = sl_harness_render(h, img);
    CHECK(ok, "%s: render", what);
    double worst = 0;
    const double heights[3] = {0.9, 1.5, 2.1};
    for (int i = 0; ok && i < 3; i++) {
        double p[3] = {SIDE_X, heights[i], 0}, got[3], E = side_irradiance(heights[i], 0) * SUN_E;
        mean3x3(img, p, got);
        for (int k = 0; k < 3; k++) {
            double want = BLOCK_RHO / M_PI * FLOOR_RHO[k] * E, rel = fabs(got[k] / want - 1);
            printf("  %s: side at h = %.1f, channel %d: %.5f, form factor %.5f (%+.1f %%)\n", what, heights[i], k, got[k],
                   want, 100 * (got[k] / want - 1));
            worst = fmax(worst, isfinite(rel) ? rel : 1e9);
        }
    }
    free(img);
    sl_harness_destroy(h);
    return ok ? worst : -1;
}

static void test_side_against_form_factor(void) {
    const char *coarse[] = {"bounce.vpls=8", "bounce.grid=6", NULL}, *fine[] = {"bounce.vpls=32", "bounce.grid=32", NULL};
    double e_default = side_error(NULL, "default"), e_coarse = side_error(coarse, "vpls 8, grid 6"),
           e_fine = side_error(fine, "vpls 32, grid 32");
    printf("side against the form factor: largest error %.3f (defaults), %.3f (coarse), %.3f (fine)\n", e_default, e_coarse,
           e_fine);
    CHECK(e_default >= 0 && e_default < 0.08, "defaults: largest error %.3f, want < 0.08", e_default);
    CHECK(e_fine >= 0 && e_fine < 0.065, "fine: largest error %.3f, want < 0.065", e_fine);
    CHECK(e_fine < e_coarse, "more probes and virtual lights do not come closer: %.3f against %.3f", e_fine, e_coarse);
}

static void test_floor_and_off(void) {
    const char *off[] = {"bounce.enabled=false", NULL};
    float *on_img = malloc(sizeof(float) * 4 * W * H), *off_img = malloc(sizeof(float) * 4 * W * H);
    sl_harness *h = open_scene(NULL);
    bool ok = h && sl_harness_render(h, on_img);
    if (h) sl_harness_destroy(h);
    h = open_scene(off);
    ok = ok && h && sl_harness_render(h, off_img);
    sl_harness_structure st = {0};
    if (h) sl_harness_structure_of(h, &st), sl_harness_destroy(h);
    CHECK(ok, "renders");
    if (ok) {
        const double floor_p[3] = {0.5, 0, 2.5}, side_p[3] = {SIDE_X, 1.5, 0};
        double f_on[3], f_off[3], s_off[3];
        mean3x3(on_img, floor_p, f_on);
        mean3x3(off_img, floor_p, f_off);
        mean3x3(off_img, side_p, s_off);
        for (int k = 0; k < 3; k++) {
            double want = FLOOR_RHO[k] / M_PI * SUN_E;
            CHECK(fabs(f_on[k] / want - 1) < 0.02, "floor channel %d with bounce: %.5f, want ρ/π E = %.5f", k, f_on[k], want);
            CHECK(fabs(f_off[k] / want - 1) < 0.01, "floor channel %d off: %.5f, want %.5f", k, f_off[k], want);
            CHECK(fabs(s_off[k]) < 1e-5, "side channel %d with bounce off: %.6f, want 0", k, s_off[k]);
        }
        for (int i = 0; i < st.pass_count; i++) CHECK(strcmp(st.passes[i], "bounce"), "off: the bounce pass ran");
    }
    free(on_img), free(off_img);
}

/* Scenes a user may give it: flat (a plane alone, no height to place probes in), lit from below
 * and by a sun of the largest intensity a light takes (10¹⁰: sums past half floats' range),
 * more directional lights than it bounces, a ground plane 10⁵ m wide under a small block, a
 * camera inside the block: finite pixels, no failure (the ground at the highest knobs too). */
static void test_hostile(void) {
    static const char *const scenes[] = {
        "{\"plugins\": [\"bounce\"], \"nodes\": [{\"name\": \"p\", \"mesh\": {\"primitive\": \"plane\"}}], "
        "\"lights\": [{\"name\": \"up\", \"type\": \"directional\", \"direction\": [0, 1, 0]}, "
        "{\"name\": \"down\", \"type\": \"directional\", \"direction\": [0.3, -1, 0], \"intensity\": 1e10}]}",
        "{\"plugins\": [\"bounce\"], \"nodes\": [{\"name\": \"p\", \"mesh\": {\"primitive\": \"plane\", \"size\": 100000}}, "
        "{\"name\": \"b\", \"translate\": [0, 0.5, 0], \"mesh\": {\"primitive\": \"cube\"}}], "
        "\"lights\": [{\"name\": \"a\", \"type\": \"directional\", \"direction\": [0, -1, 0]}, "
        "{\"name\": \"b\", \"type\": \"directional\", \"direction\": [1, -1, 0]}, "
        "{\"name\": \"c\", \"type\": \"directional\", \"direction\": [-1, -1, 0]}, "
        "{\"name\": \"d\", \"type\": \"directional\", \"direction\": [0, -1, 1]}, "
        "{\"name\": \"e\", \"type\": \"directional\", \"direction\": [0, -1, -1]}]}",
        "{\"plugins\": [\"bounce\"], \"cameras\": [{\"name\": \"in\", \"position\": [0, 0.5, 0], \"target\": [1, 0.5, 0]}], "
        "\"nodes\": [{\"name\": \"p\", \"mesh\": {\"primitive\": \"plane\"}}, "
        "{\"name\": \"b\", \"translate\": [0, 0.5, 0], \"mesh\": {\"primitive\": \"cube\"}}], "
        "\"lights\": [{\"name\": \"a\", \"type\": \"directional\", \"direction\": [0.2, -1, 0.1]}]}",
    };
    const char *plugins[] = {BOUNCE_PLUGIN, NULL}, *knobs[] = {"bounce.vpls=32", "bounce.grid=32", NULL};
    float *img = malloc(sizeof(float) * 4 * W * H);
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++)
        for (int k = 0; k < (i == 1 ? 2 : 1); k++) { /* the highest knobs on the largest scene only */
            char err[2048];
            sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W,
                .height = H, .scene_json = scenes[i], .plugins = plugins, .settings = k ? knobs : NULL, .strict = true},
                err, sizeof err);
            CHECK(h, "hostile scene %zu: %s", i, err);
            if (!h) continue;
            bool ok = sl_harness_render(h, img);
            CHECK(ok && sl_harness_count_nonfinite(img, W, H) == 0, "hostile scene %zu (%s): render %d, non-finite pixels",
                  i, k ? "highest" : "defaults", ok);
            sl_harness_destroy(h);
        }
    free(img);
}

int main(void) {
    test_side_against_form_factor();
    test_floor_and_off();
    test_hostile();
    if (failures) printf("%d failure(s)\n", failures);
    else printf("all bounce tests passed\n");
    return failures ? 1 : 0;
}
