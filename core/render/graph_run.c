/* Executing the render graph: the core's own passes, change signatures, per-pass timing.
 * See renderer_internal.h. */
#include "render/renderer_internal.h"
#include "log.h"
#include "startup.h"
#include <shadelab/gl.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

double sl_now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static void run_forward(sl_app *app, sl_pass_ctx *ctx) {
    sl_renderer *r = R(app);
    sl_renderer_bind_outputs(app, ctx, 0);
    const sl_environment *env = &app->scene.environment;
    float bg[4] = {env->color[0] * env->intensity, env->color[1] * env->intensity, env->color[2] * env->intensity, 1};
    glDepthMask(GL_TRUE);
    glClearNamedFramebufferfv(ctx->pass->fbo, GL_COLOR, 0, bg);
    glClearNamedFramebufferfi(ctx->pass->fbo, GL_DEPTH_STENCIL, 0, 1.0f, 0);
    static const float still[4] = {0, 0, 0, 0};
    if (r->motion) glClearNamedFramebufferfv(ctx->pass->fbo, GL_COLOR, 1, still); /* background: no motion */
    sl_draw_scene_desc d = {.struct_size = sizeof d, .cull = 1};
    memcpy(d.view, r->frame.view, sizeof d.view);
    memcpy(d.proj, r->frame.proj, sizeof d.proj);
    sl_gpu_draw_meshes(app, &d, false, NULL);
}

static void run_display(sl_app *app, sl_pass_ctx *ctx) {
    sl_renderer *r = R(app);
    sl_renderer_bind_outputs(app, ctx, 0);
    unsigned prog = r->display_prog->id;
    if (!prog) return;
    glUseProgram(prog);
    glBindTextureUnit(0, sl_renderer_pass_texture(app, ctx, "color"));
    glUniform1i(glGetUniformLocation(prog, "sl_color"), 0);
    sl_renderer_draw_fullscreen(app, ctx);
}

static void run_resolve(sl_app *app, sl_pass_ctx *ctx) {
    sl_renderer *r = R(app);
    sl_renderer_bind_outputs(app, ctx, 0);
    unsigned prog = r->resolve_prog->id;
    if (!prog) return;
    glUseProgram(prog);
    glBindTextureUnit(0, sl_renderer_pass_texture(app, ctx, "forward.ssaa"));
    glUniform1i(glGetUniformLocation(prog, "sl_src"), 0);
    glUniform1i(glGetUniformLocation(prog, "sl_factor"), r->ssaa);
    sl_renderer_draw_fullscreen(app, ctx);
}

static void run_pass(sl_app *app, graph_pass *g, int stat_index) {
    sl_renderer *r = R(app);
    sl_pass_ctx ctx = {.pass = g};
    r->current = &ctx;
    if (g->core_forward) run_forward(app, &ctx);
    else if (g->core_display) run_display(app, &ctx);
    else if (g->core_resolve) run_resolve(app, &ctx);
    else g->d->execute(g->d->user, &ctx, &r->frame);
    r->current = NULL;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    /* writes: ping-ponged targets flip, versions bump */
    for (int k = 0; k < g->d->output_count; k++) {
        resource *e = sl_graph_find(r, g->d->outputs[k].name);
        if (!e) continue;
        if (e->tex[1] && sl_graph_lists(g->d->inputs, e->name)) e->current = 1 - e->current;
        e->version++;
    }
}

static uint64_t input_versions(sl_renderer *r, graph_pass *g) {
    uint64_t h = 0;
    for (const char *const *in = g->d->inputs; in && *in; in++) {
        resource *e = sl_graph_find(r, *in);
        if (e) h = sl_hash64(&e->version, sizeof e->version, h);
    }
    return h;
}

/* Runs passes with index in [begin, end), timing each. */
void sl_graph_run_range(sl_app *app, int begin, int end) {
    sl_renderer *r = R(app);
    for (int i = begin; i < end; i++) {
        graph_pass *g = &r->passes[i];
        sl_pass_stat *st = NULL;
        for (int k = 0; k < r->stats.pass_count; k++)
            if (!strcmp(r->stats.passes[k].name, g->d->name)) st = &r->stats.passes[k];
        if (!st && r->stats.pass_count < 64) {
            st = &r->stats.passes[r->stats.pass_count++];
            st->name = g->d->name;
            st->owner = g->owner >= 0 ? app->plugins.items[g->owner]->id : "core";
            st->ms = 0;
            st->ran = false;
        }
        if (g->broken) continue;
        if (g->d->is_active && !g->d->is_active(g->d->user, &r->frame)) continue;
        if (g->d->signature) {
            uint64_t sig = g->d->signature(g->d->user, &r->frame) ^ input_versions(r, g);
            if (g->has_run && sig == g->last_signature) continue;
            g->last_signature = sig;
        }
        double t0 = 0;
        if (r->finish_timing) { glFinish(); t0 = sl_now_ms(); }
        else glBeginQuery(GL_TIME_ELAPSED, r->queries[i & 63]);
        run_pass(app, g, i);
        double ms;
        if (r->finish_timing) { glFinish(); ms = sl_now_ms() - t0; }
        else {
            glEndQuery(GL_TIME_ELAPSED);
            GLuint64 ns = 0;
            glGetQueryObjectui64v(r->queries[i & 63], GL_QUERY_RESULT, &ns);
            ms = ns * 1e-6;
        }
        if (sl_startup_recording()) sl_startup_mark("frame %d: %s", (int)app->frame_index, g->d->name);
        g->has_run = true;
        g->last_ms = ms;
        if (st) { st->ms += ms; st->ran = true; }
    }
}


