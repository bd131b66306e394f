/* The two bias failure regions, at the default bias, for every filter and light type:
 *   acne: a plane lit at 80°–89° from its normal (nothing occludes it) has < 0.1% of its lit
 *     pixels shadowed (visibility < 0.99); with every bias off the same measurement finds acne;
 *   peter-panning: the shadow of a box resting on the plane starts within 2 pixels of the
 *     contact line (top view, rows through the box); a large normal offset is caught. */
#include "shadow_test.h"

#define W 128
#define H 96
static float img[W * H * 4], lit[W * H * 4];

/* Fraction of lit plane pixels whose visibility is below 0.99. */
static double acne_fraction(const float *sh, const float *un, int *lit_pixels) {
    int n = 0, bad = 0;
    for (int i = 0; i < W * H; i++) {
        if (un[i * 4] < 1e-6) continue;
        n++;
        bad += ss_ratio(sh, un, i) < 0.99;
    }
    *lit_pixels = n;
    return n ? (double)bad / n : 1;
}

static const char *acne_scene =
    "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 6, 8], \"target\": [0, 0, 0], \"fov_y\": 50}],\n"
    " \"materials\": [{\"name\": \"m\", \"base_color\": [0.7, 0.7, 0.7]}],\n"
    " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 30}, \"material\": \"m\"}],\n"
    " \"lights\": [%s]}";

static void test_acne(void) {
    char lights[512], json[2048];
    double worst_default = 0, least_unbiased = 1;
    /* directional lights at 80°, 83°, 86°, 89° from the normal; a spot and a point light low
     * over the plane (incidence 80°–89.5° over the visible part) */
    for (int k = 0; k < 6; k++) {
        char what[64];
        if (k < 4) {
            double a = (80 + 3 * k) * M_PI / 180;
            snprintf(lights, sizeof lights,
                     "{\"name\": \"L\", \"type\": \"directional\", \"direction\": [%.9f, %.9f, 0.3], \"intensity\": 5, "
                     "\"cast_shadows\": true}", sin(a), -cos(a));
            snprintf(what, sizeof what, "directional %d deg", 80 + 3 * k);
        } else if (k == 4) {
            snprintf(lights, sizeof lights,
                     "{\"name\": \"L\", \"type\": \"spot\", \"position\": [-6, 0.25, 2], \"direction\": [1, -0.08, -0.3], "
                     "\"intensity\": 200, \"cone_angle\": 50, \"cast_shadows\": true}");
            snprintf(what, sizeof what, "spot 0.25 m over the plane");
        } else {
            snprintf(lights, sizeof lights,
                     "{\"name\": \"L\", \"type\": \"point\", \"position\": [-5, 0.3, -1], \"intensity\": 200, "
                     "\"cast_shadows\": true}");
            snprintf(what, sizeof what, "point 0.3 m over the plane");
        }
        snprintf(json, sizeof json, acne_scene, lights);
        sl_harness *h = ss_make(W, H, json, NULL);
        CHECK(h != NULL);
        if (!h) continue;
        for (int f = 0; f < 4; f++) {
            CHECK(ss_set(h, "spotlight-shadow.filter=%s", ss_filters[f]) && ss_render_pair(h, img, lit));
            int n;
            double frac = acne_fraction(img, lit, &n);
            printf("acne, %-26s %-7s: %.4f%% of %d lit pixels shadowed\n", what, ss_filters[f], 100 * frac, n);
            CHECK(n > W * H / 3);
            CHECK_MSG(frac < 1e-3, "%s, %s: acne on %.3f%% of the plane", what, ss_filters[f], 100 * frac);
            worst_default = fmax(worst_default, frac);
            CHECK(sl_harness_count_nonfinite(img, W, H) == 0);
        }
        /* the measurement sees acne when the biases are off */
        CHECK(ss_set(h, "spotlight-shadow.filter=hard") && ss_set(h, "spotlight-shadow.bias_constant=0") &&
              ss_set(h, "spotlight-shadow.bias_slope=0") && ss_set(h, "spotlight-shadow.normal_offset=0") &&
              ss_set(h, "spotlight-shadow.receiver_plane=false") && ss_render_pair(h, img, lit));
        int n;
        double frac = acne_fraction(img, lit, &n);
        printf("acne, %-26s without bias: %.2f%% shadowed\n", what, 100 * frac);
        least_unbiased = fmin(least_unbiased, frac);
        sl_harness_destroy(h);
    }
    printf("acne: worst %.4f%% at the default bias; at least %.1f%% without bias\n", 100 * worst_default, 100 * least_unbiased);
    CHECK_MSG(least_unbiased > 0.05, "the acne measurement does not see unbiased acne (%.3f)", least_unbiased);
}

/* Top view of a 1 x 0.25 x 1 box resting on the plane at the origin, lit from -X: the shadow lies at
 * x > 0.5. Returns the largest gap (pixels) between the contact line and the first shadowed
 * ground pixel over the rows through the box; -1 if a row has no shadow. */
static const test_camera top = {{0.8f, 25, 0.01f}, {0.8f, 0, 0}, 8, W, H};

static int contact_gap(const float *sh, const float *un, double shadow_length) {
    int worst = 0, rows = 0;
    for (int y = 0; y < H; y++) {
        float p[3];
        if (!test_camera_hit_ground(&top, W / 2, y, 50, p) || fabsf(p[2]) > 0.35f) continue;
        int c0 = -1, c1 = -1;
        for (int x = 0; x < W; x++) {
            if (!test_camera_hit_ground(&top, x, y, 50, p)) continue;
            if (p[0] <= 0.5f + 1e-3f) continue; /* the box (its top and the side facing the camera) */
            if (c0 < 0) c0 = x;
            if (p[0] > 0.5f + 0.6 * shadow_length) break;
            if (ss_ratio(sh, un, y * W + x) < 0.5) { c1 = x; break; }
        }
        rows++;
        if (c0 < 0 || c1 < 0) return -1;
        if (c1 - c0 > worst) worst = c1 - c0;
    }
    return rows > 10 ? worst : -1;
}

static void test_peter_panning(void) {
    const char *scene =
        "{\"cameras\": [{\"name\": \"c\", \"position\": [0.8, 25, 0.01], \"target\": [0.8, 0, 0], \"fov_y\": 8}],\n"
        " \"materials\": [{\"name\": \"m\", \"base_color\": [0.7, 0.7, 0.7]}, {\"name\": \"b\", \"base_color\": [0.2, 0.5, 0.2]}],\n"
        " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 16}, \"material\": \"m\"},\n"
        "           {\"name\": \"box\", \"translate\": [0, 0.125, 0], \"scale\": [1, 0.25, 1], \"mesh\": {\"primitive\": \"cube\", \"size\": 1}, \"material\": \"b\"}],\n"
        " \"lights\": [%s]}";
    char lights[512], json[2048];
    for (int k = 0; k < 4; k++) {
        double elev = (k == 0 ? 30 : k == 1 ? 45 : 60) * M_PI / 180;
        char what[64];
        if (k < 3) {
            snprintf(lights, sizeof lights,
                     "{\"name\": \"L\", \"type\": \"directional\", \"direction\": [%.9f, %.9f, 0], \"intensity\": 3, "
                     "\"cast_shadows\": true}", cos(elev), -sin(elev));
            snprintf(what, sizeof what, "directional at %.0f deg", elev * 180 / M_PI);
        } else {
            elev = 45 * M_PI / 180;
            snprintf(lights, sizeof lights,
                     "{\"name\": \"L\", \"type\": \"spot\", \"position\": [-2.5, 3, 0], \"direction\": [1, -1, 0], "
                     "\"intensity\": 40, \"cone_angle\": 35, \"cast_shadows\": true}");
            snprintf(what, sizeof what, "spot at 45 deg");
        }
        double len = 0.25 / tan(elev);
        snprintf(json, sizeof json, scene, lights);
        sl_harness *h = ss_make(W, H, json, NULL);
        CHECK(h != NULL);
        if (!h) continue;
        for (int f = 0; f < 4; f++) {
            CHECK(ss_set(h, "spotlight-shadow.filter=%s", ss_filters[f]) && ss_render_pair(h, img, lit));
            int gap = contact_gap(img, lit, len);
            printf("peter-panning, %-24s %-7s: shadow starts %d px from the contact line\n", what, ss_filters[f], gap);
            CHECK_MSG(gap >= 0 && gap <= 2, "%s, %s: gap of %d pixels", what, ss_filters[f], gap);
            CHECK(sl_harness_count_nonfinite(img, W, H) == 0);
        }
        /* a lookup pushed 200 texels towards the light floats the shadow: the measurement sees it */
        CHECK(ss_set(h, "spotlight-shadow.filter=hard") && ss_set(h, "spotlight-shadow.bias_constant=200") &&
              ss_render_pair(h, img, lit));
        int gap = contact_gap(img, lit, len);
        printf("peter-panning, %-24s constant bias 200 texels: %d px\n", what, gap);
        CHECK_MSG(gap < 0 || gap > 2, "a floating shadow was not detected (%d px)", gap);
        sl_harness_destroy(h);
    }
}

int main(void) {
    test_acne();
    test_peter_panning();
    return check_result();
}
