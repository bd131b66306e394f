/* Extension "shadelab.shadow-maps/1": the shadow maps a shadow plugin rendered this frame, for
 * other plugins (subsurface translucency, volumetrics, debug tools) that need the distance
 * from a light to the first surface it hits without reaching into the provider's code.
 * Provided by the spotlight-shadow plugin.
 *
 *     #include <shadelab/ext/shadow_maps.h>
 *     const sl_ext_shadow_maps *sm = host->get_extension(host, SL_EXT_SHADOW_MAPS);
 *     sl_shadow_map m = {.struct_size = sizeof m};
 *     if (sm && sm->find(sm->ctx, light, 0, &m)) { bind m.texture, sample layer m.layer … }
 *
 * When: the maps are rendered by a SHADOW-stage pass. Call the functions (main thread) from a
 * pass at a later stage, a bind callback, or begin_frame (then they describe the previous
 * frame's maps). NULL from get_extension: no provider loaded or it is disabled.
 *
 * Which lights: every enabled light with cast_shadows = true whose type the provider handles
 * (spotlight-shadow: "spot" and "directional", one map each; "point", six cube faces).
 *
 * Revision 2 ("shadelab.shadow-maps/2", ABI 1.7; the same struct with members appended, so a
 * revision-1 user is served unchanged): another plugin may supply the views of directional
 * lights instead of the provider's one fitted map — cascaded shadow maps (extras/cascades):
 *
 *     const sl_ext_shadow_maps *sm = host->get_extension(host, SL_EXT_SHADOW_MAPS_2);
 *     sm->set_view_provider(sm->ctx, &(sl_shadow_view_provider){.struct_size = …, .views = my_views});
 *
 * The shadow pass then asks views() for every shadowed directional light, renders each view it
 * returns into its own layer (face k = view k) with the provider's usual settings (map_size,
 * cull), and its SHADOW hook picks the view by the receiver's camera depth
 * z = −(camera view · p).z: view k serves split_near ≤ z < split_far, and over the last `blend`
 * metres before split_far its visibility fades linearly into view k + 1's (continuous at the
 * split); beyond the last split_far the light is unshadowed. The pass re-renders when a returned
 * view changes (it hashes them), so a provider that snaps its views to texels re-renders only
 * when a snapped view moves. The provider's reference (filter = reference) keeps its fitted map.
 *
 * Depth convention (what a texel stores):
 *   - the window-space depth d ∈ [0, 1] of the map's view_proj under GL's defaults:
 *       c = view_proj · (p, 1);  d = 0.5 · c.z / c.w + 0.5      (glDepthRange 0..1)
 *     texel (u, v) = (0.5 · c.x / c.w + 0.5, 0.5 · c.y / c.w + 0.5); v = 0 is the first row.
 *   - cleared to 1 (no caster); casters are the materials with cast_shadows = true, both faces
 *     by default (the provider's "cull" parameter), drawn with the core's depth program.
 *   - no bias is baked in: add your own (texel_world tells how large a texel is).
 *   - linear depth (metres along `direction`, from `position`):
 *       perspective:  z = 2·n·f / (f + n − (2d − 1)·(f − n))
 *       orthographic: z = n + d·(f − n)
 *     The distance along the ray from a perspective light to that surface is
 *     z · |p − position| / dot(p − position, direction).
 *   - the texture is GL_TEXTURE_2D_ARRAY, GL_DEPTH_COMPONENT32F, GL_NEAREST, CLAMP_TO_EDGE and
 *     GL_TEXTURE_COMPARE_MODE = GL_NONE (raw depths); for hardware comparison bind your own
 *     sampler object with GL_COMPARE_REF_TO_TEXTURE. Do not modify the texture.
 */
#ifndef SHADELAB_EXT_SHADOW_MAPS_H
#define SHADELAB_EXT_SHADOW_MAPS_H
#include "../shadelab.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SL_EXT_SHADOW_MAPS "shadelab.shadow-maps/1"
#define SL_EXT_SHADOW_MAPS_2 "shadelab.shadow-maps/2" /* ABI 1.7: + set_view_provider */

typedef enum sl_shadow_projection {
    SL_SHADOW_PERSPECTIVE = 1,  /* spot lights, point-light cube faces */
    SL_SHADOW_ORTHOGRAPHIC = 2  /* directional lights, fitted to the scene bounds */
} sl_shadow_projection;

/* One shadow map (one view of one light). Fields are only ever appended; set struct_size to
 * sizeof(sl_shadow_map) before calling, the provider fills what both sides know. */
typedef struct sl_shadow_map {
    uint32_t struct_size;
    int light;               /* index into host->lights() */
    int buffer_index;        /* sl_light_info.index: the light's index in GLSL sl_lights[] */
    int face;                /* 0; point lights: cube face 0..5 = +X, −X, +Y, −Y, +Z, −Z;
                                directional lights with provided views: the view (cascade) */
    unsigned texture;        /* GL name of the 2D array texture holding every map */
    int layer;               /* this map's layer in it */
    int size;                /* width = height, texels */
    sl_shadow_projection projection;
    float view[16], proj[16], view_proj[16]; /* column-major, world → light view → clip */
    float near_plane, far_plane;             /* metres along `direction` from `position` */
    /* World size of one texel: perspective maps at distance 1 along `direction` (multiply by
     * the linear depth); orthographic maps: the size itself. */
    float texel_world;
    float position[3];       /* as rendered this frame (animated lights move); directional:
                                a point behind the scene the orthographic view starts at */
    float direction[3];      /* unit: the map's view axis (the light's direction of travel;
                                point lights: the cube face's axis) */
    /* The light's size for soft shadows: radius in metres (spot, point) or the tangent of the
     * angular radius (directional). */
    float light_size;
    /* Revision 2 (views from a view provider; 0 otherwise): the camera-depth interval this map
     * serves and the blend band before its end, metres. */
    float split_near, split_far, blend;
} sl_shadow_map;

/* Revision 2: one orthographic view a view provider asks for (a cascade). */
typedef struct sl_shadow_view {
    uint32_t struct_size;
    float view[16], proj[16];   /* column-major, world → light view → clip (orthographic; the
                                   view looks along the light's direction of travel) */
    float near_plane, far_plane; /* of proj, metres along the direction from the view's eye */
    float texel_world;          /* world size of one texel at the provider's map_size */
    float split_near, split_far; /* camera depth interval (metres along the camera's forward
                                    axis) this view serves */
    float blend;                /* metres before split_far over which it fades into the next view */
} sl_shadow_view;

/* Revision 2: a plugin that supplies the views of directional lights. */
typedef struct sl_shadow_view_provider {
    uint32_t struct_size;
    void *user;                 /* first argument of views() */
    /* Fills up to `max` views (struct_size set by the caller) for light `light` (index into
     * host->lights(), a shadowed directional light) for frame `f`, maps of `map_size` texels;
     * returns how many (0: the provider's own fitted map). Called on the main thread, GL
     * context current, from the shadow pass's signature and execute (same frame: same
     * answer). Return 0 while the supplying plugin is switched off. */
    int (*views)(void *user, const sl_frame *f, int light, int map_size, sl_shadow_view *out, int max);
} sl_shadow_view_provider;
#define SL_SHADOW_MAX_VIEWS_PER_LIGHT 8

typedef struct sl_ext_shadow_maps {
    uint32_t struct_size;    /* sizeof(sl_ext_shadow_maps) as the provider knows it */
    void *ctx;               /* first argument of every function */
    /* Maps rendered for the current frame. */
    int (*count)(void *ctx);
    /* The i-th map (0 ≤ i < count); false when out of range. */
    bool (*get)(void *ctx, int i, sl_shadow_map *out);
    /* The map of light `light` (index into host->lights()) and face (0 unless a point light or
     * a directional light with provided views);
     * false when that light has no map this frame. */
    bool (*find)(void *ctx, int light, int face, sl_shadow_map *out);
    /* Changes whenever any map was re-rendered (cache derived data on it). */
    uint64_t (*version)(void *ctx);
    /* Revision 2 (check struct_size): installs the view provider (copied), or removes it with
     * NULL; false when another one is installed. */
    bool (*set_view_provider)(void *ctx, const sl_shadow_view_provider *provider);
} sl_ext_shadow_maps;

#ifdef __cplusplus
}
#endif
#endif
