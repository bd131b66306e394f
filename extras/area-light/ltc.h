/* area-light, C side: the polygon integrals, the GGX and Blinn-Phong lobes and the LTC tables,
 * shared by the fit tool (ltc_fit.c), its Monte Carlo validation and the tests. Written here from
 * the papers; no code or table is taken from their published implementations.
 *
 *   Lambert (1760), the irradiance from a polygon: ∫_P cosθ dω = ½ Σ_i γ_i n·(v_i×v_{i+1})/|v_i×v_{i+1}|,
 *     v_i the unit directions to the polygon's vertices, γ_i the angle between v_i and v_{i+1}.
 *   Heitz, Dupuy, Hill, Neubelt (2016), "Real-Time Polygonal-Light Shading with Linearly Transformed
 *     Cosines": D(ω) = D_o(M⁻¹ω/|M⁻¹ω|) |det M⁻¹| / |M⁻¹ω|³, D_o = max(0, z)/π; the integral of D
 *     over a polygon is the integral of D_o over the polygon transformed by M⁻¹, which is
 *     Lambert's formula (over π) after clipping to the upper hemisphere.
 *   Walter, Marschner, Li, Torrance (2007): GGX D and the separable Smith G = G₁(v)G₁(l), as the
 *     bundled ggx plugin evaluates them (f = F D G / (4 |n·l| |n·v|)).
 *   Blinn (1977), normalised: the SDK's Blinn-Phong lobe (p+1)/(2π) (n·h)^p, as phong's blinn-gloss.
 *
 * Header-only (static functions): the tool and each test include it. */
#ifndef AREA_LIGHT_LTC_H
#define AREA_LIGHT_LTC_H
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct { double x, y, z; } al_v3;
static inline al_v3 al_v(double x, double y, double z) { return (al_v3){x, y, z}; }
static inline al_v3 al_add(al_v3 a, al_v3 b) { return al_v(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline al_v3 al_sub(al_v3 a, al_v3 b) { return al_v(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline al_v3 al_mul(al_v3 a, double s) { return al_v(a.x * s, a.y * s, a.z * s); }
static inline double al_dot(al_v3 a, al_v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline al_v3 al_cross(al_v3 a, al_v3 b) {
    return al_v(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double al_len(al_v3 a) { return sqrt(al_dot(a, a)); }
static inline al_v3 al_norm(al_v3 a) { double l = al_len(a); return l > 0 ? al_mul(a, 1 / l) : a; }

/* ---- polygons ------------------------------------------------------------------------------ */

#define AL_MAX_VERTS 72

/* Clips a polygon (vertices relative to the shading point, z along the normal) to z >= 0
 * (Sutherland–Hodgman against one plane). Returns the new vertex count. */
static inline int al_clip_horizon(const al_v3 *in, int n, al_v3 *out) {
    int m = 0;
    for (int i = 0; i < n; i++) {
        al_v3 a = in[i], b = in[(i + 1) % n];
        bool ain = a.z >= 0, bin = b.z >= 0;
        if (ain) out[m++] = a;
        if (ain != bin) {
            double t = a.z / (a.z - b.z);
            al_v3 p = al_add(a, al_mul(al_sub(b, a), t));
            p.z = 0;
            out[m++] = p;
        }
    }
    return m;
}

/* ∫_P cosθ dω over the part of the polygon above the horizon (z >= 0), for either winding:
 * Lambert's formula (above). Vertices relative to the shading point, local frame (z = normal). */
static inline double al_polygon_cos_integral(const al_v3 *verts, int n) {
    al_v3 clipped[AL_MAX_VERTS + 8];
    int m = al_clip_horizon(verts, n, clipped);
    if (m < 3) return 0;
    double sum = 0;
    for (int i = 0; i < m; i++) {
        al_v3 a = al_norm(clipped[i]), b = al_norm(clipped[(i + 1) % m]);
        al_v3 c = al_cross(a, b);
        double s = al_len(c), d = al_dot(a, b);
        double gamma = atan2(s, d);
        sum += s > 1e-300 ? gamma * c.z / s : 0;
    }
    return 0.5 * fabs(sum);
}

/* The vertices of a rectangle (width along ex, height along ey, centred at c) or of a disk
 * (ellipse with diameters width, height) as a regular polygon of `segments` vertices with the
 * disk's area (radius scaled by √(2π / (N sin(2π/N)))). Returns the vertex count. */
static inline int al_light_polygon(al_v3 c, al_v3 ex, al_v3 ey, double width, double height, bool disk, int segments,
                            al_v3 *out) {
    if (!disk) {
        al_v3 x = al_mul(ex, width / 2), y = al_mul(ey, height / 2);
        out[0] = al_sub(al_sub(c, x), y);
        out[1] = al_sub(al_add(c, x), y);
        out[2] = al_add(al_add(c, x), y);
        out[3] = al_add(al_sub(c, x), y);
        return 4;
    }
    int n = segments < 3 ? 3 : segments > AL_MAX_VERTS ? AL_MAX_VERTS : segments;
    double k = sqrt(2 * M_PI / (n * sin(2 * M_PI / n)));
    for (int i = 0; i < n; i++) {
        double a = 2 * M_PI * i / n;
        out[i] = al_add(c, al_add(al_mul(ex, cos(a) * width / 2 * k), al_mul(ey, sin(a) * height / 2 * k)));
    }
    return n;
}

/* ---- GGX (as the bundled ggx plugin: separable Smith) -------------------------------------- */

#define AL_MIN_ALPHA 2e-3 /* the ggx plugin's clamp */

static inline double al_ggx_D(double n_dot_h, double a) {
    if (n_dot_h <= 0) return 0;
    double a2 = a * a, d = n_dot_h * n_dot_h * (a2 - 1) + 1;
    return a2 / (M_PI * d * d);
}
static inline double al_ggx_G1(double x_dot_n, double x_dot_h, double a) {
    if (x_dot_n == 0 || x_dot_h / x_dot_n <= 0) return 0;
    double c = fmin(fmax(fabs(x_dot_n), 1e-6), 1.0), t2 = (1 - c * c) / (c * c);
    return 2 / (1 + sqrt(1 + a * a * t2));
}
/* f·cos without Fresnel: D G₁(v) G₁(l) / (4 n·v), local frame (n = z); 0 below either horizon. */
static inline double al_ggx_fcos(al_v3 v, al_v3 l, double a) {
    if (v.z <= 0 || l.z <= 0) return 0;
    al_v3 h = al_norm(al_add(v, l));
    return al_ggx_D(h.z, a) * al_ggx_G1(v.z, al_dot(v, h), a) * al_ggx_G1(l.z, al_dot(l, h), a) / (4 * v.z);
}
/* Samples l by the distribution of normals (pdf_l = D (n·h) / (4 |v·h|)); returns false when the
 * sample is below the horizon. u1, u2 in [0,1). */
static inline bool al_ggx_sample(al_v3 v, double a, double u1, double u2, al_v3 *l, double *pdf) {
    double phi = 2 * M_PI * u2;
    double cos2 = (1 - u1) / (1 + (a * a - 1) * u1), c = sqrt(cos2), s = sqrt(fmax(0, 1 - cos2));
    al_v3 h = al_v(s * cos(phi), s * sin(phi), c);
    double vh = al_dot(v, h);
    *l = al_sub(al_mul(h, 2 * vh), v);
    *pdf = al_ggx_D(c, a) * c / (4 * fabs(vh));
    return l->z > 0 && vh > 0;
}

/* ---- the lobe contract's Blinn-Phong lobe (SDK ABI 1.19, shaders/common.glsl) -------------- */

/* The power of the Blinn-Phong lobe whose GGX-equivalent α is a: p = 2/log2(1 + α²) − 2 (the
 * contract's sl_lobe_blinn_power; Blinn's median matched to GGX's). α = 1 is p = 0. */
static inline double al_blinn_power(double a) {
    double l2 = log1p(a * a) / log(2.0);
    return fmax(2 / fmax(l2, 1e-300) - 2, 0);
}
/* f·cos of the normalised Blinn-Phong lobe without Fresnel, as blinn-gloss evaluates it (phong's
 * phong_blinn_lobe / π): (p+1)/(2π) (n·h)^p (n·l), local frame; 0 below either horizon. Over h
 * it integrates to 1 ((p+1)/(2π) ∫ cos^p θ_h dω_h = 1), so h ~ (n·h)^p is its natural sampling. */
static inline double al_blinn_fcos(al_v3 v, al_v3 l, double p) {
    if (v.z <= 0 || l.z <= 0) return 0;
    al_v3 h = al_norm(al_add(v, l));
    return h.z > 0 ? (p + 1) / (2 * M_PI) * pow(h.z, p) * l.z : 0;
}
/* The density of l when h is drawn with density (p+1)/(2π) (n·h)^p and l = reflect(−v, h). */
static inline double al_blinn_pdf(al_v3 v, al_v3 l, double p) {
    al_v3 h = al_norm(al_add(v, l));
    double vh = al_dot(v, h);
    return vh > 0 && l.z > 0 && h.z > 0 ? (p + 1) / (2 * M_PI) * pow(h.z, p) / (4 * vh) : 0;
}
/* Samples l by that density (cos θ_h = (1 − u1)^(1/(p+1))); false below the horizon. */
static inline bool al_blinn_sample(al_v3 v, double p, double u1, double u2, al_v3 *l, double *pdf) {
    double c = pow(1 - u1, 1 / (p + 1)), s = sqrt(fmax(0, 1 - c * c)), phi = 2 * M_PI * u2;
    al_v3 h = al_v(s * cos(phi), s * sin(phi), c);
    double vh = al_dot(v, h);
    *l = al_sub(al_mul(h, 2 * vh), v);
    *pdf = (p + 1) / (2 * M_PI) * pow(c, p) / (4 * fabs(vh));
    return l->z > 0 && vh > 0;
}

/* ---- a lobe of either shape: what the fit and the validation integrate --------------------- */
typedef struct al_lobe { bool blinn_phong; double alpha, power; } al_lobe;
static inline al_lobe al_lobe_make(bool blinn_phong, double alpha) {
    return (al_lobe){blinn_phong, alpha, blinn_phong ? al_blinn_power(alpha) : 0};
}
static inline double al_lobe_fcos(const al_lobe *k, al_v3 v, al_v3 l) {
    return k->blinn_phong ? al_blinn_fcos(v, l, k->power) : al_ggx_fcos(v, l, k->alpha);
}
static inline double al_lobe_pdf(const al_lobe *k, al_v3 v, al_v3 l) {
    if (k->blinn_phong) return al_blinn_pdf(v, l, k->power);
    al_v3 h = al_norm(al_add(v, l));
    double vh = al_dot(v, h);
    return vh > 0 && l.z > 0 ? al_ggx_D(h.z, k->alpha) * h.z / (4 * vh) : 0;
}
static inline bool al_lobe_sample(const al_lobe *k, al_v3 v, double u1, double u2, al_v3 *l, double *pdf) {
    return k->blinn_phong ? al_blinn_sample(v, k->power, u1, u2, l, pdf) : al_ggx_sample(v, k->alpha, u1, u2, l, pdf);
}

/* ---- the LTC table ------------------------------------------------------------------------- */

/* One entry: M⁻¹ = [[a, 0, b], [0, 1, 0], [c, 0, d]] (rows; scaled so that its middle element is
 * 1: the polygon integral does not depend on the scale), in the frame (x = the view direction's
 * tangent component, y, z = n); norm = ∫ f cos dω, fresnel = ∫ f cos (1 − v·h)⁵ dω over the
 * hemisphere (Schlick: ∫ F f cos = F0·(norm − fresnel) + fresnel). Indexed by
 * u = √α (i over size−1) and t = √(1 − cos θ_v) (j over size−1); a Blinn-Phong table by the α of
 * its lobe's power (al_blinn_power), as the contract's lobes carry it. */
typedef struct al_ltc_entry { double a, b, c, d, norm, fresnel; } al_ltc_entry;
typedef struct al_ltc_table { int size; al_ltc_entry *e; /* e[j * size + i] */ } al_ltc_table;

static inline double al_table_alpha(int i, int size) {
    double u = (double)i / (size - 1);
    return fmax(u * u, AL_MIN_ALPHA);
}
static inline double al_table_cos_theta(int j, int size) {
    double t = (double)j / (size - 1);
    return fmax(1 - t * t, 1e-3); /* 89.94° at most: n·v = 0 has no BRDF */
}

/* The data file: '#' comment lines (the command that made it), then "size N", then N² lines
 * "a b c d norm fresnel" in j-major order. Returns false with a message naming file and line. */
static inline bool al_table_read(const char *path, al_ltc_table *t, char *err, size_t n) {
    FILE *f = fopen(path, "r");
    if (!f) { snprintf(err, n, "%s: cannot open", path); return false; }
    char line[512];
    int lineno = 0, count = 0;
    t->size = 0;
    t->e = NULL;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        if (line[0] == '#' || line[0] == '\n') continue;
        if (!t->size) {
            if (sscanf(line, "size %d", &t->size) != 1 || t->size < 2 || t->size > 256) {
                snprintf(err, n, "%s:%d: expected \"size N\" with 2 <= N <= 256", path, lineno);
                fclose(f);
                return false;
            }
            t->e = calloc((size_t)t->size * t->size, sizeof *t->e);
            continue;
        }
        al_ltc_entry *e = &t->e[count];
        if (count >= t->size * t->size ||
            sscanf(line, "%lf %lf %lf %lf %lf %lf", &e->a, &e->b, &e->c, &e->d, &e->norm, &e->fresnel) != 6 ||
            !isfinite(e->a + e->b + e->c + e->d + e->norm + e->fresnel)) {
            snprintf(err, n, "%s:%d: expected six finite numbers (entry %d of %d)", path, lineno, count + 1,
                     t->size * t->size);
            fclose(f);
            free(t->e);
            t->e = NULL;
            return false;
        }
        count++;
    }
    fclose(f);
    if (!t->size || count != t->size * t->size) {
        snprintf(err, n, "%s: %d entries, expected %d", path, count, t->size * t->size);
        free(t->e);
        t->e = NULL;
        return false;
    }
    return true;
}

/* Bilinear lookup at (α, cos θ_v), as the shader's texture lookup does (texel centres at grid
 * points). */
static inline al_ltc_entry al_table_lookup(const al_ltc_table *t, double alpha, double cos_theta) {
    int N = t->size;
    double x = fmin(fmax(sqrt(fmax(alpha, 0)), 0), 1) * (N - 1);
    double y = fmin(fmax(sqrt(fmax(1 - cos_theta, 0)), 0), 1) * (N - 1);
    int i0 = (int)floor(x), j0 = (int)floor(y);
    if (i0 > N - 2) i0 = N - 2;
    if (j0 > N - 2) j0 = N - 2;
    double fx = x - i0, fy = y - j0;
    const al_ltc_entry *e00 = &t->e[j0 * N + i0], *e10 = &t->e[j0 * N + i0 + 1], *e01 = &t->e[(j0 + 1) * N + i0],
                       *e11 = &t->e[(j0 + 1) * N + i0 + 1];
    al_ltc_entry r;
    double *o = &r.a;
    const double *p00 = &e00->a, *p10 = &e10->a, *p01 = &e01->a, *p11 = &e11->a;
    for (int k = 0; k < 6; k++)
        o[k] = (p00[k] * (1 - fx) + p10[k] * fx) * (1 - fy) + (p01[k] * (1 - fx) + p11[k] * fx) * fy;
    return r;
}

/* ∫_P D_LTC dω for a polygon given in the local frame (relative to the shading point; x towards
 * the view's tangent component, z = n): transform by M⁻¹, clip, Lambert's formula over π. */
static inline double al_ltc_polygon(const al_ltc_entry *e, const al_v3 *verts, int n) {
    al_v3 t[AL_MAX_VERTS];
    for (int i = 0; i < n; i++)
        t[i] = al_v(e->a * verts[i].x + e->b * verts[i].z, verts[i].y, e->c * verts[i].x + e->d * verts[i].z);
    return al_polygon_cos_integral(t, n) / M_PI;
}

#endif
