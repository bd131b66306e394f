/* One test plugin source, built in several variants (see tests/core_tests.cmake) to drive the
 * loader's success and failure paths. TP_ID is the plugin id. */
#include <shadelab/shadelab.h>
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include <stdlib.h>
#include <string.h>

#ifdef TP_DUP_MODEL
#undef TP_MODEL
#define TP_MODEL "lambert"
#endif
#ifdef TP_UNDEFINED_SYMBOL
void tp_function_that_does_not_exist(void);
#endif
#ifdef TP_DEPENDENCY
int tp_dependency_value(void);
#endif
/* TP_KEY_INPUT: the standard material input tp_scale takes; TP_LISTED_INPUT: the one the
 * descriptor's material_inputs lists (the host refuses a plugin whose two disagree) */
#ifndef TP_KEY_INPUT
#define TP_KEY_INPUT NULL
#endif

typedef struct tp {
    const sl_host *host;
    sl_program *scale;
} tp;

static const char *gain_inputs[] = {"color", NULL};
static const sl_target_desc gain_outputs[] = {{.name = "color", .format = SL_FORMAT_RGBA16F}};

static bool gain_active(void *user, const sl_frame *f) {
    tp *t = user;
    char id[64];
    return t->host->get_param(t->host, TP_ID ".gain").f[0] != 1.0f;
    (void)id;
}

static void gain_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    tp *t = user;
    const sl_host *h = t->host;
    if (h->bind_outputs(h, ctx, 0) != SL_OK) return;
    unsigned prog = h->program_id(h, t->scale);
    if (!prog) return;
    glUseProgram(prog);
    glBindTextureUnit(0, h->pass_texture(h, ctx, "color"));
    glUniform1i(glGetUniformLocation(prog, "tp_src"), 0);
    glUniform1f(glGetUniformLocation(prog, "tp_gain"), h->get_param(h, TP_ID ".gain").f[0]);
    h->draw_fullscreen(h, ctx);
}

/* A prepass drawing the materials that carry tp_mark with this plugin's model instead of their
 * own (SL_DRAW_MATERIALS), into "tp.override". */
static const sl_target_desc override_outputs[] = {{.name = "tp.override", .format = SL_FORMAT_RGBA32F},
                                                  {.name = "tp.override_depth", .format = SL_FORMAT_DEPTH32F}};

static bool override_active(void *user, const sl_frame *f) {
    tp *t = user;
    return t->host->get_param(t->host, TP_ID ".override_pass").b;
}

static void override_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    tp *t = user;
    const sl_host *h = t->host;
    if (h->bind_outputs(h, ctx, 0) != SL_OK) return;
    glClearColor(0, 0, 0, 0);
    glClearDepth(1);
    glDepthMask(GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    sl_draw_scene_desc d = {.struct_size = sizeof d, .mode = SL_DRAW_MATERIALS, .model_override = TP_MODEL,
                            .only_materials_with = "tp_mark", .cull = 1};
    memcpy(d.view, f->view, sizeof d.view);
    memcpy(d.proj, f->proj, sizeof d.proj);
    h->draw_scene(h, ctx, &d);
}

static sl_status tp_create(const sl_host *host, void **user) {
#ifdef TP_FAIL_CREATE
    host->log(host, SL_LOG_ERROR, "refusing to start (test)");
    return SL_ERR_FAILED;
#endif
#ifdef TP_UNDEFINED_SYMBOL
    tp_function_that_does_not_exist();
#endif
#ifdef TP_DEPENDENCY
    if (tp_dependency_value() != 42) return SL_ERR_FAILED;
#endif
    tp *t = calloc(1, sizeof *t);
    t->host = host;
    *user = t;
    const sl_param_desc params[] = {
        {.struct_size = sizeof(sl_param_desc), .id = "tint", .type = SL_PARAM_COLOR, .default_value = {.f = {1, 0.5f, 0.25f}},
         .description = "Multiplies the base colour of materials carrying tp_mark."},
        {.struct_size = sizeof(sl_param_desc), .id = "gain", .type = SL_PARAM_FLOAT, .default_value = {.f = {1}},
         .min = 0, .max = 16, .description = "Post pass: multiplies the HDR colour (inactive at 1)."},
        {.struct_size = sizeof(sl_param_desc), .id = "tp_mark", .type = SL_PARAM_BOOL, .scope = SL_SCOPE_MATERIAL,
         .description = "Materials with this key get the tint surface hook."},
        {.struct_size = sizeof(sl_param_desc), .id = "tp_scale", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.f = {1}}, .material_input = TP_KEY_INPUT,
         .description = "Scales the test model (a key shared by every variant)."},
        {.struct_size = sizeof(sl_param_desc), .id = "tp_lift", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL,
         .description = "Materials with this key get the vertex hook: object-space y raised by it."},
        {.struct_size = sizeof(sl_param_desc), .id = "override_pass", .type = SL_PARAM_BOOL,
         .description = "Runs the SL_DRAW_MATERIALS prepass."},
        {.struct_size = sizeof(sl_param_desc), .id = "level", .type = SL_PARAM_INT, .default_value = {.i = 2},
         .min = 1, .max = 4, .flags = SL_PARAM_QUALITY_KNOB, .description = "A quality knob for schema tests."},
    };
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_shader_chunk_desc chunks[] = {
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SURFACE, .file = TP_GLSL,
         .function = "tp_surface", .when_material_has = "tp_mark"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SHADING_MODEL, .file = TP_GLSL,
         .function = "tp_model", .name = TP_MODEL,
#ifdef TP_MASKS_FACING_AWAY /* normal perturbation leaves facing-away normals to the model */
         .flags = SL_CHUNK_MASKS_FACING_AWAY
#endif
        },
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_VERTEX, .file = TP_GLSL,
         .function = "tp_vertex", .when_material_has = "tp_lift"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_DEBUG_VIEW, .file = TP_GLSL,
         .function = "tp_view", .name = TP_ID "-view", .description = "constant test colour"},
        /* ABI 1.6: a light that returns radiance (area lights) through sl_shading_model */
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_LIGHT, .file = TP_GLSL,
         .function = "tp_glow", .name = TP_ID "-glow", .flags = SL_CHUNK_LIGHT_RADIANCE},
#ifdef TP_BAD_GATE
        /* ABI 1.17: when_param must name a bool parameter with SL_PARAM_NEEDS_RECOMPILE; gain is a float */
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SURFACE, .file = TP_GLSL,
         .function = "tp_surface", .when_material_has = "tp_mark", .when_param = "gain"},
#endif
    };
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_pass_desc pass = {.struct_size = sizeof pass, .name = TP_ID "-gain", .stage = SL_STAGE_POST,
                               .inputs = gain_inputs, .outputs = gain_outputs, .output_count = 1,
                               .execute = gain_execute, .is_active = gain_active, .user = t};
    if (host->add_pass(host, &pass) != SL_OK) return SL_ERR_FAILED;
    const sl_pass_desc prepass = {.struct_size = sizeof prepass, .name = TP_ID "-override", .stage = SL_STAGE_PREPASS,
                                  .outputs = override_outputs, .output_count = 2, .execute = override_execute,
                                  .is_active = override_active, .user = t};
    if (host->add_pass(host, &prepass) != SL_OK) return SL_ERR_FAILED;
    const sl_key_desc key = {.struct_size = sizeof key, .key = "T", .param = "tp_mark", .description = "test key"};
    (void)key;
    return SL_OK;
}

static sl_status tp_activate(void *user) {
    tp *t = user;
    if (!sl_gl_load(t->host->gl_get_proc_address, NULL)) return SL_ERR_GL;
    t->scale = t->host->load_program(t->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                  .vertex = "sl:fullscreen.vert", .fragment = "tp_gain.frag"});
    return t->scale ? SL_OK : SL_ERR_GL;
}

static void tp_destroy(void *user) { free(user); }

#ifdef TP_REQUIRES
static const char *const tp_requires[] = {TP_REQUIRES, NULL};
#endif
#ifdef TP_CONFLICTS
static const char *const tp_conflicts[] = {TP_CONFLICTS, NULL};
#endif
#ifdef TP_LISTED_INPUT
static const char *const tp_inputs[] = {TP_LISTED_INPUT, NULL};
#endif

/* TP_UNLISTED_MODEL: a descriptor that lists no model though create() registers one;
 * TP_UNPROVIDED_MODEL: one that lists a model no chunk provides (the host refuses both) */
#if defined(TP_UNLISTED_MODEL)
static const char *const tp_models[] = {NULL};
#elif defined(TP_UNPROVIDED_MODEL)
static const char *const tp_models[] = {TP_MODEL, "tp-phantom-model", NULL};
#else
static const char *const tp_models[] = {TP_MODEL, NULL};
#endif
static const sl_plugin_desc tp_desc = {
    SL_PLUGIN_HEADER,
    .id = TP_ID,
    .version = "1.0",
    .description = "shadelab test plugin",
#ifdef TP_REQUIRES
    .dependencies = tp_requires,
#endif
#ifdef TP_CONFLICTS
    .conflicts = tp_conflicts,
#endif
#ifdef TP_LISTED_INPUT
    .material_inputs = tp_inputs,
#endif
    .create = tp_create,
    .activate = tp_activate,
    .destroy = tp_destroy,
    .shading_models = tp_models,
};

#ifndef TP_NO_ENTRY
SL_DEFINE_PLUGIN(tp_desc)
#else
SL_EXPORT const sl_plugin_desc *not_the_entry_symbol(void) { return &tp_desc; }
#endif
