/* How blinn-gloss describes itself to light integrators (the SDK's lobe contract: GGX lobes),
 * derived from the formulas by quadrature (plugins/phong/README.md, "Lobes"):
 *
 *   phong_lobe_fit mixtures   the best least-squares fit of Blinn's D by w₁·D_GGX(α₁) + w₂·D_GGX(α₂),
 *                             w ≥ 0, in solid-angle measure, per gloss: it is one lobe
 *   phong_lobe_fit alpha      GGX α against the Blinn power p: Walter's √(2/(p+2)), the median
 *                             match used (sl_lobe_blinn_alpha), and the α minimising the L1,
 *                             Hellinger and KL distances between the two normalised D's
 *   phong_lobe_fit weight     the least-squares fit in phong_lobe_weight (phong_brdf.glsl): the
 *                             lobe weight that gives the model's directional albedo, printed as
 *                             GLSL, with its error over the fitted grid and a finer one
 *
 * D_Blinn(θ) = (p+2)/(2π) cos^p θ and D_GGX(θ; α) = α²/(π cos⁴θ (α² + tan²θ)²) both integrate to 1
 * against cos θ dω. The model's specular is F·k_s·(p+1)/(2π)·(n·h)^p·(n·l) per unit irradiance;
 * a GGX lobe's is weight·F·D·G₁(v)G₁(l)/(4 n·v) (Smith, separable: envmap's LUT, ggx_brdf.glsl). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static double d_blinn(double c, double p) { return c > 0 ? (p + 2) / (2 * M_PI) * pow(c, p) : 0; }
static double d_ggx(double c, double a) {
    if (c <= 0) return 0;
    double d = c * c * (a * a - 1) + 1;
    return a * a / (M_PI * d * d);
}
static double smith_g1(double c, double a) {
    if (c <= 0) return 0;
    return 2 / (1 + sqrt(1 + a * a * (1 - c * c) / (c * c)));
}
static double walter_alpha(double p) { return sqrt(2 / (p + 2)); }
/* the GGX α whose D has Blinn's median: half the projected area within θ½ of the normal,
 * 1 − cos^(p+2) θ½ = ½ and tan²θ½ / (α² + tan²θ½) = ½ */
static double median_alpha(double p) { return sqrt(exp2(2 / (p + 2)) - 1); }

/* ---- directional albedos: ∫ f cos θ_l dl over the hemisphere, by quadrature over h ------------
 * l = reflect(−v, h), dl = 4 (v·h) dω_h; θ_h = atan(k·x/(1−x)) spreads the nodes over the lobe of
 * width k and out to the horizon (GGX's long tails) */
enum { BLINN, GGX };
static double albedo(int model, double mu, double p, double a) {
    const int nt = 300, np = 96;
    double v[3] = {sqrt(1 - mu * mu), 0, mu}, k = model == BLINN ? walter_alpha(p) : a, sum = 0;
    for (int i = 0; i < nt; i++) {
        double t = (i + 0.5) / nt, x = t / (1 - t), th = atan(k * x);
        double dth = k / (1 + k * k * x * x) / ((1 - t) * (1 - t)) / nt, ct = cos(th), st = sin(th);
        for (int j = 0; j < np; j++) {
            double ph = (j + 0.5) / np * M_PI, h[3] = {st * cos(ph), st * sin(ph), ct};
            double vh = v[0] * h[0] + v[2] * h[2], ml = 2 * vh * ct - mu;
            if (vh <= 0 || ml <= 0) continue;
            double f = model == BLINN ? (p + 1) / (2 * M_PI) * pow(ct, p) * ml * 4 * vh
                                      : d_ggx(ct, a) * smith_g1(mu, a) * smith_g1(ml, a) * vh / mu;
            sum += f * st * dth * (2 * M_PI / np); /* φ over [0, π], doubled */
        }
    }
    return sum;
}

/* ---- distances between D's over θ ∈ [0, π/2] ---------------------------------------------- */
#define NQ 4000
static double theta_cos[NQ], theta_w[NQ]; /* cos θ, sin θ dθ dφ integrated over φ */
static void init_theta(void) {
    for (int i = 0; i < NQ; i++) {
        double th = (i + 0.5) * (M_PI / 2) / NQ;
        theta_cos[i] = cos(th), theta_w[i] = sin(th) * (M_PI / 2) / NQ * 2 * M_PI;
    }
}
enum { L1, HELLINGER, KL };
static double distance(int kind, double p, double a) {
    double s = 0;
    for (int i = 0; i < NQ; i++) {
        double c = theta_cos[i], b = d_blinn(c, p) * c, g = d_ggx(c, a) * c; /* densities in dω */
        if (kind == L1) s += fabs(b - g) * theta_w[i];
        else if (kind == HELLINGER) s += (sqrt(b) - sqrt(g)) * (sqrt(b) - sqrt(g)) * theta_w[i];
        else if (b > 0) s += b * log(b / g) * theta_w[i];
    }
    return s;
}
static double argmin_alpha(int kind, double p) { /* golden section over α/α_Walter ∈ [0.3, 1.5] */
    double lo = 0.3, hi = 1.5, g = (sqrt(5) - 1) / 2, aw = walter_alpha(p);
    for (int it = 0; it < 60; it++) {
        double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
        if (distance(kind, p, m1 * aw) < distance(kind, p, m2 * aw)) hi = m2;
        else lo = m1;
    }
    return 0.5 * (lo + hi) * aw;
}

static const double glosses[] = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9};
#define NGLOSS (int)(sizeof glosses / sizeof glosses[0])

static void table_alpha(void) {
    printf("| gloss | p | Walter √(2/(p+2)) | median (used) | L1 | Hellinger | KL(Blinn‖GGX) | L1 distance: Walter | median |\n");
    printf("|---|---|---|---|---|---|---|---|---|\n");
    for (int g = 0; g < NGLOSS; g++) {
        double p = exp2(12 * glosses[g]), aw = walter_alpha(p), am = median_alpha(p);
        printf("| %.1f | %.1f | %.4f | %.4f (%.3f×) | %.3f× | %.3f× | %.3f× | %.3f | %.3f |\n", glosses[g], p, aw, am, am / aw,
               argmin_alpha(L1, p) / aw, argmin_alpha(HELLINGER, p) / aw, argmin_alpha(KL, p) / aw, distance(L1, p, aw),
               distance(L1, p, am));
    }
}

/* ---- two GGX lobes: least squares in solid angle, non-negative weights -------------------- */
/* for fixed α₁, α₂ the best w ≥ 0 solve a 2 × 2 non-negative least-squares problem */
static double lsq_pair(const double *b, const double *g1, const double *g2, double *w1, double *w2) {
    double a11 = 0, a12 = 0, a22 = 0, r1 = 0, r2 = 0, bb = 0;
    for (int i = 0; i < NQ; i++) {
        double w = theta_w[i];
        a11 += g1[i] * g1[i] * w, a12 += g1[i] * g2[i] * w, a22 += g2[i] * g2[i] * w;
        r1 += g1[i] * b[i] * w, r2 += g2[i] * b[i] * w, bb += b[i] * b[i] * w;
    }
    double det = a11 * a22 - a12 * a12, x1 = -1, x2 = -1;
    if (det > 1e-12 * a11 * a22) x1 = (r1 * a22 - r2 * a12) / det, x2 = (r2 * a11 - r1 * a12) / det;
    if (!(x1 >= 0 && x2 >= 0)) { /* an edge of the cone: one lobe alone */
        double e1 = bb - r1 * r1 / a11, e2 = bb - r2 * r2 / a22;
        if (e1 <= e2) x1 = r1 / a11, x2 = 0;
        else x1 = 0, x2 = r2 / a22;
    }
    *w1 = x1, *w2 = x2;
    return bb - 2 * (x1 * r1 + x2 * r2) + x1 * x1 * a11 + 2 * x1 * x2 * a12 + x2 * x2 * a22;
}
static void table_mixtures(void) {
    enum { NK = 121 }; /* α/α_Walter from 0.3 to 2.1 */
    static double b[NQ], g[NK][NQ];
    printf("| gloss | one lobe: w, α/α_W, rel. L2 | two lobes (w ≥ 0): w₁, α₁/α_W, w₂, α₂/α_W, rel. L2 |\n|---|---|---|\n");
    for (int gi = 0; gi < NGLOSS; gi++) {
        double p = exp2(12 * glosses[gi]), aw = walter_alpha(p), norm = 0;
        for (int i = 0; i < NQ; i++) b[i] = d_blinn(theta_cos[i], p), norm += b[i] * b[i] * theta_w[i];
        for (int k = 0; k < NK; k++)
            for (int i = 0; i < NQ; i++) g[k][i] = d_ggx(theta_cos[i], (0.3 + 0.015 * k) * aw);
        double best1 = INFINITY, best2 = INFINITY, w1b = 0, k1b = 0, u1 = 0, u2 = 0, q1 = 0, q2 = 0;
        for (int i = 0; i < NK; i++)
            for (int j = i; j < NK; j++) {
                double w1, w2, e = lsq_pair(b, g[i], g[j], &w1, &w2);
                if (e < best2) best2 = e, u1 = w1, u2 = w2, q1 = 0.3 + 0.015 * i, q2 = 0.3 + 0.015 * j;
                if (j == i && e < best1) best1 = e, w1b = w1 + w2, k1b = 0.3 + 0.015 * i;
            }
        printf("| %.1f | %.3f, %.3f, %.4f | %.3f, %.3f, %.3f, %.3f, %.4f |\n", glosses[gi], w1b, k1b, sqrt(best1 / norm), u1, q1,
               u2, q2, sqrt(best2 / norm));
    }
}

/* ---- the weight: directional albedo of the model over that of the GGX lobe ----------------
 * weight(μ, p) = R_Blinn(μ, p) / E_GGX(μ, α), α = median_alpha(p), fitted as
 *   weight = 4μ²/G₁(μ, α)² · exp(Σ c_ij α^i t^j),  t = α/(μ' + α) − α/(1 + α),  μ' = max(μ, 0.1),
 * i + j ≤ 4, (i, j) ≠ (0, 0): 4μ²/G₁² is the narrow-lobe limit (α → 0: the exponent → 0), t is 0 at
 * μ = 1 and grows where the lobe reaches the horizon (μ ≲ α) */
#define DEG 4
#define MU_MIN 0.1
static int basis(double a, double mu, double *f) {
    double m = fmax(mu, MU_MIN), t = a / (m + a) - a / (1 + a);
    int n = 0;
    for (int i = 0; i <= DEG; i++)
        for (int j = 0; j <= DEG - i; j++)
            if (i || j) f[n++] = pow(a, i) * pow(t, j);
    return n;
}
static double target(double mu, double p) { /* log(weight / (4μ²/G₁²)) */
    double a = median_alpha(p), g = smith_g1(mu, a);
    return log(albedo(BLINN, mu, p, 0) / albedo(GGX, mu, p, a) * g * g / (4 * mu * mu));
}
static void solve(int n, double *m, double *x) { /* Gauss–Jordan with partial pivoting, m n×n */
    for (int i = 0; i < n; i++) {
        int piv = i;
        for (int r = i + 1; r < n; r++)
            if (fabs(m[r * n + i]) > fabs(m[piv * n + i])) piv = r;
        for (int c = 0; c < n; c++) { double t = m[i * n + c]; m[i * n + c] = m[piv * n + c]; m[piv * n + c] = t; }
        double t = x[i]; x[i] = x[piv]; x[piv] = t;
        for (int r = 0; r < n; r++) {
            if (r == i) continue;
            double f = m[r * n + i] / m[i * n + i];
            for (int c = 0; c < n; c++) m[r * n + c] -= f * m[i * n + c];
            x[r] -= f * x[i];
        }
    }
    for (int i = 0; i < n; i++) x[i] /= m[i * n + i];
}
/* p on the gloss scale from 0 (p = 0) to 1 (p = 4095), μ from MU_MIN to 1 */
static double grid_p(int i, int n) { return exp2(12.0 * i / (n - 1)) - 1; }
static double grid_mu(int j, int n) { return MU_MIN + (1 - MU_MIN) * j / (n - 1); }
static void report(const double *c, int n, int np, int nm, const char *what) {
    double f[32], rms = 0, worst = 0, wp = 0, wmu = 0;
    for (int i = 0; i < np; i++)
        for (int j = 0; j < nm; j++) {
            double p = grid_p(i, np), mu = grid_mu(j, nm), s = 0;
            basis(median_alpha(p), mu, f);
            for (int k = 0; k < n; k++) s += c[k] * f[k];
            double e = fabs(exp(s - target(mu, p)) - 1);
            rms += e * e;
            if (e > worst) worst = e, wp = p, wmu = mu;
        }
    printf("%s (%d × %d): relative error of the weight rms %.4f, max %.4f (p %.1f, μ %.2f)\n", what, np, nm,
           sqrt(rms / (np * nm)), worst, wp, wmu);
}
static void fit_weight(void) {
    enum { NP = 25, NM = 19 };
    double f[32], ata[32 * 32] = {0}, atb[32] = {0};
    int n = basis(0.1, 0.5, f);
    for (int i = 0; i < NP; i++)
        for (int j = 0; j < NM; j++) {
            double p = grid_p(i, NP), mu = grid_mu(j, NM), y = target(mu, p);
            basis(median_alpha(p), mu, f);
            for (int r = 0; r < n; r++) {
                atb[r] += f[r] * y;
                for (int c = 0; c < n; c++) ata[r * n + c] += f[r] * f[c];
            }
        }
    solve(n, ata, atb);
    printf("// phong_lobe_fit weight: c_ij for α^i t^j, i + j ≤ %d, in the order i = 0…%d, j = 0…%d − i\n", DEG, DEG, DEG);
    printf("const float PHONG_LOBE_FIT[%d] = float[](", n);
    for (int k = 0; k < n; k++) printf("%s%.5f", k ? ", " : "", atb[k]);
    printf(");\n");
    report(atb, n, NP, NM, "fitted grid");
    report(atb, n, 2 * NP - 1, 2 * NM - 1, "finer grid");
}

int main(int argc, char **argv) {
    const char *what = argc > 1 ? argv[1] : "";
    init_theta();
    if (!strcmp(what, "mixtures")) table_mixtures();
    else if (!strcmp(what, "alpha")) table_alpha();
    else if (!strcmp(what, "weight")) fit_weight();
    else {
        fprintf(stderr, "usage: phong_lobe_fit mixtures | alpha | weight\n");
        return 2;
    }
    return 0;
}
