/* The panel: parameters (by plugin and group), materials, lights, debug views, plugins, keys and
 * per-pass times, all generated from the schema and the registry. See panel.h. */
#include "gui/panel.h"
#include "gui/gui.h"
#include "budget/budget.h"
#include "core_plugin.h"
#include "log.h"
#include "render/composer.h"
#include "render/renderer.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct text_field { char id[300]; char buf[1024]; } text_field;
typedef struct pass_avg { char name[64]; double ms; bool timed; } pass_avg; /* timed: ms holds a measurement */

struct sl_panel {
    sl_app *app;
    bool visible;
    char *shader_error;
    const char *status;        /* "compiling shaders …" while a change recompiles; NULL otherwise */
    char apply_error[1024];
    const sl_key_binding *bindings;
    int binding_count;
    text_field *fields; int field_count;  /* edit buffers of texture fields */
    pass_avg avg[64]; int avg_count;      /* smoothed per-pass times */
    double interval_avg;                  /* smoothed seconds per frame */
    unsigned long seen_builds;            /* programs built at the last frame rate sample (composer.h) */
    unsigned timing_tick;                 /* frames drawn with the timing view open */
};

/* ------------------------------------------------------------------ applying changes ---- */

bool sl_panel_apply(sl_app *app, const char *assignment, char *err, size_t n) {
    if (sl_app_set(app, assignment, SL_SRC_GUI, err, n)) {
        SL_DEBUG("gui: %s", assignment);
        return true;
    }
    SL_WARN("gui: %s: %s", assignment, err);
    return false;
}

bool sl_panel_set_debug_view(sl_app *app, const char *name, char *err, size_t n) {
    if (sl_app_set_debug_view(app, name, err, n)) {
        SL_DEBUG("gui: debug view %s", name);
        return true;
    }
    SL_WARN("gui: debug view: %s", err);
    return false;
}

/* Value as text that parses back to exactly the same value (floats with 9 digits). */
static void format_exact(const sl_param *q, const sl_value *v, char *buf, size_t n) {
    switch (q->desc.type) {
    case SL_PARAM_FLOAT: snprintf(buf, n, "%.9g", v->f[0]); break;
    case SL_PARAM_COLOR:
    case SL_PARAM_VEC3: snprintf(buf, n, "%.9g,%.9g,%.9g", v->f[0], v->f[1], v->f[2]); break;
    default: sl_param_format(q, v, buf, n);
    }
}

static void apply_value(sl_panel *p, const char *id, const sl_param *q, const sl_value *v) {
    char text[1200], assignment[1600];
    format_exact(q, v, text, sizeof text);
    snprintf(assignment, sizeof assignment, "%s=%s", id, text);
    p->apply_error[0] = 0;
    sl_panel_apply(p->app, assignment, p->apply_error, sizeof p->apply_error);
}

/* ------------------------------------------------------------------ one widget ---------- */

static const char *source_name(sl_param_source s) {
    static const char *names[] = {"default", "scene", "command line", "GUI"};
    return s >= 0 && s <= SL_SRC_GUI ? names[s] : "?";
}

static void tooltip_for(const char *id, const sl_param *q, bool show_source) {
    char tip[2048];
    size_t u = 0;
    static const char *types[] = {"?", "bool", "int", "float", "enum", "colour", "vec3", "texture"};
    u += snprintf(tip + u, sizeof tip - u, "%s\n\n%s (%s", q->desc.description ? q->desc.description : "", id,
                  types[q->desc.type <= SL_PARAM_TEXTURE ? q->desc.type : 0]);
    if ((q->desc.type == SL_PARAM_INT || q->desc.type == SL_PARAM_FLOAT) && q->desc.min < q->desc.max)
        u += snprintf(tip + u, sizeof tip - u, ", %g .. %g", q->desc.min, q->desc.max);
    if (q->desc.unit && *q->desc.unit) u += snprintf(tip + u, sizeof tip - u, " %s", q->desc.unit);
    if (q->desc.zero_label) u += snprintf(tip + u, sizeof tip - u, "; 0 = %s", q->desc.zero_label);
    u += snprintf(tip + u, sizeof tip - u, ")");
    if (q->desc.flags & SL_PARAM_NEEDS_RECOMPILE) u += snprintf(tip + u, sizeof tip - u, "\nchanging it recompiles shaders");
    if (q->desc.flags & SL_PARAM_QUALITY_KNOB) u += snprintf(tip + u, sizeof tip - u, "\nquality knob (swept by the benchmark)");
    if (show_source) snprintf(tip + u, sizeof tip - u, "\nset by: %s", source_name(q->source));
    sl_ui_tooltip(tip);
}

static int decimals_for(float step) {
    if (!(step > 0)) return 3;
    int d = (int)ceilf(-log10f(step) - 1e-4f);
    return d < 0 ? 0 : d > 6 ? 6 : d;
}

/* s with '%' doubled, for a printf format */
static void escape_percent(const char *s, char *out, size_t n) {
    size_t k = 0;
    for (; s && *s && k + 2 < n; s++) {
        if (*s == '%') out[k++] = '%';
        out[k++] = *s;
    }
    out[k] = 0;
}

/* printf format for a numeric widget holding `zero` (value 0) with its unit: the parameter's
 * zero_label ("auto", "off") in place of "0 <unit>" where it has one. */
static void number_format(const sl_param *q, bool is_int, bool zero, char *fmt, size_t n) {
    char unit[64];
    if (zero && q->desc.zero_label) {
        escape_percent(q->desc.zero_label, fmt, n);
        return;
    }
    escape_percent(q->desc.unit, unit, sizeof unit);
    if (is_int) snprintf(fmt, n, "%%d%s%s", *unit ? " " : "", unit);
    else snprintf(fmt, n, "%%.%df%s%s", decimals_for(q->desc.step), *unit ? " " : "", unit);
}

static text_field *field_for(sl_panel *p, const char *id, const char *initial) {
    for (int i = 0; i < p->field_count; i++)
        if (!strcmp(p->fields[i].id, id)) return &p->fields[i];
    p->fields = realloc(p->fields, (p->field_count + 1) * sizeof *p->fields);
    text_field *f = &p->fields[p->field_count++];
    snprintf(f->id, sizeof f->id, "%s", id);
    snprintf(f->buf, sizeof f->buf, "%s", initial ? initial : "");
    return f;
}

/* Draws the widget for schema entry q holding *v (addressed as `id`); applies a change. */
static void param_widget(sl_panel *p, const char *id, const sl_param *q, const sl_value *current) {
    sl_value v = *current;
    char label[400], fmt[96];
    snprintf(label, sizeof label, "%s##%s", q->desc.id, id);
    bool changed = false;
    switch (q->desc.type) {
    case SL_PARAM_BOOL: changed = sl_ui_checkbox(label, &v.b); break;
    case SL_PARAM_INT:
        number_format(q, true, v.i == 0, fmt, sizeof fmt);
        changed = sl_ui_int(label, &v.i, (int)q->desc.min, (int)q->desc.max, q->desc.step > 0 ? q->desc.step : 0.2f, fmt);
        break;
    case SL_PARAM_FLOAT: {
        number_format(q, false, v.f[0] == 0, fmt, sizeof fmt);
        float speed = q->desc.step > 0 ? q->desc.step
                      : q->desc.min < q->desc.max ? (q->desc.max - q->desc.min) / 500.f : 0.01f;
        changed = sl_ui_float(label, &v.f[0], q->desc.min, q->desc.max, speed, fmt);
        break;
    }
    case SL_PARAM_ENUM: {
        int count = 0;
        while (q->desc.enum_values && q->desc.enum_values[count]) count++;
        changed = count > 0 && sl_ui_combo(label, &v.i, q->desc.enum_values, count);
        break;
    }
    case SL_PARAM_COLOR: changed = sl_ui_color3(label, v.f); break;
    case SL_PARAM_VEC3:
        number_format(q, false, false, fmt, sizeof fmt);
        changed = sl_ui_float3(label, v.f, q->desc.step > 0 ? q->desc.step : 0.01f, fmt);
        break;
    case SL_PARAM_TEXTURE: {
        text_field *f = field_for(p, id, v.s);
        if (sl_ui_input_text(label, f->buf, sizeof f->buf)) {
            char assignment[1400];
            snprintf(assignment, sizeof assignment, "%s=%s", id, f->buf);
            p->apply_error[0] = 0;
            sl_panel_apply(p->app, assignment, p->apply_error, sizeof p->apply_error);
        }
        break;
    }
    }
    tooltip_for(id, q, q->desc.scope == SL_SCOPE_GLOBAL);
    if (changed) apply_value(p, id, q, &v);
}

/* ------------------------------------------------------------------ sections ------------ */

static void plugin_params(sl_panel *p, const char *owner) {
    sl_params *P = &p->app->params;
    /* ungrouped first, then each group in the order it first appears */
    const char *groups[64];
    int ngroups = 0;
    for (int i = 0; i < P->count; i++) {
        sl_param *q = &P->items[i];
        if (q->desc.scope != SL_SCOPE_GLOBAL || strcmp(q->owner, owner) || (q->desc.flags & SL_PARAM_HIDDEN)) continue;
        if (!q->desc.group) { param_widget(p, q->full_id, q, &q->value); continue; }
        bool seen = false;
        for (int g = 0; g < ngroups; g++) seen |= !strcmp(groups[g], q->desc.group);
        if (!seen && ngroups < 64) groups[ngroups++] = q->desc.group;
    }
    for (int g = 0; g < ngroups; g++) {
        if (!sl_ui_tree_push(groups[g], true)) continue;
        for (int i = 0; i < P->count; i++) {
            sl_param *q = &P->items[i];
            if (q->desc.scope != SL_SCOPE_GLOBAL || strcmp(q->owner, owner) || (q->desc.flags & SL_PARAM_HIDDEN)) continue;
            if (q->desc.group && !strcmp(q->desc.group, groups[g])) param_widget(p, q->full_id, q, &q->value);
        }
        sl_ui_tree_pop();
    }
}

static void section_parameters(sl_panel *p) {
    sl_app *app = p->app;
    for (int i = 0; i < app->plugins.count; i++) {
        sl_plugin_rec *r = app->plugins.items[i];
        char label[300];
        const char *state = !r->ok ? "  [disabled]" : sl_plugin_enabled(&app->plugins, i) ? "" : "  [off]";
        snprintf(label, sizeof label, "%s%s##plugin-%s", r->id, state, r->id);
        sl_ui_push_id(r->id);
        if (sl_ui_tree_push(label, i == 0 || r->ok)) {
            if (r->desc.description) sl_ui_tooltip(r->desc.description);
            if (!r->ok) sl_ui_text_colored(1, 0.5f, 0.4f, "disabled: %s", r->disabled_reason ? r->disabled_reason : "?");
            else plugin_params(p, r->id);
            sl_ui_tree_pop();
        } else if (r->desc.description) {
            sl_ui_tooltip(r->desc.description);
        }
        sl_ui_pop_id();
    }
}

static void section_materials(sl_panel *p) {
    sl_app *app = p->app;
    for (int m = 0; m < app->scene.material_count; m++) {
        const sl_material *mat = &app->scene.materials[m];
        char label[300];
        snprintf(label, sizeof label, "%s (%s)##material-%d", mat->name, mat->model, m);
        if (!sl_ui_tree_push(label, false)) continue;
        sl_mat_state *ms = &app->materials[m];
        for (int k = 0; k < ms->count; k++) {
            sl_mat_value *mv = &ms->values[k];
            const sl_param *q = &app->params.items[mv->param];
            if (q->desc.flags & SL_PARAM_HIDDEN) continue;
            char id[600];
            snprintf(id, sizeof id, "material.%s.%s", mat->name, q->full_id);
            param_widget(p, id, q, &mv->v);
            if (!mv->present) {
                sl_ui_same_line();
                sl_ui_text_disabled("(default)");
            }
        }
        sl_ui_tree_pop();
    }
}

/* The current value of a light key: core keys live in the light record, plugin keys in
 * app->light_params by their slot. */
static sl_value light_value(sl_app *app, int li, const sl_param *q) {
    const sl_light *L = &app->scene.lights[li];
    sl_value v = {0};
    if (sl_core_light_get(L, q->full_id, &v)) return v;
    const float *s = app->light_params[li];
    int slot = q->desc.light_slot;
    int comps = q->desc.type == SL_PARAM_COLOR || q->desc.type == SL_PARAM_VEC3 ? 3 : 1;
    if (slot < 0 || slot + comps > 8) return v;
    switch (q->desc.type) {
    case SL_PARAM_BOOL: v.b = s[slot] != 0; break;
    case SL_PARAM_INT: case SL_PARAM_ENUM: v.i = (int)s[slot]; break;
    default: for (int c = 0; c < comps; c++) v.f[c] = s[slot + c];
    }
    return v;
}

static void section_lights(sl_panel *p) {
    sl_app *app = p->app;
    for (int li = 0; li < app->scene.light_count; li++) {
        const sl_light *L = &app->scene.lights[li];
        sl_ui_push_id(L->name);
        /* the per-light on/off sits on the row itself, like the plugin toggles */
        char id[300];
        snprintf(id, sizeof id, "light.%s.enabled", L->name);
        sl_param *en = sl_params_find_key(&app->params, SL_SCOPE_LIGHT, "enabled", L->type);
        if (en) {
            sl_value v = light_value(app, li, en);
            if (sl_ui_checkbox("##enabled", &v.b)) apply_value(p, id, en, &v);
            sl_ui_tooltip("Per-light on/off (light.NAME.enabled).");
            sl_ui_same_line();
        }
        char label[300];
        snprintf(label, sizeof label, "%s (%s)", L->name, L->type);
        if (sl_ui_tree_push(label, false)) {
            for (int i = 0; i < app->params.count; i++) {
                const sl_param *q = &app->params.items[i];
                if (q->desc.scope != SL_SCOPE_LIGHT || (q->desc.flags & SL_PARAM_HIDDEN)) continue;
                if (q->desc.light_type && strcmp(q->desc.light_type, L->type)) continue;
                if (q == en) continue;
                snprintf(id, sizeof id, "light.%s.%s", L->name, q->full_id);
                sl_value v = light_value(app, li, q);
                param_widget(p, id, q, &v);
            }
            sl_ui_tree_pop();
        }
        sl_ui_pop_id();
    }
}

static void section_view(sl_panel *p, sl_panel_actions *act) {
    sl_app *app = p->app;
    const char *names[128];
    const char *descs[128];
    int count = 0, current = 0;
    names[count] = "final";
    descs[count++] = "the shaded image";
    for (int i = 0; i < app->plugins.chunk_count && count < 128; i++) {
        const sl_chunk_reg *c = &app->plugins.chunks[i];
        if (c->d.hook != SL_HOOK_DEBUG_VIEW && c->d.hook != SL_HOOK_DEBUG_VIEW_LIGHT) continue;
        if (!sl_plugin_enabled(&app->plugins, c->owner)) continue;
        if (app->debug_view && !strcmp(app->debug_view, c->d.name)) current = count;
        descs[count] = c->d.description;
        names[count++] = c->d.name;
    }
    int chosen = current;
    if (sl_ui_combo("debug view", &chosen, names, count) && chosen != current) {
        char err[512];
        sl_panel_set_debug_view(app, names[chosen], err, sizeof err);
    }
    sl_ui_tooltip(descs[current]);
    if (sl_ui_button("reload shaders (F5)")) act->reload_shaders = true;
    sl_ui_same_line();
    if (sl_ui_button("screenshot (P)")) act->screenshot = true;
}

static void section_timing(sl_panel *p, double dt) {
    sl_app *app = p->app;
    const sl_frame_stats *st = sl_renderer_stats(app);
    /* pass times only while this view is open, and one frame in ten: timing brackets every pass
     * with glFinish, which serialises a CPU rasteriser's frame */
    if (++p->timing_tick % 10 == 0) sl_renderer_request_timing(app);
    /* an interval in which a program was built (the first frames, an edit that recompiles, the
     * first use of a program) times the compiler, not the frame: left out, as the budget leaves
     * it out of its cost model (budget.c) */
    bool compiled = sl_program_built_since(&p->seen_builds);
    if (dt > 1e-4 && !compiled) p->interval_avg = p->interval_avg > 0 ? 0.9 * p->interval_avg + 0.1 * dt : dt;
    sl_ui_text("%s  %dx%d  %.1f fps", app->backend.name, app->backend.width, app->backend.height,
               p->interval_avg > 0 ? 1.0 / p->interval_avg : 0.0);
    /* the long lines wrap at the panel's edge rather than run out of it */
    char line[512];
    const char *budget = sl_budget_status(app);
    if (*budget) snprintf(line, sizeof line, "budget %s", budget), sl_ui_text_wrapped(line);
    if (!st) return;
    bool timed = st->timing_mode && strcmp(st->timing_mode, "off");
    snprintf(line, sizeof line, "frame %.2f ms (CPU), %d draw calls, %ld triangles, %d programs", st->frame_ms,
             st->draw_calls, st->triangles, st->program_count);
    sl_ui_text_wrapped(line);
    sl_ui_text_disabled("pass times: %s%s", st->timing_mode ? st->timing_mode : "?",
                        st->timing_mode && !strcmp(st->timing_mode, "glfinish") ? " (CPU rasteriser: honest, serialising)" : "");
    if (!sl_ui_begin_table("passes", 3)) return;
    static const char *cols[] = {"pass", "plugin", "ms (avg)"};
    sl_ui_table_header(cols, 3);
    for (int i = 0; i < st->pass_count; i++) {
        const sl_pass_stat *ps = &st->passes[i];
        pass_avg *a = NULL;
        for (int k = 0; k < p->avg_count; k++)
            if (!strcmp(p->avg[k].name, ps->name)) a = &p->avg[k];
        if (!a && p->avg_count < 64) {
            a = &p->avg[p->avg_count++];
            snprintf(a->name, sizeof a->name, "%s", ps->name);
        }
        /* the average starts at the first timed frame (frames between timed ones report 0) */
        if (a && ps->ran && timed) a->ms = a->timed ? 0.7 * a->ms + 0.3 * ps->ms : ps->ms, a->timed = true;
        sl_ui_table_next_row();
        sl_ui_table_next_column();
        sl_ui_text("%s", ps->name);
        sl_ui_table_next_column();
        sl_ui_text("%s", ps->owner ? ps->owner : "core");
        sl_ui_table_next_column();
        if (!ps->ran) sl_ui_text_disabled("skipped");
        else if (a ? a->timed : timed) sl_ui_text("%8.3f", a ? a->ms : ps->ms);
        else sl_ui_text_disabled("ran"); /* not timed yet: one frame in ten is */
    }
    sl_ui_end_table();
}

static void section_plugins(sl_panel *p) {
    sl_app *app = p->app;
    for (int i = 0; i < app->plugins.count; i++) {
        sl_plugin_rec *r = app->plugins.items[i];
        if (!r->ok) {
            sl_ui_text_colored(1, 0.45f, 0.35f, "%s  DISABLED", r->id);
            sl_ui_indent();
            sl_ui_text_wrapped(r->disabled_reason ? r->disabled_reason : "?");
            sl_ui_text_disabled("%s, requested by %s", r->path ? r->path : "-", r->requested_by ? r->requested_by : "?");
            sl_ui_unindent();
            continue;
        }
        bool on = sl_plugin_enabled(&app->plugins, i);
        if (on) sl_ui_text("%s  %s", r->id, r->desc.version ? r->desc.version : "");
        else sl_ui_text_disabled("%s  %s (off: costs nothing)", r->id, r->desc.version ? r->desc.version : "");
        char tip[2048];
        snprintf(tip, sizeof tip, "%s\n%s\nrequested by %s", r->desc.description ? r->desc.description : "",
                 r->path ? r->path : "", r->requested_by ? r->requested_by : "?");
        sl_ui_tooltip(tip);
    }
}

static void section_keys(sl_panel *p, sl_panel_actions *act) {
    sl_app *app = p->app;
    sl_ui_text_disabled("viewer: drag orbit/pan, wheel zoom, WASDQE fly, C camera, P screenshot, F1 panel, F5 reload");
    for (int i = 0; i < p->binding_count; i++) {
        const sl_key_binding *b = &p->bindings[i];
        const sl_key_reg *k = &app->plugins.keys[b->reg];
        char label[512], key[32];
        if (b->unbound) snprintf(key, sizeof key, "(none)");
        else snprintf(key, sizeof key, "%s%s", b->shift ? "Shift+" : "", b->key);
        snprintf(label, sizeof label, "%-9s %s [%s]##key%d", key, k->d.description ? k->d.description : "",
                 app->plugins.items[k->owner]->id, i);
        if (sl_ui_selectable(label, false)) act->trigger_binding = i;
        if (b->clash[0]) {
            char tip[400];
            snprintf(tip, sizeof tip, "%s%s was taken by %s", b->key, b->unbound ? " (and Shift+key)" : "", b->clash);
            sl_ui_tooltip(tip);
        }
    }
}

/* ------------------------------------------------------------------ panel --------------- */

sl_panel *sl_panel_create(sl_app *app, const sl_key_binding *bindings, int count) {
    sl_panel *p = calloc(1, sizeof *p);
    p->app = app;
    p->visible = true;
    p->bindings = bindings;
    p->binding_count = count;
    return p;
}

void sl_panel_destroy(sl_panel *p) {
    if (!p) return;
    free(p->shader_error);
    free(p->fields);
    free(p);
}

void sl_panel_toggle(sl_panel *p) { p->visible = !p->visible; }

void sl_panel_set_shader_error(sl_panel *p, const char *text) {
    free(p->shader_error);
    p->shader_error = text && *text ? strdup(text) : NULL;
}

void sl_panel_set_status(sl_panel *p, const char *text) { p->status = text; }

void sl_panel_draw(sl_panel *p, double dt, sl_panel_actions *act) {
    memset(act, 0, sizeof *act);
    act->trigger_binding = -1;
    if (p->visible) {
        float w = (float)p->app->backend.width, h = (float)p->app->backend.height;
        if (sl_ui_begin("shadelab  (F1 hides)", 8, 8, w * 0.6f < 380 ? w * 0.6f : 380, h - 16 > 200 ? h - 16 : 200, 0.85f)) {
            if (p->apply_error[0]) sl_ui_text_colored(1, 0.45f, 0.35f, "%s", p->apply_error);
            if (sl_ui_header("Timing", true)) section_timing(p, dt);
            if (sl_ui_header("View", true)) section_view(p, act);
            if (sl_ui_header("Parameters", true)) section_parameters(p);
            if (sl_ui_header("Materials", false)) section_materials(p);
            if (sl_ui_header("Lights", true)) section_lights(p);
            if (sl_ui_header("Plugins", false)) section_plugins(p);
            if (sl_ui_header("Keys", false)) section_keys(p, act);
        }
        sl_ui_end();
    }
    /* the status line shows whether or not the panel is visible */
    if (p->status) {
        if (sl_ui_begin_overlay_right("##status", 0.1f, 0.1f, 0.1f, 0.85f)) sl_ui_text_colored(1, 0.9f, 0.4f, "%s", p->status);
        sl_ui_end();
    }
    /* a failed shader stays on screen whether or not the panel is visible */
    if (p->shader_error) {
        bool dismiss = false;
        if (sl_ui_begin_overlay("##shader-error", 0.35f, 0.02f, 0.02f, 0.92f)) {
            if (strstr(p->shader_error, "keep their last good program"))
                sl_ui_text_colored(1, 0.8f, 0.3f, "Shader error: the last good program is still in use. "
                                                  "Fix the file; it reloads on save (or F5).");
            else if (!strncmp(p->shader_error, "Loading reported:", 17))
                sl_ui_text_colored(1, 0.8f, 0.3f, "Problems while loading (stderr has the full log):");
            else
                sl_ui_text_colored(1, 0.8f, 0.3f, "Error (stderr has the full log):");
            const char *nl = strchr(p->shader_error, '\n');
            sl_ui_text_wrapped(!strncmp(p->shader_error, "Loading reported:", 17) && nl ? nl + 1 : p->shader_error);
            dismiss = sl_ui_small_button("dismiss");
        }
        sl_ui_end();
        if (dismiss) sl_panel_set_shader_error(p, NULL);
    }
}
