/* Closed-form image tests of the core's shading: Lambert under directional and point lights
 * (radiance computed per pixel in C from the camera, independently of the renderer), the white
 * furnace, debug views, the display encoding, accumulation and supersampling. */
#include "check.h"
#include <shadelab/harness.h>
#include "camera_rays.h"
#include <stdlib.h>

#define W 96
#define H 72
static float img[W * H * 4], img2[W * H * 4];

static sl_harness *make(const char *json, const char *const *settings) {
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                          .scene_json = json, .settings = settings, .float32 = true},
                                      err, sizeof err);
    if (!h) fprintf(stderr, "harness: %s\n", err);
    return h;
}

/* Camera rays from the same definition the scene gives: position, target, vertical fov. */
static const test_camera cam = {{0, 5, 5}, {0, 0, 0}, 50, W, H};
static bool plane_hit(int px, int py, float hit[3]) { return test_camera_hit_ground(&cam, px, py, 9.5f, hit); }

#define PLANE_SCENE(LIGHTS, ENV) \
    "{ \"cameras\": [{\"name\": \"c\", \"position\": [0,5,5], \"target\": [0,0,0], \"fov_y\": 50, \"near\": 0.1, \"far\": 100}]," \
    "  \"materials\": [{\"name\": \"m\", \"base_color\": [0.7, 0.5, 0.3]}]," \
    "  \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 20}, \"material\": \"m\"}]," \
    "  \"lights\": [" LIGHTS "]" ENV "}"

static void test_directional(void) {
    /* E = 2 arriving at 60° from the normal: L = k_d/π · E · cos 60° */
    sl_harness *h = make(PLANE_SCENE("{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -0.5, -0.8660254], \"intensity\": 2}", ""), NULL);
    CHECK(h != NULL);
    if (!h) return;
    CHECK(sl_harness_render(h, img));
    const float kd[3] = {0.7f, 0.5f, 0.3f};
    int checked = 0;
    for (int y = 0; y < H; y += 7)
        for (int x = 0; x < W; x += 7) {
            float p[3];
            if (!plane_hit(x, y, p)) continue;
            for (int c = 0; c < 3; c++) CHECK_NEAR(img[(y * W + x) * 4 + c], kd[c] / M_PI * 2 * 0.5, 2e-3);
            checked++;
        }
    CHECK_MSG(checked > 50, "only %d plane pixels sampled", checked);
    sl_harness_destroy(h);
}

static void test_point_light(void) {
    /* I = 10 at (0.5, 1.5, -0.3): L = k_d/π · I/d² · max(0, n·l), per pixel from the camera ray */
    sl_harness *h = make(PLANE_SCENE("{\"name\": \"bulb\", \"type\": \"point\", \"position\": [0.5, 1.5, -0.3], \"intensity\": 10}", ""), NULL);
    CHECK(h != NULL);
    if (!h) return;
    CHECK(sl_harness_render(h, img));
    const float kd[3] = {0.7f, 0.5f, 0.3f}, lp[3] = {0.5f, 1.5f, -0.3f};
    int checked = 0;
    double worst = 0;
    for (int y = 0; y < H; y += 5)
        for (int x = 0; x < W; x += 5) {
            float p[3];
            if (!plane_hit(x, y, p)) continue;
            float d[3] = {lp[0] - p[0], lp[1] - p[1], lp[2] - p[2]};
            float d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            float cosv = d[1] / sqrtf(d2);
            for (int c = 0; c < 3; c++) {
                double expect = kd[c] / M_PI * 10 / d2 * cosv;
                double rel = fabs(img[(y * W + x) * 4 + c] - expect) / expect;
                if (rel > worst) worst = rel;
            }
            checked++;
        }
    CHECK_MSG(worst < 0.01, "worst relative error %.4f over %d pixels", worst, checked);
    CHECK(checked > 50);
    /* per-light on/off: disabling the only light leaves the (black) ambient */
    char err[512];
    CHECK(sl_harness_set(h, "light.bulb.enabled=false", err, sizeof err));
    CHECK(sl_harness_render(h, img2));
    double sum = 0;
    for (int i = 0; i < W * H * 4; i += 4) sum += img2[i];
    CHECK_NEAR(sum, 0, 1e-6);
    sl_harness_destroy(h);
}

static void test_furnace(void) {
    /* unit white environment, white Lambert spheres: every pixel reads exactly 1 */
    char path[1024];
    snprintf(path, sizeof path, "%s/furnace.json", SL_SCENES_DIR);
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                          .scene_file = path, .float32 = true}, err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return;
    CHECK(sl_harness_render(h, img));
    double maxdev = 0;
    for (int i = 0; i < W * H * 4; i++)
        if (i % 4 != 3 && fabs(img[i] - 1.0) > maxdev) maxdev = fabs(img[i] - 1.0);
    CHECK_MSG(maxdev < 1e-4, "furnace deviates by %g", maxdev);
    /* the furnace is not trivially white: the normal debug view shows the spheres */
    CHECK(sl_harness_set_debug_view(h, "normal", err, sizeof err));
    CHECK(sl_harness_render(h, img2));
    sl_compare cmp;
    sl_harness_compare(img, img2, W, H, 0.05, &cmp);
    CHECK_MSG(cmp.pixels_over > W * H / 10, "normal view differs on only %ld pixels", cmp.pixels_over);
    sl_harness_destroy(h);
}

static void test_debug_views_and_display(void) {
    sl_harness *h = make(PLANE_SCENE("{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, 0], \"intensity\": 7}", ""), NULL);
    CHECK(h != NULL);
    if (!h) return;
    char err[512];
    /* normal view of an upward plane: (0,1,0)·0.5 + 0.5 */
    CHECK(sl_harness_set_debug_view(h, "normal", err, sizeof err));
    CHECK(sl_harness_render(h, img));
    int c = (H / 2 * W + W / 2) * 4;
    CHECK_NEAR(img[c + 0], 0.5, 1e-3);
    CHECK_NEAR(img[c + 1], 1.0, 1e-3);
    CHECK_NEAR(img[c + 2], 0.5, 1e-3);
    CHECK(sl_harness_set_debug_view(h, "diffuse-texture", err, sizeof err));
    CHECK(sl_harness_render(h, img));
    CHECK_NEAR(img[c + 0], 0.7, 1e-3);
    CHECK(!sl_harness_set_debug_view(h, "normals", err, sizeof err));
    CHECK_CONTAINS(err, "did you mean \"normal\"");
    /* display transform: sRGB(clamp(L)); E = 7 overexposes the red channel (0.7/π·7 > 1) */
    CHECK(sl_harness_set_debug_view(h, "final", err, sizeof err));
    CHECK(sl_harness_render(h, img));
    CHECK(sl_harness_read_display(h, img2));
    double worst = 0;
    for (int i = 0; i < W * H * 4; i++) {
        if (i % 4 == 3) continue;
        float l = img[i] < 0 ? 0 : img[i] > 1 ? 1 : img[i];
        float e = l <= 0.0031308f ? 12.92f * l : 1.055f * powf(l, 1 / 2.4f) - 0.055f;
        if (fabs(img2[i] - e) > worst) worst = fabs(img2[i] - e);
    }
    CHECK_MSG(worst <= 1.0 / 255 + 1e-6, "display encoding off by %g", worst);
    CHECK_NEAR(img2[c + 0], 1.0, 1e-6);
    sl_harness_destroy(h);
}

static void test_accumulate_and_ssaa(void) {
    const char *json = PLANE_SCENE("{\"name\": \"bulb\", \"type\": \"point\", \"position\": [0.5, 1.5, -0.3], \"intensity\": 10}", "");
    sl_harness *h = make(json, NULL);
    CHECK(h != NULL);
    if (!h) return;
    CHECK(sl_harness_render(h, img));
    sl_harness_destroy(h);
    /* a static scene accumulated over 5 frames is the single frame */
    char err[1024];
    h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                             .scene_json = json, .float32 = true, .accumulate = 5}, err, sizeof err);
    CHECK(h != NULL);
    if (!h) return;
    CHECK(sl_harness_render(h, img2));
    sl_compare cmp;
    sl_harness_compare(img, img2, W, H, 1e-5, &cmp);
    CHECK_MSG(cmp.max_abs < 1e-5, "accumulated static frame differs by %g", cmp.max_abs);
    sl_harness_destroy(h);
    /* supersampling changes the silhouette of the plane's far edge but not its smooth interior */
    h = make(json, (const char *[]){"core.ssaa=4", NULL});
    CHECK(h != NULL);
    if (!h) return;
    CHECK(sl_harness_render(h, img2));
    sl_harness_compare(img, img2, W, H, 1e-3, &cmp);
    CHECK_MSG(cmp.pixels_over > 0, "ssaa changed nothing");
    CHECK_MSG(cmp.pixels_over < W * H / 4, "ssaa changed %ld pixels (expected only edges)", cmp.pixels_over);
    int c = (H * 3 / 4 * W + W / 2) * 4;
    CHECK_NEAR(img2[c], img[c], 2e-3 * img[c] + 1e-4);
    sl_harness_destroy(h);
}

/* The default anisotropic filtering keeps edges straight (issue 42): a black-and-white checker
 * floor seen from 0.6 above it, 320 × 160, whose x = 0 checker edge runs straight away from the
 * camera up the middle of the image. Per row (rows 70–149, where it is seen at grazing angles)
 * the edge's width is the second moment of |∂I/∂x| within 20 px of the middle; a straight edge
 * blurring with distance has a width that changes monotonically down the rows, so its "scallop
 * index" Σ|w(y+1) − w(y)| / (max w − min w) is 1, and a stack of disks (llvmpipe's anisotropic
 * filter, the default 8 before issue 42) makes it oscillate. The reference is 8 × 8 supersampled
 * without anisotropic taps: measured 1.00; the default on OSMesa (0 = auto: 1 on a CPU renderer)
 * 2.15; core.anisotropy=8 7.99. The default must stay under 3. */
static double scallop_index(const float *im, int w, int rows0, int rows1, int *rows) {
    double width[160], lo = 1e30, hi = -1e30, tv = 0;
    int n = 0;
    for (int y = rows0; y < rows1 && n < 160; y++) {
        double g[40], sum = 0, c = 0, m2 = 0;
        for (int i = 0; i < 40; i++) {
            int x = w / 2 - 20 + i;
            g[i] = fabs(im[(y * w + x + 1) * 4 + 1] - im[(y * w + x) * 4 + 1]);
            sum += g[i], c += g[i] * (x + 1.0);
        }
        if (sum < 0.3) continue;
        c /= sum;
        for (int i = 0; i < 40; i++) m2 += g[i] * (w / 2 - 20 + i + 1.0 - c) * (w / 2 - 20 + i + 1.0 - c);
        width[n] = sqrt(m2 / sum);
        lo = fmin(lo, width[n]), hi = fmax(hi, width[n]);
        if (n) tv += fabs(width[n] - width[n - 1]);
        n++;
    }
    *rows = n;
    return hi > lo ? tv / (hi - lo) : 0;
}
static void test_anisotropy_default(void) {
    enum { GW = 320, GH = 160 };
    const char *json =
        "{ \"cameras\": [{\"name\": \"c\", \"position\": [0, 0.6, 6], \"target\": [0, 0, -10], \"fov_y\": 30}],"
        "  \"materials\": [{\"name\": \"m\", \"base_color_map\": \"checker:40:1,1,1:0,0,0\"}],"
        "  \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 80}, \"material\": \"m\"}],"
        "  \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, 0], \"intensity\": 3.14159}],"
        "  \"environment\": {\"color\": [0, 0, 0]}}";
    const char *const settings[3][4] = {{"aa.enabled=false", NULL},
                                        {"aa.enabled=false", "core.ssaa=8", "core.anisotropy=1", NULL},
                                        {"aa.enabled=false", "core.anisotropy=8", NULL}};
    const char *what[3] = {"default", "reference (8x8 supersampled, anisotropy 1)", "anisotropy 8"};
    float *im = malloc((size_t)GW * GH * 16);
    double index[3];
    for (int k = 0; k < 3; k++) {
        char err[4096];
        sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = GW, .height = GH,
                                                              .scene_json = json, .settings = settings[k], .float32 = true},
                                          err, sizeof err);
        CHECK_MSG(h != NULL, "%s", err);
        if (!h) continue;
        CHECK(sl_harness_render(h, im));
        int rows;
        index[k] = scallop_index(im, GW, 70, 150, &rows);
        printf("grazing checker edge, %s: %d rows, scallop index %.2f\n", what[k], rows, index[k]);
        CHECK(rows > 50);
        sl_harness_destroy(h);
    }
    free(im);
    CHECK_MSG(index[1] < 1.5, "the reference's edge is not straight (%.2f): the measure is broken", index[1]);
    CHECK_MSG(index[0] < 3, "the default filtering scallops edges at grazing angles: index %.2f (reference %.2f)", index[0], index[1]);
}

/* core.anisotropy: a checker floor seen at grazing angles filters differently with 1 and 8
 * anisotropic taps; a change at run time reaches the textures already loaded (the image equals a
 * fresh harness created with that value). */
static void test_anisotropy(void) {
    const char *json =
        "{ \"cameras\": [{\"name\": \"c\", \"position\": [0, 0.6, 6], \"target\": [0, 0, -4], \"fov_y\": 50}],"
        "  \"materials\": [{\"name\": \"m\", \"base_color_map\": \"checker:64:1,1,1:0,0,0\"}],"
        "  \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 20}, \"material\": \"m\"}],"
        "  \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, 0], \"intensity\": 3}]}";
    static float iso[W * H * 4], def[W * H * 4];
    char err[1024];
    sl_compare cmp;
    sl_harness *h = make(json, (const char *[]){"core.anisotropy=1", NULL});
    CHECK(h != NULL);
    if (!h) return;
    CHECK(sl_harness_render(h, iso));
    sl_harness_destroy(h);
    h = make(json, (const char *[]){"core.anisotropy=8", NULL});
    CHECK(h != NULL);
    if (!h) return;
    CHECK(sl_harness_render(h, def));
    sl_harness_compare(iso, def, W, H, 1e-3, &cmp);
    CHECK_MSG(cmp.pixels_over > 0, "anisotropy 8 filters like 1 at grazing angles");
    CHECK(sl_harness_set(h, "core.anisotropy=1", err, sizeof err));
    CHECK(sl_harness_render(h, img));
    sl_harness_compare(iso, img, W, H, 1e-6, &cmp);
    CHECK_MSG(cmp.max_abs <= 1e-6, "core.anisotropy=1 set at run time differs from a fresh harness by %g", cmp.max_abs);
    sl_harness_destroy(h);
}

/* Animated lights (core keys animate*): an orbiting point light and a rotating directional light
 * at t = 1/60 s render as static lights placed where the rotation about +Y puts them (computed
 * here: x' = c·x + s·z, z' = −s·x + c·z; a wobbling sun tilted about dir × up), and a live --set
 * animate gives the fresh start's frame. */
static void test_light_animation(void) {
    const double a = 6.0 / 60.0, c = cos(a), s = sin(a);
    char json[2048], err[1024];
    sl_compare cmp;
    /* wobble of the directional light: axis = dir × up = +Z, angle 15°·sin(6·t) */
    const double w = 15 * M_PI / 180 * sin(a), cw = cos(w), sw = sin(w);
    char expect[3][512];
    snprintf(expect[0], sizeof expect[0], "{\"name\": \"l\", \"type\": \"point\", \"position\": [%.9g, 2, %.9g], \"intensity\": 20}",
             c * 2 + s * 0.5, -s * 2 + c * 0.5);
    snprintf(expect[1], sizeof expect[1], "{\"name\": \"l\", \"type\": \"directional\", \"direction\": [%.9g, -0.8, %.9g], \"intensity\": 2}",
             c * 0.6, -s * 0.6);
    snprintf(expect[2], sizeof expect[2], "{\"name\": \"l\", \"type\": \"directional\", \"direction\": [%.9g, %.9g, 0], \"intensity\": 2}",
             0.6 * cw + 0.8 * sw, 0.6 * sw - 0.8 * cw);
    const char *animated[3] = {
        "{\"name\": \"l\", \"type\": \"point\", \"position\": [2, 2, 0.5], \"intensity\": 20, \"animate\": \"orbit\", \"animate_speed\": 6}",
        "{\"name\": \"l\", \"type\": \"directional\", \"direction\": [0.6, -0.8, 0], \"intensity\": 2, \"animate\": \"orbit\", \"animate_speed\": 6}",
        "{\"name\": \"l\", \"type\": \"directional\", \"direction\": [0.6, -0.8, 0], \"intensity\": 2, \"animate\": \"wobble\", \"animate_speed\": 6}",
    };
    const char *modes[3] = {"orbit", "orbit", "wobble"};
    for (int i = 0; i < 3; i++) {
        snprintf(json, sizeof json, PLANE_SCENE("%s", ""), animated[i]);
        sl_harness *h = make(json, NULL);
        CHECK(h != NULL);
        if (!h) return;
        sl_harness_set_frame(h, 1);
        CHECK(sl_harness_render(h, img));
        sl_harness_set_frame(h, 0);
        CHECK(sl_harness_render(h, img2));
        sl_harness_compare(img, img2, W, H, 1e-4, &cmp);
        /* a sun turning about the plane's normal lights the plane the same: only the others move it */
        if (i != 1) CHECK_MSG(cmp.pixels_over > 100, "case %d: the animated light does not move (%ld pixels)", i, cmp.pixels_over);
        sl_harness_destroy(h);
        snprintf(json, sizeof json, PLANE_SCENE("%s", ""), expect[i]);
        h = make(json, NULL);
        CHECK(h && sl_harness_render(h, img2));
        sl_harness_compare(img, img2, W, H, 1e-3, &cmp);
        CHECK_MSG(cmp.pixels_over <= 2, "case %d: animated light at t = 1/60 differs from the static light there (%ld px, max %g)",
                  i, cmp.pixels_over, cmp.max_abs);
        char light[512];
        /* live: the static light set to orbit equals the fresh animated start at the same frame */
        snprintf(light, sizeof light, "light.l.animate=%s", modes[i]);
        CHECK(sl_harness_set(h, light, err, sizeof err));
        CHECK(sl_harness_set(h, "light.l.animate_speed=6", err, sizeof err));
        snprintf(light, sizeof light, "light.l.%s=%s", i ? "direction" : "position", i ? "0.6,-0.8,0" : "2,2,0.5");
        CHECK(sl_harness_set(h, light, err, sizeof err));
        sl_harness_set_frame(h, 1);
        CHECK(sl_harness_render(h, img2));
        sl_harness_compare(img, img2, W, H, 1e-6, &cmp);
        CHECK_MSG(cmp.max_abs <= 1e-6, "case %d: live animate differs from the fresh start by %g", i, cmp.max_abs);
        sl_harness_destroy(h);
    }
    /* a refused light key never suggests itself */
    sl_harness *h = make(PLANE_SCENE("{\"name\": \"l\", \"type\": \"point\", \"position\": [0, 2, 0]}", ""), NULL);
    CHECK(h != NULL);
    if (!h) return;
    CHECK(!sl_harness_set(h, "light.l.animat=orbit", err, sizeof err));
    CHECK_CONTAINS(err, "did you mean \"animate\"");
    CHECK(!sl_harness_set(h, "light.l.cone_angle=30", err, sizeof err)); /* spot key, spotlight-shadow not loaded */
    CHECK_MSG(!strstr(err, "did you mean \"cone_angle\""), "suggests the refused key: %s", err);
    sl_harness_destroy(h);
}

/* ABI 1.6: a LIGHT chunk flagged SL_CHUNK_LIGHT_RADIANCE returns radiance, added as it is to the
 * light loop, and may call sl_shading_model (the material's model). The test plugin's glow light
 * calls Lambert with l = n and E = colour × intensity (in two halves): L = k_d/π · E on every
 * plane pixel.
 * The second scene has three glow lights flagged cast_shadows beside a casting sun straight
 * overhead (E = 1, no shadow plugin: visibility 1). A radiance type has no casters' loop, so its
 * lights are packed once, in its own range: packing them among the casters as well (the tenth
 * round's first packer did) writes past the light records' end (ASan, the sanitize test). */
static void test_radiance_light(void) {
    char err[4096];
    const char *plugins[] = {SL_TEST_PLUGIN_DIR "/tp-good/tp-good.so", NULL};
    const char *scenes[] = {
        PLANE_SCENE("{\"name\": \"g\", \"type\": \"tp-good-glow\", \"intensity\": 3, \"color\": [1, 0.5, 0.25]}", ""),
        PLANE_SCENE("{\"name\": \"g1\", \"type\": \"tp-good-glow\", \"intensity\": 1, \"color\": [1, 0.5, 0.25], \"cast_shadows\": true},"
                    "{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, 0], \"intensity\": 1, \"cast_shadows\": true},"
                    "{\"name\": \"g2\", \"type\": \"tp-good-glow\", \"intensity\": 1.5, \"color\": [1, 0.5, 0.25], \"cast_shadows\": true},"
                    "{\"name\": \"g3\", \"type\": \"tp-good-glow\", \"intensity\": 0.5, \"color\": [1, 0.5, 0.25], \"cast_shadows\": true}", "")};
    const float sun[2] = {0, 1};
    for (int sc = 0; sc < 2; sc++) {
        sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
            .scene_json = scenes[sc], .plugins = plugins, .float32 = true, .strict = true}, err, sizeof err);
        CHECK_MSG(h != NULL, "harness (scene %d): %s", sc, err);
        if (!h) return;
        CHECK(sl_harness_render(h, img));
        const float kd[3] = {0.7f, 0.5f, 0.3f}, E[3] = {3, 1.5f, 0.75f};
        int checked = 0;
        for (int y = 0; y < H; y += 7)
            for (int x = 0; x < W; x += 7) {
                float p[3];
                if (!plane_hit(x, y, p)) continue;
                for (int c = 0; c < 3; c++) CHECK_NEAR(img[(y * W + x) * 4 + c], kd[c] / M_PI * (E[c] + sun[sc]), 1e-4);
                checked++;
            }
        CHECK_MSG(checked > 50, "only %d plane pixels sampled", checked);
        sl_harness_destroy(h);
    }
}

/* Issue 18: programs specialise on the set of light types, not on which lights are on. Switching
 * off the only point light (or every light) live must keep every program (same hashes: the
 * program cache is keyed by them, so nothing compiles) and give the frame of a fresh start with
 * the light off; switching it back gives the first frame again. Fails with programs composed
 * from the enabled lights' types (the point loop would drop out: a new hash). */
static void test_light_toggle_keeps_programs(void) {
    static float fresh_img[W * H * 4];
    const char *scene = PLANE_SCENE("{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -0.5, -0.8660254], \"intensity\": 2},"
                                    "{\"name\": \"bulb\", \"type\": \"point\", \"position\": [1, 2, 0], \"intensity\": 10}", "");
    sl_harness *h = make(scene, NULL);
    CHECK(h != NULL);
    if (!h) return;
    char err[512];
    sl_harness_structure s0, s1, s2;
    sl_compare c;
    CHECK(sl_harness_render(h, img));
    sl_harness_structure_of(h, &s0);
    CHECK(s0.program_count >= 1);
    /* every light off: black (no environment), the same programs */
    CHECK(sl_harness_set(h, "light.sun.enabled=false", err, sizeof err));
    CHECK(sl_harness_set(h, "light.bulb.enabled=false", err, sizeof err));
    CHECK(sl_harness_render(h, img2));
    sl_harness_structure_of(h, &s1);
    CHECK_MSG(sl_harness_structure_equal(&s0, &s1), "switching the lights off changed the programs");
    double sum = 0;
    for (int i = 0; i < W * H * 4; i += 4) sum += img2[i] + img2[i + 1] + img2[i + 2];
    CHECK_NEAR(sum, 0, 1e-6);
    /* back on: the first frame again */
    CHECK(sl_harness_set(h, "light.sun.enabled=true", err, sizeof err));
    CHECK(sl_harness_set(h, "light.bulb.enabled=true", err, sizeof err));
    CHECK(sl_harness_render(h, img2));
    sl_harness_compare(img, img2, W, H, 1e-6, &c);
    CHECK_MSG(c.max_abs == 0, "lights back on: max difference %g", c.max_abs);
    /* the only point light off */
    CHECK(sl_harness_set(h, "light.bulb.enabled=false", err, sizeof err));
    CHECK(sl_harness_render(h, img2));
    sl_harness_structure_of(h, &s1);
    CHECK_MSG(sl_harness_structure_equal(&s0, &s1), "switching the point light off changed the programs");
    sl_harness_compare(img, img2, W, H, 1e-3, &c);
    CHECK_MSG(c.pixels_over > W * H / 4, "the point light lights nothing (%ld pixels differ)", c.pixels_over);
    sl_harness_destroy(h);
    /* a fresh start with it off: the same programs and frame */
    const char *off[] = {"light.bulb.enabled=false", NULL};
    sl_harness *f = make(scene, off);
    CHECK(f != NULL);
    if (!f) return;
    CHECK(sl_harness_render(f, fresh_img));
    sl_harness_structure_of(f, &s2);
    CHECK(sl_harness_structure_equal(&s1, &s2));
    sl_harness_compare(img2, fresh_img, W, H, 1e-6, &c);
    CHECK_MSG(c.max_abs == 0, "live toggle vs fresh start: max difference %g", c.max_abs);
    sl_harness_destroy(f);
}

int main(void) {
    test_light_toggle_keeps_programs();
    test_light_animation();
    test_directional();
    test_point_light();
    test_furnace();
    test_debug_views_and_display();
    test_accumulate_and_ssaa();
    test_anisotropy();
    test_anisotropy_default();
    test_radiance_light();
    return check_result();
}
