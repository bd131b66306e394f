/* The toggle matrix (issue 13): every feature toggles live, alone and in pairs, and a live change
 * gives the frame a fresh start with the same setting gives.
 *
 * For every bundled scene (scenes/NAME.json; those that need ../shared/assets only when it is there)
 * and every plugin the scene loads:
 *   1. render (frame 0);
 *   2. switch the plugin off live (sl_harness_set, the path the GUI, keys and script take), render
 *      frame 0 again, and compare with a fresh harness created with the plugin off (the setting
 *      given at creation): the same passes, draw calls and program hashes, and display pixels
 *      within 1/255;
 *   3. switch it back on live and compare with the first render.
 * Scenes that load three or more plugins also switch every pair off together. Then every plugin's
 * key bindings and debug views must change the image on at least one scene and give finite pixels
 * on every scene that loads the plugin; every other global parameter is switched too, and each
 * change must give finite pixels (parameters that change nothing on any bundled scene are listed)
 * and, on the first scene that loads its plugin, the same frame as a fresh start given it.
 *
 * A failing cell names the scene, the plugin(s) and what differs (the pass list, the program of a
 * material, or the pixels). Small images keep the whole matrix inside the CI budget. */
#include "check.h"
#include <shadelab/harness.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

static const char *scenes_dir = SL_SCENES_DIR;
static bool have_data;

/* Settings every harness of the matrix starts with: small texture-space work for sss, and sss's
 * disk cache off: a fresh start that loads the diffusion's result draws fewer calls than a live
 * change that computes it (the same pixels: test_sss_render "cache"), and the matrix compares the
 * computing path. */
static int base_settings(const char **ids, int n, const char **out) {
    int k = 0;
    for (int i = 0; i < n; i++)
        if (!strcmp(ids[i], "sss")) out[k++] = "sss.ts_size=64", out[k++] = "sss.cache=false";
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

static void toggle_cell(const char *scene, const char *path, const char **ids, int nids, const char *off_a,
                        const char *off_b, sl_harness **live, const frame *first) {
    char why[512], err[2048], set_a[128], set_b[128] = "";
    const char *settings[8];
    int k = base_settings(ids, nids, settings);
    snprintf(set_a, sizeof set_a, "%s.enabled=false", off_a);
    settings[k++] = set_a;
    if (off_b) snprintf(set_b, sizeof set_b, "%s.enabled=false", off_b), settings[k++] = set_b;
    settings[k] = NULL;
    char cell[256];
    snprintf(cell, sizeof cell, "%s: %s%s%s off", scene, off_a, off_b ? " + " : "", off_b ? off_b : "");
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
    settings[k - 1 - (off_b ? 1 : 0)] = NULL;
    *live = open_scene(path, settings, err, sizeof err);
    if (!*live) {
        printf("FAIL %s: reopening the scene: %s\n", cell, err);
        failed_cells++;
        goto done;
    }
    capture(*live, now); /* a frame with everything on, so the toggle happens on a warm renderer */
    bool ok = sl_harness_set(*live, set_a, err, sizeof err) && (!off_b || sl_harness_set(*live, set_b, err, sizeof err));
    CHECK_MSG(ok, "%s: live set: %s", cell, ok ? "" : err);
    capture(*live, now);
    bool same_off = same_frame(now, fresh, why, sizeof why);
    if (!same_off) printf("FAIL %s: live differs from a fresh start: %s\n", cell, why);
    CHECK_MSG(same_off, "%s: live == fresh", cell);
    snprintf(set_a, sizeof set_a, "%s.enabled=true", off_a);
    if (off_b) snprintf(set_b, sizeof set_b, "%s.enabled=true", off_b);
    ok = sl_harness_set(*live, set_a, err, sizeof err) && (!off_b || sl_harness_set(*live, set_b, err, sizeof err));
    capture(*live, now);
    bool same_on = same_frame(now, first, why, sizeof why);
    if (!same_on) printf("FAIL %s, switched back on: differs from the first render: %s\n", cell, why);
    CHECK_MSG(same_on, "%s: back on == first", cell);
    if (!same_off || !same_on) failed_cells++;
done:
    free(fresh);
    free(now);
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

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

int main(int argc, char **argv) {
    const char *only = argc > 1 ? argv[1] : NULL; /* run one scene: test_toggle_matrix NAME.json */
    have_data = getenv("SHADELAB_DATA") && *getenv("SHADELAB_DATA");
    DIR *d = opendir(scenes_dir);
    CHECK_MSG(d != NULL, "open %s", scenes_dir);
    if (!d) return check_result();
    char *names[256];
    int count = 0;
    for (struct dirent *e; (e = readdir(d)) && count < 256;) {
        size_t len = strlen(e->d_name);
        if (len > 5 && !strcmp(e->d_name + len - 5, ".json")) names[count++] = strdup(e->d_name);
    }
    closedir(d);
    qsort(names, count, sizeof *names, cmp_str);

    for (int s = 0; s < count; s++) {
        if (only && strcmp(only, names[s])) continue;
        char path[1024], err[2048];
        snprintf(path, sizeof path, "%s/%s", scenes_dir, names[s]);
        /* which plugins the scene loads, and the settings that keep it small */
        sl_harness *h = open_scene(path, NULL, err, sizeof err);
        if (!h) {
            bool needs_data = strstr(err, "not found") || strstr(err, "No such file") || strstr(err, "cannot open");
            if (!have_data && needs_data) {
                printf("skip %s: needs the data directory (../shared/assets): %s\n", names[s], err);
                continue;
            }
            CHECK_MSG(0, "%s: opens: %s", names[s], err);
            continue;
        }
        const char *ids[MAX_PLUGINS];
        char idbuf[MAX_PLUGINS][64];
        int nids = sl_harness_plugins(h, ids, MAX_PLUGINS);
        if (nids > MAX_PLUGINS) nids = MAX_PLUGINS;
        for (int i = 0; i < nids; i++) snprintf(idbuf[i], sizeof idbuf[i], "%s", ids[i]), ids[i] = idbuf[i];
        sl_harness_destroy(h);
        /* aa is loaded for every scene by default (antialiasing on, plugins/aa/README.md): it stays
         * on while the scene's own plugins toggle; its own cells run on the scenes that name it
         * (aa_edges.json), which keeps the matrix inside its time budget */
        if (!names_plugin(path, "aa"))
            for (int i = 0; i < nids; i++)
                if (!strcmp(ids[i], "aa")) {
                    for (int j = i; j + 1 < nids; j++) snprintf(idbuf[j], sizeof idbuf[j], "%s", idbuf[j + 1]);
                    nids--;
                    break;
                }
        const char *settings[8];
        settings[base_settings(ids, nids, settings)] = NULL;
        h = open_scene(path, settings, err, sizeof err);
        CHECK_MSG(h != NULL, "%s: opens small: %s", names[s], err);
        if (!h) continue;
        frame *first = calloc(1, sizeof *first);
        capture(h, first);
        CHECK_MSG(first->ok && nonfinite(first) == 0, "%s: first render, finite pixels", names[s]);
        printf("%s: %d plugin(s):", names[s], nids);
        for (int i = 0; i < nids; i++) printf(" %s", ids[i]);
        printf("\n");
        fflush(stdout);

        for (int i = 0; i < nids; i++) toggle_cell(names[s], path, ids, nids, ids[i], NULL, &h, first);
        if (nids >= 3)
            for (int i = 0; i < nids; i++)
                for (int j = i + 1; j < nids; j++) toggle_cell(names[s], path, ids, nids, ids[i], ids[j], &h, first);
        if (!h) h = open_scene(path, settings, err, sizeof err);
        for (int i = 0; h && i < nids; i++) cover_plugin(names[s], h, ids[i], first);
        sl_harness_destroy(h);
        /* each parameter changed live (on the first scene that loads its plugin) equals a fresh
         * start given the same setting */
        for (int i = 0; i < pending_count; i++) {
            pending *p = &pendings[i];
            const char *with[10];
            int k = base_settings(ids, nids, with);
            with[k++] = p->set;
            with[k] = NULL;
            frame *f = calloc(1, sizeof *f);
            char why[512];
            h = open_scene(path, with, err, sizeof err);
            CHECK_MSG(h != NULL, "%s: a fresh start with %s opens: %s", names[s], p->set, err);
            if (h) {
                capture(h, f);
                sl_harness_destroy(h);
                bool same = same_frame(p->live, f, why, sizeof why);
                if (!same) printf("FAIL %s: %s live differs from a fresh start: %s\n", names[s], p->set, why);
                CHECK_MSG(same, "%s: %s live == fresh", names[s], p->set);
                params_checked++;
            }
            free(f);
            free(p->live);
        }
        pending_count = 0;
        free(first);
    }

    printf("\n%d toggle cells, %d failed; %d parameters set live compared with a fresh start\n", cells, failed_cells,
           params_checked);
    for (int i = 0; i < feature_count; i++) {
        feature *f = &features[i];
        if (!f->tried) continue;
        if (f->must_change && !only) CHECK_MSG(f->changed, "%s %s changes the image on at least one bundled scene", f->plugin, f->what);
        else if (!f->changed) printf("note: %s %s changes nothing on any bundled scene at %dx%d\n", f->plugin, f->what, W, H);
    }
    for (int i = 0; i < count; i++) free(names[i]);
    return check_result();
}
