/* The toggle matrix (issue 13, issue 43): every feature toggles live, and a live change gives the
 * frame a fresh start with the same setting gives.
 *
 *   usage: test_toggle_matrix [--exhaustive] [--scene NAME] SCENE_DIR...
 *
 * For every scene (SCENE_DIR/NAME.json, named NAME.json for the first directory and
 * MODULE/NAME.json for a MODULE/scenes after it; those that need ../shared/assets only when it is
 * there)
 * and the plugins it loads:
 *   1. render (frame 0);
 *   2. switch a set of plugins off live (sl_harness_set, the path the GUI, keys and script take),
 *      render frame 0 again, and compare with a fresh harness created with them off (the setting
 *      given at creation): the same passes, draw calls and program hashes, and display pixels
 *      within 1/255;
 *   3. switch them back on live and compare with the first render.
 * Which sets (the cells): by default a pairwise design over the scene's plugins, each an on/off
 * factor: for every two plugins A and B some cell has A off with B on, one B off with A on, and
 * one both off (pairwise_cells; 3 cells for 2 or 3 plugins, 4 for 4, 5 for up to 10), once per set
 * of plugins, on the smallest scene that loads that set. With --exhaustive (ctest -L long): every
 * plugin off alone and every two off together, on every scene.
 * Then every plugin's key bindings and debug views must change the image on at least one scene
 * and give finite pixels; every other global parameter is switched too, and each change must give
 * finite pixels (parameters that change nothing on any scene are listed) and, on the first scene
 * that loads its plugin, the same frame as a fresh start given it. Scenes run smallest first
 * (fewest plugins, then fewest draw calls), so that first scene is the smallest one. By default a
 * plugin's features run on the scenes that load it until each has run and each key and view has
 * changed the image; with --exhaustive on every scene that loads it.
 *
 * A failing cell names the scene, the plugin(s) and what differs (the pass list, the program of a
 * material, or the pixels). Small images keep it quick. */
#include "check.h"
#include <shadelab/harness.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define W 48
#define H 32
#define MAX_PLUGINS 16

/* A frame as the matrix compares it: its structure (pass names copied, they outlive no harness)
 * and its display-encoded pixels. */
typedef struct frame {
    int draw_calls, pass_count, program_count;
    char passes[64][64];
    uint64_t hashes[256];
    float px[W * H * 4];
    bool ok;
} frame;

static bool have_data, exhaustive;

/* Settings every harness of the matrix starts with: small texture-space work for sss, and sss's
 * disk cache off: a fresh start that loads the diffusion's result draws fewer calls than a live
 * change that computes it (the same pixels: test_sss_render "cache"), and the matrix compares the
 * computing path. Small precomputed textures too (envmap's cube and its prefilter's samples, the
 * shadow maps): at 48×32 pixels their default sizes were most of each fresh start's time (the
 * live and the fresh harness get the same, so what is compared does not change). At most 5. */
static int base_settings(const char **ids, int n, const char **out) {
    int k = 0;
    for (int i = 0; i < n; i++)
        if (!strcmp(ids[i], "sss")) out[k++] = "sss.ts_size=64", out[k++] = "sss.cache=false";
        else if (!strcmp(ids[i], "envmap")) out[k++] = "envmap.cube_size=32", out[k++] = "envmap.samples=32";
        else if (!strcmp(ids[i], "spotlight-shadow")) out[k++] = "spotlight-shadow.map_size=256";
    return k;
}

/* Whether the scene file names plugin `id` in its text ("plugins": [..., "id", ...]). */
static bool names_plugin(const char *path, const char *id) {
    FILE *f = fopen(path, "rb");
    if (!f) return false;
    static char text[1 << 20];
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = 0;
    char quoted[80];
    snprintf(quoted, sizeof quoted, "\"%s\"", id);
    return strstr(text, quoted) != NULL;
}

static sl_harness *open_scene(const char *path, const char *const *settings, char *err, size_t n) {
    return sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                .scene_file = path, .settings = settings, .strict = true},
                             err, n);
}

static void capture(sl_harness *h, frame *f) {
    sl_harness_set_frame(h, 0);
    f->ok = sl_harness_render(h, NULL) && sl_harness_read_display(h, f->px);
    sl_harness_structure s;
    sl_harness_structure_of(h, &s);
    f->draw_calls = s.effect_draw_calls;
    /* the passes in effect: a live change may skip a pass whose inputs did not change (pass.h,
     * sl_depends) that a fresh start runs; both use its output */
    f->pass_count = s.effect_count;
    f->program_count = s.program_count;
    for (int i = 0; i < s.effect_count; i++) snprintf(f->passes[i], sizeof f->passes[i], "%s", s.in_effect[i]);
    memcpy(f->hashes, s.program_hashes, sizeof f->hashes);
}

static long nonfinite(const frame *f) { return sl_harness_count_nonfinite(f->px, W, H); }

/* Describes the first difference between two frames in `why`; true when they match. */
static bool same_frame(const frame *a, const frame *b, char *why, size_t n) {
    if (!a->ok || !b->ok) return snprintf(why, n, "a render failed"), false;
    if (a->pass_count != b->pass_count) {
        snprintf(why, n, "%d passes in effect live, %d in the fresh start", a->pass_count, b->pass_count);
        return false;
    }
    for (int i = 0; i < a->pass_count; i++)
        if (strcmp(a->passes[i], b->passes[i])) {
            snprintf(why, n, "pass %d is \"%s\" live, \"%s\" in the fresh start", i, a->passes[i], b->passes[i]);
            return false;
        }
    if (a->program_count != b->program_count) {
        snprintf(why, n, "%d programs live, %d fresh", a->program_count, b->program_count);
        return false;
    }
    for (int i = 0; i < a->program_count; i++)
        if (a->hashes[i] != b->hashes[i]) {
            snprintf(why, n, "composed program %d differs (hash %016llx live, %016llx fresh)", i,
                     (unsigned long long)a->hashes[i], (unsigned long long)b->hashes[i]);
            return false;
        }
    if (a->draw_calls != b->draw_calls) {
        snprintf(why, n, "%d draw calls live, %d fresh", a->draw_calls, b->draw_calls);
        return false;
    }
    sl_compare c;
    sl_harness_compare(a->px, b->px, W, H, 1.0 / 255 + 1e-6, &c);
    if (c.pixels_over || c.nonfinite) {
        snprintf(why, n, "pixels differ: %ld over 1/255 (max %.4f), %ld non-finite", c.pixels_over, c.max_abs, c.nonfinite);
        return false;
    }
    return true;
}

static bool differs(const frame *a, const frame *b) {
    sl_compare c;
    sl_harness_compare(a->px, b->px, W, H, 1.0 / 255 + 1e-6, &c);
    return c.pixels_over > 0;
}

/* ----------------------------------------------------------------- coverage bookkeeping */

typedef struct feature {
    char plugin[64], what[160]; /* "key Z (zero_specular)", "debug view ggx-d", "param exposure" */
    bool must_change;           /* keys and debug views: must change the image somewhere */
    bool changed, tried;
    bool fresh_checked;         /* params: live set compared with a fresh start once */
} feature;
static feature features[512];
static int feature_count;

static feature *feature_get(const char *plugin, const char *what, bool must_change) {
    for (int i = 0; i < feature_count; i++)
        if (!strcmp(features[i].plugin, plugin) && !strcmp(features[i].what, what)) return &features[i];
    if (feature_count == 512) return NULL;
    feature *f = &features[feature_count++];
    snprintf(f->plugin, sizeof f->plugin, "%s", plugin);
    snprintf(f->what, sizeof f->what, "%s", what);
    f->must_change = must_change;
    return f;
}

/* A value of a global parameter other than its default, as --set text; false for textures. */
static bool other_value(const sl_param_desc *d, char *text, size_t n) {
    const sl_value *v = &d->default_value;
    switch (d->type) {
    case SL_PARAM_BOOL: snprintf(text, n, "%s", v->b ? "false" : "true"); return true;
    case SL_PARAM_ENUM: {
        int count = 0;
        while (d->enum_values && d->enum_values[count]) count++;
        if (count < 2) return false;
        snprintf(text, n, "%s", d->enum_values[(v->i + 1) % count]);
        return true;
    }
    case SL_PARAM_INT: {
        /* downward where it can: quality knobs (samples, sizes) get cheaper, not dearer */
        int step = d->step > 0 ? (int)d->step : 1, x = v->i / 2 / step * step;
        if (d->max > d->min && x < (int)d->min) x = (int)d->min;
        if (x == v->i) x = v->i + step;
        snprintf(text, n, "%d", x);
        return true;
    }
    case SL_PARAM_FLOAT: {
        float x;
        if (d->max > d->min) {
            float mid = 0.5f * (d->min + d->max);
            x = fabsf(mid - v->f[0]) > 0.05f * (d->max - d->min) ? mid : d->max;
        } else {
            x = v->f[0] * 2 + 1;
        }
        snprintf(text, n, "%.6g", x);
        return true;
    }
    case SL_PARAM_COLOR:
    case SL_PARAM_VEC3: snprintf(text, n, "%g,%g,%g", 1 - v->f[0], 0.5 + v->f[1], 1 - v->f[2]); return true;
    case SL_PARAM_TEXTURE: return false;
    }
    return false;
}

/* A parameter set live, to compare with a fresh start that is given the same setting. */
typedef struct pending { char set[256]; frame *live; } pending;
static pending pendings[256];
static int pending_count;

/* --------------------------------------------------------------------------- the matrix */

static int cells, failed_cells, params_checked;

/* Switches the plugins of `off` (a bit per index into ids) to `value` live; false and `err` on failure. */
static bool set_enabled(sl_harness *h, const char **ids, int nids, unsigned off, bool value, char *err, size_t n) {
    for (int i = 0; i < nids; i++) {
        char set[128];
        snprintf(set, sizeof set, "%s.enabled=%s", ids[i], value ? "true" : "false");
        if ((off >> i & 1) && !sl_harness_set(h, set, err, n)) return false;
    }
    return true;
}

/* One cell: the plugins of `off` switched off live against a fresh start with them off, then back
 * on against the first render. */
static void toggle_cell(const char *scene, const char *path, const char **ids, int nids, unsigned off,
                        sl_harness **live, const frame *first) {
    char why[512], err[2048], sets[MAX_PLUGINS][128], cell[1024];
    const char *settings[8 + MAX_PLUGINS];
    int k = base_settings(ids, nids, settings), base = k;
    int w = snprintf(cell, sizeof cell, "%s:", scene);
    for (int i = 0; i < nids; i++)
        if (off >> i & 1) {
            snprintf(sets[i], sizeof sets[i], "%s.enabled=false", ids[i]);
            settings[k++] = sets[i];
            w += snprintf(cell + w, sizeof cell - (size_t)w, " %s", ids[i]);
        }
    snprintf(cell + w, sizeof cell - (size_t)w, " off");
    settings[k] = NULL;
    cells++;

    /* the fresh start with the plugin(s) off; one harness at a time, so the live one closes */
    sl_harness_destroy(*live);
    *live = NULL;
    frame *fresh = calloc(1, sizeof *fresh), *now = calloc(1, sizeof *now);
    sl_harness *h = open_scene(path, settings, err, sizeof err);
    if (!h) {
        printf("FAIL %s: a fresh start with that setting fails: %s\n", cell, err);
        CHECK_MSG(0, "%s: a fresh start with that setting opens", cell);
        failed_cells++;
        goto done;
    }
    capture(h, fresh);
    sl_harness_destroy(h);
    CHECK_MSG(nonfinite(fresh) == 0, "%s: finite pixels", cell);

    /* the live path: on → off → compare → on → compare with the first render */
    settings[base] = NULL;
    *live = open_scene(path, settings, err, sizeof err);
    if (!*live) {
        printf("FAIL %s: reopening the scene: %s\n", cell, err);
        failed_cells++;
        goto done;
    }
    capture(*live, now); /* a frame with everything on, so the toggle happens on a warm renderer */
    bool ok = set_enabled(*live, ids, nids, off, false, err, sizeof err);
    CHECK_MSG(ok, "%s: live set: %s", cell, ok ? "" : err);
    capture(*live, now);
    bool same_off = same_frame(now, fresh, why, sizeof why);
    if (!same_off) printf("FAIL %s: live differs from a fresh start: %s\n", cell, why);
    CHECK_MSG(same_off, "%s: live == fresh", cell);
    ok = set_enabled(*live, ids, nids, off, true, err, sizeof err);
    CHECK_MSG(ok, "%s: live set back on: %s", cell, ok ? "" : err);
    capture(*live, now);
    bool same_on = same_frame(now, first, why, sizeof why);
    if (!same_on) printf("FAIL %s, switched back on: differs from the first render: %s\n", cell, why);
    CHECK_MSG(same_on, "%s: back on == first", cell);
    if (!same_off || !same_on) failed_cells++;
done:
    free(fresh);
    free(now);
}

/* The cells of a pairwise (strength-2) design over n on/off factors, the first render being the
 * all-on case: each plugin gets a distinct set ("code") of the cells it is off in, all of one
 * size above half the cell count. Two such codes share a cell (both off: together they would
 * need more cells than there are) and neither contains the other (same size), so each has a cell
 * without the other (one off, the other on). The fewest cells R with C(R, R/2+1) >= n codes.
 * Writes the cells as bit sets of plugins off; returns how many. */
static int pairwise_cells(int n, unsigned cells_off[8]) {
    if (n <= 0) return 0;
    int R = 1;
    for (;; R++) {
        int weight = R / 2 + 1, codes = 0;
        for (unsigned m = 0; m < 1u << R; m++) codes += __builtin_popcount(m) == weight;
        if (codes >= n || R == 8) break;
    }
    for (int r = 0; r < R; r++) cells_off[r] = 0;
    int plugin = 0;
    for (unsigned m = 0; m < 1u << R && plugin < n; m++)
        if (__builtin_popcount(m) == R / 2 + 1) {
            for (int r = 0; r < R; r++)
                if (m >> r & 1) cells_off[r] |= 1u << plugin;
            plugin++;
        }
    int count = 0; /* drop a cell that switches nothing off */
    for (int r = 0; r < R; r++)
        if (cells_off[r]) cells_off[count++] = cells_off[r];
    return count;
}

/* Whether the cells cover every pair of n plugins in the three off/on cases. */
static bool covers_pairs(int n, const unsigned *cells_off, int count) {
    for (int a = 0; a < n; a++)
        for (int b = a + 1; b < n; b++) {
            int seen = 0; /* bit 0: both off; 1: a off, b on; 2: b off, a on */
            for (int c = 0; c < count; c++) {
                bool oa = cells_off[c] >> a & 1, ob = cells_off[c] >> b & 1;
                seen |= (oa && ob) << 0 | (oa && !ob) << 1 | (ob && !oa) << 2;
            }
            if (seen != 7) return false;
        }
    return true;
}

/* Keys, debug views and parameters of one plugin on one scene (live, on a warm harness). */
static void cover_plugin(const char *scene, sl_harness *h, const char *plugin, const frame *first) {
    char err[1024], text[128], set[256], what[160];
    frame *f = calloc(1, sizeof *f);
    const sl_key_desc *keys[32];
    int nk = sl_harness_plugin_keys(h, plugin, keys, 32);
    const sl_param_desc *params[64];
    int np = sl_harness_plugin_params(h, plugin, params, 64);
    const char *views[32];
    int nv = sl_harness_plugin_debug_views(h, plugin, views, 32);
    for (int i = 0; i < np && i < 64; i++) {
        const sl_param_desc *d = params[i];
        if (!other_value(d, text, sizeof text)) continue;
        bool keyed = false;
        for (int j = 0; j < nk && j < 32; j++) keyed |= keys[j]->param && !strcmp(keys[j]->param, d->id);
        snprintf(what, sizeof what, "%s %s", keyed ? "key-bound param" : "param", d->id);
        feature *ft = feature_get(plugin, what, keyed);
        char before[128], full[160];
        snprintf(full, sizeof full, "%s.%s", plugin, d->id);
        if (!sl_harness_get(h, full, before, sizeof before)) continue;
        snprintf(set, sizeof set, "%s.%s=%s", plugin, d->id, text);
        if (!sl_harness_set(h, set, err, sizeof err)) {
            CHECK_MSG(0, "%s: --set %s: %s", scene, set, err);
            continue;
        }
        capture(h, f);
        CHECK_MSG(f->ok && nonfinite(f) == 0, "%s: %s gives finite pixels", scene, set);
        if (ft) ft->tried = true, ft->changed |= differs(f, first);
        if (ft && !ft->fresh_checked && pending_count < 256) {
            ft->fresh_checked = true;
            pending *p = &pendings[pending_count++];
            snprintf(p->set, sizeof p->set, "%s", set);
            p->live = malloc(sizeof *p->live);
            *p->live = *f;
        }
        /* back to the value it had */
        snprintf(set, sizeof set, "%s.%s=%s", plugin, d->id, before);
        sl_harness_set(h, set, err, sizeof err);
    }
    for (int i = 0; i < nv && i < 32; i++) {
        snprintf(what, sizeof what, "debug view %s", views[i]);
        feature *ft = feature_get(plugin, what, true);
        if (!sl_harness_set_debug_view(h, views[i], err, sizeof err)) {
            CHECK_MSG(0, "%s: debug view %s: %s", scene, views[i], err);
            continue;
        }
        capture(h, f);
        CHECK_MSG(f->ok && nonfinite(f) == 0, "%s: debug view %s gives finite pixels", scene, views[i]);
        if (ft) ft->tried = true, ft->changed |= differs(f, first);
        sl_harness_set_debug_view(h, NULL, err, sizeof err);
    }
    free(f);
}

/* The scene files of `dir` (NAME.json), sorted, appended to paths[*count] with their names:
 * NAME.json for the first directory, MODULE/NAME.json for MODULE/scenes after it (extras). The
 * caller frees both. */
static void list_scenes(const char *dir, bool first_dir, char **paths, char **names, int *count, int max) {
    DIR *d = opendir(dir);
    CHECK_MSG(d != NULL, "open %s", dir);
    if (!d) return;
    char module[256] = "";
    if (!first_dir) {
        char copy[1024];
        snprintf(copy, sizeof copy, "%s", dir);
        char *slash = strrchr(copy, '/');
        if (slash && slash != copy) *slash = 0;
        slash = strrchr(copy, '/');
        snprintf(module, sizeof module, "%s/", slash ? slash + 1 : copy);
    }
    int start = *count;
    for (struct dirent *e; (e = readdir(d)) && *count < max;) {
        size_t len = strlen(e->d_name);
        if (len > 5 && !strcmp(e->d_name + len - 5, ".json")) {
            char path[2048], name[512];
            snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
            snprintf(name, sizeof name, "%s%s", module, e->d_name);
            paths[*count] = strdup(path);
            names[(*count)++] = strdup(name);
        }
    }
    closedir(d);
    /* sorted by name (paths and names together) */
    for (int i = start + 1; i < *count; i++)
        for (int j = i; j > start && strcmp(names[j - 1], names[j]) > 0; j--) {
            char *t = names[j]; names[j] = names[j - 1]; names[j - 1] = t;
            t = paths[j]; paths[j] = paths[j - 1]; paths[j - 1] = t;
        }
}

/* Whether this run covers the plugin's keys, views and parameters on another scene: always with
 * --exhaustive; else until they have run once and every key and view has changed the image. */
static bool wants_cover(const char *plugin) {
    if (exhaustive) return true;
    bool seen = false;
    for (int i = 0; i < feature_count; i++)
        if (!strcmp(features[i].plugin, plugin)) {
            seen = true;
            if (features[i].must_change && !features[i].changed) return true;
        }
    return !seen;
}

/* Each parameter changed live (on the first scene that loads its plugin) equals a fresh start
 * given the same setting. */
static void check_pending(const char *name, const char *path, const char **ids, int nids) {
    char err[2048], why[512];
    for (int i = 0; i < pending_count; i++) {
        pending *p = &pendings[i];
        const char *with[8];
        int k = base_settings(ids, nids, with);
        with[k++] = p->set;
        with[k] = NULL;
        frame *f = calloc(1, sizeof *f);
        sl_harness *h = open_scene(path, with, err, sizeof err);
        CHECK_MSG(h != NULL, "%s: a fresh start with %s opens: %s", name, p->set, err);
        if (h) {
            capture(h, f);
            sl_harness_destroy(h);
            bool same = same_frame(p->live, f, why, sizeof why);
            if (!same) printf("FAIL %s: %s live differs from a fresh start: %s\n", name, p->set, why);
            CHECK_MSG(same, "%s: %s live == fresh", name, p->set);
            params_checked++;
        }
        free(f);
        free(p->live);
    }
    pending_count = 0;
}

/* A scene of the run, the plugins it loads (aa only where the scene names it: aa is loaded for
 * every scene by default, antialiasing on, plugins/aa/README.md; it stays on while the scene's
 * own plugins toggle, and its own cells run on the scenes that name it, aa_edges.json) and its
 * first render with everything on. */
typedef struct matrix_scene {
    const char *path, *name;
    int nids;
    char ids[MAX_PLUGINS][64];
    frame *first;
} matrix_scene;

static int scene_settings(const matrix_scene *sc, const char **ids, const char **settings) {
    for (int i = 0; i < sc->nids; i++) ids[i] = sc->ids[i];
    int k = base_settings(ids, sc->nids, settings);
    settings[k] = NULL;
    return k;
}

/* Opens the scene for its plugins, then with the matrix's settings for its first render; false
 * when it cannot open (skipped or failed). */
static bool open_first(matrix_scene *sc) {
    char err[2048];
    sl_harness *h = open_scene(sc->path, NULL, err, sizeof err);
    if (!h) {
        bool needs_data = strstr(err, "not found") || strstr(err, "No such file") || strstr(err, "cannot open");
        if (!have_data && needs_data) printf("skip %s: needs the data directory (../shared/assets): %s\n", sc->name, err);
        else CHECK_MSG(0, "%s: opens: %s", sc->name, err);
        return false;
    }
    const char *ids[MAX_PLUGINS], *settings[8];
    int n = sl_harness_plugins(h, ids, MAX_PLUGINS);
    if (n > MAX_PLUGINS) n = MAX_PLUGINS;
    sc->nids = 0;
    for (int i = 0; i < n; i++)
        if (strcmp(ids[i], "aa") || names_plugin(sc->path, "aa")) snprintf(sc->ids[sc->nids++], 64, "%s", ids[i]);
    sl_harness_destroy(h);
    scene_settings(sc, ids, settings);
    h = open_scene(sc->path, settings, err, sizeof err);
    CHECK_MSG(h != NULL, "%s: opens small: %s", sc->name, err);
    if (!h) return false;
    sc->first = calloc(1, sizeof *sc->first);
    capture(h, sc->first);
    sl_harness_destroy(h);
    CHECK_MSG(sc->first->ok && nonfinite(sc->first) == 0, "%s: first render, finite pixels", sc->name);
    return true;
}

/* Smaller scenes first: fewer plugins, then fewer draw calls (then by name), so that a plugin's
 * features are covered, and its parameters compared with fresh starts, on the smallest scene
 * that loads it. */
static int cmp_scene(const void *a, const void *b) {
    const matrix_scene *x = a, *y = b;
    if (x->nids != y->nids) return x->nids - y->nids;
    if (x->first->draw_calls != y->first->draw_calls) return x->first->draw_calls - y->first->draw_calls;
    return strcmp(x->name, y->name);
}

static double now_s(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

/* The pairwise cells run once per set of plugins, on its smallest scene (the scenes are sorted):
 * another scene with the same plugins toggles the same passes and programs' switches, and repeating
 * them on every bench and showcase scene of a model cost a minute of the suite. --exhaustive and
 * --scene run every scene's cells. Returns the scene that ran this set, or NULL (now recorded). */
static const char *set_already_run(const char *name, const char **ids, int nids) {
    static char sets[512][256], owners[512][128];
    static int nsets;
    char key[256] = "";
    bool used[MAX_PLUGINS] = {false};
    for (int k = 0; k < nids; k++) { /* ids in name order, joined */
        int best = -1;
        for (int i = 0; i < nids; i++)
            if (!used[i] && (best < 0 || strcmp(ids[i], ids[best]) < 0)) best = i;
        used[best] = true;
        snprintf(key + strlen(key), sizeof key - strlen(key), "%s,", ids[best]);
    }
    for (int i = 0; i < nsets; i++)
        if (!strcmp(sets[i], key)) return owners[i];
    if (nsets < 512) {
        snprintf(sets[nsets], sizeof sets[nsets], "%s", key);
        snprintf(owners[nsets++], sizeof owners[0], "%s", name);
    }
    return NULL;
}

static void run_scene(const matrix_scene *sc, bool every_scene) {
    double t0 = now_s();
    const char *path = sc->path, *name = sc->name, *ids[MAX_PLUGINS], *settings[8];
    int nids = sc->nids;
    char err[2048];
    scene_settings(sc, ids, settings);
    printf("%s: %d plugin(s):", name, nids);
    for (int i = 0; i < nids; i++) printf(" %s", ids[i]);
    printf("\n");
    fflush(stdout);

    unsigned off[MAX_PLUGINS * MAX_PLUGINS];
    int count = 0;
    if (exhaustive) {
        for (int i = 0; i < nids; i++) off[count++] = 1u << i;
        for (int i = 0; i < nids; i++)
            for (int j = i + 1; j < nids; j++) off[count++] = 1u << i | 1u << j;
    } else {
        count = pairwise_cells(nids, off);
    }
    const char *ran = set_already_run(name, ids, nids);
    if (ran && !every_scene) {
        printf("%s: its plugins' cells ran on %s\n", name, ran);
        count = 0;
    }
    CHECK_MSG(count == 0 || covers_pairs(nids, off, count), "%s: the %d cells cover every pair of its %d plugins", name,
              count, nids);
    sl_harness *h = NULL;
    for (int c = 0; c < count; c++) toggle_cell(name, path, ids, nids, off[c], &h, sc->first);
    bool cover = false;
    for (int i = 0; i < nids; i++) cover |= wants_cover(ids[i]);
    if (cover && !h) h = open_scene(path, settings, err, sizeof err);
    for (int i = 0; h && i < nids; i++)
        if (wants_cover(ids[i])) cover_plugin(name, h, ids[i], sc->first);
    sl_harness_destroy(h);
    check_pending(name, path, ids, nids);
    printf("%s: %d cell(s), %.1f s\n", name, count, now_s() - t0);
}

int main(int argc, char **argv) {
    const char *only = NULL; /* --scene NAME: that scene only */
    char *paths[512], *names[512];
    int count = 0, dirs = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--exhaustive")) exhaustive = true;
        else if (!strcmp(argv[i], "--scene") && i + 1 < argc) only = argv[++i];
        else list_scenes(argv[i], dirs++ == 0, paths, names, &count, 512);
    }
    if (!count) {
        fprintf(stderr, "usage: test_toggle_matrix [--exhaustive] [--scene NAME] SCENE_DIR...\n");
        return 2;
    }
    have_data = getenv("SHADELAB_DATA") && *getenv("SHADELAB_DATA");
    matrix_scene *scenes = calloc((size_t)count, sizeof *scenes);
    int nscenes = 0;
    for (int s = 0; s < count; s++) {
        matrix_scene *sc = &scenes[nscenes];
        sc->path = paths[s], sc->name = names[s];
        if ((!only || !strcmp(only, sc->name)) && open_first(sc)) nscenes++;
    }
    qsort(scenes, (size_t)nscenes, sizeof *scenes, cmp_scene);
    for (int s = 0; s < nscenes; s++) run_scene(&scenes[s], exhaustive || only);
    for (int s = 0; s < nscenes; s++) free(scenes[s].first);
    free(scenes);
    printf("\n%d toggle cells (%s), %d failed; %d parameters set live compared with a fresh start\n", cells,
           exhaustive ? "every plugin off alone and every two together" : "pairwise", failed_cells, params_checked);
    for (int i = 0; i < feature_count; i++) {
        feature *f = &features[i];
        if (!f->tried) continue;
        if (f->must_change && !only) CHECK_MSG(f->changed, "%s %s changes the image on at least one scene", f->plugin, f->what);
        else if (!f->changed) printf("note: %s %s changes nothing on any scene at %dx%d\n", f->plugin, f->what, W, H);
    }
    for (int i = 0; i < count; i++) free(paths[i]), free(names[i]);
    return check_result();
}
