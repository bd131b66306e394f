/* <shadelab/matrix.h>: sl_mat4_invert against closed-form inverses, a projection whose float
 * elimination would lose the far range, and the singular and NaN refusals. */
#include "check.h"
#include <shadelab/matrix.h>

/* column-major: element (row r, column c) at m[c * 4 + r] */
static void set(float m[16], int r, int c, float v) { m[c * 4 + r] = v; }

static void identity(float m[16]) {
    for (int i = 0; i < 16; i++) m[i] = i % 5 == 0;
}

static void multiply(const float a[16], const float b[16], double out[16]) {
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += (double)a[k * 4 + r] * b[c * 4 + k];
            out[c * 4 + r] = s;
        }
}

/* T(t) · S(s) has the inverse S(1/s) · T(−t): diagonal 1/s, last column −t/s. */
static void scale_translate(void) {
    const float s[3] = {2, 0.5f, -4}, t[3] = {3, -1, 10};
    float m[16], inv[16];
    identity(m);
    for (int i = 0; i < 3; i++) set(m, i, i, s[i]), set(m, i, 3, t[i]);
    CHECK(sl_mat4_invert(m, inv));
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) {
            double want = r == 3 ? (c == 3) : c == r ? 1.0 / s[r] : c == 3 ? -t[r] / s[r] : 0;
            CHECK_NEAR(inv[c * 4 + r], want, 1e-7);
        }
}

/* A rotation's inverse is its transpose; the rotation about z by 30°. */
static void rotation(void) {
    const double a = 30 * M_PI / 180;
    float m[16], inv[16];
    identity(m);
    set(m, 0, 0, (float)cos(a)), set(m, 0, 1, (float)-sin(a));
    set(m, 1, 0, (float)sin(a)), set(m, 1, 1, (float)cos(a));
    CHECK(sl_mat4_invert(m, inv));
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) CHECK_NEAR(inv[c * 4 + r], m[r * 4 + c], 1e-7);
}

/* An OpenGL perspective (near 0.01, far 1000) times a view with a row swap needed for pivoting:
 * m · m⁻¹ = I, and the closed-form inverse of the projection's lower-right 2x2 block. */
static void projection(void) {
    const double n = 0.01, f = 1000, fy = 1 / tan(0.5 * 40 * M_PI / 180), aspect = 16.0 / 9;
    float p[16] = {0}, inv[16];
    set(p, 0, 0, (float)(fy / aspect)), set(p, 1, 1, (float)fy);
    set(p, 2, 2, (float)((f + n) / (n - f))), set(p, 2, 3, (float)(2 * f * n / (n - f)));
    set(p, 3, 2, -1);
    CHECK(sl_mat4_invert(p, inv));
    /* [A B; -1 0]⁻¹ = [0 -1; 1/B A/B] for the block of rows/columns 2 and 3 */
    double A = p[2 * 4 + 2], B = p[3 * 4 + 2];
    CHECK_NEAR(inv[2 * 4 + 2], 0, 1e-9);
    CHECK_NEAR(inv[3 * 4 + 2], -1, 1e-9);
    CHECK_NEAR(inv[2 * 4 + 3], 1 / B, 1e-3 * fabs(1 / B));
    CHECK_NEAR(inv[3 * 4 + 3], A / B, 1e-5 * fabs(A / B));
    CHECK_NEAR(inv[0], aspect / fy, 1e-6);

    float view[16] = {0}, m[16];
    set(view, 0, 1, 1), set(view, 1, 2, 1), set(view, 2, 0, 1), set(view, 3, 3, 1); /* axes permuted */
    set(view, 0, 3, 2), set(view, 2, 3, -5);
    double pv[16];
    multiply(p, view, pv);
    for (int i = 0; i < 16; i++) m[i] = (float)pv[i];
    CHECK(sl_mat4_invert(m, inv));
    double id[16];
    multiply(m, inv, id);
    for (int i = 0; i < 16; i++) CHECK_NEAR(id[i], i % 5 == 0, 1e-5);
}

/* Singular matrices and a NaN pivot are refused and the output is left as it was; out may be m. */
static void refusals(void) {
    float m[16], out[16];
    for (int i = 0; i < 16; i++) out[i] = 7;
    identity(m);
    set(m, 2, 2, 0);
    CHECK(!sl_mat4_invert(m, out));
    identity(m);
    set(m, 1, 0, 1), set(m, 1, 1, 0); /* row 1 = row 0 = (1, 0, 0, 0) */
    CHECK(!sl_mat4_invert(m, out));
    identity(m);
    set(m, 1, 1, NAN);
    CHECK(!sl_mat4_invert(m, out));
    for (int i = 0; i < 16; i++) CHECK(out[i] == 7);
    identity(m);
    set(m, 0, 0, 4), set(m, 0, 3, 8);
    CHECK(sl_mat4_invert(m, m));
    CHECK_NEAR(m[0], 0.25, 1e-9);
    CHECK_NEAR(m[12], -2, 1e-9);
}

int main(void) {
    scale_translate();
    rotation();
    projection();
    refusals();
    return check_result();
}
