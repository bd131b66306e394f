/* nod: colour and position variations over time (the head assignment's extra credit).
 *
 * A free-running time (sl_time) drives
 *   - a VERTEX hook (nod.glsl, nod_vertex) that rotates the part of the tagged meshes on one side
 *     of a plane through the pivot ("above the neck", "beyond the ear root") about an axis
 *     through the pivot, by θ(t) = amplitude · sin(2π f t); a band of width `blend` eases the
 *     rotation in (θ·w, w = smoothstep), so the surface stays connected; run only on meshes of
 *     scene nodes tagged "nod" (ABI 1.6 when_node_tag), in every program of them (forward,
 *     shadow maps), so shadows follow;
 *   - a SURFACE hook (nod_surface) that mixes the base colour of materials carrying the key
 *     `nod_color` toward that colour inside a sphere around a point of the rest pose (found from
 *     SlSurface.object_position, ABI 1.6, so it stays on the moving surface), by strength · (1 − cos 2π f_c t)/2 (the nose reddens
 *     and fades, periodically).
 * Positions and directions are in the scene's world space of the rest pose: every mesh under a
 * tagged node (skull, ears, nose; a file's sub-meshes) has its own object space, one pivot must
 * be shared. Loaded but switched off, or with no tagged node and no nod_color material, it compiles nothing
 * (the core drops a when_node_tag hook from programs no tagged node draws).
 *
 * Quality knob: nod.normals — how normals and tangents follow the deformation: rest (unchanged:
 * wrong shading on the moved part), rigid (rotated by R(θw): exact where the motion is rigid,
 * approximate in the blend band), exact (the deformation's Jacobian, closed form: J = R(I + v'uᵀ),
 * normals by its inverse transpose). The reference is exact. */
#include <shadelab/shadelab.h>
#include <stdlib.h>

static const char *const normal_modes[] = {"rest", "rigid", "exact", NULL};

static sl_status nod_create(const sl_host *host, void **user) {
    *user = NULL;
    static const char *const motion = "motion", *const colour = "colour";
    const sl_param_desc params[] = {
        {.struct_size = sizeof(sl_param_desc), .id = "amplitude", .type = SL_PARAM_FLOAT, .default_value = {.f = {12}},
         .min = -90, .max = 90, .step = 0.5f, .unit = "°", .group = motion,
         .description = "Peak rotation angle of the moving region: θ(t) = amplitude · sin(2π·frequency·t)."},
        {.struct_size = sizeof(sl_param_desc), .id = "frequency", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.5f}},
         .min = 0, .max = 10, .step = 0.01f, .unit = "Hz", .group = motion,
         .description = "Nods per second (0 = no motion)."},
        {.struct_size = sizeof(sl_param_desc), .id = "pose_time", .type = SL_PARAM_FLOAT, .default_value = {.f = {-1}},
         .min = -1, .max = 3600, .step = 0.01f, .unit = "s", .group = motion,
         .description = "-1: free-running (the viewer's time); t >= 0: hold the pose and colour of time t (stills, benchmarks)."},
        {.struct_size = sizeof(sl_param_desc), .id = "pivot", .type = SL_PARAM_VEC3, .default_value = {.f = {0, 0, 0}},
         .group = motion, .description = "Point the region turns about (the neck, an ear root); world space of the rest pose."},
        {.struct_size = sizeof(sl_param_desc), .id = "axis", .type = SL_PARAM_VEC3, .default_value = {.f = {1, 0, 0}},
         .group = motion, .description = "Rotation axis through the pivot, world space (normalised; x = a nod, z = a tilt)."},
        {.struct_size = sizeof(sl_param_desc), .id = "region", .type = SL_PARAM_VEC3, .default_value = {.f = {0, 1, 0}},
         .group = motion,
         .description = "World direction u: rest points p with (p − pivot)·u > 0 move; (0,1,0) = above the pivot's height."},
        {.struct_size = sizeof(sl_param_desc), .id = "mirror", .type = SL_PARAM_VEC3, .default_value = {.f = {0, 0, 0}},
         .group = motion,
         .description = "(0,0,0) = off; else the normal of a mirror plane through the world origin: the motion is repeated mirrored on its other side (both ears flap)."},
        {.struct_size = sizeof(sl_param_desc), .id = "blend", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.2f}},
         .min = 0, .max = 10, .step = 0.01f, .unit = "m", .group = motion,
         .description = "Width of the band over which the rotation eases in (smoothstep); 0 = a hard cut."},
        {.struct_size = sizeof(sl_param_desc), .id = "normals", .type = SL_PARAM_ENUM, .default_value = {.i = 2},
         .enum_values = normal_modes, .flags = SL_PARAM_NEEDS_RECOMPILE | SL_PARAM_QUALITY_KNOB, .group = motion,
         .description = "How normals follow: rest (unchanged), rigid (rotated), exact (the deformation's Jacobian; the reference)."},
        {.struct_size = sizeof(sl_param_desc), .id = "color_frequency", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.25f}},
         .min = 0, .max = 10, .step = 0.01f, .unit = "Hz", .group = colour,
         .description = "Colour cycles per second: weight (1 − cos 2π f t)/2, 0 at t = 0."},
        {.struct_size = sizeof(sl_param_desc), .id = "color_strength", .type = SL_PARAM_FLOAT, .default_value = {.f = {0.8f}},
         .min = 0, .max = 1, .step = 0.01f, .group = colour,
         .description = "Peak mix toward the material's nod_color (1 = fully that colour)."},
        {.struct_size = sizeof(sl_param_desc), .id = "color_center", .type = SL_PARAM_VEC3, .default_value = {.f = {0, 0, 0}},
         .group = colour, .description = "Centre of the recoloured region in the rest pose, world space (the nose tip)."},
        {.struct_size = sizeof(sl_param_desc), .id = "color_radius", .type = SL_PARAM_FLOAT, .default_value = {.f = {1}},
         .min = 0, .max = 1000, .step = 0.01f, .unit = "m", .group = colour,
         .description = "Radius of the recoloured region; the weight falls off smoothly from half this radius to it."},
        {.struct_size = sizeof(sl_param_desc), .id = "nod_color", .type = SL_PARAM_COLOR, .scope = SL_SCOPE_MATERIAL,
         .default_value = {.f = {0.8f, 0.1f, 0.08f}},
         .description = "Materials carrying this key change colour toward it over time (linear RGB)."},
    };
    for (size_t i = 0; i < sizeof params / sizeof *params; i++)
        if (host->add_param(host, &params[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_shader_chunk_desc chunks[] = {
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_VERTEX, .file = "nod.glsl",
         .function = "nod_vertex", .when_node_tag = "nod"},
        {.struct_size = sizeof(sl_shader_chunk_desc), .hook = SL_HOOK_SURFACE, .file = "nod_color.glsl",
         .function = "nod_surface", .when_material_has = "nod_color", .order = 5},
    };
    for (size_t i = 0; i < sizeof chunks / sizeof *chunks; i++)
        if (host->add_shader_chunk(host, &chunks[i]) != SL_OK) return SL_ERR_FAILED;
    const sl_reference_desc ref = {.struct_size = sizeof ref, .settings = "nod.normals=exact",
                                   .description = "normals by the inverse transpose of the deformation's exact Jacobian"};
    host->set_reference(host, &ref);
    return SL_OK;
}

static const sl_plugin_desc desc = {
    SL_PLUGIN_HEADER,
    .id = "nod",
    .version = "1.0.0",
    .description = "Vertex and colour animation over time: a region of tagged nodes nods, a region's colour changes",
    .create = nod_create,
};
SL_DEFINE_PLUGIN(desc)
