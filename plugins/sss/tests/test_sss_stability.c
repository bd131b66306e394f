/* sss: translucency against closed forms, stability in the known failure regions, and the
 * structural "unused costs nothing" checks.
 *   slab        translucency through a slab of thickness d (0.5–4 mm) lit from behind by a
 *               directional, a spot and a point light (orthographic, perspective and cube-face
 *               maps of the spotlight-shadow plugin) = k_d/π·E·Σ wᵢ exp(−d²/2vᵢ)
 *   no maps     without the spotlight-shadow plugin: a clear message, the image without the
 *               transmitted light, finite
 *   stability   every method: a 10 µm sheet lit from both sides, a light behind the object, a
 *               point light inside it and one on its surface, grazing light, E = 10⁴: no
 *               NaN/Inf, no negative values, within the Lambert bound where one applies
 *   zero cost   program hashes, passes and draw calls against a run without the plugin
 *   head        the head scan (when the data directory has it): every method renders finite
 * Scenes in millimetres (sss_radius = 1) unless stated. */
#include "sss_test.h"
#include "log.h"
#include <string.h>

static const char *const METHODS[] = {"none", "wrap", "translucency", "texture-space", "screen-space", "pre-integrated"};

/* ------------------------------------------------------------------ slab ------------------- */
/* A 40×40×d mm slab (white, no specular) facing the camera, the light behind it on the axis. */
static const char *slab_scene(double d, const char *light, bool shadow_plugin) {
    static char scene[4096];
    snprintf(scene, sizeof scene,
             "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 120], \"target\": [0, 0, 0], \"fov_y\": 30,"
             " \"near\": 1, \"far\": 500}],\n"
             " \"plugins\": [\"sss\"%s],\n"
             " \"materials\": [{\"name\": \"skin\", \"model\": \"skin\", \"base_color\": [1, 1, 1], \"sss_radius\": 1,"
             " \"specular\": 0}],\n"
             " \"nodes\": [{\"name\": \"slab\", \"mesh\": {\"primitive\": \"cube\", \"size\": 1}, \"scale\": [40, 40, %.6f],"
             " \"material\": \"skin\"}],\n"
             " \"lights\": [%s]}\n",
             shadow_plugin ? ", \"spotlight-shadow\"" : "", d, light);
    return scene;
}

static void test_slab(void) {
    const double E = M_PI; /* directional: radiance k_d/π·E·T = T */
    const double thickness[] = {0.5, 1, 2, 4};
    enum { N = 32 };
    static float img[N * N * 4];
    char light[512];
    for (int kind = 0; kind < 3; kind++)
        for (int k = 0; k < 4; k++) {
            double d = thickness[k], expected_scale;
            const char *label;
            if (kind == 0) {
                label = "directional";
                snprintf(light, sizeof light,
                         "{\"name\": \"back\", \"type\": \"directional\", \"direction\": [0, 0, 1], \"intensity\": %.9f,"
                         " \"cast_shadows\": true}", E);
                expected_scale = 1;
            } else {
                /* I = π·100²: E = π at 100 mm, so the front face (100 + d/2 from the light) gets
                 * π·(100/(100 + d/2))² on the axis */
                label = kind == 1 ? "spot" : "point";
                snprintf(light, sizeof light,
                         "{\"name\": \"back\", \"type\": \"%s\", \"position\": [0, 0, -100], %s \"intensity\": %.9f,"
                         " \"cast_shadows\": true}",
                         label, kind == 1 ? "\"direction\": [0, 0, 1], \"cone_angle\": 30," : "", M_PI * 1e4);
                double r = 100 / (100 + d / 2);
                expected_scale = r * r;
            }
            if (kind && k != 2) continue; /* spot and point: one thickness each */
            char err[8192];
            sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = N,
                                                                  .height = N, .scene_json = slab_scene(d, light, true),
                                                                  .float32 = true, .strict = true,
                                                                  .settings = (const char *[]){"sss.method=translucency",
                                                                                               NULL}},
                                              err, sizeof err);
            if (!h) {
                printf("SKIP slab (%s): the spotlight-shadow plugin did not load: %s\n", label, err);
                return;
            }
            CHECK(sl_harness_render(h, img));
            sl_harness_destroy(h);
            const float *p = sss_t_px(img, N, N / 2, N / 2);
            for (int c = 0; c < 3; c++) {
                double want = expected_scale * sss_t_transmittance(d, c);
                printf("slab %-11s d = %.1f mm, channel %d: %.6f, expected %.6f\n", label, d, c, p[c], want);
                CHECK_MSG(fabs(p[c] - want) <= 2e-3 * want + 1e-6, "%s slab %.1f mm channel %d: %g, expected %g", label,
                          d, c, p[c], want);
            }
            CHECK(sl_harness_count_nonfinite(img, N, N) == 0);
        }
}

/* Without a shadow-map provider: a message that names the fix, and the image without the
 * transmitted light (black: the slab is lit from behind only). */
static void test_no_maps(void) {
    char light[256], log[16384] = "";
    snprintf(light, sizeof light,
             "{\"name\": \"back\", \"type\": \"directional\", \"direction\": [0, 0, 1], \"intensity\": 3.14159265,"
             " \"cast_shadows\": true}");
    sl_log_capture(log, sizeof log);
    sl_harness *h = sss_t_harness(slab_scene(2, light, false), 32, 32, (const char *[]){"sss", NULL},
                                  (const char *[]){"sss.method=translucency", NULL});
    static float img[32 * 32 * 4];
    if (h) CHECK(sl_harness_render(h, img));
    sl_log_capture(NULL, 0);
    if (!h) return;
    sl_harness_destroy(h);
    CHECK_CONTAINS(log, "spotlight-shadow");
    CHECK_CONTAINS(log, "shadelab.shadow-maps/1");
    CHECK(sl_harness_count_nonfinite(img, 32, 32) == 0);
    double most = 0;
    for (int i = 0; i < 32 * 32 * 4; i++)
        if (i % 4 != 3) most = fmax(most, img[i]);
    printf("translucency without shadow maps: brightest %.3g (lit only from behind)\n", most);
    CHECK(most == 0);
}

/* ------------------------------------------------------------------ stability -------------- */
typedef struct stab_case {
    const char *name, *nodes, *lights;
    double bound; /* > 0: every channel ≤ bound (specular is off) */
    int lit;      /* the case is reached when some pixels are lit: 1 always, 2 translucency with maps, 0 never */
} stab_case;

static void test_stability(bool shadows) {
    /* white albedo, sss_color 0.6, 0.15, 0.1: the Lambert bound for a directional E is (1 +
     * 0.6)/π·E (the wrap band adds sss_color/π·E at most); translucency adds the back light */
    const stab_case cases[] = {
        {"10 um sheet, lights on both sides",
         "{\"name\": \"sheet\", \"mesh\": {\"primitive\": \"cube\", \"size\": 1}, \"scale\": [40, 40, 0.01], \"material\": \"skin\"}",
         "{\"name\": \"a\", \"type\": \"directional\", \"direction\": [0.3, 0, -1], \"intensity\": 3, \"cast_shadows\": true},"
         "{\"name\": \"b\", \"type\": \"directional\", \"direction\": [-0.2, 0.1, 1], \"intensity\": 3, \"cast_shadows\": true}",
         1.6 / M_PI * 6 * 1.01, 1},
        {"light behind the object",
         "{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 20}, \"material\": \"skin\"}",
         "{\"name\": \"a\", \"type\": \"directional\", \"direction\": [0.3, 0, 1], \"intensity\": 3, \"cast_shadows\": true}",
         1.6 / M_PI * 3 * 1.01, 2},
        {"light from the side",
         "{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 20}, \"material\": \"skin\"}",
         "{\"name\": \"a\", \"type\": \"directional\", \"direction\": [1, 0, 0.001], \"intensity\": 3, \"cast_shadows\": true}",
         1.6 / M_PI * 3 * 1.01, 1},
        {"E = 1e4", "{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 20}, \"material\": \"skin\"}",
         "{\"name\": \"a\", \"type\": \"directional\", \"direction\": [-0.5, -0.2, -1], \"intensity\": 1e4, \"cast_shadows\": true}",
         1.6 / M_PI * 1e4 * 1.01, 1},
        {"point light inside the object",
         "{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 20}, \"material\": \"skin\"}",
         "{\"name\": \"a\", \"type\": \"point\", \"position\": [0, 0, 0], \"intensity\": 1000, \"cast_shadows\": true}", 0, 0},
        {"point light on the surface",
         "{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 20}, \"material\": \"skin\"}",
         "{\"name\": \"a\", \"type\": \"point\", \"position\": [0, 0, 20], \"intensity\": 10, \"cast_shadows\": true}", 0, 1},
    };
    enum { N = 48 };
    static float img[N * N * 4];
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        char scene[4096];
        snprintf(scene, sizeof scene,
                 "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 120], \"target\": [0, 0, 0], \"fov_y\": 30,"
                 " \"near\": 1, \"far\": 500}],\n"
                 " \"materials\": [{\"name\": \"skin\", \"model\": \"skin\", \"base_color\": [1, 1, 1], \"sss_radius\": 1,"
                 " \"sss_color\": [0.6, 0.15, 0.1], \"specular\": 0}],\n"
                 " \"nodes\": [%s],\n \"lights\": [%s]}\n",
                 cases[k].nodes, cases[k].lights);
        const char *plugins[] = {"sss", shadows ? "spotlight-shadow" : NULL, NULL};
        sl_harness *h = sss_t_harness(scene, N, N, plugins, (const char *[]){"sss.ts_size=128", NULL});
        if (!h) continue;
        for (int m = 0; m < 6; m++) {
            sss_t_set(h, "sss.method=%s", METHODS[m]);
            if (!sl_harness_render(h, img)) continue;
            long bad = sl_harness_count_nonfinite(img, N, N), neg = sl_harness_count_negative(img, N, N);
            double most = 0, lit = 0;
            for (int i = 0; i < N * N * 4; i++)
                if (i % 4 != 3 && isfinite(img[i])) most = fmax(most, img[i]), lit += img[i] > 0;
            CHECK_MSG(bad == 0 && neg == 0, "%s, %s%s: %ld NaN/Inf, %ld negative", cases[k].name, METHODS[m],
                      shadows ? " (shadows)" : "", bad, neg);
            bool expect_lit = cases[k].lit == 1 || (cases[k].lit == 2 && shadows && m == 2);
            if (expect_lit)
                CHECK_MSG(lit > 10, "%s, %s: the object is not lit (the case was not reached)", cases[k].name, METHODS[m]);
            if (cases[k].bound > 0)
                CHECK_MSG(most <= cases[k].bound, "%s, %s: %g above the bound %g", cases[k].name, METHODS[m], most,
                          cases[k].bound);
            if (m == 5) printf("stability%s: %-34s ok for every method (brightest %.4g)\n", shadows ? " + shadows" : "",
                               cases[k].name, most);
        }
        sl_harness_destroy(h);
    }
}

/* ------------------------------------------------------------------ zero cost -------------- */
static const char *zc_scene(bool skin) {
    static char scene[2048];
    snprintf(scene, sizeof scene,
             "{\"materials\": [{\"name\": \"plain\", \"base_color\": [0.5, 0.5, 0.5]},\n"
             "  {\"name\": \"shiny\", \"model\": \"ggx\", \"alpha\": 0.2}%s],\n"
             " \"nodes\": [{\"name\": \"a\", \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"plain\"},\n"
             "  {\"name\": \"b\", \"translate\": [2, 0, 0], \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"shiny\"}%s],\n"
             " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, -1]}]}\n",
             skin ? ",\n  {\"name\": \"skin\", \"model\": \"skin\", \"sss_radius\": 0.01}" : "",
             skin ? ",\n  {\"name\": \"c\", \"translate\": [-2, 0, 0], \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"skin\"}" : "");
    return scene;
}

static bool structure(bool skin, const char *const *plugins, const char *const *settings, sl_harness_structure *st) {
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 32, .height = 32,
                                                          .scene_json = zc_scene(skin), .plugins = plugins,
                                                          .settings = settings},
                                      err, sizeof err);
    if (!h) { fprintf(stderr, "%s\n", err); return false; }
    bool ok = sl_harness_render(h, NULL) && sl_harness_render(h, NULL); /* the second frame: skipped work stays skipped */
    sl_harness_structure_of(h, st);
    sl_harness_destroy(h);
    return ok;
}

static void test_zero_cost(void) {
    sl_harness_structure none, loaded, disabled, skin_none, skin[6];
    const char *const ggx[] = {"ggx", NULL}, *const sss[] = {"sss", NULL};
    CHECK(structure(false, ggx, NULL, &none));
    CHECK(structure(false, sss, (const char *[]){"sss.method=texture-space", NULL}, &loaded));
    CHECK(structure(false, sss, (const char *[]){"sss.enabled=false", NULL}, &disabled));
    /* no material uses it: the same programs, passes and draw calls as without the plugin */
    CHECK_MSG(sl_harness_structure_equal(&none, &loaded), "sss loaded but unused changed programs, passes or draw calls");
    CHECK_MSG(sl_harness_structure_equal(&none, &disabled), "sss disabled changed programs, passes or draw calls");
    CHECK(structure(true, sss, (const char *[]){"sss.method=none", NULL}, &skin_none));
    /* second frame: nothing changed, so texture space reuses its stretch map, irradiance and blur
     * (0 extra passes); screen space re-runs its two passes (they depend on the camera) */
    const int extra_passes[6] = {0, 0, 0, 0, 2, 0};
    for (int m = 0; m < 6; m++) {
        char set[64];
        snprintf(set, sizeof set, "sss.method=%s", METHODS[m]);
        CHECK(structure(true, sss, (const char *[]){set, NULL}, &skin[m]));
        /* the other materials' programs are those of the run without the plugin */
        CHECK(skin[m].program_count == 3);
        CHECK(skin[m].program_hashes[0] == none.program_hashes[0]);
        CHECK(skin[m].program_hashes[1] == none.program_hashes[1]);
        CHECK_MSG(skin[m].pass_count == none.pass_count + extra_passes[m], "%s: %d passes ran, expected %d", METHODS[m],
                  skin[m].pass_count, none.pass_count + extra_passes[m]);
        printf("zero cost: %-14s passes %d (%+d), draw calls %d\n", METHODS[m], skin[m].pass_count,
               skin[m].pass_count - none.pass_count, skin[m].draw_calls);
    }
    /* a changed light re-runs texture space's irradiance and blur (not the stretch map) */
    {
        char err[4096];
        sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 32,
                                                              .height = 32, .scene_json = zc_scene(true), .plugins = sss,
                                                              .settings = (const char *[]){"sss.method=texture-space", NULL}},
                                          err, sizeof err);
        CHECK_MSG(h != NULL, "%s", err);
        if (h) {
            sl_harness_structure st;
            CHECK(sl_harness_render(h, NULL) && sl_harness_render(h, NULL));
            CHECK(sl_harness_set(h, "light.sun.intensity=2", err, sizeof err));
            CHECK(sl_harness_render(h, NULL));
            sl_harness_structure_of(h, &st);
            CHECK_MSG(st.pass_count == none.pass_count + 2, "after a light change %d passes ran, expected %d", st.pass_count,
                      none.pass_count + 2);
            sl_harness_destroy(h);
        }
    }
    /* the method is a permutation: the skin program differs between methods */
    CHECK(skin[3].program_hashes[2] != skin[4].program_hashes[2] && skin[0].program_hashes[2] != skin[1].program_hashes[2]);
}

/* ------------------------------------------------------------------ head ------------------- */
static void test_head(void) {
    char path[1024];
    snprintf(path, sizeof path, "%s/skin_head.json", SL_SCENES_DIR);
    const char *data = getenv("SHADELAB_DATA");
    char glb[2048];
    snprintf(glb, sizeof glb, "%s/head/LeePerrySmith.glb", data ? data : "");
    FILE *f = data ? fopen(glb, "rb") : NULL;
    if (!f) {
        printf("SKIP head: no head/LeePerrySmith.glb in the data directory (SHADELAB_DATA=%s)\n", data ? data : "(unset)");
        return;
    }
    fclose(f);
    enum { N = 64 };
    char err[8192];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = N, .height = N,
                                                          .scene_file = path, .float32 = true,
                                                          .settings = (const char *[]){"sss.ts_size=256", NULL}},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return;
    static float img[N * N * 4], ref[N * N * 4];
    sss_t_set(h, "sss.method=none");
    CHECK(sl_harness_render(h, ref));
    for (int m = 1; m < 6; m++) {
        sss_t_set(h, "sss.method=%s", METHODS[m]);
        CHECK(sl_harness_render(h, img));
        sl_compare cmp;
        sl_harness_compare(img, ref, N, N, 0.0, &cmp);
        CHECK(cmp.nonfinite == 0 && sl_harness_count_negative(img, N, N) == 0);
        printf("head: %-14s vs none: rmse %.4f, max %.4f\n", METHODS[m], cmp.rmse, cmp.max_abs);
        CHECK(cmp.max_abs > 1e-3); /* the method did something */
    }
    sl_harness_destroy(h);
}

int main(void) {
    test_slab();
    test_no_maps();
    test_stability(false);
    test_stability(true);
    test_zero_cost();
    test_head();
    return check_result();
}
