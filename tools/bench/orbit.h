/* shadelab-bench --orbit: the viewer's frames as a user feels them (issue 44 item 2).
 *
 * A scripted, slow orbit of the camera about the scene's target, driven by the wall clock as a
 * user's drag is: frame i is rendered at yaw0 + speed * (its start time), as fast as the
 * renderer goes, for `seconds`; the scene's clock stays at 0 (only the camera moves). Reported:
 *   - frame times (render + glFinish, CPU wall): p50, p95, p99, mean, and the fraction of
 *     frames over the budget; the CPU time of the process's threads per frame (p50, mean): on a
 *     CPU rasteriser the work a frame costs, which other processes on the machine do not inflate;
 *   - at `points` moments evenly spread over the orbit, a pair of consecutive motion frames
 *     (f_{k-1}, f_k), compared afterwards, untimed, with the highest-quality still at each
 *     frame's camera (h_{k-1}, h_k: the scene with `hq_settings` on top, rendered as a complete
 *     still): FLIP and RMSE of f_k against h_k ("motion"); the same for the converged still of
 *     the orbit's own settings at f_k's camera ("still");
 *   - flicker: RMS over pixels and R, G, B of ((f_k - h_k) - (f_{k-1} - h_{k-1})) on
 *     display-encoded values (sRGB of the value clamped to [0,1]): the frame-to-frame change
 *     that the change of the truth between the two cameras (the motion) does not explain.
 * Documentation: tools/bench/README.md, "--orbit". */
#ifndef SL_BENCH_ORBIT_H
#define SL_BENCH_ORBIT_H
#include "toolkit.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SL_ORBIT_DEGREES_PER_SECOND 10.0
#define SL_ORBIT_BUDGET_MS 66.0
#define SL_ORBIT_POINTS 4
#define SL_ORBIT_HQ_SETTINGS "core.ssaa=4"

typedef struct sl_orbit_options {
    const char *scene_path;          /* NULL: the built-in default scene */
    const char *data_dir;
    const char *const *settings; int setting_count; /* "id=value" for every render */
    const char *variant;             /* "a=1 b=2": the orbit's renders only, not the truth's (NULL: none) */
    int width, height;               /* default 320x180 */
    sl_backend_kind backend;         /* default OSMesa */
    double seconds;                  /* wall-clock length of the orbit, > 0 */
    double degrees_per_second;       /* 0: SL_ORBIT_DEGREES_PER_SECOND */
    double budget_ms;                /* 0: SL_ORBIT_BUDGET_MS */
    int points;                      /* 0: SL_ORBIT_POINTS */
    const char *hq_settings;         /* NULL: SL_ORBIT_HQ_SETTINGS; "" = the orbit's own settings */
    bool progress;                   /* progress lines on stderr */
    bool pass_times;                 /* time every pass of every timed frame (glFinish around each on
                                      * llvmpipe: the frames are slower by what that costs) */
    const char *image_prefix;        /* non-NULL: PREFIX-motion-K.png, -still-K.png, -truth-K.png
                                      * (f_k, the still, h_k of point K) */
} sl_orbit_options;

#define SL_ORBIT_MAX_PASSES 64

typedef struct sl_orbit_passes {
    int count;                       /* passes seen in any frame, in the order first seen */
    char *name[SL_ORBIT_MAX_PASSES];
    double *ms;                      /* frames x SL_ORBIT_MAX_PASSES, NAN where the pass did not run */
    double *outside_ms;              /* per frame: the frame's time less its passes' (set-up, waits) */
} sl_orbit_passes;

typedef struct sl_orbit_result {
    char *scene;
    int width, height;
    char *backend, *renderer;
    double seconds, degrees, budget_ms;
    int frames;                      /* timed frames */
    double *frame_ms;                /* their times in the order rendered (pooled rounds: one after another) */
    int rounds;                      /* orbits pooled into this result (sl_orbit_pool) */
    double p50_ms, p95_ms, p99_ms, mean_ms, max_ms;
    double *cpu_ms;                  /* CPU time of every thread of the process per frame, same order */
    double cpu_p50_ms, cpu_mean_ms;  /* what a frame costs, whatever else the machine runs */
    double over_budget;              /* fraction of frames slower than budget_ms */
    int points;                      /* frame pairs compared */
    int still_frames;                /* frames of the orbit's settings' still (TAA's history) */
    double motion_flip, motion_rmse; /* means over the points */
    double still_flip, still_rmse;
    double flicker, flicker_max;     /* mean and largest over the points */
    char *hq_settings;
    sl_orbit_passes passes;          /* with pass_times only (count 0 otherwise) */
} sl_orbit_result;

/* Runs the orbit. False with err when the scene, a plugin or GL fails. */
bool sl_orbit_run(const sl_orbit_options *opt, sl_orbit_result *res, char *err, size_t n);
void sl_orbit_result_free(sl_orbit_result *res);
/* Pools another orbit of the same scene and settings into `into` (empty: takes `r` over): frame
 * times appended and their statistics recomputed over all, errors averaged over every frame pair
 * of both, seconds and degrees added. `r` is left empty (freed). False when out of memory. */
bool sl_orbit_pool(sl_orbit_result *into, sl_orbit_result *r);
/* Median ms of pass k over the frames it ran in (*runs of them); NAN when it never ran. k = -1:
 * the time outside the passes. */
double sl_orbit_pass_median(const sl_orbit_result *r, int k, int *runs);
/* The q-quantile (0..1) of v (n values) by linear interpolation between order statistics
 * (sorted v[(n-1)q]); NaN when n == 0. v is sorted in place. */
double sl_orbit_quantile(double *v, int n, double q);
/* The flicker of one pair (see above): frames f0, f1 and the truths h0, h1, RGBA w*h. */
double sl_orbit_flicker(const float *f0, const float *f1, const float *h0, const float *h1, int w, int h);

#ifdef __cplusplus
}
#endif
#endif
