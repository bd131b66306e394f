/* --auto-quality: for each loaded plugin, apply the cheapest setting of a saved benchmark (the
 * JSON shadelab-bench writes) whose error is within a budget.
 *
 * Wiring into the viewer (core/main.c), after sl_app_init and before sl_app_start_gl:
 *     if (c.auto_quality && !sl_autoquality_apply(&app, c.auto_quality, err, sizeof err)) → error
 *
 * SPEC is "[METRIC=]BUDGET[@FRONTS]":
 *   METRIC  rmse | relmse | dssim (1 - SSIM) | psnr; default: the metric the benchmark was
 *           charted with (its "primary_metric", rmse unless --metric said otherwise). For psnr
 *           BUDGET is the lowest acceptable PSNR in dB; for the others the highest error.
 *   FRONTS  comma-separated JSON files or directories of them; default: the "fronts" folder of
 *           the bench cache (sl_bench_default_cache_dir()/fronts, where shadelab-bench saves a
 *           copy of every run).
 * Per plugin, the run measured on the same scene (same file contents) is preferred, then the
 * newest. When no setting meets the budget, the most accurate one is applied, with a warning.
 * A parameter the user set with --set keeps the user's value. The choices and their measured
 * cost (median frame ms, per-pass ms) and error are printed on stderr. */
#ifndef SL_AUTOQUALITY_H
#define SL_AUTOQUALITY_H
#include "app.h"
#include "metrics.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sl_aq_choice {
    char plugin[64];
    char settings[1024];     /* "core.ssaa=2" */
    char metric[16];         /* the metric the budget applied to */
    double frame_ms;         /* measured median frame time of that setting */
    double error;            /* its error under `metric` (psnr: dB) */
    bool within_budget;      /* false: nothing met the budget, this is the most accurate */
    char passes[512];        /* "forward 2.10 ms, display 0.20 ms" */
    char measured_on[512];   /* "scenes/default.json 320x180, osmesa (llvmpipe …)" */
} sl_aq_choice;

/* Picks from one benchmark JSON text; metric NULL = the file's primary metric. */
bool sl_autoquality_choose(const char *json_text, const char *metric, double budget, sl_aq_choice *out,
                           char *err, size_t n);
/* Parses SPEC (see above), chooses per loaded plugin and applies with sl_app_set. Returns false
 * (with err) on a malformed SPEC, unreadable fronts or a setting the app refuses; finding no
 * front for any loaded plugin is a warning, not an error. */
bool sl_autoquality_apply(sl_app *app, const char *spec, char *err, size_t n);

#ifdef __cplusplus
}
#endif
#endif
