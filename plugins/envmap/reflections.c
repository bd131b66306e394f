/* envmap's screen-space reflections (reflections=screen): the pass that draws the opaque scene,
 * lit as the forward pass lights it but without these reflections (envmap_scene.frag), the pass
 * that traces one reflected ray per texel of it (envmap_reflections.frag), and the uniforms with
 * which the forward programs read what the rays found (envmap_shading.glsl).
 * README.md, "Reflections of the scene". */
#include "reflections.h"

#include <math.h>
#include <string.h>

#include <shadelab/matrix.h>

static void mat4_mul(float out[16], const float a[16], const float b[16]) { /* column-major a·b */
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            float v = 0;
            for (int k = 0; k < 4; k++) v += a[k * 4 + row] * b[c * 4 + k];
            out[c * 4 + row] = v;
        }
}

static sl_value param(const em_reflections *r, const char *id) {
    char full[64];
    snprintf(full, sizeof full, "envmap.%s", id);
    return r->host->get_param(r->host, full);
}

bool em_reflections_on(const em_reflections *r) { return param(r, "reflections").i == 1; }

static bool pass_active(void *user, const sl_frame *f) {
    (void)f;
    em_reflections *r = user;
    return em_reflections_on(r) && r->lit(r->lit_user) && r->host->scene_uses_uniform(r->host, "envmap_refl");
}

/* Of the forward pass's size, which core.ssaa multiplies: the image never finer than the output. */
static float scale_of(const em_reflections *r) {
    int ssaa = r->host->get_param(r->host, "core.ssaa").i;
    return param(r, "reflections_scale").f[0] / (float)(ssaa > 1 ? ssaa : 1);
}

static void scene_io(void *user, const char *const **in, const sl_target_desc **out, int *n) {
    em_reflections *r = user;
    float scale = scale_of(r);
    r->scene_targets[0] = (sl_target_desc){.name = "envmap.scene", .format = SL_FORMAT_RGBA16F, .scale = scale};
    r->scene_targets[1] = (sl_target_desc){.name = "envmap.scene_lobe", .format = SL_FORMAT_RGBA16F, .scale = scale};
    r->scene_targets[2] = (sl_target_desc){.name = "envmap.scene_depth", .format = SL_FORMAT_DEPTH32F, .scale = scale};
    *in = NULL, *out = r->scene_targets, *n = 3;
}

static const char *const trace_inputs[] = {"envmap.scene_lobe", "envmap.scene_depth", NULL};
static void trace_io(void *user, const char *const **in, const sl_target_desc **out, int *n) {
    em_reflections *r = user;
    r->trace_target = (sl_target_desc){.name = "envmap.reflections", .format = SL_FORMAT_RGBA16F, .scale = scale_of(r)};
    *in = trace_inputs, *out = &r->trace_target, *n = 1;
}

static const char *const resolve_inputs[] = {"envmap.reflections", "envmap.scene_depth", NULL};
static void resolve_io(void *user, const char *const **in, const sl_target_desc **out, int *n) {
    em_reflections *r = user;
    r->resolve_target = (sl_target_desc){.name = "envmap.reflections_resolved", .format = SL_FORMAT_RGBA16F,
                                         .scale = scale_of(r)};
    *in = resolve_inputs, *out = &r->resolve_target, *n = 1;
}

/* The frame's projection without the jitter a temporal method added (sl_frame.jitter, pixels):
 * the jitter shifts clip x (y) by 2j/size times w, so rows 0 and 1 hold 2j/size times row 3 more. */
static void unjittered_proj(const sl_frame *f, float p[16]) {
    memcpy(p, f->proj, 16 * sizeof *p);
    for (int c = 0; c < 4; c++) {
        p[c * 4 + 0] -= 2.0f * f->jitter[0] / (float)f->width * p[c * 4 + 3];
        p[c * 4 + 1] -= 2.0f * f->jitter[1] / (float)f->height * p[c * 4 + 3];
    }
}

/* Runs when the view (without jitter: a still's frames reuse the first's image), the scene's
 * content or its size moved: the declared categories cover the rest. */
static uint64_t pass_signature(void *user, const sl_frame *f) {
    em_reflections *r = user;
    float p[16];
    unjittered_proj(f, p);
    uint64_t h = 1469598103934665603ull ^ (uint64_t)r->generation;
    const float *parts[2] = {f->view, p};
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < 16; i++) {
            uint32_t u;
            memcpy(&u, &parts[k][i], sizeof u);
            h = (h ^ u) * 1099511628211ull;
        }
    return h ^ ((uint64_t)f->width << 40) ^ ((uint64_t)f->height << 20);
}

/* The colour with a mip chain (the lobes' footprints): the pass's target copied into a texture
 * of envmap's own, made again when the size changes. */
static void ensure_mips(em_reflections *r, int w, int h) {
    if (r->color && r->w == w && r->h == h) return;
    if (r->color) glDeleteTextures(1, &r->color);
    r->w = w, r->h = h;
    r->levels = 1;
    while ((w >> r->levels) > 0 || (h >> r->levels) > 0) r->levels++;
    glCreateTextures(GL_TEXTURE_2D, 1, &r->color);
    glTextureStorage2D(r->color, r->levels, GL_RGBA16F, w, h);
    glTextureParameteri(r->color, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(r->color, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(r->color, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(r->color, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

static void scene_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    em_reflections *r = user;
    const sl_host *h = r->host;
    if (h->bind_outputs(h, ctx, 0) != SL_OK) return;
    glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDisable(GL_BLEND);
    sl_draw_scene_desc d = {.struct_size = sizeof d, .mode = SL_DRAW_MATERIALS, .cull = 1, .fragment = "envmap_scene.frag"};
    memcpy(d.view, f->view, sizeof d.view);
    unjittered_proj(f, d.proj);
    h->draw_scene(h, ctx, &d);
    glDisable(GL_DEPTH_TEST);
    unsigned color = h->pass_texture(h, ctx, "envmap.scene");
    r->depth = h->pass_texture(h, ctx, "envmap.scene_depth");
    int w = 0, hh = 0;
    glGetTextureLevelParameteriv(color, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(color, 0, GL_TEXTURE_HEIGHT, &hh);
    ensure_mips(r, w, hh);
    glCopyImageSubData(color, GL_TEXTURE_2D, 0, 0, 0, 0, r->color, GL_TEXTURE_2D, 0, 0, 0, 0, w, hh, 1);
    glGenerateTextureMipmap(r->color);
    mat4_mul(r->view_proj, d.proj, d.view);
    /* view distance from NDC z through the inverse projection's z and w rows (perspective and
     * orthographic alike); a texel's world size at distance 1 (perspective) or anywhere */
    float inv[16];
    if (!sl_mat4_invert(d.proj, inv)) memset(inv, 0, sizeof inv), inv[15] = 1;
    r->depth_lin[0] = -inv[10], r->depth_lin[1] = -inv[14], r->depth_lin[2] = inv[11], r->depth_lin[3] = inv[15];
    bool perspective = fabsf(d.proj[11]) > 0.5f;
    r->texel[0] = 2.0f / (fabsf(d.proj[5]) * (float)(hh > 0 ? hh : 1));
    r->texel[1] = perspective ? 1.0f : 0.0f;
    float ext[3];
    for (int i = 0; i < 3; i++) ext[i] = f->scene_max[i] - f->scene_min[i];
    r->length = sqrtf(ext[0] * ext[0] + ext[1] * ext[1] + ext[2] * ext[2]);
    if (!(r->length > 0) || !isfinite(r->length)) r->length = 1;
}

/* One ray per texel of the scene's image (envmap_reflections.frag), after each new image. */
static void trace_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    (void)f;
    em_reflections *r = user;
    const sl_host *h = r->host;
    unsigned lobe = h->pass_texture(h, ctx, "envmap.scene_lobe");
    if (h->bind_outputs(h, ctx, 0) != SL_OK) return;
    unsigned prog = h->program_id(h, r->trace_prog);
    if (!prog || !r->color) return;
    glUseProgram(prog);
    /* the material units are free between material draws (host.h): this pass's own inputs */
    glBindTextureUnit(0, r->color);
    glBindTextureUnit(1, r->depth);
    glBindTextureUnit(2, lobe);
    glUniform1i(glGetUniformLocation(prog, "envmap_refl_color"), 0);
    glUniform1i(glGetUniformLocation(prog, "envmap_refl_depth"), 1);
    glUniform1i(glGetUniformLocation(prog, "envmap_refl_lobe"), 2);
    float inv[16];
    if (!sl_mat4_invert(r->view_proj, inv)) return;
    glUniformMatrix4fv(glGetUniformLocation(prog, "envmap_refl_view_proj"), 1, GL_FALSE, r->view_proj);
    glUniformMatrix4fv(glGetUniformLocation(prog, "envmap_refl_inv_view_proj"), 1, GL_FALSE, inv);
    glUniform4fv(glGetUniformLocation(prog, "envmap_refl_depth_lin"), 1, r->depth_lin);
    glUniform2f(glGetUniformLocation(prog, "envmap_refl_texel"), r->texel[0], r->texel[1]);
    glUniform1f(glGetUniformLocation(prog, "envmap_refl_alpha"), param(r, "reflections_alpha").f[0]);
    glUniform1f(glGetUniformLocation(prog, "envmap_refl_length"), r->length);
    glUniform1i(glGetUniformLocation(prog, "envmap_refl_steps"), param(r, "reflections_steps").i);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    h->draw_fullscreen(h, ctx);
}

/* The rays' hits filtered over their neighbours (envmap_reflections_resolve.frag): what the
 * forward programs read. */
static void resolve_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    (void)f;
    em_reflections *r = user;
    const sl_host *h = r->host;
    unsigned found = h->pass_texture(h, ctx, "envmap.reflections"), depth = h->pass_texture(h, ctx, "envmap.scene_depth");
    if (h->bind_outputs(h, ctx, 0) != SL_OK) return;
    r->found = h->pass_texture(h, ctx, "envmap.reflections_resolved");
    unsigned prog = h->program_id(h, r->resolve_prog);
    if (!prog) return;
    glUseProgram(prog);
    glBindTextureUnit(0, found);
    glBindTextureUnit(1, depth);
    glUniform1i(glGetUniformLocation(prog, "envmap_refl_found"), 0);
    glUniform1i(glGetUniformLocation(prog, "envmap_refl_depth"), 1);
    glUniform4fv(glGetUniformLocation(prog, "envmap_refl_depth_lin"), 1, r->depth_lin);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    h->draw_fullscreen(h, ctx);
}

sl_status em_reflections_create(em_reflections *r, const sl_host *host, bool (*lit)(void *), void *lit_user) {
    *r = (em_reflections){.host = host, .lit = lit, .lit_user = lit_user};
    scene_io(r, &(const char *const *){NULL}, &(const sl_target_desc *){NULL}, &(int){0});
    trace_io(r, &(const char *const *){NULL}, &(const sl_target_desc *){NULL}, &(int){0});
    resolve_io(r, &(const char *const *){NULL}, &(const sl_target_desc *){NULL}, &(int){0});
    const sl_pass_desc scene = {.struct_size = sizeof scene, .name = "envmap-reflections", .stage = SL_STAGE_PREPASS + 10,
                                .outputs = r->scene_targets, .output_count = 3, .execute = scene_execute,
                                .is_active = pass_active, .io = scene_io, .signature = pass_signature, .user = r,
                                .depends = SL_DEPENDS_LIGHTS | SL_DEPENDS_GEOMETRY | SL_DEPENDS_MATERIALS | SL_DEPENDS_PARAMS};
    const sl_pass_desc trace = {.struct_size = sizeof trace, .name = "envmap-reflections-trace",
                                .stage = SL_STAGE_PREPASS + 11, .inputs = trace_inputs, .outputs = &r->trace_target,
                                .output_count = 1, .execute = trace_execute, .is_active = pass_active, .io = trace_io,
                                .user = r, .depends = SL_DEPENDS_INPUTS | SL_DEPENDS_OWN_PARAMS};
    const sl_pass_desc resolve = {.struct_size = sizeof resolve, .name = "envmap-reflections-resolve",
                                  .stage = SL_STAGE_PREPASS + 12, .inputs = resolve_inputs, .outputs = &r->resolve_target,
                                  .output_count = 1, .execute = resolve_execute, .is_active = pass_active,
                                  .io = resolve_io, .user = r, .depends = SL_DEPENDS_INPUTS};
    if (host->add_pass(host, &scene) != SL_OK || host->add_pass(host, &trace) != SL_OK ||
        host->add_pass(host, &resolve) != SL_OK)
        return SL_ERR_FAILED;
    if ((r->unit_found = host->reserve_texture_unit(host)) < 0) return SL_ERR_FAILED;
    return SL_OK;
}

sl_status em_reflections_activate(em_reflections *r) {
    r->trace_prog = r->host->load_program(r->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                       .vertex = "sl:fullscreen.vert",
                                                                       .fragment = "envmap_reflections.frag"});
    r->resolve_prog = r->host->load_program(r->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                         .vertex = "sl:fullscreen.vert",
                                                                         .fragment = "envmap_reflections_resolve.frag"});
    static const float zero[4] = {0, 0, 0, 0};
    glCreateTextures(GL_TEXTURE_2D, 1, &r->nothing);
    glTextureStorage2D(r->nothing, 1, GL_RGBA16F, 1, 1);
    glTextureSubImage2D(r->nothing, 0, 0, 0, 1, 1, GL_RGBA, GL_FLOAT, zero);
    return r->trace_prog && r->resolve_prog ? SL_OK : SL_ERR_GL;
}

void em_reflections_bind(em_reflections *r, unsigned prog) {
    int l = glGetUniformLocation(prog, "envmap_refl");
    if (l < 0) return;
    /* until the passes have run (no image yet) nothing was found: a texel of weight 0 */
    glBindTextureUnit(r->unit_found, r->found ? r->found : r->nothing);
    glUniform1i(l, r->unit_found);
    glUniformMatrix4fv(glGetUniformLocation(prog, "envmap_refl_view_proj"), 1, GL_FALSE, r->view_proj);
    glUniform1f(glGetUniformLocation(prog, "envmap_refl_alpha"), param(r, "reflections_alpha").f[0]);
}

void em_reflections_free(em_reflections *r) {
    if (r->color) glDeleteTextures(1, &r->color);
    if (r->nothing) glDeleteTextures(1, &r->nothing);
    r->color = 0, r->depth = 0, r->found = 0, r->nothing = 0, r->w = r->h = 0;
    r->generation++;
}
