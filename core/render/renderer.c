/* GPU scene, render graph and timing. See renderer.h. */
#include "render/renderer.h"
#include "state.h"
#include "image/image.h"
#include "log.h"
#include "render/composer.h"
#include "render/forward.h"
#include <shadelab/gl.h>
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

typedef struct gpu_mesh { unsigned vao, vbo[4], ibo; int index_count; } gpu_mesh;
typedef struct gpu_texture { char *key; unsigned id; } gpu_texture;

typedef struct override_variant { char *model; sl_forward_variant v; } override_variant;

typedef struct material_rt {
    sl_forward_variant forward, depth;
    override_variant overrides[8]; /* SL_DRAW_MATERIALS variants, composed on first use */
    int override_count;
    unsigned textures[16];
} material_rt;

typedef struct resource {
    char *name;
    sl_target_desc desc;
    unsigned tex[2];      /* [1] only for ping-ponged "color" */
    int current;          /* which of tex[] holds the latest contents */
    int w, h;
    uint64_t version;     /* bumps each time a pass writes it */
} resource;

typedef struct graph_pass {
    const sl_pass_desc *d;
    int owner;            /* plugin index; -1 = core pass */
    bool core_forward, core_display, core_resolve;
    unsigned fbo;
    uint64_t last_signature; bool has_run;
    double last_ms;       /* time of the last run (for --explain when skipped since) */
    bool broken;          /* disabled at plan time (message given) */
} graph_pass;

struct sl_pass_ctx { graph_pass *pass; int out_slot[8]; int in_slot[16]; };

typedef struct sl_renderer {
    gpu_mesh *meshes;
    gpu_texture *textures; int texture_count;
    material_rt *materials;
    sl_program **cache; int cache_count;          /* composed forward/depth programs */
    sl_program **programs; int program_count;     /* stand-alone programs (plugins, core) */
    int *program_owner;
    sl_program *display_prog, *accum_prog, *resolve_prog;
    int ssaa;
    int anisotropy;                               /* core.anisotropy applied to the material textures */
    unsigned empty_vao, light_buffer;
    sl_light_info *lights; int light_count;
    int type_range[32][2]; const char *types[32]; int ntypes;
    resource *res; int res_count;
    graph_pass *passes; int pass_count;
    bool plan_dirty;
    int width, height;
    uint64_t seen_recompile, seen_materials, seen_lights_version, seen_param_version;
    double seen_light_time;
    uint64_t lights_packed;   /* bumps each time the lights are packed */   /* app->time of the packed lights (animated lights repack) */
    char *seen_debug_view;
    bool finish_timing;
    unsigned queries[64];
    sl_frame frame;
    sl_frame_stats stats;
    unsigned display_fbo;
    /* the pass being executed, for draw_scene */
    sl_pass_ctx *current;
} sl_renderer;

#define R(app) ((sl_renderer *)(app)->renderer)

static double now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

/* ------------------------------------------------------------------ meshes ---------- */

static void upload_mesh(gpu_mesh *g, const sl_mesh_data *m) {
    glCreateVertexArrays(1, &g->vao);
    glCreateBuffers(4, g->vbo);
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
        glVertexArrayVertexBuffer(g->vao, a, g->vbo[a], 0, comps[a] * sizeof(float));
        glVertexArrayAttribFormat(g->vao, a, comps[a], GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(g->vao, a, a);
        glEnableVertexArrayAttrib(g->vao, a);
    }
    static const uint32_t no_indices[1];
    glNamedBufferData(g->ibo, m->index_count ? (size_t)m->index_count * 4 : 4, m->index_count ? m->indices : no_indices,
                      GL_STATIC_DRAW);
    glVertexArrayElementBuffer(g->vao, g->ibo);
    g->index_count = m->index_count;
}

/* ------------------------------------------------------------------ textures -------- */

bool sl_texture_is_procedural(const char *spec) {
    static const char *prefixes[] = {"checker:", "grid:", "constant:", "gradient", "uv"};
    for (size_t i = 0; i < sizeof prefixes / sizeof *prefixes; i++) {
        size_t l = strlen(prefixes[i]);
        if (!strncmp(spec, prefixes[i], l) && (prefixes[i][l - 1] == ':' || spec[l] == 0 || spec[l] == ':')) return true;
    }
    return false;
}

/* Loads a material texture: colour textures decode sRGB in the sampler (8-bit) or on the CPU
 * (16-bit); data textures stay linear. */
/* core.anisotropy onto every material texture (a parameter change reaches the loaded ones too). */
static void apply_anisotropy(sl_app *app) {
    sl_renderer *r = R(app);
    const sl_param *p = sl_params_find(&app->params, "core.anisotropy");
    int a = p ? p->value.i : 8;
    a = a < 1 ? 1 : a > 16 ? 16 : a;
    if (a == r->anisotropy) return;
    r->anisotropy = a;
    for (int i = 0; i < r->texture_count; i++) glTextureParameterf(r->textures[i].id, GL_TEXTURE_MAX_ANISOTROPY, (float)a);
}

static unsigned load_texture(sl_app *app, const char *spec, bool linear_data, bool clamp) {
    sl_renderer *r = R(app);
    char key[2100];
    snprintf(key, sizeof key, "%s|%d|%d", spec, linear_data, clamp);
    for (int i = 0; i < r->texture_count; i++)
        if (!strcmp(r->textures[i].key, key)) return r->textures[i].id;
    sl_image img = {0};
    char err[1024] = "";
    bool ok;
    bool srgb_storage = false;
    if (sl_texture_is_procedural(spec)) {
        ok = sl_image_procedural(&img, spec, 256, err, sizeof err);
        /* procedural colours are linear already */
    } else {
        char *path = sl_scene_resolve_path(&app->scene, app->opt.data_dir, spec, err, sizeof err);
        ok = path && sl_image_load(&img, path, err, sizeof err);
        free(path);
        if (ok && !linear_data && img.source_srgb) {
            if (img.source_bits == 8) srgb_storage = true;
            else sl_image_srgb_to_linear(&img);
        }
        /* policy for texture files: finite, >= 0 and at most SL_MAX_RADIANCE, with one warning */
        long nonfinite = 0, negative = 0, over = 0;
        if (ok && img.source_float && sl_image_sanitize(&img, (float)SL_MAX_RADIANCE, &nonfinite, &negative, &over))
            SL_WARN("texture %s: replaced %ld NaN/Inf, %ld negative and %ld over-%g samples (NaN, -Inf and "
                    "negatives by 0; +Inf and large values by %g)", spec, nonfinite, negative, over, SL_MAX_RADIANCE,
                    SL_MAX_RADIANCE);
    }
    unsigned tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    if (!ok) {
        SL_ERROR("texture %s: %s (using a magenta placeholder)", spec, err);
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
        glTextureSubImage2D(tex, 0, 0, 0, img.width, img.height, GL_RGBA, GL_FLOAT, img.pixels);
        glGenerateTextureMipmap(tex);
        glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_S, clamp ? GL_CLAMP_TO_EDGE : GL_REPEAT);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_T, clamp ? GL_CLAMP_TO_EDGE : GL_REPEAT);
        if (!r->anisotropy) apply_anisotropy(app);
        glTextureParameterf(tex, GL_TEXTURE_MAX_ANISOTROPY, (float)r->anisotropy);
    }
    sl_image_free(&img);
    r->textures = realloc(r->textures, (r->texture_count + 1) * sizeof *r->textures);
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

static bool lights_animated(sl_app *app) {
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

/* The light buffer and the lights plugins see (sl_host.lights), at app->time. */
static void pack_lights(sl_app *app) {
    sl_renderer *r = R(app);
    r->lights_packed++;
    sl_scene *s = &app->scene;
    free(r->lights);
    r->lights = calloc(s->light_count + 1, sizeof *r->lights);
    r->light_count = s->light_count;
    r->ntypes = sl_forward_light_types(app, r->types, 32);
    typedef struct { float position[4], direction[4], color[4], params[8]; } gpu_light;
    gpu_light *buf = calloc(s->light_count + 1, sizeof *buf);
    int k = 0;
    for (int t = 0; t < r->ntypes; t++) {
        r->type_range[t][0] = k;
        for (int i = 0; i < s->light_count; i++) {
            const sl_light *L = &s->lights[i];
            if (!L->enabled || strcmp(L->type, r->types[t])) continue;
            sl_light_info *info = &r->lights[i];
            info->index = k;
            gpu_light *g = &buf[k++];
            sl_light_at_time(L, app->time, g->position, g->direction);
            light_radiant(L, g->color);
            memcpy(g->params, app->light_params[i], sizeof g->params);
        }
        r->type_range[t][1] = k;
    }
    for (int i = 0; i < s->light_count; i++) {
        const sl_light *L = &s->lights[i];
        sl_light_info *info = &r->lights[i];
        info->struct_size = sizeof *info;
        info->name = L->name;
        info->type = L->type;
        sl_light_at_time(L, app->time, info->position, info->direction); /* where the animation puts it */
        light_radiant(L, info->color);
        memcpy(info->params, app->light_params[i], sizeof info->params);
        info->enabled = L->enabled;
        info->cast_shadows = L->cast_shadows;
        if (!L->enabled) info->index = -1;
    }
    if (!r->light_buffer) glCreateBuffers(1, &r->light_buffer);
    glNamedBufferData(r->light_buffer, (k ? k : 1) * sizeof(gpu_light), buf, GL_DYNAMIC_DRAW);
    free(buf);
}

const sl_light_info *sl_renderer_lights(sl_app *app, int *count) {
    sl_renderer *r = R(app);
    *count = r ? r->light_count : 0;
    return r ? r->lights : NULL;
}

/* ------------------------------------------------------------------ materials ------- */

static void compose_all(sl_app *app) {
    sl_renderer *r = R(app);
    char err[16384];
    for (int m = 0; m < app->scene.material_count; m++) {
        material_rt *mr = &r->materials[m];
        sl_forward_compose(app, m, SL_VARIANT_FORWARD, NULL, &mr->forward, &r->cache, &r->cache_count, err, sizeof err);
        sl_forward_compose(app, m, SL_VARIANT_DEPTH, NULL, &mr->depth, &r->cache, &r->cache_count, err, sizeof err);
        for (int k = 0; k < mr->override_count; k++)
            sl_forward_compose(app, m, SL_VARIANT_FORWARD, mr->overrides[k].model, &mr->overrides[k].v, &r->cache,
                               &r->cache_count, err, sizeof err);
        for (int t = 0; t < mr->forward.texture_count; t++) {
            const sl_param *q = &app->params.items[mr->forward.texture_params[t]];
            sl_mat_value *v = sl_app_material_value(app, m, q->full_id);
            mr->textures[t] = v && v->str ? load_texture(app, v->str, q->desc.flags & SL_PARAM_LINEAR_DATA,
                                                         q->desc.flags & SL_PARAM_CLAMP_TO_EDGE)
                                          : 0;
        }
    }
}

static void set_value_uniform(unsigned prog, const char *name, const sl_param *q, const sl_value *v) {
    int loc = glGetUniformLocation(prog, name);
    if (loc < 0) return;
    switch (q->desc.type) {
    case SL_PARAM_BOOL: glProgramUniform1i(prog, loc, v->b); break;
    case SL_PARAM_INT: case SL_PARAM_ENUM: glProgramUniform1i(prog, loc, v->i); break;
    case SL_PARAM_FLOAT: glProgramUniform1f(prog, loc, v->f[0]); break;
    case SL_PARAM_COLOR: case SL_PARAM_VEC3: glProgramUniform3f(prog, loc, v->f[0], v->f[1], v->f[2]); break;
    case SL_PARAM_TEXTURE: break;
    }
}

static void set_camera_uniforms(sl_app *app, unsigned prog, const float *view, const float *proj) {
    sl_renderer *r = R(app);
    mat4 vp;
    glm_mat4_mul((vec4 *)proj, (vec4 *)view, vp);
    glUniformMatrix4fv(glGetUniformLocation(prog, "sl_view"), 1, GL_FALSE, view);
    glUniformMatrix4fv(glGetUniformLocation(prog, "sl_proj"), 1, GL_FALSE, proj);
    glUniformMatrix4fv(glGetUniformLocation(prog, "sl_view_proj"), 1, GL_FALSE, (float *)vp);
    glUniform3fv(glGetUniformLocation(prog, "sl_camera_pos"), 1, r->frame.camera_pos);
    glUniform1f(glGetUniformLocation(prog, "sl_time"), (float)r->frame.time);
    glUniform1i(glGetUniformLocation(prog, "sl_frame_index"), r->frame.accumulate_index);
    glUniform2f(glGetUniformLocation(prog, "sl_viewport_size"), (float)r->frame.width, (float)r->frame.height);
}

/* Binds a material's program and every uniform it reads except the per-object ones. */
static unsigned bind_material(sl_app *app, int m, const sl_forward_variant *var, const float *view, const float *proj) {
    sl_renderer *r = R(app);
    unsigned prog = var->program ? var->program->id : 0;
    if (!prog) return 0;
    glUseProgram(prog);
    set_camera_uniforms(app, prog, view, proj);
    const sl_environment *env = &app->scene.environment;
    glUniform3f(glGetUniformLocation(prog, "sl_ambient_irradiance"), (float)M_PI * env->color[0] * env->intensity,
                (float)M_PI * env->color[1] * env->intensity, (float)M_PI * env->color[2] * env->intensity);
    for (int t = 0; t < r->ntypes; t++) {
        char name[160], id[128];
        sl_glsl_ident(r->types[t], id, sizeof id, false);
        snprintf(name, sizeof name, "sl_lights_%s", id);
        glUniform2i(glGetUniformLocation(prog, name), r->type_range[t][0], r->type_range[t][1]);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, r->light_buffer);
    sl_mat_state *ms = &app->materials[m];
    for (int i = 0; i < ms->count; i++) {
        const sl_param *q = &app->params.items[ms->values[i].param];
        if (q->desc.type == SL_PARAM_TEXTURE || (q->desc.flags & SL_PARAM_NEEDS_RECOMPILE)) continue;
        char name[200];
        snprintf(name, sizeof name, "sl_mat_%s", q->full_id);
        set_value_uniform(prog, name, q, &ms->values[i].v);
    }
    for (int t = 0; t < var->texture_count; t++) glBindTextureUnit(t, r->materials[m].textures[t]);
    for (int i = 0; i < app->params.count; i++) {
        const sl_param *q = &app->params.items[i];
        if (q->desc.scope != SL_SCOPE_GLOBAL || (q->desc.flags & SL_PARAM_NEEDS_RECOMPILE)) continue;
        int owner = sl_plugins_find(&app->plugins, q->owner);
        if (owner < 0 || !(var->owners & (1ull << (owner & 63)))) continue;
        char name[300], oid[128];
        sl_glsl_ident(q->owner, oid, sizeof oid, false);
        snprintf(name, sizeof name, "%s_%s", oid, q->desc.id);
        set_value_uniform(prog, name, q, &q->value);
    }
    for (int i = 0; i < app->plugins.count; i++) {
        sl_plugin_rec *pr = app->plugins.items[i];
        if ((var->owners & (1ull << (i & 63))) && pr->bind && sl_plugin_enabled(&app->plugins, i)) pr->bind(pr->bind_user, prog, m, &r->frame);
    }
    return prog;
}

/* ------------------------------------------------------------------ drawing --------- */

/* The material's program with its shading model replaced (SL_DRAW_MATERIALS). */
static const sl_forward_variant *override_variant_of(sl_app *app, int m, const char *model) {
    material_rt *mr = &R(app)->materials[m];
    for (int k = 0; k < mr->override_count; k++)
        if (!strcmp(mr->overrides[k].model, model)) return &mr->overrides[k].v;
    if (mr->override_count == 8) return NULL;
    override_variant *o = &mr->overrides[mr->override_count++];
    memset(o, 0, sizeof *o);
    o->model = strdup(model);
    char err[16384];
    sl_forward_compose(app, m, SL_VARIANT_FORWARD, model, &o->v, &R(app)->cache, &R(app)->cache_count, err, sizeof err);
    return &o->v;
}

static void draw_meshes(sl_app *app, const sl_draw_scene_desc *d, bool depth_only, sl_program *custom) {
    const char *model_override = d->mode == SL_DRAW_MATERIALS ? d->model_override : NULL;
    sl_renderer *r = R(app);
    sl_scene *s = &app->scene;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    if (d->cull == 0) glDisable(GL_CULL_FACE);
    else { glEnable(GL_CULL_FACE); glCullFace(d->cull == 2 ? GL_FRONT : GL_BACK); }
    if (custom) {
        if (!custom->id) return;
        glUseProgram(custom->id);
        set_camera_uniforms(app, custom->id, d->view, d->proj);
        glUniform1i(glGetUniformLocation(custom->id, "sl_uv_space"), d->uv_space);
    }
    for (int m = 0; m < s->material_count; m++) {
        if (d->shadow_casters_only && !s->materials[m].cast_shadows) continue;
        if (d->only_materials_with) {
            sl_mat_value *v = sl_app_material_value(app, m, d->only_materials_with);
            if (!v || !v->present) continue;
        }
        unsigned prog = custom ? custom->id : 0;
        bool bound = custom != NULL;
        for (int ni = 0; ni < s->node_count; ni++) {
            const sl_node *node = &s->nodes[ni];
            for (int k = 0; k < node->mesh_count; k++) {
                int mi = node->meshes[k];
                if (s->meshes[mi].material != m || !r->meshes[mi].index_count) continue;
                if (!bound) {
                    const sl_forward_variant *var = depth_only       ? &r->materials[m].depth
                                                    : model_override ? override_variant_of(app, m, model_override)
                                                                     : &r->materials[m].forward;
                    prog = var ? bind_material(app, m, var, d->view, d->proj) : 0;
                    glUniform1i(glGetUniformLocation(prog, "sl_uv_space"), d->uv_space);
                    bound = true;
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
                glUniformMatrix4fv(glGetUniformLocation(prog, "sl_model"), 1, GL_FALSE, (float *)model);
                glUniformMatrix3fv(glGetUniformLocation(prog, "sl_normal_matrix"), 1, GL_FALSE, (float *)nrm);
                glBindVertexArray(r->meshes[mi].vao);
                glDrawElements(GL_TRIANGLES, r->meshes[mi].index_count, GL_UNSIGNED_INT, 0);
                r->stats.draw_calls++;
            }
        }
    }
    glBindVertexArray(0);
    glFrontFace(GL_CCW);
}

void sl_renderer_draw_scene(sl_app *app, sl_pass_ctx *ctx, const sl_draw_scene_desc *in) {
    sl_draw_scene_desc d = {0};
    memcpy(&d, in, in->struct_size < sizeof d ? in->struct_size : sizeof d);
    if (in->struct_size < offsetof(sl_draw_scene_desc, cull) + sizeof(int)) d.cull = 1;
    if (d.mode == SL_DRAW_PROGRAM && !d.program) {
        SL_ERROR("draw_scene: SL_DRAW_PROGRAM without a program");
        return;
    }
    if (d.mode == SL_DRAW_MATERIALS && !d.model_override) {
        SL_ERROR("draw_scene: SL_DRAW_MATERIALS without model_override");
        return;
    }
    draw_meshes(app, &d, d.mode == SL_DRAW_DEPTH_ONLY, d.mode == SL_DRAW_PROGRAM ? d.program : NULL);
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

/* ------------------------------------------------------------------ programs -------- */

sl_program *sl_renderer_load_program(sl_app *app, int owner, const sl_program_desc *in) {
    sl_renderer *r = R(app);
    sl_program_desc d = {0};
    memcpy(&d, in, in->struct_size < sizeof d ? in->struct_size : sizeof d);
    if (!d.vertex || !d.fragment) {
        SL_ERROR("load_program: vertex and fragment files are required");
        return NULL;
    }
    char err[16384] = "";
    const char *dir = owner >= 0 ? app->plugins.items[owner]->resource_dir : sl_shader_dir();
    sl_program *p = sl_program_from_files(dir, d.vertex, d.fragment, d.defines, err, sizeof err);
    if (!p->id) SL_ERROR("%s", err);
    p->owner = owner;
    r->programs = realloc(r->programs, (r->program_count + 1) * sizeof *r->programs);
    r->programs[r->program_count++] = p;
    return p;
}

unsigned sl_renderer_program_id(sl_program *p) { return p ? p->id : 0; }

int sl_renderer_reload_shaders(sl_app *app) {
    sl_renderer *r = R(app);
    int failures = 0;
    char err[16384];
    for (int i = 0; i < r->program_count; i++) {
        sl_program *p = r->programs[i];
        const char *dir = p->owner >= 0 ? app->plugins.items[p->owner]->resource_dir : sl_shader_dir();
        if (!sl_program_rebuild_files(p, dir, err, sizeof err)) { SL_ERROR("%s", err); failures++; }
    }
    /* composed programs: recompose everything; failures keep the previous variant program */
    int before = sl_log_count(SL_LOG_ERROR);
    for (int i = 0; i < r->cache_count; i++) r->cache[i]->stale = true; /* compiled from old files */
    compose_all(app);
    failures += sl_log_count(SL_LOG_ERROR) - before;
    /* Stamp the files' current mtimes on every source, including programs whose rebuild failed
     * and cache entries no longer in use: otherwise their stale mtimes make the poll reload (and
     * re-print the error) every time, forever. A later edit changes the mtime again. */
    for (int i = 0; i < r->program_count + r->cache_count; i++) {
        sl_program *p = i < r->program_count ? r->programs[i] : r->cache[i - r->program_count];
        sl_source *src[2] = {&p->vs, &p->fs};
        for (int k = 0; k < 2; k++)
            for (int f = 1; f < src[k]->file_count; f++) {
                struct stat st;
                if (stat(src[k]->files[f], &st) == 0) src[k]->mtimes[f] = st.st_mtime;
            }
    }
    return failures;
}

static bool any_source_changed(sl_renderer *r) {
    for (int i = 0; i < r->program_count; i++)
        if (sl_source_changed(&r->programs[i]->vs) || sl_source_changed(&r->programs[i]->fs)) return true;
    for (int i = 0; i < r->cache_count; i++)
        if (sl_source_changed(&r->cache[i]->vs) || sl_source_changed(&r->cache[i]->fs)) return true;
    return false;
}

/* ------------------------------------------------------------------ graph ----------- */

static const sl_target_desc core_color = {.name = "color", .format = SL_FORMAT_RGBA16F};
static const sl_target_desc core_color32 = {.name = "color", .format = SL_FORMAT_RGBA32F};
static const sl_target_desc core_depth = {.name = "depth", .format = SL_FORMAT_DEPTH32F};
static const sl_target_desc core_display = {.name = "display", .format = SL_FORMAT_RGBA8};
static sl_target_desc forward_outputs[2];
static const char *resolve_inputs[] = {"forward.ssaa", NULL};
static sl_target_desc resolve_outputs[1];
static sl_pass_desc resolve_pass = {.struct_size = sizeof(sl_pass_desc), .name = "ssaa-resolve", .stage = SL_STAGE_OPAQUE,
                                    .inputs = resolve_inputs, .outputs = resolve_outputs, .output_count = 1};
static const char *display_inputs[] = {"color", NULL};
static sl_pass_desc forward_pass = {.struct_size = sizeof(sl_pass_desc), .name = "forward", .stage = SL_STAGE_OPAQUE,
                                    .outputs = forward_outputs, .output_count = 2};
static sl_pass_desc display_pass = {.struct_size = sizeof(sl_pass_desc), .name = "display", .stage = SL_STAGE_DISPLAY,
                                    .inputs = display_inputs, .outputs = &core_display, .output_count = 1};

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

static resource *find_res(sl_renderer *r, const char *name) {
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

static void free_resources(sl_renderer *r) {
    for (int i = 0; i < r->res_count; i++) {
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

static void add_resource(sl_renderer *r, const sl_target_desc *d, bool pingpong) {
    resource *e = find_res(r, d->name);
    if (e) {
        if (pingpong && !e->tex[1]) e->tex[1] = make_target(&e->desc, e->w, e->h);
        return;
    }
    r->res = realloc(r->res, (r->res_count + 1) * sizeof *r->res);
    e = &r->res[r->res_count++];
    memset(e, 0, sizeof *e);
    e->name = strdup(d->name);
    e->desc = *d;
    e->desc.name = e->name;
    float scale = d->scale > 0 ? d->scale : 1;
    e->w = d->width > 0 ? d->width : (int)(r->width * scale + 0.5f);
    e->h = d->height > 0 ? d->height : (int)(r->height * scale + 0.5f);
    if (e->w < 1) e->w = 1;
    if (e->h < 1) e->h = 1;
    e->tex[0] = make_target(d, e->w, e->h);
    if (pingpong) e->tex[1] = make_target(d, e->w, e->h);
}

static bool lists_name(const char *const *list, const char *name) {
    for (; list && *list; list++)
        if (!strcmp(*list, name)) return true;
    return false;
}

static int cmp_stage(const void *a, const void *b) {
    const graph_pass *x = a, *y = b;
    if (x->d->stage != y->d->stage) return x->d->stage < y->d->stage ? -1 : 1;
    return 0;
}

/* Orders passes, checks inputs, allocates targets. */
static void plan(sl_app *app) {
    sl_renderer *r = R(app);
    free_resources(r);
    /* core.ssaa > 1: the forward pass renders "forward.ssaa" at k× the viewport and the resolve
     * pass box-filters it into the viewport-sized "color" everything downstream sees. */
    sl_param *ssaa = sl_params_find(&app->params, "core.ssaa");
    r->ssaa = ssaa && ssaa->value.i > 1 ? ssaa->value.i : 1;
    forward_outputs[0] = app->opt.float32 ? core_color32 : core_color;
    forward_outputs[1] = core_depth;
    resolve_outputs[0] = forward_outputs[0];
    if (r->ssaa > 1) {
        forward_outputs[0].name = "forward.ssaa";
        forward_outputs[0].scale = forward_outputs[1].scale = (float)r->ssaa;
    }
    int total = app->plugins.pass_count + 3;
    r->passes = calloc(total, sizeof *r->passes);
    r->passes[r->pass_count++] = (graph_pass){.d = &forward_pass, .owner = -1, .core_forward = true};
    if (r->ssaa > 1) r->passes[r->pass_count++] = (graph_pass){.d = &resolve_pass, .owner = -1, .core_resolve = true};
    for (int i = 0; i < app->plugins.pass_count; i++) {
        sl_pass_reg *reg = &app->plugins.passes[i];
        if (!sl_plugin_enabled(&app->plugins, reg->owner)) continue; /* disabled plugins cost nothing */
        r->passes[r->pass_count++] = (graph_pass){.d = &reg->d, .owner = reg->owner};
    }
    r->passes[r->pass_count++] = (graph_pass){.d = &display_pass, .owner = -1, .core_display = true};
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
            add_resource(r, o, lists_name(g->d->inputs, o->name));
        }
    }
    r->plan_dirty = false;
}

/* For a resource a pass both reads and writes ("color" in a post pass), pass_texture gives the
 * input (current contents) and bind_outputs attaches the other half of the ping-pong pair. */
unsigned sl_renderer_pass_texture(sl_app *app, sl_pass_ctx *ctx, const char *name) {
    sl_renderer *r = R(app);
    resource *e = find_res(r, name);
    if (!e || !ctx) return 0;
    return e->tex[e->current];
}

static unsigned output_texture(sl_pass_ctx *ctx, resource *e) {
    if (e->tex[1] && lists_name(ctx->pass->d->inputs, e->name)) return e->tex[1 - e->current];
    return e->tex[e->current];
}

sl_status sl_renderer_bind_outputs(sl_app *app, sl_pass_ctx *ctx, int layer) {
    sl_renderer *r = R(app);
    graph_pass *g = ctx->pass;
    if (!g->fbo) glCreateFramebuffers(1, &g->fbo);
    GLenum bufs[8];
    int nc = 0, w = 0, h = 0;
    for (int k = 0; k < g->d->output_count && k < 8; k++) {
        const sl_target_desc *o = &g->d->outputs[k];
        resource *e = find_res(r, o->name);
        unsigned tex = output_texture(ctx, e);
        bool depth = o->format == SL_FORMAT_DEPTH32F;
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
    return SL_OK;
}

static void run_forward(sl_app *app, sl_pass_ctx *ctx) {
    sl_renderer *r = R(app);
    sl_renderer_bind_outputs(app, ctx, 0);
    const sl_environment *env = &app->scene.environment;
    float bg[4] = {env->color[0] * env->intensity, env->color[1] * env->intensity, env->color[2] * env->intensity, 1};
    glDepthMask(GL_TRUE);
    glClearNamedFramebufferfv(ctx->pass->fbo, GL_COLOR, 0, bg);
    glClearNamedFramebufferfi(ctx->pass->fbo, GL_DEPTH_STENCIL, 0, 1.0f, 0);
    sl_draw_scene_desc d = {.struct_size = sizeof d, .cull = 1};
    memcpy(d.view, r->frame.view, sizeof d.view);
    memcpy(d.proj, r->frame.proj, sizeof d.proj);
    draw_meshes(app, &d, false, NULL);
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
        resource *e = find_res(r, g->d->outputs[k].name);
        if (!e) continue;
        if (e->tex[1] && lists_name(g->d->inputs, e->name)) e->current = 1 - e->current;
        e->version++;
    }
}

static uint64_t input_versions(sl_renderer *r, graph_pass *g) {
    uint64_t h = 0;
    for (const char *const *in = g->d->inputs; in && *in; in++) {
        resource *e = find_res(r, *in);
        if (e) h = sl_hash64(&e->version, sizeof e->version, h);
    }
    return h;
}

/* Runs passes with index in [begin, end), timing each. */
static void run_range(sl_app *app, int begin, int end) {
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
        if (r->finish_timing) { glFinish(); t0 = now_ms(); }
        else glBeginQuery(GL_TIME_ELAPSED, r->queries[i & 63]);
        run_pass(app, g, i);
        double ms;
        if (r->finish_timing) { glFinish(); ms = now_ms() - t0; }
        else {
            glEndQuery(GL_TIME_ELAPSED);
            GLuint64 ns = 0;
            glGetQueryObjectui64v(r->queries[i & 63], GL_QUERY_RESULT, &ns);
            ms = ns * 1e-6;
        }
        g->has_run = true;
        g->last_ms = ms;
        if (st) { st->ms += ms; st->ran = true; }
    }
}

/* ------------------------------------------------------------------ frame ----------- */

static void refresh(sl_app *app) {
    sl_renderer *r = R(app);
    bool recompose = sl_renderer_compose_pending(app); /* before the lights' version is marked seen */
    bool lights_changed = r->seen_lights_version != app->lights_version;
    if (lights_changed || (lights_animated(app) && r->seen_light_time != app->time)) pack_lights(app);
    r->seen_light_time = app->time;
    if (recompose) {
        compose_all(app);
        free(r->seen_debug_view);
        r->seen_debug_view = app->debug_view ? strdup(app->debug_view) : NULL;
        r->seen_recompile = app->params.recompile_version;
        r->seen_materials = app->materials_version;
    }
    r->seen_lights_version = app->lights_version;
    if (r->seen_param_version != app->params.version) {
        /* enabling/disabling a plugin changes the pass list */
        r->plan_dirty = true;
        r->seen_param_version = app->params.version;
        apply_anisotropy(app);
    }
    if (r->plan_dirty) plan(app);
}

static void fill_frame(sl_app *app, int acc_index, int acc_count) {
    sl_renderer *r = R(app);
    sl_frame *f = &r->frame;
    f->struct_size = sizeof *f;
    f->index = app->frame_index;
    f->time = app->time;
    f->width = r->width;
    f->height = r->height;
    app->camera.aspect = (float)r->width / (float)(r->height ? r->height : 1);
    sl_camera_matrices(&app->camera, f->view, f->proj);
    glm_mat4_mul((vec4 *)f->proj, (vec4 *)f->view, (vec4 *)f->view_proj);
    sl_camera_position(&app->camera, f->camera_pos);
    memcpy(f->scene_min, app->scene.bounds_min, 12);
    memcpy(f->scene_max, app->scene.bounds_max, 12);
    f->camera_version = app->camera.version;
    /* geometry changes every frame when a vertex hook (displacement, animation over sl_time)
     * is active; otherwise only when the scene is reloaded */
    bool animated = false;
    for (int i = 0; i < app->plugins.chunk_count && !animated; i++)
        animated = app->plugins.chunks[i].d.hook == SL_HOOK_VERTEX && sl_plugin_enabled(&app->plugins, app->plugins.chunks[i].owner);
    f->geometry_version = animated ? app->frame_index + 1 : 0;
    f->lights_version = r->lights_packed; /* changes with every edit and every animated frame */
    f->params_version = app->params.version + app->materials_version;
    f->accumulate_index = acc_index;
    f->accumulate_count = acc_count;
}

bool sl_renderer_frame(sl_app *app, int unused_index, int unused_count) {
    sl_renderer *r = R(app);
    if (!r) return false;
    refresh(app);
    double t0 = now_ms();
    r->stats.pass_count = 0;
    r->stats.draw_calls = 0;
    r->stats.timing_mode = r->finish_timing ? "glfinish" : "timer-query";
    fill_frame(app, 0, 1);
    for (int i = 1; i < app->plugins.count; i++) {
        sl_plugin_rec *pr = app->plugins.items[i];
        if (pr->active && pr->desc.begin_frame && sl_plugin_enabled(&app->plugins, i)) pr->desc.begin_frame(pr->user, &r->frame);
    }
    int post_begin = r->pass_count;
    for (int i = 0; i < r->pass_count; i++)
        if (r->passes[i].d->stage >= SL_STAGE_POST) { post_begin = i; break; }
    int count = app->opt.accumulate > 1 ? app->opt.accumulate : 1;
    if (count == 1) {
        run_range(app, 0, r->pass_count);
    } else {
        /* average the linear HDR colour of `count` sub-frames before any post pass */
        resource *color = find_res(r, "color");
        static const sl_target_desc mean_desc = {.name = "accumulate.mean", .format = SL_FORMAT_RGBA32F};
        add_resource(r, &mean_desc, true);
        resource *mean = find_res(r, "accumulate.mean");
        color = find_res(r, "color");
        unsigned fbo;
        glCreateFramebuffers(1, &fbo);
        for (int k = 0; k < count; k++) {
            fill_frame(app, k, count);
            for (int i = 0; i < post_begin; i++) r->passes[i].has_run = false; /* sub-frames differ */
            run_range(app, 0, post_begin);
            glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, mean->tex[1 - mean->current], 0);
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glViewport(0, 0, mean->w, mean->h);
            glUseProgram(r->accum_prog->id);
            glBindTextureUnit(0, color->tex[color->current]);
            glBindTextureUnit(1, mean->tex[mean->current]);
            glUniform1i(glGetUniformLocation(r->accum_prog->id, "sl_color"), 0);
            glUniform1i(glGetUniformLocation(r->accum_prog->id, "sl_previous_mean"), 1);
            glUniform1f(glGetUniformLocation(r->accum_prog->id, "sl_weight"), 1.0f / (k + 1));
            sl_renderer_draw_fullscreen(app, NULL);
            mean->current = 1 - mean->current;
        }
        /* the mean becomes "color" for the post passes */
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color->tex[color->current], 0);
        unsigned src;
        glCreateFramebuffers(1, &src);
        glNamedFramebufferTexture(src, GL_COLOR_ATTACHMENT0, mean->tex[mean->current], 0);
        glBlitNamedFramebuffer(src, fbo, 0, 0, mean->w, mean->h, 0, 0, color->w, color->h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glDeleteFramebuffers(1, &src);
        glDeleteFramebuffers(1, &fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        color->version++;
        fill_frame(app, 0, 1);
        run_range(app, post_begin, r->pass_count);
    }
    /* programs in use, for the structural zero-cost checks */
    r->stats.program_count = 0;
    for (int m = 0; m < app->scene.material_count && r->stats.program_count < 255; m++) {
        sl_program *p = r->materials[m].forward.program;
        if (p) r->stats.program_hashes[r->stats.program_count++] = p->hash;
    }
    r->stats.frame_ms = now_ms() - t0;
    app->frame_index++;
    sl_renderer_present(app);
    return true;
}

void sl_renderer_present(sl_app *app) {
    sl_renderer *r = R(app);
    resource *disp = r ? find_res(r, "display") : NULL;
    if (!app->backend.has_window || !disp) return;
    unsigned src;
    glCreateFramebuffers(1, &src);
    glNamedFramebufferTexture(src, GL_COLOR_ATTACHMENT0, disp->tex[disp->current], 0);
    glBlitNamedFramebuffer(src, 0, 0, 0, disp->w, disp->h, 0, 0, r->width, r->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glDeleteFramebuffers(1, &src);
}

bool sl_renderer_compose_pending(sl_app *app) {
    sl_renderer *r = R(app);
    if (!r) return false;
    bool view_changed = (r->seen_debug_view == NULL) != (app->debug_view == NULL) ||
                        (app->debug_view && strcmp(app->debug_view, r->seen_debug_view));
    return view_changed || r->seen_lights_version != app->lights_version ||
           r->seen_recompile != app->params.recompile_version || r->seen_materials != app->materials_version;
}

const sl_frame_stats *sl_renderer_stats(sl_app *app) { return R(app) ? &R(app)->stats : NULL; }

bool sl_renderer_read(sl_app *app, const char *name, float *rgba) {
    sl_renderer *r = R(app);
    resource *e = r ? find_res(r, name) : NULL;
    if (!e) return false;
    size_t row = (size_t)e->w * 4;
    float *tmp = malloc(row * e->h * sizeof(float));
    glGetTextureImage(e->tex[e->current], 0, GL_RGBA, GL_FLOAT, (int)(row * e->h * sizeof(float)), tmp);
    for (int y = 0; y < e->h; y++) memcpy(rgba + row * y, tmp + row * (e->h - 1 - y), row * sizeof(float));
    free(tmp);
    return true;
}

void sl_renderer_invalidate(sl_app *app) {
    if (R(app)) R(app)->plan_dirty = true;
}

void sl_renderer_resize(sl_app *app, int w, int h) {
    sl_renderer *r = R(app);
    if (!r || (w == r->width && h == r->height) || w < 1 || h < 1) return;
    r->width = w;
    r->height = h;
    r->plan_dirty = true;
    for (int i = 0; i < app->plugins.count; i++) {
        sl_plugin_rec *pr = app->plugins.items[i];
        if (pr->active && pr->desc.resize) pr->desc.resize(pr->user, w, h);
    }
}

void sl_renderer_explain(sl_app *app, FILE *f) {
    sl_renderer *r = R(app);
    fprintf(f, "passes (in order; ms from the last frame, %s timing):\n", r->stats.timing_mode);
    for (int i = 0; i < r->pass_count; i++) {
        graph_pass *g = &r->passes[i];
        const sl_pass_stat *st = NULL;
        for (int k = 0; k < r->stats.pass_count; k++)
            if (!strcmp(r->stats.passes[k].name, g->d->name)) st = &r->stats.passes[k];
        bool ran = st && st->ran;
        fprintf(f, "  %-24s %-18s %s %8.3f ms%s\n", g->d->name, g->owner >= 0 ? app->plugins.items[g->owner]->id : "core",
                g->broken ? "BROKEN " : ran ? "ran    " : "skipped", ran ? st->ms : g->last_ms,
                ran || g->broken ? "" : g->has_run ? " (when it last ran; unchanged since)" : " (inactive: never ran)");
    }
    fprintf(f, "materials (program hash: chunks):\n");
    for (int m = 0; m < app->scene.material_count; m++) {
        material_rt *mr = &r->materials[m];
        fprintf(f, "  %-20s %016llx  %s\n", app->scene.materials[m].name,
                mr->forward.program ? (unsigned long long)mr->forward.program->hash : 0ull, mr->forward.chunks ? mr->forward.chunks : "");
    }
    int distinct = 0;
    for (int i = 0; i < r->cache_count; i++) distinct += r->cache[i]->id != 0;
    fprintf(f, "composed programs compiled: %d; draw calls last frame: %d; frame %.3f ms\n", distinct, r->stats.draw_calls,
            r->stats.frame_ms);
    fprintf(f, "plugins:\n");
    for (int i = 0; i < app->plugins.count; i++)
        fprintf(f, "  %-20s %s\n", app->plugins.items[i]->id,
                !app->plugins.items[i]->ok ? "disabled (error)" : sl_plugin_enabled(&app->plugins, i) ? "enabled" : "off (costs nothing)");
}

/* ------------------------------------------------------------------ lifecycle ------- */

bool sl_renderer_create(sl_app *app, char *err, size_t n) {
    sl_renderer *r = calloc(1, sizeof *r);
    app->renderer = (struct sl_renderer *)r;
    r->width = app->backend.width;
    r->height = app->backend.height;
    r->finish_timing = app->opt.finish_timing || !app->backend.is_gpu;
    glGenQueries(64, r->queries);
    glCreateVertexArrays(1, &r->empty_vao);
    r->display_prog = sl_program_from_files(NULL, "sl:fullscreen.vert", "sl:display.frag", NULL, err, n);
    if (!r->display_prog->id) return false;
    r->accum_prog = sl_program_from_files(NULL, "sl:fullscreen.vert", "sl:accumulate.frag", NULL, err, n);
    if (!r->accum_prog->id) return false;
    r->resolve_prog = sl_program_from_files(NULL, "sl:fullscreen.vert", "sl:resolve.frag", NULL, err, n);
    if (!r->resolve_prog->id) return false;
    /* the core's own programs hot-reload like plugin programs */
    r->programs = malloc(3 * sizeof *r->programs);
    r->programs[0] = r->display_prog;
    r->programs[1] = r->accum_prog;
    r->programs[2] = r->resolve_prog;
    r->display_prog->owner = r->accum_prog->owner = r->resolve_prog->owner = -1;
    r->program_count = 3;
    return true;
}

bool sl_renderer_load_scene(sl_app *app, char *err, size_t n) {
    sl_renderer *r = R(app);
    sl_scene *s = &app->scene;
    r->meshes = calloc(s->mesh_count + 1, sizeof *r->meshes);
    for (int i = 0; i < s->mesh_count; i++) upload_mesh(&r->meshes[i], &s->meshes[i].data);
    r->materials = calloc(s->material_count + 1, sizeof *r->materials);
    pack_lights(app);
    r->seen_lights_version = app->lights_version;
    compose_all(app);
    r->seen_recompile = app->params.recompile_version;
    r->seen_materials = app->materials_version;
    r->seen_param_version = app->params.version;
    r->seen_debug_view = app->debug_view ? strdup(app->debug_view) : NULL;
    for (int m = 0; m < s->material_count; m++)
        if (!r->materials[m].forward.program) {
            snprintf(err, n, "material \"%s\": its program failed to compile (see above)", s->materials[m].name);
            return false;
        }
    plan(app);
    return true;
}

bool sl_renderer_poll_reload(sl_app *app) {
    sl_renderer *r = R(app);
    if (!r || !any_source_changed(r)) return false;
    int failures = sl_renderer_reload_shaders(app);
    SL_INFO("shaders changed on disk: reloaded (%d failed, last good programs kept)", failures);
    return true;
}

void sl_renderer_destroy(sl_app *app) {
    sl_renderer *r = R(app);
    if (!r) return;
    free_resources(r);
    for (int i = 0; r->meshes && i < app->scene.mesh_count; i++) {
        gpu_mesh *g = &r->meshes[i];
        glDeleteVertexArrays(1, &g->vao);
        glDeleteBuffers(4, g->vbo);
        glDeleteBuffers(1, &g->ibo);
    }
    free(r->meshes);
    for (int i = 0; i < r->texture_count; i++) {
        glDeleteTextures(1, &r->textures[i].id);
        free(r->textures[i].key);
    }
    free(r->textures);
    for (int m = 0; r->materials && m < app->scene.material_count; m++) {
        free(r->materials[m].forward.chunks);
        free(r->materials[m].depth.chunks);
        for (int k = 0; k < r->materials[m].override_count; k++) {
            free(r->materials[m].overrides[k].model);
            free(r->materials[m].overrides[k].v.chunks);
        }
    }
    free(r->materials);
    for (int i = 0; i < r->cache_count; i++) sl_program_free(r->cache[i]);
    free(r->cache);
    for (int i = 0; i < r->program_count; i++) sl_program_free(r->programs[i]);
    free(r->programs);
    free(r->program_owner);
    glDeleteVertexArrays(1, &r->empty_vao);
    if (r->light_buffer) glDeleteBuffers(1, &r->light_buffer);
    glDeleteQueries(64, r->queries);
    free(r->lights);
    free(r->seen_debug_view);
    free(r);
    app->renderer = NULL;
}
