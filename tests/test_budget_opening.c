/* The window opens as a still (docs/budget.md): with a frame-time budget, no frame after the
 * opening one is taken for motion while nothing moves, also where a plugin switches on a light of
 * its own as the first frame begins (envmap's sky sun, scenes/env_sky.json): a light the renderer
 * saw come on in the opening frame is not a change the next frame reports. Taken for motion, that
 * frame restarted the still and put off its best settings by a frame. */
#include "app.h"
#include "budget/budget.h"
#include "check.h"
#include <stdio.h>
#include <string.h>

int main(void) {
    sl_app app;
    char err[4096];
    sl_app_options o = {.scene_path = SL_TEST_DATA_DIR "/../../scenes/env_sky.json", .backend = SL_BACKEND_OSMESA,
                        .width = 48, .height = 32, .settings = {"core.budget=66"}, .setting_count = 1};
    bool ok = sl_app_init(&app, &o, err, sizeof err) && sl_app_start_gl(&app, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    for (int i = 0; ok && i < 5; i++) {
        ok = sl_app_render_frame(&app);
        const char *status = sl_budget_status(&app);
        printf("frame %d: %s\n", i, status);
        CHECK_MSG(strncmp(status, "moving", 6) != 0, "frame %d taken for motion: %s", i, status);
    }
    CHECK_MSG(ok && !strncmp(sl_budget_status(&app), "still: best settings", 20), "after 5 still frames: %s",
              sl_budget_status(&app));
    sl_app_shutdown(&app);
    return check_result();
}
