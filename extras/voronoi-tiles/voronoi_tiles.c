/* voronoi-tiles: procedural Voronoi tiles with an analytic seam and ambient occlusion (the
 * gloss-map assignment's procedural extra credit). See README.md.
 *
 * A SURFACE hook (voronoi_tiles.glsl) used only by materials carrying the key `voronoi_tiles`:
 * texture space (uv · scale) is divided into cells with one hashed seed each; the nearest seed
 * gives the tile's colour and gloss (GGX α / blinn-gloss's α); the distance to the bisectors
 * between the nearest and the second and third nearest seeds gives the seam's rounded
 * (quarter-circle) profile, its normal and an analytic ambient occlusion between 1 (tile top) and
 * 0.5 (the foot of the vertical wall at the bisector).
 *
 * Quality knobs: search (3x3 cells / seeds within √3.25 cells, the assignment's rule / exact
 * 7x7) and samples (samples² positions over the pixel footprint). Reference: search=exact,
 * samples=8. */
#include <shadelab/shadelab.h>
#include <stdlib.h>

static const char *const searches[] = {"3x3", "radius", "exact", NULL};

static sl_status vt_create(const sl_host *host, void **user) {
    *user = NULL;
    static const char *const cells = "cells", *const look = "look", *const quality = "quality";
    const sl_param_desc params[] = {
        {.struct_size = sizeof(sl_param_desc), .id = "voronoi_tiles", .type = SL_PARAM_BOOL, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.b = true},
         .description = "Materials carrying this key are tiled (their base colour is multiplied by the tile colour)."},
        {.struct_size = sizeof(sl_param_desc), .id = "scale", .type = SL_PARAM_FLOAT, .default_value = {.f = {8}},
         .min = 0.5f, .max = 256, .step = 0.5f, .unit = "cells per uv unit", .group = cells,
         .description = "Cells across one unit of texture space."},
        {.struct_size = sizeof(sl_param_desc), .id = "jitter", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.8f}},
         .min = 0, .max = 1, .step = 0.01f, .group = cells,
         .description = "How far a seed may sit from its cell's centre (0 = a square grid, 1 = anywhere in the cell)."},
        {.struct_size = sizeof(sl_param_desc), .id = "seed", .type = SL_PARAM_INT, .default_value = {.i = 1},
         .min = 0, .max = 1000000, .group = cells, .description = "Hash seed: another value gives another tiling."},
        {.struct_size = sizeof(sl_param_desc), .id = "seam_width", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.12f}},
         .min = 0, .max = 1, .step = 0.005f, .unit = "cells", .group = look,
         .description = "Width of the seam (two rounded tile edges meeting at the bisector); 0 = no seam."},
        {.struct_size = sizeof(sl_param_desc), .id = "color_a", .type = SL_PARAM_COLOR, .default_value = {.f = {0.75f, 0.42f, 0.25f}},
         .group = look, .description = "Tile colours are mixed between color_a and color_b by the seed's hash (linear RGB)."},
        {.struct_size = sizeof(sl_param_desc), .id = "color_b", .type = SL_PARAM_COLOR, .default_value = {.f = {0.35f, 0.45f, 0.6f}},
         .group = look, .description = "Second end of the tile colour range (linear RGB)."},
        {.struct_size = sizeof(sl_param_desc), .id = "alpha_min", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.08f}},
         .min = 0.002f, .max = 1, .step = 0.005f, .group = look,
         .description = "Glossiest tile's α (GGX roughness², blinn-gloss's α); a tile's α is hashed between alpha_min and alpha_max."},
        {.struct_size = sizeof(sl_param_desc), .id = "alpha_max", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.5f}},
         .min = 0.002f, .max = 1, .step = 0.005f, .group = look, .description = "Roughest tile's α."},
        {.struct_size = sizeof(sl_param_desc), .id = "search", .type = SL_PARAM_ENUM, .default_value = {.i = 1},
         .enum_values = searches, .flags = SL_PARAM_NEEDS_RECOMPILE | SL_PARAM_QUALITY_KNOB, .group = quality,
         .description = "Seeds searched: 3x3 cells (misses some 2nd/3rd nearest), radius √3.25 cells (the assignment), exact (7x7)."},
        {.struct_size = sizeof(sl_param_desc), .id = "samples", .type = SL_PARAM_INT, .default_value = {.i = 1},
         .min = 1, .max = 8, .flags = SL_PARAM_QUALITY_KNOB, .group = quality,
         .description = "samples × samples positions over the pixel's footprint, averaged (antialiases the seams)."},
    };
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_shader_chunk_desc chunks[] = {
        /* after the models' own α (ggx 0..2, phong 20) and normal-map (10): the tile sets them */
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SURFACE, .file = "voronoi_tiles.glsl",
         .function = "voronoi_tiles_surface", .when_material_has = "voronoi_tiles", .order = 30},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_DEBUG_VIEW, .file = "voronoi_tiles.glsl",
         .function = "voronoi_tiles_view", .name = "voronoi-tiles",
         .description = "voronoi-tiles: seam distance in cells (r), analytic AO (g), tile hash (b)"},
    };
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_reference_desc ref = {.struct_size = sizeof ref, .settings = "voronoi-tiles.search=exact voronoi-tiles.samples=8",
                                   .description = "every seed that can be among the three nearest (7x7 cells), 64 samples over each pixel"};
    host->set_reference(host, &ref);
    return SL_OK;
}

static const sl_plugin_desc desc = {
    SL_PLUGIN_HEADER,
    .id = "voronoi-tiles",
    .version = "1.0.0",
    .description = "Procedural Voronoi tiles: hashed colour and gloss per cell, rounded seams with analytic AO",
    .create = vt_create,
};
SL_DEFINE_PLUGIN(desc)
