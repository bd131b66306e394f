/* The CPU reference of extras/refraction (README "Reference"): analytic ray paths through a
 * sphere, in double precision, sharing no code with the GLSL.
 *
 * Environment: envmap's procedural "uv" lat-long map (its texel centres hold u and v exactly and
 * bilinear filtering reproduces a linear function), so radiance along a world direction d is
 *     L(d) = (u, v, 0),  u = frac(atan2(d.z, d.x) / 2π + ½),  v = acos(d.y) / π
 * (sdk/docs/conventions.md's lat-long orientation, three.js' formula, yaw 0, intensity 1). v
 * (green) is continuous everywhere; u (red) jumps from 1 to 0 across the half-plane z = 0, x < 0
 * (the seam), so red is only compared where every direction that contributes stays away from it (rf_seam_margin).
 *
 * Fresnel: Walter, Marschner, Li, Torrance 2007 eq. 22, written with g = √(n² − 1 + c²) and n the
 * ratio n_transmitted / n_incident (the GLSL's ggx_fresnel_exact is written with β and the
 * inverse ratio: an independent form of the same function).
 *
 * Paths: a camera ray hits the sphere; reflected part F·L(r); the refracted ray crosses the
 * sphere, and at each inner hit (1 − F')·L(exit direction) leaves and F' is reflected inside,
 * until the carried weight is below 1e-9 (or 10,000 bounces). single = 1 stops after the first
 * interface: F·L(r) + (1 − F)·L(t) (what method=single approximates the object with). */
#ifndef RF_SPHERE_REF_H
#define RF_SPHERE_REF_H
#include <math.h>
#include <stdbool.h>

#define RF_PI 3.14159265358979323846

static double rf_seam_margin; /* smallest |distance in u| to the seam of a contributing lookup */

static double rf_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void rf_norm(double a[3]) {
    double l = sqrt(rf_dot(a, a));
    for (int k = 0; k < 3; k++) a[k] /= l;
}

/* environment radiance along d (unit), channel-wise; weight: how much it contributes */
static void rf_env(const double d[3], double weight, double out[3]) {
    double u = atan2(d[2], d[0]) / (2 * RF_PI) + 0.5;
    u -= floor(u);
    double v = acos(fmax(-1.0, fmin(1.0, d[1]))) / RF_PI;
    if (weight > 1e-4) {
        double m = fmin(u, 1 - u);
        if (m < rf_seam_margin) rf_seam_margin = m;
    }
    out[0] = u, out[1] = v, out[2] = 0;
}

/* n = n_transmitted / n_incident, c = cos of the incidence angle */
static double rf_fresnel(double c, double n) {
    double g2 = n * n - 1 + c * c;
    if (g2 < 0) return 1; /* total internal reflection */
    double g = sqrt(g2), a = (g - c) / (g + c), b = (c * (g + c) - 1) / (c * (g - c) + 1);
    return 0.5 * a * a * (1 + b * b);
}

/* refraction of unit w at a surface with unit normal n facing against w; eta = n_i / n_t.
 * false under total internal reflection */
static bool rf_refract(const double w[3], const double n[3], double eta, double t[3]) {
    double ci = -rf_dot(w, n), k = 1 - eta * eta * (1 - ci * ci);
    if (k < 0) return false;
    for (int j = 0; j < 3; j++) t[j] = eta * w[j] + (eta * ci - sqrt(k)) * n[j];
    rf_norm(t);
    return true;
}

typedef struct rf_sphere {
    double center[3], radius;
} rf_sphere;

/* Where ray o + s·w first hits the sphere: s, or −1. */
static double rf_hit(const rf_sphere *S, const double o[3], const double w[3]) {
    double oc[3] = {o[0] - S->center[0], o[1] - S->center[1], o[2] - S->center[2]};
    double b = rf_dot(oc, w), c = rf_dot(oc, oc) - S->radius * S->radius, disc = b * b - c;
    if (disc < 0) return -1;
    double s = -b - sqrt(disc);
    return s > 0 ? s : -1;
}

/* Radiance (all three channels, each traced with its own η: ior[k]) along the camera ray o + s·w.
 * *cos_i (optional) receives the cosine of the first incidence angle (−1: the ray missed). */
static void rf_trace(const rf_sphere *S, const double o[3], const double w[3], const double ior[3], bool single,
                     double out[3], double *cos_i) {
    double s = rf_hit(S, o, w);
    if (cos_i) *cos_i = -1;
    if (s < 0) {
        double e[3];
        rf_env(w, 1, e);
        for (int k = 0; k < 3; k++) out[k] = e[k];
        return;
    }
    double p[3], n[3];
    for (int j = 0; j < 3; j++) p[j] = o[j] + s * w[j], n[j] = (p[j] - S->center[j]) / S->radius;
    double c = -rf_dot(w, n), r[3], e[3];
    if (cos_i) *cos_i = c;
    for (int j = 0; j < 3; j++) r[j] = w[j] + 2 * c * n[j];
    for (int k = 0; k < 3; k++) {
        double F = rf_fresnel(c, ior[k]);
        rf_env(r, F, e);
        double L = F * e[k], t[3];
        if (F < 1 && rf_refract(w, n, 1 / ior[k], t)) {
            if (single) {
                rf_env(t, 1 - F, e);
                L += (1 - F) * e[k];
            } else {
                double weight = 1 - F, q[3] = {p[0], p[1], p[2]}, d[3] = {t[0], t[1], t[2]};
                for (int bounce = 0; bounce < 10000 && weight > 1e-9; bounce++) {
                    double qc[3] = {q[0] - S->center[0], q[1] - S->center[1], q[2] - S->center[2]};
                    double len = -2 * rf_dot(qc, d), nn[3], m[3], x[3];
                    for (int j = 0; j < 3; j++) q[j] += len * d[j];
                    for (int j = 0; j < 3; j++) nn[j] = (q[j] - S->center[j]) / S->radius, m[j] = -nn[j];
                    double c2 = rf_dot(d, nn), F2 = rf_fresnel(c2, 1 / ior[k]);
                    if (F2 < 1 && rf_refract(d, m, ior[k], x)) {
                        rf_env(x, weight * (1 - F2), e);
                        L += weight * (1 - F2) * e[k];
                    }
                    for (int j = 0; j < 3; j++) d[j] = d[j] - 2 * c2 * nn[j];
                    rf_norm(d);
                    weight *= F2;
                }
            }
        }
        out[k] = L;
    }
}

/* A pinhole camera as the core builds it (look-at, vertical fov, pixel centres; row 0 the top). */
typedef struct rf_camera {
    double pos[3], fwd[3], right[3], up[3], tan_half, aspect;
} rf_camera;

static rf_camera rf_camera_make(const double pos[3], const double target[3], double fov_y_deg, int w, int h) {
    rf_camera c = {.pos = {pos[0], pos[1], pos[2]}, .tan_half = tan(fov_y_deg * RF_PI / 360), .aspect = (double)w / h};
    for (int j = 0; j < 3; j++) c.fwd[j] = target[j] - pos[j];
    rf_norm(c.fwd);
    double y[3] = {0, 1, 0};
    c.right[0] = c.fwd[1] * y[2] - c.fwd[2] * y[1];
    c.right[1] = c.fwd[2] * y[0] - c.fwd[0] * y[2];
    c.right[2] = c.fwd[0] * y[1] - c.fwd[1] * y[0];
    rf_norm(c.right);
    c.up[0] = c.right[1] * c.fwd[2] - c.right[2] * c.fwd[1];
    c.up[1] = c.right[2] * c.fwd[0] - c.right[0] * c.fwd[2];
    c.up[2] = c.right[0] * c.fwd[1] - c.right[1] * c.fwd[0];
    return c;
}
static void rf_camera_ray(const rf_camera *c, double px, double py, int w, int h, double d[3]) {
    double x = (2 * (px + 0.5) / w - 1) * c->tan_half * c->aspect, y = (1 - 2 * (py + 0.5) / h) * c->tan_half;
    for (int j = 0; j < 3; j++) d[j] = c->fwd[j] + x * c->right[j] + y * c->up[j];
    rf_norm(d);
}
#endif
