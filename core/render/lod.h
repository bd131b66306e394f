/* Level of detail by projected size (core.lod_pixels): at upload, a mesh of many triangles gets
 * coarser index lists made by meshoptimizer's simplifier (meshopt_simplify, the same vertices),
 * each with its geometric error in object space (the simplifier's relative error times the mesh's
 * extent, meshopt_simplifyScale); at draw time the coarsest level whose error, projected onto the
 * target, stays within core.lod_pixels pixels is drawn. */
#ifndef SL_LOD_H
#define SL_LOD_H
#include "scene/scene.h"
#include <stdint.h>

#define SL_LOD_MAX 5            /* levels including the full mesh (level 0) */
#define SL_LOD_MIN_TRIANGLES 2048 /* smaller meshes keep one level */

typedef struct sl_lod_levels {
    int count;                  /* >= 1 */
    int first[SL_LOD_MAX];      /* first index of each level in the mesh's index buffer */
    int index_count[SL_LOD_MAX];
    float error[SL_LOD_MAX];    /* object-space distance, 0 for level 0, growing */
} sl_lod_levels;

/* The levels of m: level 0 is m's own index list; the others follow it. Returns the index buffer
 * to upload (m->indices and the coarser lists, *total indices), malloc'd, or NULL when m keeps one
 * level (upload m->indices then) or memory runs out. */
uint32_t *sl_lod_build(const sl_mesh_data *m, sl_lod_levels *out, int *total);

/* The level to draw: the coarsest whose error, at the distance of the bounds' nearest point to
 * the eye (an object of `radius` about `center_view`, view space) through `proj` onto a target
 * `height` pixels high, is at most `pixels`; `scale` turns object-space lengths into world ones.
 * 0 when pixels <= 0 (off) or the bounds reach the eye. */
int sl_lod_pick(const sl_lod_levels *l, const float proj[16], const float center_view[3], float radius, float scale,
                int height, float pixels);
#endif
