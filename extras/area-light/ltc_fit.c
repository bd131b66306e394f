/* area-light's LTC fit and its validation (Heitz, Dupuy, Hill, Neubelt 2016, §4: fit M per
 * roughness and view angle so that the LTC distribution matches the normalised cosine-weighted
 * BRDF). Written here: the BRDF is the ggx plugin's or the lobe contract's Blinn-Phong lobe
 * (ltc.h), the optimiser a Nelder–Mead simplex (Nelder & Mead 1965), the error the L³ difference
 * of the two normalised distributions estimated with samples of both (multiple importance
 * sampling, balance heuristic), as the paper's fit does.
 *
 *   ltc_fit fit [--lobe ggx|blinn-phong] [--error l3|regions] [--size N] [--samples S] [-o FILE]
 *                    fits the table, writes FILE (ltc_ggx.txt, ltc_blinn_phong.txt); the error
 *                    minimised: the paper's L³ (GGX's table) or the regions error (below; the
 *                    Blinn-Phong table's, whose falloff an LTC cannot take: README)
 *   ltc_fit validate FILE [--lobe ggx|blinn-phong] [--samples S]
 *                    the table against a Monte Carlo integration of the BRDF over light
 *                    polygons (markdown)
 *
 * The table's frame: local x = the view direction's tangent component, z = the normal, so
 * v = (sin θ, 0, cos θ). M = F · [[m00, 0, m02], [0, m11, 0], [0, 0, 1]] with F the rotation
 * (about y) that takes z to the lobe's average direction; three parameters per cell. */
#include "ltc.h"
#include <stdint.h>

/* ---- deterministic low-discrepancy samples (stratified grid, jittered by a fixed hash) ------ */
static double hash01(uint32_t x) {
    x ^= x >> 16; x *= 0x7feb352dU; x ^= x >> 15; x *= 0x846ca68bU; x ^= x >> 16;
    return (x >> 8) * (1.0 / 16777216.0);
}

/* ---- moments of the BRDF lobe (importance sampled) ----------------------------------------- */
typedef struct moments { double norm, fresnel; al_v3 avg; } moments;
static moments brdf_moments(al_v3 v, const al_lobe *k, int s) {
    moments r = {0};
    for (int j = 0; j < s; j++)
        for (int i = 0; i < s; i++) {
            double u1 = (i + hash01(i * 7919u + j * 104729u + 1)) / s, u2 = (j + hash01(i * 15485863u + j * 32452843u + 2)) / s;
            al_v3 l;
            double pdf;
            if (!al_lobe_sample(k, v, u1, u2, &l, &pdf) || !(pdf > 0)) continue;
            double w = al_lobe_fcos(k, v, l) / pdf;
            al_v3 h = al_norm(al_add(v, l));
            double m = 1 - al_dot(v, h), m5 = m * m * m * m * m;
            r.norm += w;
            r.fresnel += w * m5;
            r.avg = al_add(r.avg, al_mul(l, w));
        }
    r.norm /= (double)s * s;
    r.fresnel /= (double)s * s;
    r.avg = al_norm(r.avg);
    return r;
}

/* ---- the LTC distribution ------------------------------------------------------------------ */
typedef struct ltc { double m[3][3], inv[3][3], det_inv; } ltc;

static bool mat_inverse(const double m[3][3], double inv[3][3], double *det_out) {
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if (!(fabs(det) > 1e-300)) return false;
    double id = 1 / det;
    inv[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * id;
    inv[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * id;
    inv[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * id;
    inv[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * id;
    inv[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * id;
    inv[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * id;
    inv[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * id;
    inv[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * id;
    inv[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * id;
    *det_out = 1 / det;
    return true;
}
static al_v3 mat_apply(const double m[3][3], al_v3 x) {
    return al_v(m[0][0] * x.x + m[0][1] * x.y + m[0][2] * x.z, m[1][0] * x.x + m[1][1] * x.y + m[1][2] * x.z,
                m[2][0] * x.x + m[2][1] * x.y + m[2][2] * x.z);
}

/* M = F · P, F = rotation about y taking z to `avg` (in the x–z plane). */
static bool ltc_make(ltc *t, al_v3 avg, const double p[3]) {
    double c = avg.z, s = avg.x; /* avg = (sin φ, 0, cos φ) */
    double F[3][3] = {{c, 0, s}, {0, 1, 0}, {-s, 0, c}};
    double P[3][3] = {{p[0], 0, p[2]}, {0, p[1], 0}, {0, 0, 1}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) t->m[i][j] = F[i][0] * P[0][j] + F[i][1] * P[1][j] + F[i][2] * P[2][j];
    return p[0] > 0 && p[1] > 0 && mat_inverse(t->m, t->inv, &t->det_inv);
}
static double ltc_eval(const ltc *t, al_v3 w) {
    al_v3 o = mat_apply(t->inv, w);
    double len = al_len(o);
    if (o.z <= 0) return 0;
    return (o.z / len) / M_PI * fabs(t->det_inv) / (len * len * len);
}
static al_v3 ltc_sample(const ltc *t, double u1, double u2) {
    double r = sqrt(u1), phi = 2 * M_PI * u2;
    al_v3 o = al_v(r * cos(phi), r * sin(phi), sqrt(fmax(0, 1 - u1)));
    return al_norm(mat_apply(t->m, o));
}

/* The regions error (--error regions): what lights see of the lobe. In the plane tangent to the
 * unit sphere at the lobe's average direction w (x along the plane of incidence, y across), the
 * share of the normalised lobe in half-planes x cosφ + y sinφ ≥ s (the edge of a large light: 8
 * directions φ, 6 offsets s) and in centred squares (small lights), offsets and sizes in units of
 * the lobe's spread σ (the rms tangent-plane radius of its samples, at most 2). The targets come
 * from the BRDF's own samples, once per cell; the LTC's shares are exact (its polygon integral). */
#define REGION_DIRS 8
#define REGION_OFFSETS 6
#define REGION_SQUARES 3
#define REGIONS (REGION_DIRS * REGION_OFFSETS + REGION_SQUARES)
typedef struct regions { al_v3 poly[REGIONS][4]; double target[REGIONS]; } regions;

static void make_regions(regions *r, al_v3 v, const al_lobe *k, al_v3 w, double norm, int s) {
    al_v3 t1 = al_v(w.z, 0, -w.x), t2 = al_v(0, 1, 0);
    double half[REGIONS][4]; /* (cos φ, sin φ, s) of a half-plane, or (0, 0, h) of a square: h in [3] */
    /* the spread */
    double r2 = 0, wsum = 0;
    for (int j = 0; j < s; j++)
        for (int i = 0; i < s; i++) {
            double u1 = (i + hash01(i * 7919u + j * 104729u + 5)) / s, u2 = (j + hash01(i * 15485863u + j * 32452843u + 6)) / s;
            al_v3 l;
            double pdf;
            if (!al_lobe_sample(k, v, u1, u2, &l, &pdf) || !(pdf > 0) || al_dot(l, w) <= 0) continue;
            double x = al_dot(l, t1) / al_dot(l, w), y = al_dot(l, t2) / al_dot(l, w), f = al_lobe_fcos(k, v, l) / pdf;
            r2 += f * fmin(x * x + y * y, 4), wsum += f;
        }
    double sigma = fmax(sqrt(r2 / fmax(wsum, 1e-300)), 1e-4);
    const double offsets[REGION_OFFSETS] = {-1, -0.5, 0, 0.5, 1, 2}, squares[REGION_SQUARES] = {0.5, 1, 2};
    const double R = 1e3; /* the plane's far edge: 89.94° from w */
    int n = 0;
    for (int d = 0; d < REGION_DIRS; d++)
        for (int o = 0; o < REGION_OFFSETS; o++, n++) {
            double phi = 2 * M_PI * d / REGION_DIRS, cs = cos(phi), sn = sin(phi), off = 0.7 * sigma * offsets[o];
            double uv[4][2] = {{off, -R}, {R, -R}, {R, R}, {off, R}};
            for (int q = 0; q < 4; q++) {
                double x = uv[q][0] * cs - uv[q][1] * sn, y = uv[q][0] * sn + uv[q][1] * cs;
                r->poly[n][q] = al_add(w, al_add(al_mul(t1, x), al_mul(t2, y)));
            }
            half[n][0] = cs, half[n][1] = sn, half[n][2] = off, half[n][3] = 0;
        }
    for (int q = 0; q < REGION_SQUARES; q++, n++) {
        double h = 0.7 * sigma * squares[q], uv[4][2] = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
        for (int c = 0; c < 4; c++) r->poly[n][c] = al_add(w, al_add(al_mul(t1, uv[c][0]), al_mul(t2, uv[c][1])));
        half[n][0] = half[n][1] = 0, half[n][2] = h, half[n][3] = 1;
    }
    /* the targets: the lobe's share in each region, by its own samples */
    memset(r->target, 0, sizeof r->target);
    for (int j = 0; j < s; j++)
        for (int i = 0; i < s; i++) {
            double u1 = (i + hash01(i * 2654435761u + j * 40503u + 7)) / s, u2 = (j + hash01(i * 97u + j * 2246822519u + 8)) / s;
            al_v3 l;
            double pdf;
            if (!al_lobe_sample(k, v, u1, u2, &l, &pdf) || !(pdf > 0) || al_dot(l, w) <= 0) continue;
            double x = al_dot(l, t1) / al_dot(l, w), y = al_dot(l, t2) / al_dot(l, w);
            double f = al_lobe_fcos(k, v, l) / pdf / norm / ((double)s * s);
            for (int q = 0; q < REGIONS; q++) {
                bool in = half[q][3] > 0 ? fabs(x) <= half[q][2] && fabs(y) <= half[q][2]
                                         : x * half[q][0] + y * half[q][1] >= half[q][2] && fabs(x) < R && fabs(y) < R;
                if (in) r->target[q] += f;
            }
        }
}

/* The error to minimise: the paper's L³ distance, or (regions != NULL) the regions error. */
typedef struct fit_ctx { al_v3 v, avg; al_lobe lobe; double norm; int s; const regions *regions; } fit_ctx;
static double regions_error(const fit_ctx *c, const ltc *t) {
    double sum = 0;
    for (int q = 0; q < REGIONS; q++) {
        al_v3 tv[4];
        for (int k = 0; k < 4; k++) tv[k] = mat_apply(t->inv, c->regions->poly[q][k]);
        double e = al_polygon_cos_integral(tv, 4) / M_PI - c->regions->target[q];
        sum += e * e;
    }
    return sum / REGIONS;
}
/* L³ error between the normalised BRDF lobe and the LTC, samples of both, balance heuristic. */
static double fit_error(const fit_ctx *c, const double p[3]) {
    ltc t;
    if (!ltc_make(&t, c->avg, p)) return 1e30;
    if (c->regions) return regions_error(c, &t);
    double sum = 0;
    for (int j = 0; j < c->s; j++)
        for (int i = 0; i < c->s; i++) {
            double u1 = (i + hash01(i * 2654435761u + j * 40503u + 3)) / c->s, u2 = (j + hash01(i * 97u + j * 2246822519u + 4)) / c->s;
            /* a sample of the LTC */
            al_v3 l = ltc_sample(&t, u1, u2);
            double pl = ltc_eval(&t, l), lb;
            double fb = al_lobe_fcos(&c->lobe, c->v, l) / c->norm, pb = al_lobe_pdf(&c->lobe, c->v, l);
            if (pl + pb > 0) { double e = fabs(fb - pl); sum += e * e * e / (pl + pb); }
            /* a sample of the BRDF */
            al_v3 l2;
            if (al_lobe_sample(&c->lobe, c->v, u1, u2, &l2, &lb) && lb > 0) {
                double f2 = al_lobe_fcos(&c->lobe, c->v, l2) / c->norm, p2 = ltc_eval(&t, l2);
                double e = fabs(f2 - p2);
                sum += e * e * e / (p2 + lb);
            }
        }
    return sum / (2.0 * c->s * c->s);
}

/* Nelder–Mead in 3 dimensions, relative initial steps. */
static double nelder_mead(const fit_ctx *c, double x[3], int iters) {
    double s[4][3], f[4];
    for (int k = 0; k < 4; k++) {
        for (int d = 0; d < 3; d++) s[k][d] = x[d];
        if (k) s[k][k - 1] += k - 1 == 2 ? 0.05 + 0.1 * fabs(x[2]) : 0.1 * fabs(x[k - 1]) + 1e-4;
        f[k] = fit_error(c, s[k]);
    }
    for (int it = 0; it < iters; it++) {
        /* order */
        for (int a = 0; a < 4; a++)
            for (int b = a + 1; b < 4; b++)
                if (f[b] < f[a]) {
                    double tf = f[a]; f[a] = f[b]; f[b] = tf;
                    for (int d = 0; d < 3; d++) { double t = s[a][d]; s[a][d] = s[b][d]; s[b][d] = t; }
                }
        if (fabs(f[3] - f[0]) <= 1e-12 * (fabs(f[0]) + 1e-20)) break;
        double cen[3] = {0}, xr[3], xe[3], xc[3];
        for (int k = 0; k < 3; k++)
            for (int d = 0; d < 3; d++) cen[d] += s[k][d] / 3;
        for (int d = 0; d < 3; d++) xr[d] = cen[d] + (cen[d] - s[3][d]);
        double fr = fit_error(c, xr);
        if (fr < f[0]) {
            for (int d = 0; d < 3; d++) xe[d] = cen[d] + 2 * (cen[d] - s[3][d]);
            double fe = fit_error(c, xe);
            if (fe < fr) { memcpy(s[3], xe, sizeof xe); f[3] = fe; }
            else { memcpy(s[3], xr, sizeof xr); f[3] = fr; }
        } else if (fr < f[2]) {
            memcpy(s[3], xr, sizeof xr); f[3] = fr;
        } else {
            bool outside = fr < f[3];
            for (int d = 0; d < 3; d++) xc[d] = outside ? cen[d] + 0.5 * (xr[d] - cen[d]) : cen[d] + 0.5 * (s[3][d] - cen[d]);
            double fc = fit_error(c, xc);
            if (fc < (outside ? fr : f[3])) { memcpy(s[3], xc, sizeof xc); f[3] = fc; }
            else
                for (int k = 1; k < 4; k++) {
                    for (int d = 0; d < 3; d++) s[k][d] = s[0][d] + 0.5 * (s[k][d] - s[0][d]);
                    f[k] = fit_error(c, s[k]);
                }
        }
    }
    int best = 0;
    for (int k = 1; k < 4; k++) if (f[k] < f[best]) best = k;
    memcpy(x, s[best], sizeof(double) * 3);
    return f[best];
}

/* --lobe NAME: false (with a message) when NAME is neither shape */
static bool parse_lobe(const char *name, bool *blinn_phong) {
    *blinn_phong = !strcmp(name, "blinn-phong");
    if (*blinn_phong || !strcmp(name, "ggx")) return true;
    fprintf(stderr, "ltc_fit: --lobe %s: expected ggx or blinn-phong\n", name);
    return false;
}

static int fit(int argc, char **argv) {
    int N = 64, S = 32;
    bool blinn_phong = false, by_regions = false;
    const char *out = NULL;
    for (int i = 2; i < argc; i++) {
        if (!strcmp(argv[i], "--lobe") && i + 1 < argc) { if (!parse_lobe(argv[++i], &blinn_phong)) return 2; }
        else if (!strcmp(argv[i], "--error") && i + 1 < argc && (!strcmp(argv[i + 1], "l3") || !strcmp(argv[i + 1], "regions")))
            by_regions = !strcmp(argv[++i], "regions");
        else if (!strcmp(argv[i], "--size") && i + 1 < argc) N = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--samples") && i + 1 < argc) S = atoi(argv[++i]);
        else if (!strcmp(argv[i], "-o") && i + 1 < argc) out = argv[++i];
        else { fprintf(stderr, "ltc_fit fit: unknown argument %s\n", argv[i]); return 2; }
    }
    if (N < 2 || N > 256 || S < 4 || S > 1024) { fprintf(stderr, "ltc_fit fit: --size 2..256, --samples 4..1024\n"); return 2; }
    if (!out) out = blinn_phong ? "ltc_blinn_phong.txt" : "ltc_ggx.txt";
    al_ltc_entry *tab = calloc((size_t)N * N, sizeof *tab);
    double (*params)[3] = calloc((size_t)N * N, sizeof *params);
    double worst = 0;
    /* from the roughest row down (the paper's order): each fit starts from its neighbour's */
    for (int i = N - 1; i >= 0; i--) {
        for (int j = 0; j < N; j++) {
            double a = al_table_alpha(i, N), ct = al_table_cos_theta(j, N);
            fit_ctx c = {.v = al_v(sqrt(fmax(0, 1 - ct * ct)), 0, ct), .lobe = al_lobe_make(blinn_phong, a), .s = S};
            moments lb = brdf_moments(c.v, &c.lobe, 2 * S);
            c.norm = lb.norm;
            c.avg = j == 0 ? al_v(0, 0, 1) : al_norm(al_v(lb.avg.x, 0, lb.avg.z));
            regions reg;
            if (by_regions) make_regions(&reg, c.v, &c.lobe, c.avg, c.norm, 4 * S), c.regions = &reg;
            double p[3];
            if (j > 0) memcpy(p, params[(j - 1) * N + i], sizeof p);
            else if (i < N - 1) memcpy(p, params[i + 1], sizeof p);
            else p[0] = p[1] = 1, p[2] = 0;
            if (j == 0) p[2] = 0, p[0] = p[1] = (p[0] + p[1]) / 2; /* isotropic at normal incidence */
            double e = nelder_mead(&c, p, 400);
            e = nelder_mead(&c, p, 200); /* restart: the simplex may have collapsed */
            if (e > worst) worst = e;
            memcpy(params[j * N + i], p, sizeof p);
            ltc t;
            ltc_make(&t, c.avg, p);
            double k = t.inv[1][1];
            al_ltc_entry *en = &tab[j * N + i];
            en->a = t.inv[0][0] / k, en->b = t.inv[0][2] / k, en->c = t.inv[2][0] / k, en->d = t.inv[2][2] / k;
            en->norm = lb.norm, en->fresnel = lb.fresnel;
        }
        fprintf(stderr, "\rltc_fit: alpha row %d/%d", N - i, N);
    }
    fprintf(stderr, "\n");
    FILE *f = fopen(out, "w");
    if (!f) { fprintf(stderr, "ltc_fit: cannot write %s\n", out); return 1; }
    if (blinn_phong)
        fprintf(f, "# area-light LTC table for the lobe contract's Blinn-Phong lobe ((p+1)/(2 pi) (n.h)^p (n.l),\n"
                   "# p = 2/log2(1 + alpha^2) - 2), fitted by\n");
    else
        fprintf(f, "# area-light LTC table for the ggx plugin's BRDF (GGX D, separable Smith G), fitted by\n");
    fprintf(f, "#   ltc_fit fit --lobe %s --error %s --size %d --samples %d -o %s\n", blinn_phong ? "blinn-phong" : "ggx",
            by_regions ? "regions" : "l3", N, S, out);
    fprintf(f, "# Rows: a b c d norm fresnel  with M^-1 = [[a,0,b],[0,1,0],[c,0,d]] (see ltc.h);\n");
    fprintf(f, "# entry (i, j) at line j*size+i: alpha = max((i/(size-1))^2, 2e-3), cos(theta_v) = max(1-(j/(size-1))^2, 1e-3)\n");
    fprintf(f, "size %d\n", N);
    for (int k = 0; k < N * N; k++)
        fprintf(f, "%.9g %.9g %.9g %.9g %.9g %.9g\n", tab[k].a, tab[k].b, tab[k].c, tab[k].d, tab[k].norm, tab[k].fresnel);
    fclose(f);
    fprintf(stderr, "ltc_fit: wrote %s (%dx%d), worst fit error %.3g\n", out, N, N, worst);
    free(tab);
    free(params);
    return 0;
}

/* ---- validation: the table against Monte Carlo over light polygons ------------------------- */

/* Ray from the origin along l against a convex polygon: true when it hits the polygon's plane
 * inside it, in front. */
static bool hits_polygon(al_v3 l, const al_v3 *p, int n) {
    al_v3 nrm = al_cross(al_sub(p[1], p[0]), al_sub(p[2], p[0]));
    double dn = al_dot(l, nrm);
    if (dn == 0) return false;
    double t = al_dot(p[0], nrm) / dn;
    if (t <= 0) return false;
    al_v3 x = al_mul(l, t);
    for (int i = 0; i < n; i++) {
        al_v3 e = al_sub(p[(i + 1) % n], p[i]);
        if (al_dot(al_cross(e, al_sub(x, p[i])), nrm) < 0) return false;
    }
    return true;
}

/* Monte Carlo estimate of ∫_P f cos dω: BRDF importance sampling with a ray–polygon test
 * (unbiased; independent of Lambert's formula and of the LTC). */
static double mc_polygon(al_v3 v, const al_lobe *lobe, const al_v3 *p, int n, long samples, double *stderr_out) {
    double sum = 0, sum2 = 0;
    uint32_t seed = 12345;
    for (long k = 0; k < samples; k++) {
        double u1 = hash01(seed++), u2 = hash01(seed++ ^ 0x9e3779b9u);
        al_v3 l;
        double pdf, w = 0;
        if (al_lobe_sample(lobe, v, u1, u2, &l, &pdf) && pdf > 0 && hits_polygon(l, p, n)) w = al_lobe_fcos(lobe, v, l) / pdf;
        sum += w;
        sum2 += w * w;
    }
    double mean = sum / samples;
    *stderr_out = sqrt(fmax(0, sum2 / samples - mean * mean) / samples);
    return mean;
}

static int validate(int argc, char **argv) {
    if (argc < 3) { fprintf(stderr, "usage: ltc_fit validate FILE [--lobe ggx|blinn-phong] [--samples S]\n"); return 2; }
    long S = 400000;
    bool blinn_phong = false;
    for (int i = 3; i < argc; i++) {
        if (!strcmp(argv[i], "--samples") && i + 1 < argc) S = atol(argv[++i]);
        else if (!strcmp(argv[i], "--lobe") && i + 1 < argc) { if (!parse_lobe(argv[++i], &blinn_phong)) return 2; }
        else { fprintf(stderr, "ltc_fit validate: unknown argument %s\n", argv[i]); return 2; }
    }
    al_ltc_table t;
    char err[512];
    if (!al_table_read(argv[2], &t, err, sizeof err)) { fprintf(stderr, "ltc_fit: %s\n", err); return 1; }
    const double roughness[] = {0.1, 0.25, 0.5, 0.75, 1.0};
    const double theta_deg[] = {0, 30, 60, 80};
    /* the light: a 1 m × 0.5 m rectangle at distance 2 m, centred on the mirror direction of v
     * ("mirror") or 45° away from it in azimuth ("side"), facing the shading point */
    printf("| roughness | θ_v | light | MC ∫_P f cos (±1σ) | LTC | relative error | error / ∫_Ω f cos |\n"
           "|---|---|---|---|---|---|---|\n");
    double worst_rel = 0, worst_norm = 0;
    for (size_t ir = 0; ir < sizeof roughness / sizeof *roughness; ir++)
        for (size_t it = 0; it < sizeof theta_deg / sizeof *theta_deg; it++)
            for (int side = 0; side < 2; side++) {
                double th = theta_deg[it] * M_PI / 180, a = fmax(roughness[ir] * roughness[ir], AL_MIN_ALPHA);
                al_v3 v = al_v(sin(th), 0, cos(th));
                double el = fmin(th, 70 * M_PI / 180), az = side ? M_PI * 0.75 : M_PI;
                al_v3 dir = al_v(sin(el) * cos(az), sin(el) * sin(az), cos(el)); /* mirror: -x side */
                al_v3 c = al_mul(dir, 2), ex = al_norm(al_cross(al_v(0, 0, 1), dir));
                if (al_len(al_cross(al_v(0, 0, 1), dir)) < 1e-6) ex = al_v(1, 0, 0);
                al_v3 ey = al_cross(dir, ex), p[4];
                al_light_polygon(c, ex, ey, 1.0, 0.5, false, 4, p);
                al_lobe k = al_lobe_make(blinn_phong, a);
                double se, mc = mc_polygon(v, &k, p, 4, S, &se);
                al_ltc_entry e = al_table_lookup(&t, a, cos(th));
                double ltc = e.norm * al_ltc_polygon(&e, p, 4);
                double rel = mc > 0 ? (ltc - mc) / mc : 0;
                double of_norm = (ltc - mc) / e.norm; /* as a fraction of the whole lobe's reflectance */
                if (fabs(rel) > worst_rel) worst_rel = fabs(rel);
                if (fabs(of_norm) > worst_norm) worst_norm = fabs(of_norm);
                char rough[32];
                snprintf(rough, sizeof rough, blinn_phong ? "%.2f (p %.0f)" : "%.2f", roughness[ir], k.power);
                printf("| %s | %.0f° | %s | %.5f (±%.5f) | %.5f | %+.1f%% | %+.2f%% |\n", rough, theta_deg[it],
                       side ? "side" : "mirror", mc, se, ltc, 100 * rel, 100 * of_norm);
            }
    printf("\nworst relative error %.1f%%, worst error as a fraction of the lobe's reflectance %.2f%% (%ld Monte Carlo "
           "samples per case)\n", 100 * worst_rel, 100 * worst_norm, S);
    free(t.e);
    return 0;
}

int main(int argc, char **argv) {
    if (argc >= 2 && !strcmp(argv[1], "fit")) return fit(argc, argv);
    if (argc >= 2 && !strcmp(argv[1], "validate")) return validate(argc, argv);
    fprintf(stderr, "usage: ltc_fit fit [--lobe ggx|blinn-phong] [--error l3|regions] [--size N] [--samples S] [-o FILE]\n"
                    "       ltc_fit validate FILE [--lobe ggx|blinn-phong] [--samples S]\n");
    return 2;
}
