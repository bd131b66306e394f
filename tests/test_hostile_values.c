/* Hostile values (issue 14): NaN/Inf/negative/huge inputs never reach the image as NaN, Inf or
 * negative radiance with exit 0. Policies checked here:
 *   - texture files: sanitised at load (NaN, -Inf, negatives -> 0; +Inf and > 65504 -> 65504),
 *     one warning naming the file and the counts;
 *   - light intensity and colour: the same ranges from a scene file as from --set (intensity 1e30
 *     and colour 3e38 refused, naming the scene line); the largest allowed light renders finite;
 *   - environment colour x intensity above what the RGBA16F target holds (65504): refused;
 *   - the forward pass clamps radiance at 65504 instead of writing Inf (the default RGBA16F target). */
#include "check.h"
#include "test_tmp.h"
#include <shadelab/harness.h>
#include "image/image.h"
#include "log.h"
#include <stdlib.h>

#define W 48
#define H 32
static float img[W * H * 4];
static char json[4096], err[4096], logbuf[16384];

static sl_harness *make(const char *text) {
    return sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                .scene_json = text},
                             err, sizeof err);
}

#define PLANE(MAT, LIGHT, ENV)                                                                                       \
    "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 3, 3], \"target\": [0, 0, 0]}],\n"                          \
    " \"materials\": [{\"name\": \"m\" " MAT "}],\n"                                                                \
    " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 10}, \"material\": \"m\"}],\n" \
    " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, -0.3] " LIGHT "}]" ENV "}"

static void expect_finite(const char *what) {
    long nonfinite = sl_harness_count_nonfinite(img, W, H), negative = sl_harness_count_negative(img, W, H);
    float peak = 0;
    for (int i = 0; i < W * H * 4; i++) peak = img[i] > peak ? img[i] : peak;
    printf("%-40s non-finite %ld, negative %ld, peak %g\n", what, nonfinite, negative, peak);
    CHECK_MSG(nonfinite == 0 && negative == 0, "%s: %ld non-finite, %ld negative", what, nonfinite, negative);
    CHECK_MSG(peak <= 65504, "%s: radiance %g over the colour target's maximum", what, peak);
}

int main(void) {
    /* 1. an EXR texture with NaN, +Inf, -Inf, negative and huge texels */
    char path[4096];
    snprintf(path, sizeof path, "%s/poison.exr", sl_test_dir());
    float tex[4 * 4 * 4];
    for (int i = 0; i < 64; i++) tex[i] = 0.5f;
    tex[0] = NAN, tex[5] = INFINITY, tex[10] = -INFINITY, tex[16] = -3.0f, tex[21] = 60000.0f, tex[26] = 1e6f;
    CHECK_MSG(sl_image_write(path, tex, 4, 4, false, err, sizeof err), "%s", err);
    snprintf(json, sizeof json, PLANE(", \"base_color_map\": \"%s\"", ", \"intensity\": 3", ""), path);
    sl_log_capture(logbuf, sizeof logbuf);
    sl_harness *h = make(json);
    CHECK_MSG(h != NULL, "%s", err);
    if (h) {
        CHECK(sl_harness_render(h, img));
        sl_log_capture(NULL, 0);
        expect_finite("EXR texture with NaN/Inf/negative texels");
        CHECK_CONTAINS(logbuf, "poison.exr: replaced");
        sl_harness_destroy(h);
    }
    sl_log_capture(NULL, 0);

    /* 2. a light intensity the schema refuses from --set is refused from the scene too */
    h = make(PLANE("", ", \"intensity\": 1e30", ""));
    CHECK_MSG(h == NULL, "intensity 1e30 accepted from a scene");
    if (h) sl_harness_destroy(h);
    CHECK_CONTAINS(err, "<text>:4");
    CHECK_CONTAINS(err, "intensity");
    printf("intensity 1e30 in a scene: %s\n", err);

    /* 3. a colour beyond what a pixel holds is refused; the largest allowed light renders finite */
    h = make(PLANE("", ", \"intensity\": 1, \"color\": [3e38, 3e38, 3e38]", ""));
    CHECK_MSG(h == NULL, "light colour 3e38 accepted");
    if (h) sl_harness_destroy(h);
    CHECK_CONTAINS(err, "must be <= 65504");
    h = make(PLANE("", ", \"intensity\": 1e10, \"color\": [65504, 65504, 65504]", ""));
    CHECK_MSG(h != NULL, "%s", err);
    if (h) {
        CHECK(sl_harness_render(h, img));
        expect_finite("light colour 65504 x intensity 1e10");
        sl_harness_destroy(h);
    }

    /* 4. an environment brighter than the colour target holds: refused, naming the line */
    h = make(PLANE("", "", ", \"environment\": {\"color\": [3e38, 0, 0]}"));
    CHECK_MSG(h == NULL, "environment colour 3e38 accepted");
    if (h) sl_harness_destroy(h);
    CHECK_CONTAINS(err, "more radiance than the colour target holds");
    printf("environment colour 3e38: %s\n", err);

    /* 5. radiance over 65504 from an allowed light: clamped, not Inf */
    h = make(PLANE("", ", \"intensity\": 1e6", ""));
    CHECK_MSG(h != NULL, "%s", err);
    if (h) {
        CHECK(sl_harness_render(h, img));
        expect_finite("directional light of 1e6 W/m2");
        float centre = img[4 * (H / 2 * W + W / 2)];
        CHECK_MSG(centre == 65504.0f, "centre radiance %g: expected the clamp 65504", centre);
        sl_harness_destroy(h);
    }
    return check_result();
}
