/* The frame-time budget's controller (controller.h). */
#include "budget/controller.h"
#include <math.h>
#include <string.h>

/* Weight of the past per observation: about the last 10 frames count (a change of load or of
 * what is on screen shows within a few frames). */
#define DECAY 0.9
#define SURPRISE 0.25
/* A better choice replaces the current one only when it lowers the predicted error by this much
 * (relative) and is predicted within this share of the budget: hysteresis, since each change
 * restarts the accumulation and, for the render scale, re-allocates the targets. */
#define SWITCH_GAIN 0.15
#define HEADROOM 0.9

void sl_budget_init(sl_budget *b, double budget_ms) {
    memset(b, 0, sizeof *b);
    b->budget_ms = budget_ms;
}

bool sl_budget_add_knob(sl_budget *b, const sl_budget_knob *k) {
    if (b->knob_count == SL_BUDGET_MAX_KNOBS || k->count < 1 || k->count > SL_BUDGET_MAX_SETTINGS) return false;
    for (int i = 0; i < k->count; i++)
        if (!(k->cost[i] > 0) || !(k->error[i] >= 0)) return false;
    if (fabs(k->cost[k->count - 1] - 1.0) > 1e-9) return false;
    b->knobs[b->knob_count] = *k;
    b->choice[b->knob_count] = k->count - 1;
    b->knob_count++;
    return true;
}

double sl_budget_work(const sl_budget *b, const int *choice) {
    double w = 1;
    for (int k = 0; k < b->knob_count; k++) w *= b->knobs[k].cost[choice[k]];
    return w;
}

double sl_budget_predict_ms(const sl_budget *b, const int *choice) {
    return b->fixed_ms + b->unit_ms * sl_budget_work(b, choice);
}

double sl_budget_error(const sl_budget *b, const int *choice) {
    double e = 0;
    for (int k = 0; k < b->knob_count; k++) e += b->knobs[k].error[choice[k]];
    return e;
}

/* Odometer over every combination (at most 12^12 in principle; the core's knobs are a handful
 * with a few settings each, so a few hundred combinations). */
static bool next_combination(const sl_budget *b, int *c) {
    for (int k = 0; k < b->knob_count; k++) {
        if (++c[k] < b->knobs[k].count) return true;
        c[k] = 0;
    }
    return false;
}

void sl_budget_choose(const sl_budget *b, double budget_ms, int *choice) {
    int c[SL_BUDGET_MAX_KNOBS] = {0};
    double best_err = INFINITY, best_ms = INFINITY, cheapest_ms = INFINITY;
    int best[SL_BUDGET_MAX_KNOBS], cheapest[SL_BUDGET_MAX_KNOBS];
    bool found = false;
    do {
        double ms = sl_budget_predict_ms(b, c), err = sl_budget_error(b, c);
        if (ms < cheapest_ms) cheapest_ms = ms, memcpy(cheapest, c, sizeof cheapest);
        if (ms <= budget_ms && (err < best_err || (err == best_err && ms < best_ms))) {
            best_err = err, best_ms = ms, found = true;
            memcpy(best, c, sizeof best);
        }
    } while (next_combination(b, c));
    memcpy(choice, found ? best : cheapest, sizeof(int) * (size_t)b->knob_count);
}

/* Weighted least squares of ms = fixed + unit × work over the decayed sums. With too little
 * spread in work to separate the two, the fixed part is kept and only unit moves. */
static void fit(sl_budget *b) {
    double mx = b->wx / b->w, my = b->wy / b->w;
    double var = b->wxx / b->w - mx * mx, cov = b->wxy / b->w - mx * my;
    if (var > 0.01 * mx * mx && cov > 0) {
        b->unit_ms = cov / var;
        b->fixed_ms = my - b->unit_ms * mx;
    }
    if (b->fixed_ms < 0 || b->fixed_ms > my) b->fixed_ms = b->fixed_ms < 0 ? 0 : 0.5 * my;
    b->unit_ms = fmax((my - b->fixed_ms) / mx, 1e-6);
}

void sl_budget_observe(sl_budget *b, const int *choice, double ms) {
    if (!(ms > 0) || !isfinite(ms) || b->still > 0) return;
    double x = sl_budget_work(b, choice);
    /* a frame far from the prediction (the load changed, other content on screen): the past
     * counts for less, so the model follows within a few frames */
    double pred = sl_budget_predict_ms(b, choice);
    double d = b->observations && fabs(ms / pred - 1) > SURPRISE ? DECAY * DECAY * DECAY : DECAY;
    b->w = d * b->w + 1;
    b->wx = d * b->wx + x;
    b->wy = d * b->wy + ms;
    b->wxx = d * b->wxx + x * x;
    b->wxy = d * b->wxy + x * ms;
    b->observations++;
    fit(b);
    bool cheapest = true;
    for (int k = 0; k < b->knob_count; k++) cheapest = cheapest && choice[k] == 0;
    b->lod_over = cheapest && ms > b->budget_ms ? b->lod_over + 1 : 0;
    if (b->lod_over >= SL_BUDGET_LOD_FRAMES && b->lod_pixels < SL_BUDGET_LOD_MAX) {
        b->lod_pixels = b->lod_pixels > 0 ? fminf(2 * b->lod_pixels, SL_BUDGET_LOD_MAX) : 1;
        b->lod_over = 0;
    }
}

static bool set_choice(sl_budget *b, const int *c) {
    bool changed = memcmp(b->choice, c, sizeof(int) * (size_t)b->knob_count) != 0;
    memcpy(b->choice, c, sizeof(int) * (size_t)b->knob_count);
    return changed;
}

bool sl_budget_step(sl_budget *b, bool moving) {
    b->still = moving ? 0 : b->still + 1;
    int c[SL_BUDGET_MAX_KNOBS];
    if (b->still >= SL_BUDGET_STILL_FRAMES) { /* refine: every knob's best */
        for (int k = 0; k < b->knob_count; k++) c[k] = b->knobs[k].count - 1;
        return set_choice(b, c);
    }
    if (!b->observations || b->still > 0) return false; /* nothing known yet; a pause keeps the choice */
    double now_ms = sl_budget_predict_ms(b, b->choice), now_err = sl_budget_error(b, b->choice);
    if (now_ms > b->budget_ms) { /* over: the best choice within the budget, with headroom */
        sl_budget_choose(b, HEADROOM * b->budget_ms, c);
        return set_choice(b, c);
    }
    sl_budget_choose(b, HEADROOM * b->budget_ms, c);
    double err = sl_budget_error(b, c);
    if (err < now_err * (1 - SWITCH_GAIN) - 1e-12) return set_choice(b, c);
    return false;
}
