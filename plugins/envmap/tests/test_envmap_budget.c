/* envmap.specular and envmap.reflections under the frame-time budget (docs/budget.md): envmap
 * registers a cost and error model for each (dominant, fitted, filtered; sky, screen), so that in the window a scene
 * configured with `filtered` — or with `fitted`, the default — gets the one-lookup `dominant` while the view moves and its
 * setting back when it is still.
 * A 64² GGX sphere under the procedural sky, "envmap.specular": "filtered" and "core.budget": 0.001
 * (ms; nothing fits, so the budget takes the cheapest choice) in the scene's params: rendered
 * still (filtered), then 6 frames with the camera moving each frame (dominant from the second
 * moving frame on), then still again (filtered after the budget's still frames, and the image of
 * the still equals a render with filtered and no budget: the configured setting is back). The
 * same with "envmap.specular" given as a setting (--set: the user's choice, which the budget
 * leaves alone): filtered throughout. And a scene configured with "envmap.reflections": "screen":
 * the sky alone while the view moves, screen again when it is still, and the settled still equals
 * screen without a budget. */
#include "check.h"
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 64
#define H 64
static float img[W * H * 4], ref[W * H * 4];

static sl_harness *make(const char *params, const char *const *settings) {
    char json[2048], err[4096];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"envmap\"],\n"
             " \"params\": {%s},\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y\": 40}],\n"
             " \"materials\": [{\"name\": \"m\", \"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 1, "
             "\"base_color\": [1, 1, 1], \"alpha\": 0.3}],\n"
             " \"nodes\": [{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1}, \"material\": \"m\"}]}",
             params);
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                          .scene_json = json, .settings = settings, .float32 = true,
                                                          .strict = true},
                                      err, sizeof err);
    if (!h) fprintf(stderr, "harness: %s\n", err);
    return h;
}

static const char *value_of(sl_harness *h, const char *knob) {
    static char v[32];
    return sl_harness_get(h, knob, v, sizeof v) ? v : "?";
}

/* Renders `n` frames, moving the camera round the sphere before each when `moving`; returns how
 * many of them rendered `knob` at `want` (read after the frame: the setting it was rendered with),
 * not counting the first `grace` frames. */
static float angle = 0;
static void camera_at(sl_harness *h, float a) {
    const float pos[3] = {4 * sinf(a), 0, 4 * cosf(a)}, target[3] = {0, 0, 0};
    CHECK(sl_harness_set_camera(h, pos, target));
}
static int frames_with(sl_harness *h, const char *knob, int n, int grace, bool moving, const char *want, float *out) {
    int hits = 0;
    for (int i = 0; i < n; i++) {
        if (moving) camera_at(h, angle += 0.05f);
        CHECK(sl_harness_render(h, out));
        hits += i >= grace && !strcmp(value_of(h, knob), want);
    }
    return hits;
}

static const char *const base_settings[] = {"aa.enabled=false", "envmap.cube_size=32", "envmap.samples=64",
                                            "envmap.cache=false", NULL};

/* A scene configures `knob` (envmap.NAME) at `best`; with a 0.001 ms budget (no frame fits it on
 * any machine: at 1 ms a 64² frame could, and the controller then stepped up) the moving frames
 * get `cheap` and the still goes back to `best`, equal to a render of `best` without a budget. */
static void test_knob_model(const char *name, const char *best, const char *cheap) {
    char knob[64], params[256];
    snprintf(knob, sizeof knob, "envmap.%s", name);
    snprintf(params, sizeof params, "\"%s\": \"%s\", \"core.budget\": 0.001", knob, best);
    sl_harness *h = make(params, base_settings);
    CHECK(h != NULL);
    if (!h) return;
    int still = frames_with(h, knob, 4, 0, false, best, img);
    /* the first moving frame may keep the still's choice: the controller knows no frame time
     * until a moving frame has been observed (core/budget/controller.c) */
    int moving = frames_with(h, knob, 6, 1, true, cheap, img);
    /* the budget's still frames (3) at the moving choice, then the best (configured) one */
    int back = frames_with(h, knob, 6, 3, false, best, img);
    printf("scene configures %s=%s, budget 0.001 ms: still %d/4 frames %s, moving frames 2-6 %d/5 %s, "
           "still again frames 4-6 %d/3 %s\n", knob, best, still, best, moving, cheap, back, best);
    CHECK_MSG(moving == 5, "the budget left %s=%s in %d of 5 moving frames", knob, value_of(h, knob), 5 - moving);
    CHECK_MSG(back == 3, "the still did not go back to %s (%d of 3)", best, back);
    sl_harness_destroy(h);

    /* the settled still is what `best` renders without a budget from the same camera */
    snprintf(params, sizeof params, "\"%s\": \"%s\"", knob, best);
    h = make(params, base_settings);
    CHECK(h != NULL);
    if (!h) return;
    camera_at(h, angle);
    CHECK(sl_harness_render(h, ref));
    double worst = 0;
    for (int i = 0; i < W * H * 4; i++) worst = fmax(worst, fabs(img[i] - ref[i]));
    printf("the settled still against %s without a budget: largest difference %.3g\n", best, worst);
    CHECK_MSG(worst <= 1e-4, "the settled still differs from %s without a budget by %.3g", best, worst);
    sl_harness_destroy(h);
}

static void test_user_choice(void) {
    const char *const user[] = {"aa.enabled=false", "envmap.cube_size=32", "envmap.samples=64", "envmap.cache=false",
                                "envmap.specular=filtered", NULL};
    sl_harness *h = make("\"core.budget\": 0.001", user);
    CHECK(h != NULL);
    if (!h) return;
    int moving = frames_with(h, "envmap.specular", 4, 0, true, "filtered", img);
    printf("--set envmap.specular=filtered, budget 0.001 ms: moving %d/4 frames filtered\n", moving);
    CHECK_MSG(moving == 4, "the budget changed the user's envmap.specular to %s", value_of(h, "envmap.specular"));
    sl_harness_destroy(h);
}

int main(void) {
    test_knob_model("specular", "filtered", "dominant");
    test_knob_model("specular", "fitted", "dominant"); /* the default */
    test_knob_model("reflections", "screen", "sky");
    test_user_choice();
    return check_result();
}
