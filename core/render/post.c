/* Fused full-screen passes (post.h, sdk/include/shadelab/ext/post.h). */
#include "render/post.h"
#include "render/renderer_internal.h"
#include "log.h"
#include <shadelab/gl.h>
#include <stdlib.h>
#include <string.h>

#define MAX_REGS 16
#define MAX_PASSES 128

typedef struct point_reg {
    int owner;
    char *pass, *file, *function; /* file: absolute (the plugin's resource dir joined) */
    const char *(*defines)(void *user, const sl_frame *frame);
    void (*bind)(void *user, unsigned program, const sl_frame *frame);
    void *user;
} point_reg;

typedef struct variant { sl_program *base; uint64_t key; sl_program *program; } variant;

typedef struct sl_post {
    point_reg points[MAX_REGS]; int point_count;
    struct { int owner; char *pass; } accepts[MAX_REGS]; int accept_count;
    /* this frame: fused_into[i] = the accepting pass's graph index, or -1 */
    int fused_into[MAX_PASSES]; int routed;
    const point_reg *point_of[MAX_PASSES];
    variant *variants; int variant_count;
    unsigned extra_fbo; int extra_from, extra_count; /* bind_outputs_with attached these */
} sl_post;

static sl_post *post_of(sl_app *app) {
    if (!app->post) app->post = calloc(1, sizeof(sl_post));
    return app->post;
}

static bool is_only_color(const char *const *list) { return list && list[0] && !strcmp(list[0], "color") && !list[1]; }

static const sl_pass_reg *own_pass(sl_app *app, int owner, const char *name) {
    for (int i = 0; name && i < app->plugins.pass_count; i++)
        if (app->plugins.passes[i].owner == owner && !strcmp(app->plugins.passes[i].d.name, name)) return &app->plugins.passes[i];
    return NULL;
}

sl_status sl_post_add_pointwise(sl_app *app, int owner, const sl_pointwise_desc *in) {
    sl_pointwise_desc d = {0};
    if (!in) return SL_ERR_INVALID;
    memcpy(&d, in, in->struct_size < sizeof d ? in->struct_size : sizeof d);
    const sl_pass_reg *p = own_pass(app, owner, d.pass);
    const char *who = app->plugins.items[owner]->id;
    if (!p || !d.file || !d.function || !d.bind) {
        SL_ERROR("plugin %s: add_pointwise(\"%s\"): %s", who, d.pass ? d.pass : "",
                 !p ? "no pass of this plugin has that name" : "file, function and bind are required");
        return SL_ERR_INVALID;
    }
    if (!is_only_color(p->d.inputs) || p->d.output_count != 1 || strcmp(p->d.outputs[0].name, "color")) {
        SL_ERROR("plugin %s: add_pointwise(\"%s\"): a pointwise pass reads and writes \"color\" only", who, d.pass);
        return SL_ERR_INVALID;
    }
    sl_post *s = post_of(app);
    if (s->point_count == MAX_REGS) return SL_ERR_FAILED;
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", app->plugins.items[owner]->resource_dir, d.file);
    s->points[s->point_count++] = (point_reg){.owner = owner, .pass = strdup(d.pass), .file = strdup(path),
                                              .function = strdup(d.function), .defines = d.defines, .bind = d.bind,
                                              .user = d.user};
    return SL_OK;
}

sl_status sl_post_accept(sl_app *app, int owner, const char *pass) {
    if (!own_pass(app, owner, pass)) {
        SL_ERROR("plugin %s: accept_pointwise(\"%s\"): no pass of this plugin has that name", app->plugins.items[owner]->id,
                 pass ? pass : "");
        return SL_ERR_INVALID;
    }
    sl_post *s = post_of(app);
    if (s->accept_count == MAX_REGS) return SL_ERR_FAILED;
    s->accepts[s->accept_count].owner = owner;
    s->accepts[s->accept_count++].pass = strdup(pass);
    return SL_OK;
}

sl_program *sl_post_load_program(sl_app *app, int owner, const sl_program_desc *desc) {
    sl_program *p = sl_renderer_load_program(app, owner, desc);
    if (!p || !p->deferred) return p; /* a missing file: already an error */
    p->epilogue = true; /* composed again with the identity epilogue (it compiles at first use) */
    char err[16384];
    if (!sl_program_rebuild_files(p, app->plugins.items[owner]->resource_dir, err, sizeof err)) SL_ERROR("%s", err);
    return p;
}

static const point_reg *point_for(sl_post *s, const graph_pass *g) {
    for (int k = 0; k < s->point_count; k++)
        if (s->points[k].owner == g->owner && !strcmp(s->points[k].pass, g->d->name)) return &s->points[k];
    return NULL;
}

static bool accepts(sl_post *s, const graph_pass *g) {
    for (int k = 0; k < s->accept_count; k++)
        if (s->accepts[k].owner == g->owner && !strcmp(s->accepts[k].pass, g->d->name)) return true;
    return false;
}

static bool runs(sl_renderer *r, const graph_pass *g) {
    return !g->broken && (!g->d->is_active || g->d->is_active(g->d->user, &r->frame));
}

void sl_post_route(sl_app *app, int first) {
    sl_post *s = app->post;
    sl_renderer *r = R(app);
    if (!s) return;
    for (int i = 0; i < MAX_PASSES; i++) s->fused_into[i] = -1;
    s->routed = r->pass_count < MAX_PASSES ? r->pass_count : MAX_PASSES;
    /* SHADELAB_NO_FUSION=1: every pass on its own (the test that compares both; A/B timing) */
    const char *off = getenv("SHADELAB_NO_FUSION");
    if (off && *off && strcmp(off, "0")) return;
    for (int i = first < 0 ? 0 : first; i < s->routed; i++) {
        graph_pass *a = &r->passes[i];
        if (a->owner < 0 || !accepts(s, a) || !runs(r, a)) continue;
        int fused = 0, last = -1;
        for (int j = i + 1; j < s->routed && fused < SL_EPILOGUE_MAX; j++) {
            graph_pass *q = &r->passes[j];
            if (j == r->upscaler) break; /* it changes the size of "color" (pass.h, SL_SIZE_OUTPUT) */
            if (q->core_display || !runs(r, q)) continue; /* inactive passes are not in between */
            const point_reg *pt = q->owner >= 0 ? point_for(s, q) : NULL;
            if (!pt) break;
            s->fused_into[j] = i;
            s->point_of[j] = pt;
            last = j;
            fused++;
        }
        if (last < 0) continue;
        /* the accepting pass now writes what the last fused pass wrote ("display" on the fly or
         * "color"); a changed target invalidates what the pass last left there */
        bool to = r->passes[last].to_display;
        if (to != a->to_display) a->has_run = false;
        a->to_display = to;
        for (int j = i + 1; j <= last; j++)
            if (s->fused_into[j] == i) r->passes[j].to_display = false, r->passes[j].has_run = false;
        i = last;
    }
}

int sl_post_fused_into(sl_app *app, int index) {
    sl_post *s = app->post;
    return s && index >= 0 && index < s->routed ? s->fused_into[index] : -1;
}

/* The pass being executed and its graph index, or -1. */
static int current_index(sl_renderer *r) {
    return r->current ? (int)(r->current->pass - r->passes) : -1;
}

unsigned sl_post_program_id(sl_app *app, sl_program *p) {
    sl_post *s = app->post;
    sl_renderer *r = R(app);
    int cur = r ? current_index(r) : -1;
    if (!p || !p->epilogue || !s || cur < 0) return sl_program_id(p);
    sl_epilogue_point pts[SL_EPILOGUE_MAX];
    int n = 0;
    uint64_t key = sl_hash64(&r->programs_version, sizeof r->programs_version, 0);
    for (int j = cur + 1; j < s->routed && n < SL_EPILOGUE_MAX; j++) {
        if (s->fused_into[j] != cur) continue;
        const point_reg *pt = s->point_of[j];
        const char *defs = pt->defines ? pt->defines(pt->user, &r->frame) : NULL;
        pts[n++] = (sl_epilogue_point){.file = pt->file, .owner = pt->owner, .function = pt->function,
                                       .defines = (char *)(defs ? defs : "")};
        key = sl_hash64(pt->file, strlen(pt->file), key);
        key = sl_hash64(pt->function, strlen(pt->function), key);
        key = sl_hash64(pts[n - 1].defines, strlen(pts[n - 1].defines), key);
    }
    if (!n) return sl_program_id(p);
    for (int i = 0; i < s->variant_count; i++)
        if (s->variants[i].base == p && s->variants[i].key == key) return s->variants[i].program->id;
    const char *dir = p->owner >= 0 ? app->plugins.items[p->owner]->resource_dir : sl_shader_dir();
    char err[16384] = "";
    sl_program *v = sl_program_epilogue_variant(p, dir, pts, n, err, sizeof err);
    if (!v->id) { /* a fused function that does not compile switches its plugin off (app.c) */
        int k = v->error_owner > 0 ? v->error_owner : p->owner;
        sl_renderer_blame_plugin(app, k, err);
    }
    variant *grown = realloc(s->variants, (s->variant_count + 1) * sizeof *s->variants);
    if (!grown) return v->id; /* used, not cached: the next frame compiles it again */
    s->variants = grown;
    s->variants[s->variant_count++] = (variant){.base = p, .key = key, .program = v};
    return v->id;
}

void sl_post_bind_fused(sl_app *app) {
    sl_post *s = app->post;
    sl_renderer *r = R(app);
    int cur = r ? current_index(r) : -1;
    if (!s || cur < 0) return;
    GLint prog = 0;
    bool got = false;
    for (int j = cur + 1; j < s->routed; j++) {
        if (s->fused_into[j] != cur) continue;
        if (!got) glGetIntegerv(GL_CURRENT_PROGRAM, &prog), got = true;
        if (prog) s->point_of[j]->bind(s->point_of[j]->user, (unsigned)prog, &r->frame);
    }
}

sl_status sl_post_bind_outputs_with(sl_app *app, sl_pass_ctx *ctx, int layer, const unsigned *textures, int count) {
    sl_status st = sl_renderer_bind_outputs(app, ctx, layer);
    if (st != SL_OK || count <= 0) return st;
    graph_pass *g = ctx->pass;
    int nc = 0;
    for (int k = 0; k < g->d->output_count; k++) nc += g->d->outputs[k].format != SL_FORMAT_DEPTH32F;
    if (count > 4 || nc + count > 8) return SL_ERR_INVALID;
    GLenum bufs[8];
    for (int k = 0; k < nc + count; k++) bufs[k] = GL_COLOR_ATTACHMENT0 + k;
    for (int k = 0; k < count; k++) glNamedFramebufferTexture(g->fbo, GL_COLOR_ATTACHMENT0 + nc + k, textures[k], 0);
    glNamedFramebufferDrawBuffers(g->fbo, nc + count, bufs);
    sl_post *s = post_of(app);
    s->extra_fbo = g->fbo, s->extra_from = nc, s->extra_count = count;
    if (glCheckNamedFramebufferStatus(g->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        SL_ERROR("pass %s: bind_outputs_with: framebuffer incomplete (a texture of another size or format?)", g->d->name);
        return SL_ERR_GL;
    }
    return SL_OK;
}

/* After a pass: what bind_outputs_with attached is detached (the pass's framebuffer is the core's). */
void sl_post_end_pass(sl_app *app, unsigned fbo) {
    sl_post *s = app->post;
    if (!s || !s->extra_count || s->extra_fbo != fbo) return;
    for (int k = 0; k < s->extra_count; k++) glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + s->extra_from + k, 0, 0);
    s->extra_count = 0;
}

void sl_post_free(sl_app *app) {
    sl_post *s = app->post;
    if (!s) return;
    for (int i = 0; i < s->variant_count; i++) sl_program_free(s->variants[i].program);
    free(s->variants);
    for (int i = 0; i < s->point_count; i++) free(s->points[i].pass), free(s->points[i].file), free(s->points[i].function);
    for (int i = 0; i < s->accept_count; i++) free(s->accepts[i].pass);
    free(s);
    app->post = NULL;
}
