/* envmap.specular and envmap.reflections under the frame-time budget (docs/budget.md): envmap
 * registers a cost and error model for each (dominant, filtered; sky, screen), so that in the window a scene configured with `filtered`
 * gets the one-lookup `dominant` while the view moves and `filtered` back when it is still.
 * A 64² GGX sphere under the procedural sky, "envmap.specular": "filtered" and "core.budget": 1
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

static const char *knob = "envmap.specular";
static const char *specular(sl_harness *h) {
    static char v[32];
    return sl_harness_get(h, knob, v, sizeof v) ? v : "?";
}

/* Renders `n` frames, moving the camera round the sphere before each when `moving`; returns how
 * many of them rendered with `want` (read after the frame: the setting it was rendered with),
 * not counting the first `grace` frames. */
static float angle = 0;
static void camera_at(sl_harness *h, float a) {
    const float pos[3] = {4 * sinf(a), 0, 4 * cosf(a)}, target[3] = {0, 0, 0};
    CHECK(sl_harness_set_camera(h, pos, target));
}
static int frames_with(sl_harness *h, int n, int grace, bool moving, const char *want, float *out) {
    int hits = 0;
    for (int i = 0; i < n; i++) {
        if (moving) camera_at(h, angle += 0.05f);
        CHECK(sl_harness_render(h, out));
        hits += i >= grace && !strcmp(specular(h), want);
    }
    return hits;
}

static void test_budget_model(void) {
    const char *const none[] = {"aa.enabled=false", "envmap.cube_size=32", "envmap.samples=64", "envmap.cache=false", NULL};
    sl_harness *h = make("\"envmap.specular\": \"filtered\", \"core.budget\": 1", none);
    CHECK(h != NULL);
    if (!h) return;
    int still = frames_with(h, 4, 0, false, "filtered", img);
    /* the first moving frame may keep the still's choice: the controller knows no frame time
     * until a moving frame has been observed (core/budget/controller.c) */
    int moving = frames_with(h, 6, 1, true, "dominant", img);
    /* the budget's still frames (3) at the moving choice, then the best (configured) one */
    int back = frames_with(h, 6, 3, false, "filtered", img);
    printf("scene configures filtered, budget 1 ms: still %d/4 frames filtered, moving frames 2-6 %d/5 dominant, "
           "still again frames 4-6 %d/3 filtered\n", still, moving, back);
    CHECK_MSG(moving == 5, "the budget left envmap.specular=%s in %d of 5 moving frames", specular(h), 5 - moving);
    CHECK_MSG(back == 3, "the still did not go back to filtered (%d of 3)", back);
    sl_harness_destroy(h);

    /* the settled still is what filtered renders without a budget from the same camera */
    h = make("\"envmap.specular\": \"filtered\"", none);
    CHECK(h != NULL);
    if (!h) return;
    camera_at(h, angle);
    CHECK(sl_harness_render(h, ref));
    double worst = 0;
    for (int i = 0; i < W * H * 4; i++) worst = fmax(worst, fabs(img[i] - ref[i]));
    printf("the settled still against filtered without a budget: largest difference %.3g\n", worst);
    CHECK_MSG(worst <= 1e-4, "the settled still differs from filtered without a budget by %.3g", worst);
    sl_harness_destroy(h);
}

static void test_user_choice(void) {
    const char *const user[] = {"aa.enabled=false", "envmap.cube_size=32", "envmap.samples=64", "envmap.cache=false",
                                "envmap.specular=filtered", NULL};
    sl_harness *h = make("\"core.budget\": 1", user);
    CHECK(h != NULL);
    if (!h) return;
    int moving = frames_with(h, 4, 0, true, "filtered", img);
    printf("--set envmap.specular=filtered, budget 1 ms: moving %d/4 frames filtered\n", moving);
    CHECK_MSG(moving == 4, "the budget changed the user's envmap.specular to %s", specular(h));
    sl_harness_destroy(h);
}

static void test_reflections_model(void) {
    const char *const none[] = {"aa.enabled=false", "envmap.cube_size=32", "envmap.samples=64", "envmap.cache=false", NULL};
    knob = "envmap.reflections";
    sl_harness *h = make("\"envmap.reflections\": \"screen\", \"core.budget\": 1", none);
    CHECK(h != NULL);
    if (!h) return;
    int still = frames_with(h, 4, 0, false, "screen", img);
    int moving = frames_with(h, 6, 1, true, "sky", img);
    int back = frames_with(h, 6, 3, false, "screen", img);
    printf("scene configures reflections=screen, budget 1 ms: still %d/4 frames screen, moving frames 2-6 %d/5 sky, "
           "still again frames 4-6 %d/3 screen\n", still, moving, back);
    CHECK_MSG(moving == 5, "the budget left envmap.reflections=%s in %d of 5 moving frames", specular(h), 5 - moving);
    CHECK_MSG(back == 3, "the still did not go back to screen (%d of 3)", back);
    sl_harness_destroy(h);
    h = make("\"envmap.reflections\": \"screen\"", none);
    CHECK(h != NULL);
    if (!h) return;
    camera_at(h, angle);
    CHECK(sl_harness_render(h, ref));
    double worst = 0;
    for (int i = 0; i < W * H * 4; i++) worst = fmax(worst, fabs(img[i] - ref[i]));
    printf("the settled still against reflections=screen without a budget: largest difference %.3g\n", worst);
    CHECK_MSG(worst <= 1e-4, "the settled still differs from screen without a budget by %.3g", worst);
    sl_harness_destroy(h);
    knob = "envmap.specular";
}

int main(void) {
    test_budget_model();
    test_reflections_model();
    test_user_choice();
    return check_result();
}
