/* What the frame-time budget takes for motion in a real scene (scenes/env_sky.json, whose envmap
 * switches on a light of its own, the sky's sun, core.budget=66), and what it learns from:
 *  - nothing in the frames after the opening one while nothing moves: the window opens as a
 *    still (docs/budget.md), though the sun came on as the first frame began;
 *  - an edit that recompiles the materials (ggx.zero_specular) is a frame of motion whose time is
 *    the compile's: it stays out of the cost model (no prediction yet afterwards);
 *  - an edit that switches the sun off (envmap.sun_light=false) is one frame of motion, not a
 *    second one when the renderer next sees which plugins have lights on. */
#include "app.h"
#include "budget/budget.h"
#include "check.h"
#include <stdio.h>
#include <string.h>

static bool moving(sl_app *app, int frame) {
    const char *status = sl_budget_status(app);
    printf("frame %d: %s\n", frame, status);
    return !strncmp(status, "moving", 6);
}

int main(void) {
    sl_app app;
    char err[4096];
    sl_app_options o = {.scene_path = SL_TEST_DATA_DIR "/../../scenes/env_sky.json", .backend = SL_BACKEND_OSMESA,
                        .width = 48, .height = 32, .settings = {"core.budget=66"}, .setting_count = 1};
    bool ok = sl_app_init(&app, &o, err, sizeof err) && sl_app_start_gl(&app, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    int frame = 0;
    for (; ok && frame < 5; frame++) {
        ok = sl_app_render_frame(&app);
        CHECK_MSG(!moving(&app, frame), "frame %d of the opening still taken for motion", frame);
    }
    CHECK_MSG(ok && !strncmp(sl_budget_status(&app), "still: best settings", 20), "after 5 still frames: %s",
              sl_budget_status(&app));
    /* an edit that recompiles the materials: a frame of motion whose time is the compile's */
    CHECK_MSG(ok && sl_app_set(&app, "ggx.zero_specular=true", SL_SRC_CLI, err, sizeof err), "%s", err);
    for (int i = 0; ok && i < 4; i++, frame++) {
        ok = sl_app_render_frame(&app);
        moving(&app, frame);
    }
    CHECK_MSG(ok && !strstr(sl_budget_status(&app), "(predicted"), "a frame that compiled entered the cost model: %s",
              sl_budget_status(&app));
    CHECK_MSG(ok && sl_app_set(&app, "envmap.sun_light=false", SL_SRC_CLI, err, sizeof err), "%s", err);
    int moved = 0;
    for (int i = 0; ok && i < 6; i++, frame++) {
        ok = sl_app_render_frame(&app);
        moved += moving(&app, frame);
    }
    CHECK_MSG(ok && moved == 1, "the edit was taken for %d frames of motion", moved);
    CHECK_MSG(ok && !strncmp(sl_budget_status(&app), "still: best settings", 20), "after the edit: %s",
              sl_budget_status(&app));
    sl_app_shutdown(&app);
    return check_result();
}
