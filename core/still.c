/* Stills that stop when they are done (see still.h). */
#include "still.h"
#include "render/renderer.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

void sl_still_begin(sl_still *s, double budget_s) {
    memset(s, 0, sizeof *s);
    s->budget_s = budget_s;
    s->t0 = now_s();
    s->change = NAN;
}

/* The largest change of a display value since the previous frame; NaN on the first. */
static double display_change(sl_still *s, sl_app *app) {
    size_t n = (size_t)app->backend.width * app->backend.height * 4;
    if (!s->cur) {
        s->cur = malloc(sizeof(float) * n);
        s->prev = malloc(sizeof(float) * n);
        if (!s->cur || !s->prev) return NAN;
    }
    if (!sl_app_read_display(app, s->cur)) return NAN;
    double most = NAN;
    if (s->frames >= 2) {
        most = 0;
        for (size_t i = 0; i < n; i++)
            if (i % 4 != 3) most = fmax(most, fabs((double)s->cur[i] - s->prev[i]));
    }
    float *t = s->prev;
    s->prev = s->cur, s->cur = t;
    return most;
}

bool sl_still_done(sl_still *s, sl_app *app) {
    s->frames++;
    s->needed = sl_renderer_still_frames(app);
    if (s->frames >= s->needed) { s->stopped = "complete"; return true; }
    if (s->budget_s > 0 && now_s() - s->t0 >= s->budget_s) { s->stopped = "budget"; return true; }
    s->change = display_change(s, app);
    if (s->change < SL_STILL_CHANGE) { s->stopped = "converged"; return true; } /* NaN: not yet */
    return false;
}

void sl_still_end(sl_still *s) {
    free(s->prev);
    free(s->cur);
    s->prev = s->cur = NULL;
}
