/* The core registers its own shading model, light types, debug views and keys through the
 * same host interface plugins use: one path for everything, and the core is the first example
 * of the API. Its GLSL lives in shaders/. */
#include "core_plugin.h"
#include "log.h"
#include <shadelab/ext/budget.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* ---- the light keys every light has ---------------------------------------------------------
 * One table: each key is a field of the light record (sl_light, scene/scene.h) of the same name;
 * its schema is registered below, and sl_core_light_get/set read and write the field. */

static const char *const animations[] = {"none", "orbit", "wobble", NULL}; /* sl_light_animation */

typedef enum field_kind { FIELD_BOOL, FIELD_FLOAT, FIELD_FLOAT3, FIELD_ANIMATION } field_kind;

typedef struct light_key {
    sl_param_desc desc;
    size_t offset;    /* of the field in sl_light */
    field_kind field; /* the field's C type, from the field itself */
    bool unit_vector; /* normalised on write; zero refused */
} light_key;

#define FIELD_KIND(f) _Generic(((sl_light *)0)->f, bool: FIELD_BOOL, float: FIELD_FLOAT, float *: FIELD_FLOAT3, \
                               sl_light_animation: FIELD_ANIMATION)
#define LIGHT_KEY_(f, unit, ...)                                                                         \
    {.desc = {.struct_size = sizeof(sl_param_desc), .id = #f, .scope = SL_SCOPE_LIGHT, .group = "light", __VA_ARGS__}, \
     .offset = offsetof(sl_light, f), .field = FIELD_KIND(f), .unit_vector = unit}
#define LIGHT_KEY(f, ...) LIGHT_KEY_(f, false, __VA_ARGS__)
#define UNIT_VECTOR_KEY(f, ...) LIGHT_KEY_(f, true, __VA_ARGS__)

static const light_key light_keys[] = {
    LIGHT_KEY(enabled, .type = SL_PARAM_BOOL, .default_value = {.b = true}, .description = "Per-light on/off."),
    LIGHT_KEY(intensity, .type = SL_PARAM_FLOAT, .default_value = {.f = {1}}, .min = 0, .max = 1e10f,
              .description = "Directional: irradiance E at normal incidence (W/m²); point/spot: intensity I (E = I/d²)."),
    LIGHT_KEY(color, .type = SL_PARAM_COLOR, .default_value = {.f = {1, 1, 1}},
              .description = "Linear RGB tint, multiplied by intensity."),
    LIGHT_KEY(position, .type = SL_PARAM_VEC3, .unit = "m", .description = "World position (point and spot lights)."),
    UNIT_VECTOR_KEY(direction, .type = SL_PARAM_VEC3, .default_value = {.f = {0, -1, 0}},
                    .description = "Direction light travels (directional and spot lights); normalised."),
    LIGHT_KEY(cast_shadows, .type = SL_PARAM_BOOL,
              .description = "Whether a shadow plugin renders a shadow map for this light."),
    LIGHT_KEY(angular_radius, .type = SL_PARAM_FLOAT, .default_value = {.f = {0.5f}}, .min = 0, .max = 45, .unit = "deg",
              .description = "Directional lights: the angular radius of the light's disk (the sun: 0.27). Specular "
                             "highlights widen to its reflection (sl_light_spread); shadow plugins soften by it."),
    LIGHT_KEY(animate, .type = SL_PARAM_ENUM, .enum_values = animations,
              .description = "orbit: position and direction circle the world Y axis (a directional light rotates); "
                             "wobble: the direction swings about the horizontal axis across it."),
    LIGHT_KEY(animate_speed, .type = SL_PARAM_FLOAT, .default_value = {.f = {0.5f}}, .min = -100, .max = 100,
              .unit = "rad/s", .description = "Angular speed of the animation."),
    LIGHT_KEY(animate_amount, .type = SL_PARAM_FLOAT, .default_value = {.f = {15}}, .min = 0, .max = 90,
              .unit = "deg", .description = "Wobble amplitude."),
};
#define LIGHT_KEY_COUNT (sizeof light_keys / sizeof *light_keys)

/* The schema's type must describe the field (a bool key on a float field would write garbage). */
static bool light_key_valid(const light_key *k) {
    sl_param_type t = k->desc.type;
    bool ok = k->field == FIELD_BOOL ? t == SL_PARAM_BOOL
            : k->field == FIELD_FLOAT ? t == SL_PARAM_FLOAT
            : k->field == FIELD_FLOAT3 ? t == SL_PARAM_COLOR || t == SL_PARAM_VEC3
            : t == SL_PARAM_ENUM;
    if (!ok) SL_ERROR("core light key %s: its schema type does not match the sl_light field's type", k->desc.id);
    return ok;
}

static const light_key *find_light_key(const char *key) {
    for (size_t i = 0; i < LIGHT_KEY_COUNT; i++)
        if (!strcmp(light_keys[i].desc.id, key)) return &light_keys[i];
    return NULL;
}

bool sl_core_light_key(const char *key) { return find_light_key(key) != NULL; }

bool sl_core_light_get(const sl_light *L, const char *key, sl_value *out) {
    const light_key *k = find_light_key(key);
    if (!k) return false;
    const char *field = (const char *)L + k->offset;
    memset(out, 0, sizeof *out);
    switch (k->field) {
    case FIELD_BOOL: out->b = *(const bool *)field; break;
    case FIELD_FLOAT: out->f[0] = *(const float *)field; break;
    case FIELD_FLOAT3: memcpy(out->f, field, 3 * sizeof(float)); break;
    case FIELD_ANIMATION: out->i = (int)*(const sl_light_animation *)field; break;
    }
    return true;
}

bool sl_core_light_set(sl_light *L, const char *key, const sl_value *v, const char *what, char *err, size_t n) {
    const light_key *k = find_light_key(key);
    if (!k) { snprintf(err, n, "%s: not a key of every light", what); return false; }
    char *field = (char *)L + k->offset;
    switch (k->field) {
    case FIELD_BOOL: *(bool *)field = v->b; break;
    case FIELD_FLOAT: *(float *)field = v->f[0]; break;
    case FIELD_ANIMATION: *(sl_light_animation *)field = (sl_light_animation)v->i; break;
    case FIELD_FLOAT3: {
        float f[3] = {v->f[0], v->f[1], v->f[2]};
        if (k->unit_vector) {
            float len = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
            if (!(len > 0)) { snprintf(err, n, "%s: a %s must not be zero", what, key); return false; }
            for (int i = 0; i < 3; i++) f[i] /= len;
        }
        memcpy(field, f, sizeof f);
        break;
    }
    }
    return true;
}

/* ---- registration --------------------------------------------------------------------------- */

static sl_status core_create(const sl_host *host, void **user) {
    static const sl_param_desc params[] = {
        {.struct_size = sizeof(sl_param_desc), .id = "ssaa", .type = SL_PARAM_INT, .default_value = {.i = 1},
         .min = 1, .max = 8, .step = 1, .unit = "x", .group = "quality", .flags = SL_PARAM_QUALITY_KNOB,
         .description = "Supersampling: the forward pass renders at ssaa x the viewport per axis and is box-filtered "
                        "down in linear HDR."},
        {.struct_size = sizeof(sl_param_desc), .id = "anisotropy", .type = SL_PARAM_INT, .default_value = {.i = 0},
         .min = 0, .max = 16, .step = 1, .unit = "x", .group = "quality", .zero_label = "auto",
         .description = "Maximum anisotropic filtering of material textures; 0 = what looks right on the backend: 8 on "
                        "a GPU, 1 on a CPU renderer (llvmpipe's anisotropic filter scallops edges seen at grazing "
                        "angles). References set 1: anisotropic taps average a normal map along the view direction, "
                        "a prefilter a ground truth must not have. (Not a swept quality knob: a reference setting.)"},
        {.struct_size = sizeof(sl_param_desc), .id = "budget", .type = SL_PARAM_FLOAT, .min = 0, .max = 10000,
         .step = 1, .unit = "ms", .group = "budget", .zero_label = "off",
         .description = "Frame-time budget: while anything moves, the render scale and the plugins' quality knobs "
                        "are chosen per frame for the least predicted error within it; a still view refines to the "
                        "best settings. 0 = off (headless default); the window starts at 66 (--budget). See "
                        "docs/budget.md."},
        {.struct_size = sizeof(sl_param_desc), .id = "lod_pixels", .type = SL_PARAM_FLOAT, .min = 0, .max = 16,
         .step = 0.25f, .unit = "px", .group = "quality", .zero_label = "off",
         .description = "Level of detail: a mesh of 2048 triangles or more is drawn with the coarsest of its "
                        "simplified versions (meshoptimizer, made at first use) whose geometric error, projected "
                        "onto the image, is at most this many pixels. 0 = off (the default): every mesh in full."},
        {.struct_size = sizeof(sl_param_desc), .id = "render_scale", .type = SL_PARAM_FLOAT, .default_value = {.f = {1}},
         .min = 0.25f, .max = 1, .step = 0.05f, .unit = "x", .group = "quality", .flags = SL_PARAM_QUALITY_KNOB,
         .description = "Render at this fraction of the window per axis; the window shows it scaled up (bilinear, "
                        "or by an upscaler pass: aa.taa_upscale). The budget lowers it while the view moves."},
        {.struct_size = sizeof(sl_param_desc), .id = "rerun_passes", .type = SL_PARAM_BOOL, .group = "debug",
         .description = "Run every pass in every frame, none skipped because nothing it depends on changed: what a "
                        "frame costs while everything moves (benchmarks of passes that a still runs once: sss, "
                        "shadow maps). The image is the same."},
        /* material keys */
        {.struct_size = sizeof(sl_param_desc), .id = "base_color", .type = SL_PARAM_COLOR, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.f = {0.8f, 0.8f, 0.8f}}, .group = "material", .material_input = "base_color",
         .description = "Diffuse albedo k_d (linear RGB); multiplies base_color_map when both are given."},
        {.struct_size = sizeof(sl_param_desc), .id = "base_color_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL,
         .group = "material", .material_input = "base_color_texture",
         .description = "Diffuse colour texture (sRGB), or a procedural spec such as checker:8:r,g,b:r,g,b."},
        /* glTF 2.0 material inputs every model honours (shaders/material.glsl): emission adds its
         * radiance to whatever the model computes; occlusion scales s.ao, which only the ambient and
         * environment terms read (glTF: occlusion "applies only to indirect lighting") */
        {.struct_size = sizeof(sl_param_desc), .id = "emissive", .type = SL_PARAM_COLOR, .scope = SL_SCOPE_MATERIAL,
         .group = "material", .material_input = "emissive",
         .description = "Emitted radiance (linear RGB, W/(m² sr)) added to the shading: glTF emissiveFactor; times "
                        "emissive_map and emissive_strength when given."},
        {.struct_size = sizeof(sl_param_desc), .id = "emissive_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL,
         .group = "material", .material_input = "emissive_texture",
         .description = "Emission texture (sRGB), times emissive (glTF emissiveTexture; without emissive it emits nothing)."},
        {.struct_size = sizeof(sl_param_desc), .id = "emissive_strength", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.f = {1}}, .min = 0, .max = 10000, .group = "material", .material_input = "emissive_strength",
         .description = "Multiplier of the emission (KHR_materials_emissive_strength)."},
        {.struct_size = sizeof(sl_param_desc), .id = "opacity", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.f = {1}}, .min = 0, .max = 1, .group = "material", .material_input = "opacity",
         .description = "Coverage factor (glTF baseColorFactor.a), times base_color_map's alpha; read by alpha_cutoff "
                        "and alpha_blend."},
        {.struct_size = sizeof(sl_param_desc), .id = "alpha_cutoff", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.f = {0.5f}}, .min = 0, .max = 1, .group = "material", .material_input = "alpha_cutoff",
         .description = "glTF alphaMode MASK: fragments whose coverage (opacity x base_color_map alpha) is below it "
                        "are cut out; materials without the key are opaque."},
        {.struct_size = sizeof(sl_param_desc), .id = "alpha_blend", .type = SL_PARAM_BOOL, .scope = SL_SCOPE_MATERIAL,
         .flags = SL_PARAM_NEEDS_RECOMPILE, .group = "material", .material_input = "alpha_blend",
         .description = "glTF alphaMode BLEND: drawn after the opaque materials, back to front, over what is behind by "
                        "its coverage a (opacity x base_color_map alpha): a c + (1 - a) behind, no depth writes; its "
                        "shadows are dithered to let 1 - a of the light through."},
        {.struct_size = sizeof(sl_param_desc), .id = "double_sided", .type = SL_PARAM_BOOL, .scope = SL_SCOPE_MATERIAL,
         .group = "material", .material_input = "double_sided",
         .description = "glTF doubleSided: back faces are drawn (shaded with the flipped normal) instead of culled."},
        {.struct_size = sizeof(sl_param_desc), .id = "unlit", .type = SL_PARAM_BOOL, .scope = SL_SCOPE_MATERIAL,
         .flags = SL_PARAM_NEEDS_RECOMPILE, .group = "material", .material_input = "unlit",
         .description = "KHR_materials_unlit: the surface shows its base colour (base_color x base_color_map) as "
                        "radiance, no lighting."},
        {.struct_size = sizeof(sl_param_desc), .id = "occlusion_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL,
         .flags = SL_PARAM_LINEAR_DATA, .group = "material", .material_input = "occlusion_texture",
         .description = "Ambient occlusion in the red channel (linear, glTF occlusionTexture): scales the ambient and "
                        "environment light only, never a light's direct term."},
        {.struct_size = sizeof(sl_param_desc), .id = "occlusion_strength", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.f = {1}}, .min = 0, .max = 1, .group = "material", .material_input = "occlusion_strength",
         .description = "glTF occlusionTexture.strength: ao = 1 + strength · (texel.r − 1)."},
    };
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    for (size_t i = 0; i < LIGHT_KEY_COUNT; i++)
        if (!light_key_valid(&light_keys[i]) || host->add_param(host, &light_keys[i].desc) != SL_OK) return SL_ERR_FAILED;
    /* the render scale's model for the budget: cost the pixels' share (s²); error the RMSE of the
     * default scene rendered at s and scaled up bilinearly against the full size (docs/budget.md) */
    static const char *const scales[] = {"0.25", "0.35", "0.5", "0.6", "0.7", "0.85", "1"};
    static const float scale_cost[] = {0.0625f, 0.1225f, 0.25f, 0.36f, 0.49f, 0.7225f, 1};
    static const float scale_error[] = {0.0359f, 0.0274f, 0.0218f, 0.0181f, 0.0166f, 0.0145f, 0};
    const sl_ext_budget *budget = host->get_extension(host, SL_EXT_BUDGET);
    const sl_quality_model scale = {.struct_size = sizeof scale, .param = "render_scale", .count = 7, .values = scales,
                                    .cost = scale_cost, .error = scale_error,
                                    .measured_with = "docs/budget.md: the default scene at 1280x720, RMSE of linear radiance"};
    if (!budget || budget->add_quality_model(host, &scale) != SL_OK) return SL_ERR_FAILED;

    static const sl_shader_chunk_desc chunks[] = {
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SHADING_MODEL, .file = "lambert.glsl",
         .function = "sl_model_lambert", .name = "lambert"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_MODEL_AMBIENT, .file = "lambert.glsl",
         .function = "sl_model_lambert_ambient", .name = "lambert"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_MODEL_LOBES, .file = "lambert.glsl",
         .function = "sl_model_lambert_lobes", .name = "lambert"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_LIGHT, .file = "lights.glsl",
         .function = "sl_light_directional", .name = "directional"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_LIGHT, .file = "lights.glsl",
         .function = "sl_light_point", .name = "point"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SURFACE, .file = "occlusion.glsl",
         .function = "sl_surface_occlusion", .when_material_has = "occlusion_map", .order = 30},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_DEBUG_VIEW, .file = "debug_views.glsl",
         .function = "sl_debug_diffuse_texture", .name = "diffuse-texture", .description = "base colour (texture × factor)"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_DEBUG_VIEW, .file = "debug_views.glsl",
         .function = "sl_debug_normal", .name = "normal", .description = "shading normal, n·0.5 + 0.5"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_DEBUG_VIEW, .file = "debug_views.glsl",
         .function = "sl_debug_uv", .name = "uv", .description = "texture coordinates (fract(u), fract(v), 0)"},
    };
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
    static const sl_reference_desc reference = {
        .struct_size = sizeof reference, .settings = "core.ssaa=8",
        .description = "8x8 supersampling (64 samples per pixel, box filter) of the same scene."};
    host->set_reference(host, &reference);
    *user = NULL;
    return SL_OK;
}

const sl_plugin_desc sl_core_plugin = {
    SL_PLUGIN_HEADER,
    .id = "core",
    .version = SL_VERSION,
    .description = "Lambert shading, directional and point lights, debug views (built in).",
    .create = core_create,
};
