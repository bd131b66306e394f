/* Per-vertex tangent frames from positions, normals and UVs.
 *
 * Method: Lengyel, "Computing Tangent Space Basis Vectors for an Arbitrary Mesh" (2001). For
 * each triangle the UV derivatives dP/du and dP/dv solve
 *     e1 = du1·T + dv1·B,   e2 = du2·T + dv2·B
 * (e1, e2 the edge vectors, du/dv the UV deltas). Every triangle adds its normalised dP/du and
 * its "image up" direction −dP/dv, weighted by its area, to its three vertices; each vertex then
 * Gram-Schmidts the sum against its normal, and w is the sign of the accumulated image-up
 * direction relative to cross(n, t). The minus sign: v = 0 is the top row of the image (see
 * scene.h), so a normal map's green channel points toward decreasing v.
 *
 * Robustness: triangles with zero area or a degenerate UV mapping (all three UVs on a line,
 * NaN) contribute nothing; a vertex left with no usable tangent gets an arbitrary unit vector
 * orthogonal to its normal and w = +1, so the result is always finite. */
#include "scene/scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static float dot3(const float *a, const float *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void cross3(const float *a, const float *b, float *out) {
    float x = a[1] * b[2] - a[2] * b[1];
    float y = a[2] * b[0] - a[0] * b[2];
    float z = a[0] * b[1] - a[1] * b[0];
    out[0] = x, out[1] = y, out[2] = z;
}

static bool finite3(const float *v) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

/* Normalises v in place; false (v untouched) when it is too short or not finite. */
static bool normalize3(float *v) {
    if (!finite3(v)) return false;
    double len = sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
    if (!(len > 1e-20) || !isfinite(len)) return false;
    v[0] = (float)(v[0] / len), v[1] = (float)(v[1] / len), v[2] = (float)(v[2] / len);
    return true;
}

/* A unit vector orthogonal to the unit vector n (the axis least aligned with n, projected). */
static void any_orthogonal(const float *n, float *t) {
    float axis[3] = {0, 0, 0};
    if (fabsf(n[0]) < 0.9f) axis[0] = 1;
    else axis[1] = 1;
    float d = dot3(axis, n);
    for (int c = 0; c < 3; c++) t[c] = axis[c] - d * n[c];
    if (!normalize3(t)) t[0] = 1, t[1] = 0, t[2] = 0;
}

static bool triangle_ok(const sl_mesh_data *m, int t) {
    const uint32_t *idx = m->indices + 3 * t;
    return idx[0] < (uint32_t)m->vertex_count && idx[1] < (uint32_t)m->vertex_count &&
           idx[2] < (uint32_t)m->vertex_count;
}

/* Fixes bad normals from the area-weighted normals of the triangles using them. */
static int repair_normals(sl_mesh_data *m) {
    int bad = 0;
    char *is_bad = calloc((size_t)(m->vertex_count > 0 ? m->vertex_count : 1), 1);
    if (!is_bad) return 0;
    for (int i = 0; i < m->vertex_count; i++) {
        float *n = m->normals + 3 * i;
        if (!normalize3(n)) {
            is_bad[i] = 1;
            n[0] = n[1] = n[2] = 0;
            bad++;
        }
    }
    if (bad) {
        for (int t = 0; t < m->index_count / 3; t++) {
            if (!triangle_ok(m, t)) continue;
            const uint32_t *idx = m->indices + 3 * t;
            if (!is_bad[idx[0]] && !is_bad[idx[1]] && !is_bad[idx[2]]) continue;
            const float *p0 = m->positions + 3 * idx[0], *p1 = m->positions + 3 * idx[1],
                        *p2 = m->positions + 3 * idx[2];
            float e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
            float e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
            float fn[3];
            cross3(e1, e2, fn); /* length = 2·area: area weighting for free */
            if (!finite3(fn)) continue;
            for (int k = 0; k < 3; k++)
                if (is_bad[idx[k]])
                    for (int c = 0; c < 3; c++) m->normals[3 * idx[k] + c] += fn[c];
        }
        for (int i = 0; i < m->vertex_count; i++) {
            if (!is_bad[i]) continue;
            float *n = m->normals + 3 * i;
            if (!normalize3(n)) n[0] = 0, n[1] = 1, n[2] = 0;
        }
    }
    free(is_bad);
    return bad;
}

int sl_mesh_repair_frames(sl_mesh_data *m) {
    if (!m || m->vertex_count <= 0 || !m->normals || !m->tangents) return 0;
    int repaired = repair_normals(m);
    for (int i = 0; i < m->vertex_count; i++) {
        const float *n = m->normals + 3 * i;
        float *t = m->tangents + 4 * i;
        bool fixed = false;
        if (finite3(t)) {
            float d = dot3(t, n);
            for (int c = 0; c < 3; c++) t[c] -= d * n[c];
        }
        if (!normalize3(t)) {
            any_orthogonal(n, t);
            fixed = true;
        }
        if (t[3] != 1.0f && t[3] != -1.0f) {
            t[3] = t[3] < 0.0f ? -1.0f : 1.0f; /* NaN compares false: +1 */
            fixed = true;
        }
        repaired += fixed;
    }
    return repaired;
}

void sl_mesh_generate_tangents(sl_mesh_data *m) {
    if (!m || m->vertex_count <= 0 || !m->tangents || !m->normals || !m->positions) return;
    repair_normals(m);
    size_t n = (size_t)m->vertex_count;
    float *tan_u = calloc(n * 3, sizeof(float));  /* Σ area · normalize(dP/du) */
    float *tan_up = calloc(n * 3, sizeof(float)); /* Σ area · normalize(−dP/dv) */
    if (!tan_u || !tan_up) {
        free(tan_u);
        free(tan_up);
        memset(m->tangents, 0, n * 4 * sizeof(float));
        sl_mesh_repair_frames(m);
        return;
    }
    if (m->uvs) {
        for (int t = 0; t < m->index_count / 3; t++) {
            if (!triangle_ok(m, t)) continue;
            const uint32_t *idx = m->indices + 3 * t;
            const float *p0 = m->positions + 3 * idx[0], *p1 = m->positions + 3 * idx[1],
                        *p2 = m->positions + 3 * idx[2];
            const float *w0 = m->uvs + 2 * idx[0], *w1 = m->uvs + 2 * idx[1], *w2 = m->uvs + 2 * idx[2];
            float e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
            float e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
            float du1 = w1[0] - w0[0], dv1 = w1[1] - w0[1];
            float du2 = w2[0] - w0[0], dv2 = w2[1] - w0[1];
            float fn[3];
            cross3(e1, e2, fn);
            float area = 0.5f * sqrtf(dot3(fn, fn));
            float r = du1 * dv2 - du2 * dv1;
            if (!(area > 0.0f) || !isfinite(area) || !isfinite(r) || r == 0.0f) continue;
            /* Scale-free test for a degenerate UV triangle: |r| relative to the UV edges. */
            float uv_scale = fabsf(du1) + fabsf(dv1) + fabsf(du2) + fabsf(dv2);
            if (fabsf(r) < 1e-7f * uv_scale * uv_scale) continue;
            float s_dir[3], t_dir[3];
            for (int c = 0; c < 3; c++) {
                s_dir[c] = (e1[c] * dv2 - e2[c] * dv1) / r;     /* dP/du */
                t_dir[c] = -((e2[c] * du1 - e1[c] * du2) / r);  /* −dP/dv: image up */
            }
            if (!normalize3(s_dir) || !normalize3(t_dir)) continue;
            for (int k = 0; k < 3; k++)
                for (int c = 0; c < 3; c++) {
                    tan_u[3 * idx[k] + c] += area * s_dir[c];
                    tan_up[3 * idx[k] + c] += area * t_dir[c];
                }
        }
    }
    for (size_t i = 0; i < n; i++) {
        const float *nrm = m->normals + 3 * i;
        float *out = m->tangents + 4 * i;
        float t[3] = {tan_u[3 * i], tan_u[3 * i + 1], tan_u[3 * i + 2]};
        float d = dot3(t, nrm);
        for (int c = 0; c < 3; c++) t[c] -= d * nrm[c];
        float w = 1.0f;
        if (normalize3(t)) {
            float b[3];
            cross3(nrm, t, b);
            w = dot3(b, tan_up + 3 * i) < 0.0f ? -1.0f : 1.0f;
        } else {
            any_orthogonal(nrm, t);
        }
        out[0] = t[0], out[1] = t[1], out[2] = t[2], out[3] = w;
    }
    free(tan_u);
    free(tan_up);
}
