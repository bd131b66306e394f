/* A toon (cel) shading model as a third party writes it: only the public SDK (<shadelab/...>).
 *
 *   model "toon"   SHADING_MODEL toon_model (toon.glsl): flat bands of the Lambert term, a rim
 *                  and a hard highlight, per light
 *   its lobes      MODEL_LOBES toon_lobes: SL_LOBES_MODEL_AT_DOMINANT_LIGHT (ABI 1.16), so that
 *                  environment and area lights evaluate the model at their dominant direction
 *                  instead of integrating it, and the bands and rim survive them
 *   material keys  toon_bands, toon_rim, toon_rim_color, toon_highlight, toon_highlight_color
 * No GL of its own, no pass: the core composes the GLSL into each toon material's program. */
#include <shadelab/shadelab.h>

#define P(...) {.struct_size = sizeof(sl_param_desc), .scope = SL_SCOPE_MATERIAL, .group = "toon", __VA_ARGS__}

static sl_status toon_create(const sl_host *host, void **user) {
    *user = NULL;
    static const sl_param_desc keys[] = {
        P(.id = "toon_bands", .type = SL_PARAM_INT, .default_value = {.i = 3}, .min = 1, .max = 1024, .step = 1,
          .description = "Number of flat bands of the Lambert term n.l: band k (1..N) where (k-1)/N < n.l <= k/N "
                         "has brightness k/N."),
        P(.id = "toon_rim", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.3f}}, .min = 0, .max = 1, .step = 0.01f,
          .description = "Rim where n.v is below this, on the lit side (0 = no rim)."),
        P(.id = "toon_rim_color", .type = SL_PARAM_COLOR, .default_value = {.f = {0.6f, 0.6f, 0.6f}},
          .description = "Reflectance added in the rim (linear RGB; radiance = colour x E / pi)."),
        P(.id = "toon_highlight", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.97f}}, .min = 0, .max = 1,
          .step = 0.001f, .description = "Hard highlight where n.h is at least this (1 = only exactly at the mirror "
                                         "direction)."),
        P(.id = "toon_highlight_color", .type = SL_PARAM_COLOR, .default_value = {.f = {1, 1, 1}},
          .description = "Reflectance added in the highlight (linear RGB; radiance = colour x E / pi)."),
    };
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
        if (host->add_param(host, &keys[i]) != SL_OK) return SL_ERR_FAILED;
    static const sl_shader_chunk_desc chunks[] = {
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SHADING_MODEL, .file = "toon.glsl",
         .function = "toon_model", .name = "toon"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_MODEL_LOBES, .file = "toon.glsl",
         .function = "toon_lobes", .name = "toon"},
    };
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
    return SL_OK;
}

static const char *const toon_models[] = {"toon", NULL};

static const sl_plugin_desc toon_desc = {
    SL_PLUGIN_HEADER,
    .id = "toon",
    .version = "1.0.0",
    .description = "SDK example: a toon shading model (bands, rim, highlight) that keeps its look under "
                   "environment and area lights.",
    .create = toon_create,
    .shading_models = toon_models,
};
SL_DEFINE_PLUGIN(toon_desc)
