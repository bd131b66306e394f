/* Composition of the forward material programs: for each material, the core template plus
 * exactly the plugin chunks that material uses (its shading model, surface hooks for the keys
 * it carries, the light types present in the scene, the active debug view). */
#ifndef SL_FORWARD_H
#define SL_FORWARD_H
#include <shadelab/shadelab.h>
#include "render/composer.h"
#include <shadelab/host.h>

struct sl_app;

/* The composer's limits. Each is an error naming what overflowed, never a silent drop. */
#define SL_MAX_HOOKS 64       /* VERTEX, SURFACE, AMBIENT, DISPLACEMENT or SCENE_BEHIND hooks of one kind per material */
#define SL_MAX_NODE_TAGS 31   /* node tags the VERTEX hooks of one material are gated on (bits of an int) */
#define SL_MAX_LIGHT_TYPES 32 /* distinct light types in a scene (checked when the scene is loaded) */

typedef struct sl_forward_variant {
    sl_program *program;
    uint64_t owners;            /* bit i: plugin i contributed chunks (bind callbacks, uniforms) */
    int texture_params[SL_TEXTURE_UNIT_MATERIAL_COUNT]; /* material texture keys on units 0.. (param indices) */
    int texture_count;
    bool texture_overflow_reported; /* a texture key beyond the material units was reported */
    char *chunks;               /* human-readable list of the chunks included (--explain) */
    /* VERTEX hooks with when_node_tag: bit k of the uniform sl_vertex_hook_mask runs node_tags[k]'s
     * hook; the draw sets the bits of the tags its node carries (sl_scene_node_has_tag) */
    const char *node_tags[SL_MAX_NODE_TAGS];
    int node_tag_count;
    int failed_plugin;          /* after a failed composition: the plugin to blame (>= 1), or -1 */
} sl_forward_variant;

typedef enum sl_variant_kind { SL_VARIANT_FORWARD, SL_VARIANT_DEPTH } sl_variant_kind;

/* Which program of a material to compose. */
typedef struct sl_variant_request {
    sl_variant_kind kind;
    const char *model_override; /* a shading model instead of the material's (draw_scene SL_DRAW_MATERIALS) */
    const char *fragment;       /* a plugin's main (SL_DRAW_MATERIALS `fragment`, ABI 1.7: a resolved path,
                                   included after forward.frag with SL_CUSTOM_MAIN defined), or NULL */
    bool fullscreen;            /* with fragment: the full-screen vertex stage (SL_FULLSCREEN_MATERIAL) */
} sl_variant_request;

/* The composed programs, shared by text: materials whose programs come out the same use one. */
typedef struct sl_program_cache { sl_program **items; int count; } sl_program_cache;

/* Builds the program source for material m (the core template plus exactly the chunks it uses)
 * and compiles it unless a program with the same text is in the cache. Returns false with the
 * message in err, logging nothing: the variant keeps its last program and out->failed_plugin
 * names the plugin to blame (or -1). */
bool sl_forward_compose(struct sl_app *app, int material, const sl_variant_request *request, sl_forward_variant *out,
                        sl_program_cache *cache, char *err, size_t n);
/* Light types present among the scene's enabled lights, in packing order. */
int sl_forward_light_types(struct sl_app *app, const char **types, int max);
/* Whether a light of the scene (enabled or not) of a type with an l/E pair casts shadows: the
 * forward programs then loop over the enabled casters apart (ranges sl_shadowed_<type>, first in
 * the light buffer), the only loop that calls the SHADOW hook. */
bool sl_forward_shadow_casters(struct sl_app *app);
/* A light type with an l/E pair (not SL_CHUNK_LIGHT_RADIANCE), from the loaded plugins. */
bool sl_forward_light_type_lit(struct sl_app *app, const char *type);
/* Whether material m's forward program gets a SCENE_BEHIND hook (ABI 1.17): the material is then
 * drawn by the core's forward-behind pass over the captured opaque scene, not by the forward pass. */
bool sl_forward_reads_scene_behind(struct sl_app *app, int m);
/* GLSL-safe identifier from a name ("spotlight-shadow" → "spotlight_shadow"). */
void sl_glsl_ident(const char *in, char *out, size_t n, bool upper);
#endif
