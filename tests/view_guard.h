/* The view guard of perturbed normals (shaders/normal_guard.glsl), derived again in double for the
 * tests that state a mapped normal's shading per pixel. */
#ifndef SHADELAB_TEST_VIEW_GUARD_H
#define SHADELAB_TEST_VIEW_GUARD_H
#include <math.h>

static inline double vg_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void vg_normalize(double v[3]) {
    double l = sqrt(vg_dot(v, v));
    for (int i = 0; i < 3; i++) v[i] /= l;
}

/* sl_face_viewer (shaders/normal_guard.glsl), in double. */
static inline void vg_face_viewer(double n[3], const float vf[3]) {
    const double eps = 0.02;
    double v[3] = {vf[0], vf[1], vf[2]};
    double d = vg_dot(n, v);
    if (d >= eps) return;
    for (int i = 0; i < 3; i++) n[i] += (eps - d) * v[i];
    vg_normalize(n);
}

/* sl_valid_reflection (shaders/normal_guard.glsl), in double, derived again here:
 * n' = a·x + b·g (x: n's direction in the surface plane, a, b ≥ 0) whose mirror direction of v
 * rises t = min(0.9·(v·g), 0.01) above the surface: 2b(a·vx + b·vz) − vz = t, a quadratic in
 * b² after squaring, solved directly; of its two roots, the one that solves the equation before
 * squaring. A normal below the surface is bent too (its azimuth kept), whatever its reflection. */
static inline void vg_valid_reflection(double n[3], const double v[3], const double g[3]) {
    double vz = vg_dot(v, g), t = fmin(0.9 * vz, 0.01), nv = vg_dot(n, v), r[3], x[3];
    for (int i = 0; i < 3; i++) r[i] = 2 * nv * n[i] - v[i];
    if (vz <= 0 || (vg_dot(n, g) >= 0 && vg_dot(r, g) >= t)) return;
    for (int i = 0; i < 3; i++) x[i] = n[i] - vg_dot(n, g) * g[i];
    if (vg_dot(x, x) < 1e-12) { /* n = −g */
        for (int i = 0; i < 3; i++) n[i] = g[i];
        return;
    }
    vg_normalize(x);
    double vx = vg_dot(v, x), p2 = vx * vx + vz * vz, best = 1e30, out[3];
    for (int k = -1; k <= 1; k += 2) {
        double u = (vx * vx + vz * (t + vz) + k * fabs(vx) * sqrt(p2 - t * t)) / (2 * p2); /* b² */
        double b = sqrt(fmin(fmax(u, 0), 1)), a = sqrt(1 - b * b);
        double err = fabs(2 * a * b * vx + 2 * b * b * vz - vz - t);
        if (err >= best) continue;
        best = err;
        for (int i = 0; i < 3; i++) out[i] = a * x[i] + b * g[i];
    }
    for (int i = 0; i < 3; i++) n[i] = out[i];
    vg_normalize(n);
}

/* sl_view_guard, the whole view guard: the reflection guard against the surface's
 * normal g, then the n·v ≥ ε guard. */
static inline void vg_view_guard(double n[3], const float vf[3], const double g[3]) {
    const double v[3] = {vf[0], vf[1], vf[2]};
    vg_valid_reflection(n, v, g);
    vg_face_viewer(n, vf);
}

#endif
