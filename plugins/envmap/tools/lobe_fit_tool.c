/* envmap_lobe_fit: fits specular=fitted's lobes (lobe_fit.h) over the table's (α, θ_v) grid and
 * writes the table envmap.c uploads for the shader. Deterministic; about a minute on one core:
 *   build/plugins/envmap/envmap_lobe_fit plugins/envmap/lobe_fit_table.h
 * The first row (α = 0.1) starts at θ_v = 0 (the t's held at 0: no plane of incidence there) from
 * lobes of 0.8α, α and 1.2α, each next cell from its neighbour's fit; every other cell from the
 * cell below it, and each fit is held a little towards its neighbour (EM_LOBE_CONTINUITY), so
 * tap k moves smoothly both ways (the shader interpolates tap k of four cells). The last row
 * (α = 1) is the dominant lookup itself, three equal taps along it: the fit there is held to the
 * chain's widest lobe (α = 1) and measured further from Cycles than the dominant lookup (README,
 * "The first frame"); between α = 0.9 and 1 the taps slide onto it. */
#include "../lobe_fit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

int main(int argc, char **argv) {
    if (argc != 2 || argv[1][0] == '-') {
        fprintf(stderr, "usage: envmap_lobe_fit OUT.h\n(writes specular=fitted's table; plugins/envmap/README.md)\n");
        return argc == 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) ? 0 : 1;
    }
    em_lobe_ctx *c = em_lobe_ctx_create(128, 64);
    if (!c) return 1;
    static em_lobe_taps cell[EM_LOBE_ALPHAS][EM_LOBE_THETAS];
    static double err[EM_LOBE_ALPHAS][EM_LOBE_THETAS], dom[EM_LOBE_ALPHAS][EM_LOBE_THETAS];
    for (int ai = 0; ai < EM_LOBE_ALPHAS; ai++) {
        double alpha = EM_LOBE_ALPHA_MIN + EM_LOBE_ALPHA_STEP * ai;
        em_lobe_taps taps = {.t = {0, 0, 0}, .alpha = {0.8 * alpha, alpha, fmin(1.2 * alpha, 0.99)}};
        for (int ti = 0; ti < EM_LOBE_THETAS; ti++) {
            double mu = cos(EM_LOBE_THETA_STEP * ti * M_PI / 180);
            double td = em_lobe_dominant_t(mu, alpha);
            dom[ai][ti] = em_lobe_single_error(c, mu, alpha, td);
            if (ai == EM_LOBE_ALPHAS - 1) { /* α = 1: the dominant lookup itself (below) */
                cell[ai][ti] = (em_lobe_taps){.t = {td, td, td}, .alpha = {1, 1, 1}, .w = {1 / 3.0, 1 / 3.0, 1 / 3.0}};
                err[ai][ti] = dom[ai][ti];
                continue;
            }
            /* row 0 continues along θ_v; every other row from the cell below, its lobes scaled by
             * the step in α, so the taps move smoothly both ways (the shader interpolates tap k of
             * four cells) */
            if (ai > 0) {
                taps = cell[ai - 1][ti];
                for (int k = 0; k < EM_LOBE_TAPS; k++) taps.alpha[k] = fmin(0.99, taps.alpha[k] * alpha / (alpha - EM_LOBE_ALPHA_STEP));
            }
            err[ai][ti] = em_lobe_fit(c, mu, alpha, &taps, ti == 0, ti > 0 ? &cell[ai][ti - 1] : NULL);
            if (ai > 0) em_lobe_match(&taps, &cell[ai - 1][ti]);
            else if (ti > 0) em_lobe_match(&taps, &cell[ai][ti - 1]);
            cell[ai][ti] = taps;
        }
        fprintf(stderr, "alpha %.1f: fitted error %.3f at theta 0 .. %.3f at 85 (dominant %.3f .. %.3f)\n", alpha,
                err[ai][0], err[ai][EM_LOBE_THETAS - 1], dom[ai][0], dom[ai][EM_LOBE_THETAS - 1]);
    }
    em_lobe_ctx_free(c);
    FILE *f = fopen(argv[1], "w");
    if (!f) {
        perror(argv[1]);
        return 1;
    }
    fprintf(f, "/* specular=fitted's table, written by envmap_lobe_fit (plugins/envmap/tools/lobe_fit_tool.c,\n"
               " * lobe_fit.h): do not edit. Cell [i][j]: α = %.1f + %.1f i, θ_v = %g° j; (t0, a0, w0, t1, a1, w1,\n"
               " * t2, a2), w2 = 1 − w0 − w1: tap k reads the chain at roughness a_k along r turned by t_k radians\n"
               " * towards n in the plane of incidence. envmap.c uploads it as two layers of a 2D array texture.\n"
               " * Error of the mix against GGX's lobe (relative L2) at θ_v = 0 / 45 / 85°, and of the dominant\n"
               " * lookup alone (the α = 1 row is the dominant lookup):\n",
            EM_LOBE_ALPHA_MIN, EM_LOBE_ALPHA_STEP, EM_LOBE_THETA_STEP);
    for (int ai = 0; ai < EM_LOBE_ALPHAS; ai++)
        fprintf(f, " *   α %.1f: %.3f / %.3f / %.3f (dominant %.3f / %.3f / %.3f)\n", EM_LOBE_ALPHA_MIN + EM_LOBE_ALPHA_STEP * ai,
                err[ai][0], err[ai][9], err[ai][17], dom[ai][0], dom[ai][9], dom[ai][17]);
    fprintf(f, " */\nstatic const float em_lobe_table[%d][%d][8] = {\n", EM_LOBE_ALPHAS, EM_LOBE_THETAS);
    for (int ai = 0; ai < EM_LOBE_ALPHAS; ai++) {
        fprintf(f, "    {\n");
        for (int ti = 0; ti < EM_LOBE_THETAS; ti++) {
            const em_lobe_taps *t = &cell[ai][ti];
            fprintf(f, "        {%.6ff, %.6ff, %.6ff, %.6ff, %.6ff, %.6ff, %.6ff, %.6ff},\n", t->t[0], t->alpha[0], t->w[0],
                    t->t[1], t->alpha[1], t->w[1], t->t[2], t->alpha[2]);
        }
        fprintf(f, "    },\n");
    }
    fprintf(f, "};\n");
    return fclose(f) == 0 ? 0 : 1;
}
