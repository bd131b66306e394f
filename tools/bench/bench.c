/* shadelab-bench engine (see bench.h and docs/benchmarks.md).
 *
 * Every setting gets a fresh application (scene, plugins, GL context): nothing a previous
 * setting changed can leak into the next one, and the first frames (shader compilation,
 * uploads) are excluded as warm-up. Timed frames advance the clock as the viewer does, so
 * passes that skip unchanged work skip here too; the image that is compared with the reference
 * is rendered afterwards at time 0, as the reference is. */
#define _XOPEN_SOURCE 700 /* nftw */
#include "bench.h"
#include <shadelab/gl.h>
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <ftw.h>
#include <time.h>
#include <unistd.h>

#define CACHE_FORMAT "shadelab-bench-reference/1"

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static char *xstrdup(const char *s) { return s ? strdup(s) : NULL; }

/* ------------------------------------------------------------------ files and hashes -- */

bool sl_bench_mkdirs(const char *dir, char *err, size_t n) {
    char path[4096];
    snprintf(path, sizeof path, "%s", dir);
    for (char *p = path + 1; ; p++) {
        if (*p == '/' || !*p) {
            char c = *p;
            *p = 0;
            if (mkdir(path, 0755) && errno != EEXIST) {
                snprintf(err, n, "cannot create directory %s: %s", path, strerror(errno));
                return false;
            }
            *p = c;
            if (!c) break;
        }
    }
    return true;
}

/* sl_bench_default_cache_dir and sl_bench_scene_hash: core/quality (autoquality.h), which the
 * viewer's --auto-quality shares. */

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* Hash of a directory's files (names and contents, sorted, following links, 3 levels): a
 * plugin's .so and GLSL, the core's shader library. A changed shader changes the key. */
static uint64_t hash_dir(const char *dir, uint64_t h, int depth) {
    DIR *d = opendir(dir);
    if (!d) return sl_tool_hash64(dir, strlen(dir), h);
    char **names = NULL;
    int count = 0;
    for (struct dirent *e; (e = readdir(d));) {
        size_t len = strlen(e->d_name);
        /* a plugin's build directory also holds CMake's files: not part of what it renders */
        if (e->d_name[0] == '.' || !strcmp(e->d_name, "CMakeFiles") || !strcmp(e->d_name, "Makefile") ||
            (len > 6 && !strcmp(e->d_name + len - 6, ".cmake")))
            continue;
        names = realloc(names, sizeof *names * (count + 1));
        names[count++] = strdup(e->d_name);
    }
    closedir(d);
    qsort(names, count, sizeof *names, cmp_str);
    for (int i = 0; i < count; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        struct stat st;
        if (!stat(path, &st)) {
            if (S_ISDIR(st.st_mode) && depth < 3) {
                h = sl_tool_hash64(names[i], strlen(names[i]), h);
                h = hash_dir(path, h, depth + 1);
            } else if (S_ISREG(st.st_mode) && st.st_size < (64 << 20)) {
                size_t len;
                char *text = sl_read_file(path, &len, NULL, 0);
                h = sl_tool_hash64(names[i], strlen(names[i]) + 1, h);
                if (text) h = sl_tool_hash64(text, len, h);
                free(text);
            }
        }
        free(names[i]);
    }
    free(names);
    return h;
}

/* --------------------------------------------------------------------- settings ------- */

typedef struct tokens { char *buf; const char *items[128]; int count; } tokens;

/* Splits "a=1 b=2" on white space (values cannot contain spaces). */
static bool split_settings(const char *text, tokens *t, char *err, size_t n) {
    t->buf = strdup(text ? text : "");
    t->count = 0;
    char *save = NULL;
    for (char *tok = strtok_r(t->buf, " \t\n", &save); tok; tok = strtok_r(NULL, " \t\n", &save)) {
        if (t->count == 128) { snprintf(err, n, "too many assignments in \"%s\"", text); return false; }
        if (!strchr(tok, '=')) { snprintf(err, n, "\"%s\" in \"%s\": expected id=value", tok, text); return false; }
        t->items[t->count++] = tok;
    }
    return true;
}

char *sl_bench_label(const char *settings, const char *plugin) {
    size_t plen = plugin ? strlen(plugin) : 0;
    char *out = calloc(1, strlen(settings) + 1);
    const char *p = settings;
    size_t u = 0;
    while (*p) {
        while (*p == ' ' || *p == '\t') p++;
        if (!*p) break;
        if (u) out[u++] = ' ';
        if (plen && !strncmp(p, plugin, plen) && p[plen] == '.') p += plen + 1;
        while (*p && *p != ' ' && *p != '\t') out[u++] = *p++;
    }
    out[u] = 0;
    return out;
}

/* ----------------------------------------------------------------------- the app -------- */

typedef struct bench_app {
    sl_app app;
    tokens base, extra;
    bool inited, started;
} bench_app;

static void close_app(bench_app *b) {
    if (b->inited) sl_app_shutdown(&b->app);
    free(b->base.buf);
    free(b->extra.buf);
    memset(b, 0, sizeof *b);
}

/* Scene + plugins + base settings + `settings`; GL started when `gl`. */
static bool open_app(const sl_bench_options *o, const char *settings, int accumulate, int scale, bool gl, bench_app *b,
                     char *err, size_t n) {
    memset(b, 0, sizeof *b);
    sl_app_options opt = {0};
    opt.scene_path = o->scene_path;
    opt.data_dir = o->data_dir;
    opt.backend = o->backend ? o->backend : SL_BACKEND_OSMESA;
    opt.width = (o->width > 0 ? o->width : 320) * scale;
    opt.height = (o->height > 0 ? o->height : 180) * scale;
    opt.float32 = o->float32;
    opt.accumulate = accumulate > 1 ? accumulate : 1;
    opt.strict = true; /* measure exactly the plugins asked for, or stop */
    opt.timings = true;    /* per-pass times are the point */
    opt.keep_color = true; /* the error metrics read the linear "color" */
    if (o->plugin && strcmp(o->plugin, "core")) opt.plugins[opt.plugin_count++] = o->plugin;
    for (int i = 0; i < o->plugin_count && opt.plugin_count < 64; i++) opt.plugins[opt.plugin_count++] = o->plugins[i];
    char *base_text = NULL;
    size_t blen = 0;
    for (int i = 0; i < o->base_setting_count; i++) blen += strlen(o->base_settings[i]) + 1;
    base_text = calloc(1, blen + 1);
    for (int i = 0; i < o->base_setting_count; i++) { strcat(base_text, o->base_settings[i]); strcat(base_text, " "); }
    bool ok = split_settings(base_text, &b->base, err, n) && split_settings(settings, &b->extra, err, n);
    free(base_text);
    if (!ok) return false;
    if (b->base.count + b->extra.count > 128) { snprintf(err, n, "more than 128 assignments"); return false; }
    for (int i = 0; i < b->base.count; i++) opt.settings[opt.setting_count++] = b->base.items[i];
    for (int i = 0; i < b->extra.count; i++) opt.settings[opt.setting_count++] = b->extra.items[i];
    b->inited = true;
    if (!sl_app_init(&b->app, &opt, err, n)) return false;
    int idx = o->plugin ? sl_plugins_find(&b->app.plugins, o->plugin) : 0;
    if (idx < 0 || !b->app.plugins.items[idx]->ok) {
        snprintf(err, n, "plugin %s is not loaded%s", o->plugin,
                 idx >= 0 && b->app.plugins.items[idx]->disabled_reason ? b->app.plugins.items[idx]->disabled_reason : "");
        return false;
    }
    /* against Cycles every render is compared before tone mapping, as shadelab-xcheck does */
    if (o->reference_cycles && sl_plugins_find(&b->app.plugins, "tonemap") >= 0 &&
        !sl_app_set(&b->app, "tonemap.enabled=false", SL_SRC_CLI, err, n))
        return false;
    if (gl) {
        if (!sl_app_start_gl(&b->app, err, n)) return false;
        b->started = true;
    }
    return true;
}

static sl_plugin_rec *plugin_rec(sl_app *app, const char *plugin) {
    int idx = plugin ? sl_plugins_find(&app->plugins, plugin) : 0;
    return idx >= 0 ? app->plugins.items[idx] : NULL;
}

/* ------------------------------------------------------------------- enumeration ------ */

typedef struct knob { const sl_param *p; char **values; int count; } knob;

static void knob_add(knob *k, const char *v) {
    for (int i = 0; i < k->count; i++)
        if (!strcmp(k->values[i], v)) return;
    k->values = realloc(k->values, sizeof *k->values * (k->count + 1));
    k->values[k->count++] = strdup(v);
}

static void knob_values(knob *k, const char *vary) {
    const sl_param *p = k->p;
    const sl_param_desc *d = &p->desc;
    char buf[64];
    if (vary) {
        char *copy = strdup(vary), *save = NULL;
        for (char *t = strtok_r(copy, ",", &save); t; t = strtok_r(NULL, ",", &save)) knob_add(k, t);
        free(copy);
        return;
    }
    bool bounded = d->max > d->min;
    switch (d->type) {
    case SL_PARAM_BOOL: knob_add(k, "false"); knob_add(k, "true"); break;
    case SL_PARAM_ENUM:
        for (const char *const *e = d->enum_values; e && *e; e++) knob_add(k, *e);
        break;
    case SL_PARAM_INT: {
        if (!bounded) { /* around the default: ×1/4 … ×4 */
            int v0 = d->default_value.i ? d->default_value.i : 1;
            int f[] = {-4, -2, 1, 2, 4};
            for (int i = 0; i < 5; i++) {
                int v = f[i] < 0 ? v0 / -f[i] : v0 * f[i];
                snprintf(buf, sizeof buf, "%d", v);
                knob_add(k, buf);
            }
            break;
        }
        int lo = (int)d->min, hi = (int)d->max, step = d->step >= 1 ? (int)d->step : 1;
        if ((hi - lo) / step + 1 <= 12) {
            for (int v = lo; v <= hi; v += step) { snprintf(buf, sizeof buf, "%d", v); knob_add(k, buf); }
        } else if (lo >= 1) { /* sizes and counts: powers of two */
            snprintf(buf, sizeof buf, "%d", lo);
            knob_add(k, buf);
            for (long v = 1; v <= hi; v *= 2)
                if (v > lo) { snprintf(buf, sizeof buf, "%ld", v); knob_add(k, buf); }
            snprintf(buf, sizeof buf, "%d", hi);
            knob_add(k, buf);
        } else {
            for (int i = 0; i < 9; i++) {
                int v = lo + (int)lround((double)(hi - lo) * i / 8.0);
                v = lo + (v - lo) / step * step;
                snprintf(buf, sizeof buf, "%d", v);
                knob_add(k, buf);
            }
        }
        break;
    }
    case SL_PARAM_FLOAT:
        if (bounded) {
            for (int i = 0; i < 5; i++) { snprintf(buf, sizeof buf, "%g", d->min + (d->max - d->min) * i / 4.0); knob_add(k, buf); }
        } else {
            double v0 = d->default_value.f[0] != 0 ? d->default_value.f[0] : 1.0;
            double f[] = {0.25, 0.5, 1, 2, 4};
            for (int i = 0; i < 5; i++) { snprintf(buf, sizeof buf, "%g", v0 * f[i]); knob_add(k, buf); }
        }
        break;
    default: break; /* colours, vectors, textures are not sweepable */
    }
}

static void push(char ***list, int *count, char *s) {
    *list = realloc(*list, sizeof **list * (*count + 1));
    (*list)[(*count)++] = s;
}

bool sl_bench_enumerate(const sl_bench_options *o, char ***out, int *out_count, char *err, size_t n) {
    *out = NULL;
    *out_count = 0;
    if (o->setting_count > 0) {
        for (int i = 0; i < o->setting_count; i++) push(out, out_count, strdup(o->settings[i]));
        return true;
    }
    bench_app b;
    if (!open_app(o, "", 1, 1, false, &b, err, n)) { close_app(&b); return false; }
    sl_params *ps = &b.app.params;
    knob knobs[32];
    int nk = 0;
    for (int i = 0; i < ps->count && nk < 32; i++) {
        const sl_param *p = &ps->items[i];
        if (p->desc.scope != SL_SCOPE_GLOBAL || !(p->desc.flags & SL_PARAM_QUALITY_KNOB) || strcmp(p->owner, o->plugin)) continue;
        knobs[nk] = (knob){.p = p};
        knob *k = &knobs[nk];
        const char *vary = NULL;
        size_t idlen = strlen(p->full_id);
        for (int v = 0; v < o->vary_count; v++)
            if (!strncmp(o->vary[v], p->full_id, idlen) && o->vary[v][idlen] == '=') vary = o->vary[v] + idlen + 1;
        knob_values(k, vary);
        if (k->count) nk++;
        else free(k->values);
    }
    /* every --vary must name a knob of this plugin */
    for (int v = 0; v < o->vary_count; v++) {
        bool found = false;
        for (int i = 0; i < nk; i++) {
            size_t l = strlen(knobs[i].p->full_id);
            found |= !strncmp(o->vary[v], knobs[i].p->full_id, l) && o->vary[v][l] == '=';
        }
        if (!found) {
            snprintf(err, n, "--vary %s: not a quality knob of %s (see shadelab --plugin %s --dump-params)", o->vary[v],
                     o->plugin, o->plugin);
            for (int i = 0; i < nk; i++) { for (int k = 0; k < knobs[i].count; k++) free(knobs[i].values[k]); free(knobs[i].values); }
            close_app(&b);
            return false;
        }
    }
    bool ok = true;
    if (!nk) {
        snprintf(err, n, "plugin %s declares no quality knobs (parameters flagged SL_PARAM_QUALITY_KNOB); "
                 "give the settings to compare with --settings \"id=value …\"", o->plugin);
        ok = false;
    } else {
        long product = 1;
        for (int i = 0; i < nk && product <= 100000; i++) product *= knobs[i].count;
        bool grid = o->sweep == SL_SWEEP_GRID || (o->sweep == SL_SWEEP_AUTO && product <= 64);
        if (grid && product > 4096) {
            snprintf(err, n, "a grid over %d knobs would be %ld settings; use --one-at-a-time or --vary", nk, product);
            ok = false;
        } else if (grid) {
            int idx[32] = {0};
            for (long c = 0; c < product; c++) {
                char buf[4096] = "";
                size_t u = 0;
                for (int i = 0; i < nk; i++)
                    u += snprintf(buf + u, sizeof buf - u, "%s%s=%s", i ? " " : "", knobs[i].p->full_id, knobs[i].values[idx[i]]);
                push(out, out_count, strdup(buf));
                for (int i = nk - 1; i >= 0; i--) { /* last knob fastest */
                    if (++idx[i] < knobs[i].count) break;
                    idx[i] = 0;
                }
            }
        } else {
            for (int i = 0; i < nk; i++)
                for (int v = 0; v < knobs[i].count; v++) {
                    char buf[512];
                    snprintf(buf, sizeof buf, "%s=%s", knobs[i].p->full_id, knobs[i].values[v]);
                    push(out, out_count, strdup(buf));
                }
        }
    }
    for (int i = 0; i < nk; i++) { for (int k = 0; k < knobs[i].count; k++) free(knobs[i].values[k]); free(knobs[i].values); }
    close_app(&b);
    return ok;
}

/* -------------------------------------------------------------------- timing ---------- */

typedef struct series { const char *name, *owner; double *ms; int n; } series;

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static void summarise(const double *v, int n, double *med, double *mean, double *mn);
static double median_of(const double *v, int n) {
    double med, mean, mn;
    summarise(v, n, &med, &mean, &mn);
    return med;
}

static void summarise(const double *v, int n, double *med, double *mean, double *mn) {
    if (n <= 0) { *med = *mean = *mn = NAN; return; }
    double *c = malloc(sizeof *c * n);
    memcpy(c, v, sizeof *c * n);
    qsort(c, n, sizeof *c, cmp_double);
    *med = n % 2 ? c[n / 2] : 0.5 * (c[n / 2 - 1] + c[n / 2]);
    *mn = c[0];
    double s = 0;
    for (int i = 0; i < n; i++) s += c[i];
    *mean = s / n;
    free(c);
}

/* Raw timings of one setting, pooled over rounds. */
typedef struct samples { series s[64]; int ns; double *frame; int nframe; } samples;

static void samples_free(samples *sm) {
    for (int k = 0; k < sm->ns; k++) { free((char *)sm->s[k].name); free((char *)sm->s[k].owner); free(sm->s[k].ms); }
    free(sm->frame);
    memset(sm, 0, sizeof *sm);
}

/* Renders warm-up + timed frames, appending their times; then, when image is not NULL,
 * renders the frame at time 0 whose colour is compared with the reference. */
static bool time_setting(sl_app *app, int warmup, int frames, samples *sm, float *image) {
    bool ok = true;
    sm->frame = realloc(sm->frame, sizeof *sm->frame * (sm->nframe + frames + 1));
    for (int f = 0; f < warmup + frames && ok; f++) {
        app->time = f * app->opt.fixed_dt;
        ok = sl_app_render_frame(app);
        if (!ok || f < warmup) continue;
        sl_tool_frame_times times, *st = &times;
        sl_tool_frame_times_of(app, st);
        sm->frame[sm->nframe++] = st->frame_ms;
        for (int i = 0; i < st->pass_count; i++) {
            if (!st->passes[i].ran) continue;
            series *e = NULL;
            for (int k = 0; k < sm->ns; k++)
                if (!strcmp(sm->s[k].name, st->passes[i].name)) e = &sm->s[k];
            if (!e && sm->ns < 64) { /* names are copied: a plugin's strings go with its app */
                e = &sm->s[sm->ns++];
                *e = (series){.name = strdup(st->passes[i].name), .owner = strdup(st->passes[i].owner ? st->passes[i].owner : "")};
            }
            if (!e) continue;
            e->ms = realloc(e->ms, sizeof *e->ms * (e->n + 1));
            e->ms[e->n++] = st->passes[i].ms;
        }
    }
    if (ok && image) {
        app->time = 0;
        ok = sl_app_render_frame(app) && sl_app_read_color(app, image);
    }
    return ok;
}

/* The noise measure (metrics.h): sample k of `samples`, each rendered on its own at time 0. */
static bool measure_noise(sl_app *app, int samples, float *image, double *noise) {
    sl_noise_acc acc;
    if (!sl_noise_begin(&acc, app->backend.width, app->backend.height)) return false;
    bool ok = true;
    app->time = 0;
    for (int k = 0; k < samples && ok; k++) {
        ok = sl_tool_render_sample(app, k, samples) && sl_app_read_color(app, image);
        if (ok) sl_noise_add(&acc, image);
    }
    *noise = sl_noise_end(&acc, NULL);
    return ok;
}

static void finish_row(sl_bench_row *row, const samples *sm) {
    row->frames = sm->nframe;
    summarise(sm->frame, sm->nframe, &row->frame_ms_median, &row->frame_ms_mean, &row->frame_ms_min);
    row->passes = calloc(sm->ns + 1, sizeof *row->passes);
    row->passes_ms = 0;
    for (int k = 0; k < sm->ns; k++) {
        sl_bench_pass *p = &row->passes[row->pass_count++];
        p->name = strdup(sm->s[k].name);
        p->owner = strdup(sm->s[k].owner);
        p->runs = sm->s[k].n;
        summarise(sm->s[k].ms, sm->s[k].n, &p->median_ms, &p->mean_ms, &p->min_ms);
        row->passes_ms += p->median_ms;
    }
}

/* ------------------------------------------------------------------ reference cache --- */

typedef struct cache_header { char magic[8]; int32_t width, height; uint64_t key; } cache_header;

static bool cache_load(const char *path, uint64_t key, int w, int h, float *px) {
    FILE *f = fopen(path, "rb");
    if (!f) return false;
    cache_header hd;
    size_t count = (size_t)w * h * 4;
    bool ok = fread(&hd, sizeof hd, 1, f) == 1 && !memcmp(hd.magic, "SLREF01", 8) && hd.width == w && hd.height == h &&
              hd.key == key && fread(px, sizeof(float), count, f) == count;
    fclose(f);
    return ok;
}

static bool cache_store(const char *dir, const char *path, uint64_t key, int w, int h, const float *px,
                        const char *description, char *err, size_t n) {
    if (!sl_bench_mkdirs(dir, err, n)) return false;
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.tmp%d", path, (int)getpid());
    FILE *f = fopen(tmp, "wb");
    if (!f) { snprintf(err, n, "cannot write %s: %s", tmp, strerror(errno)); return false; }
    cache_header hd = {.magic = "SLREF01", .width = w, .height = h, .key = key};
    size_t count = (size_t)w * h * 4;
    bool ok = fwrite(&hd, sizeof hd, 1, f) == 1 && fwrite(px, sizeof(float), count, f) == count;
    ok = (fclose(f) == 0) && ok;
    if (ok && rename(tmp, path)) ok = false;
    if (!ok) { snprintf(err, n, "cannot write %s: %s", path, strerror(errno)); unlink(tmp); return false; }
    /* a readable note beside it: what this reference is */
    char note[4300];
    snprintf(note, sizeof note, "%.*s.txt", (int)(strlen(path) - 4), path);
    FILE *t = fopen(note, "w");
    if (t) { fputs(description, t); fclose(t); }
    return true;
}

/* The key: everything that changes the reference's pixels. */
static uint64_t reference_key(const sl_bench_options *o, sl_app *app, const char *settings, int accumulate,
                              char *desc, size_t dn) {
    uint64_t h = sl_tool_hash64(CACHE_FORMAT, sizeof CACHE_FORMAT, 0);
    h = sl_tool_hash64(SL_VERSION, sizeof SL_VERSION, h);
    /* the running executable: the core is linked in statically, so any change to its C code
     * (texture upload, camera, passes) changes the reference even when SL_VERSION does not */
    static uint64_t exe_hash;
    if (!exe_hash) {
        size_t len = 0;
        char *exe = sl_read_file("/proc/self/exe", &len, NULL, 0);
        exe_hash = exe ? sl_tool_hash64(exe, len, 0) : 1;
        free(exe);
    }
    h = sl_tool_hash64(&exe_hash, sizeof exe_hash, h);
    uint64_t scene = sl_bench_scene_hash(o->scene_path);
    h = sl_tool_hash64(&scene, sizeof scene, h);
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    size_t u = snprintf(desc, dn, "%s\nscene: %s (%016llx)\nrenderer: %s (%s)\nsize: %dx%d%s\naccumulate: %d\nsettings:",
                        CACHE_FORMAT, o->scene_path ? o->scene_path : "<built-in default scene>",
                        (unsigned long long)scene, renderer ? renderer : "?", app->backend.name, app->backend.width,
                        app->backend.height, app->opt.float32 ? " RGBA32F" : "", accumulate);
    h = sl_tool_hash64(renderer ? renderer : "", renderer ? strlen(renderer) + 1 : 1, h);
    h = sl_tool_hash64(app->backend.name, strlen(app->backend.name) + 1, h);
    int dims[3] = {app->backend.width, app->backend.height, accumulate};
    h = sl_tool_hash64(dims, sizeof dims, h);
    h = sl_tool_hash64(&app->opt.float32, sizeof app->opt.float32, h);
    for (int i = 0; i < app->opt.setting_count; i++) {
        h = sl_tool_hash64(app->opt.settings[i], strlen(app->opt.settings[i]) + 1, h);
        if (u < dn) u += snprintf(desc + u, dn - u, " %s", app->opt.settings[i]);
    }
    (void)settings;
    if (u < dn) u += snprintf(desc + u, dn - u, "\nexecutable: %016llx\nplugins:", (unsigned long long)exe_hash);
    for (int i = 0; i < app->plugins.count; i++) {
        sl_plugin_rec *r = app->plugins.items[i];
        if (!r->ok) continue;
        h = sl_tool_hash64(r->id, strlen(r->id) + 1, h);
        if (r->desc.version) h = sl_tool_hash64(r->desc.version, strlen(r->desc.version) + 1, h);
        if (r->resource_dir) h = hash_dir(r->resource_dir, h, 0);
        if (u < dn) u += snprintf(desc + u, dn - u, " %s %s", r->id, r->desc.version ? r->desc.version : "");
    }
    if (u < dn) snprintf(desc + u, dn - u, "\n");
    return h;
}

/* K×K box filter of a (K·w)×(K·h) image down to w×h (--reference-scale). */
static void box_filter(const float *big, int w, int h, int k, float *out) {
    const size_t bw = (size_t)w * k;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 4; c++) {
                double s = 0;
                for (int j = 0; j < k; j++)
                    for (int i = 0; i < k; i++) s += big[((size_t)(y * k + j) * bw + (size_t)x * k + i) * 4 + c];
                out[((size_t)y * w + x) * 4 + c] = (float)(s / (k * k));
            }
}

/* Single-quotes s for /bin/sh into out (n bytes); false when it does not fit. */
static bool shell_quote(const char *s, char *out, size_t n) {
    size_t u = 0;
    if (u + 1 >= n) return false;
    out[u++] = '\'';
    for (; *s; s++) {
        const char *piece = *s == '\'' ? "'\\''" : NULL;
        size_t len = piece ? 4 : 1;
        if (u + len + 2 >= n) return false;
        if (piece) memcpy(out + u, piece, len);
        else out[u] = *s;
        u += len;
    }
    out[u++] = '\'';
    out[u] = 0;
    return true;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw) {
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

/* rm -r dir (its own files only: no symlink is followed). */
static void remove_tree(const char *dir) { nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS); }

/* EEVEE's renders in DIR (eevee.tsv: samples and ms per render; eevee-N.exr) against the
 * reference: res->peers. No eevee.tsv: no EEVEE was asked for. */
static bool eevee_peers(const char *dir, sl_bench_result *res, int w, int h, char *err, size_t n) {
    char path[4300];
    snprintf(path, sizeof path, "%s/eevee.tsv", dir);
    FILE *f = fopen(path, "r");
    if (!f) return true;
    int samples;
    double ms;
    bool ok = true;
    while (ok && res->peer_count < 16 && fscanf(f, "%d %lf", &samples, &ms) == 2) {
        sl_image img = {0};
        snprintf(path, sizeof path, "%s/eevee-%d.exr", dir, samples);
        ok = sl_image_load(&img, path, err, n);
        if (ok && (img.width != w || img.height != h)) {
            snprintf(err, n, "%s: %dx%d, expected %dx%d", path, img.width, img.height, w, h);
            ok = false;
        }
        if (ok) {
            res->peers = realloc(res->peers, sizeof *res->peers * (res->peer_count + 1));
            sl_bench_peer *p = &res->peers[res->peer_count++];
            char label[64];
            snprintf(label, sizeof label, "EEVEE %d spp", samples);
            p->label = strdup(label);
            p->ms = ms;
            sl_metric_all(img.pixels, res->reference.pixels, w, h, &p->error);
            p->error.noise = NAN; /* one render: its noise is not measured */
        }
        sl_image_free(&img);
    }
    fclose(f);
    return ok;
}

/* --reference cycles: shadelab-xcheck (beside this executable) exports the scene with the base
 * settings and renders it with Cycles, cached by its own key; its linear image is the reference. */
static bool cycles_reference(const sl_bench_options *o, sl_bench_result *res, char *err, size_t n) {
    if (!o->scene_path) {
        snprintf(err, n, "--reference cycles needs --scene (the built-in scene is scenes/default.json)");
        return false;
    }
    int w = o->width > 0 ? o->width : 320, h = o->height > 0 ? o->height : 180;
    int samples = o->cycles_samples > 0 ? o->cycles_samples : 256;
    char exe[4096], dir[4200], cmd[32768], q[8300];
    ssize_t k = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (k <= 0) { snprintf(err, n, "cannot find this executable's directory"); return false; }
    exe[k] = 0;
    *strrchr(exe, '/') = 0;
    snprintf(dir, sizeof dir, "%s/shadelab-bench-cycles.XXXXXX", getenv("TMPDIR") && *getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(dir)) { snprintf(err, n, "%s: %s", dir, strerror(errno)); return false; }
    size_t u = 0;
    bool fits = shell_quote(strcat(exe, "/shadelab-xcheck"), q, sizeof q);
    u += snprintf(cmd + u, sizeof cmd - u, "%s --reference-only --size %dx%d --samples %d", q, w, h, samples);
    const char *args[2][2] = {{"--out", dir}, {"--data", o->data_dir}};
    for (int i = 0; i < 2; i++)
        if (args[i][1] && (fits &= shell_quote(args[i][1], q, sizeof q)) && u < sizeof cmd)
            u += snprintf(cmd + u, sizeof cmd - u, " %s %s", args[i][0], q);
    if (o->cache_dir && (fits &= shell_quote(o->cache_dir, q, sizeof q)) && u < sizeof cmd)
        u += snprintf(cmd + u, sizeof cmd - u, " --cache %s", q);
    if (o->no_cache && u < sizeof cmd) u += snprintf(cmd + u, sizeof cmd - u, " --no-cache");
    if (o->unoccluded && u < sizeof cmd) u += snprintf(cmd + u, sizeof cmd - u, " --unoccluded");
    const char *eevee = o->eevee ? o->eevee : "1,16";
    if (strcmp(eevee, "none") && (fits &= shell_quote(eevee, q, sizeof q)) && u < sizeof cmd)
        u += snprintf(cmd + u, sizeof cmd - u, " --eevee %s", q);
    if (o->plugin && strcmp(o->plugin, "core") && (fits &= shell_quote(o->plugin, q, sizeof q)) && u < sizeof cmd)
        u += snprintf(cmd + u, sizeof cmd - u, " --plugin %s", q);
    for (int i = 0; i < o->plugin_count; i++)
        if ((fits &= shell_quote(o->plugins[i], q, sizeof q)) && u < sizeof cmd)
            u += snprintf(cmd + u, sizeof cmd - u, " --plugin %s", q);
    for (int i = 0; i < o->base_setting_count; i++) {
        tokens base;
        if (!split_settings(o->base_settings[i], &base, err, n)) { free(base.buf); return false; }
        for (int j = 0; j < base.count; j++)
            if ((fits &= shell_quote(base.items[j], q, sizeof q)) && u < sizeof cmd)
                u += snprintf(cmd + u, sizeof cmd - u, " --set %s", q);
        free(base.buf);
    }
    if ((fits &= shell_quote(o->scene_path, q, sizeof q)) && u < sizeof cmd) u += snprintf(cmd + u, sizeof cmd - u, " %s", q);
    if (!fits || u >= sizeof cmd - 1) { snprintf(err, n, "--reference cycles: the command line is too long"); return false; }
    if (o->progress)
        fprintf(stderr, "[bench] reference: Cycles, %d samples%s (shadelab-xcheck)\n", samples,
                o->unoccluded ? ", unoccluded" : "");
    double t0 = now_s();
    int status = system(cmd);
    res->reference.render_s = now_s() - t0;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        snprintf(err, n, WIFEXITED(status) && WEXITSTATUS(status) == 77
                             ? "--reference cycles: Blender is not installed (tools/install-deps.sh --with-tests)"
                             : "--reference cycles: shadelab-xcheck failed (exit status %d)",
                 WIFEXITED(status) ? WEXITSTATUS(status) : -1);
        return false;
    }
    char path[4300];
    snprintf(path, sizeof path, "%s/cycles.exr", dir);
    sl_image img = {0};
    if (!sl_image_load(&img, path, err, n)) return false;
    if (img.width != w || img.height != h) {
        snprintf(err, n, "%s: %dx%d, expected %dx%d", path, img.width, img.height, w, h);
        sl_image_free(&img);
        return false;
    }
    if (o->progress) fprintf(stderr, "[bench] reference: Cycles, %.1f s\n", res->reference.render_s);
    res->reference.pixels = img.pixels; /* owned by the result now */
    img.pixels = NULL;
    sl_image_free(&img);
    if (!eevee_peers(dir, res, w, h, err, n)) return false;
    char settings[64];
    snprintf(settings, sizeof settings, "cycles:%d%s", samples, o->unoccluded ? ":unoccluded" : "");
    res->reference.settings = strdup(settings);
    res->reference.description = strdup(o->unoccluded ? "Blender's Cycles through shadelab-xcheck --unoccluded (docs/xcheck.md): objects "
                                                        "seen by camera rays only, before tone mapping"
                                                      : "Blender's Cycles through shadelab-xcheck (docs/xcheck.md), before tone mapping");
    res->reference.accumulate = 1;
    res->reference.scale = 1;
    snprintf(res->reference.key, sizeof res->reference.key, "cycles-%d", samples); /* xcheck caches it */
    remove_tree(dir); /* the export and its render (the reference itself is in xcheck's cache) */
    return true;
}

static bool render_reference(const sl_bench_options *o, sl_bench_result *res, char *err, size_t n) {
    if (o->reference_cycles) return cycles_reference(o, res, err, n);
    /* the declared reference, read from a GL-less app */
    bench_app b;
    if (!open_app(o, "", 1, 1, false, &b, err, n)) { close_app(&b); return false; }
    sl_plugin_rec *r = plugin_rec(&b.app, o->plugin);
    const char *settings = o->reference_settings ? o->reference_settings : r->has_reference ? r->reference.settings : NULL;
    if (!settings) {
        snprintf(err, n, "plugin %s declares no reference (host->set_reference); give one with --reference-settings", o->plugin);
        close_app(&b);
        return false;
    }
    res->reference.settings = strdup(settings);
    res->reference.description = xstrdup(o->reference_settings ? "given on the command line"
                                         : r->reference.description ? r->reference.description : "");
    int acc = o->reference_accumulate > 0 ? o->reference_accumulate
              : r->has_reference && r->reference.accumulate_frames > 1 ? r->reference.accumulate_frames : 1;
    res->reference.accumulate = acc;
    close_app(&b);
    settings = res->reference.settings; /* the app that owned the declared text is gone */

    if (o->progress)
        fprintf(stderr, "[bench] reference: %s, %d frame%s accumulated%s\n", settings, acc, acc > 1 ? "s" : "",
                o->reference_scale > 1 ? ", rendered at a larger size and box-filtered down" : "");
    int scale = o->reference_scale > 1 ? o->reference_scale : 1;
    res->reference.scale = scale;
    if (!open_app(o, settings, acc, scale, true, &b, err, n)) { close_app(&b); return false; }
    int w = b.app.backend.width / scale, h = b.app.backend.height / scale;
    res->reference.pixels = malloc(sizeof(float) * 4 * w * h);
    char desc[8192];
    uint64_t key = reference_key(o, &b.app, settings, acc, desc, sizeof desc);
    snprintf(res->reference.key, sizeof res->reference.key, "%016llx", (unsigned long long)key);
    char dir[4096], path[4200];
    if (!o->no_cache) {
        char base[4000];
        snprintf(dir, sizeof dir, "%s/references", o->cache_dir ? o->cache_dir : sl_bench_default_cache_dir(base, sizeof base));
        snprintf(path, sizeof path, "%s/%s.f32", dir, res->reference.key);
        if (cache_load(path, key, w, h, res->reference.pixels)) {
            res->reference.from_cache = true;
            res->reference.cache_path = strdup(path);
            if (o->progress) fprintf(stderr, "[bench] reference: from the cache %s\n", path);
            close_app(&b);
            return true;
        }
    }
    double t0 = now_s();
    b.app.time = 0;
    float *big = scale > 1 ? malloc(sizeof(float) * 4 * (size_t)w * h * scale * scale) : res->reference.pixels;
    bool ok = big && sl_app_render_frame(&b.app) && sl_app_read_color(&b.app, big);
    if (ok && scale > 1) box_filter(big, w, h, scale, res->reference.pixels);
    if (big != res->reference.pixels) free(big);
    res->reference.render_s = now_s() - t0;
    close_app(&b);
    if (!ok) { snprintf(err, n, "the reference render failed"); return false; }
    long bad = 0;
    for (long i = 0; i < (long)w * h * 4; i++) bad += !isfinite(res->reference.pixels[i]);
    if (bad) SL_WARN("the reference has %ld non-finite values; those pixels are left out of every metric", bad);
    if (o->progress) fprintf(stderr, "[bench] reference: rendered in %.1f s\n", res->reference.render_s);
    if (!o->no_cache) {
        char why[1024];
        if (cache_store(dir, path, key, w, h, res->reference.pixels, desc, why, sizeof why)) res->reference.cache_path = strdup(path);
        else SL_WARN("reference not cached: %s", why);
    }
    return true;
}

/* ----------------------------------------------------------------------- run ---------- */

void sl_bench_mark_fronts(sl_bench_result *res) {
    int n = res->row_count;
    double *cost = malloc(sizeof(double) * (n + 1)), *error = malloc(sizeof(double) * (n + 1));
    bool *front = malloc(sizeof(bool) * (n + 1));
    for (int i = 0; i < n; i++) res->rows[i].noisy = res->rows[i].error.noise > res->noise_limit; /* NaN: not noisy */
    for (int m = 0; m < SL_METRIC_COUNT; m++) {
        for (int i = 0; i < n; i++) {
            bool on = res->rows[i].ok && !res->rows[i].noisy;
            cost[i] = on ? res->rows[i].frame_ms_median : NAN;
            error[i] = on ? sl_metric_value(&res->rows[i].error, (sl_metric)m) : NAN;
        }
        sl_pareto_front(cost, error, n, front);
        for (int i = 0; i < n; i++) res->rows[i].front[m] = front[i];
    }
    free(cost);
    free(error);
    free(front);
}

static void fmt_duration(double s, char *buf, size_t n) {
    if (s < 60) snprintf(buf, n, "%.1f s", s);
    else if (s < 3600) snprintf(buf, n, "%d min %02d s", (int)s / 60, (int)s % 60);
    else snprintf(buf, n, "%d h %02d min", (int)s / 3600, (int)s % 3600 / 60);
}

static void save_image(const sl_bench_options *o, const char *label, const float *px, int w, int h) {
    char path[4096], clean[256];
    size_t u = 0;
    for (const char *p = label; *p && u + 1 < sizeof clean; p++)
        clean[u++] = (*p == ' ' || *p == '/' || *p == ',') ? '_' : *p;
    clean[u] = 0;
    snprintf(path, sizeof path, "%s-%s.png", o->image_prefix, clean);
    char err[1024];
    if (!sl_image_write(path, px, w, h, false, err, sizeof err)) SL_WARN("%s", err);
}

bool sl_bench_run(const sl_bench_options *o, sl_bench_result *res, char *err, size_t n) {
    memset(res, 0, sizeof *res);
    if (!o->plugin) { snprintf(err, n, "no plugin given (--plugin NAME, or core)"); return false; }
    double t_start = now_s();
    time_t now = time(NULL);
    strftime(res->created, sizeof res->created, "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
    res->scene = strdup(o->scene_path ? o->scene_path : "<built-in default scene>");
    snprintf(res->scene_hash, sizeof res->scene_hash, "%016llx", (unsigned long long)sl_bench_scene_hash(o->scene_path));
    res->plugin = strdup(o->plugin);
    res->frames = o->frames > 0 ? o->frames : 30;
    res->warmup = o->warmup >= 0 ? o->warmup : 5;
    if (o->warmup == 0 && o->frames == 0) res->warmup = 5; /* zeroed options: the defaults */
    res->noise_samples = o->noise_samples < 0 ? 0 : o->noise_samples > 0 ? o->noise_samples : SL_NOISE_SAMPLES;
    res->noise_limit = o->noise_limit > 0 ? o->noise_limit : SL_NOISE_VISIBLE;
    char **settings = NULL;
    int count = 0;
    if (!sl_bench_enumerate(o, &settings, &count, err, n)) return false;
    if (!render_reference(o, res, err, n)) {
        for (int i = 0; i < count; i++) free(settings[i]);
        free(settings);
        return false;
    }
    res->rows = calloc(count + 1, sizeof *res->rows);
    res->row_count = count;
    samples *sm = calloc(count + 1, sizeof *sm);
    /* rounds: every setting is timed in each round, so a burst of load on a shared machine
     * spreads over all settings instead of biasing one */
    int rounds = o->rounds > 1 ? o->rounds : 1;
    int per_round = (res->frames + rounds - 1) / rounds;
    res->rounds = rounds;
    res->frames = per_round * rounds;
    double t_settings = now_s();
    float *image = NULL;
    int steps = count * rounds, step = 0;
    for (int round = 0; round < rounds; round++)
        for (int i = 0; i < count; i++) {
            sl_bench_row *row = &res->rows[i];
            step++;
            if (round == 0) {
                row->settings = settings[i];
                row->label = sl_bench_label(settings[i], o->plugin);
            } else if (!row->ok) {
                continue;
            }
            double t0 = now_s();
            if (o->progress && rounds > 1)
                fprintf(stderr, "[bench] step %d of %d (setting %d of %d, round %d of %d): %s …\n", step, steps, i + 1, count,
                        round + 1, rounds, row->settings);
            else if (o->progress)
                fprintf(stderr, "[bench] setting %d of %d: %s …\n", i + 1, count, row->settings);
            bench_app b;
            char why[4096] = "";
            bool ok = false;
            if (open_app(o, row->settings, 1, 1, true, &b, why, sizeof why)) {
                int w = b.app.backend.width, h = b.app.backend.height;
                if (!res->backend) {
                    res->width = w;
                    res->height = h;
                    res->backend = strdup(b.app.backend.name);
                    const char *rs = (const char *)glGetString(GL_RENDERER);
                    res->renderer = strdup(rs ? rs : "?");
                    res->gpu = b.app.backend.is_gpu;
                    char list[2048] = "";
                    size_t u = 0;
                    for (int k = 0; k < b.app.plugins.count && u < sizeof list; k++)
                        if (b.app.plugins.items[k]->ok)
                            u += snprintf(list + u, sizeof list - u, "%s%s %s", u ? ", " : "", b.app.plugins.items[k]->id,
                                          b.app.plugins.items[k]->desc.version ? b.app.plugins.items[k]->desc.version : "");
                    res->plugins_loaded = strdup(list);
                }
                if (!image) image = malloc(sizeof(float) * 4 * w * h);
                ok = time_setting(&b.app, res->warmup, per_round, &sm[i], round == 0 ? image : NULL);
                if (ok && round == 0) {
                    if (!res->timing_mode) {
                        sl_tool_frame_times t;
                        sl_tool_frame_times_of(&b.app, &t);
                        res->timing_mode = strdup(t.timing_mode ? t.timing_mode : "");
                    }
                    sl_metric_all(image, res->reference.pixels, w, h, &row->error);
                    if (o->image_prefix) save_image(o, row->label, image, w, h);
                    if (res->noise_samples > 1) ok = measure_noise(&b.app, res->noise_samples, image, &row->error.noise);
                }
                if (!ok) snprintf(why, sizeof why, "rendering failed");
            }
            close_app(&b);
            if (round == 0) row->ok = ok;
            if (!ok) {
                row->ok = false;
                free(row->failure);
                row->failure = strdup(why);
                SL_ERROR("setting %s: %s", row->settings, why);
            }
            row->wall_s += now_s() - t0;
            if (o->progress) {
                double elapsed = now_s() - t_start, per = (now_s() - t_settings) / step;
                char e[64], left[64];
                fmt_duration(elapsed, e, sizeof e);
                fmt_duration(per * (steps - step), left, sizeof left);
                if (row->ok)
                    fprintf(stderr, "[bench]   %s: %.3f ms/frame (median of this round's %d), rmse %.3g, flip %.4f, "
                            "noise %.4g; elapsed %s, about %s left\n", row->label,
                            median_of(sm[i].frame + sm[i].nframe - per_round, per_round), per_round,
                            row->error.rmse, row->error.flip, row->error.noise, e, left);
                else
                    fprintf(stderr, "[bench]   %s FAILED; elapsed %s, about %s left\n", row->label, e, left);
            }
        }
    for (int i = 0; i < count; i++) {
        if (res->rows[i].ok) finish_row(&res->rows[i], &sm[i]);
        samples_free(&sm[i]);
    }
    free(sm);
    if (o->image_prefix && res->width) save_image(o, "reference", res->reference.pixels, res->width, res->height);
    free(image);
    free(settings);
    sl_bench_mark_fronts(res);
    res->total_s = now_s() - t_start;
    if (!res->backend) { snprintf(err, n, "every setting failed (see above)"); return false; }
    return true;
}

void sl_bench_result_free(sl_bench_result *res) {
    for (int i = 0; i < res->row_count; i++) {
        sl_bench_row *r = &res->rows[i];
        free(r->settings);
        free(r->label);
        free(r->failure);
        for (int k = 0; k < r->pass_count; k++) { free(r->passes[k].name); free(r->passes[k].owner); }
        free(r->passes);
    }
    free(res->rows);
    for (int i = 0; i < res->peer_count; i++) free(res->peers[i].label);
    free(res->peers);
    free(res->scene);
    free(res->plugin);
    free(res->plugins_loaded);
    free(res->backend);
    free(res->renderer);
    free(res->timing_mode);
    free(res->reference.settings);
    free(res->reference.description);
    free(res->reference.cache_path);
    free(res->reference.pixels);
    memset(res, 0, sizeof *res);
}

