/* normal-map offline tools: procedural maps, the tangent → object-space bake and the green
 * convention detector. See nm_tools.h for the contracts and the image convention. */
#include "nm_tools.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static bool alloc_image(sl_image *img, int w, int h) {
    memset(img, 0, sizeof *img);
    if (w < 1 || h < 1 || w > SL_IMAGE_MAX_DIM || h > SL_IMAGE_MAX_DIM) return false;
    img->pixels = calloc((size_t)w * h * 4, sizeof(float));
    if (!img->pixels) return false;
    img->width = w, img->height = h, img->channels = 4, img->source_bits = 32;
    return true;
}

/* ---- procedural maps ------------------------------------------------------------------- */

float nm_bumps_height(float X, float Y, int n, float amplitude) {
    return amplitude / (2.0f * (float)M_PI * n) * sinf(2.0f * (float)M_PI * n * X) * sinf(2.0f * (float)M_PI * n * Y);
}

/* The core's procedural normal maps (flat, tilt, bumps, waves: one parser and one generator,
 * also what a scene's "normal_map": "bumps:16:0.8" gets). */
bool nm_generate_tangent_map(sl_image *out, const char *spec, int size, char *err, size_t n) {
    static const char *const kinds[] = {"flat", "tilt:", "bumps:", "waves:", NULL};
    bool normal_kind = false;
    for (const char *const *k = kinds; *k && !normal_kind; k++)
        normal_kind = (*k)[strlen(*k) - 1] == ':' ? !strncmp(spec, *k, strlen(*k)) : !strcmp(spec, *k);
    memset(out, 0, sizeof *out);
    if (!normal_kind) {
        snprintf(err, n, "normal map '%s': expected flat, tilt:X,Y, bumps:N:A or waves:N:A:SEED", spec);
        return false;
    }
    return sl_image_procedural(out, spec, size, err, n);
}

bool nm_generate_property_map(sl_image *out, const char *spec, int size, char *err, size_t n) {
    int N = 0;
    float a = 0, g = 0, ao = 0;
    char tail;
    bool constant = sscanf(spec, "constant:%f,%f%c", &g, &ao, &tail) == 2;
    bool pattern = !constant && sscanf(spec, "property:%d:%f%c", &N, &a, &tail) == 2 && N >= 1 && N <= 4096;
    memset(out, 0, sizeof *out);
    if (!constant && !pattern) {
        snprintf(err, n, "property map '%s': expected property:N:A or constant:GLOSS,AO", spec);
        return false;
    }
    if (!alloc_image(out, size, size)) {
        snprintf(err, n, "property map '%s': size %d outside 1..%d", spec, size, SL_IMAGE_MAX_DIM);
        return false;
    }
    for (int row = 0; row < size; row++)
        for (int col = 0; col < size; col++) {
            float X = (col + 0.5f) / size, Y = 1.0f - (row + 0.5f) / size, gloss = g, occl = ao;
            if (pattern) {
                gloss = (((int)(X * 4) + (int)(Y * 4)) & 1) ? 0.35f : 0.85f;
                /* sin·sin ∈ [−1, 1] → AO 0.45 in the hollows, 1 on the crests */
                float s = sinf(2.0f * (float)M_PI * N * X) * sinf(2.0f * (float)M_PI * N * Y);
                occl = 0.725f + 0.275f * s;
            }
            float *p = out->pixels + ((size_t)row * size + col) * 4;
            p[0] = gloss, p[1] = 0, p[2] = occl, p[3] = 1;
        }
    return true;
}

/* ---- sampling ------------------------------------------------------------------------- */

static int wrap(int i, int n) { int r = i % n; return r < 0 ? r + n : r; }

void nm_sample_bilinear(const sl_image *img, float u, float v, float out[4]) {
    /* continuous texel coordinates with texel centres at integers; row 0 at the top (v = 0) */
    float x = u * img->width - 0.5f, y = v * img->height - 0.5f;
    int x0 = (int)floorf(x), y0 = (int)floorf(y);
    float fx = x - x0, fy = y - y0;
    for (int c = 0; c < 4; c++) out[c] = 0;
    for (int k = 0; k < 4; k++) {
        int xi = wrap(x0 + (k & 1), img->width), yi = wrap(y0 + (k >> 1), img->height);
        float w = ((k & 1) ? fx : 1 - fx) * ((k >> 1) ? fy : 1 - fy);
        const float *p = img->pixels + ((size_t)yi * img->width + xi) * 4;
        for (int c = 0; c < 4; c++) out[c] += w * p[c];
    }
}

/* ---- the bake --------------------------------------------------------------------------- */

static float dot3(const float *a, const float *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const float *a, const float *b, float *o) {
    float x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
    o[0] = x, o[1] = y, o[2] = z;
}
static bool normalize3(float *v) {
    float l = sqrtf(dot3(v, v));
    if (!(l > 1e-20f) || !isfinite(l)) return false;
    v[0] /= l, v[1] /= l, v[2] /= l;
    return true;
}

/* The object-space normal at barycentrics b of triangle idx, exactly as the shader builds it
 * (shaders/forward.frag, then nm_surface): interpolated normal and tangent, tangent
 * Gram-Schmidt against the normal, bitangent w·cross(n, t), image up = sign·bitangent. */
static void mapped_normal(const sl_mesh_data *m, const uint32_t *idx, const float b[3], const float geo_n[3],
                          const float texel[3], const nm_bake_opts *o, float out[3]) {
    float n[3] = {0, 0, 0}, t[3] = {0, 0, 0}, w = 0;
    for (int k = 0; k < 3; k++) {
        const float *vn = m->normals + 3 * idx[k], *vt = m->tangents + 4 * idx[k];
        for (int c = 0; c < 3; c++) n[c] += b[k] * vn[c], t[c] += b[k] * vt[c];
        w += b[k] * vt[3];
    }
    if (!normalize3(n)) memcpy(n, geo_n, sizeof n);
    float d = dot3(n, t);
    for (int c = 0; c < 3; c++) t[c] -= n[c] * d;
    if (!normalize3(t)) {
        float axis[3] = {0, 0, 0};
        if (fabsf(n[1]) < 0.999f) axis[1] = 1; else axis[0] = 1;
        cross3(axis, n, t);
        normalize3(t);
    }
    float bt[3];
    cross3(n, t, bt);
    float up = NM_IMAGE_UP_SIGN * (w < 0 ? -1.0f : 1.0f);
    /* tangent-space vector: decode, green convention, strength (nm_tangent_scaled) */
    float x = texel[0] * 2 - 1, y = (texel[1] * 2 - 1) * (float)o->green_sign, z = texel[2] * 2 - 1;
    float sx = x * o->strength, sy = y * o->strength, sz = z > 0 ? z : 0;
    float l2 = sx * sx + sy * sy + sz * sz;
    if (l2 > 1e-12f) { float il = 1.0f / sqrtf(l2); sx *= il, sy *= il, sz *= il; }
    else sx = 0, sy = 0, sz = 1;
    for (int c = 0; c < 3; c++) out[c] = sx * t[c] + sy * up * bt[c] + sz * n[c];
    if (!normalize3(out)) memcpy(out, n, 3 * sizeof(float));
}

static float edge(const float *a, const float *b, float px, float py) {
    return (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]);
}

long nm_bake_object_space(const sl_mesh_data *const *meshes, int mesh_count, const sl_image *tmap,
                          const nm_bake_opts *opts, int W, int H, sl_image *out, char *err, size_t n) {
    nm_bake_opts o = opts ? *opts : (nm_bake_opts){.green_sign = 1, .strength = 1, .dilate = 8};
    if (o.green_sign == 0) o.green_sign = 1;
    if (!alloc_image(out, W, H)) {
        snprintf(err, n, "bake: output size %dx%d outside 1..%d (or out of memory)", W, H, SL_IMAGE_MAX_DIM);
        return -1;
    }
    float *acc = out->pixels;
    unsigned char *mask = calloc((size_t)W * H, 1);
    if (!mask) { snprintf(err, n, "bake: out of memory"); sl_image_free(out); return -1; }
    long covered = 0;
    for (int mi = 0; mi < mesh_count; mi++) {
        const sl_mesh_data *m = meshes[mi];
        if (!m->uvs || !m->tangents || !m->normals) {
            snprintf(err, n, "bake: mesh %d has no UVs/tangents/normals", mi);
            free(mask);
            sl_image_free(out);
            return -1;
        }
        for (int tri = 0; tri < m->index_count / 3; tri++) {
            const uint32_t *idx = m->indices + 3 * tri;
            if (idx[0] >= (uint32_t)m->vertex_count || idx[1] >= (uint32_t)m->vertex_count ||
                idx[2] >= (uint32_t)m->vertex_count)
                continue;
            float p[3][2], geo[3];
            for (int k = 0; k < 3; k++) {
                const float *uv = m->uvs + 2 * idx[k];
                p[k][0] = uv[0] * W - 0.5f;            /* texel centres at integers */
                p[k][1] = uv[1] * H - 0.5f;            /* row 0 = top = v near 0 */
            }
            const float *a = m->positions + 3 * idx[0], *b = m->positions + 3 * idx[1], *c = m->positions + 3 * idx[2];
            float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            cross3(e1, e2, geo);
            if (!normalize3(geo)) geo[0] = 0, geo[1] = 1, geo[2] = 0;
            float area = edge(p[0], p[1], p[2][0], p[2][1]);
            if (!(fabsf(area) > 1e-9f) || !isfinite(area)) continue; /* zero-area UV triangle */
            float minx = fminf(p[0][0], fminf(p[1][0], p[2][0])), maxx = fmaxf(p[0][0], fmaxf(p[1][0], p[2][0]));
            float miny = fminf(p[0][1], fminf(p[1][1], p[2][1])), maxy = fmaxf(p[0][1], fmaxf(p[1][1], p[2][1]));
            if (maxx - minx > 4.0f * W || maxy - miny > 4.0f * H) continue; /* absurd UVs */
            float tol = 1e-5f * fabsf(area);
            for (int py = (int)ceilf(miny); py <= (int)floorf(maxy); py++)
                for (int px = (int)ceilf(minx); px <= (int)floorf(maxx); px++) {
                    float w0 = edge(p[1], p[2], (float)px, (float)py) / area;
                    float w1 = edge(p[2], p[0], (float)px, (float)py) / area;
                    float w2 = 1.0f - w0 - w1;
                    if (w0 * fabsf(area) < -tol || w1 * fabsf(area) < -tol || w2 * fabsf(area) < -tol) continue;
                    float bary[3] = {w0, w1, w2}, texel[4], nrm[3];
                    /* sample the tangent map where the renderer would: at this texel's uv */
                    float u = (px + 0.5f) / W, v = (py + 0.5f) / H;
                    nm_sample_bilinear(tmap, u, v, texel);
                    mapped_normal(m, idx, bary, geo, texel, &o, nrm);
                    size_t at = (size_t)wrap(py, H) * W + wrap(px, W);
                    if (!mask[at]) covered++;
                    mask[at] = 1;
                    for (int k = 0; k < 3; k++) acc[at * 4 + k] = nrm[k];
                    acc[at * 4 + 3] = 1;
                }
        }
    }
    /* dilation: grow islands by averaging covered neighbours, so bilinear and mip filtering at
     * island borders do not pull in undefined texels */
    unsigned char *next = malloc((size_t)W * H);
    for (int it = 0; it < o.dilate && next; it++) {
        memcpy(next, mask, (size_t)W * H);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                if (mask[(size_t)y * W + x]) continue;
                float s[3] = {0, 0, 0};
                int cnt = 0;
                for (int dy = -1; dy <= 1; dy++)
                    for (int dx = -1; dx <= 1; dx++) {
                        int xx = x + dx, yy = y + dy;
                        if (xx < 0 || yy < 0 || xx >= W || yy >= H || !mask[(size_t)yy * W + xx]) continue;
                        for (int k = 0; k < 3; k++) s[k] += acc[((size_t)yy * W + xx) * 4 + k];
                        cnt++;
                    }
                if (!cnt || !normalize3(s)) continue;
                memcpy(acc + ((size_t)y * W + x) * 4, s, sizeof s);
                next[(size_t)y * W + x] = 1;
            }
        memcpy(mask, next, (size_t)W * H);
    }
    free(next);
    for (size_t i = 0; i < (size_t)W * H; i++) {
        float *q = acc + i * 4;
        if (!mask[i]) q[0] = q[1] = q[2] = 0;
        for (int k = 0; k < 3; k++) q[k] = q[k] * 0.5f + 0.5f;
        q[3] = 1;
    }
    free(mask);
    return covered;
}

/* ---- green convention ------------------------------------------------------------------- */

int nm_detect_green(const sl_image *img, double *curl_plus, double *curl_minus) {
    int W = img->width, H = img->height;
    double c[2] = {0, 0};
    long cnt = 0;
#define NV(x, r, ch) (2.0 * img->pixels[((size_t)(r) * W + (x)) * 4 + (ch)] - 1.0)
#define SX(x, r) (-NV(x, r, 0) / fmax(NV(x, r, 2), 0.2))             /* ∂h/∂X */
#define SY(x, r, s) (-(s) * NV(x, r, 1) / fmax(NV(x, r, 2), 0.2))    /* ∂h/∂Y, Y = image up */
    for (int r = 1; r < H - 1; r++)
        for (int x = 1; x < W - 1; x++) {
            for (int k = 0; k < 2; k++) {
                double s = k == 0 ? 1 : -1;
                double dsx_dY = -(SX(x, r + 1) - SX(x, r - 1)) / 2; /* Y grows toward row 0 */
                double dsy_dX = (SY(x + 1, r, s) - SY(x - 1, r, s)) / 2;
                c[k] += fabs(dsx_dY - dsy_dX);
            }
            cnt++;
        }
#undef NV
#undef SX
#undef SY
    if (cnt) c[0] /= cnt, c[1] /= cnt;
    if (curl_plus) *curl_plus = c[0];
    if (curl_minus) *curl_minus = c[1];
    return c[0] <= c[1] ? 1 : -1;
}
