/* Test plugin for the ABI 1.6 vertex-hook node filter and SlSurface.object_position
 * (test_vertex_node_tags.c): a VERTEX hook gated on the node tag "lift" (and the material key
 * tp_tag_lift) that raises object-space y by the key's value, and a debug view that shows
 * s.object_position. */
#include <shadelab/shadelab.h>
#include <stdlib.h>

#ifndef TP_TAGGED_ID
#define TP_TAGGED_ID "tp-tagged"
#endif

static sl_status tagged_create(const sl_host *host, void **user) {
    *user = NULL;
    const sl_param_desc lift = {.struct_size = sizeof lift, .id = "tp_tag_lift", .type = SL_PARAM_FLOAT,
                                .scope = SL_SCOPE_MATERIAL, .min = -10, .max = 10,
                                .description = "Object-space y lift of meshes of nodes tagged \"lift\"."};
    if (host->add_param(host, &lift) != SL_OK) return SL_ERR_FAILED;
    const sl_shader_chunk_desc chunks[] = {
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_VERTEX, .file = "tp_tagged.glsl",
         .function = "tp_tagged_vertex", .when_material_has = "tp_tag_lift", .when_node_tag = "lift"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_DEBUG_VIEW, .file = "tp_tagged.glsl",
         .function = "tp_tagged_object_position", .name = "tp-object-position",
         .description = "SlSurface.object_position"},
    };
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
#ifdef TP_TAGGED_BAD
    /* when_node_tag is for VERTEX hooks only: a SURFACE chunk with it is refused (the plugin is
     * then disabled, as for any refused registration) */
    const sl_shader_chunk_desc bad = {.struct_size = sizeof bad, .hook = SL_HOOK_SURFACE, .file = "tp_tagged.glsl",
                                      .function = "tp_tagged_surface", .when_node_tag = "lift"};
    if (host->add_shader_chunk(host, &bad) != SL_ERR_INVALID) return SL_OK; /* loads: the test fails */
#endif
    return SL_OK;
}

static const sl_plugin_desc desc = {SL_PLUGIN_HEADER, .id = TP_TAGGED_ID, .version = "1",
                                    .description = "test: node-tag vertex hook, object_position view",
                                    .create = tagged_create};
SL_DEFINE_PLUGIN(desc)
