/* The skin diffusion profile and everything the sss plugin derives from it on the CPU: the
 * reduced k-Gaussian fits (quality knob), the separable blur taps, the screen-space kernel, the
 * slab transmittance and the pre-integrated (Penner 2011) look-up table. Pure C, no GL: the
 * plugin uploads the results, the tests call nothing here (they integrate the profile
 * themselves, independently).
 *
 * The profile: d'Eon & Luebke, "Advanced Techniques for Realistic Real-Time Skin Rendering",
 * GPU Gems 3 ch. 14 (2007) — the three-layer skin model fitted by six Gaussians,
 *     R(r) = Σᵢ wᵢ G(vᵢ, r),  G(v, r) = exp(−r² / 2v) / (2πv),  r in millimetres,
 * variances vᵢ = 0.0064, 0.0484, 0.187, 0.567, 1.99, 7.41 mm² and RGB weights wᵢ from their
 * table (each channel's weights sum to 1: the profile is white, skin colour comes from the
 * albedo). A 2D Gaussian is the product of two 1D ones g(v, x) = exp(−x²/2v)/√(2πv), which
 * is what makes the blurs separable. */
#ifndef SSS_PROFILE_H
#define SSS_PROFILE_H

#define SSS_MAX_GAUSSIANS 6
#define SSS_MAX_TS_TAPS 31
#define SSS_MAX_SS_TAPS 63

extern const double sss_skin_variance[SSS_MAX_GAUSSIANS];    /* mm² */
extern const double sss_skin_weight[SSS_MAX_GAUSSIANS][3];   /* RGB */

/* A sum of n Gaussians, ascending variance. */
typedef struct sss_gaussians {
    int n;
    double variance[SSS_MAX_GAUSSIANS];
    double weight[SSS_MAX_GAUSSIANS][3];
} sss_gaussians;

/* The skin profile reduced to k Gaussians (1..6): the six are split into k runs of neighbours;
 * each run becomes one Gaussian carrying the run's summed RGB weights and its weight-averaged
 * variance (first moment matched), and of all the C(5, k−1) splits the one whose line response
 * (below) is closest to the full profile's in L2 is kept. k = 6 is the profile itself. */
void sss_profile_reduce(int k, sss_gaussians *out);

/* Response to a thin line of unit irradiance at distance x mm (the profile integrated along
 * the line): Σᵢ wᵢ g(vᵢ, x) for channel c. */
double sss_line_response(const sss_gaussians *g, int c, double x_mm);

/* Transmittance through a slab of thickness d mm lit uniformly on its far side (d'Eon & Luebke
 * ch. 14, translucent shadow maps: R(√(r² + d²)) = Σ wᵢ exp(−d²/2vᵢ) G(vᵢ, r), integrated over r): Σ wᵢ exp(−d²/2vᵢ). */
void sss_transmittance(const sss_gaussians *g, double d_mm, double rgb[3]);

/* Separable Gaussian blur taps in units of σ: `taps` (odd, 1..SSS_MAX_TS_TAPS) evenly spaced
 * offsets over ±3σ (7 taps: −3..3, d'Eon & Luebke's), each weighted by the Gaussian's integral
 * over the interval nearest to it, the outer intervals reaching ±∞ — so the weights sum to 1
 * exactly (7 taps reproduce their 0.006, 0.061, 0.242, 0.383). */
void sss_blur_taps(int taps, float *offsets, float *weights);

/* Screen-space kernel (Jimenez et al. 2015): `taps` (odd) offsets over ±range_mm, denser near
 * the centre (x = range·t·|t|, t evenly spaced in [−1, 1]); for each tap and Gaussian the
 * Gaussian's RGB-weighted integral over the tap's interval (outer ones to ±∞). Output layout,
 * row-major RGBA32F texels: row g (Gaussian), column t (tap): (w_R, w_G, w_B, offset_mm). The
 * sum over taps and Gaussians is exactly 1 per channel. */
void sss_ss_kernel(const sss_gaussians *g, int taps, double range_mm, float *rgba);

/* Pre-integrated skin (Penner 2011, "Pre-Integrated Skin Shading", SIGGRAPH course): column i
 * holds n·l = 2i/(width−1) − 1, row j curvature κ = j/(height−1)·kappa_max mm⁻¹ (so the first and
 * last texel centres are exactly −1, 1 and 0, kappa_max; sample at (i + 0.5)/width):
 *   D(θ, r) = ∫ max(0, cos(θ + x)) R₁(2r sin(x/2)) dx / ∫ R₁(2r sin(x/2)) dx,  x ∈ [−π, π],
 * R₁ the line response (the profile integrated across the ring of a cylinder of radius r = 1/κ).
 * Row 0 is max(0, n·l) exactly. RGBA32F, alpha 1, width×height texels row-major. */
void sss_preintegrated_lut(int width, int height, double kappa_max, float *rgba);

#endif
