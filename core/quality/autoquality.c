/* --auto-quality (see autoquality.h). */
#include "autoquality.h"
#include "app.h"
#include "fileio.h"
#include "log.h"
#include "render/composer.h"
#include <cjson/cJSON.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static double jnum(const cJSON *o, const char *key) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    if (cJSON_IsNumber(v)) return v->valuedouble;
    if (cJSON_IsString(v) && !strcmp(v->valuestring, "inf")) return INFINITY;
    return NAN;
}
static const char *jstr(const cJSON *o, const char *key) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsString(v) ? v->valuestring : "";
}

/* Error of a row under metric m, lower is better (psnr negated). */
static double row_error(const cJSON *row, sl_metric m) {
    const cJSON *e = cJSON_GetObjectItemCaseSensitive(row, "error");
    if (!cJSON_IsObject(e)) return NAN;
    switch (m) {
    case SL_METRIC_RMSE: return jnum(e, "rmse");
    case SL_METRIC_RELMSE: return jnum(e, "relmse");
    case SL_METRIC_DSSIM: { double s = jnum(e, "ssim"); return 1.0 - s; }
    case SL_METRIC_PSNR: {
        double p = jnum(e, "psnr");
        if (isnan(p) && jnum(e, "rmse") == 0) p = INFINITY;
        return -p;
    }
    case SL_METRIC_FLIP: return jnum(e, "flip");
    case SL_METRIC_NOISE: return jnum(e, "noise");
    default: return NAN;
    }
}

/* shadelab-bench marked it noisy: its frames scatter visibly (metrics.h, "noise"). */
static bool row_noisy(const cJSON *row) {
    return cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(row, "error"), "noisy"));
}

static bool choose_json(const cJSON *root, const char *metric_name, double budget, sl_aq_choice *out, char *err, size_t n) {
    memset(out, 0, sizeof *out);
    if (strcmp(jstr(root, "format"), "shadelab-bench/1")) {
        snprintf(err, n, "not a shadelab-bench result (\"format\": \"shadelab-bench/1\" missing)");
        return false;
    }
    const char *mname = metric_name ? metric_name : jstr(root, "primary_metric");
    if (!*mname) mname = "rmse";
    sl_metric m;
    if (!sl_metric_parse(mname, &m)) {
        snprintf(err, n, "unknown metric \"%s\" (rmse, relmse, dssim, psnr, flip, noise)", mname);
        return false;
    }
    const cJSON *rows = cJSON_GetObjectItemCaseSensitive(root, "settings");
    int count = cJSON_GetArraySize(rows);
    if (!cJSON_IsArray(rows) || count == 0) { snprintf(err, n, "no measured settings"); return false; }
    double *cost = calloc(count, sizeof *cost), *error = calloc(count, sizeof *error);
    double limit = m == SL_METRIC_PSNR ? -budget : budget;
    int pick = -1;
    /* noisy settings only when every setting is noisy: a lower mean error does not make up for
     * visible noise */
    for (int with_noisy = 0; with_noisy < 2 && pick < 0; with_noisy++) {
        for (int i = 0; i < count; i++) {
            const cJSON *r = cJSON_GetArrayItem(rows, i);
            bool ok = cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(r, "ok")) && (with_noisy || !row_noisy(r));
            cost[i] = ok ? jnum(cJSON_GetObjectItemCaseSensitive(r, "frame_ms"), "median") : NAN;
            error[i] = ok ? row_error(r, m) : NAN;
        }
        pick = sl_pareto_cheapest_within(cost, error, count, limit);
        out->within_budget = pick >= 0;
        if (pick < 0) pick = sl_pareto_most_accurate(cost, error, count);
        out->noisy = pick >= 0 && with_noisy && row_noisy(cJSON_GetArrayItem(rows, pick));
    }
    if (pick < 0) {
        free(cost);
        free(error);
        snprintf(err, n, "no setting was measured successfully");
        return false;
    }
    const cJSON *r = cJSON_GetArrayItem(rows, pick);
    snprintf(out->plugin, sizeof out->plugin, "%s", jstr(root, "plugin"));
    snprintf(out->settings, sizeof out->settings, "%s", jstr(r, "settings"));
    snprintf(out->metric, sizeof out->metric, "%s", sl_metric_name(m));
    out->frame_ms = cost[pick];
    out->error = m == SL_METRIC_PSNR ? -error[pick] : error[pick];
    size_t u = 0;
    const cJSON *p;
    cJSON_ArrayForEach(p, cJSON_GetObjectItemCaseSensitive(r, "passes")) {
        if (u >= sizeof out->passes) break;
        u += snprintf(out->passes + u, sizeof out->passes - u, "%s%s %.3f ms", u ? ", " : "", jstr(p, "name"), jnum(p, "median_ms"));
    }
    snprintf(out->measured_on, sizeof out->measured_on, "%s %dx%d, %s (%s)", jstr(root, "scene"), (int)jnum(root, "width"),
             (int)jnum(root, "height"), jstr(root, "backend"), jstr(root, "renderer"));
    free(cost);
    free(error);
    return true;
}

bool sl_autoquality_choose(const char *text, const char *metric, double budget, sl_aq_choice *out, char *err, size_t n) {
    cJSON *root = cJSON_Parse(text);
    if (!root) { snprintf(err, n, "malformed JSON near \"%.20s\"", cJSON_GetErrorPtr() ? cJSON_GetErrorPtr() : ""); return false; }
    bool ok = choose_json(root, metric, budget, out, err, n);
    cJSON_Delete(root);
    return ok;
}

/* ------------------------------------------------------------------- apply ----------- */

typedef struct front_file { char *path; cJSON *root; } front_file;
typedef struct front_list { front_file *items; int count; } front_list;


static bool add_file(front_list *l, const char *path, bool from_dir, char *err, size_t n) {
    char *text = sl_read_file(path, NULL, NULL, 0);
    if (!text) { snprintf(err, n, "--auto-quality: cannot read %s", path); return false; }
    cJSON *root = cJSON_Parse(text);
    free(text);
    if (!root || strcmp(jstr(root, "format"), "shadelab-bench/1")) {
        cJSON_Delete(root);
        if (from_dir) return true; /* other JSON in a folder: not ours */
        snprintf(err, n, "--auto-quality: %s is not a shadelab-bench result", path);
        return false;
    }
    l->items = realloc(l->items, sizeof *l->items * (l->count + 1));
    l->items[l->count++] = (front_file){strdup(path), root};
    return true;
}

static bool add_path(front_list *l, const char *path, bool must_exist, char *err, size_t n) {
    struct stat st;
    if (stat(path, &st)) {
        if (!must_exist) return true;
        snprintf(err, n, "--auto-quality: %s does not exist", path);
        return false;
    }
    if (!S_ISDIR(st.st_mode)) return add_file(l, path, false, err, n);
    DIR *d = opendir(path);
    if (!d) { snprintf(err, n, "--auto-quality: cannot open %s", path); return false; }
    bool ok = true;
    for (struct dirent *e; ok && (e = readdir(d));) {
        size_t len = strlen(e->d_name);
        if (len < 6 || strcmp(e->d_name + len - 5, ".json")) continue;
        char p[4096];
        snprintf(p, sizeof p, "%s/%s", path, e->d_name);
        ok = add_file(l, p, true, err, n);
    }
    closedir(d);
    return ok;
}

static uint64_t app_scene_hash(sl_app *app) {
    if (app->opt.scene_text) return sl_hash64(app->opt.scene_text, strlen(app->opt.scene_text), 0);
    return sl_bench_scene_hash(app->opt.scene_path);
}

bool sl_autoquality_apply(sl_app *app, const char *spec, char *err, size_t n) {
    /* [METRIC=]BUDGET[@FRONTS] */
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", spec ? spec : "");
    char *fronts = strchr(buf, '@');
    if (fronts) *fronts++ = 0;
    char *metric = NULL, *value = buf, *eq = strchr(buf, '=');
    if (eq) { *eq = 0; metric = buf; value = eq + 1; }
    sl_metric m;
    if (metric && !sl_metric_parse(metric, &m)) {
        snprintf(err, n, "--auto-quality %s: unknown metric \"%s\" (rmse, relmse, dssim, psnr)", spec, metric);
        return false;
    }
    char *end;
    double budget = strtod(value, &end);
    if (end == value || *end || !isfinite(budget) || (budget < 0 && (!metric || strcmp(metric, "psnr")))) {
        snprintf(err, n, "--auto-quality %s: expected [METRIC=]BUDGET[@FRONT.json,…], e.g. rmse=0.01 or psnr=40@bench.json", spec);
        return false;
    }
    front_list list = {0};
    bool ok = true;
    char where[4096];
    if (fronts && *fronts) {
        snprintf(where, sizeof where, "%s", fronts);
        char *save = NULL;
        for (char *p = strtok_r(fronts, ",", &save); ok && p; p = strtok_r(NULL, ",", &save)) ok = add_path(&list, p, true, err, n);
    } else {
        char cache[4000];
        snprintf(where, sizeof where, "%s/fronts", sl_bench_default_cache_dir(cache, sizeof cache));
        ok = add_path(&list, where, false, err, n);
    }
    uint64_t scene_hash = app_scene_hash(app);
    char hash_hex[17];
    snprintf(hash_hex, sizeof hash_hex, "%016llx", (unsigned long long)scene_hash);
    int applied = 0;
    for (int pi = 0; ok && pi < app->plugins.count; pi++) {
        sl_plugin_rec *rec = app->plugins.items[pi];
        if (!rec->ok) continue;
        /* the best run for this plugin: same scene first, then the newest */
        int best = -1;
        for (int i = 0; i < list.count; i++) {
            if (strcmp(jstr(list.items[i].root, "plugin"), rec->id)) continue;
            if (best < 0) { best = i; continue; }
            bool same_i = !strcmp(jstr(list.items[i].root, "scene_hash"), hash_hex);
            bool same_b = !strcmp(jstr(list.items[best].root, "scene_hash"), hash_hex);
            if (same_i != same_b) { if (same_i) best = i; continue; }
            if (strcmp(jstr(list.items[i].root, "created"), jstr(list.items[best].root, "created")) > 0) best = i;
        }
        if (best < 0) continue;
        sl_aq_choice c;
        char why[1024];
        if (!choose_json(list.items[best].root, metric, budget, &c, why, sizeof why)) {
            snprintf(err, n, "--auto-quality: %s: %s", list.items[best].path, why);
            ok = false;
            break;
        }
        bool same_scene = !strcmp(jstr(list.items[best].root, "scene_hash"), hash_hex);
        /* apply, leaving what the user set explicitly alone */
        char *copy = strdup(c.settings), *save = NULL;
        char kept[1024] = "";
        for (char *t = strtok_r(copy, " \t", &save); ok && t; t = strtok_r(NULL, " \t", &save)) {
            char id[512];
            snprintf(id, sizeof id, "%.*s", (int)(strcspn(t, "=")), t);
            sl_param *q = sl_params_find(&app->params, id);
            if (q && q->source == SL_SRC_CLI) {
                size_t u = strlen(kept);
                snprintf(kept + u, sizeof kept - u, "%s%s", u ? ", " : "", id);
                continue;
            }
            if (!sl_app_set(app, t, SL_SRC_CLI, why, sizeof why)) {
                snprintf(err, n, "--auto-quality: %s (from %s): %s", t, list.items[best].path, why);
                ok = false;
            }
        }
        free(copy);
        if (!ok) break;
        applied++;
        bool psnr = !strcmp(c.metric, "psnr");
        fprintf(stderr, "auto-quality %s: %s — %.3f ms/frame measured (%s); %s %.4g %s %s %.4g%s\n", rec->id, c.settings,
                c.frame_ms, c.passes, c.metric, c.error, c.within_budget ? (psnr ? ">=" : "<=") : (psnr ? "<" : ">"),
                "budget", budget, c.within_budget ? "" : " (nothing meets the budget: the most accurate setting)");
        fprintf(stderr, "  measured on %s%s [%s]\n", c.measured_on, same_scene ? "" : " — a different scene than this one",
                list.items[best].path);
        if (kept[0]) fprintf(stderr, "  kept your --set for %s\n", kept);
        if (!c.within_budget) SL_WARN("auto-quality %s: no measured setting meets %s budget %g", rec->id, c.metric, budget);
        if (c.noisy) SL_WARN("auto-quality %s: every measured setting is noisy (shadelab-bench's noise limit)", rec->id);
    }
    if (ok && !applied)
        SL_WARN("--auto-quality: no benchmark result for any loaded plugin in %s (run shadelab-bench first)", where);
    for (int i = 0; i < list.count; i++) { free(list.items[i].path); cJSON_Delete(list.items[i].root); }
    free(list.items);
    return ok;
}
