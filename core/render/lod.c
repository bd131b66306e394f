/* Level of detail by projected size (lod.h). */
#include "render/lod.h"
#include <math.h>
#include <meshoptimizer.h>
#include <stdlib.h>
#include <string.h>

/* Each level aims at a quarter of the previous one's triangles, within 5 % of the mesh's extent
 * of error (beyond that a mesh loses its shape: no projected size makes it worth drawing); one
 * that saves less than a third (the simplifier stopped at that error or at the topology's
 * limits) ends the chain. */
#define LOD_STEP 4
#define LOD_MAX_ERROR 0.05f

uint32_t *sl_lod_build(const sl_mesh_data *m, sl_lod_levels *out, int *total) {
    memset(out, 0, sizeof *out);
    out->count = 1, out->index_count[0] = m->index_count;
    *total = m->index_count;
    if (!m->positions || m->index_count / 3 < SL_LOD_MIN_TRIANGLES) return NULL;
    /* room for every level: each at most the previous one's size */
    size_t cap = (size_t)m->index_count * 3;
    uint32_t *all = malloc(cap * sizeof *all);
    if (!all) return NULL;
    memcpy(all, m->indices, (size_t)m->index_count * sizeof *all);
    float scale = meshopt_simplifyScale(m->positions, (size_t)m->vertex_count, 3 * sizeof(float));
    size_t used = (size_t)m->index_count, prev = used;
    while (out->count < SL_LOD_MAX) {
        const uint32_t *src = all + out->first[out->count - 1];
        size_t target = prev / LOD_STEP / 3 * 3;
        if (target < 3 || used + prev > cap) break;
        float err = 0;
        size_t n = meshopt_simplify(all + used, src, prev, m->positions, (size_t)m->vertex_count, 3 * sizeof(float),
                                    target, LOD_MAX_ERROR, 0, &err);
        if (n == 0 || n * 3 > prev * 2) break;
        int k = out->count++;
        out->first[k] = (int)used, out->index_count[k] = (int)n;
        /* errors add up along the chain (each level simplifies the one before) */
        out->error[k] = out->error[k - 1] + err * scale;
        used += n, prev = n;
    }
    if (out->count == 1) {
        free(all);
        return NULL;
    }
    *total = (int)used;
    return all;
}

int sl_lod_pick(const sl_lod_levels *l, const float proj[16], const float center_view[3], float radius, float scale,
                int height, float pixels) {
    if (!(pixels > 0) || l->count < 2 || height <= 0) return 0;
    bool ortho = proj[11] == 0; /* a perspective projection has -1 there (w = -z) */
    float px_per_unit = fabsf(proj[5]) * 0.5f * (float)height; /* at depth 1, or everywhere (ortho) */
    if (!ortho) {
        float depth = -center_view[2] - radius * scale; /* the bounds' nearest depth */
        if (!(depth > 1e-4f)) return 0;
        px_per_unit /= depth;
    }
    int pick = 0;
    for (int k = 1; k < l->count; k++)
        if (l->error[k] * scale * px_per_unit <= pixels) pick = k;
    return pick;
}
