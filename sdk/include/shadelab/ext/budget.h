/* Extension "shadelab.budget/1": a plugin's quality knobs with their cost and error models, for
 * the viewer's frame-time budget (`core.budget`, `--budget 66ms`; docs/budget.md). Provided by
 * the core.
 *
 * While the camera, lights or parameters move, the core picks per frame the render scale and each
 * knob's setting that minimise the predicted error within the budget; when the view is still it
 * sets every knob to its best and lets the still accumulate. A knob's model is what the plugin
 * measured once (its shadelab-bench chart, its README): per setting the cost relative to its best
 * and the error against its reference. The core corrects the costs online from the frame times it
 * observes (one fitted model for the whole frame: a fixed part and a part the knobs scale).
 *
 *     #include <shadelab/ext/budget.h>
 *     static const char *const taps[] = {"1", "3", "5"};
 *     static const float cost[] = {0.82f, 0.9f, 1}, error[] = {0.0033f, 0.0022f, 0.0019f};
 *     const sl_ext_budget *b = host->get_extension(host, SL_EXT_BUDGET);
 *     if (b) b->add_quality_model(host, &(sl_quality_model){.struct_size = sizeof(sl_quality_model),
 *                                 .param = "pcf_size", .count = 3, .values = taps, .cost = cost, .error = error,
 *                                 .measured_with = "bench/spheres.sh, README table"});
 *
 * Rules: the parameter is the plugin's own global one, flagged SL_PARAM_QUALITY_KNOB; settings
 * run from cheapest to best, the best's cost is 1; errors are RMSE of linear radiance against the
 * plugin's reference (the core's render scale is modelled in the same unit), so that errors of
 * different knobs add up. The knob's value the user or the scene configured is the ceiling: the
 * budget only lowers it while moving (settings above it are ignored), and a value set with --set
 * or in the panel is left alone. Call add_quality_model in create(), after add_param.
 */
#ifndef SHADELAB_EXT_BUDGET_H
#define SHADELAB_EXT_BUDGET_H
#include "../shadelab.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SL_EXT_BUDGET "shadelab.budget/1"

/* Fields are only ever appended; set struct_size to sizeof(sl_quality_model). */
typedef struct sl_quality_model {
    uint32_t struct_size;
    const char *param;              /* the plugin's own parameter, without the "plugin." prefix */
    int count;                      /* settings, 1..12, cheapest first, best last */
    const char *const *values;      /* each setting as --set text */
    const float *cost;              /* frame cost at each setting relative to the best (> 0; best = 1) */
    const float *error;             /* RMSE of linear radiance against the plugin's reference (>= 0) */
    const char *measured_with;      /* where the numbers come from (shown with the choices) */
} sl_quality_model;

typedef struct sl_ext_budget {
    uint32_t struct_size;           /* sizeof(sl_ext_budget) of the host */
    /* SL_ERR_INVALID (with a message naming the rule) when a rule above is broken. */
    sl_status (*add_quality_model)(const sl_host *host, const sl_quality_model *model);
} sl_ext_budget;

#ifdef __cplusplus
}
#endif
#endif
