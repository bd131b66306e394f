/* A test plugin that uses the shadelab.shadow-maps/1 extension the way another plugin would
 * (subsurface translucency): from a PREPASS-stage pass it reads every map's texels back and
 * rebuilds the world points they saw from view_proj and the documented depth convention. The
 * test (test_shadow_extension.c) checks those points lie on the scene's surfaces. Results are
 * reached through a second exported symbol (test plugins only). */
#include "shadow_consumer.h"
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#define CGLM_ALL_UNALIGNED
#include <cglm/cglm.h>
#include <stdlib.h>
#include <string.h>

#define GRID SS_CONSUMER_GRID
static consumer_results results;
static const sl_host *host;
typedef void (*get_sub_image_fn)(GLuint, GLint, GLint, GLint, GLint, GLsizei, GLsizei, GLsizei, GLenum, GLenum, GLsizei, void *);
static get_sub_image_fn get_sub_image;

SL_EXPORT const consumer_results *shadow_consumer_results(void) { return &results; }

static void execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    const sl_ext_shadow_maps *sm = host->get_extension(host, SL_EXT_SHADOW_MAPS);
    results.runs++;
    results.had_extension = sm != NULL;
    results.count = 0;
    if (!sm) return;
    results.version = sm->version(sm->ctx);
    int n = sm->count(sm->ctx);
    for (int i = 0; i < n && i < 32; i++) {
        consumer_map *c = &results.maps[results.count++];
        memset(c, 0, sizeof *c);
        c->m.struct_size = sizeof c->m;
        if (!sm->get(sm->ctx, i, &c->m)) continue;
        sl_shadow_map again = {.struct_size = sizeof again};
        c->find_agrees = sm->find(sm->ctx, c->m.light, c->m.face, &again) && again.layer == c->m.layer;
        int S = c->m.size;
        float *depth = malloc(sizeof(float) * S * S);
        get_sub_image(c->m.texture, 0, 0, 0, c->m.layer, S, S, 1, GL_DEPTH_COMPONENT, GL_FLOAT, (GLsizei)(sizeof(float) * S * S),
                      depth);
        mat4 inv;
        glm_mat4_inv((vec4 *)c->m.view_proj, inv);
        float n_ = c->m.near_plane, f_ = c->m.far_plane;
        c->texel_world_error = fabs(c->m.texel_world * S / 2 - 1 / c->m.proj[0]) * c->m.proj[0];
        for (int gy = 0; gy < GRID; gy++)
            for (int gx = 0; gx < GRID; gx++) {
                int x = (int)((gx + 0.5) / GRID * S), y = (int)((gy + 0.5) / GRID * S);
                float d = depth[y * S + x];
                if (d >= 1.0f) continue;
                float u = (x + 0.5f) / S, v = (y + 0.5f) / S;
                vec4 ndc = {2 * u - 1, 2 * v - 1, 2 * d - 1, 1}, w;
                glm_mat4_mulv(inv, ndc, w);
                float *p = c->p[c->points++];
                for (int k = 0; k < 3; k++) p[k] = w[k] / w[3];
                /* the documented linear depth against the point's own depth along the axis */
                double z = c->m.projection == SL_SHADOW_ORTHOGRAPHIC ? n_ + d * (f_ - n_)
                                                                      : 2.0 * n_ * f_ / (f_ + n_ - (2.0 * d - 1) * (f_ - n_));
                double along = (p[0] - c->m.position[0]) * c->m.direction[0] + (p[1] - c->m.position[1]) * c->m.direction[1] +
                               (p[2] - c->m.position[2]) * c->m.direction[2];
                double e = fabs(z - along) / fmax(fabs(along), 1e-3);
                if (e > c->depth_formula_error) c->depth_formula_error = e;
            }
        free(depth);
    }
}

static sl_status create(const sl_host *h, void **user) {
    host = h;
    const sl_pass_desc pass = {.struct_size = sizeof pass, .name = "shadow-consumer", .stage = SL_STAGE_PREPASS,
                               .execute = execute};
    *user = NULL;
    return h->add_pass(h, &pass);
}

static sl_status activate(void *user) {
    if (!sl_gl_load(host->gl_get_proc_address, NULL)) return SL_ERR_GL;
    get_sub_image = (get_sub_image_fn)host->gl_get_proc_address("glGetTextureSubImage");
    return get_sub_image ? SL_OK : SL_ERR_GL;
}

static const sl_plugin_desc desc = {
    SL_PLUGIN_HEADER,
    .id = "shadow-consumer",
    .version = "1.0",
    .description = "test: reads the shadow maps through shadelab.shadow-maps/1",
    .create = create,
    .activate = activate,
};

SL_DEFINE_PLUGIN(desc)
