/* Render targets of the graph and their binding for a pass. See renderer_internal.h. */
#include "render/renderer_internal.h"
#include "log.h"
#include <shadelab/gl.h>
#include <stdlib.h>
#include <string.h>

static GLenum gl_format(sl_format f) {
    switch (f) {
    case SL_FORMAT_RGBA8: return GL_RGBA8;
    case SL_FORMAT_RGBA16F: return GL_RGBA16F;
    case SL_FORMAT_RGBA32F: return GL_RGBA32F;
    case SL_FORMAT_RG16F: return GL_RG16F;
    case SL_FORMAT_R32F: return GL_R32F;
    case SL_FORMAT_DEPTH32F: return GL_DEPTH_COMPONENT32F;
    }
    return GL_RGBA8;
}

resource *sl_graph_find(sl_renderer *r, const char *name) {
    for (int i = 0; i < r->res_count; i++)
        if (!strcmp(r->res[i].name, name)) return &r->res[i];
    return NULL;
}

static unsigned make_target(const sl_target_desc *d, int w, int h) {
    unsigned t;
    int layers = d->layers > 1 ? d->layers : 1;
    glCreateTextures(layers > 1 ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D, 1, &t);
    if (layers > 1) glTextureStorage3D(t, 1, gl_format(d->format), w, h, layers);
    else glTextureStorage2D(t, 1, gl_format(d->format), w, h);
    bool depth = d->format == SL_FORMAT_DEPTH32F;
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, depth && !d->compare ? GL_NEAREST : GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, depth && !d->compare ? GL_NEAREST : GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (depth && d->compare) {
        glTextureParameteri(t, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(t, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    }
    return t;
}

void sl_graph_free(sl_renderer *r) {
    for (int i = 0; i < r->res_count; i++) {
        if (r->res[i].srgb_view) glDeleteTextures(1, &r->res[i].srgb_view);
        glDeleteTextures(r->res[i].tex[1] ? 2 : 1, r->res[i].tex);
        free(r->res[i].name);
    }
    free(r->res);
    r->res = NULL;
    r->res_count = 0;
    for (int i = 0; i < r->pass_count; i++)
        if (r->passes[i].fbo) glDeleteFramebuffers(1, &r->passes[i].fbo);
    free(r->passes);
    r->passes = NULL;
    r->pass_count = 0;
}

/* The viewport of the pass at graph index `at` (ABI 1.18): the output size after the upscaler,
 * the render size up to it and in it. */
static void viewport_at(const sl_renderer *r, int at, int *w, int *h) {
    bool after = r->upscaler >= 0 && at > r->upscaler;
    *w = after ? r->out_width : r->width;
    *h = after ? r->out_height : r->height;
}

const char *sl_graph_name_at(const sl_renderer *r, int at, const char *name, bool output) {
    bool upscaled = r->upscaler >= 0 && (at > r->upscaler || (at == r->upscaler && output));
    return upscaled && !strcmp(name, "color") ? SL_OUTPUT_COLOR : name;
}

resource *sl_graph_resource(sl_renderer *r, const graph_pass *g, const char *name, bool output) {
    return sl_graph_find(r, sl_graph_name_at(r, (int)(g - r->passes), name, output));
}

bool sl_graph_pass_reads(const sl_renderer *r, const graph_pass *g, const resource *e) {
    for (const char *const *in = g->d->inputs; in && *in; in++)
        if (!strcmp(sl_graph_name_at(r, (int)(g - r->passes), *in, false), e->name)) return true;
    return false;
}

void sl_graph_add_target(sl_renderer *r, const sl_target_desc *d, int at, bool pingpong) {
    const char *name = sl_graph_name_at(r, at, d->name, true);
    resource *e = sl_graph_find(r, name);
    if (e) {
        if (pingpong && !e->tex[1]) e->tex[1] = make_target(&e->desc, e->w, e->h);
        return;
    }
    resource *grown = realloc(r->res, (r->res_count + 1) * sizeof *r->res);
    if (!grown) {
        SL_ERROR("target \"%s\": out of memory: not created", name);
        return;
    }
    r->res = grown;
    e = &r->res[r->res_count++];
    memset(e, 0, sizeof *e);
    e->name = strdup(name);
    e->desc = *d;
    e->desc.name = e->name;
    resource *color = strcmp(name, SL_OUTPUT_COLOR) ? NULL : sl_graph_find(r, "color");
    if (color) e->desc.format = color->desc.format; /* the upscaled "color" keeps the format (--float) */
    float scale = d->scale > 0 ? d->scale : 1;
    int vw, vh;
    viewport_at(r, at, &vw, &vh);
    if (d->width == SL_SIZE_OUTPUT) vw = r->out_width, vh = r->out_height;
    bool sized = d->width > 0 && d->width != SL_SIZE_OUTPUT;
    e->w = sized ? d->width : (int)(vw * scale + 0.5f);
    e->h = sized && d->height > 0 ? d->height : (int)(vh * scale + 0.5f);
    if (e->w < 1) e->w = 1;
    if (e->h < 1) e->h = 1;
    e->tex[0] = make_target(&e->desc, e->w, e->h);
    if (pingpong) e->tex[1] = make_target(&e->desc, e->w, e->h);
}

bool sl_graph_lists(const char *const *list, const char *name) {
    for (; list && *list; list++)
        if (!strcmp(*list, name)) return true;
    return false;
}

/* For a resource a pass both reads and writes ("color" in a post pass), pass_texture gives the
 * input (current contents) and bind_outputs attaches the other half of the ping-pong pair. */
unsigned sl_renderer_pass_texture(sl_app *app, sl_pass_ctx *ctx, const char *name) {
    sl_renderer *r = R(app);
    resource *e = ctx ? sl_graph_resource(r, ctx->pass, name, false) : NULL;
    if (!e || !ctx) return 0;
    return e->tex[e->current];
}

/* "display" seen as sRGB (a view of the same RGBA8 storage, GL 4.3 texture views): writes through
 * it with GL_FRAMEBUFFER_SRGB enabled are clamped and encoded (IEC 61966-2-1) by the hardware,
 * while readers of "display" keep seeing the RGBA8 code values. Its alpha is whatever the
 * passes wrote: readers take it as 1 (sl_renderer_read), as the display pass writes it. */
static unsigned display_view(sl_renderer *r) {
    resource *d = sl_graph_find(r, "display");
    if (!d) return 0;
    if (!d->srgb_view) {
        glGenTextures(1, &d->srgb_view);
        glTextureView(d->srgb_view, GL_TEXTURE_2D, d->tex[0], GL_SRGB8_ALPHA8, 0, 1, 0, 1);
        static const float opaque[4] = {0, 0, 0, 1};
        glClearTexImage(d->tex[0], 0, GL_RGBA, GL_FLOAT, opaque);
    }
    return d->srgb_view;
}

/* The texture a pass writes for its output `declared` (resource e): the display view when its
 * "color" goes to the display, the other half of a ping-pong pair it reads. */
static unsigned output_texture(sl_renderer *r, sl_pass_ctx *ctx, const char *declared, resource *e) {
    if (ctx->pass->to_display && !strcmp(declared, "color")) return 0; /* bind_outputs: the display view */
    if (e->tex[1] && sl_graph_pass_reads(r, ctx->pass, e)) return e->tex[1 - e->current];
    return e->tex[e->current];
}

sl_status sl_renderer_bind_outputs(sl_app *app, sl_pass_ctx *ctx, int layer) {
    sl_renderer *r = R(app);
    graph_pass *g = ctx->pass;
    if (!g->fbo) glCreateFramebuffers(1, &g->fbo);
    GLenum bufs[8];
    int nc = 0, w = 0, h = 0, display_slot = -1;
    for (int k = 0; k < g->d->output_count && k < 8; k++) {
        const sl_target_desc *o = &g->d->outputs[k];
        resource *e = sl_graph_resource(r, g, o->name, true);
        unsigned tex = output_texture(r, ctx, o->name, e);
        bool depth = o->format == SL_FORMAT_DEPTH32F;
        if (!tex && g->to_display) tex = display_view(r), display_slot = nc;
        GLenum att = depth ? GL_DEPTH_ATTACHMENT : GL_COLOR_ATTACHMENT0 + nc;
        if (o->layers > 1) glNamedFramebufferTextureLayer(g->fbo, att, tex, 0, layer);
        else glNamedFramebufferTexture(g->fbo, att, tex, 0);
        if (!depth) bufs[nc] = att, nc++;
        w = e->w;
        h = e->h;
    }
    if (nc) glNamedFramebufferDrawBuffers(g->fbo, nc, bufs);
    else glNamedFramebufferDrawBuffer(g->fbo, GL_NONE);
    GLenum status = glCheckNamedFramebufferStatus(g->fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        SL_ERROR("pass %s: framebuffer incomplete (0x%x)", g->d->name, status);
        return SL_ERR_GL;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    glViewport(0, 0, w, h);
    /* undone after the pass (graph_run.c). No colour mask on alpha: a mask costs llvmpipe a
     * read-modify-write of every pixel the pass touches (3-4 ns a pixel: the forward pass of
     * scenes/ratio_sphere.json at 1080p, 15.6 -> 8.3 CPU ms with a flat shader; a TAA draw at
     * 256x256 about a fifth of its cost); the readers of "display" take alpha as 1 instead. */
    if (display_slot >= 0) glEnable(GL_FRAMEBUFFER_SRGB);
    return SL_OK;
}

