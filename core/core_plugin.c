/* The core registers its own shading model, light types, debug views and keys through the
 * same host interface plugins use: one path for everything, and the core is the first example
 * of the API. Its GLSL lives in shaders/. */
#include "core_plugin.h"

static const char *const animations[] = {"none", "orbit", "wobble", NULL};

static sl_status core_create(const sl_host *host, void **user) {
    static const sl_param_desc params[] = {
        {.struct_size = sizeof(sl_param_desc), .id = "ssaa", .type = SL_PARAM_INT, .default_value = {.i = 1},
         .min = 1, .max = 8, .step = 1, .unit = "x", .group = "quality", .flags = SL_PARAM_QUALITY_KNOB,
         .description = "Supersampling: the forward pass renders at ssaa x the viewport per axis and is box-filtered "
                        "down in linear HDR."},
        {.struct_size = sizeof(sl_param_desc), .id = "anisotropy", .type = SL_PARAM_INT, .default_value = {.i = 8},
         .min = 1, .max = 16, .step = 1, .unit = "x", .group = "quality",
         .description = "Maximum anisotropic filtering of material textures. References set 1: anisotropic taps "
                        "average a normal map along the view direction, a prefilter a ground truth must not have. "
                        "(Not a swept quality knob: a reference setting.)"},
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
        /* light keys every light has (they map onto the light record's own fields) */
        {.struct_size = sizeof(sl_param_desc), .id = "enabled", .type = SL_PARAM_BOOL, .scope = SL_SCOPE_LIGHT,
         .default_value = {.b = true}, .group = "light", .description = "Per-light on/off."},
        {.struct_size = sizeof(sl_param_desc), .id = "intensity", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_LIGHT,
         .default_value = {.f = {1}}, .min = 0, .max = 1e10f, .group = "light",
         .description = "Directional: irradiance E at normal incidence (W/m²); point/spot: intensity I (E = I/d²)."},
        {.struct_size = sizeof(sl_param_desc), .id = "color", .type = SL_PARAM_COLOR, .scope = SL_SCOPE_LIGHT,
         .default_value = {.f = {1, 1, 1}}, .group = "light", .description = "Linear RGB tint, multiplied by intensity."},
        {.struct_size = sizeof(sl_param_desc), .id = "position", .type = SL_PARAM_VEC3, .scope = SL_SCOPE_LIGHT,
         .group = "light", .unit = "m", .description = "World position (point and spot lights)."},
        {.struct_size = sizeof(sl_param_desc), .id = "direction", .type = SL_PARAM_VEC3, .scope = SL_SCOPE_LIGHT,
         .default_value = {.f = {0, -1, 0}}, .group = "light",
         .description = "Direction light travels (directional and spot lights); normalised."},
        {.struct_size = sizeof(sl_param_desc), .id = "cast_shadows", .type = SL_PARAM_BOOL, .scope = SL_SCOPE_LIGHT,
         .group = "light", .description = "Whether a shadow plugin renders a shadow map for this light."},
        {.struct_size = sizeof(sl_param_desc), .id = "animate", .type = SL_PARAM_ENUM, .scope = SL_SCOPE_LIGHT,
         .enum_values = animations, .group = "light",
         .description = "orbit: position and direction circle the world Y axis (a directional light rotates); "
                        "wobble: the direction swings about the horizontal axis across it."},
        {.struct_size = sizeof(sl_param_desc), .id = "animate_speed", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_LIGHT,
         .default_value = {.f = {0.5f}}, .min = -100, .max = 100, .unit = "rad/s", .group = "light",
         .description = "Angular speed of the animation."},
        {.struct_size = sizeof(sl_param_desc), .id = "animate_amount", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_LIGHT,
         .default_value = {.f = {15}}, .min = 0, .max = 90, .unit = "deg", .group = "light",
         .description = "Wobble amplitude."},
    };
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;

    static const sl_shader_chunk_desc chunks[] = {
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SHADING_MODEL, .file = "lambert.glsl",
         .function = "sl_model_lambert", .name = "lambert"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_MODEL_AMBIENT, .file = "lambert.glsl",
         .function = "sl_model_lambert_ambient", .name = "lambert"},
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

/* the standard material inputs of imported assets the core's keys take */
static const char *const core_inputs[] = {"base_color", "base_color_texture", "emissive", "emissive_texture",
                                          "emissive_strength", "occlusion_texture", "occlusion_strength", "opacity",
                                          "alpha_cutoff", "alpha_blend", "double_sided", "unlit", NULL};

const sl_plugin_desc sl_core_plugin = {
    SL_PLUGIN_HEADER,
    .id = "core",
    .version = SL_VERSION,
    .description = "Lambert shading, directional and point lights, debug views (built in).",
    .create = core_create,
    .material_inputs = core_inputs,
};
