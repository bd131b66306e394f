/* The scene on the GPU: meshes, material textures, the light buffer, material programs and the
 * draws that use them. See renderer_internal.h. */
#include "render/renderer_internal.h"
#include "log.h"
#include <shadelab/gl.h>
#include <stdlib.h>
#include <string.h>
#include "image/image.h"
#include "render/texture_prefetch.h"
#include "plugin_lights.h"
#include "render/composer.h"
#include <cglm/cglm.h>
#include <math.h>

/* ------------------------------------------------------------------ meshes ---------- */

/* attribute `loc` of vao reads `comps` floats per vertex, tightly packed, from vbo */
static void bind_float_attrib(unsigned vao, int loc, unsigned vbo, int comps) {
    glVertexArrayVertexBuffer(vao, loc, vbo, 0, comps * sizeof(float));
    glVertexArrayAttribFormat(vao, loc, comps, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, loc, loc);
    glEnableVertexArrayAttrib(vao, loc);
}

void sl_gpu_upload_mesh(gpu_mesh *g, const sl_mesh_data *m) {
    glCreateVertexArrays(1, &g->vao);
    glCreateBuffers(4, g->vbo);
    if (m->uvs1) glCreateBuffers(1, &g->vbo[4]);
    if (m->colors) glCreateBuffers(1, &g->vbo[5]);
    glCreateBuffers(1, &g->ibo);
    const float *arrays[4] = {m->positions, m->normals, m->tangents, m->uvs};
    const int comps[4] = {3, 3, 4, 2};
    for (int a = 0; a < 4; a++) {
        size_t bytes = (size_t)m->vertex_count * comps[a] * sizeof(float);
        float *fallback = NULL;
        if (!arrays[a]) { /* missing attribute: zeros (tangent w = 1) */
            fallback = calloc((size_t)m->vertex_count * comps[a] + 1, sizeof(float));
            if (a == 2) for (int v = 0; v < m->vertex_count; v++) fallback[v * 4 + 3] = 1;
        }
        static const float none[4];
        glNamedBufferData(g->vbo[a], bytes ? bytes : sizeof none,
                          !bytes ? (const void *)none : arrays[a] ? (const void *)arrays[a] : fallback, GL_STATIC_DRAW);
        free(fallback);
        bind_float_attrib(g->vao, a, g->vbo[a], comps[a]);
    }
    /* the second UV set (location 4) only where the mesh has one; programs read it only for
     * materials with a texture on it (SL_MAT_USES_UV1), elsewhere the attribute stays off */
    if (m->uvs1 && m->vertex_count > 0) {
        glNamedBufferData(g->vbo[4], (size_t)m->vertex_count * 2 * sizeof(float), m->uvs1, GL_STATIC_DRAW);
        bind_float_attrib(g->vao, 4, g->vbo[4], 2);
    }
    /* vertex colours (location 6) likewise: read by the programs of materials a coloured mesh uses
     * (SL_MAT_USES_VERTEX_COLOR); a mesh without them drawn by such a program reads white (the
     * attribute's current value, set once at the renderer's creation) */
    if (m->colors && m->vertex_count > 0) {
        glNamedBufferData(g->vbo[5], (size_t)m->vertex_count * 4 * sizeof(float), m->colors, GL_STATIC_DRAW);
        bind_float_attrib(g->vao, 6, g->vbo[5], 4);
    }
    /* the previous frame's positions (motion vectors, forward.vert): a static mesh's own; a
     * deformed mesh's buffer of them (deform.c) replaces this binding */
    bind_float_attrib(g->vao, 5, g->vbo[0], 3);
    static const uint32_t no_indices[1];
    glNamedBufferData(g->ibo, m->index_count ? (size_t)m->index_count * 4 : 4, m->index_count ? m->indices : no_indices,
                      GL_STATIC_DRAW);
    glVertexArrayElementBuffer(g->vao, g->ibo);
    g->index_count = m->index_count;
    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int v = 0; m->positions && v < m->vertex_count; v++)
        for (int c = 0; c < 3; c++) {
            float x = m->positions[v * 3 + c];
            if (v == 0 || x < lo[c]) lo[c] = x;
            if (v == 0 || x > hi[c]) hi[c] = x;
        }
    for (int c = 0; c < 3; c++) g->center[c] = 0.5f * (lo[c] + hi[c]), g->lo[c] = lo[c], g->hi[c] = hi[c];
    g->radius = 0.5f * sqrtf((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                             (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/* ------------------------------------------------------------------ textures -------- */

/* Loads a material texture: colour textures decode sRGB in the sampler (8-bit) or on the CPU
 * (16-bit); data textures stay linear. */
/* core.anisotropy onto every material texture (a parameter change reaches the loaded ones too).
 * 0 (the default) is what looks right on the backend: 8 on a GPU; 1 on a CPU renderer, whose
 * anisotropic filter (llvmpipe: the same image for 2…16) draws a checker edge seen at a grazing
 * angle as a stack of disks — scallops — where isotropic filtering keeps it straight
 * (tests/test_core_render.c, test_anisotropy_default). */
void sl_gpu_apply_anisotropy(sl_app *app) {
    sl_renderer *r = R(app);
    const sl_param *p = sl_params_find(&app->params, "core.anisotropy");
    int a = p ? p->value.i : 0;
    if (a == 0) a = app->backend.is_gpu ? 8 : 1;
    a = a < 1 ? 1 : a > 16 ? 16 : a;
    if (a == r->anisotropy) return;
    r->anisotropy = a;
    for (int i = 0; i < r->texture_count; i++) glTextureParameterf(r->textures[i].id, GL_TEXTURE_MAX_ANISOTROPY, (float)a);
}

/* The texture LOD bias plugins asked for this frame (ABI 1.21: a TAA still's) onto every material
 * texture, when it changed. */
void sl_gpu_apply_lod_bias(sl_app *app, float bias) {
    sl_renderer *r = R(app);
    if (bias == r->lod_bias) return;
    r->lod_bias = bias;
    for (int i = 0; i < r->texture_count; i++) glTextureParameterf(r->textures[i].id, GL_TEXTURE_LOD_BIAS, bias);
}

/* 8-bit files: every level as bytes, the mip chain made on the CPU (sl_image_mip_rgba8, a box
 * filter, sRGB-correct for sRGB storage) — what glGenerateTextureMipmap makes, without llvmpipe
 * compiling a blit shader per format at start-up (60-180 ms each, issue 18 item 5) and without
 * the driver converting float to bytes. False (nothing uploaded) for other images or without memory. */
static bool upload_rgba8_mipmapped(unsigned tex, const sl_image *img, int levels, bool srgb) {
    if (img->source_bits != 8 || img->source_float) return false;
    size_t n = (size_t)img->width * img->height * 4;
    unsigned char *a = malloc(n), *b = malloc(n); /* levels shrink: either holds any */
    if (!a || !b) {
        free(a), free(b);
        return false;
    }
    for (size_t i = 0; i < n; i++) { /* the file's codes: k/255 exactly, back to k */
        float v = img->pixels[i];
        a[i] = !(v > 0.0f) ? 0 : v >= 1.0f ? 255 : (unsigned char)(v * 255.0f + 0.5f);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    int w = img->width, h = img->height;
    for (int l = 0; l < levels; l++) {
        glTextureSubImage2D(tex, l, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, a);
        if (l + 1 == levels) break;
        sl_image_mip_rgba8(a, w, h, b, srgb);
        w = w > 1 ? w / 2 : 1, h = h > 1 ? h / 2 : 1;
        unsigned char *t = a;
        a = b, b = t;
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    free(a), free(b);
    return true;
}

/* Other images in linear storage (procedural textures, 16-bit and float files): the same box mip
 * chain in float on the CPU (sl_image_mip_rgbaf), for the same reason. False (nothing uploaded)
 * without memory. */
static bool upload_float_mipmapped(unsigned tex, const sl_image *img, int levels) {
    int w = img->width > 1 ? img->width / 2 : 1, h = img->height > 1 ? img->height / 2 : 1;
    float *a = malloc((size_t)w * h * 4 * sizeof(float)), *b = malloc((size_t)w * h * 4 * sizeof(float));
    if (!a || !b) {
        free(a), free(b);
        return false;
    }
    glTextureSubImage2D(tex, 0, 0, 0, img->width, img->height, GL_RGBA, GL_FLOAT, img->pixels);
    const float *src = img->pixels;
    w = img->width, h = img->height;
    for (int l = 1; l < levels; l++) {
        sl_image_mip_rgbaf(src, w, h, a);
        w = w > 1 ? w / 2 : 1, h = h > 1 ? h / 2 : 1;
        glTextureSubImage2D(tex, l, 0, 0, w, h, GL_RGBA, GL_FLOAT, a);
        float *t = a;
        a = b, b = t;
        src = b;
    }
    free(a), free(b);
    return true;
}

/* `where` names the scene line, material and key (or the asset file) for the messages. */
static unsigned load_texture(sl_app *app, const char *spec, bool linear_data, bool clamp, const char *where) {
    sl_renderer *r = R(app);
    char key[2100];
    snprintf(key, sizeof key, "%s|%d|%d", spec, linear_data, clamp);
    for (int i = 0; i < r->texture_count; i++)
        if (!strcmp(r->textures[i].key, key)) return r->textures[i].id;
    sl_image img = {0};
    char err[1024] = "";
    bool ok;
    bool srgb_storage = false;
    if (sl_image_is_procedural(spec)) {
        ok = sl_image_procedural(&img, spec, 256, err, sizeof err);
        /* procedural colours are linear already */
    } else {
        const sl_embedded_image *e = sl_scene_find_image(&app->scene, spec); /* a .glb's own images */
        if (sl_texture_prefetch_take(app, spec, &img, &ok, err, sizeof err)) {
            /* decoded on the worker thread (texture_prefetch.h) */
        } else if (e) {
            ok = sl_image_load_memory(&img, e->data, e->size, e->name, err, sizeof err);
        } else {
            char *path = sl_scene_resolve_path(&app->scene, app->opt.data_dir, spec, err, sizeof err);
            ok = path && sl_image_load(&img, path, err, sizeof err);
            free(path);
        }
        if (ok && !linear_data && img.source_srgb) {
            if (img.source_bits == 8) srgb_storage = true;
            else sl_image_srgb_to_linear(&img);
        }
        /* policy for texture files: finite, >= 0 and at most SL_MAX_RADIANCE, with one warning */
        long nonfinite = 0, negative = 0, over = 0;
        if (ok && img.source_float && sl_image_sanitize(&img, (float)SL_MAX_RADIANCE, &nonfinite, &negative, &over))
            SL_WARN("%s: texture %s: replaced %ld NaN/Inf, %ld negative and %ld over-%g samples (NaN, -Inf and "
                    "negatives by 0; +Inf and large values by %g)", where, spec, nonfinite, negative, over, SL_MAX_RADIANCE,
                    SL_MAX_RADIANCE);
    }
    unsigned tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    if (!ok) {
        SL_ERROR("%s: texture %s: %s (using a magenta placeholder)", where, spec, err);
        float magenta[4] = {1, 0, 1, 1};
        glTextureStorage2D(tex, 1, GL_RGBA8, 1, 1);
        glTextureSubImage2D(tex, 0, 0, 0, 1, 1, GL_RGBA, GL_FLOAT, magenta);
    } else {
        int levels = 1;
        for (int s = img.width > img.height ? img.width : img.height; s > 1; s >>= 1) levels++;
        GLenum fmt = srgb_storage ? GL_SRGB8_ALPHA8
                   : img.source_bits == 8 ? GL_RGBA8 : img.source_bits == 16 ? GL_RGBA16F : GL_RGBA32F;
        glTextureStorage2D(tex, levels, fmt, img.width, img.height);
        /* UV convention (scenes/README.md): v = 0 is the TOP row of the image, as in glTF. GL's
         * t = 0 is the first row uploaded, so rows go up top first, as the image stores them. */
        if (!upload_rgba8_mipmapped(tex, &img, levels, srgb_storage) &&
            (srgb_storage || !upload_float_mipmapped(tex, &img, levels))) {
            glTextureSubImage2D(tex, 0, 0, 0, img.width, img.height, GL_RGBA, GL_FLOAT, img.pixels);
            glGenerateTextureMipmap(tex);
        }
        glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_S, clamp ? GL_CLAMP_TO_EDGE : GL_REPEAT);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_T, clamp ? GL_CLAMP_TO_EDGE : GL_REPEAT);
        /* an imported texture's own sampler (glTF "samplers": GL enums; 0 keeps the default) */
        const sl_texture_sampler *smp = sl_scene_find_sampler(&app->scene, spec);
        if (smp && smp->wrap_s) glTextureParameteri(tex, GL_TEXTURE_WRAP_S, smp->wrap_s);
        if (smp && smp->wrap_t) glTextureParameteri(tex, GL_TEXTURE_WRAP_T, smp->wrap_t);
        if (smp && smp->mag_filter) glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, smp->mag_filter);
        if (smp && smp->min_filter) glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, smp->min_filter);
        if (!r->anisotropy) sl_gpu_apply_anisotropy(app);
        glTextureParameterf(tex, GL_TEXTURE_MAX_ANISOTROPY, (float)r->anisotropy);
        glTextureParameterf(tex, GL_TEXTURE_LOD_BIAS, r->lod_bias);
    }
    sl_image_free(&img);
    gpu_texture *grown = realloc(r->textures, (r->texture_count + 1) * sizeof *r->textures);
    if (!grown) return tex; /* drawn, not cached */
    r->textures = grown;
    r->textures[r->texture_count++] = (gpu_texture){strdup(key), tex};
    return tex;
}

unsigned sl_renderer_material_texture(sl_app *app, int m, const char *key) {
    sl_renderer *r = R(app);
    if (!r || m < 0 || m >= app->scene.material_count) return 0;
    const material_rt *mr = &r->materials[m];
    for (int t = 0; t < mr->forward.texture_count; t++)
        if (!strcmp(app->params.items[mr->forward.texture_params[t]].full_id, key)) return mr->textures[t];
    return 0;
}

/* ------------------------------------------------------------------ lights ---------- */

bool sl_gpu_lights_animated(sl_app *app) {
    for (int i = 0; i < app->scene.light_count; i++) {
        const sl_light *L = &app->scene.lights[i];
        if (L->enabled && L->animate != SL_ANIMATE_NONE && L->animate_speed != 0) return true;
    }
    return false;
}

/* colour × intensity: finite by the schema's ranges (colour <= 65504, intensity <= 1e10, the same
 * from a scene as from --set), with room for any BRDF value before float overflow; the forward
 * pass clamps what it writes to SL_MAX_RADIANCE. */
static void light_radiant(const sl_light *L, float out[3]) {
    for (int c = 0; c < 3; c++) out[c] = L->color[c] * L->intensity;
}

typedef struct { float position[4], direction[4], color[4], params[8]; } gpu_light; /* SlLight (std140 = std430) */

/* A uniform block or a storage buffer for sl_lights[]: llvmpipe reads a uniform block markedly
 * faster (per light, 1920x1080, scenes/ratio_sphere.json: 16 lights 79.4 -> 64.9 CPU ms a frame,
 * 64 lights 287 -> 250; docs/design-notes.md "The light loop"), but one holds only
 * GL_MAX_UNIFORM_BLOCK_SIZE bytes (64 KiB: 819 lights); more lights use a storage buffer
 * (the many-lights extra's thousands). */
int sl_gpu_light_block_capacity(void) {
    static int cap;
    if (!cap) {
        GLint bytes = 0;
        glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &bytes);
        if (bytes > 65536) bytes = 65536;
        cap = bytes >= (GLint)sizeof(gpu_light) ? bytes / (int)sizeof(gpu_light) : -1;
    }
    return cap;
}

bool sl_gpu_lights_in_uniform_block(sl_app *app) { return app->scene.light_count <= sl_gpu_light_block_capacity(); }

/* The light buffer and the lights plugins see (sl_host.lights), at app->time. */
void sl_gpu_pack_lights(sl_app *app) {
    sl_renderer *r = R(app);
    r->lights_packed++;
    sl_scene *s = &app->scene;
    free(r->lights);
    r->lights = calloc(s->light_count + 1, sizeof *r->lights);
    r->light_count = s->light_count;
    r->ntypes = sl_forward_light_types(app, r->types, SL_MAX_LIGHT_TYPES);
    gpu_light *buf = calloc(s->light_count + 1, sizeof *buf);
    int k = 0;
    /* the enabled shadow casters of the types with an l/E pair first, in ranges of their own
     * (sl_shadowed_<type>: the forward programs' casters loop, forward.c), then the rest */
    bool casters = sl_forward_shadow_casters(app);
    for (int pass = casters ? 0 : 1; pass < 2; pass++)
        for (int t = 0; t < r->ntypes; t++) {
            int(*range)[2] = pass == 0 ? r->shadowed_range : r->type_range;
            bool lit = sl_forward_light_type_lit(app, r->types[t]);
            range[t][0] = k;
            if (pass == 0 && !lit) { /* no casters' loop for a type without an l/E pair: its */
                range[t][1] = k;     /* casters stay in its own range (pass 1) */
                continue;
            }
            for (int i = 0; i < s->light_count; i++) {
                const sl_light *L = &s->lights[i];
                if (!sl_light_on(app, L) || strcmp(L->type, r->types[t])) continue;
                if (casters && lit && L->cast_shadows != (pass == 0)) continue;
                sl_light_info *info = &r->lights[i];
                info->index = k;
                gpu_light *g = &buf[k++];
                sl_light_at_time(L, app->time, g->position, g->direction);
                g->direction[3] = L->angular_radius * (float)M_PI / 180; /* SlLight.direction.w */
                light_radiant(L, g->color);
                memcpy(g->params, app->light_params[i], sizeof g->params);
            }
            range[t][1] = k;
        }
    if (!casters) memset(r->shadowed_range, 0, sizeof r->shadowed_range);
    for (int i = 0; i < s->light_count; i++) {
        const sl_light *L = &s->lights[i];
        sl_light_info *info = &r->lights[i];
        info->struct_size = sizeof *info;
        info->name = L->name;
        info->type = L->type;
        sl_light_at_time(L, app->time, info->position, info->direction); /* where the animation puts it */
        light_radiant(L, info->color);
        memcpy(info->params, app->light_params[i], sizeof info->params);
        info->enabled = sl_light_on(app, L);
        info->cast_shadows = L->cast_shadows;
        info->owner = L->plugin ? app->plugins.items[L->plugin - 1]->id : NULL;
        info->angular_radius = L->angular_radius;
        if (!info->enabled) info->index = -1;
    }
    if (!r->light_buffer) glCreateBuffers(1, &r->light_buffer);
    /* a uniform block is read as its declared size: the buffer holds the whole capacity */
    int records = sl_gpu_lights_in_uniform_block(app) ? sl_gpu_light_block_capacity() : k + 1;
    glNamedBufferData(r->light_buffer, (size_t)records * sizeof(gpu_light), NULL, GL_DYNAMIC_DRAW);
    if (k) glNamedBufferSubData(r->light_buffer, 0, (size_t)k * sizeof(gpu_light), buf);
    free(buf);
}

const sl_light_info *sl_renderer_lights(sl_app *app, int *count) {
    sl_renderer *r = R(app);
    *count = r ? r->light_count : 0;
    return r ? r->lights : NULL;
}

/* ------------------------------------------------------------------ materials ------- */

/* A material program that did not compose or compile (issue 41: one failure policy). Its plugin
 * is switched off between frames with one message (sl_renderer_failed_plugin, app.c), except in a
 * hot reload that keeps the variant's last good program; an error no plugin can be blamed for
 * (the core's own GLSL) is logged as it is. */
static void compose_failed(sl_app *app, const sl_forward_variant *v, const char *err) {
    sl_renderer *r = R(app);
    int k = v->failed_plugin;
    bool keep_last_good = r->reloading && v->program && !(k < 64 && (r->retried >> k & 1));
    if (k >= 1 && !keep_last_good) sl_renderer_blame_plugin(app, k, err);
    else SL_ERROR("%s", err);
}

static void compose(sl_app *app, int m, sl_variant_kind kind, const char *model, const char *fragment, bool fullscreen,
                    sl_forward_variant *v) {
    sl_renderer *r = R(app);
    char err[16384];
    sl_variant_request req = {.kind = kind, .model_override = model, .fragment = fragment, .fullscreen = fullscreen};
    if (!sl_forward_compose(app, m, &req, v, &r->cache, err, sizeof err))
        compose_failed(app, v, err);
}

void sl_gpu_compose_all(sl_app *app) {
    sl_renderer *r = R(app);
    for (int m = 0; m < app->scene.material_count; m++) {
        material_rt *mr = &r->materials[m];
        compose(app, m, SL_VARIANT_FORWARD, NULL, NULL, false, &mr->forward);
        compose(app, m, SL_VARIANT_DEPTH, NULL, NULL, false, &mr->depth);
        /* draw_scene's variants are dropped, not composed again: the next draw that asks composes
         * its own (its programs from the cache when the sources match). Composing them here would
         * compile a switched-off plugin's main without its chunks, and blame that plugin. */
        for (int k = 0; k < mr->override_count; k++) {
            free(mr->overrides[k].model);
            free(mr->overrides[k].fragment);
            free(mr->overrides[k].v.chunks);
        }
        mr->override_count = 0;
        mr->override_overflow_reported = false;
        for (int t = 0; t < mr->forward.texture_count; t++) {
            const sl_param *q = &app->params.items[mr->forward.texture_params[t]];
            sl_mat_value *v = sl_app_material_value(app, m, q->full_id);
            if (!v || !v->str) {
                mr->textures[t] = 0;
                continue;
            }
            /* messages name where the texture was given: the scene line and material and key, or
             * the asset file an imported material came from */
            const sl_material *sm = &app->scene.materials[m];
            const sl_prop *given = sl_prop_find(&sm->props, q->desc.id);
            if (!given) given = sl_prop_find(&sm->props, q->full_id);
            char where[1400];
            if (sm->source && !given)
                snprintf(where, sizeof where, "%.600s: material '%.300s' (%s)", sm->source, sm->name, q->desc.id);
            else if (given && given->line > 0)
                snprintf(where, sizeof where, "%.600s:%d: material '%.300s' \"%s\"", app->scene.path ? app->scene.path : "scene",
                         given->line, sm->name, q->desc.id);
            else
                snprintf(where, sizeof where, "material '%.300s' \"%s\"", sm->name, q->desc.id);
            mr->textures[t] = load_texture(app, v->str, q->desc.flags & SL_PARAM_LINEAR_DATA,
                                           q->desc.flags & SL_PARAM_CLAMP_TO_EDGE, where);
        }
    }
}

static void set_value_uniform(sl_program *p, const char *name, const sl_param *q, const sl_value *v) {
    int loc = sl_program_uniform(p, name);
    if (loc < 0) return;
    unsigned prog = p->id;
    switch (q->desc.type) {
    case SL_PARAM_BOOL: glProgramUniform1i(prog, loc, v->b); break;
    case SL_PARAM_INT: case SL_PARAM_ENUM: glProgramUniform1i(prog, loc, v->i); break;
    case SL_PARAM_FLOAT: glProgramUniform1f(prog, loc, v->f[0]); break;
    case SL_PARAM_COLOR: case SL_PARAM_VEC3: glProgramUniform3f(prog, loc, v->f[0], v->f[1], v->f[2]); break;
    case SL_PARAM_TEXTURE: break;
    }
}

static void set_camera_uniforms(sl_app *app, sl_program *p, const float *view, const float *proj) {
    sl_renderer *r = R(app);
    mat4 vp;
    glm_mat4_mul((vec4 *)proj, (vec4 *)view, vp);
    glUniformMatrix4fv(sl_program_uniform(p, "sl_view"), 1, GL_FALSE, view);
    glUniformMatrix4fv(sl_program_uniform(p, "sl_proj"), 1, GL_FALSE, proj);
    glUniformMatrix4fv(sl_program_uniform(p, "sl_view_proj"), 1, GL_FALSE, (float *)vp);
    glUniform3fv(sl_program_uniform(p, "sl_camera_pos"), 1, r->frame.camera_pos);
    glUniform1f(sl_program_uniform(p, "sl_time"), (float)r->frame.time);
    glUniform1i(sl_program_uniform(p, "sl_frame_index"), r->frame.accumulate_index);
    glUniform1i(sl_program_uniform(p, "sl_sample_index"), r->frame.sample_index);
    glUniform1i(sl_program_uniform(p, "sl_sample_count"), r->frame.sample_count);
    glUniform2f(sl_program_uniform(p, "sl_viewport_size"), (float)r->frame.width, (float)r->frame.height);
    glUniform2f(sl_program_uniform(p, "sl_jitter"), r->frame.jitter[0], r->frame.jitter[1]);
    glUniform1f(sl_program_uniform(p, "sl_texture_lod_bias"), r->lod_bias);
    if (r->motion) { /* SL_MOTION_VECTORS programs (forward.vert) */
        glUniformMatrix4fv(sl_program_uniform(p, "sl_unjittered_view_proj"), 1, GL_FALSE, r->frame.unjittered_view_proj);
        glUniformMatrix4fv(sl_program_uniform(p, "sl_prev_view_proj"), 1, GL_FALSE,
                           r->have_prev ? r->prev_unjittered_vp : r->frame.unjittered_view_proj);
        glUniform1f(sl_program_uniform(p, "sl_prev_time"), (float)(r->have_prev ? r->prev_time : r->frame.time));
    }
}

/* Binds a material's program and every uniform it reads except the per-object ones. */
static sl_program *bind_material(sl_app *app, int m, const sl_forward_variant *var, const float *view, const float *proj) {
    sl_renderer *r = R(app);
    sl_program *p = var->program;
    unsigned prog = p ? p->id : 0;
    if (!prog) return NULL;
    glUseProgram(prog);
    set_camera_uniforms(app, p, view, proj);
    const sl_environment *env = &app->scene.environment;
    glUniform3f(sl_program_uniform(p, "sl_ambient_irradiance"), (float)M_PI * env->color[0] * env->intensity,
                (float)M_PI * env->color[1] * env->intensity, (float)M_PI * env->color[2] * env->intensity);
    for (int t = 0; t < r->ntypes; t++) {
        char name[160], id[128];
        sl_glsl_ident(r->types[t], id, sizeof id, false);
        snprintf(name, sizeof name, "sl_lights_%s", id);
        glUniform2i(sl_program_uniform(p, name), r->type_range[t][0], r->type_range[t][1]);
        snprintf(name, sizeof name, "sl_shadowed_%s", id);
        glUniform2i(sl_program_uniform(p, name), r->shadowed_range[t][0], r->shadowed_range[t][1]);
    }
    glBindBufferBase(sl_gpu_lights_in_uniform_block(app) ? GL_UNIFORM_BUFFER : GL_SHADER_STORAGE_BUFFER, 0, r->light_buffer);
    if (var->program->tessellated) {
        /* levels from the frame's camera in every pass (shaders/tess.glsl): shadow maps tessellate
         * as the view does; proj[1][1] × height / 2 = pixels per unit at unit distance */
        glUniform1f(sl_program_uniform(p, "sl_tess_pixel_scale"), r->frame.proj[5] * 0.5f * (float)r->frame.height);
        glUniform1i(sl_program_uniform(p, "sl_tess_orthographic"), r->frame.proj[15] == 1.0f);
    }
    sl_mat_state *ms = &app->materials[m];
    for (int i = 0; i < ms->count; i++) {
        const sl_param *q = &app->params.items[ms->values[i].param];
        if (q->desc.type == SL_PARAM_TEXTURE || (q->desc.flags & SL_PARAM_NEEDS_RECOMPILE)) continue;
        char name[200];
        snprintf(name, sizeof name, "sl_mat_%s", q->full_id);
        set_value_uniform(p, name, q, &ms->values[i].v);
    }
    for (int t = 0; t < var->texture_count; t++) glBindTextureUnit(SL_TEXTURE_UNIT_MATERIAL_FIRST + t, r->materials[m].textures[t]);
    for (int i = 0; i < app->params.count; i++) {
        const sl_param *q = &app->params.items[i];
        if (q->desc.scope != SL_SCOPE_GLOBAL || (q->desc.flags & SL_PARAM_NEEDS_RECOMPILE)) continue;
        int owner = sl_plugins_find(&app->plugins, q->owner);
        if (owner < 0 || !(var->owners & (1ull << (owner & 63)))) continue;
        char name[300], oid[128];
        sl_glsl_ident(q->owner, oid, sizeof oid, false);
        snprintf(name, sizeof name, "%s_%s", oid, q->desc.id);
        set_value_uniform(p, name, q, &q->value);
    }
    for (int i = 0; i < app->plugins.count; i++) {
        sl_plugin_rec *pr = app->plugins.items[i];
        if ((var->owners & (1ull << (i & 63))) && pr->bind && sl_plugin_enabled(&app->plugins, i)) pr->bind(pr->bind_user, prog, m, &r->frame);
    }
    return p;
}

/* ------------------------------------------------------------------ drawing --------- */

/* The forward-blend pass's own uniforms (forward.frag, SL_MAT_ALPHA_BLEND): "depth" holds
 * ssaa × ssaa samples per pixel of "color"; the fragment tests them itself. 0 outside that pass:
 * the material's fragments are written opaque (alpha 1), as before blending existed. */
static void blend_uniforms(sl_app *app, sl_program *p, bool blend_pass) {
    sl_renderer *r = R(app);
    glUniform1i(sl_program_uniform(p, "sl_blend_depth"), SL_BLEND_DEPTH_UNIT);
    glUniform1i(sl_program_uniform(p, "sl_blend_ssaa"), blend_pass ? r->ssaa : 0);
    /* the capture's mip count − 1 (shaders/scene_behind.glsl) */
    int side = r->behind_w > r->behind_h ? r->behind_w : r->behind_h;
    glUniform1f(sl_program_uniform(p, "sl_scene_behind_levels"), side > 0 ? floorf(log2f((float)side)) : 0.0f);
}

/* The material's program with its shading model replaced (SL_DRAW_MATERIALS). */
static bool same_name(const char *a, const char *b) { return a == b || (a && b && !strcmp(a, b)); }

/* The material's program with its shading model replaced and/or a plugin's fragment main
 * (SL_DRAW_MATERIALS; fragment: ABI 1.7). */
static const sl_forward_variant *override_variant_of(sl_app *app, int m, const char *model, const char *fragment,
                                                     bool fullscreen) {
    material_rt *mr = &R(app)->materials[m];
    for (int k = 0; k < mr->override_count; k++)
        if (same_name(mr->overrides[k].model, model) && same_name(mr->overrides[k].fragment, fragment) &&
            mr->overrides[k].fullscreen == fullscreen)
            return &mr->overrides[k].v;
    if (mr->override_count == SL_MAX_OVERRIDE_VARIANTS) {
        if (!mr->override_overflow_reported)
            SL_ERROR("material \"%s\": draw_scene asked for a program variant too many (model %s, fragment %s): a "
                     "material keeps at most %d (renderer_internal.h, SL_MAX_OVERRIDE_VARIANTS); not drawn there",
                     app->scene.materials[m].name, model ? model : "its own", fragment ? fragment : "none",
                     SL_MAX_OVERRIDE_VARIANTS);
        mr->override_overflow_reported = true;
        return NULL;
    }
    override_variant *o = &mr->overrides[mr->override_count++];
    memset(o, 0, sizeof *o);
    o->model = model ? strdup(model) : NULL;
    o->fragment = fragment ? strdup(fragment) : NULL;
    o->fullscreen = fullscreen;
    compose(app, m, SL_VARIANT_FORWARD, model, fragment, fullscreen, &o->v);
    return &o->v;
}

/* SL_DRAW_MATERIALS with a fragment and `fullscreen` (ABI 1.7): one full-screen triangle per
 * material with its program and uniforms bound (deferred lighting). */
static void draw_materials_fullscreen(sl_app *app, const sl_draw_scene_desc *d, const char *fragment) {
    sl_renderer *r = R(app);
    glDisable(GL_CULL_FACE); /* the depth test stays as the pass set it (pass.h) */
    glBindVertexArray(r->empty_vao);
    for (int m = 0; m < app->scene.material_count; m++) {
        if (d->only_materials_with) {
            sl_mat_value *v = sl_app_material_value(app, m, d->only_materials_with);
            if (!v || !v->present) continue;
        }
        const sl_forward_variant *var = override_variant_of(app, m, d->model_override, fragment, true);
        sl_program *p = var ? bind_material(app, m, var, d->view, d->proj) : NULL;
        if (!p) continue;
        glUniform1i(sl_program_uniform(p, "sl_material_index"), m);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        r->stats.draw_calls++;
    }
    glBindVertexArray(0);
}

/* glTF alphaMode BLEND (the core's material key alpha_blend): drawn after the opaque materials,
 * back to front, blended, without depth writes (the core's "forward-blend" pass). */
bool sl_gpu_material_blended(sl_app *app, int m) {
    const sl_mat_value *v = sl_app_material_value(app, m, "alpha_blend");
    return v && v->v.b;
}

bool sl_gpu_scene_has_blended(sl_app *app) {
    for (int m = 0; m < app->scene.material_count; m++)
        if (sl_gpu_material_blended(app, m)) return true;
    return false;
}

/* Materials with a SCENE_BEHIND hook (shader.h, ABI 1.17) are drawn after every opaque pass over
 * the captured opaque scene, back to front (the core's "forward-behind" pass); a blended one stays
 * in forward-blend, which comes later and sees the same capture. */
bool sl_gpu_scene_has_behind(sl_app *app) {
    for (int m = 0; m < app->scene.material_count; m++)
        if (sl_forward_reads_scene_behind(app, m)) return true;
    return false;
}

/* Where a draw of material m goes: 0 the opaque passes, 1 forward-behind, 2 forward-blend. */
static int draw_class(sl_app *app, int m) {
    return sl_gpu_material_blended(app, m) ? 2 : sl_forward_reads_scene_behind(app, m) ? 1 : 0;
}

/* One draw: a mesh of a node. `depth`: view-space distance of the mesh's bounds centre (blended
 * draws sort on it, farthest first); `order`: its place in the scene (ties keep it). */
typedef struct draw_item { int m, node, k, order; float depth; } draw_item;

static int cmp_back_to_front(const void *a, const void *b) {
    const draw_item *x = a, *y = b;
    if (x->depth != y->depth) return x->depth > y->depth ? -1 : 1;
    return x->order - y->order;
}

/* Whether the view (proj × view) may skip meshes outside its frustum: not when a plugin's vertex
 * stage may move vertices beyond their bounds (a VERTEX or DISPLACEMENT hook, a plugin's own
 * program), nor in UV space (texture-space targets draw every mesh). */
static bool may_cull(sl_app *app, const sl_draw_scene_desc *d, bool custom) {
    if (custom || d->uv_space) return false;
    for (int i = 0; i < app->plugins.chunk_count; i++) {
        const sl_chunk_reg *c = &app->plugins.chunks[i];
        if ((c->d.hook == SL_HOOK_VERTEX || c->d.hook == SL_HOOK_DISPLACEMENT) && sl_plugin_enabled(&app->plugins, c->owner))
            return false;
    }
    return true;
}

/* The mesh's object-space box, placed by `world`, lies wholly outside one of the side planes of
 * the clip volume whose planes are `planes` (left, right, bottom, top: cglm's order). Only the
 * sides: a shadow map's casters before its near plane are drawn (depth clamp), and the far plane
 * saves little. Conservative: a box that may touch the view is kept. */
static bool outside_frustum(const gpu_mesh *g, const float world[16], vec4 planes[6]) {
    vec3 box[2] = {{g->lo[0], g->lo[1], g->lo[2]}, {g->hi[0], g->hi[1], g->hi[2]}}, wbox[2];
    glm_aabb_transform(box, (vec4 *)world, wbox);
    for (int p = 0; p < 4; p++) {
        const float *n = planes[p];
        /* the box's corner farthest along the plane's normal */
        float x = n[0] > 0 ? wbox[1][0] : wbox[0][0], y = n[1] > 0 ? wbox[1][1] : wbox[0][1];
        float z = n[2] > 0 ? wbox[1][2] : wbox[0][2];
        if (n[0] * x + n[1] * y + n[2] * z + n[3] < 0) return true;
    }
    return false;
}

/* The draws of a frame: opaque (and masked) materials first, in material order (one program
 * bind each), then those that read the scene behind them, then blended ones, each group sorted
 * back to front by the view depth of each draw's bounds
 * centre (the usual viewer approach: per draw, not per triangle; intersecting or interleaved
 * blended surfaces are approximate). With `cull`, meshes wholly outside the view's side planes
 * are left out (may_cull, outside_frustum). */
static int draw_list(sl_app *app, const sl_draw_scene_desc *d, sl_gpu_draw_set set, bool cull, draw_item **out) {
    sl_renderer *r = R(app);
    sl_scene *s = &app->scene;
    vec4 planes[6];
    if (cull) {
        mat4 vp;
        glm_mat4_mul((vec4 *)d->proj, (vec4 *)d->view, vp);
        glm_frustum_planes(vp, planes);
        for (int p = 0; p < 4 && cull; p++) /* a degenerate matrix: no culling */
            cull = isfinite(planes[p][0] + planes[p][1] + planes[p][2] + planes[p][3]);
    }
    int cap = 0;
    for (int ni = 0; ni < s->node_count; ni++) cap += s->nodes[ni].mesh_count;
    draw_item *items = malloc((cap + 1) * sizeof *items);
    int n = 0, order = 0;
    static const int wanted[] = {[SL_GPU_DRAW_ALL] = -1, [SL_GPU_DRAW_OPAQUE] = 0, [SL_GPU_DRAW_BEHIND] = 1,
                                 [SL_GPU_DRAW_BLENDED] = 2};
    for (int pass = 0; pass < 3; pass++) { /* draw_class: opaque, then behind, then blended */
        int first = n;
        if (wanted[set] >= 0 && wanted[set] != pass) continue;
        for (int m = 0; m < s->material_count; m++) {
            bool blended = pass > 0; /* sorted back to front, no depth writes */
            if (draw_class(app, m) != pass) continue;
            if (d->shadow_casters_only && !s->materials[m].cast_shadows) continue;
            if (d->only_materials_with) {
                sl_mat_value *v = sl_app_material_value(app, m, d->only_materials_with);
                if (!v || !v->present) continue;
            }
            for (int ni = 0; ni < s->node_count; ni++) {
                const sl_node *node = &s->nodes[ni];
                for (int k = 0; k < node->mesh_count; k++) {
                    int mi = node->meshes[k];
                    if (s->meshes[mi].material != m || !r->meshes[mi].index_count) continue;
                    if (cull && !r->meshes[mi].deform && outside_frustum(&r->meshes[mi], (const float *)node->world, planes))
                        continue;
                    draw_item *it = &items[n++];
                    *it = (draw_item){.m = m, .node = ni, .k = k, .order = order++};
                    if (!blended) continue;
                    vec4 c = {r->meshes[mi].center[0], r->meshes[mi].center[1], r->meshes[mi].center[2], 1}, w, v;
                    glm_mat4_mulv((vec4 *)node->world, c, w);
                    glm_mat4_mulv((vec4 *)d->view, w, v);
                    it->depth = -v[2]; /* the camera looks down -z (conventions.md) */
                    if (!isfinite(it->depth)) it->depth = 0; /* a consistent order for qsort */
                }
            }
        }
        if (pass > 0) qsort(items + first, n - first, sizeof *items, cmp_back_to_front);
    }
    *out = items;
    return n;
}

/* On llvmpipe a draw without a depth test, without blending and with every channel written ("opaque")
 * compiles its fragment shader twice: a second function for the tiles a triangle covers whole (Mesa's
 * lp_state_fs.c, generate_variant). Blending ONE, ZERO writes the source unchanged (bit for bit,
 * NaN and Inf included: checked on Mesa 22.3) and takes the draw off that path, so the program
 * compiles once. For the draws in UV space (texture-space targets, no depth buffer: sss's irradiance
 * and stretch, 0.15 s of the head scene's cold start). Returns whether it enabled blending. */
static bool identity_blend(sl_app *app, const sl_draw_scene_desc *d) {
    if (!d->uv_space || app->backend.is_gpu || glIsEnabled(GL_BLEND)) return false;
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    return true;
}

/* The level of detail of mesh g (data m) drawn by `node` in view d (render/lod.h), 0 when pixels
 * <= 0. The levels are made at the first draw that asks (core.lod_pixels > 0): the index buffer
 * then holds level 0 and the coarser lists after it. */
static int lod_level(gpu_mesh *g, const sl_mesh_data *m, const sl_node *node, const sl_draw_scene_desc *d, int height,
                     float pixels) {
    if (!(pixels > 0) || g->deform) return 0; /* a deformed mesh's pose leaves its bounds */
    if (!g->lod_built) {
        int total = 0;
        uint32_t *levels = sl_lod_build(m, &g->lod, &total);
        if (levels) glNamedBufferData(g->ibo, (size_t)total * 4, levels, GL_STATIC_DRAW);
        free(levels);
        g->lod_built = true;
    }
    if (g->lod.count < 2) return 0;
    vec4 c = {g->center[0], g->center[1], g->center[2], 1}, w, v;
    glm_mat4_mulv((vec4 *)node->world, c, w);
    glm_mat4_mulv((vec4 *)d->view, w, v);
    float scale = 0; /* the longest axis of the node's transform */
    for (int k = 0; k < 3; k++)
        scale = fmaxf(scale, sqrtf(node->world[k * 4] * node->world[k * 4] + node->world[k * 4 + 1] * node->world[k * 4 + 1] +
                                   node->world[k * 4 + 2] * node->world[k * 4 + 2]));
    return sl_lod_pick(&g->lod, d->proj, v, g->radius, scale, height, pixels);
}

void sl_gpu_draw_meshes(sl_app *app, const sl_draw_scene_desc *d, bool depth_only, sl_program *custom, sl_gpu_draw_set set) {
    const char *model_override = d->mode == SL_DRAW_MATERIALS ? d->model_override : NULL;
    const char *fragment = d->mode == SL_DRAW_MATERIALS ? d->fragment : NULL; /* resolved (draw_scene) */
    sl_renderer *r = R(app);
    sl_scene *s = &app->scene;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    bool blend = identity_blend(app, d);
    if (d->cull == 0) glDisable(GL_CULL_FACE);
    else { glEnable(GL_CULL_FACE); glCullFace(d->cull == 2 ? GL_FRONT : GL_BACK); }
    if (custom) {
        if (!sl_program_id(custom)) { /* a deferred program compiles at its first draw */
            if (blend) glDisable(GL_BLEND);
            return;
        }
        glUseProgram(custom->id);
        set_camera_uniforms(app, custom, d->view, d->proj);
        glUniform1i(sl_program_uniform(custom, "sl_uv_space"), d->uv_space);
    }
    draw_item *items = NULL;
    bool cull = may_cull(app, d, custom != NULL);
    int count = draw_list(app, d, set, cull, &items);
    /* levels of detail where the draw may cull (a vertex stage the core knows), on this target */
    const sl_param *lod_param = sl_params_find(&app->params, "core.lod_pixels");
    float lod_pixels = cull && lod_param ? lod_param->value.f[0] : 0;
    int viewport[4] = {0, 0, 0, 0};
    if (lod_pixels > 0) glGetIntegerv(GL_VIEWPORT, viewport);
    int bound_m = -1;
    sl_program *prog = custom;
    const sl_forward_variant *var = NULL;
    for (int i = 0; i < count; i++) {
        int m = items[i].m, ni = items[i].node;
        const sl_node *node = &s->nodes[ni];
        int mi = node->meshes[items[i].k];
        if (m != bound_m) {
            bound_m = m;
            /* glTF doubleSided (the core's material key double_sided): back faces are drawn, and the
             * forward pass shades them with the flipped normal, wherever a pass culls back faces */
            const sl_mat_value *two = d->cull == 1 ? sl_app_material_value(app, m, "double_sided") : NULL;
            if (d->cull == 1) {
                if (two && two->v.b) glDisable(GL_CULL_FACE);
                else glEnable(GL_CULL_FACE);
            }
            if (!custom) {
                var = depth_only       ? &r->materials[m].depth
                      : model_override || fragment ? override_variant_of(app, m, model_override, fragment, false)
                                       : &r->materials[m].forward;
                prog = var ? bind_material(app, m, var, d->view, d->proj) : NULL;
                if (prog) glUniform1i(sl_program_uniform(prog, "sl_uv_space"), d->uv_space);
                /* a blended material's program blends only in the forward-blend pass; a plugin's
                 * draw (the same program when the sources match) sees it opaque */
                if (prog && draw_class(app, m) > 0) blend_uniforms(app, prog, set == SL_GPU_DRAW_BLENDED || set == SL_GPU_DRAW_BEHIND);
            }
        }
        if (!prog) continue;
        mat4 model, inv;
        mat3 nrm;
        memcpy(model, node->world, sizeof model);
        glm_mat4_inv(model, inv);
        glm_mat4_transpose(inv);
        glm_mat4_pick3(inv, nrm);
        /* a mirroring transform (negative determinant) reverses the winding; in UV space
         * (v = 0 at the top) unmirrored UV layouts wind clockwise: make them front faces */
        glFrontFace(d->uv_space || glm_mat4_det(model) < 0 ? GL_CW : GL_CCW);
        glUniformMatrix4fv(sl_program_uniform(prog, "sl_model"), 1, GL_FALSE, (float *)model);
        /* motion vectors: the node's world matrix in the previous frame (animated nodes move) */
        if (r->motion) {
            const float *prev = r->have_prev && r->prev_world && ni < r->prev_world_count ? r->prev_world[ni] : (float *)model;
            glUniformMatrix4fv(sl_program_uniform(prog, "sl_prev_model"), 1, GL_FALSE, prev);
        }
        glUniformMatrix3fv(sl_program_uniform(prog, "sl_normal_matrix"), 1, GL_FALSE, (float *)nrm);
        if (var && var->node_tag_count) { /* VERTEX hooks gated on node tags (when_node_tag) */
            int mask = 0;
            for (int t = 0; t < var->node_tag_count; t++)
                if (sl_scene_node_has_tag(s, ni, var->node_tags[t])) mask |= 1 << t;
            glUniform1i(sl_program_uniform(prog, "sl_vertex_hook_mask"), mask);
        }
        glBindVertexArray(r->meshes[mi].vao);
        if (var && var->program && var->program->tessellated) { /* DISPLACEMENT hooks (ABI 1.7) */
            /* at most SL_PATCHES_PER_DRAW patches per draw: llvmpipe (Mesa 22.3) drops and
             * tears the later patches of a draw that generates too many triangles
             * (measured: 128 patches at level 32 lose the lower half of a cylinder) */
            enum { SL_PATCHES_PER_DRAW = 16 };
            glPatchParameteri(GL_PATCH_VERTICES, 3);
            for (int first = 0; first < r->meshes[mi].index_count; first += 3 * SL_PATCHES_PER_DRAW) {
                int n = r->meshes[mi].index_count - first;
                glDrawElements(GL_PATCHES, n < 3 * SL_PATCHES_PER_DRAW ? n : 3 * SL_PATCHES_PER_DRAW,
                               GL_UNSIGNED_INT, (const void *)(sizeof(uint32_t) * (size_t)first));
            }
        } else {
            gpu_mesh *g = &r->meshes[mi];
            int level = lod_level(g, &s->meshes[mi].data, node, d, viewport[3], lod_pixels);
            int n = level ? g->lod.index_count[level] : g->index_count;
            glDrawElements(GL_TRIANGLES, n, GL_UNSIGNED_INT, (const void *)(sizeof(uint32_t) * (size_t)g->lod.first[level]));
            r->stats.triangles += n / 3;
        }
        r->stats.draw_calls++;
    }
    free(items);
    glBindVertexArray(0);
    glFrontFace(GL_CCW);
    if (blend) glDisable(GL_BLEND);
}

void sl_renderer_draw_scene(sl_app *app, sl_pass_ctx *ctx, const sl_draw_scene_desc *in) {
    sl_draw_scene_desc d = {0};
    memcpy(&d, in, in->struct_size < sizeof d ? in->struct_size : sizeof d);
    if (in->struct_size < offsetof(sl_draw_scene_desc, cull) + sizeof(int)) d.cull = 1;
    if (d.mode == SL_DRAW_PROGRAM && !d.program) {
        SL_ERROR("draw_scene: SL_DRAW_PROGRAM without a program");
        return;
    }
    if (d.mode == SL_DRAW_MATERIALS && !d.model_override && !d.fragment) {
        SL_ERROR("draw_scene: SL_DRAW_MATERIALS without model_override or fragment");
        return;
    }
    /* a plugin's fragment main (ABI 1.7) is a file of the calling pass's plugin */
    char frag[2048];
    if (d.mode == SL_DRAW_MATERIALS && d.fragment) {
        if (!ctx || ctx->pass->owner < 0 || strstr(d.fragment, "..") || d.fragment[0] == '/') {
            SL_ERROR("draw_scene: fragment \"%s\" must be a file in the calling plugin's directory", d.fragment);
            return;
        }
        snprintf(frag, sizeof frag, "%s/%s", app->plugins.items[ctx->pass->owner]->resource_dir, d.fragment);
        d.fragment = frag;
        if (d.fullscreen) {
            draw_materials_fullscreen(app, &d, frag);
            return;
        }
    } else {
        d.fragment = NULL, d.fullscreen = false;
    }
    sl_gpu_draw_meshes(app, &d, d.mode == SL_DRAW_DEPTH_ONLY, d.mode == SL_DRAW_PROGRAM ? d.program : NULL, SL_GPU_DRAW_ALL);
}

bool sl_renderer_materials_use_uniform(sl_app *app, const char *name) {
    sl_renderer *r = R(app);
    if (!r || !r->materials || !name) return false;
    for (int m = 0; m < app->scene.material_count; m++) {
        sl_program *p = r->materials[m].forward.program;
        if (p && sl_program_id(p) && sl_program_uniform(p, name) >= 0) return true;
    }
    return false;
}

void sl_renderer_draw_fullscreen(sl_app *app, sl_pass_ctx *ctx) {
    sl_renderer *r = R(app);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(r->empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    r->stats.draw_calls++;
}

