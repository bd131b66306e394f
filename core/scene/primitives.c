/* Procedural primitives: sphere, plane, cube, torus (the teapot is in teapot.c).
 *
 * Every primitive has positions, unit normals, UVs, tangents (xyz + w) and counter-clockwise
 * front faces, and its UVs follow the conventions of scene.h (v = 0 at the top of the image,
 * unmirrored: w = +1 everywhere). All are centred on the origin except where noted. */
#include "scene/scene.h"

#include <math.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static void set3(float *dst, float x, float y, float z) { dst[0] = x, dst[1] = y, dst[2] = z; }

/* UV sphere in the lat-long parametrisation of a globe, read from outside:
 *   d(θ, φ) = (sin θ sin φ, cos θ, sin θ cos φ),  θ ∈ [0, π] from +Y,  φ = atan2(x, z) ∈ [0, 2π)
 *   u = φ / 2π,  v = θ / π
 * so u = 0 faces +Z, u = 0.25 faces +X, v = 0 is the north pole (+Y): an image on it reads
 * unmirrored from outside. Environment maps are read from inside, in Blender's orientation
 * (u = atan2(z, x)/2π + ½, u = ½ facing +X; sdk/docs/conventions.md): the sphere's u at
 * direction d is ¾ − the environment's u there (wrapped). The seam (u = 0 and
 * u = 1) and the poles have one vertex per column, so UVs and tangents are exact there too.
 * Tangent: ∂d/∂φ normalised = (cos φ, 0, −sin φ); w = +1. */
bool sl_mesh_sphere(sl_mesh_data *m, float radius, int segments, int rings) {
    memset(m, 0, sizeof *m);
    if (!(radius > 0.0f) || !isfinite(radius) || segments < 3 || rings < 2 || segments > 8192 ||
        rings > 8192)
        return false;
    int cols = segments + 1, rows = rings + 1;
    /* pole rows have one triangle per quad */
    long tris = 2L * segments * (rings - 1);
    if ((long)cols * rows > (1L << 26) || tris * 3 > (1L << 28)) return false;
    if (!sl_mesh_alloc(m, cols * rows, (int)(tris * 3))) return false;
    for (int r = 0; r < rows; r++) {
        double v = (double)r / rings, theta = M_PI * v;
        double st = sin(theta), ct = cos(theta);
        if (r == 0) st = 0, ct = 1;
        if (r == rings) st = 0, ct = -1;
        for (int k = 0; k < cols; k++) {
            double u = (double)k / segments, phi = 2.0 * M_PI * u;
            double sp = sin(phi), cp = cos(phi);
            if (k == segments) sp = 0, cp = 1; /* seam column identical to the first */
            int i = r * cols + k;
            float d[3] = {(float)(st * sp), (float)ct, (float)(st * cp)};
            set3(m->normals + 3 * i, d[0], d[1], d[2]);
            set3(m->positions + 3 * i, radius * d[0], radius * d[1], radius * d[2]);
            m->uvs[2 * i] = (float)u;
            m->uvs[2 * i + 1] = (float)v;
            set3(m->tangents + 4 * i, (float)cp, 0.0f, (float)-sp);
            m->tangents[4 * i + 3] = 1.0f;
        }
    }
    uint32_t *ix = m->indices;
    for (int r = 0; r < rings; r++)
        for (int k = 0; k < segments; k++) {
            uint32_t a = (uint32_t)(r * cols + k), b = a + (uint32_t)cols, c = a + 1, d = b + 1;
            /* b is below a (v grows), c is to the right (u grows): (a, b, c) is CCW outside. */
            if (r != 0) ix[0] = a, ix[1] = b, ix[2] = c, ix += 3;
            if (r != rings - 1) ix[0] = c, ix[1] = b, ix[2] = d, ix += 3;
        }
    sl_mesh_compute_bounds(m);
    return true;
}

/* Plane in XZ facing +Y, centred, size_x × size_z, subdivisions² quads. u grows with +X and v
 * with +Z, so seen from above with −Z "up" (the default camera's view) an image is upright.
 * UVs span 0..1 once (a material tiles with its own key). Tangent +X, w = +1. */
bool sl_mesh_plane(sl_mesh_data *m, float size_x, float size_z, int subdivisions) {
    memset(m, 0, sizeof *m);
    if (!(size_x > 0.0f) || !(size_z > 0.0f) || !isfinite(size_x) || !isfinite(size_z) ||
        subdivisions < 1 || subdivisions > 4096)
        return false;
    int n = subdivisions, cols = n + 1;
    if (!sl_mesh_alloc(m, cols * cols, 6 * n * n)) return false;
    for (int j = 0; j < cols; j++)
        for (int i = 0; i < cols; i++) {
            int k = j * cols + i;
            float u = (float)i / n, v = (float)j / n;
            set3(m->positions + 3 * k, (u - 0.5f) * size_x, 0.0f, (v - 0.5f) * size_z);
            set3(m->normals + 3 * k, 0, 1, 0);
            m->uvs[2 * k] = u;
            m->uvs[2 * k + 1] = v;
            set3(m->tangents + 4 * k, 1, 0, 0);
            m->tangents[4 * k + 3] = 1.0f;
        }
    uint32_t *ix = m->indices;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            uint32_t a = (uint32_t)(j * cols + i), b = a + 1, c = a + (uint32_t)cols, d = c + 1;
            /* a→c is +Z, a→b is +X: (a, c, b) has normal Z × X = +Y */
            ix[0] = a, ix[1] = c, ix[2] = b;
            ix[3] = b, ix[4] = c, ix[5] = d;
            ix += 6;
        }
    sl_mesh_compute_bounds(m);
    return true;
}

/* Cube of edge `size`, centred; 24 vertices (4 per face, flat normals), 12 triangles. Each face
 * carries the whole 0..1 UV square, upright when seen from outside: side faces have the image
 * top toward +Y, the top face toward −Z (like the plane), the bottom face toward +Z. */
bool sl_mesh_cube(sl_mesh_data *m, float size) {
    memset(m, 0, sizeof *m);
    if (!(size > 0.0f) || !isfinite(size)) return false;
    if (!sl_mesh_alloc(m, 24, 36)) return false;
    /* normal, direction of +u; image up = cross(normal, u) */
    static const float faces[6][2][3] = {
        {{1, 0, 0}, {0, 0, -1}}, {{-1, 0, 0}, {0, 0, 1}}, {{0, 1, 0}, {1, 0, 0}},
        {{0, -1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 0}},  {{0, 0, -1}, {-1, 0, 0}},
    };
    float h = 0.5f * size;
    for (int f = 0; f < 6; f++) {
        const float *n = faces[f][0], *u = faces[f][1];
        float up[3] = {n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
        for (int k = 0; k < 4; k++) {
            int vi = 4 * f + k;
            float tu = (float)(k & 1), tv = (float)(k >> 1); /* 0:(0,0) top-left 1:(1,0) 2:(0,1) 3:(1,1) */
            for (int c = 0; c < 3; c++)
                m->positions[3 * vi + c] = h * (n[c] + (2 * tu - 1) * u[c] + (1 - 2 * tv) * up[c]);
            set3(m->normals + 3 * vi, n[0], n[1], n[2]);
            set3(m->tangents + 4 * vi, u[0], u[1], u[2]);
            m->tangents[4 * vi + 3] = 1.0f;
            m->uvs[2 * vi] = tu;
            m->uvs[2 * vi + 1] = tv;
        }
        /* bottom-left(2) → bottom-right(3) → top-right(1), then 2 → 1 → top-left(0): CCW */
        uint32_t b = (uint32_t)(4 * f), *ix = m->indices + 6 * f;
        ix[0] = b + 2, ix[1] = b + 3, ix[2] = b + 1;
        ix[3] = b + 2, ix[4] = b + 1, ix[5] = b + 0;
    }
    sl_mesh_compute_bounds(m);
    return true;
}

/* Torus around the Y axis: the tube's centre circle has radius major_radius in the XZ plane,
 * the tube radius minor_radius. u = φ/2π around Y (same φ as the sphere: u = 0 at +Z, growing
 * toward +X), v = ψ/2π around the tube starting on the outer equator and going DOWN on the
 * outside (so an image is upright seen from outside). Tangent (cos φ, 0, −sin φ), w = +1. */
bool sl_mesh_torus(sl_mesh_data *m, float major_radius, float minor_radius, int segments, int sides) {
    memset(m, 0, sizeof *m);
    if (!(major_radius > 0.0f) || !(minor_radius > 0.0f) || !isfinite(major_radius) ||
        !isfinite(minor_radius) || segments < 3 || sides < 3 || segments > 8192 || sides > 8192)
        return false;
    int cols = segments + 1, rows = sides + 1;
    long tris = 2L * segments * sides;
    if ((long)cols * rows > (1L << 26) || tris * 3 > (1L << 28)) return false;
    if (!sl_mesh_alloc(m, cols * rows, (int)(tris * 3))) return false;
    for (int i = 0; i < cols; i++) {
        double u = (double)i / segments, phi = 2.0 * M_PI * u;
        double sp = sin(phi), cp = cos(phi);
        if (i == segments) sp = 0, cp = 1;
        for (int j = 0; j < rows; j++) {
            double v = (double)j / sides, psi = 2.0 * M_PI * v;
            double spsi = sin(psi), cpsi = cos(psi);
            if (j == sides) spsi = 0, cpsi = 1;
            int k = i * rows + j;
            /* n = cos ψ · e − sin ψ · Y, e = (sin φ, 0, cos φ) the outward radial direction */
            float n[3] = {(float)(cpsi * sp), (float)-spsi, (float)(cpsi * cp)};
            set3(m->normals + 3 * k, n[0], n[1], n[2]);
            set3(m->positions + 3 * k, (float)(major_radius * sp) + minor_radius * n[0],
                 minor_radius * n[1], (float)(major_radius * cp) + minor_radius * n[2]);
            m->uvs[2 * k] = (float)u;
            m->uvs[2 * k + 1] = (float)v;
            set3(m->tangents + 4 * k, (float)cp, 0.0f, (float)-sp);
            m->tangents[4 * k + 3] = 1.0f;
        }
    }
    uint32_t *ix = m->indices;
    for (int i = 0; i < segments; i++)
        for (int j = 0; j < sides; j++) {
            uint32_t a = (uint32_t)(i * rows + j), b = a + 1, c = a + (uint32_t)rows, d = c + 1;
            /* b: v grows (down outside), c: u grows (toward +X at the front): (a, b, c) CCW */
            ix[0] = a, ix[1] = b, ix[2] = c;
            ix[3] = c, ix[4] = b, ix[5] = d;
            ix += 6;
        }
    sl_mesh_compute_bounds(m);
    return true;
}
