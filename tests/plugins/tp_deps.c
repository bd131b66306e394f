/* Test plugin for declared pass dependencies (pass.h, sl_depends, ABI 1.8): one pass per
 * dependency category, each writing a 1×1 target of its own (so its output persists), plus
 *   deps-every   SL_DEPENDS_EVERY_FRAME
 *   deps-none    nothing declared (0): every frame
 *   deps-old     declares LIGHTS but with the struct_size of an ABI 1.7 descriptor, so the host
 *                must not see the declaration: every frame
 *   deps-inputs  SL_DEPENDS_INPUTS on deps-camera's target
 *   deps-shared  declares LIGHTS but writes "color" in place (a POST pass): every frame, since
 *                its output does not persist
 * test_pass_skip counts which of them ran after each kind of change. It has a parameter of its
 * own (tp-deps.knob) and no shader chunk, so its parameters do not reach the material programs. */
#include <shadelab/shadelab.h>
#define SL_GL_IMPLEMENTATION /* the plugin's one file */
#include <shadelab/gl.h>
#include <stddef.h>
#include <stdlib.h>

typedef struct tpd { const sl_host *host; } tpd;

static void clear_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    (void)f;
    tpd *t = user;
    if (t->host->bind_outputs(t->host, ctx, 0) != SL_OK) return;
    glClearColor(0.25f, 0.5f, 0.75f, 1);
    glClear(GL_COLOR_BUFFER_BIT);
}

/* "color" in place: copies the input into the other half of the ping-pong pair unchanged */
static void copy_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    tpd *t = user;
    unsigned src_tex = t->host->pass_texture(t->host, ctx, "color");
    if (t->host->bind_outputs(t->host, ctx, 0) != SL_OK || !src_tex) return;
    GLint draw = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    GLuint src;
    glCreateFramebuffers(1, &src);
    glNamedFramebufferTexture(src, GL_COLOR_ATTACHMENT0, src_tex, 0);
    glBlitNamedFramebuffer(src, (GLuint)draw, 0, 0, f->width, f->height, 0, 0, f->width, f->height, GL_COLOR_BUFFER_BIT,
                           GL_NEAREST);
    glDeleteFramebuffers(1, &src);
}

#define OUT(n) static const sl_target_desc out_##n[] = {{.name = "tp-deps." #n, .format = SL_FORMAT_RGBA8, .width = 1, .height = 1}}
OUT(lights);
OUT(geometry);
OUT(camera);
OUT(materials);
OUT(own);
OUT(params);
OUT(time);
OUT(inputs);
OUT(every);
OUT(none);
OUT(old);
static const char *const camera_in[] = {"tp-deps.camera", NULL};
static const char *const color_in[] = {"color", NULL};
static const sl_target_desc color_out[] = {{.name = "color", .format = SL_FORMAT_RGBA16F}};

static sl_status create(const sl_host *host, void **user) {
    tpd *t = calloc(1, sizeof *t);
    if (!t) return SL_ERR_FAILED;
    t->host = host;
    *user = t;
    static const sl_param_desc knob = {.struct_size = sizeof(sl_param_desc), .id = "knob", .type = SL_PARAM_FLOAT,
                                       .default_value = {.f = {1}}, .min = 0, .max = 10,
                                       .description = "does nothing; a parameter of the plugin's own"};
    if (host->add_param(host, &knob) != SL_OK) return SL_ERR_FAILED;
#define PASS(n, dep, ...) {.struct_size = sizeof(sl_pass_desc), .name = "deps-" #n, .stage = SL_STAGE_PREPASS, \
                           .outputs = out_##n, .output_count = 1, .execute = clear_execute, .user = t, .depends = (dep), __VA_ARGS__}
    const sl_pass_desc passes[] = {
        PASS(lights, SL_DEPENDS_LIGHTS),
        PASS(geometry, SL_DEPENDS_GEOMETRY),
        PASS(camera, SL_DEPENDS_CAMERA),
        PASS(materials, SL_DEPENDS_MATERIALS),
        PASS(own, SL_DEPENDS_OWN_PARAMS),
        PASS(params, SL_DEPENDS_PARAMS),
        PASS(time, SL_DEPENDS_TIME),
        PASS(inputs, SL_DEPENDS_INPUTS, .inputs = camera_in),
        PASS(every, SL_DEPENDS_EVERY_FRAME),
        PASS(none, 0),
        /* an ABI 1.7 plugin's descriptor ends before `depends`: whatever lies there is not read */
        {.struct_size = offsetof(sl_pass_desc, depends), .name = "deps-old", .stage = SL_STAGE_PREPASS, .outputs = out_old,
         .output_count = 1, .execute = clear_execute, .user = t, .depends = SL_DEPENDS_LIGHTS},
        {.struct_size = sizeof(sl_pass_desc), .name = "deps-shared", .stage = SL_STAGE_POST, .inputs = color_in,
         .outputs = color_out, .output_count = 1, .execute = copy_execute, .user = t, .depends = SL_DEPENDS_LIGHTS},
    };
#undef PASS
    for (size_t i = 0; i < sizeof passes / sizeof *passes; i++)
        if (host->add_pass(host, &passes[i]) != SL_OK) return SL_ERR_FAILED;
    return SL_OK;
}

static sl_status activate(void *user) {
    tpd *t = user;
    return sl_gl_load(t->host->gl_get_proc_address, NULL) ? SL_OK : SL_ERR_GL;
}

static void destroy(void *user) { free(user); }

static const sl_plugin_desc desc = {
    SL_PLUGIN_HEADER,
    .id = "tp-deps",
    .version = "1.0",
    .description = "test: one pass per declared dependency (sl_depends)",
    .create = create,
    .activate = activate,
    .destroy = destroy,
};
SL_DEFINE_PLUGIN(desc)
