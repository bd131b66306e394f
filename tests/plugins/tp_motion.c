/* Test plugin for test_gltf_blend: a post pass that reads the core's "motion" resource (so the
 * forward pass writes it) and shows it as colour, rg = UV now minus UV in the previous frame, b = 0,
 * so a test reads motion vectors back through sl_harness_render. */
#include <shadelab/shadelab.h>
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include <stdlib.h>

typedef struct tpm { const sl_host *host; sl_program *prog; } tpm;

static const char *const inputs[] = {"color", "motion", NULL};
static const sl_target_desc outputs[] = {{.name = "color", .format = SL_FORMAT_RGBA32F}};

static void show_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    (void)f;
    tpm *t = user;
    const sl_host *h = t->host;
    if (h->bind_outputs(h, ctx, 0) != SL_OK) return;
    unsigned prog = h->program_id(h, t->prog);
    if (!prog) return;
    glUseProgram(prog);
    glBindTextureUnit(16, h->pass_texture(h, ctx, "motion"));
    glUniform1i(glGetUniformLocation(prog, "tp_motion"), 16);
    h->draw_fullscreen(h, ctx);
}

static sl_status create(const sl_host *host, void **user) {
    tpm *t = calloc(1, sizeof *t);
    t->host = host;
    *user = t;
    const sl_pass_desc pass = {.struct_size = sizeof pass, .name = "tp-motion-show", .stage = SL_STAGE_POST,
                               .inputs = inputs, .outputs = outputs, .output_count = 1, .execute = show_execute,
                               .user = t};
    return host->add_pass(host, &pass);
}

static sl_status activate(void *user) {
    tpm *t = user;
    if (!sl_gl_load(t->host->gl_get_proc_address, NULL)) return SL_ERR_GL;
    t->prog = t->host->load_program(t->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                 .vertex = "sl:fullscreen.vert",
                                                                 .fragment = "tp_motion.frag"});
    return t->prog ? SL_OK : SL_ERR_GL;
}

static void destroy(void *user) { free(user); }

static const sl_plugin_desc desc = {SL_PLUGIN_HEADER, .id = "tp-motion", .version = "1",
                                    .description = "test: shows the motion vectors as colour",
                                    .create = create, .activate = activate, .destroy = destroy};
SL_DEFINE_PLUGIN(desc)
