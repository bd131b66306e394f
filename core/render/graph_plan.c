/* The render graph's plan: the core's passes and the enabled plugins' passes ordered by stage,
 * inputs checked against earlier outputs, targets allocated. See renderer_internal.h. */
#include "render/renderer_internal.h"
#include "log.h"
#include <shadelab/gl.h>
#include <stdlib.h>
#include <limits.h>
#include <string.h>


static const sl_target_desc core_color = {.name = "color", .format = SL_FORMAT_RGBA16F};
static const sl_target_desc core_color32 = {.name = "color", .format = SL_FORMAT_RGBA32F};
static const sl_target_desc core_depth = {.name = "depth", .format = SL_FORMAT_DEPTH32F};
static const sl_target_desc core_display = {.name = "display", .format = SL_FORMAT_RGBA8};
static const sl_target_desc core_motion = {.name = "motion", .format = SL_FORMAT_RG16F};
static const sl_target_desc core_normal = {.name = "normal", .format = SL_FORMAT_RGBA16F};
static sl_target_desc forward_outputs[4];
static const char *resolve_inputs[] = {"forward.ssaa", NULL};
static sl_target_desc resolve_outputs[1];
static sl_pass_desc resolve_pass = {.struct_size = sizeof(sl_pass_desc), .name = "ssaa-resolve", .stage = SL_STAGE_OPAQUE,
                                    .inputs = resolve_inputs, .outputs = resolve_outputs, .output_count = 1,
                                    .display_on_write = true};
/* glTF alphaMode BLEND: the blended materials over everything opaque (the forward pass, envmap's
 * background, deferred lighting), back to front; only while a material is blended. Not
 * display_on_write: blending over the clamped display image would differ from blending in linear
 * HDR, so with a blended material the display pass encodes "color" as before. */
static const char *blend_inputs[] = {"depth", NULL};
static sl_target_desc blend_outputs[1];
static sl_pass_desc blend_pass = {.struct_size = sizeof(sl_pass_desc), .name = "forward-blend", .stage = SL_STAGE_BLEND,
                                  .inputs = blend_inputs, .outputs = blend_outputs, .output_count = 1};
/* The scene behind (ABI 1.17, shader.h): materials with a SCENE_BEHIND hook over everything
 * opaque, which it captures first (graph_run.c); only while such a material exists. Not
 * display_on_write, for the reason above; it reads "color" through the capture, not as an input
 * (which would ping-pong it). */
static sl_target_desc behind_outputs[1];
static sl_pass_desc behind_pass = {.struct_size = sizeof(sl_pass_desc), .name = "forward-behind",
                                   .stage = SL_STAGE_BEHIND, .inputs = blend_inputs, .outputs = behind_outputs,
                                   .output_count = 1};
static const char *display_inputs[] = {"color", NULL};
static sl_pass_desc forward_pass = {.struct_size = sizeof(sl_pass_desc), .name = "forward", .stage = SL_STAGE_OPAQUE,
                                    .outputs = forward_outputs, .output_count = 2, /* + "motion", "normal" */
                                    .display_on_write = true};
/* The depth pre-pass (ABI 1.13, pass.h): "depth" and "normal" before the forward pass, for the
 * passes between them that read either (screen-space ambient occlusion feeding the forward pass). */
static sl_target_desc prepass_outputs[2];
static sl_pass_desc prepass_pass = {.struct_size = sizeof(sl_pass_desc), .name = "depth-prepass",
                                    .stage = SL_STAGE_DEPTH_PREPASS, .outputs = prepass_outputs, .output_count = 2};
/* The separate display pass runs only on frames where no pass wrote "display" on the fly. */
static bool display_active(void *user, const sl_frame *f) {
    (void)f;
    return ((sl_renderer *)user)->color_final;
}
static sl_pass_desc display_pass = {.struct_size = sizeof(sl_pass_desc), .name = "display", .stage = SL_STAGE_DISPLAY,
                                    .inputs = display_inputs, .outputs = &core_display, .output_count = 1,
                                    .is_active = display_active};

/* A pass that writes "color" at the output size (ABI 1.18, SL_SIZE_OUTPUT): the upscaler. */
static bool upscales(const graph_pass *g) {
    for (int k = 0; k < g->d->output_count; k++)
        if (!strcmp(g->d->outputs[k].name, "color") && g->d->outputs[k].width == SL_SIZE_OUTPUT) return true;
    return false;
}

static int cmp_stage(const void *a, const void *b) {
    const graph_pass *x = a, *y = b;
    if (x->d->stage != y->d->stage) return x->d->stage < y->d->stage ? -1 : 1;
    return 0;
}

/* Whether an enabled plugin's pass reads `name`, at a stage in [from, to). */
static bool read_between(sl_app *app, const char *name, int from, int to) {
    for (int i = 0; i < app->plugins.pass_count; i++) {
        const sl_pass_reg *p = &app->plugins.passes[i];
        if (sl_plugin_enabled(&app->plugins, p->owner) && (int)p->d.stage >= from && (int)p->d.stage < to &&
            sl_graph_lists(p->d.inputs, name))
            return true;
    }
    return false;
}

bool sl_graph_wants_motion(sl_app *app) { return read_between(app, "motion", INT_MIN, INT_MAX); }

bool sl_graph_wants_prepass(sl_app *app) {
    return read_between(app, "depth", INT_MIN, SL_STAGE_OPAQUE) || read_between(app, "normal", INT_MIN, SL_STAGE_OPAQUE);
}

bool sl_graph_wants_normal(sl_app *app) { return !sl_graph_wants_prepass(app) && read_between(app, "normal", INT_MIN, INT_MAX); }

/* A pass that writes no target of the graph (shadow maps, a prefiltered environment: textures of
 * its own) keeps what it wrote when the graph is planned again, e.g. for a new render scale: it
 * keeps its skip state too, so it re-runs only when what it declared it depends on changed. */
typedef struct kept_pass { const sl_pass_desc *d; int owner; uint64_t signature, depends; int draws; double ms; } kept_pass;

static int keep_own_output_passes(const sl_renderer *r, kept_pass **out) {
    *out = calloc(r->pass_count + 1, sizeof **out);
    int n = 0;
    for (int i = 0; *out && i < r->pass_count; i++) {
        const graph_pass *g = &r->passes[i];
        if (g->has_run && !g->broken && g->d->output_count == 0)
            (*out)[n++] = (kept_pass){g->d, g->owner, g->last_signature, g->last_depends, g->last_draws, g->last_ms};
    }
    return n;
}

static void restore_own_output_passes(sl_renderer *r, const kept_pass *kept, int n) {
    for (int i = 0; i < r->pass_count; i++)
        for (int k = 0; k < n; k++) {
            graph_pass *g = &r->passes[i];
            if (g->d != kept[k].d || g->owner != kept[k].owner || g->broken) continue;
            g->has_run = true;
            g->last_signature = kept[k].signature, g->last_depends = kept[k].depends;
            g->last_draws = kept[k].draws, g->last_ms = kept[k].ms;
        }
}

void sl_graph_plan(sl_app *app) {
    sl_renderer *r = R(app);
    kept_pass *kept;
    int kept_count = keep_own_output_passes(r, &kept);
    sl_graph_free(r);
    for (int i = 0; i < app->plugins.pass_count; i++) sl_plugins_update_pass_io(&app->plugins, i); /* ABI 1.13 */
    /* core.ssaa > 1: the forward pass renders "forward.ssaa" at k× the viewport and the resolve
     * pass box-filters it into the viewport-sized "color" everything downstream sees. */
    sl_param *ssaa = sl_params_find(&app->params, "core.ssaa");
    r->ssaa = ssaa && ssaa->value.i > 1 ? ssaa->value.i : 1;
    const sl_param *rerun = sl_params_find(&app->params, "core.rerun_passes");
    r->rerun_passes = rerun && rerun->value.b;
    forward_outputs[0] = app->opt.float32 ? core_color32 : core_color;
    forward_outputs[1] = core_depth;
    /* "motion" (pass.h, ABI 1.6) and "normal" (ABI 1.13) only while an enabled plugin's pass reads
     * them: the forward programs then compute them (SL_MOTION_VECTORS, SL_NORMAL_TARGET), so they are
     * recomposed when that changes. A pass before the forward pass that reads "depth" or "normal"
     * brings the depth pre-pass, which writes both; the forward pass then leaves "normal" alone. */
    bool motion = sl_graph_wants_motion(app), normal = sl_graph_wants_normal(app);
    r->prepass = sl_graph_wants_prepass(app);
    forward_pass.output_count = 2;
    if (motion) forward_outputs[forward_pass.output_count++] = core_motion;
    if (normal) forward_outputs[forward_pass.output_count++] = core_normal;
    prepass_outputs[0] = core_depth;
    prepass_outputs[1] = core_normal;
    if (motion != r->motion || normal != r->normal) {
        r->motion = motion;
        r->normal = normal;
        sl_gpu_compose_all(app);
    }
    resolve_outputs[0] = forward_outputs[0];
    /* "color" drawn over, not read: its latest texture is bound, no ping-pong */
    blend_outputs[0] = forward_outputs[0];
    r->blend_planned = sl_gpu_scene_has_blended(app);
    behind_outputs[0] = forward_outputs[0];
    r->behind_planned = sl_gpu_scene_has_behind(app);
    if (r->ssaa > 1) { /* "depth", "motion" and "normal" at the forward pass's size */
        forward_outputs[0].name = "forward.ssaa";
        for (int k = 0; k < 4; k++) forward_outputs[k].scale = (float)r->ssaa;
        prepass_outputs[0].scale = prepass_outputs[1].scale = (float)r->ssaa;
    }
    r->display_desc = display_pass; /* its own copy: is_active reads this renderer (harnesses coexist) */
    r->display_desc.user = r;
    r->color_final = true;
    int total = app->plugins.pass_count + 6;
    r->passes = calloc(total, sizeof *r->passes);
    if (r->prepass) r->passes[r->pass_count++] = (graph_pass){.d = &prepass_pass, .owner = -1, .core_prepass = true};
    r->passes[r->pass_count++] = (graph_pass){.d = &forward_pass, .owner = -1, .core_forward = true};
    if (r->ssaa > 1) r->passes[r->pass_count++] = (graph_pass){.d = &resolve_pass, .owner = -1, .core_resolve = true};
    if (r->behind_planned) r->passes[r->pass_count++] = (graph_pass){.d = &behind_pass, .owner = -1, .core_behind = true};
    if (r->blend_planned) r->passes[r->pass_count++] = (graph_pass){.d = &blend_pass, .owner = -1, .core_blend = true};
    for (int i = 0; i < app->plugins.pass_count; i++) {
        sl_pass_reg *reg = &app->plugins.passes[i];
        if (!sl_plugin_enabled(&app->plugins, reg->owner)) continue; /* disabled plugins cost nothing */
        r->passes[r->pass_count++] = (graph_pass){.d = &reg->d, .owner = reg->owner};
    }
    r->passes[r->pass_count++] = (graph_pass){.d = &r->display_desc, .owner = -1, .core_display = true};
    /* stable sort by stage (insertion sort keeps registration order) */
    for (int i = 1; i < r->pass_count; i++)
        for (int j = i; j > 0 && cmp_stage(&r->passes[j - 1], &r->passes[j]) > 0; j--) {
            graph_pass t = r->passes[j]; r->passes[j] = r->passes[j - 1]; r->passes[j - 1] = t;
        }
    /* validate inputs against what earlier passes produce, then allocate (from the upscaler on,
     * "color" and the viewport are at the output size: pass.h, SL_SIZE_OUTPUT) */
    r->upscaler = -1;
    for (int i = 0; i < r->pass_count; i++) {
        graph_pass *g = &r->passes[i];
        for (const char *const *in = g->d->inputs; in && *in; in++) {
            bool produced = false;
            for (int j = 0; j < i && !produced; j++)
                for (int k = 0; k < r->passes[j].d->output_count; k++)
                    produced |= !strcmp(r->passes[j].d->outputs[k].name, *in) && !r->passes[j].broken;
            if (!produced) {
                SL_ERROR("render graph: pass \"%s\" (%s) reads \"%s\", which no earlier pass writes; pass skipped",
                         g->d->name, g->owner >= 0 ? app->plugins.items[g->owner]->id : "core", *in);
                g->broken = true;
            }
        }
        if (g->broken) continue;
        if (r->upscaler < 0 && upscales(g)) r->upscaler = i;
        for (int k = 0; k < g->d->output_count; k++) {
            const sl_target_desc *o = &g->d->outputs[k];
            resource probe = {.name = (char *)sl_graph_name_at(r, i, o->name, true)};
            sl_graph_add_target(r, o, i, sl_graph_pass_reads(r, g, &probe));
        }
    }
    restore_own_output_passes(r, kept, kept_count);
    free(kept);
    r->plan_dirty = false;
}


static bool writes(const graph_pass *g, const char *name) {
    for (int k = 0; k < g->d->output_count; k++)
        if (!strcmp(g->d->outputs[k].name, name)) return true;
    return false;
}

/* The display encoding on the fly (sl_pass_desc.display_on_write, ABI 1.8). "color" is built by a
 * chain of writers: the last pass that reads and writes it (ping-pong: it samples the previous
 * contents and writes the other texture) or, when none does, the first pass that writes it,
 * followed by passes that only draw on top of it (envmap's background). When every pass of that
 * final chain writes through bind_outputs only and nothing after its start reads "color", the
 * chain's "color" attachment becomes the sRGB view of "display": the same draws, clamped and
 * encoded by the blending hardware, and the core's display pass is skipped. "color" then keeps
 * the input of the chain (e.g. the linear colour before tone mapping), not the final image:
 * keep_color (EXR output, tests and benchmarks reading "color") turns this off. */
void sl_graph_route_display(sl_app *app, int first, bool keep_color) {
    sl_renderer *r = R(app);
    int start = -1, last_reader = -1;
    bool *runs = calloc(r->pass_count + 1, sizeof *runs);
    for (int i = 0; i < r->pass_count; i++) {
        graph_pass *g = &r->passes[i];
        if (g->core_display || g->broken) continue;
        runs[i] = !g->d->is_active || g->d->is_active(g->d->user, &r->frame);
        if (!runs[i]) continue;
        bool w = writes(g, "color"), rd = sl_graph_lists(g->d->inputs, "color");
        if (w && (rd || start < 0)) start = i;
        else if (rd) last_reader = i;
    }
    /* a pass view (SL_CHUNK_PASS_VIEW) is written by the display pass itself */
    bool ok = !keep_color && !sl_graph_pass_view(app) && start >= first && last_reader < start &&
              start >= r->upscaler; /* the display has the output size from the upscaler on */
    for (int i = start; ok && i >= 0 && i < r->pass_count; i++)
        if (runs[i] && writes(&r->passes[i], "color") && !r->passes[i].d->display_on_write) ok = false;
    for (int i = 0; i < r->pass_count; i++) {
        graph_pass *g = &r->passes[i];
        bool to = ok && runs[i] && i >= start && writes(g, "color");
        if (to != g->to_display) g->has_run = false; /* its last output went to the other target */
        g->to_display = to;
    }
    r->color_final = !ok;
    free(runs);
}
