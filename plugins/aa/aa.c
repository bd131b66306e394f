/* aa: antialiasing as post passes. FXAA (Lottes 2009) on the display-referred colour at the end of
 * the post chain; TAA (Karis 2014) on linear HDR colour right after the opaque passes, fed by the
 * core's projection jitter and motion vectors. The reference is the core's 8x8 supersampling.
 * See README.md. */
#include <shadelab/shadelab.h>
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const methods[] = {"none", "fxaa", "taa", NULL};
enum { AA_NONE, AA_FXAA, AA_TAA };

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}
static const sl_param_desc params[] = {
    P(.id = "method", .type = SL_PARAM_ENUM, .enum_values = methods, .default_value = {.i = AA_FXAA},
      .flags = SL_PARAM_QUALITY_KNOB, .group = "method",
      .description = "none; fxaa (Lottes 2009: edge-directed blend of the final image, one pass); taa (Karis 2014: "
                     "jittered frames accumulated with motion-vector reprojection, neighbourhood clamping and "
                     "disocclusion rejection; a still converges after taa_frames frames)."),
    P(.id = "fxaa_threshold", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.125f}}, .min = 0.03f, .max = 0.5f,
      .step = 0.005f, .group = "fxaa",
      .description = "FXAA: contrast of the 4-neighbourhood's display luma, relative to its brightest, below which a "
                     "pixel is left untouched (Lottes: 1/8 high quality, 1/4 fast)."),
    P(.id = "fxaa_threshold_min", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.0625f}}, .min = 0, .max = 0.25f,
      .step = 0.005f, .group = "fxaa",
      .description = "FXAA: absolute contrast below which a pixel is left untouched (dark areas; Lottes 1/16..1/12)."),
    P(.id = "fxaa_subpix", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.75f}}, .min = 0, .max = 1, .step = 0.05f,
      .group = "fxaa", .description = "FXAA: strength of the sub-pixel blend (single-pixel features; 0 off, 1 soft)."),
    P(.id = "taa_frames", .type = SL_PARAM_INT, .default_value = {.i = 8}, .min = 1, .max = 64, .step = 1,
      .group = "taa",
      .description = "TAA: length of the jitter sequence (Halton 2,3) and of the history: a still is the exact mean "
                     "of this many jittered frames, after that each frame has weight 1/taa_frames. A headless still "
                     "renders this many frames (see README)."),
    P(.id = "taa_clamp", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "taa",
      .description = "TAA: clip the history to the current 3x3 neighbourhood's colour box in YCoCg (Karis 2014); off "
                     "shows the ghosts it prevents."),
    P(.id = "taa_reject", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .group = "taa",
      .description = "TAA: drop the history where the reprojected surface is not this one (disocclusion: the depth "
                     "there does not match) or falls outside the last frame."),
};

typedef struct aa {
    const sl_host *host;
    sl_program *fxaa, *taa;
    int unit0, unit1, unit2, unit3;
    unsigned sampler_linear, sampler_nearest;
} aa;

static sl_value param(aa *a, const char *id) {
    char full[64];
    snprintf(full, sizeof full, "aa.%s", id);
    return a->host->get_param(a->host, full);
}

/* ------------------------------------------------------------------ FXAA ------------ */

static bool fxaa_active(void *user, const sl_frame *f) {
    (void)f;
    return param(user, "method").i == AA_FXAA;
}

static void fxaa_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    (void)f;
    aa *a = user;
    const sl_host *h = a->host;
    unsigned src = h->pass_texture(h, ctx, "color");
    if (h->bind_outputs(h, ctx, 0) != SL_OK) return;
    unsigned p = h->program_id(h, a->fxaa);
    if (!p) return;
    glUseProgram(p);
    glBindTextureUnit(a->unit0, src);
    glBindSampler(a->unit0, a->sampler_linear);
    glUniform1i(glGetUniformLocation(p, "aa_src"), a->unit0);
    glUniform1f(glGetUniformLocation(p, "aa_edge_threshold"), param(a, "fxaa_threshold").f[0]);
    glUniform1f(glGetUniformLocation(p, "aa_edge_threshold_min"), param(a, "fxaa_threshold_min").f[0]);
    glUniform1f(glGetUniformLocation(p, "aa_subpix"), param(a, "fxaa_subpix").f[0]);
    h->draw_fullscreen(h, ctx);
    glBindSampler(a->unit0, 0);
}

/* ------------------------------------------------------------------ plugin ---------- */

static const char *const fxaa_inputs[] = {"color", NULL};
static const sl_target_desc color_out[] = {{.name = "color", .format = SL_FORMAT_RGBA16F}};

/* FXAA runs last before the display encoding: after tone mapping and display-referred effects,
 * on the image as it will be seen (Lottes: after everything but the UI). */
#define AA_STAGE_FXAA (SL_STAGE_DISPLAY_REFERRED + 10)

static sl_status create(const sl_host *host, void **user) {
    aa *a = calloc(1, sizeof *a);
    a->host = host;
    *user = a;
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_pass_desc fxaa = {.struct_size = sizeof fxaa, .name = "aa-fxaa", .stage = AA_STAGE_FXAA,
                               .inputs = fxaa_inputs, .outputs = color_out, .output_count = 1,
                               .execute = fxaa_execute, .is_active = fxaa_active, .user = a};
    if (host->add_pass(host, &fxaa) != SL_OK) return SL_ERR_FAILED;
    static const sl_key_desc key = {.struct_size = sizeof(sl_key_desc), .key = "X", .param = "method",
                                    .description = "next antialiasing method (none, fxaa, taa)"};
    if (host->add_key(host, &key) != SL_OK) return SL_ERR_FAILED;
    const sl_reference_desc ref = {.struct_size = sizeof ref, .settings = "aa.method=none core.ssaa=8",
                                   .accumulate_frames = 1,
                                   .description = "8x8 supersampling box-filtered in linear HDR (core.ssaa=8), no post AA"};
    if (host->set_reference(host, &ref) != SL_OK) return SL_ERR_FAILED;
    if ((a->unit0 = host->reserve_texture_unit(host)) < 0) return SL_ERR_FAILED;
    return SL_OK;
}

static sl_status activate(void *user) {
    aa *a = user;
    if (!sl_gl_load(a->host->gl_get_proc_address, NULL)) return SL_ERR_GL;
    a->fxaa = a->host->load_program(a->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                  .vertex = "sl:fullscreen.vert", .fragment = "fxaa.frag"});
    glCreateSamplers(1, &a->sampler_linear);
    glSamplerParameteri(a->sampler_linear, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(a->sampler_linear, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(a->sampler_linear, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(a->sampler_linear, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return a->host->program_id(a->host, a->fxaa) ? SL_OK : SL_ERR_GL;
}

static void deactivate(void *user) {
    aa *a = user;
    glDeleteSamplers(1, &a->sampler_linear);
    a->sampler_linear = 0;
}

static void destroy(void *user) { free(user); }

static const sl_plugin_desc desc = {
    SL_PLUGIN_HEADER,
    .id = "aa",
    .version = "1.0",
    .description = "Antialiasing: FXAA (Lottes 2009) and TAA (Karis 2014: jitter, motion-vector reprojection, "
                   "neighbourhood clamping, disocclusion rejection); reference: core.ssaa=8.",
    .create = create,
    .activate = activate,
    .deactivate = deactivate,
    .destroy = destroy,
};

SL_DEFINE_PLUGIN(desc)
