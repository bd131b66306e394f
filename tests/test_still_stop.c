/* Headless stills that stop when they are done (core/still.h): the white furnace (a sphere in a
 * uniform environment, exact: nothing to antialias) converges after two of TAA's 16 frames, and
 * that image is the full still's to within 2/255; the bare scene's hard edges keep changing by
 * more than 1/255 per frame, so its still runs to the end; a budget stops a still after its first
 * frame. */
#include "app.h"
#include "check.h"
#include "still.h"
#include <math.h>
#include <stdlib.h>

typedef struct still_run { int frames, needed; const char *stopped; double change; float *display; } still_run;

/* Renders scene's still as main.c does, with sl_still; full: ignore the early stops. */
static bool run(const char *scene, double budget, bool full, still_run *out) {
    sl_app app;
    char err[4096];
    sl_app_options o = {.scene_path = scene, .backend = SL_BACKEND_OSMESA, .width = 48, .height = 32};
    bool ok = sl_app_init(&app, &o, err, sizeof err) && sl_app_start_gl(&app, err, sizeof err);
    CHECK_MSG(ok, "%s: %s", scene, err);
    sl_still s;
    sl_still_begin(&s, budget);
    for (bool done = false; ok && !done;) {
        ok = sl_app_render_frame(&app);
        done = sl_still_done(&s, &app);
        if (full && done && s.frames < s.needed) done = false;
    }
    out->frames = s.frames, out->needed = s.needed, out->stopped = s.stopped, out->change = s.change;
    out->display = malloc(sizeof(float) * 48 * 32 * 4);
    ok = ok && sl_app_read_display(&app, out->display);
    sl_still_end(&s);
    sl_app_shutdown(&app);
    return ok;
}

static double max_diff(const float *a, const float *b) {
    double m = 0;
    for (int i = 0; i < 48 * 32 * 4; i++) m = fmax(m, fabs((double)a[i] - b[i]));
    return m;
}

int main(void) {
    const char *furnace = SL_TEST_DATA_DIR "/../../scenes/furnace.json", *basic = SL_TEST_DATA_DIR "/../../scenes/basic.json";
    still_run early, full, edges, budget;
    if (run(furnace, 0, false, &early) && run(furnace, 0, true, &full)) {
        CHECK_MSG(early.needed == 16 && early.frames < 16 && !strcmp(early.stopped, "converged"), "%d of %d: %s",
                  early.frames, early.needed, early.stopped);
        CHECK(early.change < 1.0 / 255);
        CHECK(full.frames == 16 && !strcmp(full.stopped, "complete"));
        double d = max_diff(early.display, full.display);
        CHECK_MSG(d <= 2.0 / 255, "the early still differs from the full one by %g", d);
        free(early.display), free(full.display);
    }
    if (run(basic, 0, false, &edges)) {
        CHECK_MSG(edges.frames == edges.needed && edges.needed > 1 && !strcmp(edges.stopped, "complete"), "%d of %d: %s",
                  edges.frames, edges.needed, edges.stopped);
        free(edges.display);
    }
    if (run(basic, 1e-3, false, &budget)) {
        CHECK_MSG(budget.frames == 1 && !strcmp(budget.stopped, "budget"), "%d frames: %s", budget.frames, budget.stopped);
        free(budget.display);
    }
    return check_result();
}
