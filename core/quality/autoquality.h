/* shadelab_quality: the --auto-quality chooser and the little of shadelab-bench it needs.
 *
 * The public header of the library `shadelab_quality` (core/quality/): the viewer (core/main.c,
 * --auto-quality) and shadelab-bench (tools/bench) both link it; nothing else of the bench is
 * in the viewer, and nothing of tools/ is in the core. The contract between the two is the
 * benchmark JSON ("format": "shadelab-bench/1", written by tools/bench/report.c) and the
 * definitions below: metric names, the Pareto front, where results are cached and how a scene
 * is identified.
 *
 * --auto-quality: for each loaded plugin, apply the cheapest setting of a saved benchmark (the
 * JSON shadelab-bench writes) whose error is within a budget.
 *
 * Wiring into the viewer (core/main.c), after sl_app_init and before sl_app_start_gl:
 *     if (c.auto_quality && !sl_autoquality_apply(&app, c.auto_quality, err, sizeof err)) → error
 *
 * SPEC is "[METRIC=]BUDGET[@FRONTS]":
 *   METRIC  rmse | relmse | dssim (1 - SSIM) | psnr | flip | noise; default: the metric the benchmark was
 *           charted with (its "primary_metric", rmse unless --metric said otherwise). For psnr
 *           BUDGET is the lowest acceptable PSNR in dB; for the others the highest error.
 *   FRONTS  comma-separated JSON files or directories of them; default: the "fronts" folder of
 *           the bench cache (sl_bench_default_cache_dir()/fronts, where shadelab-bench saves a
 *           copy of every run).
 * A setting the benchmark marked noisy (its noise above the run's "noise_limit") is never
 * chosen unless every setting is. Per plugin, the run measured on the same scene (same file contents) is preferred, then the
 * newest. When no setting meets the budget, the most accurate one is applied, with a warning.
 * A parameter the user set with --set keeps the user's value. The choices and their measured
 * cost (median frame ms, per-pass ms) and error are printed on stderr. */
#ifndef SL_AUTOQUALITY_H
#define SL_AUTOQUALITY_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

struct sl_app; /* core/app.h */

/* ------------------------------------------------------------------ metrics by name ---- */

/* Lower-is-better metrics by name, for charts, Pareto fronts and budgets (their definitions:
 * tools/bench/include/bench/metrics.h, docs/benchmarks.md). */
typedef enum sl_metric {
    SL_METRIC_RMSE, SL_METRIC_RELMSE, SL_METRIC_DSSIM, SL_METRIC_PSNR, SL_METRIC_FLIP, SL_METRIC_NOISE, SL_METRIC_COUNT
} sl_metric;
/* "rmse", "relmse", "dssim" (1 - SSIM), "psnr" (higher is better: its value is negated in
 * sl_metric_value so that every metric is lower-is-better), "flip" (mean LDR-FLIP), "noise"
 * (the spread of a still's frames). */
const char *sl_metric_name(sl_metric m);
bool sl_metric_parse(const char *name, sl_metric *out);

/* ------------------------------------------------------------------ Pareto front ------- */

/* Pareto front of (cost, error) points, both lower-is-better.
 *
 * Point i is dominated when some other point j has cost_j <= cost_i and error_j <= error_i
 * with at least one of the two strictly smaller. The front is every point that is not
 * dominated; exact duplicates of a front point are on the front too. Points with a NaN cost
 * or error are never on the front and never dominate. */

/* Marks on_front[i]; returns how many points are on the front. */
int sl_pareto_front(const double *cost, const double *error, int n, bool *on_front);
/* The cheapest point whose error is <= budget (ties in cost: the lower error, then the lower
 * index), or -1 when none is. That point is always on the front. */
int sl_pareto_cheapest_within(const double *cost, const double *error, int n, double budget);
/* The point with the lowest error (ties: the cheaper one), or -1 when all are NaN. */
int sl_pareto_most_accurate(const double *cost, const double *error, int n);

/* ------------------------------------------------------------------ bench results ------ */

/* $SHADELAB_CACHE, else $XDG_CACHE_HOME/shadelab, else $HOME/.cache/shadelab. */
const char *sl_bench_default_cache_dir(char *buf, size_t n);
/* FNV-1a 64 of the scene's text (file contents, or the built-in scene); 0 when unreadable. */
uint64_t sl_bench_scene_hash(const char *scene_path);

/* ------------------------------------------------------------------ the chooser -------- */

typedef struct sl_aq_choice {
    char plugin[64];
    char settings[1024];     /* "core.ssaa=2" */
    char metric[16];         /* the metric the budget applied to */
    double frame_ms;         /* measured median frame time of that setting */
    double error;            /* its error under `metric` (psnr: dB) */
    bool within_budget;      /* false: nothing met the budget, this is the most accurate */
    bool noisy;              /* every setting was noisy (shadelab-bench's noise limit); this one too */
    char passes[512];        /* "forward 2.10 ms, display 0.20 ms" */
    char measured_on[512];   /* "scenes/default.json 320x180, osmesa (llvmpipe …)" */
} sl_aq_choice;

/* Picks from one benchmark JSON text; metric NULL = the file's primary metric. */
bool sl_autoquality_choose(const char *json_text, const char *metric, double budget, sl_aq_choice *out,
                           char *err, size_t n);
/* Parses SPEC (see above), chooses per loaded plugin and applies with sl_app_set. Returns false
 * (with err) on a malformed SPEC, unreadable fronts or a setting the app refuses; finding no
 * front for any loaded plugin is a warning, not an error. */
bool sl_autoquality_apply(struct sl_app *app, const char *spec, char *err, size_t n);

#ifdef __cplusplus
}
#endif
#endif
