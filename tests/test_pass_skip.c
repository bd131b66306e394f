/* Skipping what did not change (issue 18 item 4; pass.h sl_depends, ABI 1.8).
 * 1. Counting: tp-deps has one pass per declared dependency. Over frames with nothing changing,
 *    only the passes that must run every frame run; after each kind of change exactly the passes
 *    that declared it (and those reading their outputs) run again. The frame index is pinned
 *    (sl_harness_set_frame) except where time is the change.
 * 2. Images: with sss (texture space) and spotlight-shadow, a frame in which the texture-space
 *    passes and the shadow maps were skipped (nothing changed; then the camera moved; then a
 *    parameter of a plugin without shader chunks changed) equals a fresh start's first frame,
 *    which runs every pass; a light change re-runs them and still equals a fresh start.
 *    core.rerun_passes runs every pass in every frame while it is on.
 * 3. The built-in default scene as shipped (aa's TAA on): its shadow map is rendered by the first
 *    frame only, not by the frames of a still (a jittered camera each), nor while the camera
 *    orbits; moving the sun renders it again, once. */
#include "check.h"
#include <shadelab/harness.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { P_LIGHTS, P_GEOMETRY, P_CAMERA, P_MATERIALS, P_OWN, P_PARAMS, P_TIME, P_INPUTS, P_EVERY, P_NONE, P_OLD, P_SHARED, NP };
static const char *NAMES[NP] = {"deps-lights", "deps-geometry", "deps-camera", "deps-materials", "deps-own", "deps-params",
                                "deps-time", "deps-inputs", "deps-every", "deps-none", "deps-old", "deps-shared"};
#define B(p) (1u << (p))
static const unsigned ALWAYS = B(P_EVERY) | B(P_NONE) | B(P_OLD) | B(P_SHARED);
static const unsigned ALL = (1u << NP) - 1;

static const char *SCENE =
    "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 4], \"target\": [0, 0, 0]}],"
    " \"materials\": [{\"name\": \"m\", \"model\": \"ggx\", \"alpha\": 0.3%s}],"
    " \"nodes\": [{\"name\": \"s\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.7}, \"material\": \"m\"}],"
    " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, -1], \"intensity\": 2}]}";

static unsigned ran(sl_harness *h) {
    sl_harness_structure s;
    sl_harness_structure_of(h, &s);
    unsigned m = 0;
    for (int i = 0; i < s.pass_count; i++)
        for (int p = 0; p < NP; p++)
            if (!strcmp(s.passes[i], NAMES[p])) m |= B(p);
    return m;
}

/* which tp-deps passes are in effect (ran, or skipped with their outputs still this frame's) */
static unsigned in_effect(sl_harness *h) {
    sl_harness_structure s;
    sl_harness_structure_of(h, &s);
    unsigned m = 0;
    for (int i = 0; i < s.effect_count; i++)
        for (int p = 0; p < NP; p++)
            if (!strcmp(s.in_effect[i], NAMES[p])) m |= B(p);
    return m;
}

static void expect(const char *what, unsigned got, unsigned want) {
    char line[512] = "";
    for (int p = 0; p < NP; p++)
        if ((got ^ want) & B(p))
            snprintf(line + strlen(line), sizeof line - strlen(line), " %s %s;", NAMES[p],
                     got & B(p) ? "ran (should not)" : "did not run (should)");
    int n = 0;
    for (int p = 0; p < NP; p++) n += (got >> p) & 1;
    printf("%-44s %2d of %d passes ran%s\n", what, n, NP, got == want ? "" : " MISMATCH");
    CHECK_MSG(got == want, "%s:%s", what, line);
}

/* renders frame `frame` (pinned) and returns which tp-deps passes ran */
static unsigned frame_at(sl_harness *h, uint64_t frame) {
    sl_harness_set_frame(h, frame);
    CHECK(sl_harness_render(h, NULL));
    return ran(h);
}

static void set(sl_harness *h, const char *assignment) {
    char err[1024];
    CHECK_MSG(sl_harness_set(h, assignment, err, sizeof err), "%s: %s", assignment, err);
}

static void test_counts(void) {
    char scene[2048], err[2048];
    snprintf(scene, sizeof scene, SCENE, "");
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 32, .height = 32,
                                                          .scene_json = scene, .strict = true,
                                                          .settings = (const char *[]){"aa.enabled=false", NULL},
                                                          .plugins = (const char *[]){"ggx", "tonemap", "tp-deps", NULL}},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return;
    expect("first frame", frame_at(h, 0), ALL);
    unsigned total[NP] = {0};
    for (int k = 0; k < 5; k++) {
        unsigned m = frame_at(h, 0);
        for (int p = 0; p < NP; p++) total[p] += (m >> p) & 1;
        expect("nothing changed", m, ALWAYS);
        CHECK_MSG(in_effect(h) == ALL, "a skipped pass is not listed in effect (harness structure)");
    }
    printf("over 5 unchanged frames:");
    for (int p = 0; p < NP; p++) printf(" %s %u", NAMES[p] + 5, total[p]);
    printf("\n");
    set(h, "light.sun.intensity=3");
    expect("a light's intensity", frame_at(h, 0), ALWAYS | B(P_LIGHTS) | B(P_PARAMS));
    expect("  and then nothing", frame_at(h, 0), ALWAYS);
    CHECK(sl_harness_set_camera(h, (const float[]){1, 1, 4}, (const float[]){0, 0, 0}));
    expect("the camera", frame_at(h, 0), ALWAYS | B(P_CAMERA) | B(P_INPUTS));
    expect("  and then nothing", frame_at(h, 0), ALWAYS);
    set(h, "material.m.alpha=0.5");
    expect("a material value", frame_at(h, 0), ALWAYS | B(P_MATERIALS) | B(P_PARAMS));
    set(h, "ggx.specular_aa=false");
    expect("a parameter of a plugin with chunks (ggx)", frame_at(h, 0), ALWAYS | B(P_MATERIALS) | B(P_PARAMS));
    set(h, "tonemap.exposure=1");
    expect("a parameter of a plugin without (tonemap)", frame_at(h, 0), ALWAYS | B(P_PARAMS));
    set(h, "tp-deps.knob=2");
    expect("the pass's own plugin's parameter", frame_at(h, 0), ALWAYS | B(P_OWN) | B(P_PARAMS));
    CHECK(sl_harness_set_debug_view(h, "normal", err, sizeof err));
    expect("a debug view (programs change)", frame_at(h, 0), ALWAYS | B(P_MATERIALS) | B(P_PARAMS));
    CHECK(sl_harness_set_debug_view(h, NULL, err, sizeof err));
    frame_at(h, 0);
    expect("time (the next frame, no animation)", frame_at(h, 1), ALWAYS | B(P_TIME));
    expect("  and then nothing", frame_at(h, 1), ALWAYS);
    /* a plugin switched off and on re-plans the graph: new targets, every pass runs */
    set(h, "tonemap.enabled=false");
    expect("a plugin switched off (new plan)", frame_at(h, 1), ALL);
    expect("  and then nothing", frame_at(h, 1), ALWAYS);
    /* core.rerun_passes (what a frame costs while everything moves): every pass in every frame;
     * off again, skipping resumes from keys kept current meanwhile */
    set(h, "core.rerun_passes=true");
    expect("core.rerun_passes", frame_at(h, 1), ALL);
    expect("  and the next frame", frame_at(h, 1), ALL);
    set(h, "core.rerun_passes=false");
    frame_at(h, 1); /* a core parameter: the graph is planned again */
    expect("  off, and then nothing", frame_at(h, 1), ALWAYS);
    sl_harness_destroy(h);

    /* a pass that reads "depth" (ssao) brings the core's depth pre-pass, which runs every frame:
     * it draws the camera's view, not the lights', so the passes that declared LIGHTS stay skipped */
    h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 32, .height = 32,
                                             .scene_json = scene, .strict = true,
                                             .settings = (const char *[]){"aa.enabled=false", NULL},
                                             .plugins = (const char *[]){"ggx", "tonemap", "ssao", "tp-deps", NULL}},
                          err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return;
    expect("with the depth pre-pass (ssao): first frame", frame_at(h, 0), ALL);
    expect("  nothing changed", frame_at(h, 0), ALWAYS);
    expect("  nothing changed again", frame_at(h, 0), ALWAYS);
    set(h, "light.sun.intensity=3");
    expect("  a light's intensity", frame_at(h, 0), ALWAYS | B(P_LIGHTS) | B(P_PARAMS));
    sl_harness_destroy(h);

    /* geometry: tp-good's vertex hook (material key tp_lift) animates the geometry over time */
    snprintf(scene, sizeof scene, SCENE, ", \"tp_lift\": 0.25");
    h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 32, .height = 32,
                                             .scene_json = scene, .strict = true,
                                             .settings = (const char *[]){"aa.enabled=false", NULL},
                                             .plugins = (const char *[]){"ggx", "tp-good", "tp-deps", NULL}},
                          err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return;
    frame_at(h, 0);
    expect("animated geometry, same frame", frame_at(h, 0), ALWAYS);
    expect("animated geometry, next frame", frame_at(h, 1), ALWAYS | B(P_GEOMETRY) | B(P_TIME));
    sl_harness_destroy(h);
}

/* ------------------------------------------------------------------ images -------------- */
enum { N = 48 };
static const char *SSS_SCENE =
    "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 1, 4], \"target\": [0, 0, 0], \"fov_y\": 40}],"
    " \"materials\": [{\"name\": \"skin\", \"model\": \"skin\", \"base_color\": [0.9, 0.7, 0.6], \"sss_radius\": 0.05,"
    " \"sss_color\": [0.6, 0.15, 0.1]}, {\"name\": \"floor\", \"base_color\": [0.5, 0.5, 0.5]}],"
    " \"nodes\": [{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.8}, \"material\": \"skin\"},"
    "  {\"name\": \"box\", \"translate\": [0.9, 0.2, 0.9], \"mesh\": {\"primitive\": \"cube\", \"size\": 0.3}, \"material\": \"floor\"},"
    "  {\"name\": \"ground\", \"translate\": [0, -0.8, 0], \"mesh\": {\"primitive\": \"plane\", \"size\": 6}, \"material\": \"floor\"}],"
    " \"lights\": [{\"name\": \"key\", \"type\": \"spot\", \"position\": [2, 3, 2], \"direction\": [-2, -3, -2],"
    " \"intensity\": 40, \"cast_shadows\": true}]}";

static const char *const SSS_PLUGINS[] = {"sss", "spotlight-shadow", "tonemap", NULL};

static sl_harness *sss_harness(const char *const *settings) {
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = N, .height = N,
                                                          .scene_json = SSS_SCENE, .plugins = SSS_PLUGINS, .strict = true,
                                                          .settings = settings},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    return h;
}

static bool ran_pass(sl_harness *h, const char *name) {
    sl_harness_structure s;
    sl_harness_structure_of(h, &s);
    for (int i = 0; i < s.pass_count; i++)
        if (!strcmp(s.passes[i], name)) return true;
    return false;
}

static const float MOVED_EYE[3] = {-1.5f, 1.2f, 3.5f}, TARGET[3] = {0, 0, 0};

/* a fresh start with the settings (and camera) of a live state: its first frame runs every pass */
static void fresh(const char *const *settings, bool moved, float *img, float *display) {
    sl_harness *f = sss_harness(settings);
    if (!f) return;
    if (moved) CHECK(sl_harness_set_camera(f, MOVED_EYE, TARGET));
    sl_harness_set_frame(f, 0);
    CHECK(sl_harness_render(f, img));
    CHECK(ran_pass(f, "sss-irradiance") && ran_pass(f, "sss-ts-blur") && ran_pass(f, "shadow-maps"));
    CHECK(sl_harness_read_display(f, display));
    sl_harness_destroy(f);
}

static void compare(const char *what, const float *live, const float *live_d, const float *ref, const float *ref_d) {
    sl_compare c, d;
    sl_harness_compare(live, ref, N, N, 1e-6, &c);
    sl_harness_compare(live_d, ref_d, N, N, 1e-6, &d);
    printf("%-52s linear max %.3g, display max %.3g\n", what, c.max_abs, d.max_abs);
    CHECK_MSG(c.max_abs <= 1e-6 && d.max_abs <= 1e-6 && c.nonfinite == 0,
              "%s: differs from a fresh start (linear max %g, display max %g)", what, c.max_abs, d.max_abs);
}

/* The live states, in order: what changed, the settings a fresh start needs for the same state,
 * whether the camera had moved, and which passes must (not) have run. */
typedef struct live_state {
    const char *what, *set;
    bool move_camera;
    bool expect_ts, expect_shadow, expect_stretch; /* sss-irradiance + sss-ts-blur, shadow-maps, sss-stretch ran */
    const char *const *fresh_settings;
} live_state;

#define BASE "aa.enabled=false", "sss.method=texture-space", "sss.ts_size=128"
static const live_state STATES[] = {
    {"still frame (sss and shadow passes skipped)", NULL, false, false, false, false, (const char *[]){BASE, NULL}},
    {"camera moved (sss and shadow passes skipped)", NULL, true, false, false, false, (const char *[]){BASE, NULL}},
    {"tonemap exposure changed (sss and shadows skipped)", "tonemap.exposure=0.5", false, false, false, false,
     (const char *[]){BASE, "tonemap.exposure=0.5", NULL}},
    {"light changed (irradiance, blur, shadows re-ran)", "light.key.intensity=20", false, true, true, false,
     (const char *[]){BASE, "tonemap.exposure=0.5", "light.key.intensity=20", NULL}},
    {"material value changed (texture space re-ran)", "material.skin.sss_radius=0.1", false, true, true, true,
     (const char *[]){BASE, "tonemap.exposure=0.5", "light.key.intensity=20", "material.skin.sss_radius=0.1", NULL}},
};
enum { NS = sizeof STATES / sizeof *STATES };

static void test_images(void) {
    static float live[NS][N * N * 4], live_d[NS][N * N * 4], ref[N * N * 4], ref_d[N * N * 4];
    sl_harness *h = sss_harness(STATES[0].fresh_settings);
    if (!h) return;
    sl_harness_set_frame(h, 0);
    /* read back like the frames below (a read-back keeps "color": the display pass runs in both) */
    CHECK(sl_harness_render(h, live[0]));
    CHECK(ran_pass(h, "sss-irradiance") && ran_pass(h, "shadow-maps"));
    sl_harness_structure first;
    sl_harness_structure_of(h, &first);
    bool moved = false;
    for (int k = 0; k < NS; k++) {
        const live_state *st = &STATES[k];
        if (st->set) set(h, st->set);
        if (st->move_camera) CHECK(sl_harness_set_camera(h, MOVED_EYE, TARGET));
        sl_harness_set_frame(h, 0);
        CHECK(sl_harness_render(h, live[k]) && sl_harness_read_display(h, live_d[k]));
        bool ts = ran_pass(h, "sss-irradiance") && ran_pass(h, "sss-ts-blur"), shadow = ran_pass(h, "shadow-maps");
        CHECK_MSG(ts == st->expect_ts && shadow == st->expect_shadow && ran_pass(h, "sss-stretch") == st->expect_stretch,
                  "%s: texture space %s, shadow maps %s, stretch %s", st->what, ts ? "ran" : "skipped",
                  shadow ? "ran" : "skipped", ran_pass(h, "sss-stretch") ? "ran" : "skipped");
        if (k == 0) { /* a still frame draws less but has the same draw calls in effect */
            sl_harness_structure s;
            sl_harness_structure_of(h, &s);
            CHECK_MSG(s.draw_calls < first.draw_calls && s.effect_draw_calls == first.draw_calls,
                      "still frame: %d draw calls, %d in effect; the first frame %d", s.draw_calls, s.effect_draw_calls,
                      first.draw_calls);
        }
    }
    sl_harness_destroy(h); /* one harness at a time */
    for (int k = 0; k < NS; k++) {
        moved = moved || STATES[k].move_camera;
        fresh(STATES[k].fresh_settings, moved, ref, ref_d);
        compare(STATES[k].what, live[k], live_d[k], ref, ref_d);
    }
}

/* ------------------------------------------------------------------ the default scene --- */

/* the pass records of the project's own graph (harness structure), not a driver's counters */
static int shadow_runs(sl_harness *h, int frames, bool orbit) {
    int runs = 0;
    for (int k = 0; k < frames; k++) {
        if (orbit) {
            float a = 0.3f * (float)(k + 1), eye[3] = {6.9f * sinf(a), 2.3f, 6.9f * cosf(a)};
            CHECK(sl_harness_set_camera(h, eye, (const float[]){0, 0.65f, 0}));
        }
        CHECK(sl_harness_render(h, NULL));
        runs += ran_pass(h, "shadow-maps");
    }
    return runs;
}

static void test_default_scene(void) {
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 48, .height = 32,
                                                          .scene_file = SL_SOURCE_DIR "/scenes/default.json", .strict = true},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return;
    char method[32] = "";
    CHECK(sl_harness_get(h, "aa.method", method, sizeof method) && !strcmp(method, "taa"));
    int first = shadow_runs(h, 1, false), still = shadow_runs(h, 6, false), orbit = shadow_runs(h, 4, true);
    set(h, "light.sun.direction=0.7,-0.6,0.3");
    int moved = shadow_runs(h, 1, false), after = shadow_runs(h, 3, false);
    printf("default scene, shadow-map runs: first frame %d, 6 still frames %d, 4 orbiting frames %d, "
           "the sun moved %d, 3 frames after %d\n", first, still, orbit, moved, after);
    CHECK_MSG(first == 1 && still == 0 && orbit == 0 && moved == 1 && after == 0,
              "shadow maps rendered when nothing they show changed (or not rendered when the sun moved)");
    sl_harness_destroy(h);
}

int main(void) {
    setenv("SHADELAB_PLUGIN_PATH", SL_TEST_PLUGIN_DIR, 1);
    test_counts();
    test_images();
    test_default_scene();
    return check_result();
}
