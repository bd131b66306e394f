/* refraction: a transparent dielectric material lit by the environment (issue 25). See README.md.
 *
 * Materials of model "dielectric" show the environment reflected and refracted, weighted by the
 * exact dielectric Fresnel term (the SDK's sl:ggx_brdf.glsl ggx_fresnel_exact; Walter et al. 2007
 * eq. 22). The environment comes from the envmap plugin through the SDK extension
 * "shadelab.environment/1" (<shadelab/ext/environment.h>): its cube, rotation and intensity.
 *
 * method = single: one interface (the object is an infinitely thick slab under each pixel: the
 *   refracted ray goes straight to the environment).
 * method = two-interface: Wyman 2005 ("An Approximate Image-Space Approach for Interactive
 *   Refraction", SIGGRAPH): a back-face pass stores each pixel's back-face normal and distance
 *   from the camera; the refracted ray travels the front-to-back distance along the view ray,
 *   reads the back face's normal where it lands and refracts out (or, beyond the critical angle,
 *   is reflected and looked up along that direction).
 * Dispersion: a material carrying `ior_rgb` refracts each channel with its own η (three lookups).
 *
 * Reference: the analytic ray paths through a sphere (any number of internal bounces, each weighted
 * by Fresnel), computed on the CPU by bench/sphere_ref.c and tests/ (sphere_ref.h). */
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include <shadelab/shadelab.h>
#include <shadelab/ext/environment.h>
#include <stdlib.h>
#include <string.h>

static const char *const methods[] = {"single", "two-interface", NULL};

typedef struct refraction {
    const sl_host *host;
    int unit_env, unit_back;
    sl_program *back_prog;
    unsigned back_tex; /* the back-face target of this frame (set by the pass) */
} refraction;

static bool two_interface(const refraction *r) { return r->host->get_param(r->host, "refraction.method").i == 1; }

static void rf_bind(void *user, unsigned prog, int material, const sl_frame *f) {
    (void)material, (void)f;
    refraction *r = user;
    const sl_ext_environment *ext = r->host->get_extension(r->host, SL_EXT_ENVIRONMENT);
    sl_environment_cube c = {.struct_size = sizeof c};
    bool ok = ext && ext->get(ext->ctx, &c);
    glBindTextureUnit(r->unit_env, ok ? c.texture : 0);
    glUniform1i(glGetUniformLocation(prog, "refraction_env"), r->unit_env);
    glUniform1i(glGetUniformLocation(prog, "refraction_env_ok"), ok);
    if (ok) {
        glUniformMatrix3fv(glGetUniformLocation(prog, "refraction_env_rot"), 1, GL_FALSE, c.world_to_map);
        glUniform1f(glGetUniformLocation(prog, "refraction_env_scale"), c.scale);
        glUniform1f(glGetUniformLocation(prog, "refraction_env_size"), (float)c.size);
        glUniform1f(glGetUniformLocation(prog, "refraction_env_lod_max"), (float)(c.levels - 1));
    }
    int l_back = glGetUniformLocation(prog, "refraction_back");
    if (l_back >= 0) {
        glBindTextureUnit(r->unit_back, r->back_tex);
        glUniform1i(l_back, r->unit_back);
    }
}

/* the back-face pass runs only in two-interface mode and when some material carries `ior`
 * (the materials it draws): a scene without glass pays nothing */
static bool back_active(void *user, const sl_frame *f) {
    (void)f;
    refraction *r = user;
    if (!two_interface(r)) return false;
    for (int i = 0, n = r->host->material_count(r->host); i < n; i++) {
        sl_value v;
        if (r->host->material_value(r->host, i, "ior", &v, NULL, 0)) return true;
    }
    return false;
}

static void back_execute(void *user, sl_pass_ctx *ctx, const sl_frame *f) {
    refraction *r = user;
    const sl_host *h = r->host;
    r->back_tex = h->pass_texture(h, ctx, "refraction.back");
    h->bind_outputs(h, ctx, 0);
    glClearColor(0, 0, 0, 0); /* w = 0: no back face here */
    glClearDepth(1);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (!h->program_id(h, r->back_prog)) return;
    sl_draw_scene_desc d = {.struct_size = sizeof d, .mode = SL_DRAW_PROGRAM, .program = r->back_prog,
                            .cull = 2, .only_materials_with = "ior"};
    memcpy(d.view, f->view, sizeof d.view);
    memcpy(d.proj, f->proj, sizeof d.proj);
    h->draw_scene(h, ctx, &d);
}

static sl_status rf_activate(void *user) {
    refraction *r = user;
    if (!sl_gl_load(r->host->gl_get_proc_address, NULL)) return SL_ERR_GL;
    r->back_prog = r->host->load_program(r->host, &(sl_program_desc){.struct_size = sizeof(sl_program_desc),
                                                                      .vertex = "refraction_back.vert",
                                                                      .fragment = "refraction_back.frag"});
    return r->back_prog ? SL_OK : SL_ERR_GL;
}

static sl_status rf_create(const sl_host *host, void **user) {
    refraction *r = calloc(1, sizeof *r);
    if (!r) return SL_ERR_FAILED;
    *user = r;
    r->host = host;
    static const char *const mat = "material", *const quality = "quality";
    const sl_param_desc params[] = {
        {.struct_size = sizeof(sl_param_desc), .id = "ior", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.f = {1.5f}}, .min = 0.2f, .max = 4, .step = 0.01f, .group = mat,
         .description = "Index of refraction of the object relative to the medium around it (η = n_inside / n_outside; "
                        "< 1: a bubble). Two-interface mode draws the back faces of materials carrying this key."},
        {.struct_size = sizeof(sl_param_desc), .id = "ior_rgb", .type = SL_PARAM_VEC3, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.f = {1.5f, 1.5f, 1.5f}}, .group = mat,
         .description = "Dispersion: one η per colour channel (linear R, G, B) instead of ior, when the material carries it."},
        {.struct_size = sizeof(sl_param_desc), .id = "transmittance", .type = SL_PARAM_COLOR, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.f = {1, 1, 1}}, .group = mat,
         .description = "Multiplies the refracted part (a tint; 1 = clear glass)."},
        {.struct_size = sizeof(sl_param_desc), .id = "method", .type = SL_PARAM_ENUM, .default_value = {.i = 1},
         .enum_values = methods, .flags = SL_PARAM_NEEDS_RECOMPILE | SL_PARAM_QUALITY_KNOB, .group = quality,
         .description = "single: one interface (refracted ray to the environment); two-interface: out through the back "
                        "face found by a back-face pass (Wyman 2005)."},
        {.struct_size = sizeof(sl_param_desc), .id = "steps", .type = SL_PARAM_INT, .default_value = {.i = 4}, .min = 0,
         .max = 4, .flags = SL_PARAM_NEEDS_RECOMPILE | SL_PARAM_QUALITY_KNOB, .group = quality,
         .description = "two-interface: refinements of the distance to the back face (0 = Wyman's front-to-back distance "
                        "along the view ray; each step re-reads the back face where the refracted ray's estimate lands)."},
        {.struct_size = sizeof(sl_param_desc), .id = "dispersion", .type = SL_PARAM_BOOL, .default_value = {.b = true},
         .flags = SL_PARAM_NEEDS_RECOMPILE | SL_PARAM_QUALITY_KNOB, .group = quality,
         .description = "Per-channel η for materials carrying ior_rgb (three refraction lookups); off: their green η for all."},
        {.struct_size = sizeof(sl_param_desc), .id = "filter", .type = SL_PARAM_BOOL, .default_value = {.b = true},
         .group = quality,
         .description = "Read the environment at the mip level of the lookup direction's screen footprint (off: level 0)."},
    };
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_shader_chunk_desc chunks[] = {
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SHADING_MODEL, .file = "refraction.glsl",
         .function = "refraction_model", .name = "dielectric",
         .description = "smooth dielectric: reflection + refraction of the environment (exact Fresnel); lights are deltas"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_MODEL_AMBIENT, .file = "refraction.glsl",
         .function = "refraction_ambient", .name = "dielectric"},
        /* no diffuse: other AMBIENT hooks (envmap's Lambert term for unknown models) add base_color·E/π */
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SURFACE, .file = "refraction.glsl",
         .function = "refraction_surface", .when_model = "dielectric", .order = 90},
    };
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
    static const sl_target_desc outputs[] = {
        {.name = "refraction.back", .format = SL_FORMAT_RGBA32F},
        {.name = "refraction.back_depth", .format = SL_FORMAT_DEPTH32F},
    };
    const sl_pass_desc pass = {.struct_size = sizeof pass, .name = "refraction-back", .stage = SL_STAGE_PREPASS + 50,
                               .outputs = outputs, .output_count = 2, .execute = back_execute,
                               .is_active = back_active, .user = r,
                               .depends = SL_DEPENDS_CAMERA | SL_DEPENDS_GEOMETRY | SL_DEPENDS_MATERIALS};
    if (host->add_pass(host, &pass) != SL_OK) return SL_ERR_FAILED;
    if ((r->unit_env = host->reserve_texture_unit(host)) < 0 || (r->unit_back = host->reserve_texture_unit(host)) < 0)
        return SL_ERR_FAILED;
    if (host->set_bind_callback(host, rf_bind, r) != SL_OK) return SL_ERR_FAILED;
    const sl_reference_desc ref = {.struct_size = sizeof ref, .settings = "refraction.method=two-interface",
                                   .description = "analytic ray paths through a sphere of the same η, every internal bounce "
                                                  "weighted by Fresnel, on the CPU (bench/sphere_ref.c; spheres only)"};
    host->set_reference(host, &ref);
    return SL_OK;
}

static void rf_destroy(void *user) { free(user); }

static const char *const deps[] = {"envmap", NULL};

static const char *const models[] = {"dielectric", NULL};
static const sl_plugin_desc desc = {
    SL_PLUGIN_HEADER,
    .id = "refraction",
    .version = "1.0.0",
    .description = "Transparent dielectric: environment reflection + refraction with exact Fresnel, one or two interfaces, "
                   "optional dispersion",
    .dependencies = deps,
    .create = rf_create,
    .activate = rf_activate,
    .destroy = rf_destroy,
    .shading_models = models,
};
SL_DEFINE_PLUGIN(desc)
