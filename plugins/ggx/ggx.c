/* ggx: the Cook–Torrance microfacet BRDF with the GGX distribution (Walter et al. 2007), exact
 * dielectric Fresnel, Schlick, and the glTF metallic-roughness combination, chosen per material.
 * GLSL: the SDK shader library's ggx_brdf.glsl (pure BRDF terms, shared with every model that
 * needs them: envmap, sss, extras), ggx_model.glsl (the shading model and debug views),
 * ggx_surface.glsl (material inputs → SlSurface). See README.md. */
#include <shadelab/shadelab.h>
#include <stdlib.h>

static const char *const fresnel_modes[] = {"exact", "schlick", "metallic-roughness", NULL};
static const char *const spaces[] = {"world", "camera", NULL};
static const char *const g1_angles[] = {"normal", "half-vector", NULL};

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}
static const sl_param_desc params[] = {
    /* globals */
    P(.id = "space", .type = SL_PARAM_ENUM, .enum_values = spaces, .flags = SL_PARAM_NEEDS_RECOMPILE, .group = "debug",
      .description = "Space the BRDF is evaluated in; world and camera must agree (a rotation)."),
    P(.id = "zero_specular", .type = SL_PARAM_BOOL, .flags = SL_PARAM_NEEDS_RECOMPILE, .group = "debug",
      .description = "Diffuse only: drops the specular term of every ggx material."),
    P(.id = "g1_angle", .type = SL_PARAM_ENUM, .enum_values = g1_angles, .flags = SL_PARAM_NEEDS_RECOMPILE,
      .group = "model",
      .description = "Angle θ_x in G1: from the normal (Walter et al. 2007) or from h (the head assignment's wording)."),
    P(.id = "specular_aa", .type = SL_PARAM_BOOL, .default_value = {.b = true},
      .flags = SL_PARAM_NEEDS_RECOMPILE | SL_PARAM_QUALITY_KNOB,
      .group = "quality",
      .description = "Toksvig specular antialiasing: normal-map variance from its mip chain widens alpha."),
    P(.id = "layer_clearcoat", .type = SL_PARAM_BOOL, .default_value = {.b = true}, .flags = SL_PARAM_NEEDS_RECOMPILE,
      .group = "layers", .description = "Render the clear coat of materials that carry one (KHR_materials_clearcoat)."),
    /* material keys */
    P(.id = "alpha", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {0.3f}}, .min = 0, .max = 1,
      .step = 0.01f, .group = "ggx", .description = "GGX α (width of the microfacet distribution); 0 is clamped to 2e-3."),
    P(.id = "roughness", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {0.5f}}, .min = 0,
      .max = 1, .step = 0.01f, .group = "ggx", .material_input = "roughness",
      .description = "Perceptual roughness (glTF): α = roughness²."),
    P(.id = "roughness_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "ggx", .material_input = "metallic_roughness_texture",
      .description = "Roughness in the green channel (glTF layout), times roughness when given; with fresnel = "
                     "metallic-roughness, metalness in the blue channel, times metallic."),
    P(.id = "specular", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1}}, .min = 0,
      .max = 1, .step = 0.01f, .group = "ggx", .description = "k_s, the weight of the specular term."),
    P(.id = "specular_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "ggx", .description = "k_s from the red channel (linear), times specular when given."),
    P(.id = "eta", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1.0f / 1.5f}},
      .min = 0.05f, .max = 20, .step = 0.01f, .group = "ggx",
      .description = "Relative index of refraction η = n1/n2 (air over glass: 1/1.5)."),
    P(.id = "fresnel", .type = SL_PARAM_ENUM, .scope = SL_SCOPE_MATERIAL, .enum_values = fresnel_modes,
      .flags = SL_PARAM_NEEDS_RECOMPILE, .group = "ggx", .material_input = "brdf",
      .description = "exact dielectric Fresnel, Schlick, or glTF metallic-roughness (F0 = mix(0.04, base, metallic))."),
    P(.id = "ior", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1.5f}}, .min = 0,
      .max = 10, .step = 0.01f, .group = "ggx", .material_input = "ior",
      .description = "fresnel = metallic-roughness: the dielectric's index of refraction (KHR_materials_ior), "
                     "F0 = ((ior - 1)/(ior + 1))^2; 0.04 without it."),
    P(.id = "metallic", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = 0, .max = 1, .step = 0.01f,
      .group = "ggx", .material_input = "metallic", .description = "Metalness for fresnel = metallic-roughness."),
    /* KHR_materials_clearcoat (README "Layers") */
    P(.id = "clearcoat", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = 0, .max = 1, .step = 0.01f,
      .group = "clearcoat", .material_input = "clearcoat",
      .description = "Clear-coat weight: a second GGX lobe (IOR 1.5) over the material, which it dims by 1 - weight*F."),
    P(.id = "clearcoat_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "clearcoat", .material_input = "clearcoat_texture",
      .description = "Clear-coat weight in the red channel, times clearcoat."),
    P(.id = "clearcoat_roughness", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .min = 0, .max = 1, .step = 0.01f,
      .group = "clearcoat", .material_input = "clearcoat_roughness",
      .description = "Perceptual roughness of the coat: its alpha = roughness^2 (0 without it)."),
    P(.id = "clearcoat_roughness_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "clearcoat", .material_input = "clearcoat_roughness_texture",
      .description = "Coat roughness in the green channel, times clearcoat_roughness."),
    P(.id = "clearcoat_normal_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
      .group = "clearcoat", .material_input = "clearcoat_normal_texture",
      .description = "The coat's own tangent-space normal map (+Y up); without it the coat follows the mesh's normal."),
    P(.id = "clearcoat_normal_scale", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1}},
      .min = 0, .max = 10, .step = 0.01f, .group = "clearcoat", .material_input = "clearcoat_normal_scale",
      .description = "Scale of the coat normal map's X and Y."),
};

#define C(...) {.struct_size = sizeof(sl_shader_chunk_desc), __VA_ARGS__}
static const sl_shader_chunk_desc chunks[] = {
    /* Smith masking gives normals facing away from the viewer no specular (G1(v) = 0), so
     * normal maps leave them unbent for this model (README, "Numerical guards") */
    C(.hook = SL_HOOK_SHADING_MODEL, .file = "ggx_model.glsl", .function = "ggx_model", .name = "ggx",
      .flags = SL_CHUNK_MASKS_FACING_AWAY),
    C(.hook = SL_HOOK_MODEL_LOBES, .file = "ggx_model.glsl", .function = "ggx_lobes", .name = "ggx"),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_alpha", .when_material_has = "alpha"),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_roughness",
      .when_material_has = "roughness", .order = 1),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_roughness_map",
      .when_material_has = "roughness_map", .order = 2),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_metallic",
      .when_material_has = "metallic", .order = 1),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_specular",
      .when_material_has = "specular"),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_specular_map",
      .when_material_has = "specular_map", .order = 1),
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_specular_aa",
      .when_material_has = "normal_map", .order = 20),
    /* before normal-map (order 10): the coat keeps the mesh's normal */
    C(.hook = SL_HOOK_SURFACE, .file = "ggx_surface.glsl", .function = "ggx_surface_clearcoat",
      .when_material_has = "clearcoat", .order = 5),
    C(.hook = SL_HOOK_DEBUG_VIEW_LIGHT, .file = "ggx_model.glsl", .function = "ggx_debug_clearcoat",
      .name = "ggx-clearcoat", .description = "the clear coat's own reflection, summed over lights"),
    C(.hook = SL_HOOK_DEBUG_VIEW_LIGHT, .file = "ggx_model.glsl", .function = "ggx_debug_D", .name = "ggx-d",
      .description = "GGX distribution D(h), summed over lights"),
    C(.hook = SL_HOOK_DEBUG_VIEW_LIGHT, .file = "ggx_model.glsl", .function = "ggx_debug_G", .name = "ggx-g",
      .description = "Smith masking-shadowing G = G1(v)G1(l)"),
    C(.hook = SL_HOOK_DEBUG_VIEW_LIGHT, .file = "ggx_model.glsl", .function = "ggx_debug_F", .name = "ggx-f",
      .description = "Fresnel F(l·h); 0 where the light is not visible"),
};

static const sl_key_desc keys[] = {
    {.struct_size = sizeof(sl_key_desc), .key = "Z", .param = "zero_specular", .description = "toggle zero specular"},
};

static sl_status ggx_create(const sl_host *host, void **user) {
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
        if (host->add_key(host, &keys[i]) != SL_OK) return SL_ERR_FAILED;
    /* ground truth for the specular_aa knob (shadelab-bench --plugin ggx, --reference ggx) */
    static const sl_reference_desc reference = {
        .struct_size = sizeof reference, .settings = "core.ssaa=8 core.anisotropy=1 ggx.specular_aa=false",
        .description = "8x8 supersampling without specular antialiasing: every sample shades the normal map at its "
                       "own, finer mip level."};
    host->set_reference(host, &reference);
    *user = NULL;
    return SL_OK;
}

/* The glTF metallic-roughness BRDF (fresnel = metallic-roughness) and its inputs: imported
 * glTF materials load this plugin (the host reads this list without calling create). */
static const char *const ggx_inputs[] = {"brdf", "metallic", "roughness", "metallic_roughness_texture", "ior",
                                         "clearcoat", "clearcoat_texture", "clearcoat_roughness",
                                         "clearcoat_roughness_texture", "clearcoat_normal_texture",
                                         "clearcoat_normal_scale", NULL};

static const char *const ggx_models[] = {"ggx", NULL};
static const sl_plugin_desc ggx_desc = {
    SL_PLUGIN_HEADER,
    .id = "ggx",
    .version = "1.0",
    .description = "Cook-Torrance GGX microfacet BRDF: exact/Schlick/metallic-roughness Fresnel, D/G/F debug views.",
    .create = ggx_create,
    .material_inputs = ggx_inputs,
    .shading_models = ggx_models,
};

SL_DEFINE_PLUGIN(ggx_desc)
