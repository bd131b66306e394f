/* Screen-space ambient occlusion as a third party writes it: only the public SDK (<shadelab/...>).
 *
 *   pass          "ssao" at SL_STAGE_PREPASS reads the core's "depth" and "normal" before the
 *                 forward pass (reading them there brings the core's depth pre-pass, pass.h) and
 *                 writes "ssao.ao": ambient visibility per pixel (ssao.frag). It draws no scene.
 *   SURFACE hook  multiplies s.ao by that visibility (ssao_surface.glsl). Only the ambient and
 *                 environment terms read s.ao, so direct light is untouched.
 *   io()          ssao.half_resolution changes the output's size live (sl_pass_desc.io, ABI 1.13).
 *   debug views   "ssao-visibility" and "ssao-normal" show the pass's input and output as they are
 *                 (SL_CHUNK_PASS_VIEW, ABI 1.13).
 */
#define SL_GL_IMPLEMENTATION /* this module's own copy of the GL entry points */
#include <shadelab/gl.h>
#include <shadelab/matrix.h>
#include <shadelab/shadelab.h>
#include <stdlib.h>

#define SSAO_ID "ssao"

typedef struct ssao {
    const sl_host *host;
    sl_program *program;
    int unit;                  /* reserved texture unit: "ssao.ao" for the SURFACE hook */
    sl_target_desc output;     /* "ssao.ao" at the current resolution */
} ssao;

static const char *const ssao_inputs[] = {"depth", "normal", NULL};

/* The pass's inputs and outputs as the parameters have them now (ABI 1.13). */
static void ssao_io(void *user, const char *const **inputs, const sl_target_desc **outputs, int *count) {
    ssao *s = user;
    s->output = (sl_target_desc){.name = SSAO_ID ".ao", .format = SL_FORMAT_R32F,
                                 .scale = s->host->get_param(s->host, SSAO_ID ".half_resolution").b ? 0.5f : 1.0f};
    *inputs = ssao_inputs;
    *outputs = &s->output;
    *count = 1;
}

static void ssao_execute(void *user, sl_pass_ctx *ctx, const sl_frame *frame) {
    ssao *s = user;
    const sl_host *h = s->host;
    unsigned prog = h->program_id(h, s->program);
    if (!prog || h->bind_outputs(h, ctx, 0) != SL_OK) return;
    float inv_proj[16];
    if (!sl_mat4_invert(frame->proj, inv_proj)) return;
    glUseProgram(prog);
    /* inputs on the material units, free between material draws (host.h, SL_TEXTURE_UNIT_*) */
    glBindTextureUnit(SL_TEXTURE_UNIT_MATERIAL_FIRST, h->pass_texture(h, ctx, "depth"));
    glBindTextureUnit(SL_TEXTURE_UNIT_MATERIAL_FIRST + 1, h->pass_texture(h, ctx, "normal"));
    glUniform1i(glGetUniformLocation(prog, "ssao_depth"), SL_TEXTURE_UNIT_MATERIAL_FIRST);
    glUniform1i(glGetUniformLocation(prog, "ssao_normal"), SL_TEXTURE_UNIT_MATERIAL_FIRST + 1);
    glUniformMatrix4fv(glGetUniformLocation(prog, "ssao_proj"), 1, GL_FALSE, frame->proj);
    glUniformMatrix4fv(glGetUniformLocation(prog, "ssao_inv_proj"), 1, GL_FALSE, inv_proj);
    glUniform1f(glGetUniformLocation(prog, "ssao_radius_world"), h->get_param(h, SSAO_ID ".radius").f[0]);
    glUniform1f(glGetUniformLocation(prog, "ssao_strength_value"), h->get_param(h, SSAO_ID ".strength").f[0]);
    glUniform1i(glGetUniformLocation(prog, "ssao_sample_count"), h->get_param(h, SSAO_ID ".samples").i);
    h->draw_fullscreen(h, ctx);
    /* the forward pass's SURFACE hook samples the result on the reserved unit */
    glBindTextureUnit((unsigned)s->unit, h->pass_texture(h, ctx, SSAO_ID ".ao"));
}

/* A material program with the SURFACE hook is bound: where its sampler reads. */
static void ssao_bind(void *user, unsigned program, int material, const sl_frame *frame) {
    (void)material, (void)frame;
    ssao *s = user;
    glProgramUniform1i(program, glGetUniformLocation(program, "ssao_visibility"), s->unit);
}

static sl_status ssao_create(const sl_host *host, void **user) {
    ssao *s = calloc(1, sizeof *s);
    *user = s;
    s->host = host;
    const sl_param_desc params[] = {
        {.struct_size = sizeof(sl_param_desc), .id = "radius", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.5f}},
         .min = 0.01f, .max = 5, .step = 0.01f, .unit = "m",
         .description = "Radius of the hemisphere searched for occluders around each point (world units)."},
        {.struct_size = sizeof(sl_param_desc), .id = "strength", .type = SL_PARAM_FLOAT, .default_value = {.f = {1.0f}},
         .min = 0, .max = 1, .step = 0.01f,
         .description = "Share of the occlusion applied: ambient visibility = 1 − strength × occluded share."},
        {.struct_size = sizeof(sl_param_desc), .id = "samples", .type = SL_PARAM_INT, .default_value = {.i = 16},
         .min = 4, .max = 64, .step = 4,
         .description = "Sample points per pixel (a cosine-weighted Fibonacci hemisphere)."},
        {.struct_size = sizeof(sl_param_desc), .id = "half_resolution", .type = SL_PARAM_BOOL,
         .description = "Compute the occlusion at half the viewport's width and height (changes the pass's target "
                        "live)."},
    };
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_shader_chunk_desc chunks[] = {
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SURFACE, .file = "ssao_surface.glsl",
         .function = "ssao_occlude", .order = 90}, /* after the hooks that set s.ao from maps */
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_DEBUG_VIEW, .file = "ssao_views.glsl",
         .function = "ssao_view_visibility", .name = "ssao-visibility", .flags = SL_CHUNK_PASS_VIEW,
         .resource = SSAO_ID ".ao", .description = "ssao: ambient visibility the pass computed (white = open)"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_DEBUG_VIEW, .file = "ssao_views.glsl",
         .function = "ssao_view_normal", .name = "ssao-normal", .flags = SL_CHUNK_PASS_VIEW, .resource = "normal",
         .description = "ssao: the core's view-space normals it reads (n × 0.5 + 0.5)"},
    };
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
    s->output = (sl_target_desc){.name = SSAO_ID ".ao", .format = SL_FORMAT_R32F};
    const sl_pass_desc pass = {.struct_size = sizeof pass, .name = SSAO_ID, .stage = SL_STAGE_PREPASS,
                               .inputs = ssao_inputs, .outputs = &s->output, .output_count = 1,
                               .execute = ssao_execute, .user = s, .io = ssao_io,
                               /* a function of "depth", "normal" and its parameters; the projection
                                  is the camera's */
                               .depends = SL_DEPENDS_INPUTS | SL_DEPENDS_OWN_PARAMS | SL_DEPENDS_CAMERA};
    if (host->add_pass(host, &pass) != SL_OK) return SL_ERR_FAILED;
    if (host->set_bind_callback(host, ssao_bind, s) != SL_OK) return SL_ERR_FAILED;
    s->unit = host->reserve_texture_unit(host);
    return s->unit >= 0 ? SL_OK : SL_ERR_FAILED;
}

static sl_status ssao_activate(void *user) {
    ssao *s = user;
    if (!sl_gl_load(s->host->gl_get_proc_address, NULL)) return SL_ERR_GL;
    const sl_program_desc prog = {.struct_size = sizeof prog, .vertex = "sl:fullscreen.vert", .fragment = "ssao.frag"};
    s->program = s->host->load_program(s->host, &prog);
    return s->program ? SL_OK : SL_ERR_GL;
}

static void ssao_destroy(void *user) { free(user); }

static const sl_plugin_desc ssao_desc = {
    SL_PLUGIN_HEADER,
    .id = SSAO_ID,
    .version = "1.0.0",
    .description = "SDK example: screen-space ambient occlusion on ambient and environment light only, from the "
                   "core's depth and normals.",
    .create = ssao_create,
    .activate = ssao_activate,
    .destroy = ssao_destroy,
};
SL_DEFINE_PLUGIN(ssao_desc)
