/* shadelab-bench --orbit (see orbit.h). */
#include "orbit.h"
#include "bench/metrics.h"
#include <shadelab/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* CPU seconds of every thread of this process (llvmpipe's rasteriser threads included). */
static double cpu_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

double sl_orbit_quantile(double *v, int n, double q) {
    if (n <= 0) return NAN;
    qsort(v, n, sizeof *v, cmp_double);
    double pos = (n - 1) * q;
    int i = (int)floor(pos);
    if (i >= n - 1) return v[n - 1];
    return v[i] + (pos - i) * (v[i + 1] - v[i]);
}

double sl_orbit_flicker(const float *f0, const float *f1, const float *h0, const float *h1, int w, int h) {
    double sum = 0;
    size_t n = (size_t)w * h;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            size_t k = 4 * i + c;
            double d = ((double)sl_srgb_encode(f1[k]) - sl_srgb_encode(h1[k])) -
                       ((double)sl_srgb_encode(f0[k]) - sl_srgb_encode(h0[k]));
            sum += d * d;
        }
    return n ? sqrt(sum / (3.0 * n)) : NAN;
}

/* The scene with the options' settings, then `extra` ("a=1 b=2", split in `buf`), GL started. */
static bool open_app(const sl_orbit_options *o, const char *extra, char *buf, size_t bufn, sl_app *app, bool *inited,
                     char *err, size_t n) {
    sl_app_options opt = {0};
    opt.scene_path = o->scene_path;
    opt.data_dir = o->data_dir;
    opt.backend = o->backend ? o->backend : SL_BACKEND_OSMESA;
    opt.width = o->width > 0 ? o->width : 320;
    opt.height = o->height > 0 ? o->height : 180;
    opt.keep_color = true; /* the comparisons read the linear "color" */
    opt.accumulate = 1;
    opt.timings = o->pass_times;
    for (int i = 0; i < o->setting_count && opt.setting_count < 128; i++) opt.settings[opt.setting_count++] = o->settings[i];
    snprintf(buf, bufn, "%s", extra ? extra : "");
    char *save = NULL;
    for (char *t = strtok_r(buf, " \t", &save); t; t = strtok_r(NULL, " \t", &save)) {
        if (opt.setting_count == 128) { snprintf(err, n, "more than 128 assignments"); return false; }
        opt.settings[opt.setting_count++] = t;
    }
    *inited = true;
    return sl_app_init(app, &opt, err, n) && sl_app_start_gl(app, err, n);
}

/* The complete still at camera `cam` (the first frame after the move, then the frames the still
 * needs), read into rgba. With a frame-time budget the still's frames are at the best settings,
 * as the window's once it is still (the window waits a few frames first; the image is the same). */
static bool render_still(sl_app *app, const sl_camera_state *cam, float *rgba) {
    unsigned long long version = app->camera.version;
    app->camera = *cam;
    app->camera.version = version + 1;
    app->time = 0;
    for (int f = 0;; f++) {
        if (!sl_app_render_frame(app)) return false;
        if (f == 0) sl_tool_budget_settle(app);
        if (f >= sl_tool_still_frames(app)) break;
    }
    return sl_app_read_color(app, rgba);
}

/* Column of pass `name` in pp (added when new), or -1 when the table is full. */
static int pass_column(sl_orbit_passes *pp, const char *name) {
    for (int k = 0; k < pp->count; k++)
        if (!strcmp(pp->name[k], name)) return k;
    if (pp->count == SL_ORBIT_MAX_PASSES) return -1;
    pp->name[pp->count] = strdup(name);
    return pp->name[pp->count] ? pp->count++ : -1;
}

/* Row `frame` of pp: the last frame's pass times and what lies outside them. */
static bool record_passes(sl_app *app, sl_orbit_passes *pp, int frame, double frame_ms) {
    double *ms = realloc(pp->ms, sizeof *ms * (size_t)(frame + 1) * SL_ORBIT_MAX_PASSES);
    if (ms) pp->ms = ms;
    double *out = ms ? realloc(pp->outside_ms, sizeof *out * (size_t)(frame + 1)) : NULL;
    if (!out) return false;
    pp->outside_ms = out;
    sl_tool_frame_times t;
    sl_tool_frame_times_of(app, &t);
    double *row = pp->ms + (size_t)frame * SL_ORBIT_MAX_PASSES, sum = 0;
    for (int k = 0; k < SL_ORBIT_MAX_PASSES; k++) row[k] = NAN;
    for (int i = 0; i < t.pass_count; i++) {
        int k = t.passes[i].ran ? pass_column(pp, t.passes[i].name) : -1;
        if (k >= 0) row[k] = t.passes[i].ms, sum += t.passes[i].ms;
    }
    pp->outside_ms[frame] = frame_ms - sum;
    return true;
}

/* Two consecutive motion frames, their cameras, and the orbit settings' still at the second. */
typedef struct orbit_pair { sl_camera_state cam[2]; float *frame[2], *still; } orbit_pair;

/* The timed orbit: wall and CPU times of each frame into ms[] and cpu[], the pairs captured at
 * their moments. */
static bool timed_orbit(const sl_orbit_options *o, sl_app *app, double speed, orbit_pair *pairs, int points,
                        double **ms, double **cpu, int *frames, sl_orbit_passes *pp) {
    const size_t px = (size_t)app->backend.width * app->backend.height * 4;
    const sl_camera_state start = app->camera;
    int cap = 256, next = 0, taking = -1;
    *ms = malloc(sizeof **ms * cap);
    *cpu = malloc(sizeof **cpu * cap);
    if (!*ms || !*cpu) return false;
    *frames = 0;
    app->time = 0;
    /* warm-up: two frames at rest, two moving (programs compiled, uploads done, TAA's motion
     * variant too), two at rest again */
    for (int f = 0; f < 6; f++) {
        if (f == 2 || f == 3) sl_camera_orbit(&app->camera, f == 2 ? 0.01f : -0.01f, 0); /* there and back */
        if (!sl_app_render_frame(app)) return false;
    }
    glFinish();
    double t0 = now_s();
    /* past the end, go on until every pair is taken: a stalled frame (a busy machine) may
     * skip moments, and the comparison needs them all */
    for (double t = 0; t < o->seconds || taking >= 0 || next < points; t = now_s() - t0) {
        unsigned long long version = app->camera.version;
        app->camera = start;
        app->camera.version = version;
        sl_camera_orbit(&app->camera, (float)(speed * t), 0); /* bumps the version */
        double f0 = now_s(), c0 = cpu_s();
        if (!sl_app_render_frame(app)) return false;
        glFinish();
        double frame_ms = (now_s() - f0) * 1e3, frame_cpu_ms = (cpu_s() - c0) * 1e3;
        if (o->pass_times && !record_passes(app, pp, *frames, frame_ms)) return false;
        if (*frames == cap) {
            cap *= 2;
            double *grown = realloc(*ms, sizeof **ms * cap);
            if (grown) *ms = grown;
            double *grown_cpu = grown ? realloc(*cpu, sizeof **cpu * cap) : NULL;
            if (!grown_cpu) return false;
            *cpu = grown_cpu;
        }
        (*cpu)[*frames] = frame_cpu_ms;
        (*ms)[(*frames)++] = frame_ms;
        /* a pair starts at the first frame past its moment, (k + 1/2)/points of the orbit */
        int slot = taking >= 0 ? 1 : 0;
        if (taking < 0 && next < points && t >= (next + 0.5) * o->seconds / points) taking = next++;
        if (taking < 0) continue;
        orbit_pair *p = &pairs[taking];
        p->cam[slot] = app->camera;
        p->frame[slot] = malloc(sizeof(float) * px);
        if (!p->frame[slot] || !sl_app_read_color(app, p->frame[slot])) return false;
        if (slot == 1) taking = -1;
    }
    return true;
}

/* FLIP and RMSE of a against the truth h, added to the sums. */
static void compare(const float *a, const float *h, int w, int hh, double *flip, double *rmse) {
    sl_bench_error e;
    sl_metric_all(a, h, w, hh, &e);
    *flip += e.flip;
    *rmse += e.rmse;
}

/* Frame-time statistics of res->frame_ms (sorted on a copy). */
static bool summarise_times(sl_orbit_result *res) {
    int over = 0;
    double *ms = malloc(sizeof *ms * (res->frames ? res->frames : 1));
    if (!ms) return false;
    memcpy(ms, res->frame_ms, sizeof *ms * res->frames);
    res->mean_ms = 0;
    for (int i = 0; i < res->frames; i++) res->mean_ms += ms[i] / res->frames, over += ms[i] > res->budget_ms;
    res->over_budget = res->frames ? (double)over / res->frames : NAN;
    res->p50_ms = sl_orbit_quantile(ms, res->frames, 0.5);
    res->p95_ms = sl_orbit_quantile(ms, res->frames, 0.95);
    res->p99_ms = sl_orbit_quantile(ms, res->frames, 0.99);
    res->max_ms = res->frames ? ms[res->frames - 1] : NAN;
    res->cpu_mean_ms = 0;
    for (int i = 0; i < res->frames; i++) ms[i] = res->cpu_ms[i], res->cpu_mean_ms += ms[i] / res->frames;
    res->cpu_p50_ms = sl_orbit_quantile(ms, res->frames, 0.5);
    free(ms);
    return true;
}

/* --images: one image of point k (linear, written display-encoded) */
static void save_image(const char *prefix, const char *what, int k, const float *px, int w, int h) {
    char path[4200], err[1024];
    snprintf(path, sizeof path, "%s-%s-%d.png", prefix, what, k);
    if (!sl_image_write(path, px, w, h, false, err, sizeof err)) SL_WARN("%s", err);
}

/* Each captured pair against the truth (its two cameras' highest-quality stills). */
static bool compare_with_truth(sl_app *truth, const char *image_prefix, orbit_pair *pairs, int points,
                               sl_orbit_result *res) {
    int w = res->width, hh = res->height;
    size_t px = (size_t)w * hh * 4;
    float *h0 = malloc(sizeof(float) * px), *h1 = malloc(sizeof(float) * px);
    bool ok = h0 && h1;
    res->flicker_max = 0;
    for (int k = 0; k < points && ok; k++) {
        orbit_pair *p = &pairs[k];
        if (!p->still) continue; /* the orbit ended before this moment */
        ok = render_still(truth, &p->cam[0], h0) && render_still(truth, &p->cam[1], h1);
        if (!ok) break;
        if (image_prefix) {
            save_image(image_prefix, "motion", k, p->frame[1], w, hh);
            save_image(image_prefix, "still", k, p->still, w, hh);
            save_image(image_prefix, "truth", k, h1, w, hh);
        }
        compare(p->frame[1], h1, w, hh, &res->motion_flip, &res->motion_rmse);
        compare(p->still, h1, w, hh, &res->still_flip, &res->still_rmse);
        double fl = sl_orbit_flicker(p->frame[0], p->frame[1], h0, h1, w, hh);
        res->flicker += fl;
        if (fl > res->flicker_max) res->flicker_max = fl;
        res->points++;
    }
    if (res->points) {
        double c = res->points;
        res->motion_flip /= c, res->motion_rmse /= c, res->still_flip /= c, res->still_rmse /= c, res->flicker /= c;
    }
    free(h0);
    free(h1);
    return ok;
}

/* The timed orbit with the orbit's settings, then (untimed) their converged still at the second
 * camera of each captured pair. One application: the truth's comes after it is closed. */
static bool orbit_and_stills(const sl_orbit_options *o, double speed, orbit_pair *pairs, int points,
                             sl_orbit_result *res, char *err, size_t n) {
    sl_app app = {0};
    bool inited = false;
    char buf[4096];
    double *ms = NULL, *cpu = NULL;
    bool ok = open_app(o, o->variant, buf, sizeof buf, &app, &inited, err, n);
    if (ok) {
        /* without --budget, the budget the orbit's own settings run under (a variant's
         * core.budget=100 is judged against 100 ms, not the default 66) */
        const sl_param *budget = sl_params_find(&app.params, "core.budget");
        if (!(o->budget_ms > 0) && budget && budget->value.f[0] > 0) res->budget_ms = budget->value.f[0];
        res->width = app.backend.width, res->height = app.backend.height;
        res->backend = strdup(app.backend.name);
        const char *rs = (const char *)glGetString(GL_RENDERER);
        res->renderer = strdup(rs ? rs : "?");
        if (o->progress) fprintf(stderr, "[orbit] %s: %.0f s at %g deg/s, %dx%d\n", res->scene, o->seconds,
                                 speed * 180 / M_PI, res->width, res->height);
        ok = timed_orbit(o, &app, speed, pairs, points, &ms, &cpu, &res->frames, &res->passes);
        if (!ok) snprintf(err, n, "rendering the orbit failed");
    }
    if (ok) res->frame_ms = ms, res->cpu_ms = cpu, ms = cpu = NULL, ok = summarise_times(res);
    size_t px = (size_t)res->width * res->height * 4;
    for (int k = 0; k < points && ok; k++) {
        if (!pairs[k].frame[1]) continue;
        pairs[k].still = malloc(sizeof(float) * px);
        ok = pairs[k].still && render_still(&app, &pairs[k].cam[1], pairs[k].still);
        if (!ok) snprintf(err, n, "rendering a still failed");
    }
    if (ok) res->still_frames = sl_tool_still_frames(&app);
    free(ms);
    free(cpu);
    if (inited) sl_app_shutdown(&app);
    return ok;
}

bool sl_orbit_run(const sl_orbit_options *o, sl_orbit_result *res, char *err, size_t n) {
    memset(res, 0, sizeof *res);
    if (!(o->seconds > 0)) { snprintf(err, n, "--orbit needs a positive number of seconds"); return false; }
    double dps = o->degrees_per_second > 0 ? o->degrees_per_second : SL_ORBIT_DEGREES_PER_SECOND;
    int points = o->points > 0 ? o->points : SL_ORBIT_POINTS;
    const char *hq = o->hq_settings ? o->hq_settings : SL_ORBIT_HQ_SETTINGS;
    res->scene = strdup(o->scene_path ? o->scene_path : "<built-in default scene>");
    res->hq_settings = strdup(*hq ? hq : "the orbit's own settings");
    res->seconds = o->seconds;
    res->degrees = dps * o->seconds;
    res->budget_ms = o->budget_ms > 0 ? o->budget_ms : SL_ORBIT_BUDGET_MS;
    res->rounds = 1;
    orbit_pair *pairs = calloc(points, sizeof *pairs);
    bool ok = pairs && orbit_and_stills(o, dps * M_PI / 180, pairs, points, res, err, n);
    if (ok) {
        if (o->progress) fprintf(stderr, "[orbit] %d frames; the truth at the captured frames (%s) …\n", res->frames, res->hq_settings);
        sl_app truth = {0};
        bool inited = false;
        char buf[4096], truth_settings[4096];
        /* the truth is a still without the variant's settings and without a frame-time budget:
         * one truth for every variant */
        snprintf(truth_settings, sizeof truth_settings, "%s core.budget=0", hq);
        ok = open_app(o, truth_settings, buf, sizeof buf, &truth, &inited, err, n);
        if (ok && !(ok = compare_with_truth(&truth, o->image_prefix, pairs, points, res))) snprintf(err, n, "rendering the truth failed");
        if (inited) sl_app_shutdown(&truth);
    }
    for (int k = 0; pairs && k < points; k++) free(pairs[k].frame[0]), free(pairs[k].frame[1]), free(pairs[k].still);
    free(pairs);
    return ok;
}

/* The mean of a (over na pairs) and b (over nb), over all. */
static double pooled(double a, int na, double b, int nb) { return na + nb ? (a * na + b * nb) / (na + nb) : 0; }

/* r's rows after into's `na` rows, its passes matched by name. */
static bool pool_passes(sl_orbit_passes *into, int na, const sl_orbit_passes *r, int nb) {
    double *ms = realloc(into->ms, sizeof *ms * (size_t)(na + nb) * SL_ORBIT_MAX_PASSES);
    double *out = ms ? realloc(into->outside_ms, sizeof *out * (size_t)(na + nb)) : NULL;
    if (ms) into->ms = ms;
    if (!ms || !out) return false;
    into->outside_ms = out;
    for (int f = 0; f < nb; f++) {
        double *row = ms + (size_t)(na + f) * SL_ORBIT_MAX_PASSES;
        for (int k = 0; k < SL_ORBIT_MAX_PASSES; k++) row[k] = NAN;
        for (int k = 0; k < r->count; k++) {
            int c = pass_column(into, r->name[k]);
            if (c >= 0) row[c] = r->ms[(size_t)f * SL_ORBIT_MAX_PASSES + k];
        }
        out[na + f] = r->outside_ms[f];
    }
    return true;
}

double sl_orbit_pass_median(const sl_orbit_result *r, int k, int *runs) {
    double *v = malloc(sizeof *v * (r->frames ? r->frames : 1));
    int n = 0;
    for (int f = 0; v && f < r->frames; f++) {
        double x = k < 0 ? r->passes.outside_ms[f] : r->passes.ms[(size_t)f * SL_ORBIT_MAX_PASSES + k];
        if (x == x) v[n++] = x;
    }
    double m = n ? sl_orbit_quantile(v, n, 0.5) : NAN;
    free(v);
    if (runs) *runs = n;
    return m;
}

bool sl_orbit_pool(sl_orbit_result *into, sl_orbit_result *r) {
    if (!into->rounds) {
        *into = *r;
        memset(r, 0, sizeof *r);
        return true;
    }
    double *ms = realloc(into->frame_ms, sizeof *ms * (into->frames + r->frames + 1));
    if (!ms) return false;
    memcpy(ms + into->frames, r->frame_ms, sizeof *ms * r->frames);
    into->frame_ms = ms;
    double *cpu = realloc(into->cpu_ms, sizeof *cpu * (into->frames + r->frames + 1));
    if (!cpu) return false;
    memcpy(cpu + into->frames, r->cpu_ms, sizeof *cpu * r->frames);
    into->cpu_ms = cpu;
    if (r->passes.count && !pool_passes(&into->passes, into->frames, &r->passes, r->frames)) return false;
    into->frames += r->frames;
    int a = into->points, b = r->points;
    into->motion_flip = pooled(into->motion_flip, a, r->motion_flip, b);
    into->motion_rmse = pooled(into->motion_rmse, a, r->motion_rmse, b);
    into->still_flip = pooled(into->still_flip, a, r->still_flip, b);
    into->still_rmse = pooled(into->still_rmse, a, r->still_rmse, b);
    into->flicker = pooled(into->flicker, a, r->flicker, b);
    into->flicker_max = fmax(into->flicker_max, r->flicker_max);
    into->points += b, into->rounds += r->rounds;
    into->seconds += r->seconds, into->degrees += r->degrees;
    sl_orbit_result_free(r);
    return summarise_times(into);
}

void sl_orbit_result_free(sl_orbit_result *res) {
    for (int k = 0; k < res->passes.count; k++) free(res->passes.name[k]);
    free(res->passes.ms);
    free(res->passes.outside_ms);
    free(res->frame_ms);
    free(res->cpu_ms);
    free(res->scene);
    free(res->backend);
    free(res->renderer);
    free(res->hq_settings);
    memset(res, 0, sizeof *res);
}
