/* The JSON scene loader (format: scenes/README.md).
 *
 * Parsing is cJSON's. cJSON keeps no source positions, so after a successful parse a small
 * scanner walks the text and the tree side by side (same order, valid JSON) and records the
 * line and column of every key and array element: error messages name exact positions.
 *
 * Every error stops the load with "file:line:column: what is wrong (what was expected)";
 * unknown keys in structural objects are warnings that name the nearest valid key. Nothing
 * here may crash on hostile input: every value is type- and range-checked before use, nesting
 * is bounded, and allocation failures are errors. */
#include "fileio.h"
#include "log.h"
#include "scene/scene.h"

#include <cjson/cJSON.h>
#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

extern const char sl_default_scene_json[]; /* generated from scenes/default.json */

#define MAX_SCENE_FILE_BYTES (64u << 20)
/* Name and key checks are linear scans: bounded counts keep hostile files from taking
 * quadratic time. Far above any hand-written scene. */
#define MAX_ITEMS 20000 /* materials, cameras, lights, nodes (each) */
#define MAX_KEYS 1024   /* keys in one object */

typedef struct pos_entry { const cJSON *item; int line, col; } pos_entry;

typedef struct loader {
    sl_scene *scene;
    const char *text; /* NUL-terminated */
    size_t len;
    const char *file; /* name used in messages */
    const char *data_dir;
    char *err;
    size_t err_size;
    bool failed;
    pos_entry *pos;
    size_t pos_count, pos_cap;
    int default_material;
    int *node_lines, *camera_lines; /* line of each scene node/camera (0: imported) */
    int node_lines_n, camera_lines_n;
} loader;

/* Remembers the line of scene item `index` in *lines (grown and zero-filled as needed). */
static bool remember_line(int **lines, int *n, int index, int line) {
    if (index >= *n) {
        int cap = index + 16;
        int *p = realloc(*lines, sizeof(int) * (size_t)cap);
        if (!p) return false;
        memset(p + *n, 0, sizeof(int) * (size_t)(cap - *n));
        *lines = p, *n = cap;
    }
    (*lines)[index] = line;
    return true;
}

/* " (first defined at line N)" or " (already used by an imported item)" */
static const char *first_defined(int line, char *buf, size_t size) {
    if (line > 0) snprintf(buf, size, "first defined at line %d", line);
    else snprintf(buf, size, "already used by an item imported from a mesh file");
    return buf;
}

/* ---- positions -------------------------------------------------------------------------- */

typedef struct scan { const char *s; size_t i, n; int line; size_t line_start; } scan;

static void sc_ws(scan *c) {
    while (c->i < c->n && (unsigned char)c->s[c->i] <= 32 && c->s[c->i] != 0) {
        if (c->s[c->i] == '\n') c->line++, c->line_start = c->i + 1;
        c->i++;
    }
}

static void sc_string(scan *c) {
    c->i++; /* opening quote */
    while (c->i < c->n && c->s[c->i] != '"') {
        if (c->s[c->i] == '\\' && c->i + 1 < c->n) c->i++;
        if (c->s[c->i] == '\n') c->line++, c->line_start = c->i + 1;
        c->i++;
    }
    if (c->i < c->n) c->i++;
}

static void record(loader *L, const cJSON *item, int line, int col) {
    if (L->pos_count == L->pos_cap) {
        size_t cap = L->pos_cap ? L->pos_cap * 2 : 256;
        pos_entry *p = realloc(L->pos, cap * sizeof *p);
        if (!p) return; /* positions are a nicety: without memory, messages say line 0 */
        L->pos = p, L->pos_cap = cap;
    }
    L->pos[L->pos_count++] = (pos_entry){item, line, col};
}

/* Walks the value starting at c->i that cJSON parsed into `item`. line/col > 0: position of
 * the member's key, recorded for the item instead of the value's own position. */
static bool walk(loader *L, scan *c, const cJSON *item, int line, int col) {
    sc_ws(c);
    if (c->i >= c->n) return false;
    int vline = c->line, vcol = (int)(c->i - c->line_start) + 1;
    record(L, item, line > 0 ? line : vline, line > 0 ? col : vcol);
    char ch = c->s[c->i];
    if (ch == '{' || ch == '[') {
        char close = ch == '{' ? '}' : ']';
        c->i++;
        for (const cJSON *child = item->child; child; child = child->next) {
            sc_ws(c);
            int kl = 0, kc = 0;
            if (ch == '{') {
                if (c->i >= c->n || c->s[c->i] != '"') return false;
                kl = c->line, kc = (int)(c->i - c->line_start) + 1;
                sc_string(c);
                sc_ws(c);
                if (c->i >= c->n || c->s[c->i] != ':') return false;
                c->i++;
            }
            if (!walk(L, c, child, kl, kc)) return false;
            sc_ws(c);
            if (c->i < c->n && c->s[c->i] == ',') c->i++;
        }
        sc_ws(c);
        if (c->i >= c->n || c->s[c->i] != close) return false;
        c->i++;
        return true;
    }
    if (ch == '"') {
        sc_string(c);
        return true;
    }
    while (c->i < c->n && (unsigned char)c->s[c->i] > 32 && !strchr(",]}", c->s[c->i])) c->i++;
    return true;
}

static int cmp_pos(const void *a, const void *b) {
    uintptr_t x = (uintptr_t)((const pos_entry *)a)->item, y = (uintptr_t)((const pos_entry *)b)->item;
    return x < y ? -1 : x > y;
}

static void where(const loader *L, const cJSON *item, int *line, int *col) {
    *line = *col = 0;
    if (!item || !L->pos) return;
    pos_entry key = {item, 0, 0};
    const pos_entry *e = bsearch(&key, L->pos, L->pos_count, sizeof key, cmp_pos);
    if (e) *line = e->line, *col = e->col;
}

static int line_of(const loader *L, const cJSON *item) {
    int line, col;
    where(L, item, &line, &col);
    return line;
}

/* ---- messages --------------------------------------------------------------------------- */

static bool failf(loader *L, const cJSON *at, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static bool failf(loader *L, const cJSON *at, const char *fmt, ...) {
    if (L->failed) return false; /* keep the first error */
    L->failed = true;
    if (!L->err || !L->err_size) return false;
    int line, col;
    where(L, at, &line, &col);
    int n;
    if (line > 0) n = snprintf(L->err, L->err_size, "%s:%d:%d: ", L->file, line, col);
    else n = snprintf(L->err, L->err_size, "%s: ", L->file);
    if (n < 0) n = 0;
    if ((size_t)n < L->err_size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(L->err + n, L->err_size - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return false;
}

static void warnf(loader *L, const cJSON *at, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void warnf(loader *L, const cJSON *at, const char *fmt, ...) {
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    int line, col;
    where(L, at, &line, &col);
    if (line > 0) SL_WARN("%s:%d:%d: %s", L->file, line, col, msg);
    else SL_WARN("%s: %s", L->file, msg);
}

/* Levenshtein distance, case-insensitive, on at most 64 characters. */
static int edit_distance(const char *a, const char *b) {
    size_t la = strlen(a), lb = strlen(b);
    if (la > 64) la = 64;
    if (lb > 64) lb = 64;
    int row[65];
    for (size_t j = 0; j <= lb; j++) row[j] = (int)j;
    for (size_t i = 1; i <= la; i++) {
        int diag = row[0];
        row[0] = (int)i;
        for (size_t j = 1; j <= lb; j++) {
            int up = row[j];
            int cost = tolower((unsigned char)a[i - 1]) != tolower((unsigned char)b[j - 1]);
            int best = diag + cost;
            if (up + 1 < best) best = up + 1;
            if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[lb];
}

/* The candidate nearest to `key` if it is near enough to be a likely typo, else NULL. */
static const char *nearest(const char *key, const char *const *candidates, int count) {
    const char *best = NULL;
    int best_d = INT_MAX;
    for (int i = 0; i < count; i++) {
        int d = edit_distance(key, candidates[i]);
        if (d < best_d) best_d = d, best = candidates[i];
    }
    int klen = (int)strlen(key);
    int limit = klen <= 3 ? 1 : klen <= 6 ? 2 : 3;
    if (best && best_d <= limit) return best;
    /* a prefix is a good hint too: "fov" → "fov_y" */
    for (int i = 0; i < count; i++)
        if (klen >= 3 && strncasecmp(candidates[i], key, (size_t)klen) == 0) return candidates[i];
    return NULL;
}

static void join_list(char *out, size_t size, const char *const *items, int count) {
    size_t used = 0;
    out[0] = 0;
    for (int i = 0; i < count && used < size; i++) {
        int w = snprintf(out + used, size - used, "%s%s", i ? ", " : "", items[i]);
        if (w < 0) break;
        used += (size_t)w;
    }
}

/* " (did you mean 'x'?)" or " (valid keys: a, b, c)" */
static void key_hint(char *out, size_t size, const char *key, const char *const *valid, int count,
                     const char *what) {
    const char *near = nearest(key, valid, count);
    if (near) {
        snprintf(out, size, " (did you mean '%s'?)", near);
    } else {
        char list[512];
        join_list(list, sizeof list, valid, count);
        snprintf(out, size, " (valid %s: %s)", what, list);
    }
}

/* A short description of what a JSON value is, for "found …". */
static const char *describe(const cJSON *v, char *buf, size_t size) {
    if (!v) return "nothing";
    if (cJSON_IsNull(v)) return "null";
    if (cJSON_IsBool(v)) return cJSON_IsTrue(v) ? "true" : "false";
    if (cJSON_IsNumber(v)) {
        snprintf(buf, size, "the number %g", v->valuedouble);
        return buf;
    }
    if (cJSON_IsString(v)) {
        snprintf(buf, size, "the string \"%.40s%s\"", v->valuestring,
                 strlen(v->valuestring) > 40 ? "…" : "");
        return buf;
    }
    if (cJSON_IsArray(v)) {
        int n = cJSON_GetArraySize(v), numbers = 0;
        for (const cJSON *e = v->child; e; e = e->next) numbers += cJSON_IsNumber(e) != 0;
        if (n == 0) snprintf(buf, size, "an empty array");
        else if (n == numbers) snprintf(buf, size, "an array of %d number%s", n, n == 1 ? "" : "s");
        else snprintf(buf, size, "an array of %d value%s, not all numbers", n, n == 1 ? "" : "s");
        return buf;
    }
    if (cJSON_IsObject(v)) return "an object";
    return "an invalid value";
}

/* ---- typed getters ---------------------------------------------------------------------- */

/* All report "<ctx>: "<key>" must be <expected>, found <what>". ctx names the object. */

static bool number_ok(const cJSON *v) {
    return cJSON_IsNumber(v) && isfinite(v->valuedouble) && fabs(v->valuedouble) <= FLT_MAX;
}

static bool get_number(loader *L, const cJSON *v, const char *ctx, float *out, double min,
                       bool min_exclusive, double max) {
    char buf[96];
    if (!number_ok(v)) {
        if (cJSON_IsNumber(v))
            return failf(L, v, "%s: \"%s\" must be a finite number (at most %g in magnitude), found %s",
                         ctx, v->string, (double)FLT_MAX, describe(v, buf, sizeof buf));
        return failf(L, v, "%s: \"%s\" must be a number, found %s", ctx, v->string,
                     describe(v, buf, sizeof buf));
    }
    double x = v->valuedouble;
    if ((min_exclusive ? !(x > min) : !(x >= min)) || !(x <= max)) {
        char range[96];
        if (max >= FLT_MAX) snprintf(range, sizeof range, "%s %g", min_exclusive ? ">" : "≥", min);
        else snprintf(range, sizeof range, "in %s%g, %g]", min_exclusive ? "(" : "[", min, max);
        return failf(L, v, "%s: \"%s\" must be a number %s, found %g", ctx, v->string, range, x);
    }
    *out = (float)x;
    return true;
}

static bool get_int(loader *L, const cJSON *v, const char *ctx, int *out, int min, int max) {
    char buf[96];
    if (!number_ok(v) || v->valuedouble != floor(v->valuedouble))
        return failf(L, v, "%s: \"%s\" must be an integer in [%d, %d], found %s", ctx, v->string,
                     min, max, describe(v, buf, sizeof buf));
    if (v->valuedouble < min || v->valuedouble > max)
        return failf(L, v, "%s: \"%s\" must be an integer in [%d, %d], found %g", ctx, v->string,
                     min, max, v->valuedouble);
    *out = (int)v->valuedouble;
    return true;
}

static bool get_bool(loader *L, const cJSON *v, const char *ctx, bool *out) {
    char buf[96];
    if (!cJSON_IsBool(v))
        return failf(L, v, "%s: \"%s\" must be true or false, found %s", ctx, v->string,
                     describe(v, buf, sizeof buf));
    *out = cJSON_IsTrue(v);
    return true;
}

static bool get_string(loader *L, const cJSON *v, const char *ctx, const char **out) {
    char buf[96];
    if (!cJSON_IsString(v) || !v->valuestring[0])
        return failf(L, v, "%s: \"%s\" must be a non-empty string, found %s", ctx, v->string,
                     describe(v, buf, sizeof buf));
    *out = v->valuestring;
    return true;
}

/* An array of exactly n finite numbers (each ≥ 0 when non_negative). */
static bool get_vec(loader *L, const cJSON *v, const char *ctx, int n, float *out, bool non_negative) {
    char buf[96];
    int count = cJSON_IsArray(v) ? cJSON_GetArraySize(v) : -1;
    bool ok = count == n;
    for (const cJSON *e = ok ? v->child : NULL; e; e = e->next) ok = ok && number_ok(e);
    if (!ok)
        return failf(L, v, "%s: \"%s\" must be an array of %d numbers, found %s", ctx, v->string, n,
                     describe(v, buf, sizeof buf));
    int i = 0;
    for (const cJSON *e = v->child; e; e = e->next, i++) {
        if (non_negative && e->valuedouble < 0)
            return failf(L, v, "%s: \"%s\" must not be negative, found %g in element %d", ctx,
                         v->string, e->valuedouble, i);
        out[i] = (float)e->valuedouble;
    }
    return true;
}

static bool get_direction(loader *L, const cJSON *v, const char *ctx, float out[3]) {
    if (!get_vec(L, v, ctx, 3, out, false)) return false;
    double len = sqrt((double)out[0] * out[0] + (double)out[1] * out[1] + (double)out[2] * out[2]);
    if (!(len > 1e-12) || !isfinite(len))
        return failf(L, v, "%s: \"%s\" must be a non-zero vector", ctx, v->string);
    for (int c = 0; c < 3; c++) out[c] = (float)(out[c] / len);
    return true;
}

/* A free-form property: number, bool, string or array of 2–4 numbers. */
static bool get_prop(loader *L, const cJSON *v, const char *ctx, sl_prop_list *list) {
    char buf[96];
    int line = line_of(L, v);
    sl_prop *p = NULL;
    if (cJSON_IsNumber(v)) {
        if (!number_ok(v))
            return failf(L, v, "%s: \"%s\" must be a finite number, found %s", ctx, v->string,
                         describe(v, buf, sizeof buf));
        p = sl_prop_set_number(list, v->string, (float)v->valuedouble, line);
    } else if (cJSON_IsBool(v)) {
        p = sl_prop_set_bool(list, v->string, cJSON_IsTrue(v), line);
    } else if (cJSON_IsString(v)) {
        p = sl_prop_set_string(list, v->string, v->valuestring, line);
    } else {
        int n = cJSON_IsArray(v) ? cJSON_GetArraySize(v) : 0;
        bool ok = n >= 2 && n <= 4;
        for (const cJSON *e = ok ? v->child : NULL; e; e = e->next) ok = ok && number_ok(e);
        if (!ok)
            return failf(L, v, "%s: \"%s\" must be a number, true/false, a string or an array of "
                         "2 to 4 finite numbers, found %s", ctx, v->string, describe(v, buf, sizeof buf));
        float f[4];
        int i = 0;
        for (const cJSON *e = v->child; e; e = e->next) f[i++] = (float)e->valuedouble;
        p = sl_prop_set_vec(list, v->string, f, n, line);
    }
    if (!p) return failf(L, v, "out of memory");
    return true;
}

/* ---- key checks ------------------------------------------------------------------------- */

/* A table and its length, counted by the compiler: a key added to a table is never both read and
 * reported as unknown because a hand-written count was not bumped. */
#define KEYS(table) (table), (int)(sizeof(table) / sizeof *(table))

static bool in_list(const char *key, const char *const *list, int count) {
    for (int i = 0; i < count; i++)
        if (strcmp(key, list[i]) == 0) return true;
    return false;
}

/* Warns about unknown keys (structural objects) and duplicate keys (any object); fails on an
 * object with more than MAX_KEYS keys. */
static bool check_keys(loader *L, const cJSON *obj, const char *ctx, const char *const *valid,
                       int count, bool unknown_is_prop) {
    if (cJSON_GetArraySize(obj) > MAX_KEYS)
        return failf(L, obj, "%s has %d keys; at most %d are allowed", ctx, cJSON_GetArraySize(obj), MAX_KEYS);
    for (const cJSON *k = obj->child; k; k = k->next) {
        for (const cJSON *e = obj->child; e != k; e = e->next)
            if (strcmp(e->string, k->string) == 0) {
                warnf(L, k, "%s: duplicate key \"%s\" (the first one, line %d, is used)", ctx,
                      k->string, line_of(L, e));
                break;
            }
        if (strcmp(k->string, "comment") == 0 || in_list(k->string, valid, count)) continue;
        if (!unknown_is_prop) {
            char hint[600];
            key_hint(hint, sizeof hint, k->string, valid, count, "keys");
            warnf(L, k, "%s: unknown key \"%s\" ignored%s", ctx, k->string, hint);
        } else {
            /* kept as a property for the plugins, but a near miss of a base key is a typo */
            const char *near = nearest(k->string, valid, count);
            if (near && strlen(k->string) >= 4)
                warnf(L, k, "%s: \"%s\" is kept as a plugin property; did you mean '%s'?", ctx,
                      k->string, near);
        }
    }
    return true;
}

static bool check_count(loader *L, const cJSON *arr, const char *what) {
    int n = cJSON_GetArraySize(arr);
    if (n > MAX_ITEMS) return failf(L, arr, "\"%s\" has %d entries; at most %d are allowed", what, n, MAX_ITEMS);
    return true;
}

/* Names: non-empty strings without control characters, at most 255 bytes. */
static bool get_name(loader *L, const cJSON *obj, const char *kind, int index, bool required,
                     char *out, size_t size) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "name");
    if (!v) {
        if (required) return failf(L, obj, "%s #%d has no \"name\" (every %s needs one)", kind, index, kind);
        snprintf(out, size, "%s%d", kind, index);
        return true;
    }
    char ctx[64], buf[96];
    snprintf(ctx, sizeof ctx, "%s #%d", kind, index);
    if (!cJSON_IsString(v) || !v->valuestring[0])
        return failf(L, v, "%s: \"name\" must be a non-empty string, found %s", ctx,
                     describe(v, buf, sizeof buf));
    if (strlen(v->valuestring) >= size || strlen(v->valuestring) > 255)
        return failf(L, v, "%s: \"name\" is longer than 255 bytes", ctx);
    for (const char *c = v->valuestring; *c; c++)
        if ((unsigned char)*c < 32)
            return failf(L, v, "%s: \"name\" must not contain control characters", ctx);
    snprintf(out, size, "%s", v->valuestring);
    return true;
}

/* ---- sections --------------------------------------------------------------------------- */

static const char *const top_keys[] = {"plugins", "params", "cameras", "materials", "nodes",
                                       "lights", "environment"};

static bool load_plugins(loader *L, const cJSON *arr) {
    char buf[96];
    if (!cJSON_IsArray(arr))
        return failf(L, arr, "\"plugins\" must be an array of plugin names, found %s",
                     describe(arr, buf, sizeof buf));
    if (!check_count(L, arr, "plugins")) return false;
    for (const cJSON *e = arr->child; e; e = e->next) {
        if (!cJSON_IsString(e) || !e->valuestring[0])
            return failf(L, e, "\"plugins\": each entry must be a plugin name (a string), found %s",
                         describe(e, buf, sizeof buf));
        const char *name = e->valuestring;
        if (strpbrk(name, "/\\.") || strchr(name, ':'))
            return failf(L, e, "\"plugins\": '%s' is a path; a scene may only name plugins (like "
                         "\"ggx\"), never paths: load plugin files with --plugin or "
                         "SHADELAB_PLUGIN_PATH", name);
        for (const char *c = name; *c; c++)
            if (!isalnum((unsigned char)*c) && *c != '_' && *c != '-')
                return failf(L, e, "\"plugins\": '%s' is not a plugin name (letters, digits, '_' "
                             "and '-' only)", name);
        bool dup = false;
        for (int i = 0; i < L->scene->plugin_count; i++) dup = dup || strcmp(L->scene->plugins[i], name) == 0;
        if (dup) {
            warnf(L, e, "\"plugins\": '%s' is listed twice", name);
            continue;
        }
        char **p = realloc(L->scene->plugins, sizeof(char *) * (size_t)(L->scene->plugin_count + 1));
        if (!p) return failf(L, e, "out of memory");
        L->scene->plugins = p;
        if (!(p[L->scene->plugin_count] = strdup(name))) return failf(L, e, "out of memory");
        L->scene->plugin_count++;
    }
    return true;
}

static bool load_params(loader *L, const cJSON *obj) {
    char buf[96];
    if (!cJSON_IsObject(obj))
        return failf(L, obj, "\"params\" must be an object of \"plugin.param\": value, found %s",
                     describe(obj, buf, sizeof buf));
    if (!check_keys(L, obj, "params", NULL, 0, true)) return false;
    for (const cJSON *e = obj->child; e; e = e->next) {
        if (strcmp(e->string, "comment") == 0) continue;
        const char *dot = strchr(e->string, '.');
        if (!dot || dot == e->string || !dot[1] || strpbrk(e->string, " \t\n"))
            return failf(L, e, "\"params\": key \"%s\" must be a parameter id \"plugin.param\" "
                         "(or \"material.NAME.key\" / \"light.NAME.key\")", e->string);
        if (!get_prop(L, e, "params", &L->scene->params)) return false;
    }
    return true;
}

/* The loader's own material keys; every other key is a property whose meaning (and whose near
 * misses) only the loaded plugins' schema knows: the application checks it (sl_app). */
static const char *const material_keys[] = {"name", "model", "cast_shadows"};

static bool load_materials(loader *L, const cJSON *arr) {
    char buf[96];
    if (!cJSON_IsArray(arr))
        return failf(L, arr, "\"materials\" must be an array of objects, found %s", describe(arr, buf, sizeof buf));
    if (!check_count(L, arr, "materials")) return false;
    int index = 0;
    for (const cJSON *o = arr->child; o; o = o->next, index++) {
        if (!cJSON_IsObject(o))
            return failf(L, o, "material #%d must be an object, found %s", index, describe(o, buf, sizeof buf));
        char name[256], ctx[300];
        if (!get_name(L, o, "material", index, true, name, sizeof name)) return false;
        snprintf(ctx, sizeof ctx, "material '%s'", name);
        int prev = sl_scene_find_material(L->scene, name);
        if (prev >= 0)
            return failf(L, cJSON_GetObjectItemCaseSensitive(o, "name"), "duplicate material name "
                         "'%s' (%s); names must be unique", name,
                         first_defined(L->scene->materials[prev].line, buf, sizeof buf));
        const char *model = "lambert";
        const cJSON *v;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "model")) && !get_string(L, v, ctx, &model)) return false;
        int mi = sl_scene_add_material(L->scene, name, model);
        if (mi < 0) return failf(L, o, "out of memory");
        L->scene->materials[mi].line = line_of(L, o);
        bool cast = true;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "cast_shadows")) && !get_bool(L, v, ctx, &cast)) return false;
        L->scene->materials[mi].cast_shadows = cast;
        if (!check_keys(L, o, ctx, KEYS(material_keys), true)) return false;
        for (const cJSON *e = o->child; e; e = e->next) {
            if (in_list(e->string, KEYS(material_keys)) || strcmp(e->string, "comment") == 0) continue;
            if (!get_prop(L, e, ctx, &L->scene->materials[mi].props)) return false;
        }
    }
    return true;
}

static const char *const camera_keys[] = {"name", "position", "target", "up", "fov_y", "near", "far",
                                          "type", "xmag", "ymag"};
static const char *const camera_types[] = {"perspective", "orthographic"};

static bool load_cameras(loader *L, const cJSON *arr) {
    char buf[96];
    if (!cJSON_IsArray(arr))
        return failf(L, arr, "\"cameras\" must be an array of objects, found %s", describe(arr, buf, sizeof buf));
    if (!check_count(L, arr, "cameras")) return false;
    int index = 0;
    for (const cJSON *o = arr->child; o; o = o->next, index++) {
        if (!cJSON_IsObject(o))
            return failf(L, o, "camera #%d must be an object, found %s", index, describe(o, buf, sizeof buf));
        char name[256], ctx[300];
        if (!get_name(L, o, "camera", index, false, name, sizeof name)) return false;
        snprintf(ctx, sizeof ctx, "camera '%s'", name);
        int prev = sl_scene_find_camera(L->scene, name);
        if (prev >= 0)
            return failf(L, o, "duplicate camera name '%s' (%s); names must be unique", name,
                         first_defined(prev < L->camera_lines_n ? L->camera_lines[prev] : 0, buf, sizeof buf));
        if (!check_keys(L, o, ctx, KEYS(camera_keys), false)) return false;
        int ci = sl_scene_add_camera(L->scene, name);
        if (ci < 0 || !remember_line(&L->camera_lines, &L->camera_lines_n, ci, line_of(L, o)))
            return failf(L, o, "out of memory");
        sl_camera *c = &L->scene->cameras[ci];
        const cJSON *v;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "position")) && !get_vec(L, v, ctx, 3, c->position, false)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "target")) && !get_vec(L, v, ctx, 3, c->target, false)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "up")) && !get_direction(L, v, ctx, c->up)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "fov_y")) &&
            !get_number(L, v, ctx, &c->fov_y_deg, 0.0, true, 179.0)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "near")) && !get_number(L, v, ctx, &c->znear, 0.0, true, FLT_MAX)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "far")) && !get_number(L, v, ctx, &c->zfar, 0.0, true, FLT_MAX)) return false;
        /* glTF 2.0 cameras: "orthographic" with half-extents xmag, ymag (the viewport's aspect
         * decides the width; xmag is kept for --list-cameras and the file's intent) */
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "type"))) {
            const char *type;
            if (!get_string(L, v, ctx, &type)) return false;
            if (!in_list(type, KEYS(camera_types))) {
                char hint[600];
                key_hint(hint, sizeof hint, type, KEYS(camera_types), "types");
                return failf(L, v, "%s: unknown camera type '%s'%s", ctx, type, hint);
            }
            c->orthographic = !strcmp(type, "orthographic");
        }
        c->ymag = c->xmag = 1.0f;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "ymag")) && !get_number(L, v, ctx, &c->ymag, 0.0, true, FLT_MAX)) return false;
        c->xmag = c->ymag;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "xmag")) && !get_number(L, v, ctx, &c->xmag, 0.0, true, FLT_MAX)) return false;
        if (!c->orthographic && (cJSON_GetObjectItemCaseSensitive(o, "xmag") || cJSON_GetObjectItemCaseSensitive(o, "ymag")))
            warnf(L, o, "%s: \"xmag\"/\"ymag\" apply to \"type\": \"orthographic\" cameras only (ignored)", ctx);
        if (!(c->zfar > c->znear))
            return failf(L, o, "%s: \"far\" (%g) must be greater than \"near\" (%g)", ctx, c->zfar, c->znear);
        /* depth precision: measured on the 32-bit float depth buffer, far/near = 1e7 already
         * z-fights where a sphere meets a plane, 1e9 renders black; refuse past 1e7, warn past 1e5 */
        double ratio = (double)c->zfar / c->znear;
        if (ratio > 1e7)
            return failf(L, o, "%s: far/near = %g is beyond the depth buffer's precision (at most 1e7; raise \"near\")",
                         ctx, ratio);
        if (ratio > 1e5)
            warnf(L, o, "%s: far/near = %g loses depth precision (surfaces close together may z-fight); raise \"near\"",
                  ctx, ratio);
        float d[3] = {c->target[0] - c->position[0], c->target[1] - c->position[1], c->target[2] - c->position[2]};
        float dl = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(dl > 0.0f)) return failf(L, o, "%s: \"position\" and \"target\" are the same point", ctx);
        float x[3] = {d[1] * c->up[2] - d[2] * c->up[1], d[2] * c->up[0] - d[0] * c->up[2],
                      d[0] * c->up[1] - d[1] * c->up[0]};
        if (!(sqrtf(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) > 1e-6f * dl))
            return failf(L, o, "%s: \"up\" is parallel to the viewing direction (target − position)", ctx);
    }
    return true;
}

static const char *const light_keys[] = {"name", "type", "position", "direction", "color",
                                         "intensity", "enabled", "cast_shadows"};

static bool load_lights(loader *L, const cJSON *arr) {
    char buf[96];
    if (!cJSON_IsArray(arr))
        return failf(L, arr, "\"lights\" must be an array of objects, found %s", describe(arr, buf, sizeof buf));
    if (!check_count(L, arr, "lights")) return false;
    int index = 0;
    for (const cJSON *o = arr->child; o; o = o->next, index++) {
        if (!cJSON_IsObject(o))
            return failf(L, o, "light #%d must be an object, found %s", index, describe(o, buf, sizeof buf));
        char name[256], ctx[300];
        if (!get_name(L, o, "light", index, false, name, sizeof name)) return false;
        snprintf(ctx, sizeof ctx, "light '%s'", name);
        int prev = sl_scene_find_light(L->scene, name);
        if (prev >= 0)
            return failf(L, o, "duplicate light name '%s' (%s); names must be unique", name,
                         first_defined(L->scene->lights[prev].line, buf, sizeof buf));
        const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, "type");
        const char *type = NULL;
        if (!v) return failf(L, o, "%s has no \"type\" (\"directional\", \"point\" or a plugin's light type such as \"spot\")", ctx);
        if (!get_string(L, v, ctx, &type)) return false;
        if (!check_keys(L, o, ctx, KEYS(light_keys), true)) return false;
        int li = sl_scene_add_light(L->scene, name, type);
        if (li < 0) return failf(L, o, "out of memory");
        sl_light *l = &L->scene->lights[li];
        l->line = line_of(L, o);
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "position")) && !get_vec(L, v, ctx, 3, l->position, false)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "direction")) && !get_direction(L, v, ctx, l->direction)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "color")) && !get_vec(L, v, ctx, 3, l->color, true)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "intensity")) && !get_number(L, v, ctx, &l->intensity, 0.0, false, FLT_MAX)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "enabled")) && !get_bool(L, v, ctx, &l->enabled)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "cast_shadows")) && !get_bool(L, v, ctx, &l->cast_shadows)) return false;
        if (strcmp(type, "directional") == 0 && cJSON_GetObjectItemCaseSensitive(o, "position"))
            warnf(L, cJSON_GetObjectItemCaseSensitive(o, "position"), "%s: a directional light has no position (ignored)", ctx);
        if (strcmp(type, "point") == 0 && cJSON_GetObjectItemCaseSensitive(o, "direction"))
            warnf(L, cJSON_GetObjectItemCaseSensitive(o, "direction"), "%s: a point light has no direction (ignored)", ctx);
        for (const cJSON *e = o->child; e; e = e->next) {
            if (in_list(e->string, KEYS(light_keys)) || strcmp(e->string, "comment") == 0) continue;
            if (!get_prop(L, e, ctx, &L->scene->lights[li].props)) return false;
        }
    }
    return true;
}

/* Procedural texture specs ("checker:…", "constant:…") are not files. */
static bool is_procedural_spec(const char *s) {
    static const char *const kinds[] = {"checker:", "grid:", "constant:", "gradient", "uv"};
    for (int i = 0; i < 5; i++) {
        size_t n = strlen(kinds[i]);
        if (strncmp(s, kinds[i], n) == 0 && (kinds[i][n - 1] == ':' || s[n] == 0 || s[n] == ':')) return true;
    }
    return false;
}

static const char *const environment_keys[] = {"map", "color", "intensity", "yaw"};

static bool load_environment(loader *L, const cJSON *o) {
    char buf[96];
    const char *ctx = "environment";
    if (!cJSON_IsObject(o)) return failf(L, o, "\"environment\" must be an object, found %s", describe(o, buf, sizeof buf));
    if (!check_keys(L, o, ctx, KEYS(environment_keys), true)) return false;
    sl_environment *env = &L->scene->environment;
    const cJSON *v;
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "map"))) {
        const char *map;
        if (!get_string(L, v, ctx, &map)) return false;
        if (is_procedural_spec(map)) {
            env->map = strdup(map);
        } else {
            char why[2048];
            env->map = sl_scene_resolve_path(L->scene, L->data_dir, map, why, sizeof why);
            if (!env->map) return failf(L, v, "environment map: %s", why);
        }
        if (!env->map) return failf(L, v, "out of memory");
    }
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "color")) && !get_vec(L, v, ctx, 3, env->color, true)) return false;
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "intensity")) && !get_number(L, v, ctx, &env->intensity, 0.0, false, FLT_MAX)) return false;
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "yaw")) && !get_number(L, v, ctx, &env->yaw_deg, -FLT_MAX, false, FLT_MAX)) return false;
    /* the constant radiance is what reaches the colour target: it must fit (RGBA16F: 65504) */
    for (int c = 0; c < 3; c++)
        if ((double)env->color[c] * env->intensity > SL_MAX_RADIANCE)
            return failf(L, o, "%s: color x intensity = %g is more radiance than the colour target holds (at most %g)",
                         ctx, (double)env->color[c] * env->intensity, SL_MAX_RADIANCE);
    for (const cJSON *e = o->child; e; e = e->next) {
        if (in_list(e->string, KEYS(environment_keys)) || strcmp(e->string, "comment") == 0) continue;
        if (!get_prop(L, e, ctx, &env->props)) return false;
    }
    return true;
}

/* ---- nodes and meshes ------------------------------------------------------------------- */

static int default_material(loader *L) {
    if (L->default_material >= 0) return L->default_material;
    int mi = sl_scene_find_material(L->scene, "default");
    if (mi < 0) {
        mi = sl_scene_add_material(L->scene, "default", "lambert");
        if (mi < 0) return -1;
        float grey[3] = {0.8f, 0.8f, 0.8f};
        if (!sl_prop_set_vec(&L->scene->materials[mi].props, "base_color", grey, 3, 0)) return -1;
    }
    return L->default_material = mi;
}

static const char *const primitive_names[] = {"sphere", "plane", "cube", "torus", "teapot"};
static const char *const sphere_keys[] = {"primitive", "radius", "segments", "rings"};
static const char *const plane_keys[] = {"primitive", "size", "subdivisions"};
static const char *const cube_keys[] = {"primitive", "size"};
static const char *const torus_keys[] = {"primitive", "major_radius", "minor_radius", "segments", "sides"};
static const char *const teapot_keys[] = {"primitive", "size", "tessellation"};
static const char *const file_keys[] = {"file", "model", "flip_v"};

static bool load_primitive(loader *L, const cJSON *mesh, const char *ctx, const char *kind,
                           sl_mesh_data *out) {
    const cJSON *v;
#define OPT_NUM(key, dst, min, excl, max) \
    if ((v = cJSON_GetObjectItemCaseSensitive(mesh, key)) && !get_number(L, v, ctx, dst, min, excl, max)) return false
#define OPT_INT(key, dst, min, max) \
    if ((v = cJSON_GetObjectItemCaseSensitive(mesh, key)) && !get_int(L, v, ctx, dst, min, max)) return false
    bool ok;
    if (strcmp(kind, "sphere") == 0) {
        float radius = 1.0f;
        int segments = 64, rings = 32;
        if (!check_keys(L, mesh, ctx, KEYS(sphere_keys), false)) return false;
        OPT_NUM("radius", &radius, 0.0, true, FLT_MAX);
        OPT_INT("segments", &segments, 3, 2048);
        OPT_INT("rings", &rings, 2, 1024);
        ok = sl_mesh_sphere(out, radius, segments, rings);
    } else if (strcmp(kind, "plane") == 0) {
        float size[2] = {10.0f, 10.0f};
        int subdivisions = 1;
        if (!check_keys(L, mesh, ctx, KEYS(plane_keys), false)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(mesh, "size"))) {
            if (cJSON_IsArray(v)) {
                if (!get_vec(L, v, ctx, 2, size, false)) return false;
                if (!(size[0] > 0 && size[1] > 0))
                    return failf(L, v, "%s: \"size\" must be a number > 0 or an array [x, z] of two numbers > 0", ctx);
            } else {
                if (!get_number(L, v, ctx, &size[0], 0.0, true, FLT_MAX)) return false;
                size[1] = size[0];
            }
        }
        OPT_INT("subdivisions", &subdivisions, 1, 1024);
        ok = sl_mesh_plane(out, size[0], size[1], subdivisions);
    } else if (strcmp(kind, "cube") == 0) {
        float size = 1.0f;
        if (!check_keys(L, mesh, ctx, KEYS(cube_keys), false)) return false;
        OPT_NUM("size", &size, 0.0, true, FLT_MAX);
        ok = sl_mesh_cube(out, size);
    } else if (strcmp(kind, "torus") == 0) {
        float major = 1.0f, minor = 0.25f;
        int segments = 64, sides = 32;
        if (!check_keys(L, mesh, ctx, KEYS(torus_keys), false)) return false;
        OPT_NUM("major_radius", &major, 0.0, true, FLT_MAX);
        OPT_NUM("minor_radius", &minor, 0.0, true, FLT_MAX);
        OPT_INT("segments", &segments, 3, 2048);
        OPT_INT("sides", &sides, 3, 1024);
        if (!(minor < major))
            return failf(L, mesh, "%s: \"minor_radius\" (%g) must be smaller than \"major_radius\" (%g)",
                         ctx, minor, major);
        ok = sl_mesh_torus(out, major, minor, segments, sides);
    } else {
        float size = 1.0f;
        int tessellation = 16;
        if (!check_keys(L, mesh, ctx, KEYS(teapot_keys), false)) return false;
        OPT_NUM("size", &size, 0.0, true, FLT_MAX);
        OPT_INT("tessellation", &tessellation, 1, 128);
        ok = sl_mesh_teapot(out, size, tessellation);
    }
#undef OPT_NUM
#undef OPT_INT
    if (!ok) return failf(L, mesh, "%s: could not build the %s (out of memory?)", ctx, kind);
    return true;
}

static bool load_mesh(loader *L, const cJSON *mesh, int node, int material, const char *node_name) {
    char buf[96], ctx[300];
    snprintf(ctx, sizeof ctx, "mesh of node '%s'", node_name);
    if (!cJSON_IsObject(mesh))
        return failf(L, mesh, "%s: \"mesh\" must be an object ({\"primitive\": …} or {\"file\": …}), found %s",
                     ctx, describe(mesh, buf, sizeof buf));
    const cJSON *prim = cJSON_GetObjectItemCaseSensitive(mesh, "primitive");
    const cJSON *file = cJSON_GetObjectItemCaseSensitive(mesh, "file");
    if (prim && file) return failf(L, mesh, "%s: give either \"primitive\" or \"file\", not both", ctx);
    if (!prim && !file) {
        const char *const both[] = {"primitive", "file"};
        char hint[600] = "";
        if (mesh->child) key_hint(hint, sizeof hint, mesh->child->string, KEYS(both), "keys");
        return failf(L, mesh, "%s: needs \"primitive\" (sphere, plane, cube, torus, teapot) or \"file\"%s",
                     ctx, hint);
    }
    if (prim) {
        const char *kind;
        if (!get_string(L, prim, ctx, &kind)) return false;
        if (!in_list(kind, KEYS(primitive_names))) {
            char hint[600];
            key_hint(hint, sizeof hint, kind, KEYS(primitive_names), "primitives");
            return failf(L, prim, "%s: unknown primitive '%s'%s", ctx, kind, hint);
        }
        sl_mesh_data data;
        if (!load_primitive(L, mesh, ctx, kind, &data)) return false;
        int mat = material >= 0 ? material : default_material(L);
        int mi = mat < 0 ? -1 : sl_scene_add_mesh(L->scene, node_name, &data, mat);
        if (mi < 0 || !sl_scene_node_add_mesh(L->scene, node, mi)) return failf(L, mesh, "out of memory");
        return true;
    }
    const char *rel, *model = NULL;
    if (!get_string(L, file, ctx, &rel)) return false;
    const cJSON *v;
    if ((v = cJSON_GetObjectItemCaseSensitive(mesh, "model")) && !get_string(L, v, ctx, &model)) return false;
    bool flip_v = false;
    if ((v = cJSON_GetObjectItemCaseSensitive(mesh, "flip_v"))) {
        if (!cJSON_IsBool(v)) return failf(L, v, "%s: \"flip_v\" must be true or false", ctx);
        flip_v = cJSON_IsTrue(v);
    }
    if (!check_keys(L, mesh, ctx, KEYS(file_keys), false)) return false;
    char why[2048];
    char *path = sl_scene_resolve_path(L->scene, L->data_dir, rel, why, sizeof why);
    if (!path) return failf(L, file, "%s: mesh file %s", ctx, why);
    int first_material = L->scene->material_count, first_mesh = L->scene->mesh_count;
    sl_scene_update_transforms(L->scene); /* imported lights/cameras need this node's world */
    bool ok = sl_scene_import_file(L->scene, path, node, why, sizeof why);
    free(path);
    if (!ok) return failf(L, file, "%s: %s", ctx, why);
    for (int i = first_mesh; i < L->scene->mesh_count; i++) {
        if (material >= 0) L->scene->meshes[i].material = material;
        /* Assets authored for flipped textures (v = 0 at the image bottom, e.g. models whose
         * textures three.js loads with flipY): v becomes 1 − v and the tangent frames are
         * regenerated, since flipping v mirrors the handedness. */
        sl_mesh_data *d = &L->scene->meshes[i].data;
        if (flip_v && d->uvs) {
            for (int k = 0; k < d->vertex_count; k++) d->uvs[2 * k + 1] = 1.0f - d->uvs[2 * k + 1];
            sl_mesh_generate_tangents(d);
        }
    }
    if (model)
        for (int i = first_material; i < L->scene->material_count; i++) {
            char *m = strdup(model);
            if (!m) return failf(L, file, "out of memory");
            free(L->scene->materials[i].model);
            L->scene->materials[i].model = m;
        }
    return true;
}

static const char *const node_keys[] = {"name", "parent", "children", "translate", "rotate",
                                        "scale", "matrix", "material", "mesh", "tags"};
#define SL_NODE_MAX_TAGS 16

/* Whether the linear part of a column-major 4×4 transform has rank ≤ 1 (every 2×2 minor zero,
 * relative to its columns' size): the node collapses to a line or a point, nothing to see. A
 * rank-2 transform (one zero scale, a flattening matrix) draws flat geometry, which the forward
 * pass shades with the geometric normal (stability_core singular_transform). */
static bool transform_collapses(const float *m) {
    const double a[3] = {m[0], m[1], m[2]}, b[3] = {m[4], m[5], m[6]}, c[3] = {m[8], m[9], m[10]};
    const double *col[3] = {a, b, c};
    double big = 0, minor = 0;
    for (int i = 0; i < 3; i++) {
        const double *x = col[i], *y = col[(i + 1) % 3];
        double cx = x[1] * y[2] - x[2] * y[1], cy = x[2] * y[0] - x[0] * y[2], cz = x[0] * y[1] - x[1] * y[0];
        minor = fmax(minor, sqrt(cx * cx + cy * cy + cz * cz));
        big = fmax(big, x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    }
    return !(minor > 1e-12 * big);
}

static bool load_node(loader *L, const cJSON *o, int parent, int depth, int *counter) {
    char buf[96];
    int index = (*counter)++;
    if (index >= MAX_ITEMS) return failf(L, o, "more than %d nodes; at most %d are allowed", MAX_ITEMS, MAX_ITEMS);
    if (!cJSON_IsObject(o)) return failf(L, o, "node #%d must be an object, found %s", index, describe(o, buf, sizeof buf));
    if (depth > SL_SCENE_MAX_DEPTH)
        return failf(L, o, "nodes are nested deeper than %d levels of \"children\"", SL_SCENE_MAX_DEPTH);
    char name[256], ctx[300];
    if (!get_name(L, o, "node", index, false, name, sizeof name)) return false;
    snprintf(ctx, sizeof ctx, "node '%s'", name);
    int prev = sl_scene_find_node(L->scene, name);
    if (prev >= 0)
        return failf(L, cJSON_GetObjectItemCaseSensitive(o, "name"), "duplicate node name '%s' "
                     "(%s); names must be unique", name,
                     first_defined(prev < L->node_lines_n ? L->node_lines[prev] : 0, buf, sizeof buf));
    if (!check_keys(L, o, ctx, KEYS(node_keys), false)) return false;
    const cJSON *v;
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "parent"))) {
        const char *pname;
        if (!get_string(L, v, ctx, &pname)) return false;
        if (parent >= 0)
            return failf(L, v, "%s is inside the \"children\" of '%s' and also names \"parent\": "
                         "use one of the two", ctx, L->scene->nodes[parent].name);
        parent = sl_scene_find_node(L->scene, pname);
        if (parent < 0) {
            const char **names = malloc(sizeof(char *) * (size_t)(L->scene->node_count + 1));
            char hint[600] = "";
            if (names) {
                for (int i = 0; i < L->scene->node_count; i++) names[i] = L->scene->nodes[i].name;
                const char *near = nearest(pname, names, L->scene->node_count);
                if (near) snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
                free(names);
            }
            return failf(L, v, "%s: unknown parent '%s'; a parent must be a node defined earlier "
                         "in the file%s", ctx, pname, hint);
        }
        int d = 0;
        for (int p = parent; p >= 0; p = L->scene->nodes[p].parent) d++;
        if (d > SL_SCENE_MAX_DEPTH)
            return failf(L, v, "%s: nodes are nested deeper than %d levels", ctx, SL_SCENE_MAX_DEPTH);
    }
    int ni = sl_scene_add_node(L->scene, name, parent);
    if (ni < 0 || !remember_line(&L->node_lines, &L->node_lines_n, ni, line_of(L, o)))
        return failf(L, o, "out of memory");

    /* transform: "matrix", or translate · rotate · scale */
    const cJSON *mat = cJSON_GetObjectItemCaseSensitive(o, "matrix");
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(o, "translate");
    const cJSON *r = cJSON_GetObjectItemCaseSensitive(o, "rotate");
    const cJSON *s = cJSON_GetObjectItemCaseSensitive(o, "scale");
    if (mat) {
        if (t || r || s)
            return failf(L, mat, "%s: give either \"matrix\" or \"translate\"/\"rotate\"/\"scale\", not both", ctx);
        float m[16];
        if (!get_vec(L, mat, ctx, 16, m, false)) return false;
        for (int k = 0; k < 16; k++)
            if (fabsf(m[k]) > SL_SCENE_MAX_EXTENT)
                return failf(L, mat, "%s: \"matrix\" element %d is %g; beyond %g float32 positions collapse", ctx, k,
                             m[k], SL_SCENE_MAX_EXTENT);
        if (transform_collapses(m))
            return failf(L, mat, "%s: \"matrix\" collapses the node to a line or a point (its 3x3 part has rank < 2, "
                         "e.g. all zero): nothing would be visible", ctx);
        memcpy(L->scene->nodes[ni].local, m, sizeof m);
    } else {
        float tr[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, sc[3] = {1, 1, 1};
        if (t && !get_vec(L, t, ctx, 3, tr, false)) return false;
        for (int c = 0; t && c < 3; c++)
            if (fabsf(tr[c]) > SL_SCENE_MAX_EXTENT)
                return failf(L, t, "%s: \"translate\" %g is beyond %g, where float32 positions collapse", ctx, tr[c],
                             SL_SCENE_MAX_EXTENT);
        if (r) {
            int n = cJSON_IsArray(r) ? cJSON_GetArraySize(r) : 0;
            if (n == 4) {
                if (!get_vec(L, r, ctx, 4, q, false)) return false;
                double len = sqrt((double)q[0] * q[0] + (double)q[1] * q[1] + (double)q[2] * q[2] + (double)q[3] * q[3]);
                if (!(len > 1e-12) || !isfinite(len))
                    return failf(L, r, "%s: \"rotate\" quaternion [x, y, z, w] must not be zero", ctx);
                for (int c = 0; c < 4; c++) q[c] = (float)(q[c] / len);
            } else {
                float deg[3];
                if (!cJSON_IsArray(r) || n != 3)
                    return failf(L, r, "%s: \"rotate\" must be [x, y, z] Euler angles in degrees or a "
                                 "quaternion [x, y, z, w], found %s", ctx, describe(r, buf, sizeof buf));
                if (!get_vec(L, r, ctx, 3, deg, false)) return false;
                sl_quat_from_euler_deg(q, deg);
            }
        }
        if (s) {
            if (cJSON_IsArray(s)) {
                if (!get_vec(L, s, ctx, 3, sc, false)) return false;
            } else if (number_ok(s)) {
                sc[0] = sc[1] = sc[2] = (float)s->valuedouble;
            } else {
                return failf(L, s, "%s: \"scale\" must be a number or an array of 3 numbers, found %s",
                             ctx, describe(s, buf, sizeof buf));
            }
            if ((sc[0] == 0) + (sc[1] == 0) + (sc[2] == 0) >= 2)
                return failf(L, s, "%s: \"scale\" must not be zero in more than one axis (the node would collapse to "
                             "a line or a point: nothing visible); one zero axis flattens it", ctx);
            for (int c = 0; c < 3; c++)
                if (fabsf(sc[c]) > SL_SCENE_MAX_EXTENT)
                    return failf(L, s, "%s: \"scale\" %g is beyond %g, where float32 positions collapse", ctx, sc[c],
                                 SL_SCENE_MAX_EXTENT);
        }
        sl_mat4_from_trs(L->scene->nodes[ni].local, tr, q, sc);
    }

    /* "tags": names that VERTEX chunks with when_node_tag select (ABI 1.6); inherited by children */
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "tags"))) {
        if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) > SL_NODE_MAX_TAGS)
            return failf(L, v, "%s: \"tags\" must be an array of at most %d names, found %s", ctx, SL_NODE_MAX_TAGS,
                         describe(v, buf, sizeof buf));
        sl_node *nd = &L->scene->nodes[ni];
        nd->tags = calloc(SL_NODE_MAX_TAGS, sizeof *nd->tags);
        if (!nd->tags) return failf(L, v, "out of memory");
        for (const cJSON *e = v->child; e; e = e->next) {
            if (!cJSON_IsString(e))
                return failf(L, e, "%s: each tag must be a string, found %s", ctx, describe(e, buf, sizeof buf));
            const char *tag = e->valuestring;
            size_t len = strlen(tag);
            if (!len || len > 64 || strspn(tag, "abcdefghijklmnopqrstuvwxyz0123456789_-") != len)
                return failf(L, e, "%s: tag '%.80s' must be 1 to 64 characters of a-z, 0-9, '_' and '-'", ctx, tag);
            if (!(nd->tags[nd->tag_count] = strdup(tag))) return failf(L, e, "out of memory");
            nd->tag_count++;
        }
    }

    int material = -1;
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "material"))) {
        const char *mname;
        if (!get_string(L, v, ctx, &mname)) return false;
        material = sl_scene_find_material(L->scene, mname);
        if (material < 0) {
            const char **names = malloc(sizeof(char *) * (size_t)(L->scene->material_count + 1));
            char hint[600] = "";
            if (names) {
                for (int i = 0; i < L->scene->material_count; i++) names[i] = L->scene->materials[i].name;
                const char *near = nearest(mname, names, L->scene->material_count);
                if (near) snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
                free(names);
            }
            return failf(L, v, "%s: unknown material '%s'; materials must be defined in "
                         "\"materials\"%s", ctx, mname, hint);
        }
        if (!cJSON_GetObjectItemCaseSensitive(o, "mesh"))
            warnf(L, v, "%s: \"material\" has no effect on a node without \"mesh\"", ctx);
    }
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "mesh")) && !load_mesh(L, v, ni, material, name)) return false;

    if ((v = cJSON_GetObjectItemCaseSensitive(o, "children"))) {
        if (!cJSON_IsArray(v))
            return failf(L, v, "%s: \"children\" must be an array of nodes, found %s", ctx, describe(v, buf, sizeof buf));
        for (const cJSON *c = v->child; c; c = c->next)
            if (!load_node(L, c, ni, depth + 1, counter)) return false;
    }
    return true;
}

static bool load_nodes(loader *L, const cJSON *arr) {
    char buf[96];
    if (!cJSON_IsArray(arr))
        return failf(L, arr, "\"nodes\" must be an array of objects, found %s", describe(arr, buf, sizeof buf));
    int counter = 0;
    for (const cJSON *o = arr->child; o; o = o->next)
        if (!load_node(L, o, -1, 0, &counter)) return false;
    return true;
}

/* ---- parse errors ----------------------------------------------------------------------- */

/* Why cJSON stopped at `at`: a best guess at the usual mistakes. */
static void parse_cause(const char *text, size_t len, size_t at, char *out, size_t size) {
    size_t first = 0;
    while (first < len && strchr(" \t\r\n", text[first]) && text[first]) first++;
    if (first >= len) {
        snprintf(out, size, "the file is empty (expected a JSON object { … })");
        return;
    }
    /* depth and string state up to `at` */
    int depth = 0, max_depth = 0;
    bool in_string = false;
    char last = 0; /* last significant character before `at` */
    for (size_t i = 0; i < at && i < len; i++) {
        char c = text[i];
        if (in_string) {
            if (c == '\\') i++;
            else if (c == '"') in_string = false, last = '"';
            continue;
        }
        if (c == '"') in_string = true;
        else if (c == '{' || c == '[') depth++;
        else if (c == '}' || c == ']') depth--;
        if (depth > max_depth) max_depth = depth;
        if ((unsigned char)c > 32) last = c;
    }
    char c = at < len ? text[at] : 0;
    if (max_depth >= CJSON_NESTING_LIMIT - 1)
        snprintf(out, size, "nested deeper than %d levels", CJSON_NESTING_LIMIT);
    else if (in_string || (c == 0 && last == '"' && at >= len))
        snprintf(out, size, "unterminated string");
    else if (at < len && c == 0)
        snprintf(out, size, "unexpected byte 0x00 (a NUL byte: is this a binary file?)");
    else if (at >= len)
        snprintf(out, size, "unexpected end of file (%d unclosed '{' or '[')", depth > 0 ? depth : 1);
    else if (c == '"') {
        size_t i = at + 1;
        while (i < len && text[i] != '"' && text[i] != '\n') i += text[i] == '\\' ? 2 : 1;
        if (i >= len || text[i] == '\n') snprintf(out, size, "unterminated string");
        else if (last && !strchr("{[,:", last)) snprintf(out, size, "missing ',' before this value");
        else snprintf(out, size, "invalid string (bad escape sequence or control character?)");
    } else if (c == '/')
        snprintf(out, size, "comments are not allowed in JSON (use a \"comment\" key)");
    else if (c == '\'')
        snprintf(out, size, "strings and keys must use double quotes");
    else if ((c == '}' || c == ']') && last == ',')
        snprintf(out, size, "trailing comma before '%c'", c);
    else if ((c == '}' || c == ']' || c == ',') && last == ':')
        snprintf(out, size, "missing value after ':'");
    else if (depth == 0 && at > first)
        snprintf(out, size, "unexpected text after the end of the top-level object");
    else if (c == 'N' || c == 'I' || (c == '-' && at + 1 < len && text[at + 1] == 'I'))
        snprintf(out, size, "NaN and Infinity are not JSON numbers");
    else if ((c == '"' || isalnum((unsigned char)c) || c == '-' || c == '{' || c == '[') &&
             last && !strchr("{[,:", last))
        snprintf(out, size, "missing ',' before this value");
    else if (isalpha((unsigned char)c))
        snprintf(out, size, "unexpected '%c' (keys and strings must be quoted; the literals are "
                 "true, false and null)", c);
    else if ((unsigned char)c < 32 || (unsigned char)c >= 127)
        snprintf(out, size, "unexpected byte 0x%02x", (unsigned char)c);
    else
        snprintf(out, size, "unexpected '%c'", c);
}

static bool fail_parse(loader *L, size_t at) {
    /* cJSON skips every byte < 32 as whitespace; JSON allows only space, tab, CR and LF, so a
     * stray control byte before the failure point is the likelier culprit. */
    bool in_string = false;
    for (size_t i = 0; i < at && i < L->len; i++) {
        char c = L->text[i];
        if (in_string) {
            if (c == '\\') i++;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if ((unsigned char)c < 32 && !strchr("\t\r\n", c)) {
            at = i;
            break;
        }
    }
    /* Where cJSON expected a string (a key after '{' or ',') it reports the byte AFTER the
     * offending one: step back onto it. */
    if (at > 0 && at <= L->len) {
        char culprit = L->text[at - 1];
        size_t j = at - 1;
        while (j > 0 && strchr(" \t\r\n", L->text[j - 1])) j--;
        char before = j > 0 ? L->text[j - 1] : 0;
        /* innermost open bracket before the culprit: only objects expect keys */
        char stack[CJSON_NESTING_LIMIT + 2];
        int depth = 0;
        bool str = false;
        for (size_t i = 0; i + 1 < at; i++) {
            char c = L->text[i];
            if (str) {
                if (c == '\\') i++;
                else if (c == '"') str = false;
            } else if (c == '"') {
                str = true;
            } else if ((c == '{' || c == '[') && depth < CJSON_NESTING_LIMIT + 1) {
                stack[depth++] = c;
            } else if ((c == '}' || c == ']') && depth > 0) {
                depth--;
            }
        }
        bool in_object = depth > 0 && stack[depth - 1] == '{';
        if (in_object && !str && culprit != '"' && !strchr(" \t\r\n,{[:", culprit) &&
            (before == '{' || before == ','))
            at--;
    }
    int line = 1;
    size_t line_start = 0;
    for (size_t i = 0; i < at && i < L->len; i++)
        if (L->text[i] == '\n') line++, line_start = i + 1;
    char cause[256];
    parse_cause(L->text, L->len, at, cause, sizeof cause);
    /* the offending line with a caret under the column */
    size_t end = line_start;
    while (end < L->len && L->text[end] != '\n' && end - line_start < 100) end++;
    size_t col = at - line_start;
    char snippet[256] = "";
    if (end > line_start && col <= end - line_start) {
        char caret[128];
        size_t n = col < sizeof caret - 2 ? col : sizeof caret - 2;
        for (size_t i = 0; i < n; i++) caret[i] = L->text[line_start + i] == '\t' ? '\t' : ' ';
        caret[n] = '^', caret[n + 1] = 0;
        snprintf(snippet, sizeof snippet, "\n    %.*s\n    %s", (int)(end - line_start),
                 L->text + line_start, caret);
    }
    L->failed = true;
    if (L->err && L->err_size)
        snprintf(L->err, L->err_size, "%s:%d:%zu: malformed JSON: %s%s", L->file, line, col + 1,
                 cause, snippet);
    return false;
}

/* ---- entry points ----------------------------------------------------------------------- */

static bool load(loader *L, const char *dir) {
    const char *text = L->text;
    if (L->len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) { /* UTF-8 byte order mark */
        L->text += 3;
        L->len -= 3;
    }
    const char *nul = memchr(L->text, 0, L->len);
    if (nul) return fail_parse(L, (size_t)(nul - L->text));
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithLengthOpts(L->text, L->len + 1, &end, true);
    if (!root) {
        size_t at = end && end >= L->text ? (size_t)(end - L->text) : 0;
        if (at > L->len) at = L->len;
        return fail_parse(L, at);
    }
    scan sc = {L->text, 0, L->len, 1, 0};
    walk(L, &sc, root, 0, 0);
    if (L->pos) qsort(L->pos, L->pos_count, sizeof *L->pos, cmp_pos);

    char buf[96];
    bool ok = true;
    sl_scene *s = L->scene;
    if (!cJSON_IsObject(root)) {
        ok = failf(L, root, "the top level must be a JSON object { … }, found %s",
                   describe(root, buf, sizeof buf));
        goto done;
    }
    if (!(s->path = strdup(L->file)) || (dir && !(s->dir = strdup(dir)))) {
        ok = failf(L, NULL, "out of memory");
        goto done;
    }
    s->environment.intensity = 1.0f;
    if (!check_keys(L, root, "top level", KEYS(top_keys), false)) {
        ok = false;
        goto done;
    }
    const cJSON *v;
    if (ok && (v = cJSON_GetObjectItemCaseSensitive(root, "plugins"))) ok = load_plugins(L, v);
    if (ok && (v = cJSON_GetObjectItemCaseSensitive(root, "params"))) ok = load_params(L, v);
    if (ok && (v = cJSON_GetObjectItemCaseSensitive(root, "materials"))) ok = load_materials(L, v);
    if (ok && (v = cJSON_GetObjectItemCaseSensitive(root, "cameras"))) ok = load_cameras(L, v);
    if (ok && (v = cJSON_GetObjectItemCaseSensitive(root, "nodes"))) ok = load_nodes(L, v);
    if (ok && (v = cJSON_GetObjectItemCaseSensitive(root, "lights"))) ok = load_lights(L, v);
    if (ok && (v = cJSON_GetObjectItemCaseSensitive(root, "environment"))) ok = load_environment(L, v);
    if (ok) sl_scene_update_transforms(s);
    if (ok && s->node_count) { /* how far the geometry reaches (imported meshes included) */
        double reach = 0;
        for (int c = 0; c < 3; c++) reach = fmax(reach, fmax(fabs(s->bounds_min[c]), fabs(s->bounds_max[c])));
        const cJSON *nodes = cJSON_GetObjectItemCaseSensitive(root, "nodes");
        if (!(reach <= SL_SCENE_MAX_EXTENT))
            ok = failf(L, nodes, "the scene's geometry reaches %g from the origin; beyond %g float32 positions "
                       "collapse (move it toward the origin or scale it down)", reach, SL_SCENE_MAX_EXTENT);
        else if (reach > SL_SCENE_WARN_EXTENT)
            warnf(L, nodes, "the scene's geometry reaches %g from the origin: float32 positions there have steps "
                  "of %g; detail smaller than that jitters", reach, reach / 8388608.0);
    }
done:
    cJSON_Delete(root);
    return ok && !L->failed;
}

static bool load_common(sl_scene *out, const char *text, size_t len, const char *name,
                        const char *dir, const sl_scene_load_opts *opts, char *err, size_t err_size) {
    if (err && err_size) err[0] = 0;
    sl_scene scene;
    memset(&scene, 0, sizeof scene);
    loader L = {.scene = &scene, .text = text, .len = len, .file = name ? name : "<scene>",
                .data_dir = opts && opts->data_dir && opts->data_dir[0] ? opts->data_dir : getenv("SHADELAB_DATA"),
                .err = err, .err_size = err_size, .default_material = -1};
    bool ok = load(&L, dir);
    free(L.pos);
    free(L.node_lines);
    free(L.camera_lines);
    if (!ok) {
        if (err && err_size && !err[0]) snprintf(err, err_size, "%s: could not load the scene", L.file);
        sl_scene_free(&scene);
        return false;
    }
    *out = scene;
    return true;
}

bool sl_scene_load_text(sl_scene *scene, const char *text, const char *name, const char *dir,
                        const sl_scene_load_opts *opts, char *err, size_t err_size) {
    if (!scene || !text) {
        if (err && err_size) snprintf(err, err_size, "sl_scene_load_text: no scene or no text");
        return false;
    }
    return load_common(scene, text, strlen(text), name, dir, opts, err, err_size);
}

bool sl_scene_load_default(sl_scene *scene, const sl_scene_load_opts *opts, char *err, size_t err_size) {
    return sl_scene_load_text(scene, sl_default_scene_json, "<default>", NULL, opts, err, err_size);
}

/* Detection by content, not by the extension: a binary glTF ("glTF" magic) or any file whose
 * first character is not '{' or '[' (OBJ, FBX, PLY… text or binary) is a model for assimp; a
 * JSON object with a top-level "asset" is a glTF document; other JSON is a shadelab scene. */
static bool is_model_head(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return false;
    unsigned char head[64];
    size_t n = fread(head, 1, sizeof head, f);
    fclose(f);
    if (n >= 4 && !memcmp(head, "glTF", 4)) return true;
    size_t i = n >= 3 && !memcmp(head, "\xEF\xBB\xBF", 3) ? 3 : 0;
    while (i < n && (head[i] == ' ' || head[i] == '\t' || head[i] == '\r' || head[i] == '\n')) i++;
    return i < n && head[i] != '{' && head[i] != '[';
}

static bool is_gltf_json(const char *text, size_t len) {
    if (!strstr(text, "\"asset\"")) return false; /* the scene format has no such key */
    cJSON *root = cJSON_ParseWithLength(text, len);
    bool yes = cJSON_IsObject(cJSON_GetObjectItemCaseSensitive(root, "asset"));
    cJSON_Delete(root);
    return yes;
}

bool sl_scene_load_file(sl_scene *scene, const char *path, const sl_scene_load_opts *opts,
                        char *err, size_t err_size) {
    if (err && err_size) err[0] = 0;
    if (!scene || !path || !path[0]) {
        if (err && err_size) snprintf(err, err_size, "no scene file given");
        return false;
    }
    struct stat st;
    if (stat(path, &st) != 0) {
        if (err && err_size) snprintf(err, err_size, "%s: %s", path, strerror(errno));
        return false;
    }
    if (S_ISDIR(st.st_mode)) {
        if (err && err_size) snprintf(err, err_size, "%s: is a directory, not a scene file", path);
        return false;
    }
    if (S_ISREG(st.st_mode) && is_model_head(path)) return sl_scene_load_model(scene, path, err, err_size);
    if (st.st_size > (off_t)MAX_SCENE_FILE_BYTES) {
        if (err && err_size)
            snprintf(err, err_size, "%s: %lld bytes is too large for a scene file (limit %u MiB)", path,
                     (long long)st.st_size, MAX_SCENE_FILE_BYTES >> 20);
        return false;
    }
    size_t len;
    char *text = sl_read_file(path, &len, err, err_size);
    if (!text) return false;
    if (is_gltf_json(text, len)) { /* a .gltf document, whatever its name */
        free(text);
        return sl_scene_load_model(scene, path, err, err_size);
    }
    /* relative assets resolve against the scene file's directory (made absolute) */
    char *copy = strdup(path);
    char *slash = copy ? strrchr(copy, '/') : NULL;
    const char *dir = ".";
    if (slash) {
        if (slash == copy) slash[1] = 0;
        else *slash = 0;
        dir = copy;
    }
    char *abs_dir = realpath(dir, NULL);
    bool ok = load_common(scene, text, len, path, abs_dir ? abs_dir : dir, opts, err, err_size);
    free(abs_dir);
    free(copy);
    free(text);
    return ok;
}
