/* Executing the render graph: the core's own passes, change signatures, per-pass timing.
 * See renderer_internal.h. */
#include "render/renderer_internal.h"
#include "render/post.h"
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
    static const float none[4] = {0, 0, 0, 0};
    if (r->motion) glClearNamedFramebufferfv(ctx->pass->fbo, GL_COLOR, 1, none); /* background: no motion */
    if (r->normal) glClearNamedFramebufferfv(ctx->pass->fbo, GL_COLOR, r->motion ? 2 : 1, none); /* nor normal */
    sl_draw_scene_desc d = {.struct_size = sizeof d, .cull = 1};
    memcpy(d.view, r->frame.view, sizeof d.view);
    memcpy(d.proj, r->frame.proj, sizeof d.proj);
    sl_gpu_draw_meshes(app, &d, false, NULL, SL_GPU_DRAW_OPAQUE);
}

/* The depth pre-pass (pass.h, ABI 1.13): the opaque materials with their surface hooks, writing
 * "depth" and "normal" (shaders/prepass.frag) as the forward pass would; background 0. */
static void run_prepass(sl_app *app, sl_pass_ctx *ctx) {
    sl_renderer *r = R(app);
    if (sl_renderer_bind_outputs(app, ctx, 0) != SL_OK) return;
    static const float none[4] = {0, 0, 0, 0};
    glDepthMask(GL_TRUE);
    glClearNamedFramebufferfv(ctx->pass->fbo, GL_COLOR, 0, none);
    glClearNamedFramebufferfi(ctx->pass->fbo, GL_DEPTH_STENCIL, 0, 1.0f, 0);
    sl_draw_scene_desc d = {.struct_size = sizeof d, .mode = SL_DRAW_MATERIALS, .cull = 1, .fragment = "sl:prepass.frag"};
    memcpy(d.view, r->frame.view, sizeof d.view);
    memcpy(d.proj, r->frame.proj, sizeof d.proj);
    sl_gpu_draw_meshes(app, &d, false, NULL, SL_GPU_DRAW_OPAQUE);
}

/* host->compile_ahead (ABI 1.12). llvmpipe compiles a program for the state it is drawn with, at
 * its first draw, on the calling thread; a pass that then waits for the rasteriser (a read-back,
 * a chain of draws each reading the last) leaves this thread idle meanwhile. Drawing the forward
 * pass's materials there under an empty scissor (nothing is rasterised) compiles the forward
 * programs during that wait, for the state the forward pass will draw them with: its own targets
 * (bind_outputs: formats, the sRGB display view), the default blend, depth and colour-mask state
 * every pass leaves, and the textures the materials bind (the caller makes sure they exist: an
 * empty unit is another state). The forward pass's own draws then find them compiled. Draws made
 * here are not counted in the frame's statistics. Nothing on a GPU, and nothing when the programs
 * were drawn ahead already. tests/cli_warm_start.sh: the same compiles and image without it. */
void sl_renderer_compile_ahead(sl_app *app) {
    sl_renderer *r = R(app);
    /* SHADELAB_NO_COMPILE_AHEAD=1: off (the test that compares both; A/B timing) */
    if (!r || app->backend.is_gpu || getenv("SHADELAB_NO_COMPILE_AHEAD")) return;
    graph_pass *g = NULL;
    for (int i = 0; i < r->pass_count && !g; i++)
        if (r->passes[i].core_forward) g = &r->passes[i];
    if (!g || g->broken) return;
    uint64_t key = sl_hash64(&r->programs_version, sizeof r->programs_version, (uint64_t)g->to_display);
    for (int m = 0; m < app->scene.material_count; m++) {
        unsigned id = r->materials[m].forward.program ? sl_program_id(r->materials[m].forward.program) : 0;
        key = sl_hash64(&id, sizeof id, key);
    }
    if (key == r->compiled_ahead) return;
    r->compiled_ahead = key;
    GLint fbo = 0, prog = 0, viewport[4], box[4];
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
    glGetIntegerv(GL_VIEWPORT, viewport);
    glGetIntegerv(GL_SCISSOR_BOX, box);
    GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
    sl_pass_ctx ctx = {.pass = g};
    sl_pass_ctx *current = r->current;
    r->current = &ctx;
    if (sl_renderer_bind_outputs(app, &ctx, 0) == SL_OK) {
        glDisable(GL_BLEND);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDepthMask(GL_TRUE);
        glDepthRange(0, 1);
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, 0, 0, 0);
        sl_draw_scene_desc d = {.struct_size = sizeof d, .cull = 1};
        memcpy(d.view, r->frame.view, sizeof d.view);
        memcpy(d.proj, r->frame.proj, sizeof d.proj);
        int draws = r->stats.draw_calls;
        sl_gpu_draw_meshes(app, &d, false, NULL, SL_GPU_DRAW_OPAQUE);
        if (g->to_display) glDisable(GL_FRAMEBUFFER_SRGB);
        /* the plugins' passes after it that declare draws_only (ABI 1.12), in their state */
        for (int i = (int)(g - r->passes) + 1; i < r->pass_count; i++) {
            graph_pass *p = &r->passes[i];
            if (p->owner < 0 || p->broken || !p->d->draws_only ||
                (p->d->is_active && !p->d->is_active(p->d->user, &r->frame)))
                continue;
            ctx.pass = p;
            glEnable(GL_SCISSOR_TEST);
            glScissor(0, 0, 0, 0);
            p->d->execute(p->d->user, &ctx, &r->frame);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            if (p->to_display) {
                glDisable(GL_FRAMEBUFFER_SRGB);
                glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            }
        }
        r->stats.draw_calls = draws;
    }
    r->current = current;
    if (!scissor) glDisable(GL_SCISSOR_TEST);
    glScissor(box[0], box[1], box[2], box[3]);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glBindFramebuffer(GL_FRAMEBUFFER, (unsigned)fbo);
    glUseProgram((unsigned)prog);
}

/* The meshes of `set` over the opaque image, back to front (scene_gpu.c): colour = alpha·c +
 * (1 − alpha)·dst with the target's alpha kept, no depth writes. The fragment tests "depth"
 * itself (forward.frag): it holds ssaa² samples per pixel of "color" here. */
static void draw_over_opaque(sl_app *app, sl_pass_ctx *ctx, sl_gpu_draw_set set) {
    sl_renderer *r = R(app);
    glBindTextureUnit(SL_BLEND_DEPTH_UNIT, sl_renderer_pass_texture(app, ctx, "depth"));
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE); /* the target's alpha stays as the opaque pass left it */
    glDepthMask(GL_FALSE);
    sl_draw_scene_desc d = {.struct_size = sizeof d, .cull = 1};
    memcpy(d.view, r->frame.view, sizeof d.view);
    memcpy(d.proj, r->frame.proj, sizeof d.proj);
    sl_gpu_draw_meshes(app, &d, false, NULL, set);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_BLEND);
    glBindTextureUnit(SL_BLEND_DEPTH_UNIT, 0);
}

/* glTF alphaMode BLEND: the blended materials over the opaque image. */
static void run_blend(sl_app *app, sl_pass_ctx *ctx) {
    if (sl_renderer_bind_outputs(app, ctx, 0) != SL_OK) return;
    draw_over_opaque(app, ctx, SL_GPU_DRAW_BLENDED);
}

/* The opaque scene as every pass before forward-behind left "color": copied into the capture's
 * level 0 and box-filtered down its mip chain (glGenerateMipmap), bound on SL_SCENE_BEHIND_UNIT
 * for the materials drawn over it (forward-behind, then forward-blend). Made again when "color"
 * changes size or format. */
static void capture_scene_behind(sl_app *app, sl_pass_ctx *ctx) {
    sl_renderer *r = R(app);
    unsigned color = sl_renderer_pass_texture(app, ctx, "color");
    if (!color) return;
    int w = 0, h = 0, format = 0;
    glGetTextureLevelParameteriv(color, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(color, 0, GL_TEXTURE_HEIGHT, &h);
    glGetTextureLevelParameteriv(color, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    if (w < 1 || h < 1) return;
    if (!r->behind_tex || w != r->behind_w || h != r->behind_h || format != r->behind_format) {
        if (r->behind_tex) glDeleteTextures(1, &r->behind_tex);
        int levels = 1;
        while ((w | h) >> levels) levels++;
        glCreateTextures(GL_TEXTURE_2D, 1, &r->behind_tex);
        glTextureStorage2D(r->behind_tex, levels, (GLenum)format, w, h);
        glTextureParameteri(r->behind_tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(r->behind_tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(r->behind_tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(r->behind_tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        r->behind_w = w, r->behind_h = h, r->behind_format = format;
    }
    glCopyImageSubData(color, GL_TEXTURE_2D, 0, 0, 0, 0, r->behind_tex, GL_TEXTURE_2D, 0, 0, 0, 0, w, h, 1);
    glGenerateTextureMipmap(r->behind_tex);
    glBindTextureUnit(SL_SCENE_BEHIND_UNIT, r->behind_tex);
}

/* The scene behind (ABI 1.17, shader.h): the opaque image captured, then the materials with a
 * SCENE_BEHIND hook drawn over it as blended ones are, their fragments covering what they are
 * in front of. */
static void run_behind(sl_app *app, sl_pass_ctx *ctx) {
    if (sl_renderer_bind_outputs(app, ctx, 0) != SL_OK) return;
    capture_scene_behind(app, ctx);
    draw_over_opaque(app, ctx, SL_GPU_DRAW_BEHIND);
}

const sl_chunk_reg *sl_graph_pass_view(sl_app *app) {
    for (int i = 0; app->debug_view && i < app->plugins.chunk_count; i++) {
        const sl_chunk_reg *c = &app->plugins.chunks[i];
        if (c->d.hook == SL_HOOK_DEBUG_VIEW && (c->d.flags & SL_CHUNK_PASS_VIEW) && !strcmp(c->d.name, app->debug_view) &&
            sl_plugin_enabled(&app->plugins, c->owner))
            return c;
    }
    return NULL;
}

/* A pass view's display program (shader.h, SL_CHUNK_PASS_VIEW): the full-screen triangle, the
 * plugin's file and a main writing its function's value. Made again when the view or the programs
 * (a hot reload) change; a compile error switches the plugin off like any of its GLSL. */
static sl_program *pass_view_program(sl_app *app, const sl_chunk_reg *v) {
    sl_renderer *r = R(app);
    uint64_t key = sl_hash64(v->d.name, strlen(v->d.name), r->programs_version + 1);
    if (r->view_key == key) return r->view_prog;
    sl_program_free(r->view_prog);
    r->view_key = key;
    sl_program *p = r->view_prog = calloc(1, sizeof *p);
    char err[16384], path[2048], text[1024];
    snprintf(text, sizeof text, "debug view \"%s\" (%s)", v->d.name, app->plugins.items[v->owner]->id);
    p->label = strdup(text);
    p->owner = v->owner;
    sl_sb_append(&p->vs.text, "#version 450 core\n");
    bool ok = sl_source_include(&p->vs, "sl:fullscreen.vert", err, sizeof err);
    sl_sb_append(&p->fs.text, "#version 450 core\n");
    ok = ok && sl_source_include(&p->fs, "sl:common.glsl", err, sizeof err);
    snprintf(path, sizeof path, "%s/%s", app->plugins.items[v->owner]->resource_dir, v->d.file);
    ok = ok && sl_source_include_from(&p->fs, path, v->owner, err, sizeof err);
    snprintf(text, sizeof text,
             "in vec2 v_uv;\nuniform sampler2D sl_view_source;\nlayout(location = 0) out vec4 o_color;\n"
             "void main() {\n    vec3 c = %s(sl_view_source, v_uv);\n"
             "    o_color = vec4(clamp(mix(c, vec3(0.0), isnan(c)), 0.0, 1.0), 1.0);\n}\n", v->d.function);
    if (ok) sl_source_generated(&p->fs, text);
    if (ok) ok = sl_program_build(p, err, sizeof err);
    if (!ok) sl_renderer_blame_plugin(app, v->owner, err);
    return p;
}

static void run_display(sl_app *app, sl_pass_ctx *ctx) {
    sl_renderer *r = R(app);
    sl_renderer_bind_outputs(app, ctx, 0);
    const sl_chunk_reg *view = sl_graph_pass_view(app);
    sl_program *shown = view ? pass_view_program(app, view) : NULL;
    if (shown && shown->id) { /* a pass's resource as it is (ABI 1.13) */
        resource *e = sl_graph_resource(r, ctx->pass, view->d.resource, false);
        glUseProgram(shown->id);
        glBindTextureUnit(0, e ? e->tex[e->current] : 0);
        glUniform1i(glGetUniformLocation(shown->id, "sl_view_source"), 0);
        sl_renderer_draw_fullscreen(app, ctx);
        return;
    }
    unsigned prog = sl_program_id(r->display_prog);
    if (!prog) return;
    glUseProgram(prog);
    glBindTextureUnit(0, sl_renderer_pass_texture(app, ctx, "color"));
    glUniform1i(glGetUniformLocation(prog, "sl_color"), 0);
    sl_renderer_draw_fullscreen(app, ctx);
}

static void run_resolve(sl_app *app, sl_pass_ctx *ctx) {
    sl_renderer *r = R(app);
    sl_renderer_bind_outputs(app, ctx, 0);
    unsigned prog = sl_program_id(r->resolve_prog);
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
    else if (g->core_blend) run_blend(app, &ctx);
    else if (g->core_behind) run_behind(app, &ctx);
    else if (g->core_prepass) run_prepass(app, &ctx);
    else g->d->execute(g->d->user, &ctx, &r->frame);
    r->current = NULL;
    sl_post_end_pass(app, g->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    if (g->to_display) { /* it wrote "display" through the sRGB view instead of "color" (graph_plan.c) */
        glDisable(GL_FRAMEBUFFER_SRGB);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        resource *d = sl_graph_find(r, "display");
        if (d) d->version++;
    }
    /* writes: ping-ponged targets flip, versions bump */
    for (int k = 0; k < g->d->output_count; k++) {
        const char *declared = g->d->outputs[k].name;
        resource *e = sl_graph_resource(r, g, declared, true);
        if (!e || (g->to_display && !strcmp(declared, "color"))) continue;
        if (e->tex[1] && sl_graph_pass_reads(r, g, e)) e->current = 1 - e->current;
        e->version++;
    }
}

static uint64_t input_versions(sl_renderer *r, graph_pass *g) {
    uint64_t h = 0;
    for (const char *const *in = g->d->inputs; in && *in; in++) {
        resource *e = sl_graph_resource(r, g, *in, false);
        if (e) h = sl_hash64(&e->version, sizeof e->version, h);
    }
    return h;
}

/* ------------------------------------------------------------ declared dependencies ---- */
/* A pass's sl_pass_desc.depends (pass.h, ABI 1.8) turns into one key per frame: the hash of the
 * current state of each thing it declared. The pass is skipped while the key is the one it had
 * when the pass last ran and its outputs persist (see outputs_persist). */

/* The core's parameters that no program reads and that change no pass's work but through what
 * passes declare otherwise: the render scale reaches them as the viewport size
 * (SL_DEPENDS_CAMERA), the frame-time budget only through the settings it changes. Left out of
 * SL_DEPENDS_MATERIALS, so that a new render scale re-renders no shadow map. */
bool sl_graph_viewport_only(const sl_param *q) {
    return !strcmp(q->owner, "core") && (!strcmp(q->desc.id, "render_scale") || !strcmp(q->desc.id, "budget"));
}

static uint64_t hash_globals(sl_app *app, const char *owner, bool materials, uint64_t h) {
    for (int i = 0; i < app->params.count; i++) {
        const sl_param *q = &app->params.items[i];
        if (q->desc.scope != SL_SCOPE_GLOBAL || strcmp(q->owner, owner) || (materials && sl_graph_viewport_only(q))) continue;
        h = sl_hash64(&q->value.b, sizeof q->value.b, h);
        h = sl_hash64(&q->value.i, sizeof q->value.i, h);
        h = sl_hash64(q->value.f, sizeof q->value.f, h);
        if (q->value.s) h = sl_hash64(q->value.s, strlen(q->value.s), h);
    }
    return h;
}

/* Whether plugin `owner`'s parameters can reach the material programs: it adds shader chunks or
 * binds uniforms (the core's do). */
static bool reaches_materials(sl_app *app, int owner) {
    if (owner <= 0 || app->plugins.items[owner]->bind) return true;
    for (int i = 0; i < app->plugins.chunk_count; i++)
        if (app->plugins.chunks[i].owner == owner) return true;
    return false;
}

static uint64_t depends_key(sl_app *app, graph_pass *g) {
    sl_renderer *r = R(app);
    const sl_frame *f = &r->frame;
    uint32_t dep = g->d->depends;
    uint64_t h = sl_hash64(&dep, sizeof dep, 0);
    if (dep & SL_DEPENDS_LIGHTS) {
        h = sl_hash64(&f->lights_version, sizeof f->lights_version, h);
        h = sl_hash64(&r->plugin_light_moves, sizeof r->plugin_light_moves, h); /* plugin_lights.h */
        /* a pass after the shadow stage sees the shadow maps through the material programs */
        if (g->d->stage >= SL_STAGE_PREPASS) h = sl_hash64(&r->shadow_runs, sizeof r->shadow_runs, h);
    }
    if (dep & SL_DEPENDS_GEOMETRY) {
        h = sl_hash64(&f->geometry_version, sizeof f->geometry_version, h);
        h = sl_hash64(f->scene_min, sizeof f->scene_min, h);
        h = sl_hash64(f->scene_max, sizeof f->scene_max, h);
    }
    if (dep & SL_DEPENDS_CAMERA) {
        h = sl_hash64(&f->camera_version, sizeof f->camera_version, h);
        h = sl_hash64(f->view, sizeof f->view, h);
        h = sl_hash64(f->proj, sizeof f->proj, h);
        h = sl_hash64(&f->width, sizeof f->width, h);
        h = sl_hash64(&f->height, sizeof f->height, h);
        h = sl_hash64(&f->sample_index, sizeof f->sample_index, h); /* ABI 1.9: the next sample */
    }
    if (dep & SL_DEPENDS_MATERIALS) {
        uint64_t v[3] = {app->materials_version, app->params.recompile_version, r->programs_version};
        h = sl_hash64(v, sizeof v, h);
        for (int p = 0; p < app->plugins.count; p++)
            if (reaches_materials(app, p)) h = hash_globals(app, app->plugins.items[p]->id, true, h);
    }
    if (dep & SL_DEPENDS_OWN_PARAMS) h = hash_globals(app, g->owner >= 0 ? app->plugins.items[g->owner]->id : "core", false, h);
    if (dep & SL_DEPENDS_PARAMS) h = sl_hash64(&f->edits_version, sizeof f->edits_version, h);
    if (dep & SL_DEPENDS_TIME) h = sl_hash64(&f->time, sizeof f->time, h);
    if (dep & SL_DEPENDS_INPUTS) {
        for (const char *const *in = g->d->inputs; in && *in; in++) {
            resource *e = sl_graph_resource(r, g, *in, false);
            if (e) h = sl_hash64(&e->version, sizeof e->version, h);
        }
    }
    return h;
}

/* A skipped pass's outputs must still hold what it wrote: no other pass of the graph writes them
 * (a pass that writes "color" in place, or after the forward pass, runs every frame). Targets are
 * re-made when the graph is planned, which also clears has_run. */
static bool outputs_persist(sl_renderer *r, graph_pass *g) {
    for (int k = 0; k < g->d->output_count; k++)
        for (int j = 0; j < r->pass_count; j++) {
            graph_pass *o = &r->passes[j];
            if (o == g || o->broken) continue;
            for (int m = 0; m < o->d->output_count; m++)
                if (!strcmp(o->d->outputs[m].name, g->d->outputs[k].name)) return false;
        }
    return true;
}

/* Whether the pass can be skipped this frame: its signature (if any) and its declaration (if any)
 * both say that nothing it depends on changed. Undeclared passes without a signature, and
 * SL_DEPENDS_EVERY_FRAME ones, always run. */
static bool unchanged(sl_app *app, graph_pass *g) {
    sl_renderer *r = R(app);
    uint32_t dep = g->d->depends;
    if ((dep & SL_DEPENDS_EVERY_FRAME) || (!dep && !g->d->signature)) return false;
    bool same = g->has_run;
    if (g->d->signature) {
        uint64_t sig = g->d->signature(g->d->user, &r->frame) ^ input_versions(r, g);
        same = same && sig == g->last_signature;
        g->last_signature = sig;
    }
    if (dep) {
        uint64_t key = depends_key(app, g);
        same = same && key == g->last_depends && outputs_persist(r, g);
        g->last_depends = key;
    } else {
        /* a signature alone (ABI < 1.8): any edit re-runs it, as re-planning on every parameter
         * change did before plans were kept */
        same = same && r->frame.params_version == g->last_depends;
        g->last_depends = r->frame.params_version;
    }
    return same;
}

/* The upscaler does not run this frame (ABI 1.18, pass.h): its output-size "color" is the
 * render-size one scaled up bilinearly, as the window shows an image without an upscaler. */
static void upscale_bilinear(sl_renderer *r, graph_pass *g) {
    resource *src = sl_graph_resource(r, g, "color", false), *dst = sl_graph_resource(r, g, "color", true);
    if (!src || !dst) return;
    unsigned fbo[2];
    glCreateFramebuffers(2, fbo);
    glNamedFramebufferTexture(fbo[0], GL_COLOR_ATTACHMENT0, src->tex[src->current], 0);
    glNamedFramebufferTexture(fbo[1], GL_COLOR_ATTACHMENT0, dst->tex[dst->current], 0);
    glBlitNamedFramebuffer(fbo[0], fbo[1], 0, 0, src->w, src->h, 0, 0, dst->w, dst->h, GL_COLOR_BUFFER_BIT,
                           src->w == dst->w && src->h == dst->h ? GL_NEAREST : GL_LINEAR);
    glDeleteFramebuffers(2, fbo);
    dst->version++;
}

/* Runs passes with index in [begin, end), timing each. Passes after the upscaler see the output
 * size as their viewport (sl_frame.width, height: pass.h, ABI 1.18). */
void sl_graph_run_range(sl_app *app, int begin, int end) {
    sl_renderer *r = R(app);
    for (int i = begin; i < end; i++) {
        graph_pass *g = &r->passes[i];
        bool after = r->upscaler >= 0 && i > r->upscaler;
        r->frame.width = after ? r->out_width : r->width;
        r->frame.height = after ? r->out_height : r->height;
        sl_pass_stat *st = NULL;
        for (int k = 0; k < r->stats.pass_count; k++)
            if (!strcmp(r->stats.passes[k].name, g->d->name)) st = &r->stats.passes[k];
        if (!st && r->stats.pass_count < 64) {
            st = &r->stats.passes[r->stats.pass_count++];
            st->name = g->d->name;
            st->owner = g->owner >= 0 ? app->plugins.items[g->owner]->id : "core";
            st->ms = 0;
            st->ran = st->reused = false;
            st->fused_into = NULL;
        }
        if (g->broken) continue;
        int into = sl_post_fused_into(app, i);
        if (into >= 0) { /* its function runs inside that pass's draw (render/post.h) */
            if (st) st->fused_into = r->passes[into].d->name;
            continue;
        }
        if (g->d->is_active && !g->d->is_active(g->d->user, &r->frame)) {
            if (i == r->upscaler) upscale_bilinear(r, g);
            continue;
        }
        /* unchanged() keeps its keys current even when core.rerun_passes runs the pass anyway */
        if (unchanged(app, g) && !r->rerun_passes) { /* its declared inputs and its signature did not move */
            if (st) st->reused = true;
            r->stats.reused_draw_calls += g->last_draws;
            continue;
        }
        double t0 = 0;
        /* timed only when asked (--bench, --stats, the panel's timing view): glFinish serialises */
        if (!r->timing) {}
        else if (r->finish_timing) { glFinish(); t0 = sl_now_ms(); }
        else glBeginQuery(GL_TIME_ELAPSED, r->queries[i & 63]);
        int draws_before = r->stats.draw_calls;
        run_pass(app, g, i);
        g->last_draws = r->stats.draw_calls - draws_before;
        double ms = 0;
        if (!r->timing) {}
        else if (r->finish_timing) { glFinish(); ms = sl_now_ms() - t0; }
        else {
            glEndQuery(GL_TIME_ELAPSED);
            GLuint64 ns = 0;
            glGetQueryObjectui64v(r->queries[i & 63], GL_QUERY_RESULT, &ns);
            ms = ns * 1e-6;
        }
        if (sl_startup_recording()) sl_startup_mark("frame %d: %s", (int)app->frame_index, g->d->name);
        g->has_run = true;
        /* SL_DEPENDS_LIGHTS of later passes: what the light-space passes made. Not the core's depth
         * pre-pass (the camera's view, every frame while a pass reads "depth" or "normal"): counted,
         * it re-ran every pass that declared LIGHTS in every frame of a still. */
        if (g->d->stage < SL_STAGE_DEPTH_PREPASS) r->shadow_runs++;
        g->last_ms = ms;
        if (st) { st->ms += ms; st->ran = true; }
    }
    r->frame.width = r->width, r->frame.height = r->height;
}


