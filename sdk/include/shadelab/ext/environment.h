/* Extension "shadelab.environment/1": the scene's environment as a filtered cube map, for plugins
 * that look radiance up along arbitrary directions (refraction, clear coats, volumetrics) without
 * reaching into the provider's code. Provided by the envmap plugin (ABI 1.6).
 *
 *     #include <shadelab/ext/environment.h>
 *     const sl_ext_environment *env = host->get_extension(host, SL_EXT_ENVIRONMENT);
 *     sl_environment_cube c = {.struct_size = sizeof c};
 *     if (env && env->get(env->ctx, &c)) { bind c.texture, sample c.world_to_map · d … × c.scale }
 *
 * When: call get() on the main thread with the GL context current (a bind callback, a pass's
 * execute, begin_frame); the first call may build the cube (the provider saves and restores the
 * GL state it touches). NULL from get_extension: no provider loaded or it is disabled; get()
 * false: no environment yet.
 *
 * Radiance along a world direction d (unit, pointing away from the scene towards the sky):
 *     L(d) = scale · textureLod(texture, mat3(world_to_map) · d, lod).rgb
 * with lod 0 the sharpest; level m is the plain (solid-angle-weighted) 2^m-texel box average of
 * level 0, not a GGX prefilter. A lookup `angle` radians wide reads about
 * lod = log2(angle / (0.5π / size)). Faces follow OpenGL's cube convention (table 8.19).
 * The texture is GL_TEXTURE_CUBE_MAP, RGBA16F, trilinear; do not modify it.
 */
#ifndef SHADELAB_EXT_ENVIRONMENT_H
#define SHADELAB_EXT_ENVIRONMENT_H
#include "../shadelab.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SL_EXT_ENVIRONMENT "shadelab.environment/1"

/* Fields are only ever appended; set struct_size to sizeof(sl_environment_cube) before calling. */
typedef struct sl_environment_cube {
    uint32_t struct_size;
    unsigned texture;        /* GL name of the cube map */
    int size;                /* face size of level 0, texels */
    int levels;              /* mip levels (level count − 1 is the coarsest) */
    float world_to_map[9];   /* column-major 3×3: world direction → cube lookup direction (the yaw) */
    float scale;             /* multiplies every lookup (the scene environment's intensity) */
    uint64_t version;        /* changes whenever the texture's contents change */
} sl_environment_cube;

typedef struct sl_ext_environment {
    uint32_t struct_size;    /* sizeof(sl_ext_environment) as the provider knows it */
    void *ctx;               /* first argument of every function */
    /* The current environment; false when there is none yet. */
    bool (*get)(void *ctx, sl_environment_cube *out);
} sl_ext_environment;

#ifdef __cplusplus
}
#endif
#endif
