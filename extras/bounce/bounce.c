/* bounce: one bounce of diffuse indirect light from the scene's directional lights, as a light of
 * its own (type "indirect"). Built against the installed SDK only (extras/README.md). See README.md.
 *
 *   1. reflective shadow maps (Dachsbacher & Stamminger 2005): each directional light's view of
 *      the scene (orthographic, fitted to the scene's bounds), every material's own surface hooks
 *      (bounce_rsm.frag), storing the light each texel's surface sends back: its diffuse albedo ×
 *      the light's irradiance, where the surface faces the light; mipmapped;
 *   2. virtual point lights (build_vpls, on the CPU from the maps read back): the texels of the
 *      level with vpls × vpls a map (flux, flux-weighted position and normal), split into finer
 *      ones where their positions spread (an edge over a surface far behind it);
 *   3. an irradiance probe grid over the scene's bounds (bounce_probes.frag, one full-screen
 *      triangle over the slices side by side): at each probe the virtual lights' irradiance
 *      e_j = Φ_j cos θ_j / (π d² + A_j) (a disk of the light's area seen on its axis: finite as
 *      d → 0) from directions ω_j, as order-2 spherical harmonics of irradiance (Ramamoorthi &
 *      Hanrahan 2001);
 *   4. the light "bounce.indirect" (SL_CHUNK_LIGHT_RADIANCE, bounce.glsl): trilinear in the grid,
 *      E(n) from the nine harmonics, lighting each model by its lobe contract's diffuse albedo.
 * Steps 1-3 are the pass "bounce", run only when the lights, geometry, materials or this plugin's
 * parameters change.
 *
 *   globals      bounce.vpls (virtual lights per side of each map), bounce.grid (probes along the
 *                scene's longest side); both quality knobs */
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include <shadelab/shadelab.h>
#include <shadelab/matrix.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BOUNCE_ID "bounce"
#define BOUNCE_MAX_LIGHTS 4  /* directional lights bounced; more are left out with a warning */
#define BOUNCE_RSM_SCALE 8   /* map texels per virtual light, per side */
#define BOUNCE_VPL_BINDING 8   /* shader storage binding of the gather's list (the core's: 0-6) */
#define BOUNCE_SPLIT_LEVELS 3  /* a virtual light straddling a depth step splits, down to the map's texels (8 = 2³) */
#define BOUNCE_PROBE_TEXTURES 7 /* 9 order-2 harmonics × RGB = 27 floats, 4 per texel */

typedef struct bounce {
    const sl_host *host;
    int light;                       /* handle of bounce.indirect (-1: a host without add_light) */
    bool light_on;                   /* its state as last set */
    unsigned rsm[3], rsm_depth, rsm_fbo; /* flux, position, normal: 2D arrays, one layer per light */
    int rsm_size;
    unsigned probe[BOUNCE_PROBE_TEXTURES], probe_fbo; /* the harmonics, 4 floats each: 3D textures */
    unsigned atlas[BOUNCE_PROBE_TEXTURES]; /* the same, the slices side by side: what the gather draws */
    int grid[3];
    float box_min[3], box_max[3];    /* the probes' box: probe centres at its cells' centres */
    sl_program *gather;
    int unit_probe[BOUNCE_PROBE_TEXTURES];
    int rsm_layer;                   /* the map being drawn (bind callback), -1 otherwise */
    float rsm_dir[BOUNCE_MAX_LIGHTS][3], rsm_E[BOUNCE_MAX_LIGHTS][3], texel_area[BOUNCE_MAX_LIGHTS];
    int light_count;
    unsigned vpl_buffer;             /* the virtual lights (SSBO, binding BOUNCE_VPL_BINDING) */
    size_t vpl_capacity;
    int vpl_count;
    bool warned_many;
} bounce;

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}
static const sl_param_desc params[] = {
    P(.id = "vpls", .type = SL_PARAM_INT, .default_value = {.i = 16}, .min = 4, .max = 32, .step = 4,
      .flags = SL_PARAM_QUALITY_KNOB, .group = "bounce",
      .description = "Virtual point lights per side of each directional light's reflective shadow map (its map has 8× as "
                     "many texels a side); rounded down to a power of two."),
    P(.id = "grid", .type = SL_PARAM_INT, .default_value = {.i = 12}, .min = 2, .max = 32, .step = 1,
      .flags = SL_PARAM_QUALITY_KNOB, .group = "bounce",
      .description = "Irradiance probes along the scene's longest side (the other sides in proportion, 2 at least)."),
};

static int iparam(bounce *b, const char *id) {
    char full[64];
    snprintf(full, sizeof full, BOUNCE_ID ".%s", id);
    return b->host->get_param(b->host, full).i;
}

static int vpl_side(bounce *b) {
    int n = 4;
    while (n * 2 <= iparam(b, "vpls")) n *= 2;
    return n;
}

static bool bounced(const sl_light_info *L) {
    return L->enabled && L->index >= 0 && L->type && !strcmp(L->type, "directional");
}

/* ---- GL objects ---------------------------------------------------------------------------- */

static unsigned make_texture(unsigned target, unsigned format, int levels, int w, int h, int d) {
    unsigned t;
    glCreateTextures(target, 1, &t);
    if (target == GL_TEXTURE_2D) glTextureStorage2D(t, levels, format, w, h);
    else glTextureStorage3D(t, levels, format, w, h, d);
    bool mip = levels > 1;
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, mip ? GL_NEAREST_MIPMAP_NEAREST : GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, mip ? GL_NEAREST : GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    return t;
}

static void free_rsm(bounce *b) {
    glDeleteTextures(3, b->rsm);
    glDeleteTextures(1, &b->rsm_depth);
    memset(b->rsm, 0, sizeof b->rsm);
    b->rsm_depth = 0, b->rsm_size = 0;
}

static void ensure_rsm(bounce *b, int size) {
    if (b->rsm_size == size) return;
    free_rsm(b);
    int levels = 1;
    while ((1 << (levels - 1)) < size) levels++;
    const unsigned formats[3] = {GL_RGBA32F, GL_RGBA32F, GL_RGBA16F}; /* flux: lights up to 1e10 stay finite */
    for (int i = 0; i < 3; i++) b->rsm[i] = make_texture(GL_TEXTURE_2D_ARRAY, formats[i], levels, size, size, BOUNCE_MAX_LIGHTS);
    b->rsm_depth = make_texture(GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, 1, size, size, 1);
    glNamedFramebufferTexture(b->rsm_fbo, GL_DEPTH_ATTACHMENT, b->rsm_depth, 0);
    b->rsm_size = size;
}

static void ensure_probes(bounce *b, const int grid[3]) {
    if (b->probe[0] && !memcmp(grid, b->grid, sizeof b->grid)) return;
    glDeleteTextures(BOUNCE_PROBE_TEXTURES, b->probe);
    glDeleteTextures(BOUNCE_PROBE_TEXTURES, b->atlas);
    for (int i = 0; i < BOUNCE_PROBE_TEXTURES; i++) {
        b->probe[i] = make_texture(GL_TEXTURE_3D, GL_RGBA16F, 1, grid[0], grid[1], grid[2]);
        b->atlas[i] = make_texture(GL_TEXTURE_2D, GL_RGBA16F, 1, grid[0] * grid[2], grid[1], 1);
        glNamedFramebufferTexture(b->probe_fbo, GL_COLOR_ATTACHMENT0 + i, b->atlas[i], 0);
    }
    memcpy(b->grid, grid, sizeof b->grid);
}

/* ---- the light's view: orthographic, fitted to the scene's bounds ------------------------------ */

/* view and projection (column-major) of light direction `dir` (where the light travels) over the
 * box [lo, hi]; returns the area of one map texel, perpendicular to the light (world units²). */
static float light_view(const float dir[3], const float lo[3], const float hi[3], int size, float view[16], float proj[16]) {
    float z[3] = {-dir[0], -dir[1], -dir[2]}, x[3], y[3];
    sl_vec3_normalize(z);
    const float up[3] = {0, 1, 0}, side[3] = {1, 0, 0};
    sl_vec3_cross(fabsf(z[1]) < 0.99f ? up : side, z, x);
    sl_vec3_normalize(x);
    sl_vec3_cross(z, x, y);
    float mn[3] = {INFINITY, INFINITY, INFINITY}, mx[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < 8; k++) {
        float p[3] = {k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]};
        float v[3] = {x[0] * p[0] + x[1] * p[1] + x[2] * p[2], y[0] * p[0] + y[1] * p[1] + y[2] * p[2],
                      z[0] * p[0] + z[1] * p[1] + z[2] * p[2]};
        for (int c = 0; c < 3; c++) mn[c] = fminf(mn[c], v[c]), mx[c] = fmaxf(mx[c], v[c]);
    }
    float pad = 0.01f * fmaxf(fmaxf(mx[0] - mn[0], mx[1] - mn[1]), fmaxf(mx[2] - mn[2], 1e-3f));
    for (int c = 0; c < 3; c++) mn[c] -= pad, mx[c] += pad;
    float v[16] = {x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0, 0, 0, 0, 1};
    /* eye space z is the v[2] above; the camera looks down −z: depth −z from −mx[2] to −mn[2] */
    float n = -mx[2], f = -mn[2], l = mn[0], r = mx[0], bo = mn[1], t = mx[1];
    float p[16] = {2 / (r - l), 0, 0, 0, 0, 2 / (t - bo), 0, 0, 0, 0, -2 / (f - n), 0,
                   -(r + l) / (r - l), -(t + bo) / (t - bo), -(f + n) / (f - n), 1};
    memcpy(view, v, sizeof v);
    memcpy(proj, p, sizeof p);
    return (r - l) * (t - bo) / ((float)size * size);
}

/* ---- pass: the maps, then the probes ------------------------------------------------------------ */

static void draw_maps(bounce *b, sl_pass_ctx *ctx, const sl_frame *f, int size) {
    const sl_host *h = b->host;
    int n = 0, used = 0;
    const sl_light_info *lights = h->lights(h, &n);
    const float zero[4] = {0, 0, 0, 0}, one = 1;
    for (int i = 0; i < n; i++) {
        if (!bounced(&lights[i])) continue;
        if (used == BOUNCE_MAX_LIGHTS) {
            if (!b->warned_many)
                h->log(h, SL_LOG_WARN, "more than %d directional lights: light '%s' and later ones bounce no light",
                       BOUNCE_MAX_LIGHTS, lights[i].name);
            b->warned_many = true;
            break;
        }
        float view[16], proj[16];
        b->texel_area[used] = light_view(lights[i].direction, f->scene_min, f->scene_max, size, view, proj);
        memcpy(b->rsm_dir[used], lights[i].direction, sizeof b->rsm_dir[used]);
        memcpy(b->rsm_E[used], lights[i].color, sizeof b->rsm_E[used]);
        for (int k = 0; k < 3; k++) glNamedFramebufferTextureLayer(b->rsm_fbo, GL_COLOR_ATTACHMENT0 + k, b->rsm[k], 0, used);
        glBindFramebuffer(GL_FRAMEBUFFER, b->rsm_fbo);
        glViewport(0, 0, size, size);
        glDepthMask(GL_TRUE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDisable(GL_BLEND);
        for (int k = 0; k < 3; k++) glClearNamedFramebufferfv(b->rsm_fbo, GL_COLOR, k, zero);
        glClearNamedFramebufferfv(b->rsm_fbo, GL_DEPTH, 0, &one);
        b->rsm_layer = used;
        sl_draw_scene_desc d = {.struct_size = sizeof d, .mode = SL_DRAW_MATERIALS, .cull = 1, .fragment = "bounce_rsm.frag"};
        memcpy(d.view, view, sizeof view);
        memcpy(d.proj, proj, sizeof proj);
        h->draw_scene(h, ctx, &d);
        b->rsm_layer = -1;
        used++;
    }
    b->light_count = used;
    if (used)
        for (int k = 0; k < 3; k++) glGenerateTextureMipmap(b->rsm[k]);
}

/* The probes' grid over the scene's bounds: `grid` along the longest side. */
static void place_probes(bounce *b, const sl_frame *f, int grid[3]) {
    float ext[3], longest = 0;
    for (int c = 0; c < 3; c++) ext[c] = f->scene_max[c] - f->scene_min[c], longest = fmaxf(longest, ext[c]);
    if (!(longest > 0) || !isfinite(longest)) longest = 1;
    int g = iparam(b, "grid");
    for (int c = 0; c < 3; c++) {
        float e = fmaxf(ext[c], 0.05f * longest); /* a flat scene still gets a slab of probes */
        float mid = 0.5f * (f->scene_min[c] + f->scene_max[c]);
        if (!isfinite(mid)) mid = 0;
        grid[c] = (int)ceilf(g * e / longest);
        if (grid[c] < 2) grid[c] = 2;
        b->box_min[c] = mid - 0.5f * e, b->box_max[c] = mid + 0.5f * e;
    }
}

/* ---- the virtual lights: the maps' texels, merged by mip levels where they lie on one surface ---- */

typedef struct vpl_maps {
    float *flux[BOUNCE_SPLIT_LEVELS + 1], *pos[BOUNCE_SPLIT_LEVELS + 1], *nrm[BOUNCE_SPLIT_LEVELS + 1];
    int side[BOUNCE_SPLIT_LEVELS + 1]; /* texels a side at level (top − k) */
    float *out;                        /* 12 floats per light: position, area; normal, 0; flux, 0 */
    int count, capacity;
} vpl_maps;

/* Texel (x, y) of layer `layer` at split depth k: a virtual light of the given area, or, where its
 * texels' positions spread wider than its side (an edge over a surface far behind it), its four
 * texels one level finer (BOUNCE_SPLIT_LEVELS deep at most, while the list is under half its
 * capacity: the gather's time stays bounded). Texels that send no light are dropped. */
static void collect_vpl(vpl_maps *v, int layer, int k, int x, int y, float area) {
    int n = v->side[k];
    size_t i = ((size_t)layer * n * n + (size_t)y * n + x) * 4;
    const float *p = v->pos[k] + i, *nr = v->nrm[k] + i, *fl = v->flux[k] + i;
    if (!(p[3] > 0) || !isfinite(p[3])) return;
    float m[3] = {p[0] / p[3], p[1] / p[3], p[2] / p[3]};
    float spread = nr[3] / p[3] - (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    if (spread > area && k < BOUNCE_SPLIT_LEVELS && v->count < v->capacity / 2) {
        for (int c = 0; c < 4; c++) collect_vpl(v, layer, k + 1, 2 * x + (c & 1), 2 * y + (c >> 1), 0.25f * area);
        return;
    }
    float nl = sqrtf(nr[0] * nr[0] + nr[1] * nr[1] + nr[2] * nr[2]);
    if (!(nl > 0) || !isfinite(fl[0] + fl[1] + fl[2]) || v->count == v->capacity) return;
    float *o = v->out + (size_t)v->count++ * 12;
    const float rec[12] = {m[0], m[1], m[2], area, nr[0] / nl, nr[1] / nl, nr[2] / nl, 0,
                           fl[0] * area, fl[1] * area, fl[2] * area, 0};
    memcpy(o, rec, sizeof rec);
}

/* Reads the maps' top BOUNCE_SPLIT_LEVELS + 1 levels back and writes the list of virtual lights. */
static void build_vpls(bounce *b, int vpls) {
    int top = 0;
    while ((vpls << top) < b->rsm_size) top++;
    /* at most 8 per top-level texel on average: splitting stops at half of that (collect_vpl) */
    vpl_maps v = {.capacity = 8 * b->light_count * vpls * vpls + 64};
    v.out = malloc(sizeof(float) * 12 * (size_t)(v.capacity ? v.capacity : 1));
    bool ok = v.out != NULL && b->light_count > 0;
    for (int k = 0; k <= BOUNCE_SPLIT_LEVELS; k++) {
        int n = v.side[k] = vpls << k;
        size_t bytes = sizeof(float) * 4 * (size_t)n * n * BOUNCE_MAX_LIGHTS;
        float **dst[3] = {&v.flux[k], &v.pos[k], &v.nrm[k]};
        for (int t = 0; t < 3; t++) {
            *dst[t] = malloc(bytes);
            ok = ok && *dst[t];
            if (*dst[t]) glGetTextureImage(b->rsm[t], top - k, GL_RGBA, GL_FLOAT, (GLsizei)bytes, *dst[t]);
        }
    }
    for (int l = 0; ok && l < b->light_count; l++)
        for (int y = 0; y < vpls; y++)
            for (int x = 0; x < vpls; x++) collect_vpl(&v, l, 0, x, y, b->texel_area[l] * (float)(1 << top) * (float)(1 << top));
    b->vpl_count = ok ? v.count : 0;
    size_t need = sizeof(float) * 12 * (size_t)(b->vpl_count ? b->vpl_count : 1);
    if (need > b->vpl_capacity) {
        glNamedBufferData(b->vpl_buffer, (GLsizeiptr)need, NULL, GL_DYNAMIC_DRAW);
        b->vpl_capacity = need;
    }
    if (b->vpl_count) glNamedBufferSubData(b->vpl_buffer, 0, (GLsizeiptr)(sizeof(float) * 12 * b->vpl_count), v.out);
    for (int k = 0; k <= BOUNCE_SPLIT_LEVELS; k++) free(v.flux[k]), free(v.pos[k]), free(v.nrm[k]);
    free(v.out);
}

static void gather_probes(bounce *b, sl_pass_ctx *ctx) {
    const sl_host *h = b->host;
    unsigned prog = h->program_id(h, b->gather);
    if (!prog) return;
    glUseProgram(prog);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BOUNCE_VPL_BINDING, b->vpl_buffer);
    glUniform1i(glGetUniformLocation(prog, "bounce_vpl_count"), b->vpl_count);
    glUniform3fv(glGetUniformLocation(prog, "bounce_box_min"), 1, b->box_min);
    glUniform3fv(glGetUniformLocation(prog, "bounce_box_max"), 1, b->box_max);
    glUniform3f(glGetUniformLocation(prog, "bounce_grid"), (float)b->grid[0], (float)b->grid[1], (float)b->grid[2]);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glBindFramebuffer(GL_FRAMEBUFFER, b->probe_fbo);
    glViewport(0, 0, b->grid[0] * b->grid[2], b->grid[1]); /* one draw: the rasteriser's threads share it */
    h->draw_fullscreen(h, ctx);
    for (int k = 0; k < BOUNCE_PROBE_TEXTURES; k++)
        for (int z = 0; z < b->grid[2]; z++)
            glCopyImageSubData(b->atlas[k], GL_TEXTURE_2D, 0, z * b->grid[0], 0, 0, b->probe[k], GL_TEXTURE_3D, 0, 0, 0, z,
                               b->grid[0], b->grid[1], 1);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BOUNCE_VPL_BINDING, 0);
    glEnable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

static void bounce_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    bounce *b = user;
    int vpls = vpl_side(b), grid[3];
    ensure_rsm(b, vpls * BOUNCE_RSM_SCALE);
    place_probes(b, f, grid);
    ensure_probes(b, grid);
    draw_maps(b, ctx, f, b->rsm_size);
    build_vpls(b, vpls);
    gather_probes(b, ctx);
    b->host->log(b->host, SL_LOG_DEBUG, "%d virtual lights from %d directional lights, %d×%d×%d probes", b->vpl_count,
                 b->light_count, b->grid[0], b->grid[1], b->grid[2]);
}

/* ---- the light and its binding ------------------------------------------------------------------ */

static void bounce_begin_frame(void *user, const sl_frame *f) {
    (void)f;
    bounce *b = user;
    if (b->light < 0 || b->light_on) return;
    sl_plugin_light_state st = {.struct_size = sizeof st, .enabled = true, .direction = {0, -1, 0}, .color = {1, 1, 1},
                                .intensity = 1};
    b->light_on = b->host->set_light(b->host, b->light, &st);
}

static void bounce_bind(void *user, unsigned prog, int material, const sl_frame *f) {
    (void)material, (void)f;
    bounce *b = user;
    if (b->rsm_layer >= 0) { /* a map: the light it is drawn for */
        glUniform3fv(glGetUniformLocation(prog, "bounce_light_dir"), 1, b->rsm_dir[b->rsm_layer]);
        glUniform3fv(glGetUniformLocation(prog, "bounce_light_E"), 1, b->rsm_E[b->rsm_layer]);
        return;
    }
    int units[BOUNCE_PROBE_TEXTURES];
    for (int k = 0; k < BOUNCE_PROBE_TEXTURES; k++) glBindTextureUnit(b->unit_probe[k], b->probe[k]), units[k] = b->unit_probe[k];
    glUniform1iv(glGetUniformLocation(prog, "bounce_probe"), BOUNCE_PROBE_TEXTURES, units);
    glUniform3fv(glGetUniformLocation(prog, "bounce_box_min"), 1, b->box_min);
    glUniform3fv(glGetUniformLocation(prog, "bounce_box_max"), 1, b->box_max);
    float cell[3];
    for (int c = 0; c < 3; c++) cell[c] = (b->box_max[c] - b->box_min[c]) / (float)(b->grid[c] ? b->grid[c] : 1);
    glUniform3fv(glGetUniformLocation(prog, "bounce_cell"), 1, cell);
}

/* ---- lifecycle ---------------------------------------------------------------------------------- */

static sl_status bounce_create(const sl_host *host, void **user) {
    bounce *b = calloc(1, sizeof *b);
    if (!b) return SL_ERR_FAILED;
    *user = b;
    b->host = host, b->rsm_layer = -1;
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_shader_chunk_desc light = {.struct_size = sizeof light, .hook = SL_HOOK_LIGHT, .file = "bounce.glsl",
                                        .function = "bounce_radiance", .name = "indirect",
                                        .flags = SL_CHUNK_LIGHT_RADIANCE};
    if (host->add_shader_chunk(host, &light) != SL_OK) return SL_ERR_FAILED;
    const sl_shader_chunk_desc view = {.struct_size = sizeof view, .hook = SL_HOOK_DEBUG_VIEW, .file = "bounce.glsl",
                                       .function = "bounce_view", .name = "bounce",
                                       .description = "the light bounce adds alone (one bounce of the directional lights)"};
    if (host->add_shader_chunk(host, &view) != SL_OK) return SL_ERR_FAILED;
    if (host->set_bind_callback(host, bounce_bind, b) != SL_OK) return SL_ERR_FAILED;
    for (int k = 0; k < BOUNCE_PROBE_TEXTURES; k++)
        if ((b->unit_probe[k] = host->reserve_texture_unit(host)) < 0) return SL_ERR_FAILED;
    const sl_pass_desc pass = {.struct_size = sizeof pass, .name = "bounce", .stage = SL_STAGE_SHADOW + 50,
                               .execute = bounce_execute, .user = b,
                               .depends = SL_DEPENDS_LIGHTS | SL_DEPENDS_GEOMETRY | SL_DEPENDS_MATERIALS |
                                          SL_DEPENDS_OWN_PARAMS};
    if (host->add_pass(host, &pass) != SL_OK) return SL_ERR_FAILED;
    sl_plugin_light_desc d = {.struct_size = sizeof d, .name = "indirect", .type = "indirect"};
    b->light = host->add_light(host, &d);
    if (b->light < 0) {
        host->log(host, SL_LOG_ERROR, "could not add its light (needs SDK ABI 1.22)");
        return SL_ERR_FAILED;
    }
    return SL_OK;
}

static sl_status bounce_activate(void *user) {
    bounce *b = user;
    if (!sl_gl_load(b->host->gl_get_proc_address, NULL)) return SL_ERR_GL;
    glCreateFramebuffers(1, &b->rsm_fbo);
    glCreateFramebuffers(1, &b->probe_fbo);
    unsigned bufs[BOUNCE_PROBE_TEXTURES]; /* the maps write 3 of them, the gather all */
    for (int k = 0; k < BOUNCE_PROBE_TEXTURES; k++) bufs[k] = GL_COLOR_ATTACHMENT0 + k;
    glNamedFramebufferDrawBuffers(b->rsm_fbo, 3, bufs);
    glNamedFramebufferDrawBuffers(b->probe_fbo, BOUNCE_PROBE_TEXTURES, bufs);
    glCreateBuffers(1, &b->vpl_buffer);
    b->vpl_capacity = 0, b->vpl_count = 0;
    const int grid[3] = {2, 2, 2};
    ensure_probes(b, grid); /* zero until the pass runs */
    const float zero[4] = {0, 0, 0, 0};
    for (int k = 0; k < BOUNCE_PROBE_TEXTURES; k++) glClearTexImage(b->probe[k], 0, GL_RGBA, GL_FLOAT, zero);
    b->gather = b->host->load_program(b->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                  .vertex = "sl:fullscreen.vert",
                                                                  .fragment = "bounce_probes.frag"});
    b->light_on = false;
    return b->gather ? SL_OK : SL_ERR_FAILED;
}

static void bounce_deactivate(void *user) {
    bounce *b = user;
    free_rsm(b);
    glDeleteTextures(BOUNCE_PROBE_TEXTURES, b->probe);
    glDeleteTextures(BOUNCE_PROBE_TEXTURES, b->atlas);
    memset(b->probe, 0, sizeof b->probe);
    memset(b->atlas, 0, sizeof b->atlas);
    glDeleteFramebuffers(1, &b->rsm_fbo);
    glDeleteFramebuffers(1, &b->probe_fbo);
    glDeleteBuffers(1, &b->vpl_buffer);
    b->rsm_fbo = b->probe_fbo = b->vpl_buffer = 0;
    b->vpl_capacity = 0;
}

static void bounce_destroy(void *user) { free(user); }

static const sl_plugin_desc bounce_desc = {
    SL_PLUGIN_HEADER,
    .id = BOUNCE_ID,
    .version = "1.0.0",
    .description = "One bounce of diffuse indirect light from directional lights: reflective shadow maps gathered "
                   "into an order-1 spherical-harmonics irradiance probe grid, as the light bounce.indirect.",
    .create = bounce_create,
    .activate = bounce_activate,
    .begin_frame = bounce_begin_frame,
    .deactivate = bounce_deactivate,
    .destroy = bounce_destroy,
};
SL_DEFINE_PLUGIN(bounce_desc)
