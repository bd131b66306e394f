/* ggx's KHR_materials_iridescence layer (README "Layers") against closed forms.
 *
 * This file writes the thin film's Fresnel again in C, from Belcour & Barla 2017 ("A Practical
 * Extension to Microfacet Theory for the Modeling of Varying Iridescence", §4–5: the Airy
 * reflectance as a Fourier series in the optical path difference, each order integrated over the
 * spectrum against Gaussian fits of the XYZ matching functions) in the form the extension
 * specifies (Schlick at both interfaces, orders 1..2, XYZ → linear sRGB). The series' kernel is a
 * parameter: the spectral sensitivity S(m·opd, m·φ), or cos(2π·m·opd/λ + m·φ) for one wavelength.
 *  1. independent of the renderer and of the spectral fit, what this C Fresnel must be on paper:
 *     a. at normal incidence a film of the outside's index (η2 = 1) is no interface: R = F0 for
 *        every thickness (at oblique angles Schlick's R12 = (1 − cos θ)⁵ is not 0: the spec's
 *        approximation, so only normal incidence is a closed form);
 *     b. at one wavelength (550 nm) and normal incidence (where Schlick is exact) the series summed
 *        to many orders equals the exact Airy reflectance of a film between two media,
 *        |(r12 + r23 e^{iδ})/(1 + r12 r23 e^{iδ})|², r_ab = (n_a − n_b)/(n_a + n_b), δ = 4π η2 d/λ
 *        (Born & Wolf §1.6), for films denser and lighter than the base; a quarter-wave film gives
 *        ((η3 − η2²)/(η3 + η2²))² and a half-wave one the bare base ((1 − η3)/(1 + η3))². This proves
 *        the series' coefficients and phase shifts; the spec's two orders are within a printed bound;
 *     c. a film far thicker than the coherence of the spectral fit (20 µm) reflects the incoherent
 *        sum R12 + T²R23/(1 − R12 R23): the spectral kernel's orders vanish there;
 *  2. the render under a directional light equals, per pixel, the model with this C Fresnel:
 *     f = (1 − F)(1 − m)·base/π + F·D·G/(4 n·l n·v), F = mix(Schlick(F0, v·h), F_film(v·h), w),
 *     F_film = mix(film over F0 0.04, film over the base colour, m);
 *  3. the "ggx-iridescence" view equals mix(Schlick(F0, n·v), F_film(n·v), w) per pixel;
 *  4. the extension's "no film" cases, iridescenceFactor 0 and a thickness of 0, and the layer's
 *     switch off, render exactly (bit for bit) the material without the layer. */
#include "camera_rays.h"
#include "ggx_layer_test.h"
#include <complex.h>
#include <stdlib.h>
#include <string.h>

#define W 96
#define H 72
static float img[W * H * 4], img2[W * H * 4];
static const test_camera cam = {{0, 3, 4}, {0, 0, 0}, 50, W, H};
static const double kd[3] = {0.7, 0.5, 0.3}, E = 3, metal = 0.3, weight = 0.8, alpha = 0.4 * 0.4;
static const double film_ior = 1.3, film_nm = 400;

/* ---- the film's Fresnel, written from the paper and the extension ---------------------------- */
typedef void (*kernel_fn)(double opd_nm, const double shift[3], double out[3]);

/* Order m's spectral sensitivity: the XYZ Gaussians' Fourier transforms (the paper's fit, the
 * extension's constants), normalised by the Y integral, XYZ → linear sRGB (D65). */
static void spectral(double opd_nm, const double shift[3], double out[3]) {
    static const double a[3] = {5.4856e-13, 4.4201e-13, 5.2481e-13}, mu[3] = {1.6810e6, 1.7953e6, 2.2084e6},
                        var[3] = {4.3278e9, 9.3046e9, 6.6121e9};
    double p = 2 * M_PI * opd_nm * 1e-9, xyz[3];
    for (int c = 0; c < 3; c++) xyz[c] = a[c] * sqrt(2 * M_PI * var[c]) * cos(mu[c] * p + shift[c]) * exp(-p * p * var[c]);
    xyz[0] += 9.7470e-14 * sqrt(2 * M_PI * 4.5282e9) * cos(2.2399e6 * p + shift[0]) * exp(-4.5282e9 * p * p);
    for (int c = 0; c < 3; c++) xyz[c] /= 1.0685e-7;
    out[0] = 3.2404542 * xyz[0] - 1.5371385 * xyz[1] - 0.4985314 * xyz[2];
    out[1] = -0.9692660 * xyz[0] + 1.8760108 * xyz[1] + 0.0415560 * xyz[2];
    out[2] = 0.0556434 * xyz[0] - 0.2040259 * xyz[1] + 1.0572252 * xyz[2];
}
/* One wavelength's kernel: the same term of the Airy series without the spectral integral. */
static double mono_nm;
static void monochromatic(double opd_nm, const double shift[3], double out[3]) {
    for (int c = 0; c < 3; c++) out[c] = cos(2 * M_PI * opd_nm / mono_nm + shift[c]);
}

static double f0_of(double a, double b) { return ((a - b) / (a + b)) * ((a - b) / (a + b)); }

/* R = R12 + Rs + Σ_{m=1..orders} 2(Rs − T)·r123^m·K(m·opd, m·φ), Rs = T²R23/(1 − R12R23). */
static void film_fresnel(double c1, const double f0[3], double eta2, double d_nm, int orders, kernel_fn k, double out[3]) {
    double s2 = (1 - c1 * c1) / (eta2 * eta2);
    if (s2 >= 1) {
        out[0] = out[1] = out[2] = 1;
        return;
    }
    double c2 = sqrt(1 - s2), R12 = schlick(c1, f0_of(eta2, 1)), T = 1 - R12, opd = 2 * eta2 * d_nm * c2;
    double phi21 = eta2 < 1 ? 0 : M_PI, R23[3], phi[3], r123[3], Rs[3];
    for (int c = 0; c < 3; c++) {
        double sf = sqrt(fmin(fmax(f0[c], 0), 0.9999)), eta3 = (1 + sf) / (1 - sf);
        R23[c] = schlick(c2, f0_of(eta3, eta2));
        phi[c] = phi21 + (eta3 < eta2 ? M_PI : 0);
        double R123 = fmin(R12 * R23[c], 0.9999);
        r123[c] = sqrt(R123);
        Rs[c] = T * T * R23[c] / (1 - R123);
        out[c] = R12 + Rs[c];
    }
    for (int m = 1; m <= orders; m++) {
        double shift[3] = {m * phi[0], m * phi[1], m * phi[2]}, s[3];
        k(m * opd, shift, s);
        for (int c = 0; c < 3; c++) out[c] += 2 * (Rs[c] - T) * pow(r123[c], m) * s[c];
    }
    for (int c = 0; c < 3; c++) out[c] = fmax(out[c], 0);
}

/* ---- 1: the C Fresnel against optics on paper ------------------------------------------------- */
static void test_film_of_outside_index(void) {
    double worst = 0;
    for (double d = 0; d <= 1000; d += 50)
        for (double f0 = 0.02; f0 < 0.95; f0 += 0.13) {
            double F[3], f0s[3] = {f0, f0 * 0.5, 0.04};
            film_fresnel(1, f0s, 1.0, d, 2, spectral, F);
            for (int i = 0; i < 3; i++) worst = fmax(worst, fabs(F[i] - f0s[i]));
        }
    printf("film of index 1 at normal incidence, d 0..1000 nm: worst |R - F0| %.2e\n", worst);
    CHECK_MSG(worst < 1e-12, "a film of the outside's index must be no film (%.2e)", worst);
}

static double airy_normal(double n2, double n3, double d_nm, double lambda) {
    double r12 = (1 - n2) / (1 + n2), r23 = (n2 - n3) / (n2 + n3);
    double complex e = cexp(I * 4 * M_PI * n2 * d_nm / lambda), r = (r12 + r23 * e) / (1 + r12 * r23 * e);
    return creal(r * conj(r));
}

static void test_airy_one_wavelength(void) {
    mono_nm = 550;
    const double films[][2] = {{1.3, 2.0}, {1.8, 1.5}, {2.4, 1.33}, {1.45, 3.0}}; /* η2, η3: denser and lighter bases */
    double worst_series = 0, worst_spec = 0;
    for (size_t f = 0; f < sizeof films / sizeof *films; f++) {
        double n2 = films[f][0], n3 = films[f][1], f0[3];
        f0[0] = f0[1] = f0[2] = f0_of(n3, 1);
        for (double d = 0; d <= 600; d += 17) {
            double R[3], R2[3], want = airy_normal(n2, n3, d, mono_nm);
            film_fresnel(1, f0, n2, d, 80, monochromatic, R);
            film_fresnel(1, f0, n2, d, 2, monochromatic, R2);
            worst_series = fmax(worst_series, fabs(R[1] - want));
            worst_spec = fmax(worst_spec, fabs(R2[1] - want));
        }
        double quarter = mono_nm / (4 * n2), half = mono_nm / (2 * n2), R[3];
        film_fresnel(1, f0, n2, quarter, 80, monochromatic, R);
        double want = pow((n3 - n2 * n2) / (n3 + n2 * n2), 2);
        printf("  eta2 %.2f over eta3 %.2f: quarter-wave R %.6f, closed form %.6f\n", n2, n3, R[0], want);
        CHECK_MSG(fabs(R[0] - want) < 1e-12, "quarter-wave film: %.9f vs %.9f", R[0], want);
        film_fresnel(1, f0, n2, half, 80, monochromatic, R);
        CHECK_MSG(fabs(R[0] - f0[0]) < 1e-12, "half-wave film: %.9f vs the bare base %.9f", R[0], f0[0]);
    }
    printf("Airy at 550 nm, normal incidence, d 0..600 nm: series of 80 orders worst %.2e, the spec's 2 orders %.2e\n",
           worst_series, worst_spec);
    CHECK_MSG(worst_series < 1e-12, "the series must sum to Airy's reflectance (%.2e)", worst_series);
    CHECK_MSG(worst_spec < 0.02, "two orders: %.2e", worst_spec);
}

static void test_thick_film_incoherent(void) {
    double worst = 0;
    for (double c = 0.1; c <= 1.0; c += 0.1) {
        double f0[3] = {0.04, 0.3, 0.9}, F[3];
        film_fresnel(c, f0, film_ior, 20000, 2, spectral, F);
        double c2 = sqrt(1 - (1 - c * c) / (film_ior * film_ior)), R12 = schlick(c, f0_of(film_ior, 1)), T = 1 - R12;
        for (int i = 0; i < 3; i++) {
            double eta3 = (1 + sqrt(f0[i])) / (1 - sqrt(f0[i])), R23 = schlick(c2, f0_of(eta3, film_ior));
            worst = fmax(worst, fabs(F[i] - (R12 + T * T * R23 / (1 - R12 * R23))));
        }
    }
    printf("20 um film: worst |R - incoherent sum| %.2e\n", worst);
    CHECK_MSG(worst < 1e-9, "a thick film must reflect the incoherent sum (%.2e)", worst);
}

/* ---- 2–4: the render ----------------------------------------------------------------------- */
#define BASE_KEYS "\"fresnel\": \"metallic-roughness\", \"metallic\": 0.3, \"roughness\": 0.4"

static bool render(const char *keys, const char *const *settings, const char *view, float *out) {
    char json[4096];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"ggx\"],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 3, 4], \"target\": [0, 0, 0], \"fov_y\": 50, \"near\": 0.1, \"far\": 100}],\n"
             " \"materials\": [{\"name\": \"m\", \"model\": \"ggx\", \"base_color\": [0.7, 0.5, 0.3], " BASE_KEYS "%s}],\n"
             " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 20}, \"material\": \"m\"}],\n"
             " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0.1, -0.6, 0.8], \"intensity\": 3}]}",
             keys);
    sl_harness *h = ggx_test_harness(json, W, H, settings, view);
    if (!h) return false;
    bool ok = ggx_test_render(h, W, H, out, keys);
    sl_harness_destroy(h);
    return ok;
}
/* The base's Fresnel with the film mixed in at cosine c: mix(Schlick(F0, c), F_film(c), w). */
static void fresnel(double c, double out[3]) {
    double d[3] = {0.04, 0.04, 0.04}, fd[3], fm[3];
    film_fresnel(c, d, film_ior, film_nm, 2, spectral, fd);
    film_fresnel(c, kd, film_ior, film_nm, 2, spectral, fm);
    for (int i = 0; i < 3; i++) {
        double F = schlick(c, 0.04 * (1 - metal) + kd[i] * metal);
        out[i] = F + (fd[i] * (1 - metal) + fm[i] * metal - F) * weight;
    }
}
static bool floor_pixel(int x, int y, double v[3], double l[3]) {
    float p[3], o[3], d[3];
    if (!test_camera_hit_ground(&cam, x, y, 9.5f, p)) return false;
    test_camera_ray(&cam, x, y, o, d);
    for (int i = 0; i < 3; i++) v[i] = -d[i];
    l[0] = -0.1, l[1] = 0.6, l[2] = -0.8;
    normalize3(l);
    return true;
}

#define FILM_KEYS ", \"iridescence\": 0.8"
static void test_render_closed_form(void) {
    if (!render(FILM_KEYS, NULL, NULL, img) || !render(FILM_KEYS, NULL, "ggx-iridescence", img2)) return;
    const double up[3] = {0, 1, 0};
    double worst = 0, worst_view = 0, hue_lo = 1, hue_hi = -1;
    int checked = 0;
    for (int y = 0; y < H; y += 2)
        for (int x = 0; x < W; x += 2) {
            double v[3], l[3], F[3], Fv[3];
            if (!floor_pixel(x, y, v, l)) continue;
            double h[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
            normalize3(h);
            fresnel(dot3(v, h), F);
            fresnel(v[1], Fv);
            double spec = dg_over_4(up, v, l, alpha), nl = l[1];
            for (int c = 0; c < 3; c++) {
                int i = (y * W + x) * 4 + c;
                double want = ((1 - F[c]) * (1 - metal) * kd[c] / M_PI + F[c] * spec) * E * nl;
                worst = fmax(worst, fabs(img[i] - want) / want);
                worst_view = fmax(worst_view, fabs(img2[i] - Fv[c]));
            }
            hue_lo = fmin(hue_lo, Fv[2] - Fv[0]), hue_hi = fmax(hue_hi, Fv[2] - Fv[0]);
            checked++;
        }
    printf("render vs C model: %d pixels, worst relative error %.2e; ggx-iridescence view worst %.2e; "
           "blue - red of the film's Fresnel in view %.3f..%.3f\n",
           checked, worst, worst_view, hue_lo, hue_hi);
    CHECK(checked > 500);
    CHECK_MSG(hue_hi - hue_lo > 0.05, "the view must show the film's colours change (%.3f..%.3f)", hue_lo, hue_hi);
    CHECK_MSG(worst < 2e-3, "render: worst relative error %.2e", worst);
    CHECK_MSG(worst_view < 1e-4, "ggx-iridescence view: worst %.2e", worst_view);
}

static void test_no_film_is_exact(void) {
    if (!render("", NULL, NULL, img)) return;
    const char *off[] = {"ggx.layer_iridescence=false", NULL};
    const struct { const char *keys; const char *const *settings; const char *what; } cases[] = {
        {", \"iridescence\": 0", NULL, "iridescenceFactor 0"},
        {", \"iridescence\": 1, \"iridescence_thickness_max\": 0", NULL, "thickness 0"},
        {FILM_KEYS, off, "ggx.layer_iridescence=false"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        if (!render(cases[k].keys, cases[k].settings, NULL, img2)) continue;
        int differ = 0;
        for (int i = 0; i < W * H * 4; i++) differ += img[i] != img2[i];
        printf("%s: %d channel values differ from the material without the layer\n", cases[k].what, differ);
        CHECK_MSG(differ == 0, "%s must render exactly without the film (%d values differ)", cases[k].what, differ);
    }
}

int main(void) {
    test_film_of_outside_index();
    test_airy_one_wavelength();
    test_thick_film_incoherent();
    test_render_closed_form();
    test_no_film_is_exact();
    return check_result();
}
