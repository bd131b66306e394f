/* sss: subsurface scattering for skin, from cheap to faithful (see README.md).
 *
 * Materials opt in with the "skin" shading model and the key sss_radius (plus sss_strength,
 * sss_color). sss.method picks, for every skin material at once (a permutation):
 *   wrap            wrap lighting + a red scatter band (GPU Gems 1 ch. 16)       no pass
 *   translucency    Lambert + light through the object, thickness from the light's
 *                   shadow map (extension shadelab.shadow-maps/1; GPU Gems 1 ch. 16)  no pass
 *   texture-space   d'Eon & Luebke 2007 (GPU Gems 3 ch. 14): irradiance in UV space, separable
 *                   stretch-corrected blurs building the six Gaussians, summed    passes below
 *   screen-space    Jimenez et al. 2015: a separate diffuse buffer, two depth-aware 1D passes
 *   pre-integrated  Penner 2011: a LUT over (n·l, curvature) made on first use    no pass
 *   none            the ggx model (the frame "without sss")
 * GLSL: sss_lib.glsl (pure functions), sss_model.glsl (models, hook, views), sss_ts_blur.frag,
 * sss_ss_blur.frag. CPU side of the profile: sss_profile.c.
 *
 * Passes (stage PREPASS, all inactive unless the method needs them and a material carries
 * sss_radius): sss-stretch (texture space, only when geometry or parameters change),
 * sss-irradiance, sss-ts-blur; sss-ss-diffuse, sss-ss-blur. Their targets are the plugin's own
 * textures, sized by sss.ts_size or the viewport and made on first use (nothing is allocated
 * for a scene that does not use them). */
#include <shadelab/shadelab.h>
#include <shadelab/ext/shadow_maps.h>
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include "sss_cache.h"
#include "sss_profile.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { M_NONE, M_WRAP, M_TRANSLUCENCY, M_TEXTURE_SPACE, M_SCREEN_SPACE, M_PRE_INTEGRATED };
static const char *const methods[] = {"none", "wrap", "translucency", "texture-space", "screen-space", "pre-integrated", NULL};
static const char *const albedos[] = {"post-scatter", "pre-scatter", "mixed", NULL};

#define LUT_W 128
#define LUT_H 64
#define LUT_KAPPA_MAX 0.5 /* mm⁻¹: radius of curvature down to 2 mm (ear rims, nostrils) */
#define MAX_MAPS 8

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}
#define RECOMPILE SL_PARAM_NEEDS_RECOMPILE
#define KNOB SL_PARAM_QUALITY_KNOB
static const sl_param_desc params[] = {
    P(.id = "method", .type = SL_PARAM_ENUM, .enum_values = methods, .default_value = {.i = M_TEXTURE_SPACE},
      .flags = RECOMPILE, .group = "method",
      .description = "none (ggx), wrap (+ scatter band), translucency (shadow-map thickness), texture-space "
                     "(d'Eon & Luebke), screen-space (Jimenez et al.), pre-integrated (Penner)."),
    P(.id = "albedo", .type = SL_PARAM_ENUM, .enum_values = albedos, .default_value = {.i = 2}, .flags = RECOMPILE,
      .group = "method",
      .description = "Where base_color applies in texture/screen space: after scattering (sharp), before (bled), "
                     "or sqrt before and after (mixed)."),
    P(.id = "wrap", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.2f}}, .min = 0, .max = 1, .step = 0.05f,
      .group = "wrap", .description = "Wrap amount w: diffuse = max(0, (n·l + w)/(1 + w))."),
    P(.id = "scatter_width", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.3f}}, .min = 0.01f, .max = 1,
      .step = 0.01f, .group = "wrap", .description = "Width of the scatter band (sss_color) inside the terminator."),
    P(.id = "ts_size", .type = SL_PARAM_INT, .default_value = {.i = 1024}, .min = 64, .max = 4096, .step = 64,
      .unit = "px", .flags = KNOB, .group = "texture space", .description = "Width = height of the UV-space irradiance."),
    P(.id = "cache", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "texture space",
      .description = "Keep the texture-space result on disk, keyed by the texels it is made from (a start with the same "
                     "lighting loads it instead of blurring; the frame is the same)."),
    P(.id = "ts_taps", .type = SL_PARAM_INT, .default_value = {.i = 7}, .min = 3, .max = SSS_MAX_TS_TAPS, .step = 2,
      .flags = KNOB, .group = "texture space", .description = "Taps per 1D blur over ±3σ (odd; 7 = d'Eon & Luebke's)."),
    P(.id = "gaussians", .type = SL_PARAM_INT, .default_value = {.i = 6}, .min = 1, .max = 6, .flags = KNOB,
      .group = "quality",
      .description = "Gaussians of the profile used (texture and screen space); fewer = neighbours merged, best fit."),
    P(.id = "ss_taps", .type = SL_PARAM_INT, .default_value = {.i = 17}, .min = 3, .max = SSS_MAX_SS_TAPS, .step = 2,
      .flags = KNOB, .group = "screen space", .description = "Taps per 1D screen-space pass (odd)."),
    P(.id = "ss_width", .type = SL_PARAM_FLOAT, .default_value = {.f = {8}}, .min = 1, .max = 25, .step = 0.5f,
      .unit = "mm", .flags = KNOB, .group = "screen space",
      .description = "Half-width of the screen-space kernel (the profile's widest σ is 2.7 mm)."),
    P(.id = "ss_follow_surface", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "screen space",
      .description = "Depth-aware kernel (taps across a depth step fade out); off = a plain screen-space blur."),
    /* material keys */
    P(.id = "sss_radius", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {0.001f}},
      .min = 1e-7f, .max = 1e4f, .unit = "units/mm", .group = "sss",
      .description = "Opts a material in: the scene length of 1 mm of the skin profile (0.001 in metres); larger "
                     "scatters further."),
    P(.id = "sss_strength", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1}}, .min = 0,
      .max = 1, .step = 0.05f, .group = "sss", .description = "0 = no scattering (exactly the ggx model), 1 = full."),
    P(.id = "sss_color", .type = SL_PARAM_COLOR, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {0.25f, 0.04f, 0.02f}},
      .group = "sss", .description = "Wrap method: colour of the scatter band at the terminator."),
    /* shared with ggx (the same key, ggx's schema stands when both are loaded): the skin model's
     * specular layer reads it even when no ggx chunk is in the program */
    P(.id = "eta", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1.0f / 1.4f}},
      .min = 0.05f, .max = 20, .step = 0.01f, .group = "sss",
      .description = "Relative index of refraction n1/n2 of the specular layer (skin: 1/1.4 when not given)."),
};

#define C(...) {.struct_size = sizeof(sl_shader_chunk_desc), __VA_ARGS__}
static const sl_shader_chunk_desc chunks[] = {
    C(.hook = SL_HOOK_SHADING_MODEL, .file = "sss_model.glsl", .function = "sss_skin", .name = "skin"),
    C(.hook = SL_HOOK_MODEL_AMBIENT, .file = "sss_model.glsl", .function = "sss_skin_ambient", .name = "skin"),
    C(.hook = SL_HOOK_SHADING_MODEL, .file = "sss_model.glsl", .function = "sss_irradiance", .name = "sss-irradiance"),
    C(.hook = SL_HOOK_MODEL_AMBIENT, .file = "sss_model.glsl", .function = "sss_irradiance_ambient",
      .name = "sss-irradiance"),
    C(.hook = SL_HOOK_SHADING_MODEL, .file = "sss_model.glsl", .function = "sss_stretch", .name = "sss-stretch"),
    C(.hook = SL_HOOK_MODEL_AMBIENT, .file = "sss_model.glsl", .function = "sss_stretch_ambient", .name = "sss-stretch"),
    /* what light integrators (envmap, area-light) give the override models: the pre-scatter
     * albedo's Lambert to the irradiance, nothing to the stretch (the lobe contract) */
    C(.hook = SL_HOOK_MODEL_LOBES, .file = "sss_model.glsl", .function = "sss_irradiance_lobes", .name = "sss-irradiance"),
    C(.hook = SL_HOOK_MODEL_LOBES, .file = "sss_model.glsl", .function = "sss_stretch_lobes", .name = "sss-stretch"),
    /* first of the surface hooks: curvature from the interpolated normal, before normal maps */
    C(.hook = SL_HOOK_SURFACE, .file = "sss_model.glsl", .function = "sss_surface", .when_material_has = "sss_radius",
      .order = -100),
    C(.hook = SL_HOOK_DEBUG_VIEW, .file = "sss_model.glsl", .function = "sss_view_scattered", .name = "sss-scattered",
      .description = "sss: the scattered diffuse (texture/screen space), no specular"),
    C(.hook = SL_HOOK_DEBUG_VIEW, .file = "sss_model.glsl", .function = "sss_view_thickness", .name = "sss-thickness",
      .description = "sss: translucency thickness from the first shadow map (white = 1 cm, blue = outside)"),
    C(.hook = SL_HOOK_DEBUG_VIEW, .file = "sss_model.glsl", .function = "sss_view_curvature", .name = "sss-curvature",
      .description = "sss: pre-integrated curvature / κ_max"),
};

static const sl_key_desc keys[] = {
    {.struct_size = sizeof(sl_key_desc), .key = "K", .param = "method", .description = "next sss method"},
};

typedef struct sss {
    const sl_host *host;
    int unit_diffuse, unit_lut, unit_shadow;
    /* the blur's programs along u [0] and along v [1]: the same source, a program object for
     * each pass's state (see ts_blur_execute) */
    sl_program *ts_prog[2], *ts_interior_prog[2], *dilate_prog, *ss_prog;
    unsigned warmed[5]; /* the blur programs compiled ahead of the read-back (ts_blur_execute) */
    unsigned dummy2d, dummy_array;
    /* texture space: stretch, irradiance, tmp, the chain, sums 0 and 1 (slot 4 unused) */
    int ts_size, ts_generation, ts_result;
    unsigned ts_tex[7], ts_fbo[7];
    /* interior classification (ts_classify): per-direction depth (u, v), the empty VAO of the
     * split draws, CPU scratch for the read-back coverage and stretch */
    unsigned ts_class[2], ts_vao;
    float *ts_scratch;
    /* the warm-up's own targets (ts_warm_up): the formats of tmp / the chain, the sums and the
     * classification, one 64² tile each, in ts_fbo's slots 2 to 6 */
    unsigned warm_tex[3], warm_fbo[7];
    /* the disk cache (sss_cache.h): code and renderer hash (activate), a result to store at the
     * next frame (one per activation: the start-up state), loads so far */
    uint64_t code_hash, store_key;
    bool store_pending, stored;
    int cache_loads;
    /* screen space: diffuse, depth, tmp, out */
    int ss_w, ss_h;
    unsigned ss_tex[4], ss_fbo[3];
    unsigned kernel_tex;
    /* derived from the quality parameters */
    int key_gaussians, key_ts_taps, key_ss_taps;
    float key_ss_width;
    sss_gaussians gauss;
    float ts_offsets[SSS_MAX_TS_TAPS], ts_weights[SSS_MAX_TS_TAPS];
    unsigned lut_tex;
    /* per frame */
    bool any_material;
    float ss_mm;
    uint64_t maps_frame;
    int map_count;
    sl_shadow_map maps[MAX_MAPS];
    int map_type[MAX_MAPS];
    bool warned_no_maps, warned_radius, warned_light_type;
} sss;

static sl_value param(sss *s, const char *id) {
    char full[64];
    snprintf(full, sizeof full, "sss.%s", id);
    return s->host->get_param(s->host, full);
}
static int method(sss *s) { return param(s, "method").i; }

/* ------------------------------------------------------------------ GL helpers ------------ */

static unsigned make_tex(int w, int h, GLenum fmt, bool border) {
    unsigned t;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, fmt, w, h);
    bool depth = fmt == GL_DEPTH_COMPONENT32F;
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, depth ? GL_NEAREST : GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, depth ? GL_NEAREST : GL_LINEAR);
    /* transparent border: taps and look-ups outside [0,1] have coverage 0 */
    GLenum wrap = border ? GL_CLAMP_TO_BORDER : GL_CLAMP_TO_EDGE;
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, wrap);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, wrap);
    static const float zero[4] = {0, 0, 0, 0};
    glTextureParameterfv(t, GL_TEXTURE_BORDER_COLOR, zero);
    return t;
}

static unsigned make_fbo(unsigned color0, unsigned color1, unsigned depth) {
    unsigned f;
    glCreateFramebuffers(1, &f);
    glNamedFramebufferTexture(f, GL_COLOR_ATTACHMENT0, color0, 0);
    GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    if (color1) glNamedFramebufferTexture(f, GL_COLOR_ATTACHMENT1, color1, 0);
    if (depth) glNamedFramebufferTexture(f, GL_DEPTH_ATTACHMENT, depth, 0);
    glNamedFramebufferDrawBuffers(f, color1 ? 2 : 1, bufs);
    return f;
}

static void free_ts(sss *s) {
    glDeleteFramebuffers(7, s->ts_fbo);
    glDeleteTextures(7, s->ts_tex);
    glDeleteTextures(2, s->ts_class);
    memset(s->ts_class, 0, sizeof s->ts_class);
    glDeleteFramebuffers(7, s->warm_fbo);
    glDeleteTextures(3, s->warm_tex);
    memset(s->warm_fbo, 0, sizeof s->warm_fbo);
    memset(s->warm_tex, 0, sizeof s->warm_tex);
    free(s->ts_scratch);
    s->ts_scratch = NULL;
    memset(s->ts_fbo, 0, sizeof s->ts_fbo);
    memset(s->ts_tex, 0, sizeof s->ts_tex);
    s->ts_size = 0;
}

static void free_ss(sss *s) {
    glDeleteFramebuffers(3, s->ss_fbo);
    glDeleteTextures(4, s->ss_tex);
    memset(s->ss_fbo, 0, sizeof s->ss_fbo);
    memset(s->ss_tex, 0, sizeof s->ss_tex);
    s->ss_w = s->ss_h = 0;
}

enum { TS_STRETCH, TS_IRR, TS_TMP, TS_A, TS_B, TS_SUM0, TS_SUM1 };
enum { SS_DIFFUSE, SS_DEPTH, SS_TMP, SS_OUT };

static void ensure_ts(sss *s) {
    int size = param(s, "ts_size").i;
    if (s->ts_size == size && s->ts_tex[0]) return;
    free_ts(s);
    s->ts_size = size;
    s->ts_generation++;
    s->ts_tex[TS_STRETCH] = make_tex(size, size, GL_RG16F, true);
    s->ts_tex[TS_IRR] = make_tex(size, size, GL_RGBA16F, true);
    s->ts_tex[TS_TMP] = make_tex(size, size, GL_RGBA16F, true);
    s->ts_tex[TS_A] = make_tex(size, size, GL_RGBA16F, true);
    /* one chain texture: a step's u pass reads it into tmp, its v pass writes it back (separate
     * draws); a second one (ping-pong) only cost 8 MB of page faults at start-up */
    /* the running sum in float: six roundings to half would cost the 1e-3 normalisation */
    s->ts_tex[TS_SUM0] = make_tex(size, size, GL_RGBA32F, true);
    s->ts_tex[TS_SUM1] = make_tex(size, size, GL_RGBA32F, true);
    /* the interior classification of the blurs along u and along v (ts_classify) */
    s->ts_class[0] = make_tex(size, size, GL_DEPTH_COMPONENT32F, false);
    s->ts_class[1] = make_tex(size, size, GL_DEPTH_COMPONENT32F, false);
    s->ts_fbo[0] = make_fbo(s->ts_tex[TS_STRETCH], 0, 0);
    s->ts_fbo[1] = make_fbo(s->ts_tex[TS_IRR], 0, 0);
    s->ts_fbo[2] = make_fbo(s->ts_tex[TS_TMP], 0, s->ts_class[0]);
    s->ts_fbo[3] = make_fbo(s->ts_tex[TS_A], s->ts_tex[TS_SUM0], s->ts_class[1]);
    s->ts_fbo[4] = make_fbo(s->ts_tex[TS_A], s->ts_tex[TS_SUM1], s->ts_class[1]);
    s->ts_fbo[5] = make_fbo(s->ts_tex[TS_SUM0], 0, 0);
    s->ts_fbo[6] = make_fbo(s->ts_tex[TS_SUM1], 0, 0);
    /* The warm-up draws (ts_warm_up) go to targets of their own with the same formats: on
     * llvmpipe a draw that samples a texture a queued draw renders (or clears) waits for the
     * rasteriser to reach that draw, and the forward pass's programs, compiled ahead in the blur
     * pass (host->compile_ahead), sample the result sum; warm-up draws into it, queued behind
     * envmap's GGX chain, made that compile wait for the chain first. */
    s->warm_tex[0] = make_tex(64, 64, GL_RGBA16F, true);
    s->warm_tex[1] = make_tex(64, 64, GL_RGBA32F, true);
    s->warm_tex[2] = make_tex(64, 64, GL_DEPTH_COMPONENT32F, false);
    s->warm_fbo[2] = make_fbo(s->warm_tex[0], 0, s->warm_tex[2]);
    s->warm_fbo[3] = s->warm_fbo[4] = make_fbo(s->warm_tex[0], s->warm_tex[1], s->warm_tex[2]);
    s->warm_fbo[5] = s->warm_fbo[6] = make_fbo(s->warm_tex[1], 0, 0);
    /* the result before the first blurs: zero, written by the CPU (a clear draw would be queued) */
    static const float zero[4] = {0, 0, 0, 0};
    glClearTexImage(s->ts_tex[TS_SUM0], 0, GL_RGBA, GL_FLOAT, zero);
    s->ts_result = TS_SUM0;
}

static void ensure_ss(sss *s, int w, int h) {
    if (s->ss_w == w && s->ss_h == h && s->ss_tex[0]) return;
    free_ss(s);
    s->ss_w = w, s->ss_h = h;
    /* float, not half: three half roundings in a row (llvmpipe truncates) cost 1.5e-3 on a
     * uniformly lit patch; viewport-sized, so the memory is small */
    s->ss_tex[SS_DIFFUSE] = make_tex(w, h, GL_RGBA32F, true);
    s->ss_tex[SS_DEPTH] = make_tex(w, h, GL_DEPTH_COMPONENT32F, false);
    s->ss_tex[SS_TMP] = make_tex(w, h, GL_RGBA32F, true);
    s->ss_tex[SS_OUT] = make_tex(w, h, GL_RGBA32F, true);
    s->ss_fbo[0] = make_fbo(s->ss_tex[SS_DIFFUSE], 0, s->ss_tex[SS_DEPTH]);
    s->ss_fbo[1] = make_fbo(s->ss_tex[SS_TMP], 0, 0);
    s->ss_fbo[2] = make_fbo(s->ss_tex[SS_OUT], 0, 0);
    static const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(s->ss_fbo[2], GL_COLOR, 0, zero);
}

/* The kernels follow the quality parameters. */
static void update_kernels(sss *s) {
    int k = param(s, "gaussians").i, tt = param(s, "ts_taps").i | 1, st = param(s, "ss_taps").i | 1;
    float width = param(s, "ss_width").f[0];
    if (tt > SSS_MAX_TS_TAPS) tt = SSS_MAX_TS_TAPS;
    if (st > SSS_MAX_SS_TAPS) st = SSS_MAX_SS_TAPS;
    if (s->kernel_tex && k == s->key_gaussians && tt == s->key_ts_taps && st == s->key_ss_taps && width == s->key_ss_width)
        return;
    s->key_gaussians = k, s->key_ts_taps = tt, s->key_ss_taps = st, s->key_ss_width = width;
    sss_profile_reduce(k, &s->gauss);
    sss_blur_taps(tt, s->ts_offsets, s->ts_weights);
    float *kernel = calloc((size_t)st * s->gauss.n * 4, sizeof(float));
    sss_ss_kernel(&s->gauss, st, width, kernel);
    if (s->kernel_tex) glDeleteTextures(1, &s->kernel_tex);
    glCreateTextures(GL_TEXTURE_2D, 1, &s->kernel_tex);
    glTextureStorage2D(s->kernel_tex, 1, GL_RGBA32F, st, s->gauss.n);
    glTextureSubImage2D(s->kernel_tex, 0, 0, 0, st, s->gauss.n, GL_RGBA, GL_FLOAT, kernel);
    free(kernel);
}

static void ensure_lut(sss *s) {
    if (s->lut_tex) return;
    clock_t t0 = clock();
    float *px = malloc(sizeof(float) * 4 * LUT_W * LUT_H);
    sss_preintegrated_lut(LUT_W, LUT_H, LUT_KAPPA_MAX, px);
    glCreateTextures(GL_TEXTURE_2D, 1, &s->lut_tex);
    glTextureStorage2D(s->lut_tex, 1, GL_RGBA32F, LUT_W, LUT_H);
    glTextureSubImage2D(s->lut_tex, 0, 0, 0, LUT_W, LUT_H, GL_RGBA, GL_FLOAT, px);
    glTextureParameteri(s->lut_tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(s->lut_tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(s->lut_tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(s->lut_tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    free(px);
    s->host->log(s->host, SL_LOG_INFO, "pre-integrated skin LUT %dx%d made in %.0f ms", LUT_W, LUT_H,
                 1e3 * (double)(clock() - t0) / CLOCKS_PER_SEC);
}

/* ------------------------------------------------------------------ per frame ------------- */

static void ts_store_pending(sss *s);
static void begin_frame(void *user, const sl_frame *f) {
    sss *s = user;
    const sl_host *h = s->host;
    ts_store_pending(s);
    s->any_material = false;
    float first = 0;
    bool differ = false;
    for (int m = 0; m < h->material_count(h); m++) {
        sl_value v;
        if (!h->material_value(h, m, "sss_radius", &v, NULL, 0)) continue;
        if (!s->any_material) first = v.f[0];
        else differ |= v.f[0] != first;
        s->any_material = true;
    }
    s->ss_mm = first > 0 ? first : 0.001f;
    int me = method(s);
    if (differ && me == M_SCREEN_SPACE && !s->warned_radius) {
        h->log(h, SL_LOG_WARN, "screen-space: materials give different sss_radius; the screen-space blur uses the "
                               "first one's (%g) for all", first);
        s->warned_radius = true;
    }
    if (!s->any_material) return;
    update_kernels(s);
    if (me == M_PRE_INTEGRATED) ensure_lut(s);
}

static bool needs(sss *s, int m) { return s->any_material && method(s) == m; }
static bool ts_active(void *user, const sl_frame *f) { return needs(user, M_TEXTURE_SPACE); }
static bool ss_active(void *user, const sl_frame *f) { return needs(user, M_SCREEN_SPACE); }

static void draw_materials(sss *s, sl_pass_ctx *ctx, const sl_frame *f, const char *model, bool uv_space) {
    sl_draw_scene_desc d = {.struct_size = sizeof d, .mode = SL_DRAW_MATERIALS, .model_override = model,
                            .only_materials_with = "sss_radius", .uv_space = uv_space, .cull = uv_space ? 0 : 1};
    memcpy(d.view, f->view, sizeof d.view);
    memcpy(d.proj, f->proj, sizeof d.proj);
    s->host->draw_scene(s->host, ctx, &d);
}

static void clear_bound(float depth) {
    glDepthMask(GL_TRUE);
    glClearColor(0, 0, 0, 0);
    glClearDepth(depth);
    glClear(GL_COLOR_BUFFER_BIT | (depth >= 0 ? GL_DEPTH_BUFFER_BIT : 0));
}

/* Texture space 1: the stretch map (only when the geometry, the size or a parameter changed). */
static uint64_t stretch_signature(void *user, const sl_frame *f) {
    sss *s = user;
    ensure_ts(s); /* (re)made textures must be filled: their generation is part of the signature */
    uint64_t h = 1469598103934665603ull;
    (void)f; /* geometry and parameters: the pass's declared depends (ABI 1.8) */
    uint64_t v[2] = {(uint64_t)param(s, "ts_size").i, (uint64_t)s->ts_generation};
    for (int i = 0; i < 2; i++) h = (h ^ v[i]) * 1099511628211ull;
    return h;
}

static void ts_warm_up(sss *s, sl_pass_ctx *ctx);

static void stretch_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    sss *s = user;
    ensure_ts(s);
    if (method(s) == M_TEXTURE_SPACE) ts_warm_up(s, ctx); /* the blurs' compiles (see ts_warm_up) */
    glBindFramebuffer(GL_FRAMEBUFFER, s->ts_fbo[0]);
    glViewport(0, 0, s->ts_size, s->ts_size);
    clear_bound(-1);
    draw_materials(s, ctx, f, "sss-stretch", true);
}

/* Texture space 2 and 3 change only when the irradiance in UV space can: geometry, lights (their
 * packing changes with every edit and every animated frame) and the shadow maps, what the material
 * programs see (material values, the parameters of plugins with chunks), or re-made textures. Not with the camera: UV-space lighting has
 * no viewer (normal maps do not bend toward one there). A still head then costs the two passes
 * once instead of every frame. */
static uint64_t irradiance_signature(void *user, const sl_frame *f) {
    sss *s = user;
    ensure_ts(s);
    uint64_t h = 1469598103934665603ull;
    (void)f; /* geometry, lights (and shadow maps) and parameters: the passes' declared depends (ABI 1.8) */
    uint64_t v[2] = {(uint64_t)param(s, "ts_size").i, (uint64_t)s->ts_generation};
    for (int i = 0; i < 2; i++) h = (h ^ v[i]) * 1099511628211ull;
    return h;
}

/* Texture space 2: irradiance in UV space, each material with its own surface hooks and the
 * scene's lights and shadows. */
static void irradiance_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    sss *s = user;
    ensure_ts(s);
    glBindFramebuffer(GL_FRAMEBUFFER, s->ts_fbo[1]);
    glViewport(0, 0, s->ts_size, s->ts_size);
    clear_bound(-1);
    draw_materials(s, ctx, f, "sss-irradiance", true);
}

/* Interior texels of the blurs (the split draw below). A texel is interior for the blur along
 * u (v) when every texel its taps can read is fully covered: the 7 (ts_taps) taps reach 3σ
 * texels, σ = σ_mm / (mm per texel at the centre), and a tap at offset o reads the texels
 * ⌊o⌋ and ⌊o⌋ + 1. With D the distance in texels to the nearest texel that is not fully covered
 * (alpha < 1; outside the texture counts as uncovered) along that axis, the texels up to D − 1
 * are covered, and o < D − 1 keeps ⌊o⌋ + 1 ≤ D − 1: interior when 3σ_mm < (D − 1)·mm_per_texel.
 * (D − 1.5) is used, half a texel for rounding (test_sss_render "interior": a margin of 1
 * still equals the full program, 0 does not). That bound goes into a depth
 * texture per direction as (D − 1.5)·mm_per_texel / TS_CLASS_MM (clamped to [0, 1]); uncovered
 * texels get 1 (the interior program writes them 0, as the full one does); partly covered ones
 * and those without stretch 0 (always the full program). A blur step then draws the interior
 * program where 3σ_mm / TS_CLASS_MM < depth (GL_LESS) and the full one elsewhere (GL_GEQUAL): a
 * partition, with early depth testing before any shading. Coverage is read back from the
 * irradiance (what the blurs see), the stretch from its map: once per execution of the blurs
 * (they run only when lighting or geometry changed). */
#define TS_CLASS_MM 64.0f

static float half_to_float(uint16_t h) {
    int e = (h >> 10) & 31, m = h & 1023;
    float v = e == 0 ? ldexpf((float)m, -24) : e == 31 ? INFINITY : ldexpf((float)(m | 1024), e - 25);
    return h & 0x8000 ? -v : v;
}

/* The blur's inputs read back into the scratch (coverage classes and stretch) and, when key is
 * given, hashed there with everything else the blur and dilation read: the disk cache's key. */
static uint64_t blur_key(sss *s, uint64_t h) {
    int32_t v[3] = {s->ts_size, s->gauss.n, s->key_ts_taps};
    h = sss_hash(v, sizeof v, h);
    h = sss_hash(s->gauss.variance, sizeof(double) * (size_t)s->gauss.n, h);
    h = sss_hash(s->gauss.weight, sizeof(double) * 3 * (size_t)s->gauss.n, h);
    h = sss_hash(s->ts_offsets, sizeof(float) * (size_t)s->key_ts_taps, h);
    return sss_hash(s->ts_weights, sizeof(float) * (size_t)s->key_ts_taps, h);
}

static bool ts_read_inputs(sss *s, uint64_t *key) {
    int n = s->ts_size;
    size_t texels = (size_t)n * n;
    if (!s->ts_scratch) s->ts_scratch = malloc(texels * 4 * sizeof(float));
    if (!s->ts_scratch) return false;
    /* scratch: [0, 2n²) the stretch (u, v); [2n², 3n²) depth out (ts_classify); the coverage as
     * bytes after it */
    float *stretch = s->ts_scratch;
    unsigned char *full = (unsigned char *)(s->ts_scratch + 3 * texels);
    /* read back as stored (half floats: a copy, no conversion in the driver) */
    uint16_t *irr = malloc(texels * 4 * sizeof(uint16_t));
    if (!irr) return false;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(s->ts_tex[TS_IRR], 0, GL_RGBA, GL_HALF_FLOAT, (GLsizei)(texels * 4 * sizeof(uint16_t)), irr);
    /* 1: fully covered (alpha exactly 1), 2: uncovered (all zero, as cleared), 0: anything else */
    for (size_t i = 0; i < texels; i++) {
        const uint16_t *t = irr + i * 4;
        full[i] = t[3] == 0x3C00 ? 1 : !((t[0] | t[1] | t[2] | t[3]) & 0x7FFF) ? 2 : 0;
    }
    uint64_t h = key ? sss_hash(irr, texels * 4 * sizeof(uint16_t), s->code_hash) : 0;
    glGetTextureImage(s->ts_tex[TS_STRETCH], 0, GL_RG, GL_HALF_FLOAT, (GLsizei)(texels * 2 * sizeof(uint16_t)), irr);
    if (key) *key = blur_key(s, sss_hash(irr, texels * 2 * sizeof(uint16_t), h));
    /* every half float's value: static storage (a malloc'd table held by a static pointer leaks
     * once the plugin is unloaded: LeakSanitizer, tests/sanitize) */
    static float lut[65536];
    static bool lut_ready;
    if (!lut_ready) {
        for (int v = 0; v < 65536; v++) lut[v] = half_to_float((uint16_t)v);
        lut_ready = true;
    }
    for (size_t i = 0; i < 2 * texels; i++) stretch[i] = lut[irr[i]];
    free(irr);
    return true;
}

/* The per-direction interior depth textures from what ts_read_inputs left in the scratch. */
static bool ts_classify(sss *s) {
    int n = s->ts_size;
    size_t texels = (size_t)n * n;
    float *stretch = s->ts_scratch, *depth = s->ts_scratch + 2 * texels;
    unsigned char *full = (unsigned char *)(s->ts_scratch + 3 * texels);
    int *run = calloc((size_t)n, sizeof(int)); /* along v: one running count per column */
    if (!run) return false;
    for (int axis = 0; axis < 2; axis++) {
        /* depth[i] = distance to the previous texel not fully covered (the border counts as one),
         * then, backwards, the smaller of that and the distance to the next one: D (1 = the texel
         * itself is the last covered one). Along u a row at a time, along v all columns at once
         * (row by row, cache-friendly). */
        if (axis == 0) {
            for (int y = 0; y < n; y++) {
                int d = 0;
                for (int x = 0; x < n; x++) {
                    size_t i = (size_t)y * n + x;
                    d = full[i] == 1 ? d + 1 : 0;
                    depth[i] = (float)d;
                }
                d = 0;
                for (int x = n - 1; x >= 0; x--) {
                    size_t i = (size_t)y * n + x;
                    d = full[i] == 1 ? d + 1 : 0;
                    depth[i] = fminf(depth[i], (float)d);
                }
            }
        } else {
            memset(run, 0, (size_t)n * sizeof(int));
            for (int y = 0; y < n; y++)
                for (int x = 0; x < n; x++) {
                    size_t i = (size_t)y * n + x;
                    run[x] = full[i] == 1 ? run[x] + 1 : 0;
                    depth[i] = (float)run[x];
                }
            memset(run, 0, (size_t)n * sizeof(int));
            for (int y = n - 1; y >= 0; y--)
                for (int x = 0; x < n; x++) {
                    size_t i = (size_t)y * n + x;
                    run[x] = full[i] == 1 ? run[x] + 1 : 0;
                    depth[i] = fminf(depth[i], (float)run[x]);
                }
        }
        for (size_t i = 0; i < texels; i++) {
            float mpt = stretch[i * 2 + axis];
            depth[i] = full[i] == 2 ? 1.0f
                     : full[i] == 0 || !(mpt > 0) ? 0.0f
                     : fminf(fmaxf((depth[i] - 1.5f) * mpt / TS_CLASS_MM, 0.0f), 1.0f);
        }
        glTextureSubImage2D(s->ts_class[axis], 0, 0, 0, n, n, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
    }
    free(run);
    return true;
}

/* One blur step split in two draws (see ts_classify): interior texels with `fast`, the others with
 * `full`; both programs hold the same uniforms. */
static void ts_split_draw(sss *s, unsigned fast, unsigned full, float sigma_mm) {
    double z = fmin(3.0 * sigma_mm / TS_CLASS_MM, 1.0);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glDepthRange(z, z); /* the full-screen triangle's depth, whatever its NDC z */
    glBindVertexArray(s->ts_vao);
    glUseProgram(fast);
    glDepthFunc(GL_LESS);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glUseProgram(full);
    glDepthFunc(GL_GEQUAL);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDepthRange(0, 1);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
}

/* A cached result for key: uploaded into its sum texture, which becomes the result. */
static bool ts_from_cache(sss *s, uint64_t key) {
    int result = 0;
    float *px = sss_cache_load(key, s->ts_size, &result);
    bool ok = px && (result == TS_SUM0 || result == TS_SUM1);
    if (ok) {
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTextureSubImage2D(s->ts_tex[result], 0, 0, 0, s->ts_size, s->ts_size, GL_RGBA, GL_FLOAT, px);
        s->ts_result = result;
        s->cache_loads++;
        s->host->log(s->host, SL_LOG_DEBUG, "texture space: the diffusion's result from the cache (%016llx)",
                     (unsigned long long)key);
    }
    free(px);
    return ok;
}

static void ts_store_pending(sss *s) {
    if (!s->store_pending) return;
    s->store_pending = false;
    if (!s->ts_tex[s->ts_result]) return;
    size_t bytes = (size_t)s->ts_size * s->ts_size * 4 * sizeof(float);
    float *px = malloc(bytes);
    if (!px) return;
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(s->ts_tex[s->ts_result], 0, GL_RGBA, GL_FLOAT, (GLsizei)bytes, px);
    char err[2600];
    if (!sss_cache_store(s->store_key, s->ts_size, s->ts_result, px, err, sizeof err))
        s->host->log(s->host, SL_LOG_WARN, "could not write the texture-space cache: %s", err);
    free(px);
}

/* The chain of blurs and the dilation (ts_blur_execute). warm_up: the first step's draws and the
 * dilation under an empty scissor, which rasterise nothing but make llvmpipe compile each program for
 * the state it is drawn with (the compile happens at a program's first draw, on this thread), into
 * targets of their own (ensure_ts) and sampling what the blurs sample, none of it written by a draw
 * of this frame yet. */
static void ts_blur_draws(sss *s, sl_pass_ctx *ctx, const unsigned prog[2], const unsigned fast[2], bool use_fast,
                          bool warm_up) {
    const sl_host *h = s->host;
    unsigned progs[4] = {prog[0], prog[1], use_fast ? fast[0] : 0, use_fast ? fast[1] : 0};
#define U(p, name) glGetUniformLocation(p, name)
#define EACH for (int k = 0; k < 4; k++) if (progs[k])
    EACH {
        unsigned p = progs[k];
        glProgramUniform1i(p, U(p, "sss_src"), 0);
        glProgramUniform1i(p, U(p, "sss_stretch_map"), 1);
        glProgramUniform1i(p, U(p, "sss_sum_in"), 2);
        glProgramUniform1i(p, U(p, "sss_taps"), s->key_ts_taps);
        glProgramUniform1fv(p, U(p, "sss_offsets"), s->key_ts_taps, s->ts_offsets);
        glProgramUniform1fv(p, U(p, "sss_weights"), s->key_ts_taps, s->ts_weights);
        glProgramUniform1f(p, U(p, "sss_max_texels"), s->ts_size / 8.0f);
        glProgramUniform2f(p, U(p, "sss_dir"), k % 2 == 0 ? 1.0f : 0.0f, k % 2 == 0 ? 0.0f : 1.0f);
    }
    glBindTextureUnit(1, s->ts_tex[TS_STRETCH]);
    /* Unit 2 holds a sum texture in every draw, also the first pass along u (which does not read
     * it): on llvmpipe each compiled variant's key has the state of every unit the program
     * samples, so an empty unit there compiled the programs a third time at the first frame, and
     * under a key that differed from run to run (no warm start found it in Mesa's disk cache). */
    glBindTextureUnit(2, s->ts_tex[TS_SUM1]);
    glViewport(0, 0, s->ts_size, s->ts_size);
    const unsigned *fbo = warm_up ? s->warm_fbo : s->ts_fbo; /* the warm-up's own targets (ensure_ts) */
    unsigned src = s->ts_tex[TS_IRR];
    double previous = 0;
    for (int g = 0; g < (warm_up ? 1 : s->gauss.n); g++) {
        float sigma = (float)sqrt(fmax(s->gauss.variance[g] - previous, 0.0));
        previous = s->gauss.variance[g];
        EACH glProgramUniform1f(progs[k], U(progs[k], "sss_sigma_mm"), sigma);
        /* along u into tmp */
        glBindFramebuffer(GL_FRAMEBUFFER, fbo[2]);
        glBindTextureUnit(0, src);
        glUseProgram(prog[0]);
        if (use_fast) ts_split_draw(s, fast[0], prog[0], sigma);
        else h->draw_fullscreen(h, ctx);
        /* along v back into the chain and into the sum (0, 1 alternating) */
        bool even = g % 2 == 0;
        glBindFramebuffer(GL_FRAMEBUFFER, fbo[even ? 3 : 4]);
        glBindTextureUnit(0, s->ts_tex[TS_TMP]);
        glBindTextureUnit(2, s->ts_tex[even ? TS_SUM1 : TS_SUM0]);
        EACH {
            unsigned p = progs[k];
            glProgramUniform3f(p, U(p, "sss_acc_weight"), (float)s->gauss.weight[g][0], (float)s->gauss.weight[g][1],
                               (float)s->gauss.weight[g][2]);
            glProgramUniform1i(p, U(p, "sss_first"), g == 0);
        }
        glUseProgram(prog[1]);
        if (use_fast) ts_split_draw(s, fast[1], prog[1], sigma);
        else h->draw_fullscreen(h, ctx);
        src = s->ts_tex[TS_A];
        if (!warm_up) s->ts_result = even ? TS_SUM0 : TS_SUM1;
    }
#undef EACH
#undef U
    /* one texel of linear extrapolation beyond the chart edges, into the other sum texture */
    unsigned dilate = h->program_id(h, s->dilate_prog);
    if (dilate) {
        glUseProgram(dilate);
        glUniform1i(glGetUniformLocation(dilate, "sss_src"), 0);
        glBindTextureUnit(0, s->ts_tex[s->ts_result]);
        bool into1 = s->ts_result == TS_SUM0;
        glBindFramebuffer(GL_FRAMEBUFFER, fbo[into1 ? 6 : 5]);
        if (warm_up) { /* the state draw_fullscreen draws with, but not counted as a draw of the frame */
            glDisable(GL_DEPTH_TEST);
            glDisable(GL_CULL_FACE);
            glBindVertexArray(s->ts_vao);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glBindVertexArray(0);
        } else {
            h->draw_fullscreen(h, ctx);
            s->ts_result = into1 ? TS_SUM1 : TS_SUM0;
        }
    }
    for (int u = 0; u < 3; u++) glBindTextureUnit(u, 0);
}

/* The blur programs (along u and along v: one program object per pass, the same source: the two
 * passes draw into different targets, one colour buffer and two, and llvmpipe compiles a program
 * once per state; with one program for both, the second state's compile missed Mesa's disk cache
 * at the first warm start, its key hashed over the program's IR after the first state's compile
 * changed it). false when one is missing. */
static bool ts_programs(sss *s, unsigned prog[2], unsigned fast[2], unsigned *dilate) {
    const sl_host *h = s->host;
    prog[0] = h->program_id(h, s->ts_prog[0]), prog[1] = h->program_id(h, s->ts_prog[1]);
    fast[0] = h->program_id(h, s->ts_interior_prog[0]), fast[1] = h->program_id(h, s->ts_interior_prog[1]);
    *dilate = h->program_id(h, s->dilate_prog);
    return prog[0] && prog[1];
}

/* On a CPU renderer (llvmpipe compiles a program at its first draw, on the calling thread) the
 * blur programs are compiled by drawing them under an empty scissor before their turn, while the
 * rasteriser works on what was queued before, instead of at the blurs' own draws, which follow the
 * read-back of the irradiance with the rasteriser idle (≈ 0.35 s of compiles at a cold start; a
 * few ms at a warm one, Mesa disk cache hits). Called first by the stretch pass, while the
 * rasteriser works on envmap's prefilter; and again by the blur pass, for program sets the stretch
 * pass did not see (it is skipped while the geometry does not change). Once per program set. */
static void ts_warm_up(sss *s, sl_pass_ctx *ctx) {
    const sl_host *h = s->host;
    unsigned prog[2], fast[2], dilate;
    if (h->is_gpu(h) || !ts_programs(s, prog, fast, &dilate) || !fast[0] || !fast[1]) return;
    if (getenv("SHADELAB_SSS_FULL_BLUR")) return; /* the full program everywhere: no split draws */
    if (s->warmed[0] == prog[0] && s->warmed[1] == prog[1] && s->warmed[2] == fast[0] && s->warmed[3] == fast[1] &&
        s->warmed[4] == dilate)
        return;
    ensure_ts(s);
    if (!s->ts_vao) glCreateVertexArrays(1, &s->ts_vao);
    int box[4];
    glGetIntegerv(GL_SCISSOR_BOX, box);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 0, 0);
    ts_blur_draws(s, ctx, prog, fast, true, true);
    glDisable(GL_SCISSOR_TEST);
    glScissor(box[0], box[1], box[2], box[3]);
    s->warmed[0] = prog[0], s->warmed[1] = prog[1], s->warmed[2] = fast[0], s->warmed[3] = fast[1];
    s->warmed[4] = dilate;
}

/* Texture space 3: the chain of separable blurs, each v pass adding wᵢ·blurᵢ to the sum. */
static void ts_blur_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    sss *s = user;
    const sl_host *h = s->host;
    unsigned prog[2], fast[2], dilate;
    if (!ts_programs(s, prog, fast, &dilate)) return;
    ensure_ts(s);
    bool use_fast = fast[0] && fast[1];
    if (use_fast && !s->ts_vao) glCreateVertexArrays(1, &s->ts_vao);
    /* SHADELAB_SSS_FULL_BLUR=1: the full program on every texel (the tests compare the two; A/B timing) */
    if (use_fast && getenv("SHADELAB_SSS_FULL_BLUR")) use_fast = false;
    /* the disk cache goes with the interior path (the default; the full program's tests run without) */
    bool caching = use_fast && param(s, "cache").b;
    uint64_t key = 0;
    ts_warm_up(s, ctx);
    /* The same for the forward pass's programs (ABI 1.12), which sample this pass's result (its
     * textures exist now): their compiles overlap the rasteriser's work on the irradiance and what
     * was queued before it (envmap's GGX chain), instead of following the blurs, which wait for
     * each other. A forward program that samples the chain waits at its draw until the rasteriser
     * has finished it; the read-back below would wait for it anyway. */
    if (h->struct_size >= offsetof(sl_host, compile_ahead) + sizeof h->compile_ahead && h->compile_ahead)
        h->compile_ahead(h);
    if (use_fast && (!s->ts_vao || !ts_read_inputs(s, caching ? &key : NULL))) use_fast = caching = false;
    if (caching && ts_from_cache(s, key)) return;
    if (use_fast && !ts_classify(s)) use_fast = caching = false; /* then the full program everywhere */
    ts_blur_draws(s, ctx, prog, fast, use_fast, false);
    /* the first result of an activation goes to the disk cache, read back at the next frame or at
     * deactivate (not now: that would wait here for the blurs to finish) */
    if (caching && !s->stored) {
        s->store_pending = s->stored = true;
        s->store_key = key;
    }
}

/* Screen space 1: the skin's diffuse light (irradiance × pre-scatter albedo) with its depth. */
static void ss_diffuse_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    sss *s = user;
    ensure_ss(s, f->width, f->height);
    glBindFramebuffer(GL_FRAMEBUFFER, s->ss_fbo[0]);
    glViewport(0, 0, s->ss_w, s->ss_h);
    clear_bound(1);
    draw_materials(s, ctx, f, "sss-irradiance", false);
}

/* Screen space 2: horizontal then vertical depth-aware 1D convolution. */
static void ss_blur_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    sss *s = user;
    const sl_host *h = s->host;
    unsigned prog = h->program_id(h, s->ss_prog);
    if (!prog) return;
    ensure_ss(s, f->width, f->height);
    glUseProgram(prog);
#define U(name) glGetUniformLocation(prog, name)
    glUniform1i(U("sss_src"), 0);
    glUniform1i(U("sss_depth"), 1);
    glUniform1i(U("sss_kernel"), 2);
    float var[6] = {0};
    for (int g = 0; g < s->gauss.n; g++) var[g] = (float)s->gauss.variance[g];
    glUniform1fv(U("sss_variance"), 6, var);
    glUniform1i(U("sss_taps"), s->key_ss_taps);
    glUniform1i(U("sss_gaussians"), s->gauss.n);
    glUniform2f(U("sss_px_per_unit"), f->proj[0] * s->ss_w * 0.5f, f->proj[5] * s->ss_h * 0.5f);
    glUniform1f(U("sss_mm"), s->ss_mm);
    glUniform2f(U("sss_depth_params"), f->proj[10], f->proj[14]);
    glUniform1f(U("sss_max_px"), 0.25f * (s->ss_w > s->ss_h ? s->ss_w : s->ss_h));
    glUniform1i(U("sss_follow_surface"), param(s, "ss_follow_surface").b);
    glBindTextureUnit(1, s->ss_tex[SS_DEPTH]);
    glBindTextureUnit(2, s->kernel_tex);
    glViewport(0, 0, s->ss_w, s->ss_h);
    glDisable(GL_BLEND);
    glBindFramebuffer(GL_FRAMEBUFFER, s->ss_fbo[1]);
    glBindTextureUnit(0, s->ss_tex[SS_DIFFUSE]);
    glUniform2f(U("sss_dir"), 1, 0);
    h->draw_fullscreen(h, ctx);
    glBindFramebuffer(GL_FRAMEBUFFER, s->ss_fbo[2]);
    glBindTextureUnit(0, s->ss_tex[SS_TMP]);
    glUniform2f(U("sss_dir"), 0, 1);
    h->draw_fullscreen(h, ctx);
#undef U
    for (int u = 0; u < 3; u++) glBindTextureUnit(u, 0);
}

/* Shadow maps of the lights that cast shadows, once per frame (during the forward pass, so
 * they are this frame's). */
static void collect_maps(sss *s, const sl_frame *f) {
    if (s->maps_frame == f->index + 1) return;
    s->maps_frame = f->index + 1;
    s->map_count = 0;
    const sl_host *h = s->host;
    const sl_ext_shadow_maps *ext = h->get_extension(h, SL_EXT_SHADOW_MAPS);
    int n = 0;
    const sl_light_info *lights = h->lights(h, &n);
    for (int i = 0; ext && i < n; i++) {
        if (!lights[i].enabled || lights[i].index < 0 || !lights[i].cast_shadows) continue;
        int type = !strcmp(lights[i].type, "directional") ? 0 : !strcmp(lights[i].type, "point") ? 1
                 : !strcmp(lights[i].type, "spot")        ? 2 : -1;
        if (type < 0) {
            if (!s->warned_light_type)
                h->log(h, SL_LOG_WARN, "translucency: light \"%s\" of type %s is not supported (directional, point, "
                                       "spot are)", lights[i].name, lights[i].type);
            s->warned_light_type = true;
            continue;
        }
        for (int face = 0; face < (type == 1 ? 6 : 1) && s->map_count < MAX_MAPS; face++) {
            sl_shadow_map *m = &s->maps[s->map_count];
            memset(m, 0, sizeof *m);
            m->struct_size = sizeof *m;
            if (!ext->find(ext->ctx, i, face, m)) continue;
            s->map_type[s->map_count++] = type;
        }
    }
    if (!s->map_count && !s->warned_no_maps) {
        h->log(h, SL_LOG_WARN,
               "method translucency: %s; rendering without the transmitted light (load the spotlight-shadow plugin, "
               "which provides %s, and give a light \"cast_shadows\": true)",
               ext ? "no light has a shadow map" : "no shadow maps (no plugin provides " SL_EXT_SHADOW_MAPS ")",
               SL_EXT_SHADOW_MAPS);
        s->warned_no_maps = true;
    }
}

static void bind_program(void *user, unsigned program, int material, const sl_frame *f) {
    sss *s = user;
    int me = method(s);
#define U(name) glGetUniformLocation(program, name)
    glProgramUniform1i(program, U("sss_tex_diffuse"), s->unit_diffuse);
    glProgramUniform1i(program, U("sss_tex_lut"), s->unit_lut);
    glProgramUniform1i(program, U("sss_tex_shadow"), s->unit_shadow);
    unsigned diffuse = me == M_TEXTURE_SPACE ? s->ts_tex[s->ts_result] : me == M_SCREEN_SPACE ? s->ss_tex[SS_OUT] : 0;
    glBindTextureUnit(s->unit_diffuse, diffuse ? diffuse : s->dummy2d);
    glBindTextureUnit(s->unit_lut, s->lut_tex ? s->lut_tex : s->dummy2d);
    glProgramUniform3f(program, U("sss_lut_info"), LUT_W, LUT_H, (float)LUT_KAPPA_MAX);
    int count = 0;
    if (me == M_TRANSLUCENCY) {
        collect_maps(s, f);
        count = s->map_count;
    }
    glProgramUniform1i(program, U("sss_tl_count"), count);
    glBindTextureUnit(s->unit_shadow, count ? s->maps[0].texture : s->dummy_array);
    for (int t = 0; t < count; t++) {
        const sl_shadow_map *m = &s->maps[t];
        char name[64];
#define UA(field) (snprintf(name, sizeof name, "sss_tl_%s[%d]", field, t), glGetUniformLocation(program, name))
        glProgramUniformMatrix4fv(program, UA("view_proj"), 1, GL_FALSE, m->view_proj);
        glProgramUniform4f(program, UA("map"), (float)m->layer, m->near_plane, m->far_plane,
                           m->projection == SL_SHADOW_PERSPECTIVE ? 1.0f : 0.0f);
        glProgramUniform4f(program, UA("pos"), m->position[0], m->position[1], m->position[2],
                           s->map_type[t] == 1 ? (float)m->face : -1.0f);
        glProgramUniform4f(program, UA("dir"), m->direction[0], m->direction[1], m->direction[2], (float)s->map_type[t]);
        glProgramUniform1i(program, UA("light"), m->buffer_index);
#undef UA
    }
#undef U
}

/* ------------------------------------------------------------------ lifecycle ------------- */

static sl_status sss_create(const sl_host *host, void **user) {
    sss *s = calloc(1, sizeof *s);
    if (!s) return SL_ERR_FAILED;
    s->host = host;
    *user = s;
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
        if (host->add_key(host, &keys[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_pass_desc passes[] = {
        {.struct_size = sizeof(sl_pass_desc), .name = "sss-stretch", .stage = SL_STAGE_PREPASS, .execute = stretch_execute,
         .is_active = ts_active, .signature = stretch_signature, .user = s,
         .depends = SL_DEPENDS_GEOMETRY | SL_DEPENDS_MATERIALS},
        {.struct_size = sizeof(sl_pass_desc), .name = "sss-irradiance", .stage = SL_STAGE_PREPASS,
         .execute = irradiance_execute, .is_active = ts_active, .signature = irradiance_signature, .user = s,
         .depends = SL_DEPENDS_LIGHTS | SL_DEPENDS_GEOMETRY | SL_DEPENDS_MATERIALS}, /* not the camera */
        {.struct_size = sizeof(sl_pass_desc), .name = "sss-ts-blur", .stage = SL_STAGE_PREPASS, .execute = ts_blur_execute,
         .is_active = ts_active, .signature = irradiance_signature, .user = s,
         .depends = SL_DEPENDS_LIGHTS | SL_DEPENDS_GEOMETRY | SL_DEPENDS_MATERIALS},
        {.struct_size = sizeof(sl_pass_desc), .name = "sss-ss-diffuse", .stage = SL_STAGE_PREPASS,
         .execute = ss_diffuse_execute, .is_active = ss_active, .user = s,
         .depends = SL_DEPENDS_CAMERA | SL_DEPENDS_LIGHTS | SL_DEPENDS_GEOMETRY | SL_DEPENDS_MATERIALS},
        {.struct_size = sizeof(sl_pass_desc), .name = "sss-ss-blur", .stage = SL_STAGE_PREPASS, .execute = ss_blur_execute,
         .is_active = ss_active, .user = s,
         .depends = SL_DEPENDS_CAMERA | SL_DEPENDS_LIGHTS | SL_DEPENDS_GEOMETRY | SL_DEPENDS_MATERIALS},
    };
    for (size_t i = 0; i < sizeof passes / sizeof *passes; i++)
        if (host->add_pass(host, &passes[i]) != SL_OK) return SL_ERR_FAILED;
    if (host->set_bind_callback(host, bind_program, s) != SL_OK) return SL_ERR_FAILED;
    const sl_reference_desc ref = {
        .struct_size = sizeof ref,
        .settings = "sss.method=texture-space sss.ts_size=2048 sss.ts_taps=15 sss.gaussians=6",
        .accumulate_frames = 1,
        .description = "Texture-space diffusion with the full six-Gaussian profile at 2048x2048 and 15 taps per blur."};
    if (host->set_reference(host, &ref) != SL_OK) return SL_ERR_FAILED;
    s->unit_diffuse = host->reserve_texture_unit(host);
    s->unit_lut = host->reserve_texture_unit(host);
    s->unit_shadow = host->reserve_texture_unit(host);
    if (s->unit_diffuse < 0 || s->unit_lut < 0 || s->unit_shadow < 0) return SL_ERR_FAILED;
    return SL_OK;
}

static sl_status sss_activate(void *user) {
    sss *s = user;
    const sl_host *h = s->host;
    if (!sl_gl_load(h->gl_get_proc_address, NULL)) return SL_ERR_GL;
    for (int d = 0; d < 2; d++) { /* along u, along v (ts_blur_execute) */
        s->ts_prog[d] = h->load_program(h, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                               .vertex = "sl:fullscreen.vert", .fragment = "sss_ts_blur.frag"});
        s->ts_interior_prog[d] = h->load_program(h, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                        .vertex = "sl:fullscreen.vert",
                                                                        .fragment = "sss_ts_blur.frag",
                                                                        .defines = "SSS_TS_INTERIOR"});
    }
    s->dilate_prog = h->load_program(h, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                            .vertex = "sl:fullscreen.vert", .fragment = "sss_ts_dilate.frag"});
    s->ss_prog = h->load_program(h, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                        .vertex = "sl:fullscreen.vert", .fragment = "sss_ss_blur.frag"});
    if (!s->ts_prog[0] || !s->ts_prog[1] || !s->ts_interior_prog[0] || !s->ts_interior_prog[1] || !s->dilate_prog ||
        !s->ss_prog)
        return SL_ERR_GL;
    /* the cache key's code part: the blur's and dilation's GLSL, and the renderer that runs them
     * (another rasteriser rounds differently) */
    static const char *const glsl[] = {"sss_ts_blur.frag", "sss_ts_dilate.frag", "sss_lib.glsl", NULL};
    static const char *const sdk_glsl[] = {"fullscreen.vert", NULL};
    s->code_hash = sss_hash_files(h->resource_dir(h), glsl, 0x55c0de);
    s->code_hash = sss_hash_files(h->shader_dir(h), sdk_glsl, s->code_hash);
    for (GLenum e = GL_VENDOR; e <= GL_VERSION; e++) {
        const char *str = (const char *)glGetString(e);
        if (str) s->code_hash = sss_hash(str, strlen(str), s->code_hash);
    }
    static const float zero[4] = {0, 0, 0, 0};
    glCreateTextures(GL_TEXTURE_2D, 1, &s->dummy2d);
    glTextureStorage2D(s->dummy2d, 1, GL_RGBA16F, 1, 1);
    glTextureSubImage2D(s->dummy2d, 0, 0, 0, 1, 1, GL_RGBA, GL_FLOAT, zero);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &s->dummy_array);
    glTextureStorage3D(s->dummy_array, 1, GL_R32F, 1, 1, 1);
    glTextureSubImage3D(s->dummy_array, 0, 0, 0, 0, 1, 1, 1, GL_RED, GL_FLOAT, zero);
    glBindTextureUnit(s->unit_diffuse, s->dummy2d);
    glBindTextureUnit(s->unit_lut, s->dummy2d);
    glBindTextureUnit(s->unit_shadow, s->dummy_array);
    return SL_OK;
}

static void sss_deactivate(void *user) {
    sss *s = user;
    ts_store_pending(s);
    s->stored = false;
    free_ts(s);
    free_ss(s);
    if (s->ts_vao) glDeleteVertexArrays(1, &s->ts_vao);
    s->ts_vao = 0;
    unsigned t[4] = {s->kernel_tex, s->lut_tex, s->dummy2d, s->dummy_array};
    glDeleteTextures(4, t);
    s->kernel_tex = s->lut_tex = s->dummy2d = s->dummy_array = 0;
}

static void sss_destroy(void *user) { free(user); }

static const char *const sss_requires[] = {"ggx", NULL};

/* skin for materials; the other two are the texture-space passes' own models */
static const char *const sss_models[] = {"skin", "sss-irradiance", "sss-stretch", NULL};
static const sl_plugin_desc sss_desc = {
    SL_PLUGIN_HEADER,
    .id = "sss",
    .version = "1.0",
    .description = "Subsurface scattering for skin: wrap, translucency, texture-space diffusion, screen-space "
                   "separable SSS, pre-integrated skin; GGX specular.",
    .dependencies = sss_requires,
    .create = sss_create,
    .activate = sss_activate,
    .begin_frame = begin_frame,
    .deactivate = sss_deactivate,
    .destroy = sss_destroy,
    .shading_models = sss_models,
};

SL_DEFINE_PLUGIN(sss_desc)
