/* envmap's fitted lobes: the real GGX lobe, the chain's lobes and the fit (lobe_fit.h). */
#include "lobe_fit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

struct em_lobe_ctx {
    int n;              /* directions */
    double *dir;        /* 3 per direction, in the frame of (μ) set by frame() */
    double *ring_theta; /* θ from r and dω per direction, fixed */
    double *dw;
    double *w_true, *k[EM_LOBE_TAPS];
    double mu, alpha; /* the (μ, α) w_true holds; mu < 0: none */
    double r[3], e[3], b[3], v[3];
};

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static double ggx_d(double nh, double a) {
    if (nh <= 0) return 0;
    double a2 = a * a, d = nh * nh * (a2 - 1) + 1;
    return a2 / (M_PI * d * d);
}

static double smith_g1(double nx, double a) {
    if (nx <= 0) return 0;
    double a2 = a * a;
    return 2 * nx / (nx + sqrt(a2 + (1 - a2) * nx * nx));
}

em_lobe_ctx *em_lobe_ctx_create(int n_theta, int n_phi) {
    em_lobe_ctx *c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->n = n_theta * n_phi;
    c->dir = malloc(sizeof(double) * 3 * c->n);
    c->ring_theta = malloc(sizeof(double) * 2 * c->n);
    c->dw = malloc(sizeof(double) * c->n);
    c->w_true = malloc(sizeof(double) * c->n);
    for (int i = 0; i < EM_LOBE_TAPS; i++) c->k[i] = malloc(sizeof(double) * c->n);
    if (!c->dir || !c->ring_theta || !c->dw || !c->w_true || !c->k[0] || !c->k[1] || !c->k[2]) {
        em_lobe_ctx_free(c);
        return NULL;
    }
    /* θ = π u² (rings close together about r, where the narrow lobes are), φ over a half circle:
     * every lobe here is symmetric about the plane of incidence, so the other half doubles dω */
    int k = 0;
    for (int i = 0; i < n_theta; i++) {
        double u = (i + 0.5) / n_theta, theta = M_PI * u * u, dtheta = 2 * M_PI * u / n_theta;
        for (int j = 0; j < n_phi; j++, k++) {
            c->ring_theta[2 * k] = theta;
            c->ring_theta[2 * k + 1] = M_PI * (j + 0.5) / n_phi;
            c->dw[k] = 2 * sin(theta) * dtheta * (M_PI / n_phi);
        }
    }
    c->mu = -1;
    return c;
}

void em_lobe_ctx_free(em_lobe_ctx *c) {
    if (!c) return;
    free(c->dir), free(c->ring_theta), free(c->dw), free(c->w_true);
    for (int i = 0; i < EM_LOBE_TAPS; i++) free(c->k[i]);
    free(c);
}

/* the frame of (μ): n = +Z, v in the XZ plane, r its mirror; e ⊥ r towards n in the plane of
 * incidence, b = +Y; the real lobe W for α, normalised */
static void set_lobe(em_lobe_ctx *c, double mu, double alpha) {
    if (c->mu == mu && c->alpha == alpha) return;
    double s = sqrt(fmax(0, 1 - mu * mu));
    double v[3] = {s, 0, mu}, r[3] = {-s, 0, mu}, e[3] = {mu, 0, s}, b[3] = {0, 1, 0};
    memcpy(c->v, v, sizeof v), memcpy(c->r, r, sizeof r), memcpy(c->e, e, sizeof e), memcpy(c->b, b, sizeof b);
    double sum = 0;
    for (int k = 0; k < c->n; k++) {
        double th = c->ring_theta[2 * k], ph = c->ring_theta[2 * k + 1];
        double ct = cos(th), st = sin(th), cp = cos(ph), sp = sin(ph);
        double *l = c->dir + 3 * k;
        for (int a = 0; a < 3; a++) l[a] = ct * r[a] + st * (cp * e[a] + sp * b[a]);
        double w = 0;
        if (l[2] > 0) {
            double h[3] = {l[0] + v[0], l[1] + v[1], l[2] + v[2]}, hl = sqrt(dot3(h, h));
            if (hl > 1e-12) w = ggx_d(h[2] / hl, alpha) * smith_g1(l[2], alpha);
        }
        c->w_true[k] = w;
        sum += w * c->dw[k];
    }
    for (int k = 0; k < c->n; k++) c->w_true[k] /= sum;
    c->mu = mu, c->alpha = alpha;
}

/* the chain's lobe along r turned by t towards n, normalised */
static void chain_lobe(em_lobe_ctx *c, double t, double a, double *out) {
    double d[3];
    for (int i = 0; i < 3; i++) d[i] = cos(t) * c->r[i] + sin(t) * c->e[i];
    double sum = 0;
    for (int k = 0; k < c->n; k++) {
        const double *l = c->dir + 3 * k;
        double dl = dot3(d, l), val = 0;
        if (dl > 0) {
            double h[3] = {l[0] + d[0], l[1] + d[1], l[2] + d[2]}, hl = sqrt(dot3(h, h));
            if (hl > 1e-12) val = ggx_d(dot3(h, d) / hl, a) * dl;
        }
        out[k] = val;
        sum += val * c->dw[k];
    }
    for (int k = 0; k < c->n; k++) out[k] = sum > 0 ? out[k] / sum : 0;
}

static const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};

/* the distance of taps from like under the nearest permutation (t, log alpha and w) */
static double tap_distance(const em_lobe_taps *taps, const em_lobe_taps *like, int *which) {
    double best_d = INFINITY;
    for (int p = 0; p < 6; p++) {
        double d = 0;
        for (int k = 0; k < EM_LOBE_TAPS; k++) {
            int i = perm[p][k];
            d += fabs(taps->t[i] - like->t[k]) + fabs(log(taps->alpha[i] / like->alpha[k])) + fabs(taps->w[i] - like->w[k]);
        }
        if (d < best_d) best_d = d, *which = p;
    }
    return best_d;
}

void em_lobe_match(em_lobe_taps *taps, const em_lobe_taps *like) {
    int best = 0;
    tap_distance(taps, like, &best);
    em_lobe_taps out = *taps;
    for (int k = 0; k < EM_LOBE_TAPS; k++) {
        int i = perm[best][k];
        out.t[k] = taps->t[i], out.alpha[k] = taps->alpha[i], out.w[k] = taps->w[i];
    }
    *taps = out;
}

static double mix_error(const em_lobe_ctx *c, const double *w, int count) {
    double e = 0, ww = 0;
    for (int k = 0; k < c->n; k++) {
        double f = 0;
        for (int i = 0; i < count; i++) f += w[i] * c->k[i][k];
        e += (f - c->w_true[k]) * (f - c->w_true[k]) * c->dw[k];
        ww += c->w_true[k] * c->w_true[k] * c->dw[k];
    }
    return sqrt(e / ww);
}

double em_lobe_error(em_lobe_ctx *c, double mu, double alpha, const em_lobe_taps *taps) {
    set_lobe(c, mu, alpha);
    for (int i = 0; i < EM_LOBE_TAPS; i++) chain_lobe(c, taps->t[i], taps->alpha[i], c->k[i]);
    return mix_error(c, taps->w, EM_LOBE_TAPS);
}

double em_lobe_single_error(em_lobe_ctx *c, double mu, double alpha, double t) {
    set_lobe(c, mu, alpha);
    chain_lobe(c, t, alpha, c->k[0]);
    double one = 1;
    return mix_error(c, &one, 1);
}

double em_lobe_dominant_t(double mu, double alpha) {
    double s = fmin(fmax(1 - alpha, 0), 1), f = s * (sqrt(s) + alpha);
    double st = sqrt(fmax(0, 1 - mu * mu));
    /* normalize(mix(n, r, f)) with n = +Z, r = (−sin θ_v, 0, μ): its angle from r towards n */
    return atan2(-f * st, (1 - f) + f * mu) - atan2(-st, mu);
}

/* least squares for the weights with Σ w = 1 (a Lagrange multiplier), dropping the most
 * negative weight until none is: an active set over at most three lobes */
static void solve_weights(const em_lobe_ctx *c, double *w) {
    int active[EM_LOBE_TAPS] = {1, 1, 1};
    for (int pass = 0; pass < EM_LOBE_TAPS; pass++) {
        int idx[EM_LOBE_TAPS], m = 0;
        for (int i = 0; i < EM_LOBE_TAPS; i++)
            if (active[i]) idx[m++] = i;
        double a[EM_LOBE_TAPS + 1][EM_LOBE_TAPS + 2] = {{0}};
        for (int k = 0; k < c->n; k++)
            for (int i = 0; i < m; i++) {
                a[i][m + 1] += c->k[idx[i]][k] * c->w_true[k] * c->dw[k];
                for (int j = 0; j < m; j++) a[i][j] += c->k[idx[i]][k] * c->k[idx[j]][k] * c->dw[k];
            }
        for (int i = 0; i < m; i++) a[i][m] = a[m][i] = 1;
        a[m][m + 1] = 1;
        int n = m + 1;
        for (int col = 0; col < n; col++) { /* Gauss–Jordan with partial pivoting */
            int p = col;
            for (int row = col + 1; row < n; row++)
                if (fabs(a[row][col]) > fabs(a[p][col])) p = row;
            for (int j = 0; j <= n; j++) {
                double t = a[col][j];
                a[col][j] = a[p][j], a[p][j] = t;
            }
            if (fabs(a[col][col]) < 1e-300) continue;
            for (int row = 0; row < n; row++)
                if (row != col) {
                    double f = a[row][col] / a[col][col];
                    for (int j = col; j <= n; j++) a[row][j] -= f * a[col][j];
                }
        }
        for (int i = 0; i < EM_LOBE_TAPS; i++) w[i] = 0;
        int worst = -1;
        double most = 0;
        for (int i = 0; i < m; i++) {
            w[idx[i]] = fabs(a[i][i]) > 1e-300 ? a[i][n] / a[i][i] : 0;
            if (w[idx[i]] < most) most = w[idx[i]], worst = idx[i];
        }
        if (worst < 0) return;
        active[worst] = 0;
    }
}

typedef struct fit_state {
    em_lobe_ctx *c;
    int fix_t;
    const em_lobe_taps *near;
    double alpha;
    double w[EM_LOBE_TAPS];
} fit_state;

/* p: (t, log a) per tap, or log a alone when the t's are fixed at 0 */
static double objective(fit_state *s, const double *p) {
    for (int i = 0; i < EM_LOBE_TAPS; i++) {
        double t = s->fix_t ? 0 : p[2 * i], la = s->fix_t ? p[i] : p[2 * i + 1];
        double a = exp(la);
        if (!(a >= 0.01 && a <= 1) || fabs(t) > 2) return 1e9;
        chain_lobe(s->c, t, a, s->c->k[i]);
    }
    solve_weights(s->c, s->w);
    double e = mix_error(s->c, s->w, EM_LOBE_TAPS);
    if (s->near) { /* continuity: a little of the distance from the neighbour's taps */
        em_lobe_taps t;
        for (int i = 0; i < EM_LOBE_TAPS; i++)
            t.t[i] = s->fix_t ? 0 : p[2 * i], t.alpha[i] = exp(s->fix_t ? p[i] : p[2 * i + 1]), t.w[i] = s->w[i];
        int which;
        e += EM_LOBE_CONTINUITY * s->alpha * tap_distance(&t, s->near, &which);
    }
    return e;
}

/* Nelder–Mead (reflection 1, expansion 2, contraction ½, shrink ½) from p, a simplex of size step */
static double nelder_mead(fit_state *s, double *p, int n, double step, int iterations) {
    enum { MAXN = 2 * EM_LOBE_TAPS };
    double x[MAXN + 1][MAXN], f[MAXN + 1];
    for (int i = 0; i <= n; i++) {
        memcpy(x[i], p, sizeof(double) * n);
        if (i) x[i][i - 1] += step;
        f[i] = objective(s, x[i]);
    }
    for (int it = 0; it < iterations; it++) {
        for (int i = 0; i <= n; i++) /* sort best first */
            for (int j = i + 1; j <= n; j++)
                if (f[j] < f[i]) {
                    double tf = f[i], tx[MAXN];
                    f[i] = f[j], f[j] = tf;
                    memcpy(tx, x[i], sizeof tx), memcpy(x[i], x[j], sizeof tx), memcpy(x[j], tx, sizeof tx);
                }
        double mid[MAXN] = {0}, xr[MAXN], xt[MAXN];
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) mid[j] += x[i][j] / n;
        for (int j = 0; j < n; j++) xr[j] = 2 * mid[j] - x[n][j];
        double fr = objective(s, xr);
        if (fr < f[0]) {
            for (int j = 0; j < n; j++) xt[j] = 3 * mid[j] - 2 * x[n][j];
            double fe = objective(s, xt);
            if (fe < fr) memcpy(x[n], xt, sizeof xt), f[n] = fe;
            else memcpy(x[n], xr, sizeof xr), f[n] = fr;
        } else if (fr < f[n - 1]) {
            memcpy(x[n], xr, sizeof xr), f[n] = fr;
        } else {
            for (int j = 0; j < n; j++) xt[j] = 0.5 * (mid[j] + x[n][j]);
            double fc = objective(s, xt);
            if (fc < f[n]) memcpy(x[n], xt, sizeof xt), f[n] = fc;
            else
                for (int i = 1; i <= n; i++) {
                    for (int j = 0; j < n; j++) x[i][j] = 0.5 * (x[0][j] + x[i][j]);
                    f[i] = objective(s, x[i]);
                }
        }
    }
    int best = 0;
    for (int i = 1; i <= n; i++)
        if (f[i] < f[best]) best = i;
    memcpy(p, x[best], sizeof(double) * n);
    return f[best];
}

double em_lobe_fit(em_lobe_ctx *c, double mu, double alpha, em_lobe_taps *taps, int fix_t, const em_lobe_taps *near) {
    set_lobe(c, mu, alpha);
    fit_state s = {.c = c, .fix_t = fix_t, .near = near, .alpha = alpha};
    double p[2 * EM_LOBE_TAPS];
    int n = fix_t ? EM_LOBE_TAPS : 2 * EM_LOBE_TAPS;
    for (int i = 0; i < EM_LOBE_TAPS; i++) {
        if (fix_t) p[i] = log(taps->alpha[i]);
        else p[2 * i] = taps->t[i], p[2 * i + 1] = log(taps->alpha[i]);
    }
    nelder_mead(&s, p, n, fix_t ? 0.2 : 0.05, 500);
    nelder_mead(&s, p, n, 0.02, 300);
    for (int i = 0; i < EM_LOBE_TAPS; i++) {
        taps->t[i] = fix_t ? 0 : p[2 * i];
        taps->alpha[i] = exp(fix_t ? p[i] : p[2 * i + 1]);
    }
    for (int i = 0; i < EM_LOBE_TAPS; i++) chain_lobe(c, taps->t[i], taps->alpha[i], c->k[i]);
    solve_weights(c, taps->w);
    return mix_error(c, taps->w, EM_LOBE_TAPS);
}
