/* 4x4 matrix and 3-vector helpers for plugins (header only: nothing to link, no ABI). Matrices
 * are column-major float[16], as in sl_frame (element (row r, column c) is m[c * 4 + r]). */
#ifndef SHADELAB_MATRIX_H
#define SHADELAB_MATRIX_H

#include <math.h>
#include <stdbool.h>

/* out = m⁻¹, by Gauss-Jordan elimination with partial pivoting in double precision (an inverse
 * view-projection reconstructs world positions from depth, where float elimination loses the
 * far range). Returns false, leaving out untouched, when m is singular (a pivot below 1e-30 or
 * NaN). out may alias m. */
static inline bool sl_mat4_invert(const float m[16], float out[16]) {
    double a[4][8];
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) a[r][c] = m[c * 4 + r], a[r][c + 4] = r == c;
    for (int c = 0; c < 4; c++) {
        int pivot = c;
        for (int r = c + 1; r < 4; r++)
            if (fabs(a[r][c]) > fabs(a[pivot][c])) pivot = r;
        if (!(fabs(a[pivot][c]) >= 1e-30)) return false;
        for (int k = 0; k < 8; k++) {
            double t = a[c][k];
            a[c][k] = a[pivot][k];
            a[pivot][k] = t;
        }
        double d = a[c][c];
        for (int k = 0; k < 8; k++) a[c][k] /= d;
        for (int r = 0; r < 4; r++)
            if (r != c) {
                double g = a[r][c];
                for (int k = 0; k < 8; k++) a[r][k] -= g * a[c][k];
            }
    }
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) out[c * 4 + r] = (float)a[r][c + 4];
    return true;
}

/* out = a × b (out may not alias a or b). */
static inline void sl_vec3_cross(const float a[3], const float b[3], float out[3]) {
    out[0] = a[1] * b[2] - a[2] * b[1], out[1] = a[2] * b[0] - a[0] * b[2], out[2] = a[0] * b[1] - a[1] * b[0];
}

/* v /= |v|; a zero (or non-finite) vector is left as it is. Returns whether it was normalised. */
static inline bool sl_vec3_normalize(float v[3]) {
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(l > 0) || !isfinite(l)) return false;
    v[0] /= l, v[1] /= l, v[2] /= l;
    return true;
}

#endif
