/* area-light: rectangle and disk lights (light type "area"), one- or two-sided, shaded with
 * linearly transformed cosines (Heitz, Dupuy, Hill, Neubelt 2016) for the ggx model and with
 * Lambert's exact polygon formula for lambert; a Monte Carlo reference over the light's surface.
 * Built against the installed SDK only (extras/README.md). See README.md.
 *
 *   light keys   light.NAME.width, height (m), shape (rect/disk), two_sided, axis (width direction)
 *   globals      area-light.method (ltc/reference), disk_segments (knob), reference_samples
 *   material     fresnel, eta, metallic: the ggx plugin's Fresnel inputs, declared here too (a
 *                shared material vocabulary) so the LTC's Fresnel follows the material
 *   data         ltc_ggx.txt beside the module (made by ltc_fit, command in its header) */
#define SL_GL_IMPLEMENTATION
#include <shadelab/gl.h>
#include <shadelab/shadelab.h>
#include "ltc.h"

#define AL_ID "area-light"

typedef struct area_light {
    const sl_host *host;
    al_ltc_table table;
    unsigned tex_m, tex_n;
    int unit_m, unit_n;
} area_light;

static const char *const methods[] = {"ltc", "reference", NULL};
static const char *const shapes[] = {"rect", "disk", NULL};
static const char *const fresnel_modes[] = {"exact", "schlick", "metallic-roughness", NULL}; /* as ggx */

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}
static const sl_param_desc params[] = {
    P(.id = "method", .type = SL_PARAM_ENUM, .enum_values = methods, .flags = SL_PARAM_NEEDS_RECOMPILE,
      .group = "area-light", .description = "ltc: linearly transformed cosines (real time); reference: Monte Carlo over "
                                            "the light's surface with the model's exact BRDF, accumulated (no visibility)."),
    P(.id = "disk_segments", .type = SL_PARAM_INT, .default_value = {.i = 16}, .min = 4, .max = 64, .step = 1,
      .flags = SL_PARAM_NEEDS_RECOMPILE | SL_PARAM_QUALITY_KNOB, .group = "area-light",
      .description = "Disk lights are integrated as a regular polygon of this many vertices with the disk's area."),
    P(.id = "reference_samples", .type = SL_PARAM_INT, .default_value = {.i = 4}, .min = 1, .max = 16, .step = 1,
      .flags = SL_PARAM_NEEDS_RECOMPILE, .group = "area-light",
      .description = "Reference: n×n stratified points on each light per pixel and frame."),
    /* light keys of type "area" */
    P(.id = "width", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_LIGHT, .light_type = "area", .light_slot = 0,
      .default_value = {.f = {1}}, .min = 0, .max = 1000, .step = 0.01f, .unit = "m", .group = "area light",
      .description = "Extent along axis (disk: the diameter along axis)."),
    P(.id = "height", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_LIGHT, .light_type = "area", .light_slot = 1,
      .default_value = {.f = {1}}, .min = 0, .max = 1000, .step = 0.01f, .unit = "m", .group = "area light",
      .description = "Extent along direction × axis (disk: the other diameter)."),
    P(.id = "shape", .type = SL_PARAM_ENUM, .scope = SL_SCOPE_LIGHT, .light_type = "area", .light_slot = 2,
      .enum_values = shapes, .group = "area light", .description = "rect: a rectangle; disk: an ellipse (a disk when width = height)."),
    P(.id = "two_sided", .type = SL_PARAM_BOOL, .scope = SL_SCOPE_LIGHT, .light_type = "area", .light_slot = 3,
      .group = "area light", .description = "Emit from both faces (one-sided: only along direction)."),
    P(.id = "axis", .type = SL_PARAM_VEC3, .scope = SL_SCOPE_LIGHT, .light_type = "area", .light_slot = 4,
      .default_value = {.f = {1, 0, 0}}, .group = "area light",
      .description = "Direction of the width side (made orthogonal to direction)."),
    /* the ggx plugin's Fresnel inputs (shared material vocabulary, same types and values) */
    P(.id = "eta", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1.0f / 1.5f}},
      .min = 0.05f, .max = 20, .step = 0.01f, .group = "ggx", .description = "Relative index of refraction η = n1/n2 (air over glass: 1/1.5)."),
    P(.id = "fresnel", .type = SL_PARAM_ENUM, .scope = SL_SCOPE_MATERIAL, .enum_values = fresnel_modes,
      .flags = SL_PARAM_NEEDS_RECOMPILE, .group = "ggx",
      .description = "exact dielectric Fresnel, Schlick, or glTF metallic-roughness (F0 = mix(0.04, base, metallic))."),
    P(.id = "metallic", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = 0, .max = 1, .step = 0.01f,
      .group = "ggx", .description = "Metalness for fresnel = metallic-roughness."),
};

static void al_bind(void *user, unsigned program, int material, const sl_frame *frame) {
    (void)material, (void)frame;
    area_light *a = user;
    glUniform1i(glGetUniformLocation(program, "area_light_ltc_m"), a->unit_m);
    glUniform1i(glGetUniformLocation(program, "area_light_ltc_n"), a->unit_n);
    glUniform1f(glGetUniformLocation(program, "area_light_ltc_size"), (float)a->table.size);
    glBindTextureUnit(a->unit_m, a->tex_m);
    glBindTextureUnit(a->unit_n, a->tex_n);
}

static sl_status al_create(const sl_host *host, void **user) {
    area_light *a = calloc(1, sizeof *a);
    *user = a;
    a->host = host;
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_shader_chunk_desc light = {.struct_size = sizeof light, .hook = SL_HOOK_LIGHT, .file = "area_light.glsl",
                                        .function = "area_light_radiance", .name = "area",
                                        .flags = SL_CHUNK_LIGHT_RADIANCE};
    if (host->add_shader_chunk(host, &light) != SL_OK) return SL_ERR_FAILED;
    if (host->set_bind_callback(host, al_bind, a) != SL_OK) return SL_ERR_FAILED;
    if ((a->unit_m = host->reserve_texture_unit(host)) < 0 || (a->unit_n = host->reserve_texture_unit(host)) < 0)
        return SL_ERR_FAILED;
    const sl_reference_desc ref = {
        .struct_size = sizeof ref, .settings = AL_ID ".method=reference " AL_ID ".reference_samples=4",
        .accumulate_frames = 256,
        .description = "Monte Carlo over each area light's surface (stratified, 16 points per pixel and frame, "
                       "exact ellipse for disks) through the material's own model; no visibility (area lights cast "
                       "no shadows)"};
    if (host->set_reference(host, &ref) != SL_OK) return SL_ERR_FAILED;
    /* the table: read now, so a missing or damaged file is a create() error naming it */
    char path[4096], err[1024];
    snprintf(path, sizeof path, "%s/ltc_ggx.txt", host->resource_dir(host));
    if (!al_table_read(path, &a->table, err, sizeof err)) {
        host->log(host, SL_LOG_ERROR, "%s", err);
        return SL_ERR_FAILED;
    }
    return SL_OK;
}

static sl_status al_activate(void *user) {
    area_light *a = user;
    if (!sl_gl_load(a->host->gl_get_proc_address, NULL)) return SL_ERR_GL;
    int N = a->table.size;
    float *m = malloc(sizeof(float) * 4 * N * N), *n = malloc(sizeof(float) * 4 * N * N);
    for (int k = 0; k < N * N; k++) {
        const al_ltc_entry *e = &a->table.e[k];
        m[4 * k + 0] = (float)e->a, m[4 * k + 1] = (float)e->b, m[4 * k + 2] = (float)e->c, m[4 * k + 3] = (float)e->d;
        n[4 * k + 0] = (float)e->norm, n[4 * k + 1] = (float)e->fresnel, n[4 * k + 2] = 0, n[4 * k + 3] = 0;
    }
    unsigned *tex[2] = {&a->tex_m, &a->tex_n};
    float *data[2] = {m, n};
    for (int i = 0; i < 2; i++) {
        glCreateTextures(GL_TEXTURE_2D, 1, tex[i]);
        glTextureStorage2D(*tex[i], 1, GL_RGBA32F, N, N);
        glTextureSubImage2D(*tex[i], 0, 0, 0, N, N, GL_RGBA, GL_FLOAT, data[i]);
        glTextureParameteri(*tex[i], GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(*tex[i], GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(*tex[i], GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(*tex[i], GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    free(m);
    free(n);
    return SL_OK;
}

static void al_deactivate(void *user) {
    area_light *a = user;
    glDeleteTextures(1, &a->tex_m);
    glDeleteTextures(1, &a->tex_n);
    a->tex_m = a->tex_n = 0;
}

static void al_destroy(void *user) {
    area_light *a = user;
    if (a) free(a->table.e);
    free(a);
}

static const sl_plugin_desc al_desc = {
    SL_PLUGIN_HEADER,
    .id = AL_ID,
    .version = "1.0.0",
    .description = "Rectangle and disk area lights: LTC (Heitz et al. 2016) for ggx, Lambert's exact polygon irradiance, "
                   "a Monte Carlo reference.",
    .create = al_create,
    .activate = al_activate,
    .deactivate = al_deactivate,
    .destroy = al_destroy,
};
SL_DEFINE_PLUGIN(al_desc)
