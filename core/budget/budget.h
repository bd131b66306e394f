/* The frame-time budget (core.budget, --budget; docs/budget.md): before each frame the app asks
 * the controller (budget/controller.h) for the render scale and the plugins' knob settings, from
 * the models registered through the extension "shadelab.budget/1" (sdk/include/shadelab/ext/
 * budget.h), and feeds it the time the last frame took (from one frame's start to the next's, so
 * the panel, the present and the swap count). Off (core.budget = 0, the headless default) it does
 * nothing and costs nothing. */
#ifndef SL_BUDGET_H
#define SL_BUDGET_H
#include <shadelab/shadelab.h>
#include <shadelab/ext/budget.h>
#include <stddef.h>

struct sl_app;

/* add_quality_model from plugin `owner` (create(); checked against the extension's rules). */
sl_status sl_budget_add_model(struct sl_app *app, int owner, const sl_quality_model *model);
/* Once per frame, before it is rendered (sl_app_render_frame). */
void sl_budget_before_frame(struct sl_app *app);
/* Every knob to its best now (a screenshot: the still the window settles on). */
void sl_budget_settle(struct sl_app *app);
/* The budget is off or has set every knob to its best for a still ("still: best settings"). */
bool sl_budget_settled(struct sl_app *app);
/* What the budget does, one line for the panel ("66 ms: scale 0.5, spotlight-shadow.pcf_size=3;
 * last frame 58 ms (predicted 61)"); "" when off. */
const char *sl_budget_status(struct sl_app *app);
void sl_budget_free(struct sl_app *app);
#endif
