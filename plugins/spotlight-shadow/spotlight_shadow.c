/* spotlight-shadow: the "spot" light type, and shadow maps for spot, directional and point
 * lights with hard / PCF / Poisson / PCSS filtering and an area-light reference.
 *
 *   spot_falloff.glsl, spot_light.glsl  the LIGHT hook (fall-off, animation)
 *   shadow.glsl                         the SHADOW hook (bias, filters), sdk shader.h
 *   this file                           parameters, the "shadow-maps" pass (one layer of a
 *                                       depth texture array per view), the table the hook
 *                                       reads, the shadelab.shadow-maps/1 extension
 * Design and parameters: README.md; failure regions: STABILITY.md. */
#include <shadelab/shadelab.h>
#include <shadelab/ext/shadow_maps.h>
#include <shadelab/ext/budget.h>
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#define CGLM_ALL_UNALIGNED
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define ID "spotlight-shadow"

enum { FILTER_HARD, FILTER_PCF, FILTER_POISSON, FILTER_PCSS, FILTER_REFERENCE };
enum { KIND_NONE, KIND_SPOT, KIND_DIRECTIONAL, KIND_POINT };
#define TABLE_W 8

typedef struct view_rec {
    int light, buffer_index, face, kind;
    mat4 view, proj, vp;
    float near_plane, far_plane, texel_world, size;
    vec3 pos, axis;
    int count;                            /* views of its light (point: 6; cascades: 1..8) */
    bool provided;                        /* from a view provider (extension revision 2) */
    float split_near, split_far, blend;   /* camera-depth interval it serves (provided views) */
} view_rec;

typedef struct ss {
    const sl_host *host;
    int unit_cmp, unit_depth, unit_table;
    unsigned tex, fbo, table_tex, sampler_cmp, sampler_depth;
    int tex_size, tex_layers;
    int table_rows, view_base;
    view_rec *views;
    int view_count, view_cap;
    uint64_t version;
    sl_ext_shadow_maps ext;
    sl_shadow_view_provider provider;     /* installed by another plugin (cascades); views == NULL: none */
} ss;

/* ------------------------------------------------------------------ parameters ------- */

static const char *const filters[] = {"hard", "pcf", "poisson", "pcss", "reference", NULL};
static const char *const falloffs[] = {"linear", "gltf", NULL};
static const char *const culls[] = {"none", "back", "front", NULL};

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}
#define RECOMPILE SL_PARAM_NEEDS_RECOMPILE
#define KNOB SL_PARAM_QUALITY_KNOB
static const sl_param_desc params[] = {
    P(.id = "shadows", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .flags = RECOMPILE, .group = "shadows",
      .description = "Shadow maps on/off; off gives exactly the unshadowed image and runs no shadow pass."),
    P(.id = "filter", .type = SL_PARAM_ENUM, .enum_values = filters, .default_value = {.i = FILTER_PCF}, .flags = RECOMPILE,
      .group = "shadows",
      .description = "hard (1 nearest texel), pcf (k x k hardware-compared taps), poisson (rotated Poisson disk), "
                     "pcss (blocker search + penumbra from the light size), reference (area-light ground truth)."),
    P(.id = "map_size", .type = SL_PARAM_INT, .default_value = {.i = 2048}, .min = 256, .max = 8192, .step = 256,
      .unit = "px", .flags = KNOB, .group = "quality", .description = "Width = height of every shadow map."),
    P(.id = "pcf_size", .type = SL_PARAM_INT, .default_value = {.i = 5}, .min = 1, .max = 9, .step = 2,
      .flags = RECOMPILE | KNOB, .group = "quality",
      .description = "PCF kernel: k x k taps (each a bilinear hardware comparison of 2 x 2 texels)."),
    P(.id = "pcf_step", .type = SL_PARAM_FLOAT, .default_value = {.f = {1}}, .min = 0.5f, .max = 4, .step = 0.25f,
      .unit = "texels", .flags = RECOMPILE | KNOB, .group = "quality",
      .description = "Distance between PCF taps (1: the taps' texels are fetched 2x2 at a time, a permutation)."),
    P(.id = "poisson_taps", .type = SL_PARAM_INT, .default_value = {.i = 16}, .min = 4, .max = 64, .step = 4,
      .flags = RECOMPILE | KNOB, .group = "quality", .description = "Poisson-disk PCF: number of taps."),
    P(.id = "poisson_radius", .type = SL_PARAM_FLOAT, .default_value = {.f = {2.5f}}, .min = 0.5f, .max = 32, .step = 0.5f,
      .unit = "texels", .group = "quality", .description = "Poisson-disk PCF: kernel radius."),
    P(.id = "poisson_rotate", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "quality",
      .description = "Rotate the Poisson disk per pixel (interleaved gradient noise): noise instead of banding."),
    P(.id = "pcss_blocker_taps", .type = SL_PARAM_INT, .default_value = {.i = 16}, .min = 4, .max = 64, .step = 4,
      .flags = RECOMPILE | KNOB, .group = "quality", .description = "PCSS: taps of the blocker search."),
    P(.id = "pcss_filter_taps", .type = SL_PARAM_INT, .default_value = {.i = 32}, .min = 4, .max = 64, .step = 4,
      .flags = RECOMPILE | KNOB, .group = "quality", .description = "PCSS: taps of the penumbra filter."),
    P(.id = "pcss_max_radius", .type = SL_PARAM_FLOAT, .default_value = {.f = {24}}, .min = 1, .max = 128, .step = 1,
      .unit = "texels", .group = "quality", .description = "PCSS: largest blocker-search and filter radius."),
    P(.id = "bias_constant", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.5f}}, .min = 0, .max = 1000, .step = 0.1f,
      .unit = "texels", .group = "bias", .description = "Moves the lookup towards the light by this many texel widths."),
    P(.id = "bias_slope", .type = SL_PARAM_FLOAT, .default_value = {.f = {1}}, .min = 0, .max = 1000, .step = 0.1f,
      .unit = "texels", .group = "bias",
      .description = "Slope-scaled: moves the lookup towards the light by this x tan(angle of incidence) texel widths."),
    P(.id = "normal_offset", .type = SL_PARAM_FLOAT, .default_value = {.f = {1}}, .min = 0, .max = 1000, .step = 0.1f,
      .unit = "texels", .group = "bias", .description = "Moves the lookup along the surface normal by this many texel widths."),
    P(.id = "receiver_plane", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "bias",
      .description = "Each filter tap compares with the receiver's tangent plane at that tap (wide kernels without acne)."),
    P(.id = "cull", .type = SL_PARAM_ENUM, .enum_values = culls, .group = "bias",
      .description = "Faces left out of the shadow maps: none (both faces cast), back, or front."),
    P(.id = "reference_map_size", .type = SL_PARAM_INT, .default_value = {.i = 4096}, .min = 256, .max = 16384,
      .unit = "px", .group = "reference", .description = "Map size used by filter = reference."),
    P(.id = "always_render", .type = SL_PARAM_BOOL, .group = "debug",
      .description = "Re-render the maps every frame even when nothing moved (to time the shadow pass)."),
    /* light keys: spot */
    P(.id = "cone_angle", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_LIGHT, .light_type = "spot", .light_slot = 0,
      .default_value = {.f = {30}}, .min = 0, .max = 90, .unit = "deg", .group = "spot",
      .description = "Half-angle from the axis to the edge of the cone (gltf: the outer cone)."),
    P(.id = "inner_cone_angle", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_LIGHT, .light_type = "spot", .light_slot = 1,
      .min = 0, .max = 90, .unit = "deg", .group = "spot", .description = "gltf fall-off: full intensity inside this half-angle."),
    P(.id = "falloff", .type = SL_PARAM_ENUM, .scope = SL_SCOPE_LIGHT, .light_type = "spot", .light_slot = 2,
      .enum_values = falloffs, .group = "spot",
      .description = "linear: full to 90% of the cone, zero at 110%; gltf: KHR_lights_punctual smooth fall-off."),
    P(.id = "radius", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_LIGHT, .light_type = "spot", .light_slot = 3,
      .default_value = {.f = {0.05f}}, .min = 0, .max = 100, .unit = "m", .group = "spot",
      .description = "Radius of the light's disk (facing along its axis): PCSS penumbrae and the reference."),
    /* light keys: the core's types, for soft shadows (a directional light's disk is the core's
     * angular_radius, sl_light_info.angular_radius, ABI 1.22) */
    P(.id = "radius", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_LIGHT, .light_type = "point", .light_slot = 0,
      .default_value = {.f = {0.05f}}, .min = 0, .max = 100, .unit = "m", .group = "shadows",
      .description = "Radius of a point light's sphere: PCSS and the reference."),
};

#define C(...) {.struct_size = sizeof(sl_shader_chunk_desc), __VA_ARGS__}
static const sl_shader_chunk_desc chunks[] = {
    C(.hook = SL_HOOK_LIGHT, .file = "spot_light.glsl", .function = "spotlight_shadow_spot", .name = "spot"),
    C(.hook = SL_HOOK_SHADOW, .file = "shadow.glsl", .function = "spotlight_shadow_visibility"),
};

static const sl_key_desc keys[] = {
    {.struct_size = sizeof(sl_key_desc), .key = "H", .param = "shadows", .description = "toggle shadows"},
    {.struct_size = sizeof(sl_key_desc), .key = "J", .param = "filter", .description = "next shadow filter"},
};

static sl_value param(ss *s, const char *id) {
    char full[96];
    snprintf(full, sizeof full, ID ".%s", id);
    return s->host->get_param(s->host, full);
}

/* ------------------------------------------------------------------ lights → views ---- */

static int light_kind(const sl_light_info *L) {
    if (!L->enabled || !L->cast_shadows || L->index < 0) return KIND_NONE;
    if (!strcmp(L->type, "spot")) return KIND_SPOT;
    if (!strcmp(L->type, "directional")) return KIND_DIRECTIONAL;
    if (!strcmp(L->type, "point")) return KIND_POINT;
    return KIND_NONE;
}

static void basis(const vec3 axis, vec3 t1, vec3 t2) {
    vec3 up = {0, 1, 0};
    if (fabsf(axis[1]) > 0.99f) glm_vec3_copy((vec3){1, 0, 0}, up);
    glm_vec3_cross((float *)axis, up, t1);
    glm_vec3_normalize(t1);
    glm_vec3_cross(t1, (float *)axis, t2);
}

/* Point k of n on the unit disk (Vogel's golden-angle spiral: stratified for every n). */
static void disk_point(int k, int n, float *x, float *y) {
    if (n <= 1) { *x = *y = 0; return; }
    float r = sqrtf((k + 0.5f) / n), phi = k * 2.39996323f;
    *x = r * cosf(phi);
    *y = r * sinf(phi);
}

/* Depth range of the scene box along `axis` from `eye`. */
static void box_depths(const sl_frame *f, const vec3 eye, const vec3 axis, float *zmin, float *zmax) {
    *zmin = INFINITY;
    *zmax = -INFINITY;
    for (int c = 0; c < 8; c++) {
        vec3 p = {c & 1 ? f->scene_max[0] : f->scene_min[0], c & 2 ? f->scene_max[1] : f->scene_min[1],
                  c & 4 ? f->scene_max[2] : f->scene_min[2]};
        vec3 d;
        glm_vec3_sub(p, (float *)eye, d);
        float z = glm_vec3_dot(d, (float *)axis);
        if (z < *zmin) *zmin = z;
        if (z > *zmax) *zmax = z;
    }
}

static view_rec *push_view(ss *s) {
    if (s->view_count == s->view_cap) {
        s->view_cap = s->view_cap ? s->view_cap * 2 : 16;
        s->views = realloc(s->views, s->view_cap * sizeof *s->views);
    }
    view_rec *v = &s->views[s->view_count++];
    memset(v, 0, sizeof *v);
    return v;
}

static void perspective_view(view_rec *v, const sl_frame *f, const vec3 pos, const vec3 axis, float half_angle, int size) {
    vec3 t1, t2, target;
    basis(axis, t1, t2);
    glm_vec3_add((float *)pos, (float *)axis, target);
    glm_lookat((float *)pos, target, t2, v->view);
    float zmin, zmax;
    box_depths(f, pos, axis, &zmin, &zmax);
    float far_plane = fmaxf(zmax * 1.01f + 1e-3f, 1e-2f);
    float near_plane = fmaxf(fmaxf(zmin * 0.99f, far_plane * 1e-3f), 1e-3f);
    if (near_plane >= far_plane) near_plane = far_plane * 0.5f;
    glm_perspective(2 * half_angle, 1, near_plane, far_plane, v->proj);
    glm_mat4_mul(v->proj, v->view, v->vp);
    v->near_plane = near_plane;
    v->far_plane = far_plane;
    v->texel_world = 2 * tanf(half_angle) / size;
    glm_vec3_copy((float *)pos, v->pos);
    glm_vec3_copy((float *)axis, v->axis);
}

static void ortho_view(view_rec *v, const sl_frame *f, const vec3 dir, int size) {
    vec3 center, ext, eye, t1, t2, target;
    for (int i = 0; i < 3; i++) {
        center[i] = 0.5f * (f->scene_min[i] + f->scene_max[i]);
        ext[i] = 0.5f * (f->scene_max[i] - f->scene_min[i]);
    }
    float radius = glm_vec3_norm(ext) + 1e-3f;
    glm_vec3_scale((float *)dir, -(radius + 1), eye);
    glm_vec3_add(eye, center, eye);
    basis(dir, t1, t2);
    glm_vec3_add(eye, (float *)dir, target);
    glm_lookat(eye, target, t2, v->view);
    /* tight square fit of the box corners in light space, a little margin for the kernels */
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int c = 0; c < 8; c++) {
        vec4 p = {c & 1 ? f->scene_max[0] : f->scene_min[0], c & 2 ? f->scene_max[1] : f->scene_min[1],
                  c & 4 ? f->scene_max[2] : f->scene_min[2], 1}, q;
        glm_mat4_mulv(v->view, p, q);
        for (int i = 0; i < 3; i++) { lo[i] = fminf(lo[i], q[i]); hi[i] = fmaxf(hi[i], q[i]); }
    }
    float half = 0.5f * fmaxf(hi[0] - lo[0], hi[1] - lo[1]) * 1.02f + 1e-3f;
    float cx = 0.5f * (lo[0] + hi[0]), cy = 0.5f * (lo[1] + hi[1]);
    float near_plane = fmaxf(-hi[2] - 0.01f * radius, 1e-3f), far_plane = -lo[2] + 0.01f * radius;
    if (far_plane <= near_plane) far_plane = near_plane + 1;
    glm_ortho(cx - half, cx + half, cy - half, cy + half, near_plane, far_plane, v->proj);
    glm_mat4_mul(v->proj, v->view, v->vp);
    v->near_plane = near_plane;
    v->far_plane = far_plane;
    v->texel_world = 2 * half / size;
    glm_vec3_copy(eye, v->pos);
    glm_vec3_copy((float *)dir, v->axis);
}

/* Views another plugin supplies for directional light i (extension revision 2); 0 = none. */
static int provided_views(ss *s, const sl_frame *f, int i, int size, sl_shadow_view *out) {
    if (!s->provider.views) return 0;
    for (int k = 0; k < SL_SHADOW_MAX_VIEWS_PER_LIGHT; k++) out[k] = (sl_shadow_view){.struct_size = sizeof *out};
    int n = s->provider.views(s->provider.user, f, i, size, out, SL_SHADOW_MAX_VIEWS_PER_LIGHT);
    return n < 0 ? 0 : n > SL_SHADOW_MAX_VIEWS_PER_LIGHT ? SL_SHADOW_MAX_VIEWS_PER_LIGHT : n;
}

/* Builds the views of every shadowed light for this frame (reference: from a point sampled
 * on the light, index accumulate_index of accumulate_count). */
static void build_views(ss *s, const sl_frame *f, int size, bool reference) {
    int n = 0;
    const sl_light_info *lights = s->host->lights(s->host, &n);
    s->view_count = 0;
    int k = reference ? f->accumulate_index : 0, count = reference ? f->accumulate_count : 1;
    for (int i = 0; i < n; i++) {
        const sl_light_info *L = &lights[i];
        int kind = light_kind(L);
        if (kind == KIND_NONE) continue;
        vec3 pos, dir, t1, t2; /* the core has animated them already (light keys animate*) */
        glm_vec3_copy((float *)L->position, pos);
        glm_vec3_copy((float *)L->direction, dir);
        basis(dir, t1, t2);
        float jx, jy;
        disk_point(k, count, &jx, &jy);
        if (kind == KIND_SPOT) {
            float radius = L->params[3];
            if (reference) {
                glm_vec3_muladds(t1, radius * jx, pos);
                glm_vec3_muladds(t2, radius * jy, pos);
            }
            /* the map covers the lit cone: linear fall-off reaches 110% of the cone angle */
            float cone = glm_rad(L->params[0]) * (L->params[2] > 0.5f ? 1.0f : 1.1f);
            float half_angle = fminf(cone + glm_rad(2.0f), glm_rad(85.0f));
            view_rec *v = push_view(s);
            perspective_view(v, f, pos, dir, half_angle, size);
            v->kind = kind;
            v->size = radius;
            v->count = 1;
        } else if (kind == KIND_DIRECTIONAL) {
            float t = tanf(glm_rad(L->angular_radius));
            if (reference) {
                glm_vec3_muladds(t1, t * jx, dir);
                glm_vec3_muladds(t2, t * jy, dir);
                glm_vec3_normalize(dir);
            }
            sl_shadow_view pv[SL_SHADOW_MAX_VIEWS_PER_LIGHT];
            int np = reference ? 0 : provided_views(s, f, i, size, pv);
            for (int k = 0; k < np; k++) { /* cascades: one layer per view, face = view */
                view_rec *v = push_view(s);
                memcpy(v->view, pv[k].view, 64);
                memcpy(v->proj, pv[k].proj, 64);
                glm_mat4_mul(v->proj, v->view, v->vp);
                mat4 inv;
                glm_mat4_inv(v->view, inv);
                glm_vec3_copy(inv[3], v->pos);
                glm_vec3_copy(dir, v->axis);
                v->near_plane = pv[k].near_plane;
                v->far_plane = pv[k].far_plane;
                v->texel_world = pv[k].texel_world;
                v->split_near = pv[k].split_near;
                v->split_far = pv[k].split_far;
                v->blend = pv[k].blend;
                v->provided = true;
                v->face = k;
                v->count = np;
                v->kind = kind;
                v->size = t;
            }
            if (np == 0) {
                view_rec *v = push_view(s);
                ortho_view(v, f, dir, size);
                v->kind = kind;
                v->size = t;
                v->count = 1;
            }
        } else {
            float radius = L->params[0];
            if (reference && count > 1) { /* a point on the sphere (Fibonacci sphere) */
                float z = 1 - 2 * (k + 0.5f) / count, r = sqrtf(fmaxf(0, 1 - z * z)), phi = k * 2.39996323f;
                pos[0] += radius * r * cosf(phi);
                pos[1] += radius * z;
                pos[2] += radius * r * sinf(phi);
            }
            static const float axes[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
            /* faces a little wider than 90° so kernels near a face edge stay inside it */
            float half_angle = atanf(1 + 8.0f / size);
            for (int face = 0; face < 6; face++) {
                view_rec *v = push_view(s);
                perspective_view(v, f, pos, axes[face], half_angle, size);
                v->kind = kind;
                v->face = face;
                v->size = radius;
                v->count = 6;
            }
        }
        for (int j = s->view_count - s->views[s->view_count - 1].count; j < s->view_count; j++) {
            s->views[j].light = i;
            s->views[j].buffer_index = L->index;
        }
    }
}

/* ------------------------------------------------------------------ GL resources ------ */

static void ensure_texture(ss *s, int size, int layers) {
    if (layers < 1) layers = 1;
    if (s->tex && s->tex_size == size && s->tex_layers >= layers) return;
    if (s->tex) glDeleteTextures(1, &s->tex);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &s->tex);
    glTextureStorage3D(s->tex, 1, GL_DEPTH_COMPONENT32F, size, size, layers);
    glTextureParameteri(s->tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(s->tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(s->tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(s->tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(s->tex, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    s->tex_size = size;
    s->tex_layers = layers;
}

/* Uploads the table shadow.glsl reads: one row per light of the GLSL buffer, then per view. */
static void upload_table(ss *s) {
    int n = 0;
    const sl_light_info *lights = s->host->lights(s->host, &n);
    int nbuf = 0;
    for (int i = 0; i < n; i++)
        if (lights[i].index + 1 > nbuf) nbuf = lights[i].index + 1;
    int rows = nbuf + s->view_count;
    if (rows < 1) rows = 1;
    float *t = calloc((size_t)rows * TABLE_W * 4, sizeof(float));
    for (int v = 0; v < s->view_count; v++) {
        const view_rec *w = &s->views[v];
        float *light_row = t + (size_t)w->buffer_index * TABLE_W * 4;
        if (w->face == 0) {
            light_row[0] = (float)v;
            light_row[1] = (float)w->count;
            light_row[2] = (float)w->kind;
            light_row[3] = w->provided ? 1.0f : 0.0f; /* pick the view by camera depth */
            memcpy(light_row + 4, w->pos, 12);
        }
        float *row = t + (size_t)(nbuf + v) * TABLE_W * 4;
        memcpy(row, w->vp, 64);
        row[16] = (float)v; /* layer */
        row[17] = w->near_plane;
        row[18] = w->far_plane;
        row[19] = w->texel_world;
        memcpy(row + 20, w->pos, 12);
        row[23] = w->kind == KIND_DIRECTIONAL ? 1.0f : 0.0f;
        memcpy(row + 24, w->axis, 12);
        row[27] = w->size;
        row[28] = w->split_near;
        row[29] = w->split_far;
        row[30] = w->blend;
    }
    if (!s->table_tex || rows > s->table_rows) {
        if (s->table_tex) glDeleteTextures(1, &s->table_tex);
        glCreateTextures(GL_TEXTURE_2D, 1, &s->table_tex);
        glTextureStorage2D(s->table_tex, 1, GL_RGBA32F, TABLE_W, rows);
        glTextureParameteri(s->table_tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(s->table_tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        s->table_rows = rows;
    }
    glTextureSubImage2D(s->table_tex, 0, 0, 0, TABLE_W, rows, GL_RGBA, GL_FLOAT, t);
    s->view_base = nbuf;
    free(t);
}

/* ------------------------------------------------------------------ the pass ---------- */

static bool shadows_on(ss *s) { return param(s, "shadows").b; }

static bool pass_active(void *user, const sl_frame *f) {
    ss *s = user;
    if (!shadows_on(s)) return false;
    int n = 0;
    const sl_light_info *lights = s->host->lights(s->host, &n);
    for (int i = 0; i < n; i++)
        if (light_kind(&lights[i]) != KIND_NONE) return true;
    return false;
}

static uint64_t fnv(const void *data, size_t len, uint64_t h) {
    const unsigned char *p = data;
    for (size_t i = 0; i < len; i++) { h ^= p[i]; h *= 1099511628211ull; }
    return h;
}

/* Changes only when the maps would: shadowed lights, scene bounds and geometry, map settings,
 * (animated lights move, so their positions change), the light sample in reference mode. */
static uint64_t pass_signature(void *user, const sl_frame *f) {
    ss *s = user;
    uint64_t h = 1469598103934665603ull;
    int n = 0;
    const sl_light_info *lights = s->host->lights(s->host, &n);
    for (int i = 0; i < n; i++) {
        const sl_light_info *L = &lights[i];
        int kind = light_kind(L);
        h = fnv(&kind, sizeof kind, h);
        h = fnv(&L->index, sizeof L->index, h); /* the table's layout follows the light buffer */
        if (kind == KIND_NONE) continue;
        h = fnv(L->position, sizeof L->position, h);
        h = fnv(L->direction, sizeof L->direction, h);
        h = fnv(L->params, sizeof L->params, h);
        h = fnv(&L->angular_radius, sizeof L->angular_radius, h);
        if (kind == KIND_DIRECTIONAL && param(s, "filter").i != FILTER_REFERENCE) {
            /* views another plugin supplies (cascades follow the camera): re-render when one moves */
            sl_shadow_view pv[SL_SHADOW_MAX_VIEWS_PER_LIGHT];
            int np = provided_views(s, f, i, param(s, "map_size").i, pv);
            h = fnv(&np, sizeof np, h);
            for (int k = 0; k < np; k++) {
                h = fnv(pv[k].view, sizeof pv[k].view, h);
                h = fnv(pv[k].proj, sizeof pv[k].proj, h);
                float sel[6] = {pv[k].near_plane, pv[k].far_plane, pv[k].texel_world, pv[k].split_near,
                                pv[k].split_far, pv[k].blend};
                h = fnv(sel, sizeof sel, h);
            }
        }
    }
    h = fnv(f->scene_min, sizeof f->scene_min, h);
    h = fnv(f->scene_max, sizeof f->scene_max, h);
    h = fnv(&f->geometry_version, sizeof f->geometry_version, h);
    int settings[4] = {param(s, "map_size").i, param(s, "reference_map_size").i, param(s, "cull").i,
                       param(s, "filter").i == FILTER_REFERENCE};
    h = fnv(settings, sizeof settings, h);
    if (settings[3]) {
        h = fnv(&f->accumulate_index, sizeof f->accumulate_index, h);
        h = fnv(&f->accumulate_count, sizeof f->accumulate_count, h);
    }
    if (param(s, "always_render").b) h = fnv(&f->index, sizeof f->index, h);
    return h;
}

static void pass_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    ss *s = user;
    const sl_host *host = s->host;
    bool reference = param(s, "filter").i == FILTER_REFERENCE;
    int size = reference ? param(s, "reference_map_size").i : param(s, "map_size").i;
    build_views(s, f, size, reference);
    ensure_texture(s, size, s->view_count);
    int cull = param(s, "cull").i; /* none 0, back 1, front 2: draw_scene's numbering */
    float one = 1.0f;
    for (int v = 0; v < s->view_count; v++) {
        view_rec *w = &s->views[v];
        glNamedFramebufferTextureLayer(s->fbo, GL_DEPTH_ATTACHMENT, s->tex, 0, v);
        glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
        glViewport(0, 0, size, size);
        glDepthMask(GL_TRUE);
        glClearNamedFramebufferfv(s->fbo, GL_DEPTH, 0, &one);
        sl_draw_scene_desc d = {.struct_size = sizeof d, .mode = SL_DRAW_DEPTH_ONLY, .shadow_casters_only = true,
                                .cull = cull};
        memcpy(d.view, w->view, sizeof d.view);
        memcpy(d.proj, w->proj, sizeof d.proj);
        host->draw_scene(host, ctx, &d);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    upload_table(s);
    s->version++;
}

/* No shadowed light left (the pass stops running): drop the views so that a SHADOW hook still
 * compiled in (a shadowed light of a type without maps) reads "no map" for every light. */
static void ss_begin_frame(void *user, const sl_frame *f) {
    ss *s = user;
    if (s->view_count && !pass_active(s, f)) {
        s->view_count = 0;
        upload_table(s);
        s->version++;
    }
}

static void bind_program(void *user, unsigned program, int material, const sl_frame *frame) {
    ss *s = user;
    int loc = glGetUniformLocation(program, "spotlight_shadow_table");
    if (loc < 0) return; /* the program has no SHADOW hook (no shadowed light) */
    glBindTextureUnit(s->unit_cmp, s->tex);
    glBindSampler(s->unit_cmp, s->sampler_cmp);
    glBindTextureUnit(s->unit_depth, s->tex);
    glBindSampler(s->unit_depth, s->sampler_depth);
    glBindTextureUnit(s->unit_table, s->table_tex);
    glProgramUniform1i(program, loc, s->unit_table);
    glProgramUniform1i(program, glGetUniformLocation(program, "spotlight_shadow_cmp_map"), s->unit_cmp);
    glProgramUniform1i(program, glGetUniformLocation(program, "spotlight_shadow_depth_map"), s->unit_depth);
    glProgramUniform1i(program, glGetUniformLocation(program, "spotlight_shadow_view_base"), s->view_base);
    glProgramUniform1f(program, glGetUniformLocation(program, "spotlight_shadow_texels"), (float)s->tex_size);
}

/* ------------------------------------------------------------------ extension --------- */

static int ext_count(void *ctx) { return ((ss *)ctx)->view_count; }

static bool ext_get(void *ctx, int i, sl_shadow_map *out) {
    ss *s = ctx;
    if (i < 0 || i >= s->view_count || !out) return false;
    const view_rec *v = &s->views[i];
    sl_shadow_map m = {
        .struct_size = sizeof m, .light = v->light, .buffer_index = v->buffer_index, .face = v->face,
        .texture = s->tex, .layer = i, .size = s->tex_size,
        .projection = v->kind == KIND_DIRECTIONAL ? SL_SHADOW_ORTHOGRAPHIC : SL_SHADOW_PERSPECTIVE,
        .near_plane = v->near_plane, .far_plane = v->far_plane, .texel_world = v->texel_world, .light_size = v->size,
        .split_near = v->split_near, .split_far = v->split_far, .blend = v->blend};
    memcpy(m.view, v->view, 64);
    memcpy(m.proj, v->proj, 64);
    memcpy(m.view_proj, v->vp, 64);
    memcpy(m.position, v->pos, 12);
    memcpy(m.direction, v->axis, 12);
    uint32_t n = out->struct_size && out->struct_size < sizeof m ? out->struct_size : (uint32_t)sizeof m;
    memcpy(out, &m, n);
    out->struct_size = n;
    return true;
}

static bool ext_find(void *ctx, int light, int face, sl_shadow_map *out) {
    ss *s = ctx;
    for (int i = 0; i < s->view_count; i++)
        if (s->views[i].light == light && s->views[i].face == face) return ext_get(ctx, i, out);
    return false;
}

static uint64_t ext_version(void *ctx) { return ((ss *)ctx)->version; }

static bool ext_set_view_provider(void *ctx, const sl_shadow_view_provider *p) {
    ss *s = ctx;
    if (!p) {
        s->provider = (sl_shadow_view_provider){0};
        return true;
    }
    if (s->provider.views) return false;
    sl_shadow_view_provider copy = {0};
    memcpy(&copy, p, p->struct_size && p->struct_size < sizeof copy ? p->struct_size : sizeof copy);
    s->provider = copy;
    return true;
}

/* Revision 2 appends to revision 1's struct: both ids get the same table. */
static const void *get_extension(void *user, const char *id) {
    ss *s = user;
    return !strcmp(id, SL_EXT_SHADOW_MAPS) || !strcmp(id, SL_EXT_SHADOW_MAPS_2) ? &s->ext : NULL;
}

/* ------------------------------------------------------------------ lifecycle --------- */

static sl_status ss_create(const sl_host *host, void **user) {
    ss *s = calloc(1, sizeof *s);
    if (!s) return SL_ERR_FAILED;
    *user = s;
    s->host = host;
    s->ext = (sl_ext_shadow_maps){.struct_size = sizeof s->ext, .ctx = s, .count = ext_count, .get = ext_get,
                                  .find = ext_find, .version = ext_version,
                                  .set_view_provider = ext_set_view_provider};
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    /* pcf_size for the window's frame-time budget (ext/budget.h): bench/spheres_r0.1.csv, pcf at
     * 2048²: forward + display ms 8.31 (3x3) and 10.24 (5x5; the shadow pass is not re-rendered
     * while only the camera moves), RMSE against the area-light reference */
    static const char *const pcf_sizes[] = {"3", "5"};
    static const float pcf_cost[] = {0.81f, 1}, pcf_error[] = {0.00216f, 0.00186f};
    const sl_ext_budget *budget = host->get_extension(host, SL_EXT_BUDGET);
    const sl_quality_model pcf = {.struct_size = sizeof pcf, .param = "pcf_size", .count = 2, .values = pcf_sizes,
                                  .cost = pcf_cost, .error = pcf_error,
                                  .measured_with = "spotlight-shadow bench/spheres_r0.1.csv (pcf, 2048² maps)"};
    if (budget && budget->add_quality_model(host, &pcf) != SL_OK) return SL_ERR_FAILED;
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
        if (host->add_key(host, &keys[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_pass_desc pass = {.struct_size = sizeof pass, .name = "shadow-maps", .stage = SL_STAGE_SHADOW,
                               .execute = pass_execute, .is_active = pass_active, .signature = pass_signature, .user = s,
                               /* not the camera: provided views (cascades) are in the signature */
                               .depends = SL_DEPENDS_LIGHTS | SL_DEPENDS_GEOMETRY | SL_DEPENDS_MATERIALS};
    if (host->add_pass(host, &pass) != SL_OK) return SL_ERR_FAILED;
    if (host->set_bind_callback(host, bind_program, s) != SL_OK) return SL_ERR_FAILED;
    static const sl_reference_desc reference = {
        .struct_size = sizeof reference, .settings = "spotlight-shadow.filter=reference", .accumulate_frames = 256,
        .description = "Each shadowed light as a disk (spot: radius, facing its axis; directional: angular radius; "
                       "point: a sphere): the average of hard shadow maps (reference_map_size) rendered from "
                       "stratified points on the light, one per accumulated frame."};
    host->set_reference(host, &reference);
    s->unit_cmp = host->reserve_texture_unit(host);
    s->unit_depth = host->reserve_texture_unit(host);
    s->unit_table = host->reserve_texture_unit(host);
    if (s->unit_cmp < 0 || s->unit_depth < 0 || s->unit_table < 0) return SL_ERR_FAILED;
    return SL_OK;
}

static sl_status ss_activate(void *user) {
    ss *s = user;
    const char *missing = NULL;
    if (!sl_gl_load(s->host->gl_get_proc_address, &missing)) {
        s->host->log(s->host, SL_LOG_ERROR, "GL entry point %s missing", missing ? missing : "?");
        return SL_ERR_GL;
    }
    glCreateFramebuffers(1, &s->fbo);
    glNamedFramebufferDrawBuffer(s->fbo, GL_NONE);
    glNamedFramebufferReadBuffer(s->fbo, GL_NONE);
    glCreateSamplers(1, &s->sampler_cmp);
    glSamplerParameteri(s->sampler_cmp, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(s->sampler_cmp, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(s->sampler_cmp, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(s->sampler_cmp, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(s->sampler_cmp, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glSamplerParameteri(s->sampler_cmp, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glCreateSamplers(1, &s->sampler_depth);
    glSamplerParameteri(s->sampler_depth, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(s->sampler_depth, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(s->sampler_depth, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(s->sampler_depth, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(s->sampler_depth, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    ensure_texture(s, 16, 1); /* something valid to bind before the first pass */
    s->view_count = 0;
    upload_table(s);
    return SL_OK;
}

static void ss_deactivate(void *user) {
    ss *s = user;
    if (s->tex) glDeleteTextures(1, &s->tex);
    if (s->table_tex) glDeleteTextures(1, &s->table_tex);
    if (s->fbo) glDeleteFramebuffers(1, &s->fbo);
    if (s->sampler_cmp) glDeleteSamplers(1, &s->sampler_cmp);
    if (s->sampler_depth) glDeleteSamplers(1, &s->sampler_depth);
    s->tex = s->table_tex = s->fbo = s->sampler_cmp = s->sampler_depth = 0;
    s->tex_size = s->tex_layers = s->table_rows = 0;
}

static void ss_destroy(void *user) {
    ss *s = user;
    if (!s) return;
    free(s->views);
    free(s);
}

static const sl_plugin_desc ss_desc = {
    SL_PLUGIN_HEADER,
    .id = ID,
    .version = "1.0",
    .description = "Spot lights; shadow maps for spot, directional and point lights (hard, PCF, Poisson, PCSS) "
                   "with an area-light reference; the shadelab.shadow-maps/1 extension.",
    .create = ss_create,
    .activate = ss_activate,
    .begin_frame = ss_begin_frame,
    .deactivate = ss_deactivate,
    .destroy = ss_destroy,
    .get_extension = get_extension,
    .default_for = SL_PLUGIN_DEFAULT_SHADOWS,
};

SL_DEFINE_PLUGIN(ss_desc)
