/* The frame-time budget's controller (controller.h). */
#include "budget/controller.h"
#include <math.h>
#include <string.h>

/* Weight of the past per observation: about the last 10 frames count (a change of load or of
 * what is on screen shows within a few frames). */
#define DECAY 0.9
#define SURPRISE 0.25
/* A better choice replaces the current one only when it lowers the predicted error of the knobs it
 * changes by this much (relative) and is predicted within HEADROOM of the budget; the current one
 * is left only when predicted over OVER of it. Hysteresis both ways, since each change restarts the
 * accumulation and, for the render scale, re-allocates the targets: between the two a choice
 * stays, and frames vary by about ±5 % on a quiet machine (at 0.9 and 1 the default scene sat at
 * 93 % of the budget with a tenth of its frames over it). (Relative to the whole error, the knobs
 * that stay would decide: with envmap's and the shadow's errors in the sum, the default scene's
 * step from render scale 0.35 to 0.5 gained under 15 %.) */
#define SWITCH_GAIN 0.15
#define HEADROOM 0.85
#define OVER 0.95
/* Until a fit has separated the fixed part from the scaled one (every frame so far at about one
 * work, or since a fit put the fixed part below 0), fixed_ms is 0 and a prediction for more work is
 * the proportional one, an upper bound: a step up is taken within this share of the budget, so
 * that the next frames teach the fit the slope. With HEADROOM alone a frame at half the budget
 * could stay there for good: at the default scene's render scale 0.35 (28 ms at 1280x720) the
 * bound for 0.5 was 60 ms, over 0.85 x 66. */
#define EXPLORE_HEADROOM 0.95

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
 * spread in work to separate the two, the fixed part is kept and only unit moves. Returns false
 * when the frames disagree with the model: a fixed part below 0, which a frame dearer than its
 * work makes (the first frame in motion re-plans its targets and compiles TAA's motion program:
 * 414 ms at the default scene's scale 1, where later frames fit 14 + 125 × work). */
static bool fit(sl_budget *b) {
    double mx = b->wx / b->w, my = b->wy / b->w;
    double var = b->wxx / b->w - mx * mx, cov = b->wxy / b->w - mx * my;
    bool consistent = true;
    if (var > 0.01 * mx * mx && cov > 0) {
        b->unit_ms = cov / var;
        b->fixed_ms = my - b->unit_ms * mx;
        consistent = b->identified = b->fixed_ms >= 0;
    }
    if (b->fixed_ms < 0 || b->fixed_ms > my) b->fixed_ms = b->fixed_ms < 0 ? 0 : 0.5 * my;
    b->unit_ms = fmax((my - b->fixed_ms) / mx, 1e-6);
    return consistent;
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
    if (!fit(b)) { /* the past disagrees with this frame: it alone is the model now */
        b->w = 1, b->wx = x, b->wy = ms, b->wxx = x * x, b->wxy = x * ms;
        b->fixed_ms = 0, b->identified = false;
        fit(b);
    }
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

/* The choice while moving (step_moving's), and what it was when a still began (b->motion). */
static bool step_moving(sl_budget *b) {
    int c[SL_BUDGET_MAX_KNOBS];
    double now_ms = sl_budget_predict_ms(b, b->choice);
    double limit = (b->identified ? HEADROOM : EXPLORE_HEADROOM) * b->budget_ms;
    sl_budget_choose(b, limit, c);
    if (now_ms > OVER * b->budget_ms) return set_choice(b, c); /* over: the best choice within */
    /* the gain on the knobs that would change: the others' error is there either way */
    double before = 0, after = 0;
    for (int k = 0; k < b->knob_count; k++)
        if (c[k] != b->choice[k]) before += b->knobs[k].error[b->choice[k]], after += b->knobs[k].error[c[k]];
    return after < before * (1 - SWITCH_GAIN) - 1e-12 && set_choice(b, c);
}

bool sl_budget_step(sl_budget *b, bool moving) {
    bool resumed = moving && b->still >= SL_BUDGET_STILL_FRAMES;
    if (!moving && b->still == 0) memcpy(b->motion, b->choice, sizeof b->motion);
    b->still = moving ? 0 : b->still + 1;
    if (b->still >= SL_BUDGET_STILL_FRAMES) { /* refine: every knob's best */
        int c[SL_BUDGET_MAX_KNOBS];
        for (int k = 0; k < b->knob_count; k++) c[k] = b->knobs[k].count - 1;
        return set_choice(b, c);
    }
    if (!b->observations || b->still > 0) return false; /* nothing known yet; a pause keeps the choice */
    if (resumed) return set_choice(b, b->motion); /* moving again: where motion left off */
    return step_moving(b);
}
