/* aa-test-mover: a test plugin for test_aa. Materials carrying "aa_test_speed" (world units per
 * second) move along +x with sl_time through a VERTEX hook, so the core's motion vectors must
 * come from the hook evaluated at the previous frame's time. */
#include <shadelab/shadelab.h>

static sl_status create(const sl_host *host, void **user) {
    (void)user;
    const sl_param_desc speed = {.struct_size = sizeof speed, .id = "aa_test_speed", .type = SL_PARAM_FLOAT,
                                 .scope = SL_SCOPE_MATERIAL, .min = -100, .max = 100, .step = 0.1f,
                                 .description = "Object-space x velocity (units/s) of the material's meshes."};
    if (host->add_param(host, &speed) != SL_OK) return SL_ERR_FAILED;
    const sl_shader_chunk_desc hook = {.struct_size = sizeof hook, .hook = SL_HOOK_VERTEX, .file = "aa_test_mover.glsl",
                                       .function = "aa_test_move", .when_material_has = "aa_test_speed"};
    return host->add_shader_chunk(host, &hook);
}

static const sl_plugin_desc desc = {SL_PLUGIN_HEADER, .id = "aa-test-mover", .version = "1",
                                    .description = "test: moves materials with aa_test_speed along +x", .create = create};
SL_DEFINE_PLUGIN(desc)
