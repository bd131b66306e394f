/* shadelab-bench: error versus time for a plugin's quality knobs (docs/benchmarks.md). */
#include "bench.h"
#include "orbit.h"
#include <cjson/cJSON.h>
#include <math.h>
#include <sys/stat.h>
#include <shadelab/input.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *usage =
    "usage: shadelab-bench --plugin NAME [options]\n"
    "Sweeps NAME's quality knobs (\"core\" for the core's) on a scene, times each setting over\n"
    "the frames and measures its error against NAME's declared reference; writes CSV, JSON and\n"
    "an error-versus-milliseconds chart (PNG, gnuplot) with the Pareto front marked.\n"
    "  --scene FILE              JSON scene (default: the built-in scene)\n"
    "  --plugin NAME             plugin whose knobs are swept and whose reference is the truth\n"
    "  --load NAME               load another plugin too (repeatable)\n"
    "  --settings \"A=1 B=2\"      a setting to measure (repeatable); default: the knobs' values\n"
    "  --vary ID=V1,V2,...       the values to sweep for one knob (repeatable)\n"
    "  --grid | --one-at-a-time  all combinations of the knobs / one knob at a time\n"
    "                            (default: all combinations when there are at most 64)\n"
    "  --set ID=VALUE            applied to every render, the reference too (repeatable)\n"
    "  --size WxH                image size (default 320x180)\n"
    "  --backend osmesa|egl      headless backend (default osmesa: llvmpipe, glFinish timing)\n"
    "  --frames N                timed frames per setting (default 30)\n"
    "  --warmup N                frames rendered before timing (default 5)\n"
    "  --rounds R                time every setting R times, frames/R each, in turn (default 1;\n"
    "                            evens out bursts of load on a shared machine)\n"
    "  --reference cycles        the reference is Blender's Cycles (shadelab-xcheck, docs/xcheck.md):\n"
    "                            every render is compared before tone mapping; needs --scene\n"
    "  --cycles-samples N        Cycles samples per pixel for --reference cycles (default 256)\n"
    "  --unoccluded              with --reference cycles: objects seen by camera rays only in the\n"
    "                            reference (no occlusion, shadows or interreflection; docs/xcheck.md)\n"
    "  --eevee N,...|none        with --reference cycles: EEVEE at these sample counts, measured\n"
    "                            against the same reference, a peer point on the chart (default 1,16)\n"
    "  --reference-settings S    override the declared reference settings\n"
    "  --reference-accumulate N  override the declared reference accumulation (CI: small)\n"
    "  --reference-scale K       render the reference at K times the size, box-filtered down\n"
    "                            (K^2 more samples per pixel; resolution-independent methods)\n"
    "  --cache DIR               reference cache (default $SHADELAB_CACHE, $XDG_CACHE_HOME/shadelab\n"
    "                            or ~/.cache/shadelab); runs are also saved to DIR/fronts for\n"
    "                            shadelab --auto-quality\n"
    "  --no-cache                always render the reference; store nothing\n"
    "  --out PREFIX              PREFIX.csv, PREFIX.json, PREFIX.png (default bench-PLUGIN-SCENE)\n"
    "  --metric M                rmse | relmse | dssim | psnr | flip | noise: the chart's and the\n"
    "                            front's metric (repeatable: the first is primary, each other gets\n"
    "                            PREFIX-M.png; default: rmse, and flip in PREFIX-flip.png)\n"
    "  --noise-samples N         the still whose frames' spread is the noise (default 16; 0: not\n"
    "                            measured)\n"
    "  --noise-limit X           noise above X makes a setting noisy: on no front, never chosen by\n"
    "                            --auto-quality (default 0.002, half an 8-bit step)\n"
    "  --images                  also write PREFIX-<setting>.png and PREFIX-reference.png; with --orbit,\n"
    "                            PREFIX-S-V-motion-K.png, -still-K.png, -truth-K.png (scene S, variant V,\n"
    "                            point K, first round)\n"
    "  --no-chart                no PNG chart\n"
    "  --list                    print the settings that would be measured, then exit\n"
    "  --orbit SECONDS           instead of a sweep: a slow orbit of the camera driven by the wall\n"
    "                            clock, as a user's drag; frame-time p50/p95/p99, the fraction over\n"
    "                            --budget, FLIP/RMSE of motion frames and of the still against the\n"
    "                            highest-quality still, flicker; the built-in scene and, when its\n"
    "                            data is found, scenes/head.json (or each --scene); PREFIX.json\n"
    "  --budget MS               frame-time budget of --orbit's \"over\" (default: the orbit's own\n"
    "                            core.budget where it is on, else 66)\n"
    "  --orbit-speed DEG         degrees per second (default 10)\n"
    "  --orbit-points N          frame pairs compared with the truth (default 4)\n"
    "  --orbit-hq \"A=1 B=2\"      the highest-quality still (default \"core.ssaa=4\": 4x4 supersampled,\n"
    "                            with the scene's TAA still)\n"
    "  --orbit-variant \"A=1 B=2\" settings of one orbit on top of --set (repeatable: each scene is\n"
    "                            orbited once per variant, in turn; \"\" for none)\n"
    "  --orbit-passes            time every pass of every orbit frame (glFinish around each on\n"
    "                            llvmpipe, which slows the frames): per-pass medians in the output\n"
    "  --orbit-rounds R          R orbits per scene and variant, interleaved (variant 1, 2, ..., 1,\n"
    "                            2, ...); one result each, frame times and errors pooled (default 1)\n"
    "  --data DIR                asset directory (also SHADELAB_DATA)\n"
    "  --float                   RGBA32F colour targets\n"
    "  -q, --quiet | -v, --verbose | --help\n";

static int die(const char *msg) {
    fprintf(stderr, "shadelab-bench: %s\n", msg);
    return 1;
}

#define MAXN 256

/* "--orbit 20": a number in [lo, hi], or an error naming the option. */
static bool parse_number(const char *opt, const char *v, double lo, double hi, double *out, char *err, size_t n) {
    char *end = NULL;
    *out = v ? strtod(v, &end) : NAN;
    if (!v || *end || !(*out >= lo && *out <= hi)) {
        snprintf(err, n, "%s %s: expected a number in [%g, %g]", opt, v ? v : "(nothing)", lo, hi);
        return false;
    }
    return true;
}

static void print_orbit(const sl_orbit_result *r) {
    printf("orbit of %s, %dx%d, %s (%s): %.0f s, %.0f degrees, %d frames\n", r->scene, r->width, r->height, r->backend,
           r->renderer, r->seconds, r->degrees, r->frames);
    printf("  frame ms: p50 %.1f  p95 %.1f  p99 %.1f  mean %.1f  max %.1f; over the %.0f ms budget: %.1f %%\n", r->p50_ms,
           r->p95_ms, r->p99_ms, r->mean_ms, r->max_ms, r->budget_ms, 100 * r->over_budget);
    printf("  CPU ms per frame (every thread of the process): p50 %.1f  mean %.1f\n", r->cpu_p50_ms, r->cpu_mean_ms);
    printf("  against the highest-quality still (%s), mean of %d frame pairs:\n", r->hq_settings, r->points);
    printf("    motion frames:          FLIP %.4f  RMSE %.4g\n", r->motion_flip, r->motion_rmse);
    printf("    converged still (%2d f): FLIP %.4f  RMSE %.4g\n", r->still_frames, r->still_flip, r->still_rmse);
    printf("    flicker (RMS, sRGB):    mean %.4f  largest %.4f\n", r->flicker, r->flicker_max);
    if (!r->passes.count) return;
    printf("  per pass, median ms over the frames it ran in (frames):");
    for (int k = -1; k < r->passes.count; k++) {
        int runs;
        double m = sl_orbit_pass_median(r, k, &runs);
        printf("%s %s %.1f (%d)", k < 0 ? "" : ",", k < 0 ? "outside the passes" : r->passes.name[k], m, runs);
    }
    printf("\n");
}

static cJSON *orbit_json(const sl_orbit_result *r) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "scene", r->scene);
    cJSON_AddNumberToObject(o, "width", r->width);
    cJSON_AddNumberToObject(o, "height", r->height);
    cJSON_AddStringToObject(o, "backend", r->backend ? r->backend : "");
    cJSON_AddStringToObject(o, "renderer", r->renderer ? r->renderer : "");
    cJSON_AddNumberToObject(o, "seconds", r->seconds);
    cJSON_AddNumberToObject(o, "degrees", r->degrees);
    cJSON_AddNumberToObject(o, "frames", r->frames);
    cJSON_AddNumberToObject(o, "budget_ms", r->budget_ms);
    const char *keys[] = {"p50_ms", "p95_ms", "p99_ms", "mean_ms", "max_ms", "over_budget", "cpu_p50_ms", "cpu_mean_ms",
                          "motion_flip", "motion_rmse", "still_flip", "still_rmse", "flicker", "flicker_max"};
    const double vals[] = {r->p50_ms, r->p95_ms, r->p99_ms, r->mean_ms, r->max_ms, r->over_budget, r->cpu_p50_ms,
                           r->cpu_mean_ms, r->motion_flip, r->motion_rmse, r->still_flip, r->still_rmse, r->flicker,
                           r->flicker_max};
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
        cJSON_AddItemToObject(o, keys[i], isfinite(vals[i]) ? cJSON_CreateNumber(vals[i]) : cJSON_CreateNull());
    cJSON_AddNumberToObject(o, "points", r->points);
    cJSON_AddNumberToObject(o, "still_frames", r->still_frames);
    cJSON_AddStringToObject(o, "hq_settings", r->hq_settings);
    if (r->passes.count) {
        cJSON *passes = cJSON_AddObjectToObject(o, "pass_median_ms"), *runs = cJSON_AddObjectToObject(o, "pass_runs");
        for (int k = -1; k < r->passes.count; k++) {
            int n;
            double m = sl_orbit_pass_median(r, k, &n);
            const char *name = k < 0 ? "(outside the passes)" : r->passes.name[k];
            cJSON_AddItemToObject(passes, name, isfinite(m) ? cJSON_CreateNumber(m) : cJSON_CreateNull());
            cJSON_AddNumberToObject(runs, name, n);
        }
    }
    return o;
}

/* The data directory holding head/ (--data, SHADELAB_DATA, else ../shared/assets), or NULL. */
static const char *head_data(const char *data_dir) {
    const char *dirs[] = {data_dir, getenv("SHADELAB_DATA"), "../shared/assets"};
    for (int i = 0; i < 3; i++) {
        char path[4200];
        struct stat st;
        if (!dirs[i] || !*dirs[i]) continue;
        snprintf(path, sizeof path, "%s/head/LeePerrySmith.glb", dirs[i]);
        if (!stat(path, &st)) return dirs[i];
        if (i < 2) break; /* a directory the user named: no guessing past it */
    }
    return NULL;
}

#define MAX_VARIANTS 16

/* One orbit of `oo` with the variant's settings ("a=1 b=2") after oo's own (not the truth's). */
static bool orbit_variant(const sl_orbit_options *oo, const char *variant, sl_orbit_result *r, char *err, size_t n) {
    sl_orbit_options o = *oo;
    o.variant = variant;
    return sl_orbit_run(&o, r, err, n);
}

/* --orbit: the given scene, or the built-in one and the head when its data is there; each
 * variant in turn, `rounds` times. */
static int run_orbits(sl_orbit_options *oo, const char *const *variants, int variant_count, int rounds,
                      const char *prefix, bool images_wanted, char *err, size_t n) {
    const char *scenes[2] = {oo->scene_path, NULL};
    const char *data[2] = {oo->data_dir, NULL};
    int count = 1;
    struct stat st;
    if (!oo->scene_path) {
        const char *hd = head_data(oo->data_dir);
        if (hd && !stat("scenes/head.json", &st)) scenes[count] = "scenes/head.json", data[count++] = hd;
        else fprintf(stderr, "shadelab-bench: note: the head scene is left out (scenes/head.json and its data "
                             "head/LeePerrySmith.glb under --data, SHADELAB_DATA or ../shared/assets not found)\n");
    }
    cJSON *root = cJSON_CreateObject(), *runs = cJSON_AddArrayToObject(root, "orbits");
    cJSON_AddStringToObject(root, "format", "shadelab-orbit/1");
    int rc = 0;
    static const char *const none[] = {""};
    if (!variant_count) variants = none, variant_count = 1;
    sl_orbit_result pooled[2][MAX_VARIANTS];
    memset(pooled, 0, sizeof pooled);
    for (int round = 0; round < rounds && !rc; round++)
        for (int i = 0; i < count && !rc; i++)
            for (int v = 0; v < variant_count && !rc; v++) {
                oo->scene_path = scenes[i];
                oo->data_dir = data[i];
                sl_orbit_result r;
                char images[4200];
                snprintf(images, sizeof images, "%s-%d-%d", prefix, i, v); /* scene i, variant v */
                oo->image_prefix = images_wanted && round == 0 ? images : NULL;
                if (oo->progress && (rounds > 1 || variant_count > 1))
                    fprintf(stderr, "[orbit] round %d of %d, variant \"%s\"\n", round + 1, rounds, variants[v]);
                if (!orbit_variant(oo, variants[v], &r, err, n)) rc = die(err);
                else if (!sl_orbit_pool(&pooled[i][v], &r)) rc = die("out of memory");
                sl_orbit_result_free(&r);
            }
    for (int i = 0; i < count; i++)
        for (int v = 0; v < variant_count; v++) {
            sl_orbit_result *r = &pooled[i][v];
            if (!rc) {
                if (*variants[v]) printf("variant \"%s\", %d round(s):\n", variants[v], r->rounds);
                print_orbit(r);
                cJSON *o = orbit_json(r);
                cJSON_AddStringToObject(o, "variant", variants[v]);
                cJSON_AddNumberToObject(o, "rounds", r->rounds);
                cJSON_AddItemToArray(runs, o);
            }
            sl_orbit_result_free(r);
        }
    char path[4200], *text = cJSON_Print(root);
    snprintf(path, sizeof path, "%s.json", prefix);
    FILE *f = fopen(path, "w");
    if (!f || fputs(text, f) < 0) rc = die("cannot write the orbit's JSON");
    else fprintf(stderr, "wrote %s\n", path);
    if (f) fclose(f);
    free(text);
    cJSON_Delete(root);
    return rc;
}

int main(int argc, char **argv) {
    sl_bench_options o = {.warmup = 5, .frames = 30, .progress = true, .backend = SL_BACKEND_OSMESA};
    const char *plugins[64], *base[128], *settings[MAXN], *vary[64];
    int np = 0, nb = 0, ns = 0, nv = 0;
    const char *out = NULL;
    sl_metric metrics[SL_METRIC_COUNT];
    int nm = 0;
    bool chart = true, list = false, images = false;
    sl_orbit_options oo = {.progress = true};
    const char *variants[MAX_VARIANTS];
    int variant_count = 0, orbit_rounds = 1;
    char err[8192];
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
#define NEXT() (i + 1 < argc ? argv[++i] : (snprintf(err, sizeof err, "%s needs a value", a), (char *)NULL))
#define NEED(v) do { if (!(v)) return die(err); } while (0)
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) { fputs(usage, stdout); return 0; }
        else if (!strcmp(a, "--scene")) NEED(o.scene_path = NEXT());
        else if (!strcmp(a, "--plugin")) NEED(o.plugin = NEXT());
        else if (!strcmp(a, "--load")) { if (np == 64) return die("too many --load"); NEED(plugins[np++] = NEXT()); }
        else if (!strcmp(a, "--settings")) { if (ns == MAXN) return die("too many --settings"); NEED(settings[ns++] = NEXT()); }
        else if (!strcmp(a, "--vary")) { if (nv == 64) return die("too many --vary"); NEED(vary[nv++] = NEXT()); }
        else if (!strcmp(a, "--grid")) o.sweep = SL_SWEEP_GRID;
        else if (!strcmp(a, "--one-at-a-time")) o.sweep = SL_SWEEP_ONE_AT_A_TIME;
        else if (!strcmp(a, "--set")) { if (nb == 128) return die("too many --set"); NEED(base[nb++] = NEXT()); }
        else if (!strcmp(a, "--size")) {
            const char *v = NEXT();
            NEED(v);
            if (!sl_parse_size(v, 16384, &o.width, &o.height)) {
                snprintf(err, sizeof err, "--size %s: expected WxH, 1..16384 each", v);
                return die(err);
            }
        } else if (!strcmp(a, "--backend")) {
            const char *v = NEXT();
            NEED(v);
            if (!strcmp(v, "osmesa")) o.backend = SL_BACKEND_OSMESA;
            else if (!strcmp(v, "egl")) o.backend = SL_BACKEND_EGL;
            else { snprintf(err, sizeof err, "--backend %s: expected osmesa or egl (headless)", v); return die(err); }
        } else if (!strcmp(a, "--frames") || !strcmp(a, "--warmup") || !strcmp(a, "--reference-accumulate") ||
                   !strcmp(a, "--reference-scale") || !strcmp(a, "--rounds") || !strcmp(a, "--noise-samples")) {
            const char *v = NEXT();
            NEED(v);
            long x;
            bool frames = !strcmp(a, "--frames"), warm = !strcmp(a, "--warmup"), noise = !strcmp(a, "--noise-samples");
            long lo = warm || noise ? 0 : 1, hi = noise ? 4096 : 1000000;
            if (!sl_parse_long(v, lo, hi, &x)) {
                snprintf(err, sizeof err, "%s %s: expected a whole number %ld..%ld", a, v, lo, hi);
                return die(err);
            }
            if (frames) o.frames = (int)x;
            else if (noise) o.noise_samples = x ? (int)x : -1;
            else if (warm) o.warmup = (int)x;
            else if (!strcmp(a, "--reference-scale")) o.reference_scale = (int)x;
            else if (!strcmp(a, "--rounds")) o.rounds = (int)x;
            else o.reference_accumulate = (int)x;
        } else if (!strcmp(a, "--noise-limit")) {
            const char *v = NEXT();
            NEED(v);
            char *end;
            o.noise_limit = strtod(v, &end);
            if (*end || !(o.noise_limit > 0 && o.noise_limit <= 1)) {
                snprintf(err, sizeof err, "--noise-limit %s: expected a number in (0, 1]", v);
                return die(err);
            }
        } else if (!strcmp(a, "--reference-settings")) NEED(o.reference_settings = NEXT());
        else if (!strcmp(a, "--reference")) {
            const char *v = NEXT();
            NEED(v);
            if (strcmp(v, "cycles")) {
                snprintf(err, sizeof err, "--reference %s: the one other reference is \"cycles\"", v);
                return die(err);
            }
            o.reference_cycles = true;
        } else if (!strcmp(a, "--cycles-samples")) {
            const char *v = NEXT();
            NEED(v);
            char *end;
            long x = strtol(v, &end, 10);
            if (*end || x < 1 || x > 1 << 20) {
                snprintf(err, sizeof err, "--cycles-samples %s: expected an integer in [1, %d]", v, 1 << 20);
                return die(err);
            }
            o.cycles_samples = (int)x;
        }
        else if (!strcmp(a, "--unoccluded")) o.unoccluded = true;
        else if (!strcmp(a, "--eevee")) NEED(o.eevee = NEXT());
        else if (!strcmp(a, "--cache")) NEED(o.cache_dir = NEXT());
        else if (!strcmp(a, "--no-cache")) o.no_cache = true;
        else if (!strcmp(a, "--out")) NEED(out = NEXT());
        else if (!strcmp(a, "--metric")) {
            const char *v = NEXT();
            NEED(v);
            if (nm == SL_METRIC_COUNT || !sl_metric_parse(v, &metrics[nm])) {
                snprintf(err, sizeof err, "--metric %s: expected rmse, relmse, dssim, psnr, flip or noise (each once)", v);
                return die(err);
            }
            nm++;
        } else if (!strcmp(a, "--orbit")) {
            if (!parse_number(a, NEXT(), 0.1, 3600, &oo.seconds, err, sizeof err)) return die(err);
        } else if (!strcmp(a, "--budget")) {
            if (!parse_number(a, NEXT(), 0.1, 1e6, &oo.budget_ms, err, sizeof err)) return die(err);
        } else if (!strcmp(a, "--orbit-speed")) {
            if (!parse_number(a, NEXT(), 0.01, 360, &oo.degrees_per_second, err, sizeof err)) return die(err);
        } else if (!strcmp(a, "--orbit-points")) {
            double v;
            if (!parse_number(a, NEXT(), 1, 64, &v, err, sizeof err)) return die(err);
            oo.points = (int)v;
        } else if (!strcmp(a, "--orbit-hq")) NEED(oo.hq_settings = NEXT());
        else if (!strcmp(a, "--orbit-variant")) {
            if (variant_count == MAX_VARIANTS) return die("at most 16 --orbit-variant");
            NEED(variants[variant_count++] = NEXT());
        } else if (!strcmp(a, "--orbit-rounds")) {
            double v;
            if (!parse_number(a, NEXT(), 1, 100, &v, err, sizeof err)) return die(err);
            orbit_rounds = (int)v;
        }
        else if (!strcmp(a, "--orbit-passes")) oo.pass_times = true;
        else if (!strcmp(a, "--images")) images = true;
        else if (!strcmp(a, "--no-chart")) chart = false;
        else if (!strcmp(a, "--list")) list = true;
        else if (!strcmp(a, "--data")) NEED(o.data_dir = NEXT());
        else if (!strcmp(a, "--float")) o.float32 = true;
        else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) { o.progress = false; sl_log_threshold = SL_LOG_WARN; }
        else if (!strcmp(a, "-v") || !strcmp(a, "--verbose")) sl_log_threshold = SL_LOG_DEBUG;
        else { snprintf(err, sizeof err, "unknown option %s (see --help)", a); return die(err); }
#undef NEXT
#undef NEED
    }
    if (oo.seconds > 0) {
        oo.scene_path = o.scene_path, oo.data_dir = o.data_dir, oo.width = o.width, oo.height = o.height;
        oo.backend = o.backend, oo.settings = base, oo.setting_count = nb, oo.progress = o.progress;
        return run_orbits(&oo, variants, variant_count, orbit_rounds, out ? out : "bench-orbit", images, err, sizeof err);
    }
    if (!o.plugin) return die("--plugin NAME is required (\"core\" for the core's own knobs); see --help");
    if (o.reference_scale > 1) { /* every size derived from a user number is checked before use */
        long w = o.width > 0 ? o.width : 320, h = o.height > 0 ? o.height : 180, k = o.reference_scale;
        long kmax = 16384 / (w > h ? w : h);
        while (kmax > 1 && (double)(w * kmax) * (h * kmax) > SL_IMAGE_MAX_PIXELS) kmax--;
        if (k > kmax) {
            snprintf(err, sizeof err, "--reference-scale %ld: the reference would be %ldx%ld; at most 16384 per side and "
                     "%ld Mpixel, so at most %ld for --size %ldx%ld", k, w * k, h * k, (long)(SL_IMAGE_MAX_PIXELS >> 20),
                     kmax < 1 ? 1 : kmax, w, h);
            return die(err);
        }
    }
    o.plugins = plugins; o.plugin_count = np;
    o.base_settings = base; o.base_setting_count = nb;
    o.settings = settings; o.setting_count = ns;
    o.vary = vary; o.vary_count = nv;
    if (!nm) metrics[nm++] = SL_METRIC_RMSE, metrics[nm++] = SL_METRIC_FLIP;
    if (ns && nv) return die("--vary chooses values for enumerated knobs; it cannot be combined with --settings");
    if (o.eevee && !o.reference_cycles) return die("--eevee needs --reference cycles (EEVEE is measured against Cycles)");
    if (o.unoccluded && !o.reference_cycles) return die("--unoccluded needs --reference cycles (it is a kind of Cycles reference)");
    if (o.frames < 30)
        fprintf(stderr, "shadelab-bench: note: %d timed frames (fewer than 30): the medians are indicative only\n", o.frames);

    if (list) {
        char **s = NULL;
        int count = 0;
        if (!sl_bench_enumerate(&o, &s, &count, err, sizeof err)) return die(err);
        for (int i = 0; i < count; i++) { printf("%s\n", s[i]); free(s[i]); }
        free(s);
        return 0;
    }
    char prefix[4096];
    if (out) snprintf(prefix, sizeof prefix, "%s", out);
    else {
        const char *stem = o.scene_path ? strrchr(o.scene_path, '/') : NULL;
        stem = o.scene_path ? (stem ? stem + 1 : o.scene_path) : "default";
        snprintf(prefix, sizeof prefix, "bench-%s-%.*s", o.plugin, (int)strcspn(stem, "."), stem);
    }
    /* the output folder must exist before minutes of rendering, not after */
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", prefix);
    char *slash = strrchr(dir, '/');
    if (slash && slash != dir) {
        *slash = 0;
        if (!sl_bench_mkdirs(dir, err, sizeof err)) return die(err);
    }
    if (images) o.image_prefix = prefix;

    sl_bench_result res;
    if (!sl_bench_run(&o, &res, err, sizeof err)) {
        sl_bench_result_free(&res);
        return die(err);
    }
    int rc = 0;
    char path[4200];
    snprintf(path, sizeof path, "%s.csv", prefix);
    if (!sl_bench_write_csv(&res, path, metrics[0], err, sizeof err)) rc = die(err);
    else fprintf(stderr, "wrote %s\n", path);
    snprintf(path, sizeof path, "%s.json", prefix);
    if (!sl_bench_write_json(&res, path, metrics[0], err, sizeof err)) rc = die(err);
    else fprintf(stderr, "wrote %s\n", path);
    if (!o.no_cache) { /* a copy for shadelab --auto-quality */
        char cache[4000], fronts[4100], copy[4400];
        snprintf(fronts, sizeof fronts, "%s/fronts", o.cache_dir ? o.cache_dir : sl_bench_default_cache_dir(cache, sizeof cache));
        const char *stem = o.scene_path ? strrchr(o.scene_path, '/') : NULL;
        stem = o.scene_path ? (stem ? stem + 1 : o.scene_path) : "default";
        snprintf(copy, sizeof copy, "%s/%s--%.*s--%dx%d.json", fronts, o.plugin, (int)strcspn(stem, "."), stem, res.width, res.height);
        if (!sl_bench_mkdirs(fronts, err, sizeof err) || !sl_bench_write_json(&res, copy, metrics[0], err, sizeof err))
            fprintf(stderr, "shadelab-bench: warning: %s\n", err);
        else fprintf(stderr, "saved %s (for shadelab --auto-quality)\n", copy);
    }
    for (int m = 0; chart && m < nm; m++) {
        if (m == 0) snprintf(path, sizeof path, "%s.png", prefix);
        else snprintf(path, sizeof path, "%s-%s.png", prefix, sl_metric_name(metrics[m]));
        int w = sl_bench_write_chart(&res, path, metrics[m], err, sizeof err);
        if (w == 1) fprintf(stderr, "wrote %s\n", path);
        else if (w == 0) { fprintf(stderr, "shadelab-bench: %s\n", err); break; }
        else rc = die(err);
    }
    /* the table, for the terminal */
    printf("%s on %s, %dx%d, %s (%s), %s timing, median of %d frames (%d round%s, %d warm-up frames each)\n", res.plugin,
           res.scene, res.width, res.height, res.backend, res.renderer, res.timing_mode ? res.timing_mode : "?", res.frames,
           res.rounds, res.rounds > 1 ? "s" : "", res.warmup);
    printf("reference: %s (%d frame%s, %dx size box-filtered)%s\n", res.reference.settings, res.reference.accumulate,
           res.reference.accumulate > 1 ? "s accumulated" : "", res.reference.scale,
           res.reference.from_cache ? ", from the cache" : "");
    printf("  %-28s %10s %10s %10s %8s %8s %8s %8s %s\n", "setting", "frame ms", "rmse", "relmse", "psnr", "ssim", "flip",
           "noise", "front");
    int failed = 0;
    for (int i = 0; i < res.row_count; i++) {
        sl_bench_row *r = &res.rows[i];
        if (!r->ok) { printf("  %-28s FAILED: %s\n", r->label, r->failure ? r->failure : ""); failed++; continue; }
        printf("  %-28s %10.3f %10.4g %10.4g %8.2f %8.5f %8.4f %8.4g %s\n", r->label, r->frame_ms_median, r->error.rmse,
               r->error.relmse, r->error.psnr, r->error.ssim, r->error.flip, r->error.noise,
               r->noisy ? "noisy" : r->front[metrics[0]] ? "*" : "");
    }
    printf("total %.1f s\n", res.total_s);
    sl_bench_result_free(&res);
    if (failed) rc = 1;
    return rc;
}
