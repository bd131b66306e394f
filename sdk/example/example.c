/* An out-of-tree shadelab plugin: the smallest plugin that uses each extension point once.
 *
 *   parameters   example.tint, example.tint_color, example.tint_strength, example.vignette,
 *                example.vignette_strength (they appear in the GUI, --set, scenes, --dump-params)
 *   shader hook  a SURFACE hook (tint.glsl) that tints every material's base colour; compiled in
 *                only while example.tint is true (a NEEDS_RECOMPILE parameter → #define)
 *   render pass  a POST pass on "color" (vignette.frag) that darkens the corners of the linear
 *                HDR image; it costs nothing while example.vignette is false (is_active)
 *   keys         T toggles the tint, V the vignette
 *
 * Build it against the installed SDK (see CMakeLists.txt and sdk/docs/plugin-guide.md):
 *   cmake -B build -S . -DCMAKE_PREFIX_PATH=/where/shadelab/is/installed && cmake --build build
 *   shadelab --plugin build/plugins/example/example.so --set example.tint_strength=1
 */
#define SL_GL_IMPLEMENTATION /* this module's own copy of the GL entry points */
#include <shadelab/gl.h>
#include <shadelab/shadelab.h>
#include <stdlib.h>

#define EXAMPLE_ID "example" /* prefix of its parameters; GLSL names use "example_" */

typedef struct example {
    const sl_host *host;
    sl_program *vignette;  /* owned by the host; hot-reloads with the file */
} example;

static bool vignette_active(void *user, const sl_frame *frame) {
    example *e = user;
    return e->host->get_param(e->host, EXAMPLE_ID ".vignette").b;
}

/* GL context current. Reads "color", writes the other half of its ping-pong pair. */
static void vignette_execute(void *user, sl_pass_ctx *ctx, const sl_frame *frame) {
    example *e = user;
    const sl_host *h = e->host;
    unsigned prog = h->program_id(h, e->vignette);
    if (!prog) return; /* never compiled: the log says why; the image passes through untouched */
    h->bind_outputs(h, ctx, 0);
    glUseProgram(prog);
    glBindTextureUnit(0, h->pass_texture(h, ctx, "color"));
    glUniform1i(glGetUniformLocation(prog, "u_color"), 0);
    glUniform1f(glGetUniformLocation(prog, "u_strength"), h->get_param(h, EXAMPLE_ID ".vignette_strength").f[0]);
    h->draw_fullscreen(h, ctx);
}

/* No GL context: register everything. */
static sl_status example_create(const sl_host *host, void **user) {
    example *e = calloc(1, sizeof *e);
    e->host = host;
    static const char *const tint_group = "surface hook", *const post_group = "post pass";
    const sl_param_desc params[] = {
        {.struct_size = sizeof(sl_param_desc), .id = "tint", .type = SL_PARAM_BOOL, .default_value = {.b = true},
         .group = tint_group, .flags = SL_PARAM_NEEDS_RECOMPILE,
         .description = "Compile the SURFACE hook that tints every material's base colour."},
        {.struct_size = sizeof(sl_param_desc), .id = "tint_color", .type = SL_PARAM_COLOR,
         .default_value = {.f = {1.0f, 0.55f, 0.2f}}, .group = tint_group,
         .description = "Colour the base colour is multiplied by (linear RGB)."},
        {.struct_size = sizeof(sl_param_desc), .id = "tint_strength", .type = SL_PARAM_FLOAT,
         .default_value = {.f = {0.6f}}, .min = 0, .max = 1, .step = 0.01f, .group = tint_group,
         .description = "0 = untouched base colour, 1 = fully tinted."},
        {.struct_size = sizeof(sl_param_desc), .id = "vignette", .type = SL_PARAM_BOOL, .default_value = {.b = true},
         .group = post_group, .description = "Run the POST pass that darkens the image corners."},
        {.struct_size = sizeof(sl_param_desc), .id = "vignette_strength", .type = SL_PARAM_FLOAT,
         .default_value = {.f = {0.8f}}, .min = 0, .max = 2, .step = 0.01f, .group = post_group,
         .description = "Darkening at the corners (0 = none); radiance is scaled by 1 - strength·r²/2."},
    };
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;

    const sl_shader_chunk_desc tint = {.struct_size = sizeof tint, .hook = SL_HOOK_SURFACE, .file = "tint.glsl",
                                       .function = "example_tint", .order = 50};
    if (host->add_shader_chunk(host, &tint) != SL_OK) return SL_ERR_FAILED;

    static const char *const inputs[] = {"color", NULL};
    static const sl_target_desc outputs[] = {{.name = "color", .format = SL_FORMAT_RGBA16F}};
    const sl_pass_desc pass = {.struct_size = sizeof pass, .name = EXAMPLE_ID "-vignette", .stage = SL_STAGE_POST,
                               .inputs = inputs, .outputs = outputs, .output_count = 1,
                               .execute = vignette_execute, .is_active = vignette_active, .user = e,
                               .depends = SL_DEPENDS_INPUTS | SL_DEPENDS_OWN_PARAMS}; /* ABI 1.8 */
    if (host->add_pass(host, &pass) != SL_OK) return SL_ERR_FAILED;

    const sl_key_desc keys[] = {
        {.struct_size = sizeof(sl_key_desc), .key = "T", .description = "example: toggle the tint", .param = "tint"},
        {.struct_size = sizeof(sl_key_desc), .key = "V", .description = "example: toggle the vignette", .param = "vignette"},
    };
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
        if (host->add_key(host, &keys[i]) != SL_OK) return SL_ERR_FAILED;
    *user = e;
    return SL_OK;
}

/* GL context current: load GL entry points, create programs. */
static sl_status example_activate(void *user) {
    example *e = user;
    if (!sl_gl_load(e->host->gl_get_proc_address, NULL)) return SL_ERR_GL;
    const sl_program_desc prog = {.struct_size = sizeof prog, .vertex = "sl:fullscreen.vert", .fragment = "vignette.frag"};
    e->vignette = e->host->load_program(e->host, &prog);
    return e->vignette ? SL_OK : SL_ERR_GL;
}

static void example_destroy(void *user) { free(user); }

static const sl_plugin_desc example_desc = {
    SL_PLUGIN_HEADER,
    .id = EXAMPLE_ID,
    .version = "1.0.0",
    .description = "SDK example: a tint SURFACE hook and a vignette POST pass, each behind a parameter.",
    .create = example_create,
    .activate = example_activate,
    .destroy = example_destroy,
};
SL_DEFINE_PLUGIN(example_desc)
