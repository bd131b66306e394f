/* shadelab-bench as a library: sweep a plugin's quality knobs on a scene, time each setting
 * with the core's honest per-pass timing, measure its error against the plugin's declared
 * reference (cached on disk), and write CSV, JSON and an error-versus-milliseconds chart with
 * the Pareto front marked. tools/bench/main.c is the command line over this; the tests call
 * it directly. Documentation: docs/benchmarks.md. */
#ifndef SL_BENCH_H
#define SL_BENCH_H
#include "toolkit.h"
#include "bench/metrics.h"
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sl_bench_sweep {
    SL_SWEEP_AUTO = 0,     /* every combination when there are at most 64, else one knob at a time */
    SL_SWEEP_GRID,         /* every combination of the knobs' values */
    SL_SWEEP_ONE_AT_A_TIME /* each knob through its values, the others at their current values */
} sl_bench_sweep;

typedef struct sl_bench_options {
    const char *scene_path;          /* NULL: the built-in default scene */
    const char *plugin;              /* whose knobs and reference: "core" or a plugin name */
    const char *const *plugins; int plugin_count;          /* more plugins to load */
    const char *const *base_settings; int base_setting_count; /* "id=value" for every render */
    /* Settings to measure, each "id=value id=value"; none: enumerate the plugin's knobs. */
    const char *const *settings; int setting_count;
    /* "id=v1,v2,…": the values to sweep for a knob instead of the enumerated ones. */
    const char *const *vary; int vary_count;
    sl_bench_sweep sweep;
    int width, height;               /* default 320x180 */
    sl_backend_kind backend;         /* default OSMesa */
    int frames, warmup;              /* timed frames (default 30) after warm-up (default 5) */
    int rounds;                      /* > 1: time the settings in turn, frames/rounds each time */
    const char *reference_settings;  /* NULL: the plugin's declared reference settings */
    /* true: the reference is Blender's Cycles, rendered through shadelab-xcheck (beside this
     * executable) at cycles_samples (0: 256) samples per pixel, and every render is compared
     * before tone mapping (tonemap is switched off) */
    bool reference_cycles;
    int cycles_samples;
    /* with reference_cycles: objects are seen by camera rays only in the reference (no
     * occlusion, shadows or interreflection: shadelab-xcheck --unoccluded, docs/xcheck.md) */
    bool unoccluded;
    /* with reference_cycles: EEVEE's sample counts ("1,16"; NULL: "1,16"; "none": no EEVEE),
     * rendered by shadelab-xcheck and measured against the same reference as peers */
    const char *eevee;
    int reference_accumulate;        /* 0: the declared accumulation (or 1) */
    /* > 1: render the reference at scale× the size and box-filter it down (scale² more samples
     * per pixel; for methods whose result does not depend on the pixel size). */
    int reference_scale;
    const char *cache_dir;           /* NULL: sl_bench_default_cache_dir() */
    bool no_cache;                   /* always render the reference (and do not store it) */
    const char *data_dir;
    bool float32;                    /* RGBA32F colour target for every render */
    bool progress;                   /* progress lines on stderr */
    const char *image_prefix;        /* non-NULL: write PREFIX-<label>.png per setting + reference */
    int noise_samples;               /* the noise measure's still (metrics.h): 0 = SL_NOISE_SAMPLES,
                                        < 0: not measured (noise NaN) */
    double noise_limit;              /* settings noisier are "noisy": 0 = SL_NOISE_VISIBLE */
} sl_bench_options;

typedef struct sl_bench_pass {
    char *name, *owner;
    double median_ms, mean_ms, min_ms;
    int runs;                        /* timed frames in which the pass ran (skipped passes: fewer) */
} sl_bench_pass;

typedef struct sl_bench_row {
    char *settings;                  /* "core.ssaa=2" (as given or enumerated) */
    char *label;                     /* the same without the plugin prefix: "ssaa=2" */
    bool ok;
    char *failure;                   /* why not ok */
    int frames;
    double frame_ms_median, frame_ms_mean, frame_ms_min; /* CPU wall time of the whole frame */
    double passes_ms;                /* sum of the per-pass medians */
    sl_bench_pass *passes; int pass_count;
    sl_bench_error error;
    bool noisy;                      /* error.noise > the run's noise_limit: on no front */
    bool front[SL_METRIC_COUNT];     /* on the Pareto front of (frame_ms_median, metric) */
    double wall_s;                   /* time spent measuring this setting */
} sl_bench_row;

/* Another renderer measured against the same reference (EEVEE with --reference cycles): a
 * point of its own on the chart, in no Pareto front. */
typedef struct sl_bench_peer {
    char *label;                     /* "EEVEE 16 spp" */
    double ms;                       /* its time per render */
    sl_bench_error error;
} sl_bench_peer;

typedef struct sl_bench_result {
    char *scene;                     /* path as given, or "<built-in default scene>" */
    char scene_hash[17];             /* hex FNV-1a of the scene file's contents */
    char *plugin;
    char *plugins_loaded;            /* "core 0.1.0, ggx 0.1.0" */
    int width, height;
    char *backend, *renderer, *timing_mode;
    bool gpu;
    int frames, warmup, rounds;
    int noise_samples;               /* 0: noise not measured */
    double noise_limit;
    struct {
        char *settings, *description;
        int accumulate;
        int scale;                   /* rendered at scale× the size, box-filtered down */
        char key[17];                /* cache key (hex) */
        char *cache_path;            /* NULL when not cached */
        bool from_cache;
        double render_s;             /* time to render it (0 when it came from the cache) */
        float *pixels;               /* linear RGBA, width*height*4 */
    } reference;
    sl_bench_row *rows; int row_count;
    sl_bench_peer *peers; int peer_count;
    double total_s;
    char created[32];                /* ISO 8601 UTC */
} sl_bench_result;

/* The settings the sweep would measure (each "id=value …"), from the plugin's knobs. */
bool sl_bench_enumerate(const sl_bench_options *opt, char ***settings, int *count, char *err, size_t n);
/* Runs the whole benchmark. False with err on a fatal problem (scene, plugin, reference); a
 * setting that fails is a row with ok = false. */
bool sl_bench_run(const sl_bench_options *opt, sl_bench_result *res, char *err, size_t n);
void sl_bench_result_free(sl_bench_result *res);
/* Recomputes rows[].noisy and rows[].front from the measured values (sl_bench_run does it):
 * noisy rows are on no front. */
void sl_bench_mark_fronts(sl_bench_result *res);

bool sl_bench_write_csv(const sl_bench_result *res, const char *path, sl_metric primary, char *err, size_t n);
bool sl_bench_write_json(const sl_bench_result *res, const char *path, sl_metric primary, char *err, size_t n);
/* Draws error (metric) versus median frame ms with the Pareto front, through gnuplot.
 * Returns 1 when written, 0 when gnuplot is missing (err says so), -1 on failure. */
int sl_bench_write_chart(const sl_bench_result *res, const char *png_path, sl_metric metric, char *err, size_t n);

/* sl_bench_default_cache_dir() and sl_bench_scene_hash(): autoquality.h (metrics.h includes it). */
/* "a=1 b=2" → the label without "<plugin>." prefixes. Caller frees. */
char *sl_bench_label(const char *settings, const char *plugin);
/* mkdir -p. */
bool sl_bench_mkdirs(const char *dir, char *err, size_t n);

#ifdef __cplusplus
}
#endif
#endif
