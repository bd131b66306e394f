/* The frame-time budget's controller: pure logic, no GL, no app (tests/test_budget.c drives it with
 * synthetic cost models).
 *
 * A knob is a parameter with a few settings, cheapest first and best last, each with a declared
 * cost factor (the frame's cost at that setting relative to its best, which is 1) and a predicted
 * error (one metric for all knobs, errors add up). The frame time of a choice (one setting per
 * knob) is predicted as
 *     ms = fixed_ms + unit_ms × work,   work = the product of the chosen settings' cost factors,
 * where fixed_ms (what no knob changes) and unit_ms (the frame at every knob's best) are fitted
 * online to the frame times observed, by least squares weighted towards recent frames. While
 * anything moves the controller picks the choice of lowest predicted error among those predicted
 * within the budget (the cheapest choice when none is); when the view has been still for a few
 * frames it picks every knob's best, which the still then accumulates at. A step up is taken when
 * predicted within 85 % of the budget once the fit has told the fixed part from the scaled one,
 * and within 95 % while it cannot (frames at one work so far: its prediction for more work is then
 * an upper bound, and the step is what lets it learn the slope); a step down when the current
 * choice is predicted over 95 % (controller.c: HEADROOM, EXPLORE_HEADROOM, OVER). */
#ifndef SL_BUDGET_CONTROLLER_H
#define SL_BUDGET_CONTROLLER_H
#include <stdbool.h>

#define SL_BUDGET_MAX_KNOBS 12
#define SL_BUDGET_MAX_SETTINGS 12
/* consecutive still frames before the controller refines to the best settings */
#define SL_BUDGET_STILL_FRAMES 3
/* Levels of detail, the last resort: after this many consecutive motion frames over the budget
 * with every knob at its cheapest (what no knob scales, the geometry, is too much), motion frames
 * are drawn with core.lod_pixels 1, then 2, 4, ... up to SL_BUDGET_LOD_MAX. */
#define SL_BUDGET_LOD_FRAMES 3
#define SL_BUDGET_LOD_MAX 16.0f

typedef struct sl_budget_knob {
    char id[96];                                  /* the parameter ("core.render_scale") */
    int count;                                    /* settings, cheapest first, best last */
    char value[SL_BUDGET_MAX_SETTINGS][24];       /* each as --set text */
    double cost[SL_BUDGET_MAX_SETTINGS];          /* cost factor, > 0, best = 1 */
    double error[SL_BUDGET_MAX_SETTINGS];         /* predicted error, >= 0 */
} sl_budget_knob;

typedef struct sl_budget {
    sl_budget_knob knobs[SL_BUDGET_MAX_KNOBS];
    int knob_count;
    double budget_ms;
    int choice[SL_BUDGET_MAX_KNOBS];              /* the current setting of each knob */
    /* the online cost model and its weighted sums (decay per observation) */
    double fixed_ms, unit_ms;
    double w, wx, wy, wxx, wxy;
    int observations;
    bool identified;                              /* a fit has separated fixed_ms from unit_ms (kept
                                                     while later frames have one work) */
    int still;                                    /* consecutive frames without motion */
    int motion[SL_BUDGET_MAX_KNOBS];              /* the choice when the last still began */
    float lod_pixels;                             /* motion's level-of-detail tolerance (0: none) */
    int lod_over;                                 /* consecutive motion frames over at the cheapest */
} sl_budget;

/* Starts with every knob at its best and no observation; budget_ms > 0. */
void sl_budget_init(sl_budget *b, double budget_ms);
/* Appends a knob (false when full or malformed: no setting, a cost <= 0, best's cost not 1). */
bool sl_budget_add_knob(sl_budget *b, const sl_budget_knob *k);
double sl_budget_work(const sl_budget *b, const int *choice);
double sl_budget_predict_ms(const sl_budget *b, const int *choice);
double sl_budget_error(const sl_budget *b, const int *choice);
/* The choice of lowest predicted error among those predicted within `budget_ms` (ties: the
 * cheaper); when none is, the cheapest. Exhaustive over every combination. */
void sl_budget_choose(const sl_budget *b, double budget_ms, int *choice);
/* A frame rendered with `choice` took `ms`: updates the cost model, and b->lod_pixels (see
 * SL_BUDGET_LOD_FRAMES; it is kept through stills, since the scene still needs it when it moves
 * again). Call it before the next sl_budget_step. A frame rendered while still (b->still > 0) is
 * left out: a still's frames cost what motion does not (a TAA still's Monte Carlo samples), and
 * the model is motion's. */
void sl_budget_observe(sl_budget *b, const int *choice, double ms);
/* Once per frame, before rendering it: whether anything moved since the last frame. Updates
 * b->choice and returns true when it changed. Moving: the best choice within the budget, kept
 * unless it is predicted over the budget or another is better by enough to be worth a restart of
 * the image's accumulation (a change costs a TAA restart). Still for SL_BUDGET_STILL_FRAMES
 * frames: every knob's best. Before the first observation nothing changes. */
bool sl_budget_step(sl_budget *b, bool moving);
#endif
