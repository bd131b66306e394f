/* Headless test of the ssao example (link shadelab::harness), each claim against a closed form:
 *   open plane   a plane with nothing above it is not occluded: the image equals ssao off
 *   corner       in a 90° corner lit by a uniform environment only, ambient at the crease is
 *                halved (the wall closes half of the cosine-weighted hemisphere: occluded share
 *                1/2), and points farther than ssao.radius from the other plane are not darkened
 *   direct       the same corner lit by a directional light only: the image equals ssao off
 *   live         half resolution and strength change live; strength 0 equals ssao off
 *   pass view    the "ssao-visibility" debug view shows the visibility as it is (no tone mapping)
 * Ambient-only Lambert: radiance = base_color × environment × visibility, so the ratio of the
 * images with ssao on and off is the visibility. */
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 96
#define H 96
static int failures;
#define CHECK(cond, ...) do { if (!(cond)) { failures++; printf("FAIL %s:%d: ", __FILE__, __LINE__); printf(__VA_ARGS__); printf("\n"); } } while (0)

/* a floor (y = 0, z in [0, 6]) meeting a wall (z = 0, y in [0, 6]) along the x axis */
static const char *corner =
    "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 2.2, 4.2], \"target\": [0, 0.4, 0.4], \"fov_y\": 50}],\n"
    " \"materials\": [{\"name\": \"m\", \"model\": \"lambert\", \"base_color\": [0.8, 0.8, 0.8]}],\n"
    " \"nodes\": [{\"name\": \"floor\", \"translate\": [0, 0, 3], \"mesh\": {\"primitive\": \"plane\", \"size\": 6}, \"material\": \"m\"},\n"
    "           {\"name\": \"wall\", \"translate\": [0, 3, 0], \"rotate\": [90, 0, 0], \"mesh\": {\"primitive\": \"plane\", \"size\": 6}, \"material\": \"m\"}],\n"
    " \"environment\": {\"color\": [1, 1, 1], \"intensity\": %s}%s}\n";
static const char *sun = ",\n \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [-0.3, -1, -0.6], \"intensity\": 2}]";

static const char *open_plane =
    "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 3, 3], \"target\": [0, 0, 0], \"fov_y\": 50}],\n"
    " \"materials\": [{\"name\": \"m\", \"model\": \"lambert\", \"base_color\": [0.8, 0.8, 0.8]}],\n"
    " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 40}, \"material\": \"m\"}],\n"
    " \"environment\": {\"color\": [1, 1, 1], \"intensity\": 1}}\n";

static sl_harness *open_harness(const char *scene, const char *const *settings) {
    const char *plugins[] = {SSAO_PLUGIN_PATH, NULL};
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                         .scene_json = scene, .plugins = plugins, .settings = settings,
                                                         .float32 = true, .strict = true},
                                      err, sizeof err);
    if (!h) { printf("FAIL: harness: %s\n", err); exit(1); }
    return h;
}

static float *render(const char *scene, const char *const *settings) {
    sl_harness *h = open_harness(scene, settings);
    float *img = malloc(sizeof(float) * W * H * 4);
    if (!sl_harness_render(h, img)) { printf("FAIL: render\n"); exit(1); }
    sl_harness_destroy(h);
    return img;
}

static const char *off[] = {"ssao.enabled=false", NULL};

static double max_diff(const float *a, const float *b) {
    double m = 0;
    for (int i = 0; i < W * H * 4; i++) m = fmax(m, fabs(a[i] - b[i]));
    return m;
}

/* visibility per pixel: ratio of the green channels (0 where nothing was drawn) */
static void visibility(const float *on, const float *ref, float *v) {
    for (int i = 0; i < W * H; i++) v[i] = ref[i * 4 + 1] > 1e-3f ? on[i * 4 + 1] / ref[i * 4 + 1] : 0;
}

int main(void) {
    char scene[4096];
    static float v[W * H];

    /* open plane: nothing above it, nothing occluded */
    float *on = render(open_plane, NULL), *ref = render(open_plane, off);
    CHECK(max_diff(on, ref) <= 1e-5, "open plane: ssao darkened it (max diff %g)", max_diff(on, ref));
    free(on), free(ref);

    /* corner, ambient light only */
    snprintf(scene, sizeof scene, corner, "1", "");
    on = render(scene, NULL), ref = render(scene, off);
    visibility(on, ref, v);
    /* down the middle column: the wall, the crease, the floor; the crease is where v is least */
    int x = W / 2, crease = 0;
    for (int y = 0; y < H; y++)
        if (v[y * W + x] > 0 && v[y * W + x] < v[crease * W + x]) crease = y;
    float least = v[crease * W + x];
    CHECK(least > 0.40f && least < 0.62f, "corner: visibility at the crease %.3f, expected about 1/2", least);
    /* the top rows of the wall and the bottom rows of the floor are farther than the radius (0.5)
     * from the other plane: open */
    float top = v[2 * W + x], bottom = v[(H - 3) * W + x];
    CHECK(fabsf(top - 1) < 1e-3f && fabsf(bottom - 1) < 1e-3f, "corner: far from the crease visibility %.4f (wall) "
          "%.4f (floor), expected 1", top, bottom);
    /* it falls towards the crease from both sides */
    CHECK(v[(crease - 3) * W + x] > least && v[(crease + 3) * W + x] > least, "corner: not least at the crease");
    printf("corner: visibility %.3f at the crease (row %d), %.4f and %.4f far from it\n", least, crease, top, bottom);
    CHECK(sl_harness_count_nonfinite(on, W, H) == 0, "corner: non-finite pixels");

    /* the pass view shows the visibility as it is */
    {
        sl_harness *h = open_harness(scene, NULL);
        char err[512];
        CHECK(sl_harness_set_debug_view(h, "ssao-visibility", err, sizeof err), "%s", err);
        static float display[W * H * 4];
        CHECK(sl_harness_render(h, NULL) && sl_harness_read_display(h, display), "pass view: render");
        float shown_top = display[(2 * W + x) * 4], shown_crease = display[(crease * W + x) * 4];
        CHECK(fabsf(shown_top - 1) < 1.5f / 255 && fabsf(shown_crease - least) < 0.03f,
              "pass view: shows %.3f far and %.3f at the crease, the pass computed 1 and %.3f", shown_top,
              shown_crease, least);
        sl_harness_destroy(h);
    }

    /* live: half resolution still darkens the crease about as much; strength 0 is no change */
    {
        sl_harness *h = open_harness(scene, NULL);
        char err[512];
        float *img = malloc(sizeof(float) * W * H * 4);
        CHECK(sl_harness_set(h, "ssao.half_resolution=true", err, sizeof err), "%s", err);
        CHECK(sl_harness_render(h, img), "half resolution: render");
        visibility(img, ref, v);
        /* the crease's row is blurred into the rows beside it by the half-size target's filtering */
        CHECK(v[crease * W + x] < 0.75f && v[crease * W + x] != least, "half resolution: crease %.3f, full %.3f",
              v[crease * W + x], least);
        CHECK(fabsf(v[2 * W + x] - 1) < 1e-3f, "half resolution: far from the crease %.4f", v[2 * W + x]);
        CHECK(sl_harness_set(h, "ssao.strength=0", err, sizeof err), "%s", err);
        CHECK(sl_harness_render(h, img), "strength 0: render");
        CHECK(max_diff(img, ref) <= 1e-5, "strength 0 differs from off (max %g)", max_diff(img, ref));
        free(img);
        sl_harness_destroy(h);
    }
    free(on), free(ref);

    /* direct light only (no environment): untouched */
    snprintf(scene, sizeof scene, corner, "0", sun);
    on = render(scene, NULL), ref = render(scene, off);
    CHECK(max_diff(on, ref) <= 1e-5, "direct light: ssao changed it (max diff %g)", max_diff(on, ref));
    float lit = 0;
    for (int i = 0; i < W * H; i++) lit = fmaxf(lit, ref[i * 4 + 1]);
    CHECK(lit > 0.1f, "direct light: the scene is dark (%g)", lit);
    free(on), free(ref);

    if (failures) { printf("%d check(s) failed\n", failures); return 1; }
    printf("ssao: open plane, corner, direct light, live changes and the pass view match\n");
    return 0;
}
