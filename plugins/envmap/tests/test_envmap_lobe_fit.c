/* specular=fitted's table (lobe_fit_table.h, what envmap.c uploads for the shader) against GGX's real
 * lobe (lobe_fit.h: D(h)·G1(n·l), integrated in C over the sphere; independent of the GLSL):
 *   - the table read as the shader reads it (bilinear between cells, w2 = 1 − w0 − w1), at every
 *     cell and at every midpoint between four cells, for α = 0.1…0.9: weights ≥ 0 summing to 1
 *     (the furnace), and an error below the dominant lookup's (the split sum it replaces) —
 *     at most 0.8× it anywhere, and at most 0.15 up to θ_v = 60° (¾ of a sphere's pixels;
 *     the dominant lookup: 0.13–0.46 there);
 *   - the α = 1 row is the dominant lookup itself (the tool's documented choice);
 *   - the table is the tool's: one cell fitted again from its neighbour reaches the table's error
 *     within 2 %;
 *   - controls: the dominant lookup misses the real lobe by > 0.1 at α = 0.4, θ_v = 45° (so the
 *     comparison has something to see), and a table with taps 0 and 1 swapped is caught. */
#include "check.h"
#include "../lobe_fit.h"
#include <stdio.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#include "../lobe_fit_table.h"

enum { CELLS = EM_LOBE_ALPHAS * EM_LOBE_THETAS };
static double table[CELLS][8];

static void load_table(void) {
    for (int i = 0; i < CELLS; i++)
        for (int k = 0; k < 8; k++) table[i][k] = em_lobe_table[i / EM_LOBE_THETAS][i % EM_LOBE_THETAS][k];
}

/* the shader's read: bilinear in (α index, θ_v index), then the taps */
static em_lobe_taps read_table(double fa, double ft) {
    int a0 = (int)fa, t0 = (int)ft;
    if (a0 > EM_LOBE_ALPHAS - 2) a0 = EM_LOBE_ALPHAS - 2;
    if (t0 > EM_LOBE_THETAS - 2) t0 = EM_LOBE_THETAS - 2;
    double sa = fa - a0, st = ft - t0, v[8];
    for (int i = 0; i < 8; i++) {
        const double *c00 = table[a0 * EM_LOBE_THETAS + t0], *c01 = table[a0 * EM_LOBE_THETAS + t0 + 1];
        const double *c10 = table[(a0 + 1) * EM_LOBE_THETAS + t0], *c11 = table[(a0 + 1) * EM_LOBE_THETAS + t0 + 1];
        v[i] = (1 - sa) * ((1 - st) * c00[i] + st * c01[i]) + sa * ((1 - st) * c10[i] + st * c11[i]);
    }
    return (em_lobe_taps){.t = {v[0], v[3], v[6]}, .alpha = {v[1], v[4], v[7]}, .w = {v[2], v[5], 1 - v[2] - v[5]}};
}

static double alpha_at(double fa) { return EM_LOBE_ALPHA_MIN + EM_LOBE_ALPHA_STEP * fa; }
static double mu_at(double ft) { return cos(EM_LOBE_THETA_STEP * ft * M_PI / 180); }

/* every cell and midpoint of α = 0.1…0.9: the worst ratio to the dominant lookup's error */
static double check_table(em_lobe_ctx *c, bool report) {
    double worst_ratio = 0, worst_60 = 0;
    for (int ia = 0; ia <= 2 * (EM_LOBE_ALPHAS - 2); ia++)
        for (int it = 0; it <= 2 * (EM_LOBE_THETAS - 1); it++) {
            double fa = ia * 0.5, ft = it * 0.5, alpha = alpha_at(fa), mu = mu_at(ft);
            em_lobe_taps taps = read_table(fa, ft);
            bool ok_w = true;
            for (int k = 0; k < EM_LOBE_TAPS; k++) ok_w = ok_w && taps.w[k] >= -1e-6 && taps.alpha[k] > 0;
            if (report) CHECK_MSG(ok_w, "alpha %.2f theta %.1f: weights %g %g %g", alpha, ft * 5, taps.w[0], taps.w[1], taps.w[2]);
            double e = em_lobe_error(c, mu, alpha, &taps);
            double d = em_lobe_single_error(c, mu, alpha, em_lobe_dominant_t(mu, alpha));
            if (e / d > worst_ratio) worst_ratio = e / d;
            if (ft * EM_LOBE_THETA_STEP <= 60 && e > worst_60) worst_60 = e;
            if (report && it % 6 == 0 && ia % 2 == 0)
                printf("alpha %.1f theta %4.1f: fitted %.3f, dominant %.3f\n", alpha, ft * EM_LOBE_THETA_STEP, e, d);
        }
    if (report) {
        printf("worst fitted/dominant over cells and midpoints, alpha 0.1-0.9: %.3f; worst error up to 60 deg: %.3f\n",
               worst_ratio, worst_60);
        CHECK_MSG(worst_ratio <= 0.8, "fitted error %.3f of the dominant lookup's", worst_ratio);
        CHECK_MSG(worst_60 <= 0.15, "fitted error %.3f up to theta 60", worst_60);
    }
    return worst_ratio;
}

int main(void) {
    load_table();
    em_lobe_ctx *c = em_lobe_ctx_create(128, 64);
    CHECK(c != NULL);
    if (!c || check_failures_) return check_result() ? 1 : 1;

    /* control: the dominant lookup is visibly off the real lobe where the table is compared */
    double d45 = em_lobe_single_error(c, cos(M_PI / 4), 0.4, em_lobe_dominant_t(cos(M_PI / 4), 0.4));
    CHECK_MSG(d45 > 0.1, "dominant error at alpha 0.4, 45 deg: %.3f", d45);

    check_table(c, true);

    /* α = 1: the dominant lookup (three equal taps along it, roughness 1) */
    for (int it = 0; it < EM_LOBE_THETAS; it++) {
        em_lobe_taps t = read_table(EM_LOBE_ALPHAS - 1, it);
        double td = em_lobe_dominant_t(mu_at(it), 1);
        for (int k = 0; k < EM_LOBE_TAPS; k++) CHECK(fabs(t.t[k] - td) < 1e-5 && fabs(t.alpha[k] - 1) < 1e-5);
    }

    /* the tool's table: α = 0.4, θ_v = 45° fitted again from its neighbour at 40° */
    int ai = 3, ti = 9;
    em_lobe_taps from = read_table(ai, ti - 1), here = read_table(ai, ti);
    double refit = em_lobe_fit(c, mu_at(ti), alpha_at(ai), &from, 0, NULL);
    double stored = em_lobe_error(c, mu_at(ti), alpha_at(ai), &here);
    printf("alpha 0.4, theta 45: table %.4f, fitted again %.4f\n", stored, refit);
    CHECK_MSG(stored <= refit * 1.02, "table %.4f, fit %.4f", stored, refit);

    /* mutation: taps 0 and 1 swapped in every other column must be caught */
    for (int i = 0; i < CELLS; i += 2) {
        double *v = table[i], t[3] = {v[0], v[1], v[2]};
        v[0] = v[3], v[1] = v[4], v[2] = v[5], v[3] = t[0], v[4] = t[1], v[5] = t[2];
    }
    double mutated = check_table(c, false);
    printf("mutation (taps 0 and 1 swapped in every other cell): worst ratio %.3f\n", mutated);
    CHECK_MSG(mutated > 0.8, "the swapped table passes: %.3f", mutated);
    em_lobe_ctx_free(c);
    return check_result();
}
