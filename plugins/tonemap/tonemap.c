/* tonemap: a post pass on the linear HDR buffer (exposure ×2^E, then linear, Reinhard, extended
 * Reinhard, ACES fitted, AgX or Khronos PBR Neutral), optional dithering and a false-colour
 * exposure view. The core's display encoding (clamp + sRGB) follows it: on the fly as it writes
 * when it is the last pass (display_on_write), else the core's display pass. The operators
 * are tonemap_ops.glsl; shadelab-tonemap-curves plots them. The per-pixel map is also offered to
 * the pass before it (shadelab.post/1: TAA's draw runs it, and this pass does not run). See
 * README.md. */
#include <shadelab/shadelab.h>
#include <shadelab/ext/post.h>
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include <stdio.h>
#include <stdlib.h>

static const char *const operators[] = {"linear", "reinhard", "reinhard-extended", "aces", "agx", "pbr-neutral", NULL};
#define OPERATORS 6 /* tonemap_ops.glsl's TONEMAP_LINEAR .. TONEMAP_PBR_NEUTRAL */
_Static_assert(sizeof operators / sizeof *operators == OPERATORS + 1, "one program per operator");

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}
static const sl_param_desc params[] = {
    P(.id = "operator", .type = SL_PARAM_ENUM, .enum_values = operators, .default_value = {.i = 5},
      .description = "Tone curve applied after exposure: linear (identity), reinhard, reinhard-extended (white point), "
                     "aces (Hill's fit), agx, pbr-neutral (Khronos)."),
    P(.id = "exposure", .type = SL_PARAM_FLOAT, .min = -16, .max = 16, .step = 0.1f, .unit = "EV",
      .description = "Exposure in stops: radiance is multiplied by 2^exposure before the operator."),
    P(.id = "white", .type = SL_PARAM_FLOAT, .default_value = {.f = {4}}, .min = 0.01f, .max = 10000, .step = 0.1f,
      .description = "reinhard-extended: the radiance (after exposure) that maps to display white."),
    P(.id = "dither", .type = SL_PARAM_BOOL, .default_value = {.b = true},
      .description = "Triangular dither of +-1 code value of the 8-bit display, against banding."),
    P(.id = "false_color", .type = SL_PARAM_BOOL,
      .description = "False-colour exposure view: luminance in stops from middle grey as colour bands."),
};

/* The program per permutation: [operator, or OPERATORS for the false-colour view][dither]. */
typedef struct tonemap {
    const sl_host *host;
    sl_program *prog[OPERATORS + 1][2];
    int unit;
    char defines[128]; /* this frame's permutation (tonemap_point.glsl) */
} tonemap;

static sl_value param(tonemap *t, const char *id) {
    char full[64];
    snprintf(full, sizeof full, "tonemap.%s", id);
    return t->host->get_param(t->host, full);
}

/* Linear at exposure 0 without dither or false colour is the identity: the pass costs nothing. */
static bool active(void *user, const sl_frame *f) {
    tonemap *t = user;
    return param(t, "operator").i != 0 || param(t, "exposure").f[0] != 0 || param(t, "dither").b ||
           param(t, "false_color").b;
}

/* The permutation of tonemap_point.glsl the settings select: [operator, or OPERATORS for the
 * false-colour view][dither]. */
static void permutation(tonemap *t, int *op, int *dither) {
    *op = param(t, "operator").i;
    if (*op < 0 || *op >= OPERATORS) *op = 0;
    if (param(t, "false_color").b) *op = OPERATORS;
    *dither = param(t, "dither").b;
}

static const char *defines_of(int m, int d, char *buf, size_t n) {
    snprintf(buf, n, "TONEMAP_OPERATOR %d\nTONEMAP_FALSE_COLOR %d\nTONEMAP_DITHER %d", m < OPERATORS ? m : 0, m == OPERATORS, d);
    return buf;
}

/* the uniforms of tonemap_point.glsl, in this pass's program or in one it is fused into */
static void bind_point(void *user, unsigned p, const sl_frame *f) {
    tonemap *t = user;
    glUniform1f(glGetUniformLocation(p, "tonemap_exposure_ev"), param(t, "exposure").f[0]);
    glUniform1f(glGetUniformLocation(p, "tonemap_white_point"), param(t, "white").f[0]);
    glUniform1i(glGetUniformLocation(p, "tonemap_frame"), (int)(f->index & 0x7fffffff));
}

static const char *point_defines(void *user, const sl_frame *f) {
    (void)f;
    tonemap *t = user;
    int m, d;
    permutation(t, &m, &d);
    return defines_of(m, d, t->defines, sizeof t->defines);
}

static void execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    tonemap *t = user;
    const sl_host *h = t->host;
    unsigned src = h->pass_texture(h, ctx, "color");
    if (h->bind_outputs(h, ctx, 0) != SL_OK) return;
    int m, d;
    permutation(t, &m, &d);
    unsigned p = h->program_id(h, t->prog[m][d]);
    if (!p) return;
    glUseProgram(p);
    glBindTextureUnit(t->unit, src);
    glUniform1i(glGetUniformLocation(p, "tonemap_src"), t->unit);
    bind_point(t, p, f);
    h->draw_fullscreen(h, ctx);
}

static const char *const inputs[] = {"color", NULL};
static const sl_target_desc outputs[] = {{.name = "color", .format = SL_FORMAT_RGBA16F}};

static sl_status create(const sl_host *host, void **user) {
    tonemap *t = calloc(1, sizeof *t);
    t->host = host;
    *user = t;
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_pass_desc pass = {.struct_size = sizeof pass, .name = "tonemap", .stage = SL_STAGE_TONEMAP, .inputs = inputs,
                               .outputs = outputs, .output_count = 1, .execute = execute, .is_active = active, .user = t,
                               .depends = SL_DEPENDS_INPUTS | SL_DEPENDS_OWN_PARAMS,
                               .display_on_write = true /* ABI 1.8: as the last pass it writes the display */,
                               .draws_only = true /* ABI 1.12: compiled ahead (host->compile_ahead) */};
    if (host->add_pass(host, &pass) != SL_OK) return SL_ERR_FAILED;
    /* the map alone, for a pass before this one to run in its own draw (TAA): one full-screen
     * read and write of the image less */
    const sl_ext_post *post = host->get_extension(host, SL_EXT_POST);
    const sl_pointwise_desc point = {.struct_size = sizeof point, .pass = "tonemap", .file = "tonemap_point.glsl",
                                     .function = "tonemap_point", .defines = point_defines, .bind = bind_point,
                                     .user = t};
    if (post && post->add_pointwise(host, &point) != SL_OK) return SL_ERR_FAILED;
    static const sl_key_desc keys[] = {
        {.struct_size = sizeof(sl_key_desc), .key = "O", .param = "operator", .description = "next tone-mapping operator"},
        {.struct_size = sizeof(sl_key_desc), .key = "K", .param = "false_color", .description = "false-colour exposure view"},
    };
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
        if (host->add_key(host, &keys[i]) != SL_OK) return SL_ERR_FAILED;
    if ((t->unit = host->reserve_texture_unit(host)) < 0) return SL_ERR_FAILED;
    return SL_OK;
}

static sl_status activate(void *user) {
    tonemap *t = user;
    if (!sl_gl_load(t->host->gl_get_proc_address, NULL)) return SL_ERR_GL;
    /* every permutation is loaded, and each compiles when the pass first draws it (lazy): a session
     * compiles the ones its settings use */
    for (int m = 0; m <= OPERATORS; m++)
        for (int d = 0; d < 2; d++) {
            char defines[128];
            defines_of(m, d, defines, sizeof defines);
            t->prog[m][d] = t->host->load_program(t->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                               .vertex = "sl:fullscreen.vert",
                                                                               .fragment = "tonemap.frag", .defines = defines});
            if (!t->prog[m][d]) return SL_ERR_GL;
        }
    return SL_OK;
}

static void destroy(void *user) { free(user); }

static const sl_plugin_desc desc = {
    SL_PLUGIN_HEADER,
    .id = "tonemap",
    .version = "1.0",
    .description = "Tone mapping of the linear HDR buffer: exposure, linear/Reinhard/extended Reinhard/ACES/AgX/PBR "
                   "Neutral, dithering, false-colour exposure view.",
    .create = create,
    .activate = activate,
    .destroy = destroy,
    .default_for = SL_PLUGIN_DEFAULT_MODEL_FILE, /* a model file opened directly is tone mapped */
};

SL_DEFINE_PLUGIN(desc)
