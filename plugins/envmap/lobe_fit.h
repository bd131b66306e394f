/* envmap's fitted lobes (specular=fitted, README "Specular methods"): GGX's real reflected lobe
 * at n·v = μ and roughness α, approximated by a mix of three lobes of the prefiltered chain (the
 * split sum's n = v = r lobes) laid along the plane of incidence. Fitted offline by
 * tools/lobe_fit_tool.c (this library), which writes the table envmap.c uploads for the shader
 * (lobe_fit_table.h); the test (tests/test_envmap_lobe_fit.c) checks that table against the lobe
 * here. Double precision, no GL.
 *
 * Frame: n = +Z, v = (sin θ_v, 0, cos θ_v), r = reflect(−v, n). A tap at angle t is the
 * direction r turned by t towards n in the plane of incidence (t < 0: towards the horizon).
 * The real lobe, normalised to integrate to 1 over the sphere: W(l) ∝ D(h)·G1(n·l) above the
 * surface (the separable Smith BRDF times n·l; G1(v), F and 1/(4μ) are constant in l), h the
 * half vector of v and l. A chain lobe about d of roughness a: K(l) ∝ D(h_d)·max(d·l, 0), h_d
 * the half vector of d and l, as the prefilter weights its samples (envmap_ggx.frag, Karis
 * 2013). The mix Σ w_i K_i, w_i ≥ 0, Σ w_i = 1 (so a uniform environment is exact); its error is
 * ‖Σ w_i K_i − W‖ / ‖W‖ in L2 over the sphere. */
#ifndef ENVMAP_LOBE_FIT_H
#define ENVMAP_LOBE_FIT_H

#define EM_LOBE_TAPS 3
#define EM_LOBE_THETAS 18  /* θ_v = 0°, 5°, …, 85° */
#define EM_LOBE_ALPHAS 10  /* α = 0.1, 0.2, …, 1 */
#define EM_LOBE_THETA_STEP 5.0
#define EM_LOBE_ALPHA_MIN 0.1
#define EM_LOBE_ALPHA_STEP 0.1

typedef struct em_lobe_taps {
    double t[EM_LOBE_TAPS];     /* radians from r towards n */
    double alpha[EM_LOBE_TAPS]; /* the chain's roughness read */
    double w[EM_LOBE_TAPS];     /* weights, Σ = 1 */
} em_lobe_taps;

typedef struct em_lobe_ctx em_lobe_ctx;
/* A quadrature over the sphere about r: n_theta rings (denser towards r) × n_phi half-circle
 * steps (the lobes are symmetric about the plane of incidence). 128 × 64 resolves α ≥ 0.05. */
em_lobe_ctx *em_lobe_ctx_create(int n_theta, int n_phi);
void em_lobe_ctx_free(em_lobe_ctx *c);

/* The error of taps (w as given) against the real lobe at (μ, α). */
double em_lobe_error(em_lobe_ctx *c, double mu, double alpha, const em_lobe_taps *taps);
/* The error of one chain lobe along direction t (e.g. the dominant direction) at roughness α. */
double em_lobe_single_error(em_lobe_ctx *c, double mu, double alpha, double t);
/* Fits taps at (μ, α), starting from taps (t, alpha; w is solved for): Nelder–Mead over the t's
 * and log alphas (the t's held at 0 when fix_t: at μ = 1 the plane of incidence is undefined),
 * the weights by least squares with Σ w = 1, w ≥ 0. With near (a neighbouring cell's taps), the
 * objective adds EM_LOBE_CONTINUITY × α × their distance (tap_distance: t, log alpha, w under the
 * nearest order), so neighbouring cells keep one family of solutions. Deterministic. Returns
 * the error of the fit alone. */
#define EM_LOBE_CONTINUITY 0.006
double em_lobe_fit(em_lobe_ctx *c, double mu, double alpha, em_lobe_taps *taps, int fix_t, const em_lobe_taps *near);
/* Orders taps as the taps of `like` (the permutation nearest in t, log alpha and w): the shader
 * interpolates tap k of neighbouring cells, so neighbours must list the same lobe as tap k. */
void em_lobe_match(em_lobe_taps *taps, const em_lobe_taps *like);
/* t of the dominant direction (Lagarde & de Rousiers 2014; envmap_dominant_dir) at (μ, α). */
double em_lobe_dominant_t(double mu, double alpha);

#endif
