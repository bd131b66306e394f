/* displacement: true displacement mapping through the core's tessellation hook (SDK 1.7,
 * SL_HOOK_DISPLACEMENT), and parallax occlusion / plain parallax mapping as the cheap alternatives
 * (the materials assignment's extra credit; README.md).
 *
 * One height field per material, H(uv) in [0, 1] (displacement_height.glsl): a texture
 * (`height_map`, red channel) or a procedural function (`height_function`). The surface is the
 * polygon moved along its normal by h = scale·(H − 1): the polygon is the relief's top.
 *   - `displace: scale` (metres): the core tessellates the material's triangles in every pass
 *     (forward, shadow maps, sss) with edge levels from each edge's length on screen
 *     (`displacement.edge_px`) and moves the generated vertices; normals of the displaced surface.
 *   - `parallax: scale`: a SURFACE hook moves the shading point along the view ray instead
 *     (`displacement.parallax` = occlusion: Tatarchuk 2006, `pom_steps` layers; plain: Welsh 2004),
 *     no geometry: silhouettes and shadows cast stay those of the polygon. A material carrying
 *     both is displaced (the parallax code compiles out).
 * Loaded but switched off, or with no material carrying its keys, it compiles nothing. */
#include <shadelab/shadelab.h>
#include <stdlib.h>

static const char *const functions[] = {"bump", "waves", "bark", "rings", NULL};
static const char *const parallax_modes[] = {"occlusion", "plain", NULL};

static sl_status displacement_create(const sl_host *host, void **user) {
    *user = NULL;
    static const char *const tess = "tessellation", *const par = "parallax";
    const sl_param_desc params[] = {
        {.struct_size = sizeof(sl_param_desc), .id = "edge_px", .type = SL_PARAM_FLOAT, .default_value = {.f = {6}},
         .min = 1, .max = 64, .step = 0.5f, .unit = "px", .group = tess, .flags = SL_PARAM_QUALITY_KNOB,
         .description = "Target length on screen of a tessellated edge: level = edge length in pixels / edge_px "
                        "(clamped to 1..64, the GL limit)."},
        {.struct_size = sizeof(sl_param_desc), .id = "parallax", .type = SL_PARAM_ENUM, .default_value = {.i = 0},
         .enum_values = parallax_modes, .group = par, .flags = SL_PARAM_NEEDS_RECOMPILE | SL_PARAM_QUALITY_KNOB,
         .description = "Materials with `parallax`: occlusion (ray marched, Tatarchuk 2006) or plain (one offset "
                        "lookup with offset limiting, Welsh 2004)."},
        {.struct_size = sizeof(sl_param_desc), .id = "pom_steps", .type = SL_PARAM_INT, .default_value = {.i = 24},
         .min = 2, .max = 256, .step = 1, .group = par, .flags = SL_PARAM_QUALITY_KNOB,
         .description = "Parallax occlusion mapping: layers of the linear search at grazing view (a quarter of them "
                        "head-on)."},
        /* material keys */
        {.struct_size = sizeof(sl_param_desc), .id = "displace", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.f = {0.05f}}, .min = 0, .max = 100, .step = 0.001f, .unit = "m",
         .description = "True displacement: relief depth (H = 0 lies this far below the polygon, along the normal); "
                        "the material is tessellated in every pass."},
        {.struct_size = sizeof(sl_param_desc), .id = "parallax", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.f = {0.05f}}, .min = 0, .max = 100, .step = 0.001f, .unit = "m",
         .description = "Parallax mapping (displacement.parallax picks the method): relief depth below the polygon; "
                        "no geometry moves (silhouettes and cast shadows stay flat)."},
        {.struct_size = sizeof(sl_param_desc), .id = "height_map", .type = SL_PARAM_TEXTURE, .scope = SL_SCOPE_MATERIAL,
         .flags = SL_PARAM_LINEAR_DATA,
         .description = "Height field, red channel in [0, 1] (1 = the polygon's level); replaces height_function."},
        {.struct_size = sizeof(sl_param_desc), .id = "height_function", .type = SL_PARAM_ENUM, .scope = SL_SCOPE_MATERIAL,
         .enum_values = functions, .default_value = {.i = 0}, .flags = SL_PARAM_NEEDS_RECOMPILE,
         .description = "Procedural height over UV: bump (Gaussian at the centre), waves (product of sines), bark "
                        "(grooves around u, for a trunk's side), rings (growth rings, planar UVs of a sawn end)."},
        {.struct_size = sizeof(sl_param_desc), .id = "height_frequency", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.f = {4}}, .min = 0, .max = 1000, .step = 0.1f,
         .description = "Procedural heights: bump exp(-(f·r)^2); waves/bark/rings: periods (grooves, rings) over the UV square."},
        {.struct_size = sizeof(sl_param_desc), .id = "cavity", .type = SL_PARAM_FLOAT, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.f = {0}}, .min = 0, .max = 1, .step = 0.01f,
         .description = "Darkens the base colour toward H in the hollows (0 = off), whatever the method."},
    };
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_shader_chunk_desc chunks[] = {
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_DISPLACEMENT, .file = "displacement.glsl",
         .function = "displacement_height", .tess_level = "displacement_edge_level", .when_material_has = "displace"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SURFACE, .file = "displacement_surface.glsl",
         .function = "displacement_parallax", .when_material_has = "parallax", .order = 10},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SURFACE, .file = "displacement_surface.glsl",
         .function = "displacement_cavity", .when_material_has = "cavity", .order = 11},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_DEBUG_VIEW, .file = "displacement_surface.glsl",
         .function = "displacement_view_position", .name = "displacement-position",
         .description = "world-space position of the visible surface (RGB = xyz, metres)"},
    };
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_reference_desc ref = {
        .struct_size = sizeof ref, .settings = "displacement.edge_px=1",
        .description = "true displacement at 1-pixel edges (level up to 64); the tests check it against meshes "
                       "displaced on the CPU"};
    host->set_reference(host, &ref);
    return SL_OK;
}

static const sl_plugin_desc desc = {
    SL_PLUGIN_HEADER,
    .id = "displacement",
    .version = "1.0.0",
    .description = "Displacement mapping: tessellated true displacement, parallax occlusion and parallax mapping",
    .create = displacement_create,
};
SL_DEFINE_PLUGIN(desc)
