/* The frame-time budget: knobs from the registered models, motion, applying choices (budget.h). */
#include "budget/budget.h"
#include "budget/controller.h"
#include "log.h"
#include "render/composer.h"
#include "render/renderer.h"
#include "state.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MAX_MODELS 32

typedef struct model_reg {
    int owner;
    char id[96];                           /* "plugin.param" */
    int count;
    char value[SL_BUDGET_MAX_SETTINGS][24];
    double cost[SL_BUDGET_MAX_SETTINGS], error[SL_BUDGET_MAX_SETTINGS];
    char measured_with[160];
    char ceiling[24];                      /* the value configured when the budget took the knob over */
} model_reg;

typedef struct sl_budget_state {
    model_reg models[MAX_MODELS]; int model_count;
    sl_budget ctl;
    int knob_model[SL_BUDGET_MAX_KNOBS];   /* the model behind each knob of ctl */
    uint64_t knobs_key;                    /* what ctl's knobs were built from */
    bool built;
    double last_start_ms;                  /* when the previous frame began (0: none yet) */
    int last_choice[SL_BUDGET_MAX_KNOBS];
    bool skip_observation;                 /* the previous frame changed settings (re-plan, compiles) */
    unsigned long seen_builds;             /* programs built when the previous frame began (composer.h) */
    unsigned long long seen_camera;
    uint64_t seen_lights, seen_materials, seen_params;
    double seen_time;
    double last_ms;
    bool lod_taken;                        /* core.lod_pixels is the budget's (not pinned by the user) */
    float lod_ceiling;                     /* its configured value when the budget took it */
    char status[512];
} sl_budget_state;

static sl_budget_state *state_of(sl_app *app) {
    if (!app->budget) app->budget = calloc(1, sizeof(sl_budget_state));
    return app->budget;
}

static double now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

sl_status sl_budget_add_model(sl_app *app, int owner, const sl_quality_model *in) {
    sl_quality_model m = {0};
    if (!in) return SL_ERR_INVALID;
    memcpy(&m, in, in->struct_size < sizeof m ? in->struct_size : sizeof m);
    const char *who = app->plugins.items[owner]->id;
    char id[96];
    snprintf(id, sizeof id, "%s.%s", who, m.param ? m.param : "");
    sl_param *q = m.param ? sl_params_find(&app->params, id) : NULL;
    const char *why = !q || strcmp(q->owner, who) ? "not a parameter of this plugin"
                      : !(q->desc.flags & SL_PARAM_QUALITY_KNOB) ? "not flagged SL_PARAM_QUALITY_KNOB"
                      : m.count < 1 || m.count > SL_BUDGET_MAX_SETTINGS || !m.values || !m.cost || !m.error
                          ? "1 to 12 settings with values, costs and errors are required"
                          : NULL;
    for (int i = 0; !why && i < m.count; i++) {
        sl_value v;
        char err[256];
        if (!(m.cost[i] > 0) || !(m.error[i] >= 0)) why = "costs must be > 0 and errors >= 0";
        else if (!sl_param_parse(q, m.values[i], &v, err, sizeof err)) why = "a setting is not a value of the parameter";
    }
    if (!why && fabsf(m.cost[m.count - 1] - 1.0f) > 1e-6f) why = "the best (last) setting's cost must be 1";
    sl_budget_state *s = state_of(app);
    if (!why && s->model_count == MAX_MODELS) why = "too many models";
    if (why) {
        SL_ERROR("plugin %s: add_quality_model(\"%s\"): %s", who, m.param ? m.param : "", why);
        return SL_ERR_INVALID;
    }
    model_reg *r = &s->models[s->model_count++];
    memset(r, 0, sizeof *r);
    r->owner = owner, r->count = m.count;
    snprintf(r->id, sizeof r->id, "%s", id);
    snprintf(r->measured_with, sizeof r->measured_with, "%s", m.measured_with ? m.measured_with : "");
    for (int i = 0; i < m.count; i++) {
        snprintf(r->value[i], sizeof r->value[i], "%s", m.values[i]);
        r->cost[i] = m.cost[i], r->error[i] = m.error[i];
    }
    return SL_OK;
}

static double budget_ms(sl_app *app) {
    sl_param *q = sl_params_find(&app->params, "core.budget");
    return q ? q->value.f[0] : 0;
}

/* The user's own choice (--set, the panel) is left alone. */
static bool pinned(const sl_param *q) { return q->source == SL_SRC_CLI || q->source == SL_SRC_GUI; }

/* Index of the setting equal to the parameter's value, or -1. */
static int setting_of(const sl_param *q, const model_reg *r, const char *text) {
    sl_value cur, v;
    char err[256];
    if (text) {
        if (!sl_param_parse(q, text, &cur, err, sizeof err)) return -1;
    } else {
        cur = q->value;
    }
    for (int i = 0; i < r->count; i++)
        if (sl_param_parse(q, r->value[i], &v, err, sizeof err) && v.i == cur.i && v.b == cur.b &&
            fabsf(v.f[0] - cur.f[0]) <= 1e-6f * fmaxf(1, fabsf(cur.f[0])))
            return i;
    return -1;
}

/* What the knobs depend on: the budget, which plugins are on, which knobs the user pinned. */
static uint64_t knobs_key(sl_app *app, sl_budget_state *s) {
    uint64_t h = 1469598103934665603ull;
    double b = budget_ms(app);
    const unsigned char *p = (const unsigned char *)&b;
    for (size_t i = 0; i < sizeof b; i++) h = (h ^ p[i]) * 1099511628211ull;
    for (int i = 0; i < s->model_count; i++) {
        sl_param *q = sl_params_find(&app->params, s->models[i].id);
        h = (h ^ (uint64_t)(sl_plugin_enabled(&app->plugins, s->models[i].owner) * 2 + (q && pinned(q)))) * 1099511628211ull;
    }
    return h;
}

/* The controller's knobs: each registered model of an enabled plugin whose parameter the user did
 * not pin, its settings up to the configured value (the ceiling), costs relative to it. */
static void build_knobs(sl_app *app, sl_budget_state *s) {
    sl_budget_init(&s->ctl, budget_ms(app));
    for (int i = 0; i < s->model_count && s->ctl.knob_count < SL_BUDGET_MAX_KNOBS; i++) {
        model_reg *r = &s->models[i];
        sl_param *q = sl_params_find(&app->params, r->id);
        if (!q || pinned(q) || !sl_plugin_enabled(&app->plugins, r->owner)) continue;
        int top = setting_of(q, r, r->ceiling[0] ? r->ceiling : NULL);
        if (top < 0) continue; /* a value between the modelled settings: not the budget's to change */
        if (!r->ceiling[0]) sl_param_format(q, &q->value, r->ceiling, sizeof r->ceiling);
        sl_budget_knob k = {.count = top + 1};
        snprintf(k.id, sizeof k.id, "%s", r->id);
        for (int j = 0; j <= top; j++) {
            snprintf(k.value[j], sizeof k.value[j], "%s", r->value[j]);
            k.cost[j] = r->cost[j] / r->cost[top];
            k.error[j] = r->error[j];
        }
        s->knob_model[s->ctl.knob_count] = i;
        sl_budget_add_knob(&s->ctl, &k);
    }
    s->knobs_key = knobs_key(app, s);
    s->built = true;
    s->last_start_ms = 0;
    s->skip_observation = true;
}

/* Sets the parameter without taking it from its source: the scene's value stays the scene's, so
 * the user's own edits (which pin a knob) are told apart from the budget's. */
static void apply(sl_app *app, const sl_budget_knob *k, int setting) {
    sl_param *q = sl_params_find(&app->params, k->id);
    sl_value v;
    char err[256];
    if (q && sl_param_parse(q, k->value[setting], &v, err, sizeof err)) sl_params_set_value(&app->params, q, v, q->source);
}

/* Anything the image depends on moved since the last frame: the camera, lights, materials or a
 * parameter (not counting the budget's own settings, applied after this is read), or the clock
 * of a scene that animates. */
static bool moved(sl_app *app, sl_budget_state *s) {
    bool m = app->camera.version != s->seen_camera || app->lights_version != s->seen_lights ||
             app->materials_version != s->seen_materials || app->params.version != s->seen_params ||
             (app->time != s->seen_time && sl_renderer_scene_animates(app));
    s->seen_camera = app->camera.version, s->seen_lights = app->lights_version;
    s->seen_materials = app->materials_version, s->seen_time = app->time;
    return m;
}

/* core.lod_pixels: the configured value in a still, at least the controller's level in motion
 * (controller.h, SL_BUDGET_LOD_FRAMES); `off`: the configured value. A value the user set is left
 * alone. The frame after a change draws with new levels (made at first use): not observed. */
static void apply_lod(sl_app *app, sl_budget_state *s, bool off) {
    sl_param *q = sl_params_find(&app->params, "core.lod_pixels");
    if (!q || pinned(q)) {
        s->lod_taken = false;
        return;
    }
    if (!s->lod_taken) s->lod_taken = true, s->lod_ceiling = q->value.f[0];
    bool still = off || s->ctl.still >= SL_BUDGET_STILL_FRAMES;
    sl_value v = q->value;
    v.f[0] = still ? s->lod_ceiling : fmaxf(s->lod_ceiling, s->ctl.lod_pixels);
    if (v.f[0] == q->value.f[0]) return;
    sl_params_set_value(&app->params, q, v, q->source);
    s->skip_observation = true;
}

void sl_budget_before_frame(sl_app *app) {
    double b = budget_ms(app);
    sl_budget_state *s = app->budget;
    if (!(b > 0)) {
        if (s && s->built) apply_lod(app, s, true);
        if (s) s->built = false, s->status[0] = 0;
        return;
    }
    s = state_of(app);
    if (!s->built || knobs_key(app, s) != s->knobs_key) build_knobs(app, s);
    double t = now_ms();
    /* programs built during the last frame (an edit that recompiles, a first use) */
    bool compiled = sl_program_built_since(&s->seen_builds);
    if (s->last_start_ms > 0) {
        s->last_ms = t - s->last_start_ms;
        /* the frame after a change re-plans targets and may compile, and a frame that compiled
         * paid for that: not what the settings cost (the controller itself leaves out frames
         * rendered still) */
        if (!s->skip_observation && !compiled && s->last_ms < 10000) sl_budget_observe(&s->ctl, s->last_choice, s->last_ms);
    }
    /* the opening frame (or the first after the budget was switched on) is no motion: it
     * compiles programs and fills caches, and taken for motion it would open the window at the
     * cheapest settings until a still refines them */
    bool opening = !(s->last_start_ms > 0);
    s->last_start_ms = t;
    bool moving = moved(app, s) && !opening;
    int before[SL_BUDGET_MAX_KNOBS];
    memcpy(before, s->ctl.choice, sizeof before);
    s->skip_observation = sl_budget_step(&s->ctl, moving);
    for (int k = 0; k < s->ctl.knob_count; k++)
        if (s->ctl.choice[k] != before[k]) apply(app, &s->ctl.knobs[k], s->ctl.choice[k]);
    apply_lod(app, s, false);
    /* a new choice, or the view just came to rest (its best settings may be the moving choice) */
    if (s->skip_observation || s->ctl.still == SL_BUDGET_STILL_FRAMES) SL_DEBUG("budget %.0f ms: %s", b, sl_budget_status(app));
    s->seen_params = app->params.version;
    memcpy(s->last_choice, s->ctl.choice, sizeof s->last_choice);
}

void sl_budget_settle(sl_app *app) {
    sl_budget_state *s = app->budget;
    if (!s || !s->built) return;
    for (int k = 0; k < s->ctl.knob_count; k++)
        if (s->ctl.choice[k] != s->ctl.knobs[k].count - 1) apply(app, &s->ctl.knobs[k], s->ctl.choice[k] = s->ctl.knobs[k].count - 1);
    s->ctl.still = SL_BUDGET_STILL_FRAMES;
    apply_lod(app, s, true);
    s->skip_observation = true;
    s->seen_params = app->params.version;
}

bool sl_budget_settled(sl_app *app) {
    sl_budget_state *s = app->budget;
    return !s || !s->built || s->ctl.still >= SL_BUDGET_STILL_FRAMES;
}

const char *sl_budget_status(sl_app *app) {
    sl_budget_state *s = app->budget;
    if (!s || !s->built) return "";
    const char *what = s->ctl.still >= SL_BUDGET_STILL_FRAMES ? "still: best settings"
                       : s->ctl.still > 0 ? "coming to rest" : "moving";
    int n = snprintf(s->status, sizeof s->status, "%s; last frame %.0f ms", what, s->last_ms);
    if (s->ctl.observations) n += snprintf(s->status + n, sizeof s->status - n, " (predicted %.0f)",
                                           sl_budget_predict_ms(&s->ctl, s->ctl.choice));
    for (int k = 0; k < s->ctl.knob_count && n < (int)sizeof s->status; k++)
        n += snprintf(s->status + n, sizeof s->status - n, "%s%s=%s", k ? ", " : "; ", s->ctl.knobs[k].id,
                      s->ctl.knobs[k].value[s->ctl.choice[k]]);
    if (s->lod_taken && s->ctl.lod_pixels > 0 && n < (int)sizeof s->status)
        snprintf(s->status + n, sizeof s->status - n, "; in motion core.lod_pixels=%g", s->ctl.lod_pixels);
    return s->status;
}

void sl_budget_free(sl_app *app) {
    free(app->budget);
    app->budget = NULL;
}
