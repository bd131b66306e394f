/* envmap core, CPU side: direction conventions, cube layouts, input sanitising, RGBE,
 * spherical harmonics, the procedural sky and hashing. See include/envmap/prefilter.h. */
#include "envmap/prefilter.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

void em_image_free(em_image *img) {
    if (!img) return;
    free(img->px);
    memset(img, 0, sizeof *img);
}

/* ---------------------------------------------------------------- directions */

/* The equirectangular orientation of Blender and three.js (sdk/docs/conventions.md): seen from
 * inside, u grows to the right. u = 0 faces −X, u = 1/4 faces −Z (the default camera's view),
 * u = 1/2 (the image's centre) faces +X, u = 3/4 faces +Z; v = 0 is the top row (+Y). */
void em_latlong_dir(double u, double v, double d[3]) {
    double phi = 2 * M_PI * u, theta = M_PI * v;
    d[0] = -sin(theta) * cos(phi);
    d[1] = cos(theta);
    d[2] = -sin(theta) * sin(phi);
}

void em_dir_latlong(const double d[3], double *u, double *v) {
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double y = len > 0 ? d[1] / len : 1;
    /* three.js' u = atan2(z, x)/2π + ½, as φ = atan2(−z, −x) wrapped to [0, 2π); atan2(0, 0) at the poles */
    double phi = (fabs(d[0]) + fabs(d[2]) > 0) ? atan2(-d[2], -d[0]) : 0;
    double uu = phi / (2 * M_PI);
    uu -= floor(uu);
    if (uu >= 1) uu = 0;
    *u = uu;
    *v = acos(y < -1 ? -1 : y > 1 ? 1 : y) / M_PI;
}

/* GL 4.5 table 8.19, inverted: a = 2s − 1, b = 2t − 1. */
void em_cube_dir(int face, double s, double t, double d[3]) {
    double a = 2 * s - 1, b = 2 * t - 1;
    switch (face) {
    case 0: d[0] = 1; d[1] = -b; d[2] = -a; break;
    case 1: d[0] = -1; d[1] = -b; d[2] = a; break;
    case 2: d[0] = a; d[1] = 1; d[2] = b; break;
    case 3: d[0] = a; d[1] = -1; d[2] = -b; break;
    case 4: d[0] = a; d[1] = -b; d[2] = 1; break;
    default: d[0] = -a; d[1] = -b; d[2] = -1; break;
    }
    double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int i = 0; i < 3; i++) d[i] /= l;
}

int em_dir_cube(const double d[3], double *s, double *t) {
    double ax = fabs(d[0]), ay = fabs(d[1]), az = fabs(d[2]);
    int face;
    double sc, tc, ma;
    if (ax >= ay && ax >= az) {
        face = d[0] > 0 ? 0 : 1;
        ma = ax;
        sc = d[0] > 0 ? -d[2] : d[2];
        tc = -d[1];
    } else if (ay >= az) {
        face = d[1] > 0 ? 2 : 3;
        ma = ay;
        sc = d[0];
        tc = d[1] > 0 ? d[2] : -d[2];
    } else {
        face = d[2] > 0 ? 4 : 5;
        ma = az;
        sc = d[2] > 0 ? d[0] : -d[0];
        tc = -d[1];
    }
    *s = 0.5 * (sc / ma + 1);
    *t = 0.5 * (tc / ma + 1);
    return face;
}

static double area_element(double x, double y) { return atan2(x * y, sqrt(x * x + y * y + 1)); }

double em_texel_solid_angle(int size, int x, int y) {
    double x0 = 2.0 * x / size - 1, x1 = 2.0 * (x + 1) / size - 1;
    double y0 = 2.0 * y / size - 1, y1 = 2.0 * (y + 1) / size - 1;
    return area_element(x0, y0) - area_element(x0, y1) - area_element(x1, y0) + area_element(x1, y1);
}

void em_rotate_y(const double d[3], double degrees, double out[3]) {
    double a = degrees * M_PI / 180, c = cos(a), s = sin(a);
    double x = d[0], z = d[2];
    out[0] = c * x + s * z;
    out[1] = d[1];
    out[2] = -s * x + c * z;
}

/* ---------------------------------------------------------------- sanitising */

long em_sanitize(float *rgba, size_t pixels, em_sanitize_stats *st) {
    em_sanitize_stats s = {0};
    for (size_t i = 0; i < pixels; i++) {
        float *p = rgba + i * 4;
        for (int c = 0; c < 3; c++) {
            float v = p[c];
            if (isnan(v)) { s.nan++; p[c] = 0; }
            else if (isinf(v)) { s.inf++; p[c] = v > 0 ? EM_HALF_MAX : 0; }
            else if (v < 0) { s.negative++; p[c] = 0; }
            else {
                if (v > s.max_value) s.max_value = v;
                if (v > EM_HALF_MAX) { s.clamped++; p[c] = EM_HALF_MAX; }
            }
        }
        p[3] = 1;
    }
    if (st) *st = s;
    return s.nan + s.inf + s.negative;
}

/* ---------------------------------------------------------------- RGBE */

void em_rgbe_encode(const float rgb[3], unsigned char out[4]) {
    float v = rgb[0];
    if (rgb[1] > v) v = rgb[1];
    if (rgb[2] > v) v = rgb[2];
    if (!(v >= 1e-32f)) { /* also NaN */
        out[0] = out[1] = out[2] = out[3] = 0;
        return;
    }
    int e;
    double m = frexp(v, &e); /* v = m · 2^e, m in [0.5, 1) */
    double scale = m * 256.0 / v;
    for (int c = 0; c < 3; c++) {
        double x = rgb[c] > 0 ? rgb[c] * scale : 0;
        out[c] = (unsigned char)(x > 255 ? 255 : x);
    }
    out[3] = (unsigned char)(e + 128);
}

void em_rgbe_decode(const unsigned char in[4], float rgb[3]) {
    if (!in[3]) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        return;
    }
    double f = ldexp(1.0, (int)in[3] - (128 + 8));
    for (int c = 0; c < 3; c++) rgb[c] = in[c] ? (float)((in[c] + 0.5) * f) : 0.0f;
}

void em_rgbe_encode_image(const float *rgba, size_t pixels, unsigned char *out) {
    for (size_t i = 0; i < pixels; i++) em_rgbe_encode(rgba + i * 4, out + i * 4);
}

/* ---------------------------------------------------------------- layouts */

em_layout em_detect_layout(int w, int h) {
    if (w <= 0 || h <= 0) return EM_LAYOUT_UNKNOWN;
    if (w == 2 * h) return EM_LAYOUT_LATLONG;
    if (w * 3 == h * 4 && w % 4 == 0) return EM_LAYOUT_HCROSS;
    if (w * 4 == h * 3 && w % 3 == 0) return EM_LAYOUT_VCROSS;
    if (w == 6 * h) return EM_LAYOUT_HSTRIP;
    if (h == 6 * w) return EM_LAYOUT_VSTRIP;
    return EM_LAYOUT_UNKNOWN;
}

const char *em_layout_name(em_layout l) {
    switch (l) {
    case EM_LAYOUT_LATLONG: return "lat-long (2:1)";
    case EM_LAYOUT_HCROSS: return "horizontal cross (4:3)";
    case EM_LAYOUT_VCROSS: return "vertical cross (3:4)";
    case EM_LAYOUT_HSTRIP: return "horizontal strip (6:1)";
    case EM_LAYOUT_VSTRIP: return "vertical strip (1:6)";
    default: return "unknown";
    }
}

/* Where face f sits in a layout, in face-sized cells, and whether it is turned 180°. */
static void face_cell(em_layout l, int f, int *cx, int *cy, bool *rot180) {
    static const int hx[6] = {2, 0, 1, 1, 1, 3}, hy[6] = {1, 1, 0, 2, 1, 1};
    static const int vx[6] = {2, 0, 1, 1, 1, 1}, vy[6] = {1, 1, 0, 2, 1, 3};
    *rot180 = false;
    switch (l) {
    case EM_LAYOUT_HCROSS: *cx = hx[f]; *cy = hy[f]; break;
    case EM_LAYOUT_VCROSS: *cx = vx[f]; *cy = vy[f]; *rot180 = f == 5; break;
    case EM_LAYOUT_HSTRIP: *cx = f; *cy = 0; break;
    default: *cx = 0; *cy = f; break;
    }
}

bool em_extract_faces(const em_image *img, em_layout l, float *faces[6], int *size) {
    int n;
    switch (l) {
    case EM_LAYOUT_HCROSS: n = img->w / 4; break;
    case EM_LAYOUT_VCROSS: n = img->w / 3; break;
    case EM_LAYOUT_HSTRIP: n = img->h; break;
    case EM_LAYOUT_VSTRIP: n = img->w; break;
    default: return false;
    }
    *size = n;
    for (int f = 0; f < 6; f++) {
        int cx, cy;
        bool r;
        face_cell(l, f, &cx, &cy, &r);
        faces[f] = malloc((size_t)n * n * 4 * sizeof(float));
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++) {
                int sx = r ? n - 1 - x : x, sy = r ? n - 1 - y : y;
                const float *src = img->px + ((size_t)(cy * n + sy) * img->w + cx * n + sx) * 4;
                memcpy(faces[f] + ((size_t)y * n + x) * 4, src, 4 * sizeof(float));
            }
    }
    return true;
}

void em_faces_to_hcross(float *const faces[6], int n, em_image *out) {
    out->w = 4 * n;
    out->h = 3 * n;
    out->px = calloc((size_t)out->w * out->h * 4, sizeof(float));
    for (int f = 0; f < 6; f++) {
        int cx, cy;
        bool r;
        face_cell(EM_LAYOUT_HCROSS, f, &cx, &cy, &r);
        for (int y = 0; y < n; y++)
            memcpy(out->px + ((size_t)(cy * n + y) * out->w + cx * n) * 4, faces[f] + (size_t)y * n * 4,
                   (size_t)n * 4 * sizeof(float));
    }
}

/* ---------------------------------------------------------------- spherical harmonics */

/* The real SH basis of bands 0–2: k0; k1·(y, z, x); k2·(xy, yz, xz); k3·(3z² − 1); k4·(x² − y²). */
static const double SH_K0 = 0.282094791773878, SH_K1 = 0.488602511902920, SH_K2 = 1.092548430592079,
                    SH_K3 = 0.315391565252520, SH_K4 = 0.546274215296040;

static void sh9_basis(const double d[3], double y[9]) {
    double x = d[0], yy = d[1], z = d[2];
    y[0] = SH_K0;
    y[1] = SH_K1 * yy;
    y[2] = SH_K1 * z;
    y[3] = SH_K1 * x;
    y[4] = SH_K2 * x * yy;
    y[5] = SH_K2 * yy * z;
    y[6] = SH_K3 * (3 * z * z - 1);
    y[7] = SH_K2 * x * z;
    y[8] = SH_K4 * (x * x - yy * yy);
}

void em_sh9_project(const float *faces, int n, double sh[9][3]) {
    memset(sh, 0, 9 * 3 * sizeof(double));
    double *w = malloc((size_t)n * n * sizeof(double));
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) w[y * n + x] = em_texel_solid_angle(n, x, y);
    for (int f = 0; f < 6; f++)
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++) {
                double d[3], b[9];
                em_cube_dir(f, (x + 0.5) / n, (y + 0.5) / n, d);
                sh9_basis(d, b);
                const float *p = faces + (((size_t)f * n + y) * n + x) * 4;
                double dw = w[y * n + x];
                for (int k = 0; k < 9; k++)
                    for (int c = 0; c < 3; c++) sh[k][c] += p[c] * b[k] * dw;
            }
    free(w);
}

/* The image is taken in blocks of k×k texels (k = ⌈h/128⌉: a fixed cost per image, whatever its
 * size), each block's radiance as constant (the solid-angle-weighted mean of its texels), and the
 * basis is integrated over each block exactly: with d = (−sinθ cosφ, cosθ, −sinθ sinφ)
 * (em_latlong_dir) every basis function is a sum of products of a θ factor and a φ factor, so a
 * block's weights are products of θ moments ∫ f(θ) sinθ dθ and φ moments ∫ g(φ) dφ over it. Exact
 * for a constant map, where a texel-centre rule is not: on a small lat-long (envmap's
 * constant:R,G,B is 8×4) the centre rule put 3 % into the band-2 coefficients. Bands 0–2 vary
 * slowly, so blocks of ≤ 1.4° lose nothing they keep (the cube path projects a 32² mip). */
void em_sh9_project_latlong(const em_image *img, double sh[9][3]) {
    memset(sh, 0, 9 * 3 * sizeof(double));
    int w = img->w, h = img->h, k = (h + 127) / 128;
    int bw = (w + k - 1) / k, bh = (h + k - 1) / k;
    double *pm = malloc((size_t)bw * 6 * sizeof(double)), *sum = malloc((size_t)bw * 3 * sizeof(double));
    if (!pm || !sum) {
        free(pm), free(sum);
        return;
    }
    for (int c = 0; c < bw; c++) { /* the φ moments of block column c */
        int x1 = (c + 1) * k < w ? (c + 1) * k : w;
        double a = 2 * M_PI * c * k / w, b = 2 * M_PI * x1 / w, *m = pm + 6 * c;
        m[0] = b - a;                                            /* ∫ 1 */
        m[1] = sin(b) - sin(a);                                  /* ∫ cos φ */
        m[2] = cos(a) - cos(b);                                  /* ∫ sin φ */
        m[3] = 0.5 * (b - a) + 0.25 * (sin(2 * b) - sin(2 * a)); /* ∫ cos² φ */
        m[4] = 0.5 * (b - a) - 0.25 * (sin(2 * b) - sin(2 * a)); /* ∫ sin² φ */
        m[5] = 0.5 * (cos(2 * a) - cos(2 * b));                  /* ∫ sin 2φ */
    }
    const double k0 = SH_K0, k1 = SH_K1, k2 = SH_K2, k3 = SH_K3, k4 = SH_K4;
    for (int r = 0; r < bh; r++) {
        int y0 = r * k, y1 = y0 + k < h ? y0 + k : h;
        /* each block's radiance: its texels weighted by their rows' solid angle (cos θ_top − cos θ_bottom) */
        memset(sum, 0, (size_t)bw * 3 * sizeof(double));
        double rows = 0;
        for (int y = y0; y < y1; y++) {
            double wy = cos(M_PI * y / h) - cos(M_PI * (y + 1) / h);
            rows += wy;
            const float *p = img->px + (size_t)y * w * 4;
            for (int x = 0; x < w; x++, p += 4) {
                double *s = sum + 3 * (x / k);
                s[0] += p[0] * wy, s[1] += p[1] * wy, s[2] += p[2] * wy;
            }
        }
        double a = M_PI * y0 / h, b = M_PI * y1 / h;
        double ca = cos(a), cb = cos(b), sa = sin(a), sb = sin(b);
        double t0 = ca - cb;                                          /* ∫ sinθ */
        double tc = 0.5 * (sb * sb - sa * sa);                        /* ∫ cosθ sinθ */
        double ts = 0.5 * (b - a) - 0.25 * (sin(2 * b) - sin(2 * a)); /* ∫ sin²θ */
        double tsc = (sb * sb * sb - sa * sa * sa) / 3;               /* ∫ sin²θ cosθ */
        double tss = (ca - cb) - (ca * ca * ca - cb * cb * cb) / 3;   /* ∫ sin³θ */
        double tcc = (ca * ca * ca - cb * cb * cb) / 3;               /* ∫ cos²θ sinθ */
        for (int c = 0; c < bw; c++) {
            const double *m = pm + 6 * c;
            int x1 = (c + 1) * k < w ? (c + 1) * k : w, cols = x1 - c * k;
            double wt[9] = {k0 * t0 * m[0],
                            k1 * tc * m[0],
                            -k1 * ts * m[2],
                            -k1 * ts * m[1],
                            -k2 * tsc * m[1],
                            -k2 * tsc * m[2],
                            k3 * (3 * tss * m[4] - t0 * m[0]),
                            0.5 * k2 * tss * m[5],
                            k4 * (tss * m[3] - tcc * m[0])};
            double norm = rows > 0 ? 1.0 / (rows * cols) : 0;
            for (int q = 0; q < 9; q++)
                for (int ch = 0; ch < 3; ch++) sh[q][ch] += sum[3 * c + ch] * norm * wt[q];
        }
    }
    free(pm), free(sum);
}

static const double band_factor[9] = {1.0, 2.0 / 3, 2.0 / 3, 2.0 / 3, 0.25, 0.25, 0.25, 0.25, 0.25}; /* Â_l/π */

void em_sh9_diffuse(const double sh[9][3], const double n[3], double out[3]) {
    double b[9];
    sh9_basis(n, b);
    for (int c = 0; c < 3; c++) {
        out[c] = 0;
        for (int k = 0; k < 9; k++) out[c] += band_factor[k] * sh[k][c] * b[k];
    }
}

void em_sh9_diffuse_coefficients(const double sh[9][3], float out[9][3]) {
    static const double norm[9] = {0.282094791773878, 0.488602511902920, 0.488602511902920, 0.488602511902920,
                                   1.092548430592079, 1.092548430592079, 0.315391565252520, 1.092548430592079,
                                   0.546274215296040};
    for (int k = 0; k < 9; k++)
        for (int c = 0; c < 3; c++) out[k][c] = (float)(band_factor[k] * sh[k][c] * norm[k]);
}

/* ---------------------------------------------------------------- environment importance sampling */

static double luminance(const float *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

bool em_env_distribution_build(const em_image *img, int max_width, em_env_distribution *d) {
    memset(d, 0, sizeof *d);
    int k = 1;
    while (img->w / k > max_width && img->w / k > 2) k *= 2; /* box blocks of k × k texels */
    int w = (img->w + k - 1) / k, h = (img->h + k - 1) / k;
    d->conditional = malloc((size_t)w * h * sizeof(float));
    d->pdf = malloc((size_t)w * h * sizeof(float));
    d->marginal = malloc((size_t)h * sizeof(float));
    double *lum = calloc((size_t)w * h, sizeof(double)), *rows = calloc((size_t)h, sizeof(double));
    if (!d->conditional || !d->pdf || !d->marginal || !lum || !rows) {
        free(lum), free(rows), em_env_distribution_free(d);
        return false;
    }
    d->w = w, d->h = h;
    for (int y = 0; y < img->h; y++)
        for (int x = 0; x < img->w; x++) lum[(size_t)(y / k) * w + x / k] += luminance(img->px + ((size_t)y * img->w + x) * 4);
    double mean = 0; /* the map's mean luminance over the sphere (each cell by its solid angle) */
    for (int y = 0; y < h; y++) {
        int rows_in = (y + 1) * k <= img->h ? k : img->h - y * k;
        double omega = (2 * M_PI / w) * (cos(M_PI * y / h) - cos(M_PI * (y + 1) / h));
        for (int x = 0; x < w; x++) {
            int cols_in = (x + 1) * k <= img->w ? k : img->w - x * k;
            double *l = lum + (size_t)y * w + x;
            *l /= rows_in * cols_in; /* the block's mean */
            mean += *l * omega / (4 * M_PI);
        }
    }
    /* each cell's weight: the largest luminance of its 3 × 3 neighbourhood (u wraps), minus the
     * mean. The largest, because lookups are bilinear: next to a bright cell the radiance read
     * is partly the bright cell's, and a cell sampled by its own dim value would turn those
     * lookups into fireflies (L/pdf with a small pdf; BRDF samples there, at MIS weight ≈ 1,
     * likewise). */
    double *dil = malloc((size_t)w * h * sizeof(double));
    if (!dil) {
        free(lum), free(rows), em_env_distribution_free(d);
        return false;
    }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double m = 0;
            for (int j = y > 0 ? y - 1 : 0; j <= (y + 1 < h ? y + 1 : h - 1); j++)
                for (int i = -1; i <= 1; i++) {
                    double l = lum[(size_t)j * w + (x + i + w) % w];
                    m = l > m ? l : m;
                }
            /* MIS compensation; within 1 % of the mean (a constant map and its rounding) is even */
            dil[(size_t)y * w + x] = m > 1.01 * mean ? m - mean : 0;
        }
    memcpy(lum, dil, (size_t)w * h * sizeof(double));
    free(dil);
    for (int y = 0; y < h; y++) {
        double omega = (2 * M_PI / w) * (cos(M_PI * y / h) - cos(M_PI * (y + 1) / h)), sum = 0;
        for (int x = 0; x < w; x++) sum += lum[(size_t)y * w + x];
        double run = 0;
        for (int x = 0; x < w; x++) {
            run += lum[(size_t)y * w + x];
            d->conditional[(size_t)y * w + x] = sum > 0 ? (float)(run / sum) : (float)(x + 1) / w;
        }
        d->conditional[(size_t)y * w + w - 1] = 1;
        rows[y] = sum * omega;
        d->total += rows[y];
    }
    double run = 0;
    for (int y = 0; y < h; y++) {
        run += rows[y];
        d->marginal[y] = d->total > 0 ? (float)(run / d->total) : (float)(y + 1) / h;
        for (int x = 0; x < w; x++)
            d->pdf[(size_t)y * w + x] = d->total > 0 ? (float)(lum[(size_t)y * w + x] / d->total) : 0.0f;
    }
    d->marginal[h - 1] = 1;
    free(lum), free(rows);
    return true;
}

void em_env_distribution_free(em_env_distribution *d) {
    free(d->conditional), free(d->pdf), free(d->marginal);
    memset(d, 0, sizeof *d);
}

/* the first index whose CDF value exceeds xi (the GLSL's binary search) */
static int cdf_search(const float *cdf, int n, double xi) {
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (cdf[mid] > xi) hi = mid;
        else lo = mid + 1;
    }
    return lo;
}

double em_env_distribution_sample(const em_env_distribution *d, double xi1, double xi2, double dir[3]) {
    int y = cdf_search(d->marginal, d->h, xi1);
    double m0 = y ? d->marginal[y - 1] : 0, m1 = d->marginal[y];
    double t = m1 > m0 ? (xi1 - m0) / (m1 - m0) : 0.5;
    const float *row = d->conditional + (size_t)y * d->w;
    int x = cdf_search(row, d->w, xi2);
    double c0 = x ? row[x - 1] : 0, c1 = row[x];
    double s = c1 > c0 ? (xi2 - c0) / (c1 - c0) : 0.5;
    double ct0 = cos(M_PI * y / d->h), ct1 = cos(M_PI * (y + 1) / d->h), ct = ct0 + t * (ct1 - ct0);
    em_latlong_dir((x + s) / d->w, acos(ct < -1 ? -1 : ct > 1 ? 1 : ct) / M_PI, dir);
    return d->pdf[(size_t)y * d->w + x];
}

double em_env_distribution_pdf(const em_env_distribution *d, const double dir[3]) {
    double u, v;
    em_dir_latlong(dir, &u, &v);
    int x = (int)(u * d->w), y = (int)(v * d->h);
    x = x < 0 ? 0 : x >= d->w ? d->w - 1 : x;
    y = y < 0 ? 0 : y >= d->h ? d->h - 1 : y;
    return d->pdf[(size_t)y * d->w + x];
}

/* ---------------------------------------------------------------- procedural sky */

void em_sky_default(em_sky *s) {
    s->sun_elevation_deg = 35;
    s->sun_azimuth_deg = 60;
    s->sun_irradiance = 3;
    s->sun_radius_deg = 1.5f;
    s->ground[0] = 0.10f, s->ground[1] = 0.09f, s->ground[2] = 0.08f;
}

void em_sky_sun(const em_sky *s, double dir[3], double *radius, double radiance[3]) {
    double e = s->sun_elevation_deg * M_PI / 180, a = s->sun_azimuth_deg * M_PI / 180;
    dir[0] = cos(e) * sin(a);
    dir[1] = sin(e);
    dir[2] = cos(e) * cos(a);
    double r = s->sun_radius_deg * M_PI / 180, omega = 2 * M_PI * (1 - cos(r));
    static const double sun_col[3] = {1.0, 0.95, 0.88};
    for (int c = 0; c < 3; c++) radiance[c] = s->sun_irradiance > 0 ? s->sun_irradiance / omega * sun_col[c] : 0.0;
    *radius = r;
}

/* A simple analytic clear sky: zenith-to-horizon gradient, a brighter halo around the sun, the
 * ground (em_sky.ground) below the horizon, reached through a haze that continues the horizon's
 * colour (continuous at the horizon: a darker line there showed as a dark band under it), and
 * the sun as a disk of uniform radiance E/Ω. */
void em_sky_radiance(const em_sky *s, const double d[3], double out[3]) {
    static const double zenith[3] = {0.16, 0.30, 0.72}, horizon[3] = {0.70, 0.78, 0.92};
    const float *ground = s->ground;
    double sd[3], r, sun[3];
    em_sky_sun(s, sd, &r, sun);
    double y = d[1];
    double cos_sun = d[0] * sd[0] + d[1] * sd[1] + d[2] * sd[2];
    double angle = acos(cos_sun < -1 ? -1 : cos_sun > 1 ? 1 : cos_sun);
    for (int c = 0; c < 3; c++) {
        double sky;
        if (y >= 0) {
            double t = pow(1 - y, 4);
            sky = zenith[c] * (1 - t) + horizon[c] * t;
        } else {
            double t = exp(y * 25); /* a soft horizon line */
            sky = ground[c] * (1 - t) + horizon[c] * t;
        }
        double halo = (y > -0.05 ? 1.0 : 0.0) * (0.6 * exp(-angle * 8) + 0.15 * exp(-angle * 1.5));
        static const double halo_col[3] = {1.0, 0.9, 0.75};
        out[c] = sky + halo * halo_col[c];
    }
    if (angle < r && s->sun_irradiance > 0)
        for (int c = 0; c < 3; c++) out[c] += sun[c];
}

/* The sky of one texel centre with the row's terms precomputed: em_sky_radiance's expressions,
 * in the same order (the same doubles), without the sun disk (the caller sub-samples texels near
 * it through em_sky_radiance). */
typedef struct {
    double y, sky[3]; /* per row: the direction's y and the gradient */
    bool halo_on;
} sky_row;

static void sky_row_init(const em_sky *s, double y, sky_row *r) {
    static const double zenith[3] = {0.16, 0.30, 0.72}, horizon[3] = {0.70, 0.78, 0.92};
    const float *ground = s->ground;
    r->y = y;
    r->halo_on = y > -0.05;
    for (int c = 0; c < 3; c++) {
        if (y >= 0) {
            double t = pow(1 - y, 4);
            r->sky[c] = zenith[c] * (1 - t) + horizon[c] * t;
        } else {
            double t = exp(y * 25);
            r->sky[c] = ground[c] * (1 - t) + horizon[c] * t;
        }
    }
}

void em_sky_latlong(const em_sky *s, int w, int h, em_image *out) {
    static const double halo_col[3] = {1.0, 0.9, 0.75};
    out->w = w;
    out->h = h;
    out->px = malloc((size_t)w * h * 4 * sizeof(float));
    double sd[3], r, sun[3];
    em_sky_sun(s, sd, &r, sun);
    double texel = M_PI / h;
    /* each column's horizontal direction (em_latlong_dir on the horizon) and each row's sines,
     * computed once (start-up, issue 19: a third of the time it took when every texel called
     * em_latlong_dir and em_sky_radiance; same values) */
    double *col_x = malloc(2 * (size_t)w * sizeof(double)), *col_z = col_x + w;
    for (int x = 0; x < w; x++) {
        double e[3];
        em_latlong_dir((x + 0.5) / w, 0.5, e);
        col_x[x] = e[0], col_z[x] = e[2];
    }
    for (int y = 0; y < h; y++) {
        double theta = M_PI * ((y + 0.5) / h), st = sin(theta), ct = cos(theta);
        sky_row row;
        sky_row_init(s, ct, &row);
        for (int x = 0; x < w; x++) {
            double d[3] = {st * col_x[x], ct, st * col_z[x]}, c[3] = {0, 0, 0};
            double cs = d[0] * sd[0] + d[1] * sd[1] + d[2] * sd[2];
            double angle = acos(cs < -1 ? -1 : cs > 1 ? 1 : cs);
            /* near the sun disk: 8×8 sub-samples so the disk's energy does not depend on
             * where it falls on the texel grid */
            int k = angle < r + 3 * texel / fmax(sin((y + 0.5) / h * M_PI), 0.05) ? 8 : 1;
            if (k == 1) {
                double halo = (row.halo_on ? 1.0 : 0.0) * (0.6 * exp(-angle * 8) + 0.15 * exp(-angle * 1.5));
                /* (the disk is inside the sub-sampled ring: none here) */
                for (int q = 0; q < 3; q++) c[q] = row.sky[q] + halo * halo_col[q];
            } else {
                for (int j = 0; j < k; j++)
                    for (int i = 0; i < k; i++) {
                        double e[3], v[3];
                        em_latlong_dir((x + (i + 0.5) / k) / w, (y + (j + 0.5) / k) / h, e);
                        em_sky_radiance(s, e, v);
                        for (int q = 0; q < 3; q++) c[q] += v[q] / (k * k);
                    }
            }
            float *p = out->px + ((size_t)y * w + x) * 4;
            for (int q = 0; q < 3; q++) p[q] = (float)fmin(c[q], EM_HALF_MAX);
            p[3] = 1;
        }
    }
    free(col_x);
}

/* ---------------------------------------------------------------- lat-long → base cube on the CPU */

void em_latlong_mips(const em_image *img, em_image *levels, int max_levels, int *count) {
    int n = 0, w = img->w, h = img->h;
    levels[n++] = (em_image){w, h, img->px}; /* level 0 is the image itself (not copied) */
    while ((w > 1 || h > 1) && n < max_levels) {
        const em_image *a = &levels[n - 1];
        int nw = w > 1 ? w / 2 : 1, nh = h > 1 ? h / 2 : 1;
        em_image b = {nw, nh, malloc((size_t)nw * nh * 4 * sizeof(float))};
        if (!b.px) break; /* out of memory: the levels made so far */
        /* a 2×2 (or 2×1) box: what glGenerateMipmap's linear blit gives for power-of-two sizes */
        for (int y = 0; y < nh; y++)
            for (int x = 0; x < nw; x++) {
                int x0 = w > 1 ? 2 * x : x, x1 = w > 1 ? 2 * x + 1 : x, y0 = h > 1 ? 2 * y : y, y1 = h > 1 ? 2 * y + 1 : y;
                const float *p00 = a->px + ((size_t)y0 * w + x0) * 4, *p01 = a->px + ((size_t)y0 * w + x1) * 4;
                const float *p10 = a->px + ((size_t)y1 * w + x0) * 4, *p11 = a->px + ((size_t)y1 * w + x1) * 4;
                float *q = b.px + ((size_t)y * nw + x) * 4;
                for (int c = 0; c < 4; c++) q[c] = 0.25f * (p00[c] + p01[c] + p10[c] + p11[c]);
            }
        levels[n++] = b;
        w = nw, h = nh;
    }
    *count = n;
}

/* Bilinear lookup of level L at (u, v): u wraps (GL_REPEAT), v clamps to the edge. */
static void latlong_bilinear(const em_image *L, double u, double v, double out[3]) {
    double x = u * L->w - 0.5, y = v * L->h - 0.5;
    double fx = floor(x), fy = floor(y), ax = x - fx, ay = y - fy;
    int x0 = (int)fx, y0 = (int)fy;
    if (x0 < -1 || x0 >= L->w) x0 = ((x0 % L->w) + L->w) % L->w; /* u outside [0, 1]: wrap it first */
    int xs[2] = {x0 < 0 ? x0 + L->w : x0, x0 + 1 >= L->w ? x0 + 1 - L->w : x0 + 1};
    int ys[2] = {y0 < 0 ? 0 : y0 >= L->h ? L->h - 1 : y0, y0 + 1 < 0 ? 0 : y0 + 1 >= L->h ? L->h - 1 : y0 + 1};
    double wx[2] = {1 - ax, ax}, wy[2] = {1 - ay, ay};
    out[0] = out[1] = out[2] = 0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            const float *p = L->px + ((size_t)ys[j] * L->w + xs[i]) * 4;
            double wgt = wx[i] * wy[j];
            for (int c = 0; c < 3; c++) out[c] += wgt * p[c];
        }
}

/* envmap_to_cube.frag and envmap_downsample.frag for a lat-long source, on the CPU: level 0 texel
 * = the mean of K×K sub-samples, each a trilinear lookup (GL_LINEAR_MIPMAP_LINEAR; lod ≤ 0
 * magnifies) at the level whose texel solid angle matches the sub-sample's; level l = the
 * solid-angle-weighted mean of its 2×2 texels in level l − 1. */
void em_latlong_to_cube_levels(const em_image *mips, int mip_count, int size, int levels, float **out) {
    const int K = 4;
    const double texel_v = M_PI / mips[0].h;
    for (int l = 0; l < levels; l++) out[l] = malloc((size_t)6 * (size >> l) * (size >> l) * 4 * sizeof(float));
    for (int f = 0; f < 6; f++)
        for (int y = 0; y < size; y++)
            for (int x = 0; x < size; x++) {
                double sum[3] = {0, 0, 0};
                for (int j = 0; j < K; j++)
                    for (int i = 0; i < K; i++) {
                        double s = (x + (i + 0.5) / K) / size, t = (y + (j + 0.5) / K) / size, d[3], u, v;
                        em_cube_dir(f, s, t, d);
                        double a = 2 * s - 1, b = 2 * t - 1, r2 = 1 + a * a + b * b;
                        double omega = (4.0 / ((double)size * K * size * K)) / (r2 * sqrt(r2));
                        em_dir_latlong(d, &u, &v);
                        /* sin θ from d (unit) rather than sin(v π); lod = min(½ log2(ω/ω_src), log2(√ω/τ))
                         * = ½ log2(ω / max(ω_src, τ²)): one log2, none where it magnifies (lod ≤ 0) */
                        double sin_theta = sqrt(fmax(0.0, 1 - d[1] * d[1]));
                        double omega_src = (2 * M_PI / mips[0].w) * texel_v * fmax(sin_theta, 1e-6);
                        double footprint = fmax(omega_src, texel_v * texel_v);
                        double lod = omega > footprint ? fmin(0.5 * log2(omega / footprint), mip_count - 1) : 0.0;
                        int l0 = (int)floor(lod), l1 = l0 + 1 < mip_count ? l0 + 1 : l0;
                        double fr = lod - l0, c0[3], c1[3];
                        latlong_bilinear(&mips[l0], u, v, c0);
                        if (fr > 0) latlong_bilinear(&mips[l1], u, v, c1);
                        else c1[0] = c1[1] = c1[2] = 0;
                        for (int c = 0; c < 3; c++) sum[c] += c0[c] * (1 - fr) + c1[c] * fr;
                    }
                float *q = out[0] + (((size_t)f * size + y) * size + x) * 4;
                for (int c = 0; c < 3; c++) q[c] = (float)fmin(sum[c] / (K * K), EM_HALF_MAX);
                q[3] = 1;
            }
    for (int l = 1; l < levels; l++) {
        int s = size >> l, fine = 2 * s;
        for (int f = 0; f < 6; f++)
            for (int y = 0; y < s; y++)
                for (int x = 0; x < s; x++) {
                    double sum[3] = {0, 0, 0}, weight = 0;
                    for (int j = 0; j < 2; j++)
                        for (int i = 0; i < 2; i++) {
                            const float *p = out[l - 1] + (((size_t)f * fine + 2 * y + j) * fine + 2 * x + i) * 4;
                            double o = em_texel_solid_angle(fine, 2 * x + i, 2 * y + j);
                            for (int c = 0; c < 3; c++) sum[c] += p[c] * o;
                            weight += o;
                        }
                    float *q = out[l] + (((size_t)f * s + y) * s + x) * 4;
                    for (int c = 0; c < 3; c++) q[c] = (float)(sum[c] / weight);
                    q[3] = 1;
                }
    }
}

/* ---------------------------------------------------------------- hashing */

uint64_t em_hash(const void *data, size_t bytes, uint64_t h) {
    const unsigned char *p = data;
    h ^= 0x9E3779B97F4A7C15ull + bytes;
    size_t i = 0;
    for (; i + 8 <= bytes; i += 8) {
        uint64_t w;
        memcpy(&w, p + i, 8);
        w *= 0xff51afd7ed558ccdull;
        w ^= w >> 33;
        h = (h ^ w) * 0xc4ceb9fe1a85ec53ull;
        h ^= h >> 29;
    }
    for (; i < bytes; i++) h = (h ^ p[i]) * 0x100000001b3ull;
    h ^= h >> 32;
    return h;
}
