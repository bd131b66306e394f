/* Test plugin for test_upscaler (ABI 1.18, pass.h SL_SIZE_OUTPUT): an upscaler pass whose "color"
 * output has the output size and writes, per output pixel, the render texel it falls in (nearest
 * neighbour: rg = texel x, y; b = the render width it read), and a pass after it that writes the
 * sl_frame.width it was given into alpha, so a test reads the sizes each pass saw. The upscaler
 * runs while tp-upscale.active is on; the core scales up bilinearly when it does not. */
#include <shadelab/shadelab.h>
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include <stdlib.h>

typedef struct tpu { const sl_host *host; sl_program *up, *after; } tpu;

static const char *const color_in[] = {"color", NULL};
static const sl_target_desc upscaled[] = {{.name = "color", .format = SL_FORMAT_RGBA32F, .width = SL_SIZE_OUTPUT}};
static const sl_target_desc in_place[] = {{.name = "color", .format = SL_FORMAT_RGBA32F}};

static void draw(tpu *t, sl_pass_ctx *ctx, sl_program *prog, const sl_frame *f) {
    const sl_host *h = t->host;
    unsigned p = h->program_id(h, prog);
    if (!p || h->bind_outputs(h, ctx, 0) != SL_OK) return;
    glUseProgram(p);
    glBindTextureUnit(16, h->pass_texture(h, ctx, "color"));
    glUniform1i(glGetUniformLocation(p, "tp_color"), 16);
    glUniform1f(glGetUniformLocation(p, "tp_frame_width"), (float)f->width);
    h->draw_fullscreen(h, ctx);
}

static void up_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) { draw(user, ctx, ((tpu *)user)->up, f); }
static void after_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) { draw(user, ctx, ((tpu *)user)->after, f); }

static bool up_active(void *user, const sl_frame *f) {
    (void)f;
    tpu *t = user;
    return t->host->get_param(t->host, "tp-upscale.active").b;
}

static sl_status create(const sl_host *host, void **user) {
    tpu *t = calloc(1, sizeof *t);
    t->host = host;
    *user = t;
    const sl_param_desc active = {.struct_size = sizeof active, .id = "active", .type = SL_PARAM_BOOL,
                                  .default_value = {.b = true}, .description = "the upscaler runs"};
    if (host->add_param(host, &active) != SL_OK) return SL_ERR_FAILED;
    const sl_pass_desc up = {.struct_size = sizeof up, .name = "tp-upscale", .stage = SL_STAGE_POST, .inputs = color_in,
                             .outputs = upscaled, .output_count = 1, .execute = up_execute, .is_active = up_active,
                             .user = t};
    const sl_pass_desc after = {.struct_size = sizeof after, .name = "tp-after", .stage = SL_STAGE_POST + 10,
                                .inputs = color_in, .outputs = in_place, .output_count = 1, .execute = after_execute,
                                .user = t};
    return host->add_pass(host, &up) == SL_OK && host->add_pass(host, &after) == SL_OK ? SL_OK : SL_ERR_FAILED;
}

static sl_status activate(void *user) {
    tpu *t = user;
    if (!sl_gl_load(t->host->gl_get_proc_address, NULL)) return SL_ERR_GL;
    t->up = t->host->load_program(t->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                               .vertex = "sl:fullscreen.vert", .fragment = "tp_upscale.frag"});
    t->after = t->host->load_program(t->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                  .vertex = "sl:fullscreen.vert",
                                                                  .fragment = "tp_upscale.frag", .defines = "TP_AFTER 1"});
    return t->up && t->after ? SL_OK : SL_ERR_GL;
}

static void destroy(void *user) { free(user); }

static const sl_plugin_desc desc = {SL_PLUGIN_HEADER, .id = "tp-upscale", .version = "1",
                                    .description = "test: an upscaler pass (SL_SIZE_OUTPUT) and a pass after it",
                                    .create = create, .activate = activate, .destroy = destroy};
SL_DEFINE_PLUGIN(desc)
