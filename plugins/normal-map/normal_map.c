/* normal-map: perturbs the shading normal from a texture, in tangent space (per-vertex tangent
 * frame, re-orthogonalised per pixel by the core) or object space (through the object's normal
 * matrix). One SURFACE hook gated on the material key "normal_map", so a material without a
 * map compiles none of this plugin's code; two debug views. The GLSL is in nm_lib.glsl (pure
 * functions, unit-tested) and normal_map.glsl (hook and views). The offline bake tool
 * (tangent → object space for a mesh) is in tools/. See README.md. */
#include <shadelab/shadelab.h>
#include <stdlib.h>

#define P(...) {.struct_size = sizeof(sl_param_desc), __VA_ARGS__}

static sl_status nm_create(const sl_host *host, void **user) {
    static const char *const green_values[] = {"opengl", "directx", NULL};
    static const char *const space_values[] = {"tangent", "object", NULL};
    static const sl_param_desc params[] = {
        P(.id = "strength", .type = SL_PARAM_FLOAT, .default_value = {.f = {1}}, .min = 0, .max = 4, .step = 0.05f,
          .group = "normal map",
          .description = "Global strength, multiplied with each material's normal_strength: tangent-space xy are "
                         "scaled (glTF normalTexture.scale); object-space normals are blended from the interpolated "
                         "normal (0) to the map (1, the most an object-space map can give)."),
        P(.id = "green", .type = SL_PARAM_ENUM, .enum_values = green_values, .group = "normal map",
          .description = "Green channel convention of tangent-space maps: opengl = +Y (green points to the image's "
                         "top: OpenGL, glTF, Blender), directx = -Y (DirectX, Unreal). Object-space maps ignore it."),
        P(.id = "lod_bias", .type = SL_PARAM_FLOAT, .min = -16, .max = 16, .step = 0.25f, .unit = "mip levels",
          .group = "normal map", .flags = SL_PARAM_QUALITY_KNOB,
          .description = "Mip bias of the normal-map lookup (phong's gloss lookups follow it). Negative sharpens and "
                         "aliases; -16 samples level 0 everywhere (the un-prefiltered surface, used by references)."),
        P(.id = "normal_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL, .flags = SL_PARAM_LINEAR_DATA,
          .group = "normal map", .material_input = "normal_texture",
          .description = "Normal map (linear data, n = 2*texel - 1); its space is normal_space. Materials without one "
                         "get no normal-map code."),
        P(.id = "normal_space", .type = SL_PARAM_ENUM, .scope = SL_SCOPE_MATERIAL, .enum_values = space_values,
          .flags = SL_PARAM_NEEDS_RECOMPILE, .group = "normal map",
          .description = "tangent: N = T*x + up*y + N*z in the vertex tangent frame; object: the map holds object-space "
                         "normals, transformed by the normal matrix."),
        P(.id = "normal_strength", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL, .default_value = {.f = {1}},
          .min = 0, .max = 4, .step = 0.05f, .group = "normal map", .material_input = "normal_scale",
          .description = "Per-material strength (multiplies normal-map.strength)."),
    };
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;

    static const sl_shader_chunk_desc chunks[] = {
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SURFACE, .file = "normal_map.glsl",
         .function = "nm_surface", .when_material_has = "normal_map", .order = 10},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_DEBUG_VIEW, .file = "normal_map.glsl",
         .function = "nm_debug_texture", .name = "normal-map-texture",
         .description = "normal map texel as stored in the file (flat 0.5,0.5,1 without a map)"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_DEBUG_VIEW, .file = "normal_map.glsl",
         .function = "nm_debug_final_normal", .name = "final-normal",
         .description = "world normal after all surface hooks, n*0.5+0.5 as PNG values"},
    };
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;

    /* Ground truth for the lookup's filtering (the lod_bias knob): the un-prefiltered map, level 0
     * everywhere, averaged over 8x8 samples per pixel. */
    static const sl_reference_desc reference = {
        .struct_size = sizeof reference, .settings = "core.ssaa=8 core.anisotropy=1 normal-map.lod_bias=-16",
        .description = "8x8 supersampling of the un-prefiltered normal map (mip level 0 everywhere)."};
    host->set_reference(host, &reference);
    /* Key 2 of the gloss-map assignment (phong has 1, 3, 4): normal mapping on/off. */
    const sl_key_desc key = {.struct_size = sizeof key, .key = "2", .param = "enabled",
                             .description = "normal mapping on/off"};
    host->add_key(host, &key);
    *user = NULL;
    return SL_OK;
}

/* glTF's normalTexture and its scale: imported materials with a normal texture load this plugin */
static const char *const nm_inputs[] = {"normal_texture", "normal_scale", NULL};

static const sl_plugin_desc nm_desc = {
    SL_PLUGIN_HEADER,
    .id = "normal-map",
    .version = "1.0",
    .description = "Tangent- and object-space normal maps (surface hook), debug views; bake tool in tools/.",
    .create = nm_create,
    .material_inputs = nm_inputs,
};
SL_DEFINE_PLUGIN(nm_desc)
