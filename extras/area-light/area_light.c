/* area-light: rectangle and disk lights (light type "area"), one- or two-sided, shaded with
 * linearly transformed cosines (Heitz, Dupuy, Hill, Neubelt 2016) for every model's lobes and with
 * Lambert's exact polygon formula for the diffuse; a Monte Carlo reference over the light's surface.
 * Built against the installed SDK only (extras/README.md). See README.md.
 *
 *   light keys   light.NAME.width, height (m), shape (rect/disk), two_sided, axis (width direction)
 *   globals      area-light.method (ltc/reference), disk_segments (knob), reference_samples
 *   material     fresnel, eta, metallic: the ggx plugin's Fresnel inputs, declared here too (a
 *                shared material vocabulary) so the LTC's Fresnel follows the material
 *   data         ltc_ggx.txt and ltc_blinn_phong.txt beside the module (made by ltc_fit, command
 *                in their headers); the Blinn-Phong table's texture is made at the first bind of
 *                a program that reads it (a material with a Blinn-Phong lobe) */
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include <shadelab/shadelab.h>
#include <shadelab/matrix.h>
#include "ltc.h"

#define AL_ID "area-light"

/* Emission textures (Heitz et al. 2016, §5.3 "textured lights"): an area light named N takes the
 * emissive_map of the material named N (when the scene has one), prefiltered here into the
 * levels of one layer of a 2D array (al_prefilter); the shader fetches it where the shading
 * point's orthogonal projection meets the (LTC-transformed) light plane, at a level set by the
 * distance to that plane over the light's size. */
#define AL_MAX_TEX 4     /* textured lights at once (more: the rest are untextured, with a warning) */
#define AL_TEX_SIZE 256  /* the texture is resampled to this many texels a side */
#define AL_TEX_BORDER 64 /* texels of prefiltered border each side (lookups outside the light) */
#define AL_TEX_DIM (AL_TEX_SIZE + 2 * AL_TEX_BORDER)
#define AL_TEX_LEVELS 9  /* 384, 192, … 1 texels a side */

typedef struct al_tex_slot {
    char name[64];       /* the light's name */
    unsigned source;     /* the core's GL texture it was made from (0: free) */
    float position[3], direction[3];
} al_tex_slot;

/* The reference's visibility (README "Reference"): each accumulated frame, one point on each area
 * light (a Hammersley set over the frames being accumulated) and a depth cube map from it (six
 * 90° views, layers 6·slot … 6·slot + 5 of one 2D array); the shading sees that point only. */
#define AL_MAX_SHADOW 4
typedef struct al_shadow_slot {
    bool used;
    float position[3], direction[3]; /* the light's key, as for textures */
    float point[3], uv[2];           /* the light point of this frame and its (u, v) on the light */
    float near_plane, far_plane;
} al_shadow_slot;

typedef struct area_light {
    const sl_host *host;
    unsigned shadow_tex, shadow_fbo;
    int shadow_size, shadow_layers, unit_s;
    al_shadow_slot shadows[AL_MAX_SHADOW];
    al_ltc_table table, blinn_table;  /* GGX; the contract's Blinn-Phong lobe (ABI 1.19) */
    unsigned tex_m, tex_n, tex_e, tex_blinn;
    int unit_m, unit_n, unit_e, unit_blinn;
    al_tex_slot slots[AL_MAX_TEX];
    bool warned_many;
} area_light;

static const char *const methods[] = {"ltc", "reference", NULL};
static const char *const shapes[] = {"rect", "disk", NULL};
static const char *const fresnel_modes[] = {"exact", "schlick", "metallic-roughness", NULL}; /* as ggx */

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}
static const sl_param_desc params[] = {
    P(.id = "method", .type = SL_PARAM_ENUM, .enum_values = methods, .flags = SL_PARAM_NEEDS_RECOMPILE,
      .group = "area-light", .description = "ltc: linearly transformed cosines (real time); reference: Monte Carlo over "
                                            "the light's surface with the model's exact BRDF, accumulated (no visibility)."),
    P(.id = "disk_segments", .type = SL_PARAM_INT, .default_value = {.i = 16}, .min = 4, .max = 64, .step = 1,
      .flags = SL_PARAM_NEEDS_RECOMPILE | SL_PARAM_QUALITY_KNOB, .group = "area-light",
      .description = "Disk lights are integrated as a regular polygon of this many vertices with the disk's area."),
    P(.id = "reference_visibility", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .flags = SL_PARAM_NEEDS_RECOMPILE,
      .group = "area-light", .description = "Reference: shadowed. One point per light and accumulated frame (a Hammersley set "
                                            "over the frames), seen through a depth cube map rendered from it; off: "
                                            "reference_samples² unshadowed points per pixel and frame."),
    P(.id = "reference_map_size", .type = SL_PARAM_INT, .default_value = {.i = 1024}, .min = 64, .max = 4096, .step = 64,
      .group = "area-light", .description = "Reference with visibility: width = height of each cube face (texels)."),
    P(.id = "reference_samples", .type = SL_PARAM_INT, .default_value = {.i = 4}, .min = 1, .max = 16, .step = 1,
      .flags = SL_PARAM_NEEDS_RECOMPILE, .group = "area-light",
      .description = "Reference without visibility: n×n stratified points on each light per pixel and frame."),
    /* light keys of type "area" */
    P(.id = "width", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_LIGHT, .light_type = "area", .light_slot = 0,
      .default_value = {.f = {1}}, .min = 0, .max = 1000, .step = 0.01f, .unit = "m", .group = "area light",
      .description = "Extent along axis (disk: the diameter along axis)."),
    P(.id = "height", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_LIGHT, .light_type = "area", .light_slot = 1,
      .default_value = {.f = {1}}, .min = 0, .max = 1000, .step = 0.01f, .unit = "m", .group = "area light",
      .description = "Extent along direction × axis (disk: the other diameter)."),
    P(.id = "shape", .type = SL_PARAM_ENUM, .scope = SL_SCOPE_LIGHT, .light_type = "area", .light_slot = 2,
      .enum_values = shapes, .group = "area light", .description = "rect: a rectangle; disk: an ellipse (a disk when width = height)."),
    P(.id = "two_sided", .type = SL_PARAM_BOOL, .scope = SL_SCOPE_LIGHT, .light_type = "area", .light_slot = 3,
      .group = "area light", .description = "Emit from both faces (one-sided: only along direction)."),
    P(.id = "axis", .type = SL_PARAM_VEC3, .scope = SL_SCOPE_LIGHT, .light_type = "area", .light_slot = 4,
      .default_value = {.f = {1, 0, 0}}, .group = "area light",
      .description = "Direction of the width side (made orthogonal to direction)."),
    /* the ggx plugin's Fresnel inputs (shared material vocabulary, same types and values) */
    P(.id = "eta", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1.0f / 1.5f}},
      .min = 0.05f, .max = 20, .step = 0.01f, .group = "ggx", .description = "Relative index of refraction η = n1/n2 (air over glass: 1/1.5)."),
    P(.id = "fresnel", .type = SL_PARAM_ENUM, .scope = SL_SCOPE_MATERIAL, .enum_values = fresnel_modes,
      .flags = SL_PARAM_NEEDS_RECOMPILE, .group = "ggx",
      .description = "exact dielectric Fresnel, Schlick, or glTF metallic-roughness (F0 = mix(0.04, base, metallic))."),
    P(.id = "metallic", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = 0, .max = 1, .step = 0.01f,
      .group = "ggx", .description = "Metalness for fresnel = metallic-roughness."),
};

/* Prefilter (Heitz et al. 2016 §5.3): level k of the layer holds the texture T convolved with a
 * Gaussian of σ_k = 2^(k−1) texels of the 256² texture (level 0: T itself), over an extended
 * domain of AL_TEX_BORDER texels beyond each edge, as a *normalised* convolution restricted to
 * the light: (G ∗ T·1_light) / (G ∗ 1_light). A constant texture therefore stays exactly that
 * constant at every level and position (no darkening at the edges), and a lookup outside the
 * light sees the nearby edge's average. The mask of a rectangle is separable, so the 2-D
 * normalised convolution is the 1-D one along x, then along y (the x-normalisation depends on
 * x only and factors out of the y pass). Weights are taken relative to the nearest texel of the
 * light, so points far outside do not underflow. */
static void al_conv1d(const double *in, int n_in, double *out, int n_out, double scale, double sigma, int count) {
    /* output sample i sits at level-0 coordinate x = (i + 0.5)·scale − BORDER (texel centres) */
    for (int c = 0; c < count; c++)
        for (int i = 0; i < n_out; i++) {
            double x = (i + 0.5) * scale - AL_TEX_BORDER, acc[4] = {0}, wsum = 0;
            double xc = x < 0.5 ? 0.5 : x > n_in - 0.5 ? n_in - 0.5 : x; /* nearest point of the light */
            int lo = 0, hi = n_in - 1;
            if (sigma > 0) {
                int r = (int)ceil(4 * sigma) + 1;
                lo = (int)floor(xc - 0.5) - r, hi = (int)floor(xc - 0.5) + r;
                if (lo < 0) lo = 0;
                if (hi > n_in - 1) hi = n_in - 1;
            } else {
                lo = hi = (int)floor(xc - 0.5) < 0 ? 0 : (int)floor(xc - 0.5) > n_in - 1 ? n_in - 1 : (int)floor(xc - 0.5);
            }
            double d0 = x - xc;
            for (int j = lo; j <= hi; j++) {
                double d = x - (j + 0.5), w = sigma > 0 ? exp(-(d * d - d0 * d0) / (2 * sigma * sigma)) : 1;
                const double *q = in + ((size_t)c * n_in + j) * 4;
                for (int ch = 0; ch < 4; ch++) acc[ch] += w * q[ch];
                wsum += w;
            }
            double *o = out + ((size_t)c * n_out + i) * 4;
            for (int ch = 0; ch < 4; ch++) o[ch] = acc[ch] / wsum;
        }
}

static void al_prefilter_upload(area_light *a, int layer, unsigned source) {
    int w = 0, h = 0;
    glGetTextureLevelParameteriv(source, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(source, 0, GL_TEXTURE_HEIGHT, &h);
    if (w <= 0 || h <= 0 || w > 16384 || h > 16384) return;
    float *src = malloc(sizeof(float) * 4 * (size_t)w * h);
    glGetTextureImage(source, 0, GL_RGBA, GL_FLOAT, (GLsizei)(sizeof(float) * 4 * (size_t)w * h), src);
    const int S = AL_TEX_SIZE;
    /* resample to S×S: the mean of 4×4 nearest-texel samples per texel (row 0 = v = 0) */
    double *t = calloc((size_t)S * S * 4, sizeof(double));
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++)
            for (int sy = 0; sy < 4; sy++)
                for (int sx = 0; sx < 4; sx++) {
                    int ix = (int)((x + (sx + 0.5) / 4) / S * w), iy = (int)((y + (sy + 0.5) / 4) / S * h);
                    const float *p = src + ((size_t)iy * w + ix) * 4;
                    for (int c = 0; c < 3; c++) t[((size_t)y * S + x) * 4 + c] += (isfinite(p[c]) && p[c] > 0 ? p[c] : 0) / 16;
                }
    free(src);
    /* each level: the rows along x (S runs of S texels → n), transposed, then along y */
    for (int k = 0, n = AL_TEX_DIM; k < AL_TEX_LEVELS && n >= 1; k++, n /= 2) {
        double scale = (double)AL_TEX_DIM / n, sigma = k == 0 ? 0 : 0.5 * (double)(1 << k);
        double *rows = malloc(sizeof(double) * 4 * (size_t)S * n);     /* S rows × n */
        al_conv1d(t, S, rows, n, scale, sigma, S);
        double *cols = malloc(sizeof(double) * 4 * (size_t)S * n);     /* n columns × S */
        for (int y = 0; y < S; y++)
            for (int x = 0; x < n; x++) memcpy(cols + ((size_t)x * S + y) * 4, rows + ((size_t)y * n + x) * 4, 4 * sizeof(double));
        double *res = malloc(sizeof(double) * 4 * (size_t)n * n);      /* n columns × n */
        al_conv1d(cols, S, res, n, scale, sigma, n);
        float *lvl = malloc(sizeof(float) * 4 * (size_t)n * n);
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++)
                for (int c = 0; c < 4; c++) lvl[((size_t)y * n + x) * 4 + c] = c == 3 ? 1.0f : (float)res[((size_t)x * n + y) * 4 + c];
        glTextureSubImage3D(a->tex_e, k, 0, 0, layer, n, n, 1, GL_RGBA, GL_FLOAT, lvl);
        free(rows), free(cols), free(res), free(lvl);
    }
    free(t);
}

/* The emission texture of light `name`: the emissive_map the core loaded for the material of the
 * same name, or 0. */
static unsigned al_light_texture(const sl_host *h, const char *name) {
    if (!name) return 0;
    for (int m = 0; m < h->material_count(h); m++)
        if (!strcmp(h->material_name(h, m), name)) return h->material_texture(h, m, "emissive_map");
    return 0;
}

/* Keep the textured lights' slots current: a slot is (re)built when its light's texture changes;
 * the key (position, direction) is refreshed every call, as lights move. */
static void al_update_textures(area_light *a) {
    int n = 0;
    const sl_light_info *lights = a->host->lights(a->host, &n);
    bool used[AL_MAX_TEX] = {0};
    for (int i = 0; i < n; i++) {
        const sl_light_info *L = &lights[i];
        if (!L->enabled || !L->type || strcmp(L->type, "area") || L->index < 0) continue;
        unsigned tex = al_light_texture(a->host, L->name);
        if (!tex) continue;
        int k = -1;
        for (int j = 0; j < AL_MAX_TEX && k < 0; j++)
            if (!used[j] && a->slots[j].source == tex && !strcmp(a->slots[j].name, L->name)) k = j;
        if (k < 0) /* a new or changed texture: the first slot no light of this frame holds */
            for (int j = 0; j < AL_MAX_TEX && k < 0; j++)
                if (!used[j] && !(a->slots[j].source && al_light_texture(a->host, a->slots[j].name) == a->slots[j].source &&
                                  strcmp(a->slots[j].name, L->name)))
                    k = j;
        if (k < 0) {
            if (!a->warned_many)
                a->host->log(a->host, SL_LOG_WARN, "more than %d textured area lights: light '%s' is shaded untextured",
                             AL_MAX_TEX, L->name);
            a->warned_many = true;
            continue;
        }
        al_tex_slot *sl = &a->slots[k];
        if (sl->source != tex || strcmp(sl->name, L->name)) {
            snprintf(sl->name, sizeof sl->name, "%s", L->name);
            sl->source = tex;
            al_prefilter_upload(a, k, tex);
        }
        used[k] = true;
        memcpy(sl->position, L->position, sizeof sl->position);
        memcpy(sl->direction, L->direction, sizeof sl->direction);
    }
    for (int j = 0; j < AL_MAX_TEX; j++)
        if (!used[j]) a->slots[j].source = 0, a->slots[j].name[0] = 0;
}

/* A table as an RGBA32F texture, bilinear between entries: M⁻¹ (a, b, c, d), or with `magnitudes`
 * (norm, fresnel, 0, 0). Unpacks from client memory whatever buffer a pass left bound (the
 * Blinn-Phong table is made during the forward pass). */
static unsigned al_table_texture(const al_ltc_table *t, bool magnitudes) {
    int N = t->size, unpack = 0;
    float *data = malloc(sizeof(float) * 4 * N * N);
    for (int k = 0; k < N * N; k++) {
        const al_ltc_entry *e = &t->e[k];
        float m[4] = {(float)e->a, (float)e->b, (float)e->c, (float)e->d}, n[4] = {(float)e->norm, (float)e->fresnel, 0, 0};
        memcpy(data + 4 * k, magnitudes ? n : m, sizeof m);
    }
    unsigned tex;
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpack);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA32F, N, N);
    glTextureSubImage2D(tex, 0, 0, 0, N, N, GL_RGBA, GL_FLOAT, data);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, (unsigned)unpack);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    free(data);
    return tex;
}

static void al_bind(void *user, unsigned program, int material, const sl_frame *frame) {
    (void)material, (void)frame;
    area_light *a = user;
    al_update_textures(a);
    float keys[AL_MAX_TEX * 8] = {0};
    int count = 0;
    for (int j = 0; j < AL_MAX_TEX; j++) {
        const al_tex_slot *sl = &a->slots[j];
        float *k = keys + 8 * j;
        k[3] = sl->source ? 1.0f : 0.0f; /* w = 1: in use (position, used) (direction, -) */
        memcpy(k, sl->position, 3 * sizeof(float));
        memcpy(k + 4, sl->direction, 3 * sizeof(float));
        if (sl->source) count = j + 1;
    }
    glUniform4fv(glGetUniformLocation(program, "area_light_tex_key"), 2 * AL_MAX_TEX, keys);
    glUniform1i(glGetUniformLocation(program, "area_light_tex_count"), count);
    glUniform1i(glGetUniformLocation(program, "area_light_tex"), a->unit_e);
    glBindTextureUnit(a->unit_e, a->tex_e);
    float skeys[AL_MAX_SHADOW * 8] = {0}, spoint[AL_MAX_SHADOW * 4] = {0}, suv[AL_MAX_SHADOW * 4] = {0};
    int scount = 0;
    for (int j = 0; j < AL_MAX_SHADOW; j++) {
        const al_shadow_slot *sh = &a->shadows[j];
        if (!sh->used) continue;
        memcpy(skeys + 8 * j, sh->position, 3 * sizeof(float));
        skeys[8 * j + 3] = 1;
        memcpy(skeys + 8 * j + 4, sh->direction, 3 * sizeof(float));
        memcpy(spoint + 4 * j, sh->point, 3 * sizeof(float));
        spoint[4 * j + 3] = sh->near_plane;
        suv[4 * j] = sh->uv[0], suv[4 * j + 1] = sh->uv[1], suv[4 * j + 2] = sh->far_plane, suv[4 * j + 3] = (float)a->shadow_size;
        scount = j + 1;
    }
    glUniform4fv(glGetUniformLocation(program, "area_light_shadow_key"), 2 * AL_MAX_SHADOW, skeys);
    glUniform4fv(glGetUniformLocation(program, "area_light_shadow_point"), AL_MAX_SHADOW, spoint);
    glUniform4fv(glGetUniformLocation(program, "area_light_shadow_uv"), AL_MAX_SHADOW, suv);
    glUniform1i(glGetUniformLocation(program, "area_light_shadow_count"), scount);
    glUniform1i(glGetUniformLocation(program, "area_light_shadow"), a->unit_s);
    glBindTextureUnit(a->unit_s, a->shadow_tex ? a->shadow_tex : a->tex_e);
    int blinn = glGetUniformLocation(program, "area_light_ltc_blinn"); /* a material with a Blinn-Phong lobe */
    if (blinn >= 0) {
        if (!a->tex_blinn) {
            a->tex_blinn = al_table_texture(&a->blinn_table, false);
            a->host->log(a->host, SL_LOG_DEBUG, "made the Blinn-Phong LTC table (%d², a material has a Blinn-Phong lobe)",
                         a->blinn_table.size);
        }
        glUniform1i(blinn, a->unit_blinn);
        glUniform1f(glGetUniformLocation(program, "area_light_ltc_blinn_size"), (float)a->blinn_table.size);
        glBindTextureUnit(a->unit_blinn, a->tex_blinn);
    }
    glUniform1i(glGetUniformLocation(program, "area_light_ltc_m"), a->unit_m);
    glUniform1i(glGetUniformLocation(program, "area_light_ltc_n"), a->unit_n);
    glUniform1f(glGetUniformLocation(program, "area_light_ltc_size"), (float)a->table.size);
    glBindTextureUnit(a->unit_m, a->tex_m);
    glBindTextureUnit(a->unit_n, a->tex_n);
}

/* ---- the reference's visibility ----------------------------------------------------------- */
static sl_value al_param(area_light *a, const char *id) {
    char full[96];
    snprintf(full, sizeof full, AL_ID ".%s", id);
    return a->host->get_param(a->host, full);
}
static bool al_visibility_on(area_light *a) {
    return al_param(a, "method").i == 1 && al_param(a, "reference_visibility").b;
}
static bool al_is_area(const sl_light_info *L) {
    return L->enabled && L->index >= 0 && L->type && !strcmp(L->type, "area");
}

static bool al_shadow_active(void *user, const sl_frame *f) {
    (void)f;
    area_light *a = user;
    if (!al_visibility_on(a)) return false;
    int n = 0;
    const sl_light_info *lights = a->host->lights(a->host, &n);
    for (int i = 0; i < n; i++)
        if (al_is_area(&lights[i])) return true;
    return false;
}

static uint64_t al_fnv(const void *data, size_t len, uint64_t h) {
    const unsigned char *p = data;
    for (size_t i = 0; i < len; i++) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

static uint64_t al_shadow_signature(void *user, const sl_frame *f) {
    area_light *a = user;
    uint64_t h = 1469598103934665603ull;
    int n = 0;
    const sl_light_info *lights = a->host->lights(a->host, &n);
    for (int i = 0; i < n; i++) {
        if (!al_is_area(&lights[i])) continue;
        h = al_fnv(lights[i].position, sizeof lights[i].position, h);
        h = al_fnv(lights[i].direction, sizeof lights[i].direction, h);
        h = al_fnv(lights[i].params, sizeof lights[i].params, h);
    }
    int v[3] = {al_param(a, "reference_map_size").i, f->accumulate_index, f->accumulate_count};
    h = al_fnv(v, sizeof v, h);
    h = al_fnv(f->scene_min, sizeof f->scene_min, h);
    h = al_fnv(f->scene_max, sizeof f->scene_max, h);
    return al_fnv(&f->geometry_version, sizeof f->geometry_version, h);
}

/* The cube faces: view axis and up vector (the GLSL's area_light_face has the same table). */
static const float al_face_axis[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
static const float al_face_up[6][3] = {{0, 1, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 1}, {0, 1, 0}, {0, 1, 0}};


/* Radical inverse in base 2 (van der Corput): the second coordinate of the Hammersley set. */
static double al_radical_inverse(unsigned k) {
    double r = 0, f = 0.5;
    for (; k; k >>= 1, f *= 0.5)
        if (k & 1) r += f;
    return r;
}

static void al_shadow_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    area_light *a = user;
    const sl_host *host = a->host;
    int size = al_param(a, "reference_map_size").i, n = 0;
    if (size != a->shadow_size || !a->shadow_tex) {
        if (a->shadow_tex) glDeleteTextures(1, &a->shadow_tex);
        glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &a->shadow_tex);
        glTextureStorage3D(a->shadow_tex, 1, GL_DEPTH_COMPONENT32F, size, size, 6 * AL_MAX_SHADOW);
        glTextureParameteri(a->shadow_tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(a->shadow_tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(a->shadow_tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(a->shadow_tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTextureParameteri(a->shadow_tex, GL_TEXTURE_COMPARE_MODE, GL_NONE);
        a->shadow_size = size;
    }
    /* this frame's point: Hammersley point k of N (u = (k + ½)/N, v = the radical inverse of k,
     * shifted by half its smallest step), so the frames of an accumulation cover the light evenly */
    int N = f->accumulate_count > 1 ? f->accumulate_count : 1, k = f->accumulate_index % N;
    unsigned P = 1;
    while (P < (unsigned)N) P <<= 1;
    double u = (k + 0.5) / N, v = al_radical_inverse((unsigned)k) + 0.5 / P;
    double diag = 0;
    for (int c = 0; c < 3; c++) diag += (double)(f->scene_max[c] - f->scene_min[c]) * (f->scene_max[c] - f->scene_min[c]);
    diag = sqrt(diag);
    const sl_light_info *lights = host->lights(host, &n);
    memset(a->shadows, 0, sizeof a->shadows);
    int slot = 0;
    float one = 1.0f;
    for (int i = 0; i < n && slot < AL_MAX_SHADOW; i++) {
        const sl_light_info *L = &lights[i];
        if (!al_is_area(L)) continue;
        al_shadow_slot *sh = &a->shadows[slot];
        sh->used = true;
        memcpy(sh->position, L->position, sizeof sh->position);
        memcpy(sh->direction, L->direction, sizeof sh->direction);
        /* the light's frame as the GLSL makes it (area_light_axes) */
        float nl[3] = {L->direction[0], L->direction[1], L->direction[2]}, ex[3], ey[3];
        sl_vec3_normalize(nl);
        const float *axis = L->params + 4;
        float d = axis[0] * nl[0] + axis[1] * nl[1] + axis[2] * nl[2];
        for (int c = 0; c < 3; c++) ex[c] = axis[c] - nl[c] * d;
        if (sqrtf(ex[0] * ex[0] + ex[1] * ex[1] + ex[2] * ex[2]) < 1e-6f) {
            const float up[3] = {0, 1, 0}, right[3] = {1, 0, 0};
            sl_vec3_cross(fabsf(nl[1]) < 0.999f ? up : right, nl, ex);
        }
        sl_vec3_normalize(ex);
        sl_vec3_cross(nl, ex, ey);
        double su = u, sv = v;
        if (L->params[2] > 0.5f) { /* disk: the ellipse, area-uniform */
            double r = sqrt(u), phi = 2 * M_PI * v;
            su = 0.5 + 0.5 * r * cos(phi), sv = 0.5 + 0.5 * r * sin(phi);
        }
        sh->uv[0] = (float)su, sh->uv[1] = (float)sv;
        double far = 0;
        for (int c = 0; c < 3; c++) {
            sh->point[c] = (float)(L->position[c] + ex[c] * (su - 0.5) * L->params[0] + ey[c] * (sv - 0.5) * L->params[1]);
        }
        for (int corner = 0; corner < 8; corner++) { /* the farthest corner of the scene box */
            double q = 0;
            for (int c = 0; c < 3; c++) {
                double e = ((corner >> c) & 1 ? f->scene_max[c] : f->scene_min[c]) - sh->point[c];
                q += e * e;
            }
            far = fmax(far, sqrt(q));
        }
        sh->far_plane = (float)(far * 1.01 + 1e-3);
        sh->near_plane = (float)fmax(1e-3 * diag, 1e-4 * sh->far_plane);
        float nn = sh->near_plane, ff = sh->far_plane;
        float proj[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -(ff + nn) / (ff - nn), -1, 0, 0, -2 * ff * nn / (ff - nn), 0};
        for (int face = 0; face < 6; face++) {
            const float *fa = al_face_axis[face];
            float sx[3], ux[3];
            sl_vec3_cross(fa, al_face_up[face], sx);
            sl_vec3_normalize(sx);
            sl_vec3_cross(sx, fa, ux);
            const float *e = sh->point;
            float view[16] = {sx[0], ux[0], -fa[0], 0, sx[1], ux[1], -fa[1], 0, sx[2], ux[2], -fa[2], 0,
                              -(sx[0] * e[0] + sx[1] * e[1] + sx[2] * e[2]), -(ux[0] * e[0] + ux[1] * e[1] + ux[2] * e[2]),
                              fa[0] * e[0] + fa[1] * e[1] + fa[2] * e[2], 1};
            glNamedFramebufferTextureLayer(a->shadow_fbo, GL_DEPTH_ATTACHMENT, a->shadow_tex, 0, 6 * slot + face);
            glBindFramebuffer(GL_FRAMEBUFFER, a->shadow_fbo);
            glViewport(0, 0, size, size);
            glDepthMask(GL_TRUE);
            glClearNamedFramebufferfv(a->shadow_fbo, GL_DEPTH, 0, &one);
            sl_draw_scene_desc dd = {.struct_size = sizeof dd, .mode = SL_DRAW_DEPTH_ONLY, .shadow_casters_only = true,
                                     .cull = 0};
            memcpy(dd.view, view, sizeof view);
            memcpy(dd.proj, proj, sizeof proj);
            host->draw_scene(host, ctx, &dd);
        }
        slot++;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

static sl_status al_create(const sl_host *host, void **user) {
    area_light *a = calloc(1, sizeof *a);
    *user = a;
    a->host = host;
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_shader_chunk_desc light = {.struct_size = sizeof light, .hook = SL_HOOK_LIGHT, .file = "area_light.glsl",
                                        .function = "area_light_radiance", .name = "area",
                                        .flags = SL_CHUNK_LIGHT_RADIANCE};
    if (host->add_shader_chunk(host, &light) != SL_OK) return SL_ERR_FAILED;
    if (host->set_bind_callback(host, al_bind, a) != SL_OK) return SL_ERR_FAILED;
    if ((a->unit_m = host->reserve_texture_unit(host)) < 0 || (a->unit_n = host->reserve_texture_unit(host)) < 0 ||
        (a->unit_e = host->reserve_texture_unit(host)) < 0 || (a->unit_s = host->reserve_texture_unit(host)) < 0 ||
        (a->unit_blinn = host->reserve_texture_unit(host)) < 0)
        return SL_ERR_FAILED;
    const sl_pass_desc pass = {.struct_size = sizeof pass, .name = "area-light-visibility", .stage = SL_STAGE_SHADOW,
                               .execute = al_shadow_execute, .is_active = al_shadow_active,
                               .signature = al_shadow_signature, .user = a,
                               .depends = SL_DEPENDS_LIGHTS | SL_DEPENDS_GEOMETRY | SL_DEPENDS_MATERIALS};
    if (host->add_pass(host, &pass) != SL_OK) return SL_ERR_FAILED;
    const sl_reference_desc ref = {
        .struct_size = sizeof ref, .settings = AL_ID ".method=reference " AL_ID ".reference_visibility=true " AL_ID ".reference_samples=4",
        .accumulate_frames = 256,
        .description = "Monte Carlo over each area light's surface with visibility: per accumulated frame one point "
                       "per light (a Hammersley set over the 256 frames, the exact ellipse for disks) and a depth cube "
                       "map rendered from it (reference_map_size), shaded through the material's own model"};
    if (host->set_reference(host, &ref) != SL_OK) return SL_ERR_FAILED;
    /* the tables: read now, so a missing or damaged file is a create() error naming it */
    const char *files[2] = {"ltc_ggx.txt", "ltc_blinn_phong.txt"};
    al_ltc_table *tables[2] = {&a->table, &a->blinn_table};
    for (int i = 0; i < 2; i++) {
        char path[4096], err[1024];
        snprintf(path, sizeof path, "%s/%s", host->resource_dir(host), files[i]);
        if (!al_table_read(path, tables[i], err, sizeof err)) {
            host->log(host, SL_LOG_ERROR, "%s", err);
            return SL_ERR_FAILED;
        }
    }
    return SL_OK;
}

static sl_status al_activate(void *user) {
    area_light *a = user;
    if (!sl_gl_load(a->host->gl_get_proc_address, NULL)) return SL_ERR_GL;
    a->tex_m = al_table_texture(&a->table, false);
    a->tex_n = al_table_texture(&a->table, true);
    a->tex_blinn = 0; /* at the first bind that reads it */
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &a->tex_e);
    glTextureStorage3D(a->tex_e, AL_TEX_LEVELS, GL_RGBA16F, AL_TEX_DIM, AL_TEX_DIM, AL_MAX_TEX);
    glTextureParameteri(a->tex_e, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(a->tex_e, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(a->tex_e, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(a->tex_e, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    memset(a->slots, 0, sizeof a->slots);
    glCreateFramebuffers(1, &a->shadow_fbo);
    glNamedFramebufferDrawBuffer(a->shadow_fbo, GL_NONE);
    glNamedFramebufferReadBuffer(a->shadow_fbo, GL_NONE);
    a->shadow_tex = 0, a->shadow_size = 0;
    memset(a->shadows, 0, sizeof a->shadows);
    return SL_OK;
}

static void al_deactivate(void *user) {
    area_light *a = user;
    glDeleteTextures(1, &a->tex_m);
    glDeleteTextures(1, &a->tex_n);
    glDeleteTextures(1, &a->tex_e);
    if (a->tex_blinn) glDeleteTextures(1, &a->tex_blinn);
    if (a->shadow_tex) glDeleteTextures(1, &a->shadow_tex);
    glDeleteFramebuffers(1, &a->shadow_fbo);
    a->tex_m = a->tex_n = a->tex_e = a->tex_blinn = a->shadow_tex = a->shadow_fbo = 0;
    a->shadow_size = 0;
    memset(a->shadows, 0, sizeof a->shadows);
    memset(a->slots, 0, sizeof a->slots);
}

static void al_destroy(void *user) {
    area_light *a = user;
    if (a) free(a->table.e), free(a->blinn_table.e);
    free(a);
}

static const sl_plugin_desc al_desc = {
    SL_PLUGIN_HEADER,
    .id = AL_ID,
    .version = "1.0.0",
    .description = "Rectangle and disk area lights: LTC (Heitz et al. 2016) per lobe, GGX or Blinn-Phong, Lambert's "
                   "exact polygon irradiance, a Monte Carlo reference.",
    .create = al_create,
    .activate = al_activate,
    .deactivate = al_deactivate,
    .destroy = al_destroy,
};
SL_DEFINE_PLUGIN(al_desc)
