/* A test plugin with a wrap-lit shading model, "ss-wrap-lit": radiance k_d/π · E · (1 + n·l)/2
 * (wrap lighting with w = 1). Every surface the light's E reaches gets light from it, facing the
 * light or not, so shadowed / unshadowed is the shadow's visibility on grazing and back-facing
 * surfaces too, where a Lambert model returns 0 (test_shadow_grazing.c). */
#include <shadelab/shadelab.h>

static sl_status wrap_lit_create(const sl_host *host, void **user) {
    *user = NULL;
    const sl_shader_chunk_desc model = {.struct_size = sizeof model, .hook = SL_HOOK_SHADING_MODEL,
                                        .file = "wrap_lit.glsl", .function = "ss_wrap_lit_model",
                                        .name = "ss-wrap-lit"};
    return host->add_shader_chunk(host, &model) == SL_OK ? SL_OK : SL_ERR_FAILED;
}

static const char *const wrap_lit_models[] = {"ss-wrap-lit", NULL};
static const sl_plugin_desc desc = {SL_PLUGIN_HEADER, .id = "ss-wrap-lit", .version = "1",
                                    .description = "test: wrap-lit shading model (w = 1)",
                                    .create = wrap_lit_create, .shading_models = wrap_lit_models};
SL_DEFINE_PLUGIN(desc)
