/* displacement against closed forms and CPU-displaced meshes (harness, OSMesa):
 *  1. position: a plane of 8 triangles displaced by the waves height h(u, v) (tessellated at
 *     1-pixel edges); the world position of every visible pixel (debug view
 *     displacement-position, RGBA32F) lies on y = h(u(x), v(z)) computed in C (tests/height.h)
 *     within the chord error; at 64-pixel edges it does not (the check can fail).
 *  2. shadows: a Gaussian bump displaced on a coarse plane, lit by a low shadowed spot
 *     (spotlight-shadow), casts and receives the shadow that the same bump as a fine mesh built
 *     and displaced here on the CPU (an OBJ, no displacement plugin involved) does: the shadow
 *     masks (shadowed / unshadowed frame < 0.5) agree; the flat plane's do not.
 *  3. parallax occlusion mapping on a head-on view approaches the tessellated surface better than
 *     plain parallax and than the flat polygon (RMSE of the shaded frames).
 *  4. costs nothing: switched off equals not loaded (passes, draws, program hashes); on, a
 *     material without its keys keeps the program it has without the plugin.
 *  5. live equals fresh: edge_px and parallax changed with set() give a fresh harness's frame.
 *  stability: grazing views, a relief 100 m deep, 1-pixel and 64-pixel edges: finite pixels. */
#include "height.h"
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define W 160
#define H 120
static int failures;
#define CHECK(cond, ...) do { if (!(cond)) { failures++; printf("FAIL %s:%d: ", __FILE__, __LINE__); printf(__VA_ARGS__); printf("\n"); } } while (0)

static sl_harness *make(const char *json, const char *const *settings, bool with_plugin, bool float32) {
    const char *plugins[] = {DISPLACEMENT_PLUGIN_PATH, "spotlight-shadow", NULL};
    const char *only_shadow[] = {"spotlight-shadow", NULL};
    char err[8192];
    sl_harness_desc d = {.struct_size = sizeof d, .width = W, .height = H, .scene_json = json,
                         .plugins = with_plugin ? plugins : only_shadow, .settings = settings, .strict = true,
                         .float32 = float32};
    sl_harness *h = sl_harness_create(&d, err, sizeof err);
    if (!h) { printf("FAIL: harness: %s\n", err); exit(1); }
    return h;
}

static float *render_h(sl_harness *h) {
    float *img = malloc(sizeof(float) * W * H * 4);
    sl_harness_set_frame(h, 0);
    if (!sl_harness_render(h, img)) { printf("FAIL: render\n"); exit(1); }
    return img;
}

static int saved;
static float *render(const char *json, const char *const *settings, bool with_plugin, const char *view) {
    sl_harness *h = make(json, settings, with_plugin, view != NULL);
    char err[4096];
    if (view && !sl_harness_set_debug_view(h, view, err, sizeof err)) { printf("FAIL: view: %s\n", err); exit(1); }
    float *img = render_h(h);
    const char *dir = getenv("DISPLACEMENT_TEST_SAVE"); /* look at what the test renders */
    if (dir) {
        char path[1024];
        snprintf(path, sizeof path, "%s/render%02d.png", dir, saved++);
        sl_harness_save(h, path, err, sizeof err);
    }
    sl_harness_destroy(h);
    return img;
}

/* ---- 1. position read-back -------------------------------------------------------- */

static const char *plane_scene =
    "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 1.9, 2.1], \"target\": [0, -0.1, 0], \"fov_y\": 50}],"
    " \"materials\": [{\"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5], \"displace\": 0.2,"
    "                  \"height_function\": \"waves\", \"height_frequency\": 1}],"
    " \"nodes\": [{\"name\": \"p\", \"mesh\": {\"primitive\": \"plane\", \"size\": 2, \"subdivisions\": 2}, \"material\": \"m\"}],"
    " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, -0.3]}]}";

/* max |y − h| over pixels on the plane; *covered = their count */
static double position_error(const float *img, int *covered) {
    double worst = 0;
    *covered = 0;
    for (int i = 0; i < W * H; i++) {
        const float *p = img + 4 * i;
        if (p[0] == 0 && p[1] == 0 && p[2] == 0) continue; /* background */
        if (fabs(p[0]) > 1.0001 || fabs(p[2]) > 1.0001) continue;
        double u = (p[0] + 1) / 2, v = (p[2] + 1) / 2;
        double e = fabs(p[1] - hf_h(HF_WAVES, 1, 0.2, u, v));
        if (e > worst) worst = e;
        (*covered)++;
    }
    return worst;
}

static void test_position(void) {
    float *fine = render(plane_scene, (const char *[]){"displacement.edge_px=1", NULL}, true, "displacement-position");
    float *coarse = render(plane_scene, (const char *[]){"displacement.edge_px=64", NULL}, true, "displacement-position");
    int n_fine, n_coarse;
    double e_fine = position_error(fine, &n_fine), e_coarse = position_error(coarse, &n_coarse);
    printf("position: max |y - h(x,z)| = %.2e m at 1-px edges (%d px), %.2e m at 64-px edges (%d px)\n", e_fine, n_fine,
           e_coarse, n_coarse);
    CHECK(n_fine > W * H / 4, "the plane covers %d pixels only", n_fine);
    /* chord error of level-64 segments (1/64 m) on a curvature ≤ 0.2·π²/2 ≈ 1 /m: ~2e-5 m; allow 1 mm */
    CHECK(e_fine < 1e-3, "displaced surface off the closed form by %.3g m", e_fine);
    CHECK(e_coarse > 5e-3, "coarse tessellation matches too well (%.3g m): the check cannot fail", e_coarse);
    free(fine), free(coarse);
}

/* ---- 2. shadows against a CPU-displaced mesh -------------------------------------- */

#define BUMP_SCALE 0.3
#define BUMP_F 6.0
#define GRID 160

static bool write_bump_obj(const char *path) {
    FILE *f = fopen(path, "w");
    if (!f) return false;
    /* the plane primitive's layout: size 4 in XZ, u = (x+2)/4 along +X, v = (z+2)/4 along +Z */
    for (int j = 0; j <= GRID; j++)
        for (int i = 0; i <= GRID; i++) {
            double u = (double)i / GRID, v = (double)j / GRID, e = 1e-4;
            double y = hf_h(HF_BUMP, BUMP_F, BUMP_SCALE, u, v);
            /* normal of y(x, z) with x = 4u − 2, z = 4v − 2: (−∂y/∂x, 1, −∂y/∂z) */
            double dx = (hf_h(HF_BUMP, BUMP_F, BUMP_SCALE, u + e, v) - hf_h(HF_BUMP, BUMP_F, BUMP_SCALE, u - e, v)) / (2 * e * 4);
            double dz = (hf_h(HF_BUMP, BUMP_F, BUMP_SCALE, u, v + e) - hf_h(HF_BUMP, BUMP_F, BUMP_SCALE, u, v - e)) / (2 * e * 4);
            fprintf(f, "v %.7f %.7f %.7f\nvn %.7f 1 %.7f\nvt %.7f %.7f\n", 4 * u - 2, y, 4 * v - 2, -dx, -dz, u, 1 - v);
        }
    for (int j = 0; j < GRID; j++)
        for (int i = 0; i < GRID; i++) {
            int a = j * (GRID + 1) + i + 1, b = a + 1, c = a + GRID + 1, d = c + 1;
            fprintf(f, "f %d/%d/%d %d/%d/%d %d/%d/%d\n", a, a, a, c, c, c, b, b, b);
            fprintf(f, "f %d/%d/%d %d/%d/%d %d/%d/%d\n", b, b, b, c, c, c, d, d, d);
        }
    return fclose(f) == 0;
}

static char *shadow_scene(const char *mesh, const char *material_keys, bool shadows) {
    char *s = malloc(4096);
    snprintf(s, 4096,
             "{\"cameras\": [{\"name\": \"c\", \"position\": [0.3, 3.6, 2.6], \"target\": [0.3, -0.3, 0], \"fov_y\": 55}],"
             " \"materials\": [{\"name\": \"ground\", \"base_color\": [0.7, 0.7, 0.7]%s}],"
             " \"nodes\": [{\"name\": \"g\", \"mesh\": %s, \"material\": \"ground\"}],"
             " \"lights\": [{\"name\": \"spot\", \"type\": \"spot\", \"position\": [-2.4, 0.25, 0.3],"
             "   \"direction\": [1, -0.22, -0.1], \"color\": [1, 1, 1], \"intensity\": 40, \"cone_angle\": 60,"
             "   \"falloff\": \"linear\", \"cast_shadows\": %s}],"
             " \"environment\": {\"color\": [0.02, 0.02, 0.02]}}",
             material_keys, mesh, shadows ? "true" : "false");
    return s;
}

/* pixels in shadow: the shadowed frame below half the unshadowed one (where that one is lit) */
static void shadow_mask(const float *lit, const float *unlit, unsigned char *mask, int *count) {
    *count = 0;
    for (int i = 0; i < W * H; i++) {
        float a = lit[4 * i + 1], b = unlit[4 * i + 1];
        mask[i] = b > 0.05f && a < 0.5f * b;
        *count += mask[i];
    }
}

static void test_shadows(void) {
    char obj[256];
    snprintf(obj, sizeof obj, "/tmp/displacement_bump_%d.obj", (int)getpid());
    if (!write_bump_obj(obj)) { printf("FAIL: cannot write %s\n", obj); failures++; return; }
    char ref_mesh[400];
    snprintf(ref_mesh, sizeof ref_mesh, "{\"file\": \"%s\"}", obj);
    const char *coarse = "{\"primitive\": \"plane\", \"size\": 4, \"subdivisions\": 4}";
    char keys[200];
    snprintf(keys, sizeof keys, ", \"displace\": %g, \"height_function\": \"bump\", \"height_frequency\": %g", BUMP_SCALE, BUMP_F);
    const char *fine_edges[] = {"displacement.edge_px=2", "spotlight-shadow.map_size=1024", NULL};
    unsigned char m_disp[W * H], m_ref[W * H], m_flat[W * H];
    int n_disp, n_ref, n_flat;
    char *s1 = shadow_scene(coarse, keys, true), *s0 = shadow_scene(coarse, keys, false);
    float *a = render(s1, fine_edges, true, NULL), *b = render(s0, fine_edges, true, NULL);
    shadow_mask(a, b, m_disp, &n_disp);
    free(a), free(b), free(s1), free(s0);
    s1 = shadow_scene(ref_mesh, "", true), s0 = shadow_scene(ref_mesh, "", false);
    const char *ref_settings[] = {"spotlight-shadow.map_size=1024", NULL};
    a = render(s1, ref_settings, false, NULL), b = render(s0, ref_settings, false, NULL);
    shadow_mask(a, b, m_ref, &n_ref);
    free(a), free(b), free(s1), free(s0);
    /* control: the flat coarse plane (the plugin off) */
    s1 = shadow_scene(coarse, keys, true), s0 = shadow_scene(coarse, keys, false);
    const char *off[] = {"displacement.enabled=false", "spotlight-shadow.map_size=1024", NULL};
    a = render(s1, off, true, NULL), b = render(s0, off, true, NULL);
    shadow_mask(a, b, m_flat, &n_flat);
    free(a), free(b), free(s1), free(s0);
    remove(obj);
    int diff = 0, diff_flat = 0;
    for (int i = 0; i < W * H; i++) diff += m_disp[i] != m_ref[i], diff_flat += m_flat[i] != m_ref[i];
    printf("shadows: %d px in shadow displaced, %d px CPU mesh, %d flat; masks differ on %d px (flat: %d)\n", n_disp,
           n_ref, n_flat, diff, diff_flat);
    CHECK(n_ref > W * H / 50, "the reference bump casts too small a shadow (%d px)", n_ref);
    CHECK(diff <= n_ref / 20 + 10, "displaced shadow differs from the CPU mesh's on %d of %d px", diff, n_ref);
    CHECK(diff_flat > n_ref / 2, "the flat plane's shadow matches too (%d px differ): the check cannot fail", diff_flat);
}

/* ---- 3. parallax occlusion mapping -------------------------------------------------- */

static char *waves_scene(const char *key) {
    char *s = malloc(2048);
    snprintf(s, 2048,
             "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 1.6, 1.6], \"target\": [0, 0, 0], \"fov_y\": 40}],"
             " \"materials\": [{\"name\": \"m\", \"base_color\": [0.6, 0.6, 0.6], \"%s\": 0.06,"
             "  \"height_function\": \"waves\", \"height_frequency\": 4, \"cavity\": 0.6}],"
             " \"nodes\": [{\"name\": \"p\", \"mesh\": {\"primitive\": \"plane\", \"size\": 4, \"subdivisions\": 4}, \"material\": \"m\"}],"
             " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [-0.6, -0.5, -0.3], \"intensity\": 2}],"
             " \"environment\": {\"color\": [0.1, 0.1, 0.1]}}",
             key);
    return s;
}

static double rmse_central(const float *a, const float *b) {
    double sum = 0;
    int n = 0;
    for (int y = H / 4; y < 3 * H / 4; y++)
        for (int x = W / 4; x < 3 * W / 4; x++)
            for (int c = 0; c < 3; c++) {
                double d = a[4 * (y * W + x) + c] - b[4 * (y * W + x) + c];
                sum += d * d, n++;
            }
    return sqrt(sum / n);
}

static void test_parallax(void) {
    char *tess = waves_scene("displace"), *par = waves_scene("parallax");
    float *ref = render(tess, (const char *[]){"displacement.edge_px=1", NULL}, true, NULL);
    float *pom = render(par, (const char *[]){"displacement.pom_steps=64", NULL}, true, NULL);
    float *plain = render(par, (const char *[]){"displacement.parallax=plain", NULL}, true, NULL);
    /* the flat polygon with the same cavity colouring (parallax depth 0) */
    char *flat_s = waves_scene("parallax");
    char *at = strstr(flat_s, "0.06");
    memcpy(at, "0.00", 4);
    float *flat = render(flat_s, NULL, true, NULL);
    double e_pom = rmse_central(pom, ref), e_plain = rmse_central(plain, ref), e_flat = rmse_central(flat, ref);
    printf("parallax vs tessellated (RMSE, central half): occlusion %.4f, plain %.4f, flat %.4f\n", e_pom, e_plain, e_flat);
    CHECK(e_pom < e_flat && e_pom < 0.8 * e_flat, "POM (%.4f) no closer to the displaced surface than the flat polygon (%.4f)",
          e_pom, e_flat);
    CHECK(e_pom <= e_plain, "POM (%.4f) worse than plain parallax (%.4f)", e_pom, e_plain);
    CHECK(sl_harness_count_nonfinite(pom, W, H) == 0 && sl_harness_count_nonfinite(plain, W, H) == 0, "NaN/Inf");
    free(ref), free(pom), free(plain), free(flat), free(tess), free(par), free(flat_s);
}

/* ---- 4. costs nothing ----------------------------------------------------------------- */

static const char *two_materials =
    "{\"materials\": [{\"name\": \"plain\", \"base_color\": [0.5, 0.5, 0.5]},"
    "                 {\"name\": \"bumpy\", \"base_color\": [0.5, 0.5, 0.5], \"displace\": 0.1}],"
    " \"nodes\": [{\"name\": \"a\", \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"plain\"},"
    "           {\"name\": \"b\", \"translate\": [2, 0, 0], \"mesh\": {\"primitive\": \"plane\", \"size\": 2}, \"material\": \"bumpy\"}],"
    " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, -1]}]}";

static void structure(const char *json, const char *const *settings, bool with_plugin, sl_harness_structure *st) {
    sl_harness *h = make(json, settings, with_plugin, false);
    sl_harness_render(h, NULL);
    sl_harness_structure_of(h, st);
    sl_harness_destroy(h);
}

static void test_costs_nothing(void) {
    sl_harness_structure none, off, on;
    structure(two_materials, NULL, false, &none);
    structure(two_materials, (const char *[]){"displacement.enabled=false", NULL}, true, &off);
    structure(two_materials, NULL, true, &on);
    CHECK(sl_harness_structure_equal(&none, &off), "switched off differs from not loaded");
    CHECK(on.program_count == none.program_count && on.program_hashes[0] == none.program_hashes[0],
          "a material without displacement keys changed program");
    CHECK(on.program_hashes[1] != none.program_hashes[1], "the displaced material kept its program: the check cannot fail");
}

/* ---- 5. live equals fresh; stability ------------------------------------------------ */

static void test_live(void) {
    char *par = waves_scene("parallax"), *tess = waves_scene("displace");
    const char *changes[][2] = {{"displacement.edge_px=3", "displacement.edge_px=6"},
                                {"displacement.parallax=plain", "displacement.parallax=occlusion"}};
    for (int k = 0; k < 2; k++) {
        const char *scene = k == 0 ? tess : par;
        sl_harness *h = make(scene, NULL, true, false);
        free(render_h(h));
        char err[1024];
        sl_harness_set(h, changes[k][0], err, sizeof err);
        float *live = render_h(h);
        sl_harness_destroy(h);
        float *fresh = render(scene, (const char *[]){changes[k][0], NULL}, true, NULL);
        sl_compare c;
        sl_harness_compare(live, fresh, W, H, 0, &c);
        CHECK(c.max_abs == 0, "%s live differs from fresh by %g", changes[k][0], c.max_abs);
        free(live), free(fresh);
    }
    free(par), free(tess);
}

static void test_stability(void) {
    const char *cases[][3] = {
        {"displace", "displacement.edge_px=1", "[0, 0.05, 3]"},
        {"parallax", "displacement.pom_steps=256", "[0, 0.02, 3]"},
        {"parallax", "displacement.parallax=plain", "[0, 0.02, 3]"},
        {"displace", "displacement.edge_px=64", "[0, 8, 0.01]"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        char json[2048];
        snprintf(json, sizeof json,
                 "{\"cameras\": [{\"name\": \"c\", \"position\": %s, \"target\": [0, 0, 0], \"fov_y\": 60}],"
                 " \"materials\": [{\"name\": \"m\", \"%s\": 100, \"height_function\": \"waves\", \"height_frequency\": 50}],"
                 " \"nodes\": [{\"name\": \"p\", \"mesh\": {\"primitive\": \"plane\", \"size\": 4}, \"material\": \"m\"}],"
                 " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, -0.1]}]}",
                 cases[k][2], cases[k][0]);
        float *img = render(json, (const char *[]){cases[k][1], NULL}, true, NULL);
        long bad = sl_harness_count_nonfinite(img, W, H);
        CHECK(bad == 0, "%s with %s: %ld NaN/Inf values", cases[k][0], cases[k][1], bad);
        free(img);
    }
}

int main(int argc, char **argv) {
    const char *only = argc > 1 ? argv[1] : ""; /* one part: position, shadows, parallax, cost, live, stability */
#define RUN(name, fn) if (!*only || !strcmp(only, name)) fn()
    RUN("position", test_position);
    RUN("shadows", test_shadows);
    RUN("parallax", test_parallax);
    RUN("cost", test_costs_nothing);
    RUN("live", test_live);
    RUN("stability", test_stability);
    if (failures) printf("%d check(s) failed\n", failures);
    else printf("all displacement checks passed\n");
    return failures ? 1 : 0;
}
