/* The render graph's plan: the core's passes and the enabled plugins' passes ordered by stage,
 * inputs checked against earlier outputs, targets allocated. See renderer_internal.h. */
#include "render/renderer_internal.h"
#include "log.h"
#include <shadelab/gl.h>
#include <stdlib.h>
#include <string.h>


static const sl_target_desc core_color = {.name = "color", .format = SL_FORMAT_RGBA16F};
static const sl_target_desc core_color32 = {.name = "color", .format = SL_FORMAT_RGBA32F};
static const sl_target_desc core_depth = {.name = "depth", .format = SL_FORMAT_DEPTH32F};
static const sl_target_desc core_display = {.name = "display", .format = SL_FORMAT_RGBA8};
static const sl_target_desc core_motion = {.name = "motion", .format = SL_FORMAT_RG16F};
static sl_target_desc forward_outputs[3];
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
static const char *display_inputs[] = {"color", NULL};
static sl_pass_desc forward_pass = {.struct_size = sizeof(sl_pass_desc), .name = "forward", .stage = SL_STAGE_OPAQUE,
                                    .outputs = forward_outputs, .output_count = 2, /* 3 with "motion" */
                                    .display_on_write = true};
/* The separate display pass runs only on frames where no pass wrote "display" on the fly. */
static bool display_active(void *user, const sl_frame *f) {
    (void)f;
    return ((sl_renderer *)user)->color_final;
}
static sl_pass_desc display_pass = {.struct_size = sizeof(sl_pass_desc), .name = "display", .stage = SL_STAGE_DISPLAY,
                                    .inputs = display_inputs, .outputs = &core_display, .output_count = 1,
                                    .is_active = display_active};

static int cmp_stage(const void *a, const void *b) {
    const graph_pass *x = a, *y = b;
    if (x->d->stage != y->d->stage) return x->d->stage < y->d->stage ? -1 : 1;
    return 0;
}

/* Orders passes, checks inputs, allocates targets. */
bool sl_graph_wants_motion(sl_app *app) {
    for (int i = 0; i < app->plugins.pass_count; i++)
        if (sl_plugin_enabled(&app->plugins, app->plugins.passes[i].owner) &&
            sl_graph_lists(app->plugins.passes[i].d.inputs, "motion"))
            return true;
    return false;
}

void sl_graph_plan(sl_app *app) {
    sl_renderer *r = R(app);
    sl_graph_free(r);
    /* core.ssaa > 1: the forward pass renders "forward.ssaa" at k× the viewport and the resolve
     * pass box-filters it into the viewport-sized "color" everything downstream sees. */
    sl_param *ssaa = sl_params_find(&app->params, "core.ssaa");
    r->ssaa = ssaa && ssaa->value.i > 1 ? ssaa->value.i : 1;
    forward_outputs[0] = app->opt.float32 ? core_color32 : core_color;
    forward_outputs[1] = core_depth;
    /* "motion" (pass.h, ABI 1.6) only while an enabled plugin's pass reads it: the forward
     * programs then compute it (SL_MOTION_VECTORS), so they are recomposed when that changes */
    bool motion = sl_graph_wants_motion(app);
    forward_outputs[2] = core_motion;
    forward_pass.output_count = motion ? 3 : 2;
    if (motion != r->motion) {
        r->motion = motion;
        sl_gpu_compose_all(app);
    }
    resolve_outputs[0] = forward_outputs[0];
    /* "color" drawn over, not read: its latest texture is bound, no ping-pong */
    blend_outputs[0] = forward_outputs[0];
    r->blend_planned = sl_gpu_scene_has_blended(app);
    if (r->ssaa > 1) {
        forward_outputs[0].name = "forward.ssaa";
        forward_outputs[0].scale = forward_outputs[1].scale = forward_outputs[2].scale = (float)r->ssaa;
    }
    r->display_desc = display_pass; /* its own copy: is_active reads this renderer (harnesses coexist) */
    r->display_desc.user = r;
    r->color_final = true;
    int total = app->plugins.pass_count + 4;
    r->passes = calloc(total, sizeof *r->passes);
    r->passes[r->pass_count++] = (graph_pass){.d = &forward_pass, .owner = -1, .core_forward = true};
    if (r->ssaa > 1) r->passes[r->pass_count++] = (graph_pass){.d = &resolve_pass, .owner = -1, .core_resolve = true};
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
    /* validate inputs against what earlier passes produce, then allocate */
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
        for (int k = 0; k < g->d->output_count; k++) {
            const sl_target_desc *o = &g->d->outputs[k];
            sl_graph_add_target(r, o, sl_graph_lists(g->d->inputs, o->name));
        }
    }
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
    bool ok = !keep_color && start >= first && last_reader < start;
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
