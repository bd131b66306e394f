/* many-lights: 1 to 4096 point and spot lights with a finite range (ε cut-off), rendered by
 * four methods that give the same image (README.md):
 *   brute      the forward pass evaluates every light (with the cut-off): the reference loop
 *   deferred   a G-buffer pass (the materials' own surface hooks), then a full-screen lighting
 *              pass per material composed with that material's model code; every light per pixel
 *   tiled      deferred, with 16×16-pixel tiles culled against the tile's depth bounds
 *   clustered  forward+: froxels (Olsson et al. 2012) with a depth pre-pass
 * Built against the installed SDK only (extras/README.md); needs ABI 1.7 (LIGHT_LOOP hook,
 * draw_scene `fragment`/`fullscreen`). Culling runs on the CPU (ml_cull.h), the lists go to the
 * GPU in storage buffers (bindings 3-5, many_lights.glsl). */
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include <shadelab/shadelab.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "ml_cull.h"

#define ML_ID "many-lights"
enum { ML_BRUTE, ML_DEFERRED, ML_TILED, ML_CLUSTERED };

typedef struct ml {
    const sl_host *host;
    unsigned buf[3];         /* list spheres, cells, index */
    unsigned vao;            /* empty: the deferred pass's own full-screen triangle */
    sl_program *copy;
    int unit_prepass, unit_g[5], unit_color;
    unsigned tex_prepass, tex_g[5], tex_color;
    bool in_deferred;        /* inside the deferred lighting pass */
    bool prepass_ok;         /* the froxel pre-pass ran this frame */
    /* per frame */
    int n, nglobal, nranged, all_cell;
    float *r2;
    float (*wpos)[3];        /* world positions (the per-pixel range test's centres) */
    uint32_t *global;
    float (*vpos)[3];        /* view-space centres (x, y, d) of the range spheres */
    float (*cull)[4];        /* view-space sphere (x, y, d, radius) culled against cells: the range
                                sphere, or for a spot the bounding sphere of its lit cone sector */
    int gx, gy, gz, tile;
    float near_d, slope;
    uint32_t *cells;         /* 2 per cell */
    uint32_t *pairs; size_t pair_count, pair_cap; /* (cell, light) hits */
    uint32_t *index; size_t index_cap;
    float (*sph)[4]; size_t sph_cap;  /* per index entry: (world position, range²) */
    float *depth; size_t depth_cap;
    uint64_t frame_index;
} ml;

static const char *const methods[] = {"brute", "deferred", "tiled", "clustered", NULL};

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}
static const sl_param_desc params[] = {
    P(.id = "method", .type = SL_PARAM_ENUM, .enum_values = methods, .default_value = {.i = ML_CLUSTERED},
      .group = "many-lights",
      .description = "brute: every light per fragment (reference loop); deferred: G-buffer + full-screen lighting, "
                     "every light per pixel; tiled: deferred with 16x16 tiles culled by depth bounds; clustered: "
                     "forward+ with froxels and a depth pre-pass."),
    P(.id = "epsilon", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.01f}}, .min = 0, .max = 1, .step = 0.001f,
      .flags = SL_PARAM_QUALITY_KNOB, .group = "many-lights",
      .description = "Range cut-off: a point/spot light ends where its irradiance I/d^2 falls below epsilon x 1 W/m^2 "
                     "(r = sqrt(I_max/epsilon)); 0 = no cut-off (infinite range)."),
    P(.id = "tile_size", .type = SL_PARAM_INT, .default_value = {.i = 16}, .min = 4, .max = 128, .step = 4,
      .unit = "px", .group = "many-lights", .description = "tiled: tile size in pixels."),
    P(.id = "cluster_tile", .type = SL_PARAM_INT, .default_value = {.i = 16}, .min = 4, .max = 256, .step = 4,
      .unit = "px", .group = "many-lights", .description = "clustered: froxel footprint in pixels."),
    P(.id = "cluster_slices", .type = SL_PARAM_INT, .default_value = {.i = 24}, .min = 1, .max = 128, .step = 1,
      .group = "many-lights", .description = "clustered: depth slices, exponential in view distance."),
    P(.id = "spot_cone", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "many-lights",
      .description = "tiled, clustered: a spot is listed only in cells that also meet the bounding sphere of its "
                     "lit cone sector (off: its range sphere only). The image is the same either way."),
    P(.id = "prepass", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "many-lights",
      .description = "clustered: depth pre-pass; fragments behind it skip their light loop."),
};

static int method_of(ml *m) { return m->host->get_param(m->host, ML_ID ".method").i; }
static int iparam(ml *m, const char *id) {
    char full[96];
    snprintf(full, sizeof full, ML_ID ".%s", id);
    return m->host->get_param(m->host, full).i;
}

static ml_view view_of(const sl_frame *f) {
    ml_view v;
    memcpy(v.view, f->view, sizeof v.view);
    memcpy(v.proj, f->proj, sizeof v.proj);
    v.width = f->width, v.height = f->height;
    return v;
}

/* CPU time of this thread, ms: the culling's cost, logged at debug level (viewer -v) */
static double thread_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

static void upload(unsigned b, const void *data, size_t bytes) {
    static const uint32_t zero[2] = {0, 0};
    glNamedBufferData(b, bytes ? bytes : sizeof zero, bytes ? data : zero, GL_DYNAMIC_DRAW);
}

/* ranges and view-space centres of this frame's lights (sl_lights order) */
static void prepare_lights(ml *m, const sl_frame *f) {
    int count = 0;
    const sl_light_info *L = m->host->lights(m->host, &count);
    float eps = m->host->get_param(m->host, ML_ID ".epsilon").f[0];
    int n = 0;
    for (int i = 0; i < count; i++)
        if (L[i].enabled && L[i].index >= 0 && L[i].index + 1 > n) n = L[i].index + 1;
    m->n = n;
    m->r2 = realloc(m->r2, (n ? n : 1) * sizeof *m->r2);
    m->global = realloc(m->global, (n ? n : 1) * sizeof *m->global);
    m->vpos = realloc(m->vpos, (n ? n : 1) * sizeof *m->vpos);
    m->wpos = realloc(m->wpos, (n ? n : 1) * sizeof *m->wpos);
    m->cull = realloc(m->cull, (n ? n : 1) * sizeof *m->cull);
    for (int i = 0; i < n; i++) m->r2[i] = -1;
    ml_view v = view_of(f);
    bool cone = m->host->get_param(m->host, ML_ID ".spot_cone").b;
    for (int i = 0; i < count; i++) {
        if (!L[i].enabled || L[i].index < 0) continue;
        int j = L[i].index;
        bool spot = !strcmp(L[i].type, "spot"), ranged = eps > 0 && (spot || !strcmp(L[i].type, "point"));
        float r = ranged ? ml_range(L[i].color, eps) : -1;
        m->r2[j] = ranged ? r * r : -1;
        memcpy(m->wpos[j], L[i].position, sizeof m->wpos[j]);
        ml_to_view(&v, L[i].position, m->vpos[j]);
        memcpy(m->cull[j], m->vpos[j], sizeof m->vpos[j]);
        m->cull[j][3] = r;
        float c[3], R;
        /* a spot lights nothing beyond the reach of its fall-off (docs: sdk conventions, "Spot
         * lights"; packed keys params[0] = cone_angle°, inner°, falloff 0 linear / 1 gltf) */
        if (ranged && cone && spot && ml_spot_sphere(L[i].position, L[i].direction, r,
                                                     ml_spot_reach(L[i].params[0], L[i].params[2]), c, &R)) {
            ml_to_view(&v, c, m->cull[j]);
            m->cull[j][3] = R;
        }
    }
    m->nglobal = m->nranged = 0;
    for (int i = 0; i < n; i++)
        if (m->r2[i] < 0) m->global[m->nglobal++] = (uint32_t)i;
        else m->nranged++;
}

static void add_pair(ml *m, uint32_t cell, uint32_t light) {
    if (m->pair_count + 1 > m->pair_cap) {
        m->pair_cap = m->pair_cap ? 2 * m->pair_cap : 65536;
        m->pairs = realloc(m->pairs, m->pair_cap * 2 * sizeof *m->pairs);
    }
    m->pairs[2 * m->pair_count] = cell, m->pairs[2 * m->pair_count + 1] = light;
    m->pair_count++;
}

static int slice_of(const ml *m, float d) {
    if (d <= m->near_d) return 0;
    int k = (int)floorf(logf(d / m->near_d) * m->slope);
    return k < 0 ? 0 : k >= m->gz ? m->gz - 1 : k;
}

/* Index and sphere arrays: [lights without range | the cells' lists | every ranged light (cell
 * all_cell = ncell)], in ascending light order within each list (a counting sort of the
 * (cell, light) hits, found light by light), each entry with its light's (world position,
 * range²) beside it so that the shader's per-entry range test reads one vec4 (many_lights.glsl).
 * Cells are (first, count, d_lo, d_hi): the view-distance interval the list was culled for; a
 * fragment outside it (a cell no sample fell in, a surface the pre-pass did not draw) walks the
 * list of every ranged light instead. Brute force and deferred have no cells (ncell = 0). */
static void finish_lists(ml *m, int ncell, const float *dmin, const float *dmax) {
    size_t nc = (size_t)ncell + 1;
    m->cells = realloc(m->cells, 4 * nc * sizeof *m->cells);
    memset(m->cells, 0, 4 * nc * sizeof *m->cells);
    for (size_t p = 0; p < m->pair_count; p++) m->cells[4 * m->pairs[2 * p] + 1]++;
    m->cells[4 * ncell + 1] = (uint32_t)m->nranged;
    uint32_t at = (uint32_t)m->nglobal;
    for (int c = 0; c <= ncell; c++) m->cells[4 * c] = at, at += m->cells[4 * c + 1];
    if (at > m->index_cap) m->index_cap = at, m->index = realloc(m->index, at * sizeof *m->index);
    if (at > m->sph_cap) m->sph_cap = at, m->sph = realloc(m->sph, at * sizeof *m->sph);
    memcpy(m->index, m->global, m->nglobal * sizeof *m->index);
    uint32_t *fill = calloc(nc, sizeof *fill);
    for (size_t p = 0; p < m->pair_count; p++) {
        uint32_t c = m->pairs[2 * p];
        m->index[m->cells[4 * c] + fill[c]++] = m->pairs[2 * p + 1];
    }
    for (int i = 0; i < m->n; i++)
        if (m->r2[i] >= 0) m->index[m->cells[4 * ncell] + fill[ncell]++] = (uint32_t)i;
    free(fill);
    const float lo = 0, hi = INFINITY;
    for (int c = 0; c <= ncell; c++) {
        bool bounded = dmin && c < ncell;
        if (bounded && dmin[c] > dmax[c]) /* no sample: every ranged light (never an opaque fragment's) */
            m->cells[4 * c] = m->cells[4 * ncell], m->cells[4 * c + 1] = m->cells[4 * ncell + 1], bounded = false;
        memcpy(&m->cells[4 * c + 2], bounded ? &dmin[c] : &lo, 4);
        memcpy(&m->cells[4 * c + 3], bounded ? &dmax[c] : &hi, 4);
    }
    for (uint32_t k = 0; k < at; k++) {
        uint32_t i = m->index[k];
        m->sph[k][0] = m->wpos[i][0], m->sph[k][1] = m->wpos[i][1], m->sph[k][2] = m->wpos[i][2];
        m->sph[k][3] = m->r2[i];
    }
    m->all_cell = ncell;
    upload(m->buf[0], m->sph, at * sizeof *m->sph);
    upload(m->buf[1], m->cells, 4 * nc * sizeof *m->cells);
    upload(m->buf[2], m->index, at * sizeof *m->index);
}

/* Light lists per cell: tiles (gz = 1) or froxels (gz slices), each cell's box spanning the
 * view distances [dmin, dmax] of the samples in it when given (the G-buffer's or the pre-pass's
 * depth; dmin > dmax: no sample, not culled), else its whole slice. A light is listed in a cell
 * whose view-space box meets both its range sphere and its culling sphere (a spot's cone sector
 * bound, prepare_lights). */
static void build_cells(ml *m, const ml_view *v, float far_d, const float *dmin, const float *dmax) {
    int T = m->tile;
    m->pair_count = 0;
    for (int i = 0; i < m->n; i++) {
        if (m->r2[i] < 0) continue;
        const float *c = m->vpos[i], *q = m->cull[i];
        float r = sqrtf(m->r2[i]), R = q[3];
        if (q[2] + R < 0) continue; /* wholly behind the camera */
        int tx0 = 0, tx1 = m->gx - 1, ty0 = 0, ty1 = m->gy - 1;
        float x0, x1, y0, y1;
        if (ml_sphere_rect(v, q, R, 1e-4f, &x0, &x1, &y0, &y1)) {
            if (x1 < 0 || y1 < 0 || x0 > v->width || y0 > v->height) continue;
            tx0 = x0 < 0 ? 0 : (int)(x0 / T), tx1 = (int)(x1 / T);
            ty0 = y0 < 0 ? 0 : (int)(y0 / T), ty1 = (int)(y1 / T);
            if (tx1 >= m->gx) tx1 = m->gx - 1;
            if (ty1 >= m->gy) ty1 = m->gy - 1;
        }
        int k0 = 0, k1 = m->gz - 1;
        if (m->gz > 1) k0 = slice_of(m, q[2] - R), k1 = slice_of(m, q[2] + R);
        for (int k = k0; k <= k1; k++) {
            float d0 = 0, d1 = far_d;
            if (m->gz > 1) {
                d0 = k == 0 ? 0 : m->near_d * expf(k / m->slope);
                d1 = k == m->gz - 1 ? far_d : m->near_d * expf((k + 1) / m->slope);
            }
            for (int ty = ty0; ty <= ty1; ty++)
                for (int tx = tx0; tx <= tx1; tx++) {
                    int cell = (k * m->gy + ty) * m->gx + tx;
                    if (dmin) {
                        if (dmin[cell] > dmax[cell]) continue;
                        d0 = dmin[cell], d1 = dmax[cell];
                    }
                    float lo[3], hi[3];
                    float px1 = (tx + 1) * T > v->width ? v->width : (tx + 1) * T;
                    float py1 = (ty + 1) * T > v->height ? v->height : (ty + 1) * T;
                    ml_cell_box(v, (float)(tx * T), px1, (float)(ty * T), py1, d0, d1, lo, hi);
                    if (ml_sphere_box(q, R, lo, hi) && ml_sphere_box(c, r, lo, hi)) add_pair(m, (uint32_t)cell, (uint32_t)i);
                }
        }
    }
    finish_lists(m, m->gx * m->gy * m->gz, dmin, dmax);
}

/* the view-distance bounds of the samples of each cell from a depth texture (G-buffer or
 * pre-pass), widened by a relative 1e-4 (depth-buffer precision; a fragment outside its cell's
 * bounds falls back to every ranged light, so slack costs time, never a light) */
static float *depth_bounds(ml *m, const ml_view *v, unsigned tex) {
    int W = v->width, H = v->height, nt = m->gx * m->gy * m->gz, layer = m->gx * m->gy;
    size_t px = (size_t)W * H;
    if (px > m->depth_cap) m->depth_cap = px, m->depth = realloc(m->depth, px * sizeof *m->depth);
    glGetTextureImage(tex, 0, GL_DEPTH_COMPONENT, GL_FLOAT, (int)(px * sizeof *m->depth), m->depth);
    float *b = malloc(2 * (size_t)nt * sizeof *b);
    for (int t = 0; t < nt; t++) b[t] = INFINITY, b[nt + t] = -INFINITY;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float z = m->depth[(size_t)y * W + x];
            if (z >= 1.0f) continue;
            float dd = ml_depth_to_d(v, z);
            int t = (y / m->tile) * m->gx + x / m->tile;
            if (m->gz > 1) t += slice_of(m, dd) * layer;
            if (dd < b[t]) b[t] = dd;
            if (dd > b[nt + t]) b[nt + t] = dd;
        }
    for (int t = 0; t < nt; t++)
        if (b[t] <= b[nt + t]) b[t] *= 1 - 1e-4f, b[nt + t] *= 1 + 1e-4f;
    return b;
}

static void log_lists(ml *m, const char *what, double t0, double t1, double t2) {
    m->host->log(m->host, SL_LOG_DEBUG, "%s: %d x %d x %d cells, %zu list entries; CPU %.1f ms (depth bounds %.1f, lists %.1f)",
                 what, m->gx, m->gy, m->gz, m->pair_count, t2 - t0, t1 - t0, t2 - t1);
}

/* view distance range of the scene bounds: the froxels' near and far */
static void scene_depth_range(const sl_frame *f, const ml_view *v, float *near_d, float *far_d) {
    float lo = INFINITY, hi = 0;
    for (int k = 0; k < 8; k++) {
        float p[3] = {k & 1 ? f->scene_max[0] : f->scene_min[0], k & 2 ? f->scene_max[1] : f->scene_min[1],
                      k & 4 ? f->scene_max[2] : f->scene_min[2]}, q[3];
        ml_to_view(v, p, q);
        lo = fminf(lo, q[2]), hi = fmaxf(hi, q[2]);
    }
    if (!(hi > 0.2f)) hi = 0.2f;
    *far_d = hi;
    *near_d = fminf(fmaxf(lo, 0.1f), 0.5f * hi);
}

static void ml_begin_frame(void *user, const sl_frame *f) {
    ml *m = user;
    m->prepass_ok = false;
    prepare_lights(m, f);
    int method = method_of(m);
    if (method == ML_BRUTE || method == ML_DEFERRED) { /* no cells: the one list of every ranged light */
        m->gx = m->gy = m->gz = 1, m->tile = 1 << 20;
        m->pair_count = 0;
        finish_lists(m, 0, NULL, NULL);
    }
}

/* ---- passes ---- */

static bool plugin_on(ml *m) { return m->host->plugin_enabled(m->host, ML_ID); }
static bool clustered_active(void *user, const sl_frame *f) {
    (void)f;
    return plugin_on(user) && method_of(user) == ML_CLUSTERED;
}
static bool gbuffer_active(void *user, const sl_frame *f) {
    (void)f;
    int k = method_of(user);
    return plugin_on(user) && (k == ML_DEFERRED || k == ML_TILED);
}

/* clustered: the depth pre-pass, then the froxel lists */
static void clustered_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    ml *m = user;
    const sl_host *h = m->host;
    ml_view v = view_of(f);
    m->tile = iparam(m, "cluster_tile");
    m->gx = (f->width + m->tile - 1) / m->tile, m->gy = (f->height + m->tile - 1) / m->tile;
    m->gz = iparam(m, "cluster_slices");
    float far_d;
    scene_depth_range(f, &v, &m->near_d, &far_d);
    m->slope = m->gz / logf(far_d / m->near_d);
    if (m->host->get_param(m->host, ML_ID ".prepass").b) { /* (a bool: .b; reading .i here was 0, no pre-pass, before) */
        h->bind_outputs(h, ctx, 0);
        glDepthMask(GL_TRUE);
        glClearDepth(1.0);
        glClear(GL_DEPTH_BUFFER_BIT);
        sl_draw_scene_desc d = {.struct_size = sizeof d, .mode = SL_DRAW_DEPTH_ONLY, .cull = 1};
        memcpy(d.view, f->view, sizeof d.view);
        memcpy(d.proj, f->proj, sizeof d.proj);
        h->draw_scene(h, ctx, &d);
        m->tex_prepass = h->pass_texture(h, ctx, ML_ID ".depth");
        m->prepass_ok = true;
    }
    double t0 = thread_ms();
    /* the samples' depth bounds per froxel (Olsson et al. 2012: only occupied clusters are culled) */
    float *bounds = m->prepass_ok ? depth_bounds(m, &v, m->tex_prepass) : NULL;
    int nt = m->gx * m->gy * m->gz;
    double t1 = thread_ms();
    build_cells(m, &v, far_d, bounds, bounds ? bounds + nt : NULL);
    free(bounds);
    log_lists(m, "froxels", t0, t1, thread_ms());
}

/* deferred and tiled: the G-buffer; tiled: the tiles' depth bounds and lists */
static void gbuffer_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    ml *m = user;
    const sl_host *h = m->host;
    h->bind_outputs(h, ctx, 0);
    glDepthMask(GL_TRUE);
    glClearDepth(1.0);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    sl_draw_scene_desc d = {.struct_size = sizeof d, .mode = SL_DRAW_MATERIALS, .cull = 1, .fragment = "gbuffer.frag"};
    memcpy(d.view, f->view, sizeof d.view);
    memcpy(d.proj, f->proj, sizeof d.proj);
    h->draw_scene(h, ctx, &d);
    if (method_of(m) != ML_TILED) return;
    ml_view v = view_of(f);
    int W = f->width, H = f->height;
    m->tile = iparam(m, "tile_size");
    m->gx = (W + m->tile - 1) / m->tile, m->gy = (H + m->tile - 1) / m->tile, m->gz = 1;
    double t0 = thread_ms();
    float *bounds = depth_bounds(m, &v, h->pass_texture(h, ctx, ML_ID ".gdepth"));
    int nt = m->gx * m->gy;
    double t1 = thread_ms();
    build_cells(m, &v, 0, bounds, bounds + nt);
    free(bounds);
    log_lists(m, "tiles", t0, t1, thread_ms());
}

static void deferred_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    ml *m = user;
    const sl_host *h = m->host;
    static const char *const g[5] = {ML_ID ".g0", ML_ID ".g1", ML_ID ".g2", ML_ID ".g3", ML_ID ".g4"};
    for (int i = 0; i < 5; i++) m->tex_g[i] = h->pass_texture(h, ctx, g[i]);
    m->tex_color = h->pass_texture(h, ctx, "color");
    h->bind_outputs(h, ctx, 0);
    unsigned copy = h->program_id(h, m->copy);
    if (!copy) return;
    /* colour copy + material depth (copy.frag), then each material's lighting at its depth */
    glUseProgram(copy);
    glBindTextureUnit(m->unit_color, m->tex_color);
    glBindTextureUnit(m->unit_g[0], m->tex_g[0]);
    glUniform1i(glGetUniformLocation(copy, "many_lights_color"), m->unit_color);
    glUniform1i(glGetUniformLocation(copy, "many_lights_g0"), m->unit_g[0]);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(m->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    m->in_deferred = true;
    sl_draw_scene_desc d = {.struct_size = sizeof d, .mode = SL_DRAW_MATERIALS, .fragment = "deferred.frag",
                            .fullscreen = true};
    memcpy(d.view, f->view, sizeof d.view);
    memcpy(d.proj, f->proj, sizeof d.proj);
    h->draw_scene(h, ctx, &d);
    m->in_deferred = false;
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
}

/* every composed program holding the light loop (forward, G-buffer, deferred lighting) */
static void ml_bind(void *user, unsigned prog, int material, const sl_frame *f) {
    (void)f;
    ml *m = user;
    int method = method_of(m), mode = 1;
    if (method == ML_CLUSTERED) mode = 2;
    if (method == ML_DEFERRED || method == ML_TILED) mode = m->in_deferred ? (method == ML_TILED ? 3 : 1) : 0;
    glUniform1i(glGetUniformLocation(prog, "many_lights_mode"), mode);
    glUniform1i(glGetUniformLocation(prog, "many_lights_global"), m->nglobal);
    glUniform1i(glGetUniformLocation(prog, "many_lights_all"), m->all_cell);
    glUniform2i(glGetUniformLocation(prog, "many_lights_grid"), m->gx, m->gy);
    glUniform2i(glGetUniformLocation(prog, "many_lights_grid_zt"), m->gz, m->tile);
    glUniform2f(glGetUniformLocation(prog, "many_lights_slices"), m->near_d, m->slope);
    glUniform1i(glGetUniformLocation(prog, "many_lights_material"), material);
    bool pre = mode == 2 && m->prepass_ok;
    glUniform1i(glGetUniformLocation(prog, "many_lights_use_prepass"), pre);
    glUniform1i(glGetUniformLocation(prog, "many_lights_prepass_depth"), m->unit_prepass);
    if (pre) glBindTextureUnit(m->unit_prepass, m->tex_prepass);
    if (m->in_deferred) {
        static const char *const names[5] = {"many_lights_g0", "many_lights_g1", "many_lights_g2", "many_lights_g3",
                                             "many_lights_g4"};
        for (int i = 0; i < 5; i++) {
            glBindTextureUnit(m->unit_g[i], m->tex_g[i]);
            glUniform1i(glGetUniformLocation(prog, names[i]), m->unit_g[i]);
        }
        glBindTextureUnit(m->unit_color, m->tex_color);
        glUniform1i(glGetUniformLocation(prog, "many_lights_color"), m->unit_color);
    }
    for (int i = 0; i < 3; i++) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3 + i, m->buf[i]);
}

static sl_status ml_create(const sl_host *host, void **user) {
    ml *m = calloc(1, sizeof *m);
    *user = m;
    m->host = host;
    m->gx = m->gy = m->gz = 1, m->tile = 1 << 20, m->near_d = 1, m->slope = 1;
    if (host->abi_major != 1 || host->abi_minor < 7) {
        host->log(host, SL_LOG_ERROR, "needs a host with ABI 1.7 (LIGHT_LOOP hook), this one has %u.%u",
                  host->abi_major, host->abi_minor);
        return SL_ERR_FAILED;
    }
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_shader_chunk_desc chunks[] = {
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_LIGHT_LOOP, .file = "many_lights.glsl",
         .function = "many_lights_loop"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_DEBUG_VIEW, .file = "many_lights.glsl",
         .function = "many_lights_count_view", .name = "many-lights-count",
         .description = "r: lights in this pixel's tile/cluster list, g: lights within range here, b: lights with a range"},
    };
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
    static const sl_target_desc depth_out[] = {{.name = ML_ID ".depth", .format = SL_FORMAT_DEPTH32F}};
    static const sl_target_desc gbuf_out[] = {
        {.name = ML_ID ".g0", .format = SL_FORMAT_RGBA32F}, {.name = ML_ID ".g1", .format = SL_FORMAT_RGBA16F},
        {.name = ML_ID ".g2", .format = SL_FORMAT_RGBA16F}, {.name = ML_ID ".g3", .format = SL_FORMAT_RGBA16F},
        {.name = ML_ID ".g4", .format = SL_FORMAT_R32F}, {.name = ML_ID ".gdepth", .format = SL_FORMAT_DEPTH32F}};
    static const char *const deferred_in[] = {"color", ML_ID ".g0", ML_ID ".g1", ML_ID ".g2", ML_ID ".g3", ML_ID ".g4", NULL};
    static const sl_target_desc color_out[] = {{.name = "color", .format = SL_FORMAT_RGBA16F},
                                               {.name = ML_ID ".matdepth", .format = SL_FORMAT_DEPTH32F}};
    const sl_pass_desc passes[] = {
        {.struct_size = sizeof(sl_pass_desc), .name = "many-lights-clusters", .stage = SL_STAGE_PREPASS + 50,
         .outputs = depth_out, .output_count = 1, .execute = clustered_execute, .is_active = clustered_active, .user = m,
         .depends = SL_DEPENDS_CAMERA | SL_DEPENDS_GEOMETRY | SL_DEPENDS_LIGHTS | SL_DEPENDS_MATERIALS},
        {.struct_size = sizeof(sl_pass_desc), .name = "many-lights-gbuffer", .stage = SL_STAGE_PREPASS + 50,
         .outputs = gbuf_out, .output_count = 6, .execute = gbuffer_execute, .is_active = gbuffer_active, .user = m,
         .depends = SL_DEPENDS_CAMERA | SL_DEPENDS_GEOMETRY | SL_DEPENDS_MATERIALS},
        {.struct_size = sizeof(sl_pass_desc), .name = "many-lights-deferred", .stage = SL_STAGE_OPAQUE + 50,
         .inputs = deferred_in, .outputs = color_out, .output_count = 2, .execute = deferred_execute,
         .is_active = gbuffer_active, .user = m, .depends = SL_DEPENDS_EVERY_FRAME}, /* writes "color" */
    };
    for (size_t i = 0; i < sizeof passes / sizeof *passes; i++)
        if (host->add_pass(host, &passes[i]) != SL_OK) return SL_ERR_FAILED;
    if (host->set_bind_callback(host, ml_bind, m) != SL_OK) return SL_ERR_FAILED;
    if ((m->unit_prepass = host->reserve_texture_unit(host)) < 0) return SL_ERR_FAILED;
    for (int i = 0; i < 5; i++)
        if ((m->unit_g[i] = host->reserve_texture_unit(host)) < 0) return SL_ERR_FAILED;
    if ((m->unit_color = host->reserve_texture_unit(host)) < 0) return SL_ERR_FAILED;
    const sl_reference_desc ref = {
        .struct_size = sizeof ref, .settings = ML_ID ".method=brute " ML_ID ".epsilon=0", .accumulate_frames = 1,
        .description = "Every light at every fragment without a range cut-off (epsilon = 0): the exact sum"};
    return host->set_reference(host, &ref);
}

static sl_status ml_activate(void *user) {
    ml *m = user;
    if (!sl_gl_load(m->host->gl_get_proc_address, NULL)) return SL_ERR_GL;
    glCreateBuffers(3, m->buf);
    glCreateVertexArrays(1, &m->vao);
    for (int i = 0; i < 3; i++) upload(m->buf[i], NULL, 0);
    m->copy = m->host->load_program(m->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                  .vertex = "sl:fullscreen.vert", .fragment = "copy.frag"});
    return m->copy ? SL_OK : SL_ERR_FAILED;
}

static void ml_deactivate(void *user) {
    ml *m = user;
    glDeleteBuffers(3, m->buf);
    glDeleteVertexArrays(1, &m->vao);
    m->vao = 0;
    memset(m->buf, 0, sizeof m->buf);
}

static void ml_destroy(void *user) {
    ml *m = user;
    if (!m) return;
    free(m->r2), free(m->global), free(m->vpos), free(m->wpos), free(m->cull), free(m->cells), free(m->pairs);
    free(m->index), free(m->sph), free(m->depth);
    free(m);
}

static const sl_plugin_desc ml_desc = {
    SL_PLUGIN_HEADER,
    .id = ML_ID,
    .version = "1.0.0",
    .description = "Many point and spot lights with a finite range: brute force, deferred, tiled deferred (16x16 "
                   "tiles, depth bounds) and clustered forward (froxels, depth pre-pass).",
    .create = ml_create,
    .activate = ml_activate,
    .begin_frame = ml_begin_frame,
    .deactivate = ml_deactivate,
    .destroy = ml_destroy,
};
SL_DEFINE_PLUGIN(ml_desc)
