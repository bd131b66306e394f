/* phong: two shading models and the gloss-map assignment's inputs.
 *   "phong"        classic Phong: diffuse + k_s·(r·v)^shininess, ambient outside the light loop
 *   "blinn-gloss"  normalised Blinn-Phong with Schlick F0 = 0.04, SpecPower = 2^(12·gloss),
 *                  Color = mix(Ambient + Diffuse, Specular, Fresnel), AO scales the ambient
 * A SURFACE hook gated on "property_map" (R gloss, B AO) writes s.alpha (the power, through
 * p = 2/α² − 2) and s.ao. Specular antialiasing (Toksvig 2005): for a material with a normal
 * map and a property map, an explicit mip chain of the normal map's averaged normals gives
 * each level's |N̄|, which is baked into that level's gloss; the result is an RG texture of the
 * normal map's size (R = adjusted gloss, G = |N̄|) that the hook samples instead of the map's
 * gloss. It is built from the core's own textures (read back with glGetTextureImage) in the
 * bind callback, once per material and input, and bound on a reserved texture unit.
 * GLSL: phong_brdf.glsl (pure, unit-tested), phong.glsl (models, hook, view). See README.md. */
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include <shadelab/shadelab.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}

typedef struct toksvig_tex {
    int material;
    unsigned normal_tex, property_tex; /* the core's textures it was built from */
    float strength;                    /* normal-map strength it was built with */
    bool built;                        /* tried for these inputs (tex 0: failed, warned once) */
    unsigned tex;                      /* RG16F, full mip chain */
} toksvig_tex;

typedef struct phong {
    const sl_host *host;
    int unit;                          /* reserved texture unit for phong_toksvig */
    toksvig_tex *cache;
    int cache_count;
    PFNGLGETUNIFORMIVPROC get_uniform_iv;
} phong;

/* ---- Toksvig texture ----------------------------------------------------------------------- */

/* Level 0 of a GL texture as float RGBA (malloc'd), or NULL (also beyond 8192², where the
 * read-back's byte count would not fit glGetTextureImage's int). */
static float *read_texture(unsigned tex, int *w, int *h) {
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_WIDTH, w);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_HEIGHT, h);
    if (*w < 1 || *h < 1 || *w > 8192 || *h > 8192) return NULL;
    size_t bytes = (size_t)*w * *h * 4 * sizeof(float);
    float *px = malloc(bytes);
    if (px) glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, (int)bytes, px);
    return px;
}

static float sample_repeat(const float *px, int w, int h, float u, float v, int c) {
    float x = u * w - 0.5f, y = v * h - 0.5f;
    int x0 = (int)floorf(x), y0 = (int)floorf(y);
    float fx = x - x0, fy = y - y0, s = 0;
    for (int k = 0; k < 4; k++) {
        int xi = ((x0 + (k & 1)) % w + w) % w, yi = ((y0 + (k >> 1)) % h + h) % h;
        s += ((k & 1) ? fx : 1 - fx) * ((k >> 1) ? fy : 1 - fy) * px[((size_t)yi * w + xi) * 4 + c];
    }
    return s;
}

/* Builds the RG texture: per level, R = gloss' = log2(ft·2^(12·ḡ))/12 and G = |N̄|, where N̄ and ḡ
 * are 2×2 box averages of the level above (the same box filter as the core's mip chain), N̄ of
 * unit normals decoded as the shader decodes them (tangent space: xy scaled by the strength). */
static unsigned build_toksvig(unsigned normal_tex, unsigned property_tex, float strength, bool tangent) {
    int w, h, pw = 0, ph = 0;
    float *nrm = read_texture(normal_tex, &w, &h);
    float *prop = property_tex ? read_texture(property_tex, &pw, &ph) : NULL;
    if (!nrm) { free(prop); return 0; }
    size_t n = (size_t)w * h;
    float *vec = malloc(n * 4 * sizeof(float)); /* xyz = averaged normal, w = gloss */
    float *out = malloc(n * 2 * sizeof(float));
    if (!vec || !out) { free(nrm), free(prop), free(vec), free(out); return 0; }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * w + x;
            float nx = nrm[i * 4] * 2 - 1, ny = nrm[i * 4 + 1] * 2 - 1, nz = nrm[i * 4 + 2] * 2 - 1;
            if (tangent) nx *= strength, ny *= strength, nz = nz > 0 ? nz : 0;
            float l = sqrtf(nx * nx + ny * ny + nz * nz);
            if (l > 1e-6f) nx /= l, ny /= l, nz /= l;
            else nx = 0, ny = 0, nz = 1;
            vec[i * 4] = nx, vec[i * 4 + 1] = ny, vec[i * 4 + 2] = nz;
            /* gloss at this texel's centre (the property map may have another size) */
            vec[i * 4 + 3] = prop ? sample_repeat(prop, pw, ph, (x + 0.5f) / w, (y + 0.5f) / h, 0) : 0.5f;
        }
    int levels = 1;
    for (int s = w > h ? w : h; s > 1; s >>= 1) levels++;
    unsigned tex;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, levels, GL_RG16F, w, h);
    int lw = w, lh = h;
    for (int lvl = 0; lvl < levels; lvl++) {
        for (size_t i = 0; i < (size_t)lw * lh; i++) {
            const float *v = vec + i * 4;
            float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            float g = v[3] < 0 ? 0 : v[3] > 1 ? 1 : v[3];
            float p = exp2f(12.0f * g), lc = len < 1e-4f ? 1e-4f : len > 1 ? 1 : len;
            float pt = p * lc / (lc + p * (1 - lc));
            float gt = log2f(pt > 1 ? pt : 1) / 12.0f;
            out[i * 2] = gt, out[i * 2 + 1] = len;
        }
        glTextureSubImage2D(tex, lvl, 0, 0, lw, lh, GL_RG, GL_FLOAT, out);
        /* next level: 2×2 box average (odd sizes: the last row/column is clamped) */
        int nw = lw > 1 ? lw / 2 : 1, nh = lh > 1 ? lh / 2 : 1;
        for (int y = 0; y < nh; y++)
            for (int x = 0; x < nw; x++) {
                float acc[4] = {0, 0, 0, 0};
                for (int k = 0; k < 4; k++) {
                    int sx = 2 * x + (k & 1), sy = 2 * y + (k >> 1);
                    if (sx >= lw) sx = lw - 1;
                    if (sy >= lh) sy = lh - 1;
                    for (int c = 0; c < 4; c++) acc[c] += vec[((size_t)sy * lw + sx) * 4 + c];
                }
                for (int c = 0; c < 4; c++) vec[((size_t)y * nw + x) * 4 + c] = acc[c] * 0.25f;
            }
        lw = nw, lh = nh;
    }
    /* Trilinear, isotropic: the level is chosen by the footprint's MAJOR axis, so it covers every
     * normal the (anisotropic, 8x) normal-map lookup averages. With anisotropic filtering the
     * level would follow the minor axis and the taps along the major axis would average
     * per-level gloss values, missing the variance between them: at grazing angles, where
     * aliasing is worst, the antialiasing would all but vanish (measured: 3% of pixels changed). */
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTextureParameterf(tex, GL_TEXTURE_MAX_ANISOTROPY, 1.0f);
    free(nrm), free(prop), free(vec), free(out);
    return tex;
}

/* The GL texture the host bound for sampler uniform `name` of `program` (0 if none). */
static unsigned bound_texture(phong *ph, unsigned program, const char *name) {
    int loc = glGetUniformLocation(program, name), unit = -1, tex = 0, active = 0;
    if (loc < 0 || !ph->get_uniform_iv) return 0;
    ph->get_uniform_iv(program, loc, &unit);
    if (unit < 0 || unit > 31) return 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    glActiveTexture(GL_TEXTURE0 + unit);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &tex);
    glActiveTexture(active);
    return (unsigned)tex;
}

static void phong_bind(void *user, unsigned program, int material, const sl_frame *frame) {
    phong *ph = user;
    const sl_host *h = ph->host;
    int loc = glGetUniformLocation(program, "phong_toksvig");
    if (loc < 0 || ph->unit < 0) return; /* this program has no specular antialiasing */
    unsigned ntex = bound_texture(ph, program, "sl_mat_normal_map");
    unsigned ptex = bound_texture(ph, program, "sl_mat_property_map");
    if (!ntex) return;
    sl_value v;
    float strength = 1;
    bool tangent = true;
    if (h->material_value(h, material, "normal_strength", &v, NULL, 0)) strength = v.f[0];
    if (h->material_value(h, material, "normal_space", &v, NULL, 0)) tangent = v.i == 0;
    if (h->plugin_enabled(h, "normal-map")) strength *= h->get_param(h, "normal-map.strength").f[0];
    if (!tangent) strength = 1; /* object-space strength blends with the interpolated normal: not bakeable */
    toksvig_tex *t = NULL;
    for (int i = 0; i < ph->cache_count && !t; i++)
        if (ph->cache[i].material == material) t = &ph->cache[i];
    if (!t) {
        toksvig_tex *grown = realloc(ph->cache, (ph->cache_count + 1) * sizeof *grown);
        if (!grown) return;
        ph->cache = grown;
        t = &ph->cache[ph->cache_count++];
        memset(t, 0, sizeof *t);
        t->material = material;
    }
    if (!t->built || t->normal_tex != ntex || t->property_tex != ptex || t->strength != strength) {
        if (t->tex) glDeleteTextures(1, &t->tex);
        t->tex = build_toksvig(ntex, ptex, strength, tangent);
        if (!t->tex) h->log(h, SL_LOG_WARN, "material %s: no Toksvig texture (normal map unreadable or over 8192^2): "
                            "gloss without specular antialiasing", h->material_name(h, material));
        t->normal_tex = ntex, t->property_tex = ptex, t->strength = strength, t->built = true;
        h->log(h, SL_LOG_DEBUG, "Toksvig gloss texture for material %s (normal strength %g)", h->material_name(h, material),
               strength);
    }
    glBindTextureUnit((unsigned)ph->unit, t->tex);
    glProgramUniform1i(program, loc, ph->unit);
}

/* ---- lifecycle -------------------------------------------------------------------------- */

static sl_status phong_create(const sl_host *host, void **user) {
    phong *ph = calloc(1, sizeof *ph);
    if (!ph) return SL_ERR_FAILED;
    ph->host = host;
    *user = ph;
    static const sl_param_desc params[] = {
        P(.id = "color", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "gloss-map assignment",
          .description = "Key 1: albedo from the colour map (true) or grey 0.5 (false), to judge the lighting alone."),
        P(.id = "gloss_map", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "gloss-map assignment",
          .description = "Key 3: gloss from the property map's red channel (true) or the material's gloss "
                         "(false; 0.5 = SpecPower 64)."),
        P(.id = "ao", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "gloss-map assignment",
          .description = "Key 4: the property map's blue channel scales the ambient term."),
        P(.id = "specular_aa", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "quality",
          .flags = SL_PARAM_NEEDS_RECOMPILE | SL_PARAM_QUALITY_KNOB,
          .description = "Specular antialiasing (Toksvig 2005) for blinn-gloss: each mip level of the normal map's "
                         "normal variance is baked into the gloss (materials with a normal map and a property map)."),
        P(.id = "gloss", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {0.5f}}, .min = 0,
          .max = 1, .step = 0.01f, .group = "phong",
          .description = "blinn-gloss: SpecPower = 2^(12*gloss) without a property map or with the gloss map off."),
        P(.id = "property_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
          .group = "phong",
          .description = "Property map (linear): red = gloss (SpecPower = 2^(12*gloss)), blue = ambient occlusion."),
        P(.id = "shininess", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {32}}, .min = 0,
          .max = 10000, .group = "phong", .description = "Classic Phong exponent of (r.v)."),
        P(.id = "specular_color", .type = SL_PARAM_COLOR, .scope = SL_SCOPE_MATERIAL,
          .default_value = {.f = {0.5f, 0.5f, 0.5f}}, .group = "phong",
          .description = "Classic Phong k_s (linear RGB; times the surface's specular scale)."),
    };
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;

#define CHUNK(...) {.struct_size = sizeof(sl_shader_chunk_desc), .file = "phong.glsl", __VA_ARGS__}
    static const sl_shader_chunk_desc chunks[] = {
        CHUNK(.hook = SL_HOOK_SHADING_MODEL, .function = "phong_model_classic", .name = "phong"),
        CHUNK(.hook = SL_HOOK_MODEL_AMBIENT, .function = "phong_model_classic_ambient", .name = "phong"),
        CHUNK(.hook = SL_HOOK_SHADING_MODEL, .function = "phong_model_blinn_gloss", .name = "blinn-gloss"),
        CHUNK(.hook = SL_HOOK_MODEL_AMBIENT, .function = "phong_model_blinn_gloss_ambient", .name = "blinn-gloss"),
        CHUNK(.hook = SL_HOOK_MODEL_LOBES, .function = "phong_blinn_gloss_lobes", .name = "blinn-gloss"),
        CHUNK(.hook = SL_HOOK_SURFACE, .function = "phong_surface_gloss", .when_model = "blinn-gloss", .order = -100),
        CHUNK(.hook = SL_HOOK_SURFACE, .function = "phong_surface", .when_material_has = "property_map", .order = 20),
        CHUNK(.hook = SL_HOOK_DEBUG_VIEW, .function = "phong_debug_gloss", .name = "effective-gloss",
              .description = "blinn-gloss gloss after the gloss map and Toksvig: log2(SpecPower)/12"),
    };
#undef CHUNK
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;

    static const sl_key_desc keys[] = {
        {.struct_size = sizeof(sl_key_desc), .key = "1", .param = "color", .description = "colour map / grey albedo"},
        {.struct_size = sizeof(sl_key_desc), .key = "3", .param = "gloss_map", .description = "gloss map on/off"},
        {.struct_size = sizeof(sl_key_desc), .key = "4", .param = "ao", .description = "ambient occlusion on/off"},
    };
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++) host->add_key(host, &keys[i]);
    static const sl_reference_desc reference = {
        .struct_size = sizeof reference, .settings = "core.ssaa=8 core.anisotropy=1 phong.specular_aa=false",
        .description = "8x8 supersampling without prefiltering: every sample shades the normal and gloss maps at "
                       "its own, finer mip level."};
    host->set_reference(host, &reference);
    ph->unit = host->reserve_texture_unit(host);
    return host->set_bind_callback(host, phong_bind, ph);
}

static sl_status phong_activate(void *user) {
    phong *ph = user;
    const char *missing = NULL;
    if (!sl_gl_load(ph->host->gl_get_proc_address, &missing)) {
        ph->host->log(ph->host, SL_LOG_ERROR, "GL entry point %s missing", missing ? missing : "?");
        return SL_ERR_GL;
    }
    ph->get_uniform_iv = (PFNGLGETUNIFORMIVPROC)ph->host->gl_get_proc_address("glGetUniformiv");
    return SL_OK;
}

static void phong_deactivate(void *user) {
    phong *ph = user;
    for (int i = 0; i < ph->cache_count; i++)
        if (ph->cache[i].tex) glDeleteTextures(1, &ph->cache[i].tex);
    free(ph->cache);
    ph->cache = NULL;
    ph->cache_count = 0;
}

static void phong_destroy(void *user) { free(user); }

static const char *const phong_models[] = {"phong", "blinn-gloss", NULL};
static const sl_plugin_desc phong_desc = {
    SL_PLUGIN_HEADER,
    .id = "phong",
    .version = "1.0",
    .description = "Classic Phong and normalised Blinn-Phong with gloss/AO maps and Toksvig specular antialiasing.",
    .create = phong_create,
    .activate = phong_activate,
    .deactivate = phong_deactivate,
    .destroy = phong_destroy,
    .shading_models = phong_models,
};
SL_DEFINE_PLUGIN(phong_desc)
