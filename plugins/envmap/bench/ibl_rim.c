/* Where does the split sum's error on a real HDR come from (issue 16)? A CPU evaluation, no GL,
 * of the bench's metal sphere (ibl_sphere.h's camera: (0, 0, 3.1), 40°, SIZE², unit sphere) under
 * a lat-long environment, per pixel centre:
 *   T      the GGX specular integral itself, ∫ L F D G / (4 n·v) dl over n·l > 0 (F Schlick with
 *          the metal's F0 per channel, G = G1(v) G1(l) with the ggx plugin's G1);
 *   L̄      the real lobe's F-free mean radiance ∫ L D G/(4 n·v) dl / ∫ D G/(4 n·v) dl, so that
 *          (F0·A + B)·L̄ is the split sum with a perfect P: what the F/L split alone costs;
 *   P(d)   Karis' n = v = r prefilter around d, exact (full-resolution source, many samples):
 *          Σ L(l) n·l / Σ n·l over GGX half-vectors; "flat" the same without the n·l weight;
 *          d the mirror direction or the dominant direction (Lagarde & de Rousiers 2014 §4.9.3);
 *   (A, B) the environment BRDF at (n·v, α) from the same integrals with L = 1.
 * Each method's specular value is (F0·A + B)·P; relative RMS and mean against T over the sphere,
 * and the mean ratio method/T in n·v bins. An integral is a midpoint rule over the half-vector's
 * D(h)(n·h) CDF (u) × azimuth (NU × NPHI points), as tests/ibl_quadrature.c, so a "P" differs from T
 * only by what the method assumes, not by noise or the plugin's prefilter/mips.
 * --still: the aa plugin's TAA still (bench/rim.sh: rim-still.csv); checks: RIM_TAA_FRAMES=N (a
 * shorter still), RIM_REF_SAMPLES=N (the reference still's spp a frame), RIM_SX/RIM_SY=±1 (the
 * jitter's sign in T), RIM_EXTRA="key=value ..." (settings added to every GL still).
 * --gl: also renders, through the harness at the same pixels (aa off), the plugin's reference
 * (32 and 128 frames × 64 spp), specular=mirror/dominant and fis accumulated, and compares each
 * with T (is the reference right at the rim? is the GL prefilter the ideal P? what is left of fis?).
 * bench/rim.sh runs it.
 * Usage: envmap_bench_rim --env PATH [--size N] [--nu N] [--nphi N] [--gl]
 * Output: CSV rows env,alpha,method,rel_rms,rel_mean,ratio_mu<0.25,ratio_mu0.25-0.5,ratio_mu>0.5 */
#include "ibl_sphere.h"
#include "../tests/still_jitter.h"
#include <envmap/io.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
static const double f0m[3] = {0.95, 0.64, 0.54}; /* the bench's metal: F0 = base colour */
enum { NA = 5, NB = 3 };

static em_image env;
static void lookup(const double d[3], double out[3]) { /* bilinear, u wraps, v clamps */
    double u, v;
    em_dir_latlong(d, &u, &v);
    double x = u * env.w - 0.5, y = v * env.h - 0.5;
    int x0 = (int)floor(x), y0 = (int)floor(y);
    double fx = x - x0, fy = y - y0;
    for (int c = 0; c < 3; c++) out[c] = 0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            int xx = ((x0 + i) % env.w + env.w) % env.w, yy = y0 + j < 0 ? 0 : y0 + j >= env.h ? env.h - 1 : y0 + j;
            double w = (i ? fx : 1 - fx) * (j ? fy : 1 - fy);
            const float *p = env.px + ((size_t)yy * env.w + xx) * 4;
            for (int c = 0; c < 3; c++) out[c] += w * p[c];
        }
}
static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void norm(double a[3]) {
    double l = sqrt(dot(a, a));
    for (int i = 0; i < 3; i++) a[i] /= l;
}
static void frame(const double n[3], double t[3], double b[3]) {
    double up[3] = {fabs(n[1]) < 0.999 ? 0 : 1, fabs(n[1]) < 0.999 ? 1 : 0, 0};
    t[0] = up[1] * n[2] - up[2] * n[1], t[1] = up[2] * n[0] - up[0] * n[2], t[2] = up[0] * n[1] - up[1] * n[0];
    norm(t);
    b[0] = n[1] * t[2] - n[2] * t[1], b[1] = n[2] * t[0] - n[0] * t[2], b[2] = n[0] * t[1] - n[1] * t[0];
}
static double g1(double xn, double xh, double a) { /* ggx's default G1: angle from the normal */
    if (xn <= 0 || xh / xn <= 0) return 0;
    double t2 = (1 - xn * xn) / (xn * xn);
    return 2 / (1 + sqrt(1 + a * a * t2));
}
static int nu = 96, nphi = 96;
/* the half-vector grid around n: h(i, j) */
static void half(const double n[3], const double t[3], const double b[3], double a, int i, int j, double h[3]) {
    double u = (i + 0.5) / nu, ph = 2 * PI * (j + 0.5) / nphi;
    double c2 = (1 - u) / (1 + (a * a - 1) * u), c = sqrt(c2), s = sqrt(1 - c2);
    for (int k = 0; k < 3; k++) h[k] = t[k] * s * cos(ph) + b[k] * s * sin(ph) + n[k] * c;
}
/* T (per channel), L̄ (F-free lobe mean) and (A, B) at n, v */
static void truth(const double n[3], const double v[3], double a, double T[3], double Lbar[3], double *A, double *B) {
    double t[3], b[3], h[3], l[3], L[3], nv = dot(n, v);
    frame(n, t, b);
    double s[3] = {0}, sl[3] = {0}, w0 = 0, sa = 0, sb = 0;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nphi; j++) {
            half(n, t, b, a, i, j, h);
            double vh = dot(v, h);
            if (vh <= 0) continue;
            for (int k = 0; k < 3; k++) l[k] = 2 * vh * h[k] - v[k];
            double nl = dot(n, l), nh = dot(n, h);
            if (nl <= 0) continue;
            double w = g1(nv, vh, a) * g1(nl, dot(l, h), a) * vh / (nv * nh); /* D G/(4 n·v) dl / (D n·h dh) */
            double fc = pow(1 - vh, 5);
            lookup(l, L);
            for (int k = 0; k < 3; k++) {
                double F = f0m[k] + (1 - f0m[k]) * fc;
                s[k] += F * w * L[k], sl[k] += w * L[k];
            }
            w0 += w, sa += w * (1 - fc), sb += w * fc;
        }
    double N = (double)nu * nphi;
    for (int k = 0; k < 3; k++) T[k] = s[k] / N, Lbar[k] = w0 > 0 ? sl[k] / w0 : 0;
    *A = sa / N, *B = sb / N;
}
/* Karis' n = v = r prefilter around d, weighted by n·l (cosw) or not */
static void prefilter(const double d[3], double a, int cosw, double P[3]) {
    double t[3], b[3], h[3], l[3], L[3], sum[3] = {0}, w = 0;
    frame(d, t, b);
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nphi; j++) {
            half(d, t, b, a, i, j, h);
            double dh = dot(d, h);
            for (int k = 0; k < 3; k++) l[k] = 2 * dh * h[k] - d[k];
            double nl = dot(d, l);
            if (nl <= 0) continue;
            double ww = cosw ? nl : 1;
            lookup(l, L);
            for (int k = 0; k < 3; k++) sum[k] += ww * L[k];
            w += ww;
        }
    for (int k = 0; k < 3; k++) P[k] = w > 0 ? sum[k] / w : 0;
}
static int size = 48;
/* pixel i's ray in a frame jittered by (jx, jy) pixels (x right, y up: sl_frame.jitter moves the
 * projection, so the pixel sees the scene at its centre − the jitter) */
static int pixel_at(int i, double jx, double jy, double n[3], double v[3]) { /* row 0 = top, as the harness reads back */
    double tn = tan(20 * PI / 180);
    double d[3] = {(2 * ((i % size) + 0.5 - jx) / size - 1) * tn, (1 - 2 * ((i / size) + 0.5 + jy) / size) * tn, -1};
    norm(d);
    double o[3] = {0, 0, 3.1}, bb = dot(o, d), c = dot(o, o) - 1, disc = bb * bb - c;
    if (disc <= 0) return 0;
    double s = -bb - sqrt(disc);
    for (int k = 0; k < 3; k++) n[k] = o[k] + s * d[k], v[k] = -d[k];
    norm(n);
    return dot(n, v) > 0;
}
static int pixel(int i, double n[3], double v[3]) { return pixel_at(i, 0, 0, n, v); }

/* --still: what the viewer shows at rest. T averaged over the aa plugin's TAA still (taa_frames
 * Halton (2, 3) jitter points a pixel, frame 0 at the centre; a ray that misses counts 0, as the
 * background-free render), compared with the plugin's GL stills (aa on, its defaults): its
 * reference (64·R spp a frame), the default specular, dominant, fis N and hybrid N. */
static const char *still_set[][2] = {
    {"gl-still-reference", "envmap.mode=reference envmap.reference_samples=512"},
    {"gl-still-default", ""},
    {"gl-still-dominant", "envmap.specular=dominant"},
    {"gl-still-fis8", "envmap.specular=fis envmap.fis_samples=8"},
    {"gl-still-fis16", "envmap.specular=fis envmap.fis_samples=16"},
    {"gl-still-hybrid8", "envmap.specular=hybrid envmap.fis_samples=8"},
    {"gl-still-hybrid16", "envmap.specular=hybrid envmap.fis_samples=16"},
};
enum { NS = sizeof still_set / sizeof *still_set };
static int run_still(const char *path, const char *mat, double only_alpha) {
    int n = size * size;
    float *img = malloc((size_t)n * 16);
    double *T = malloc(sizeof(double) * 3 * n);
    const char *envname = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    printf("env,alpha,method,rel_rms,rel_mean\n");
    for (int a = 0; a < NA; a++) {
        double al = ibl_alphas[a];
        if (only_alpha >= 0 && fabs(al - only_alpha) > 1e-6) continue;
        int frames = 16;
        sl_harness *h = ibl_sphere_aa(path, mat, size, 1, true);
        char v[32], buf[1024];
        if (getenv("RIM_TAA_FRAMES")) { /* a shorter still (checking the jitter mapping with 1 frame) */
            snprintf(buf, sizeof buf, "aa.taa_frames=%s", getenv("RIM_TAA_FRAMES"));
            if (!ibl_set(h, buf)) return 1;
        }
        if (!h || !sl_harness_get(h, "aa.taa_frames", v, sizeof v)) return 1;
        frames = atoi(v);
        char reset[256] = "envmap.mode=split-sum ", val[64]; /* the defaults, restored after each method */
        static const char *const knobs[] = {"envmap.specular", "envmap.fis_samples", "envmap.hybrid_alpha"};
        for (int i = 0; i < 3; i++) {
            if (!sl_harness_get(h, knobs[i], val, sizeof val)) return 1;
            snprintf(reset + strlen(reset), sizeof reset - strlen(reset), "%s=%s ", knobs[i], val);
        }
        for (int i = 0; i < 3 * n; i++) T[i] = 0;
        for (int i = 0; i < n; i++)
            for (int k = 0; k < frames; k++) {
                double nn[3], vv[3], t3[3], lb[3], A, B;
                double jx = still_jitter((unsigned)k, (unsigned)frames, 2), jy = still_jitter((unsigned)k, (unsigned)frames, 3);
                double sx = getenv("RIM_SX") ? atof(getenv("RIM_SX")) : 1, sy = getenv("RIM_SY") ? atof(getenv("RIM_SY")) : 1;
                if (!pixel_at(i, sx * jx, sy * jy, nn, vv)) continue;
                truth(nn, vv, al, t3, lb, &A, &B);
                for (int c = 0; c < 3; c++) T[i * 3 + c] += t3[c] / frames;
            }
        for (int m = 0; m < NS; m++) {
            snprintf(buf, sizeof buf, "material.m.alpha=%g %s %s", al, still_set[m][1], getenv("RIM_EXTRA") ? getenv("RIM_EXTRA") : "");
            if (m == 0 && getenv("RIM_REF_SAMPLES")) /* a smaller reference still (checks) */
                snprintf(buf, sizeof buf, "material.m.alpha=%g envmap.mode=reference envmap.reference_samples=%s", al, getenv("RIM_REF_SAMPLES"));
            if (!ibl_set(h, buf)) return 1;
            for (int f = 0; f < frames; f++)
                if (!sl_harness_render(h, img)) return 1;
            double se = 0, sx = 0, sr = 0;
            for (int i = 0; i < n; i++) {
                if (T[i * 3] + T[i * 3 + 1] + T[i * 3 + 2] <= 0) continue;
                for (int c = 0; c < 3; c++) {
                    double d = img[i * 4 + c] - T[i * 3 + c];
                    se += d * d, sx += img[i * 4 + c], sr += T[i * 3 + c];
                }
            }
            long cnt = 0;
            for (int i = 0; i < n; i++) cnt += T[i * 3] + T[i * 3 + 1] + T[i * 3 + 2] > 0 ? 3 : 0;
            printf("%s,%.2f,%s,%.5f,%+.5f\n", envname, al, still_set[m][0], sqrt(se / cnt) / (sr / cnt), sx / sr - 1);
            fflush(stdout);
            /* back to the defaults for the next one (a cut: the next still restarts) */
            if (!ibl_set(h, reset)) return 1;
        }
        sl_harness_destroy(h);
    }
    free(img), free(T);
    return 0;
}

/* K taps of the n = v = r prefilter along the plane of incidence (footprint assembly): half-vectors
 * at the quantiles of GGX's one-dimensional slope marginal, p(x) = 1/(2α(1 + x²/α²)^{3/2}),
 * F(x) = ½(1 + x̃/√(1 + x̃²)), x̃ = x/α, spread σ; each tap reads P at α_tap = α·(v·h_k) (the real
 * lobe's width across the plane of incidence is 2(v·h)α, the prefilter's 2α_tap); weights
 * G(v, l)(v·h)/(n·h), the integrand over the slope density. spread: 0 σ = α, 1 σ = α√(1 − μ²). */
static void taps(const double n[3], const double v[3], double a, int K, int spread, double P[3]) {
    double nv = dot(n, v), t[3], sum[3] = {0}, ws = 0, Pk[3];
    for (int k = 0; k < 3; k++) t[k] = v[k] - nv * n[k];
    double tl = sqrt(dot(t, t));
    if (tl < 1e-9 || K == 1) {
        double r[3];
        for (int k = 0; k < 3; k++) r[k] = 2 * nv * n[k] - v[k];
        prefilter(r, a, 1, P);
        return;
    }
    for (int k = 0; k < 3; k++) t[k] /= tl;
    double sig = spread ? a * sqrt(1 - nv * nv) : a;
    for (int i = 0; i < K; i++) {
        double s = 2 * (i + 0.5) / K - 1, x = sig * s / sqrt(1 - s * s), h[3], l[3];
        for (int k = 0; k < 3; k++) h[k] = n[k] + x * t[k];
        norm(h);
        double vh = dot(v, h), nh = dot(n, h);
        for (int k = 0; k < 3; k++) l[k] = 2 * vh * h[k] - v[k];
        double nl = dot(n, l);
        if (vh <= 0 || nl <= 0) continue;
        double w = g1(nv, vh, a) * g1(nl, dot(l, h), a) * vh / nh;
        prefilter(l, a * vh, 1, Pk);
        for (int c = 0; c < 3; c++) sum[c] += w * Pk[c];
        ws += w;
    }
    for (int c = 0; c < 3; c++) P[c] = ws > 0 ? sum[c] / ws : 0;
}

enum { M_LBAR, M_MIRROR, M_DOM, M_DOM_FLAT, M_T2, M_T3, M_T4, M_T8, M_S2, M_S3, M_S4, M_S8, M_GL_REF, M_GL_REF128, M_GL_DOM,
       M_GL_MIRROR, M_GL_FIS, M_GL_FIS_NOMIP, M_GL_FIS16, M_GL_S4, M_GL_S8, M_GL_S16, M_GL_FIS128, NM };
enum { NCPU = M_GL_REF };
static const char *mname[NM] = {"ideal-P=lobe-mean", "karis-mirror", "karis-dominant", "flat-dominant",
                                "taps2", "taps3", "taps4", "taps8", "taps2-s", "taps3-s", "taps4-s", "taps8-s",
                                "gl-reference", "gl-reference-128", "gl-dominant", "gl-mirror", "gl-fis32-acc32",
                                "gl-fis32-acc32-lodbias-3", "gl-fis16-acc64", "gl-fis4-acc16", "gl-fis8-acc16",
                                "gl-fis16-acc16", "gl-fis32-acc128"};
static const int tapk[8] = {2, 3, 4, 8, 2, 3, 4, 8};

int main(int argc, char **argv) {
    const char *path = NULL;
    int gl = 0, notaps = 0, still = 0;
    double only_alpha = -1;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--env") && i + 1 < argc) path = argv[++i];
        else if (!strcmp(argv[i], "--size") && i + 1 < argc) size = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--nu") && i + 1 < argc) nu = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--nphi") && i + 1 < argc) nphi = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--gl")) gl = 1;
        else if (!strcmp(argv[i], "--no-taps")) notaps = 1;
        else if (!strcmp(argv[i], "--alpha") && i + 1 < argc) only_alpha = atof(argv[++i]);
        else if (!strcmp(argv[i], "--still")) still = 1;
        else {
            fprintf(stderr, "usage: %s --env PATH [--size N] [--nu N] [--nphi N] [--gl]\n", argv[0]);
            return 2;
        }
    }
    char err[512];
    em_io_info info;
    if (!path || !em_io_load(path, &env, &info, err, sizeof err)) {
        fprintf(stderr, "%s\n", path ? err : "--env PATH required");
        return 1;
    }
    em_sanitize(env.px, (size_t)env.w * env.h, &(em_sanitize_stats){0});
    int n = size * size;
    enum { NG = NM - NCPU };
    float *img[NG] = {0};
    const char *mat = "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 1, \"base_color\": [0.95, 0.64, 0.54]";
    if (still) return run_still(path, mat, only_alpha);
    /* the GL renders: the plugin's reference (32 and 128 frames × 64 spp), the one-lookup methods,
     * and the highest fis setting accumulated — as the plugin does it (footprint over N·F samples,
     * fis_lod_bias −1), with fis_lod_bias −3 (the lowest allowed: nearly every sample at the base level, little mip bias, more
     * noise), and with N = 16 over 64 frames (the same N·F: a per-frame ratio estimator's bias
     * would double) */
    const char *glset[NG] = {"envmap.mode=reference envmap.reference_samples=64", "envmap.mode=reference envmap.reference_samples=64",
                             "envmap.specular=dominant", "envmap.specular=mirror",
                             "envmap.specular=fis envmap.fis_samples=32", "envmap.specular=fis envmap.fis_samples=32 envmap.fis_lod_bias=-3",
                             "envmap.specular=fis envmap.fis_samples=16", "envmap.specular=fis envmap.fis_samples=4",
                             "envmap.specular=fis envmap.fis_samples=8", "envmap.specular=fis envmap.fis_samples=16",
                             "envmap.specular=fis envmap.fis_samples=32"};
    /* (the last three: fis N over 16 frames, what the viewer's 16-frame TAA still would average
     * if fis's sequence advanced with it — it does not: sl_frame_index is the --accumulate index) */
    const int glacc[NG] = {32, 128, 1, 1, 32, 32, 64, 16, 16, 16, 128};
    const char *envname = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    printf("env,alpha,method,rel_rms,rel_mean,ratio_mu<0.25,ratio_mu0.25-0.5,ratio_mu>0.5,sqerr_share_mu<0.25,share_0.25-0.5,share>0.5\n");
    for (int a = 0; a < NA; a++) {
        double al = ibl_alphas[a];
        if (only_alpha >= 0 && fabs(al - only_alpha) > 1e-6) continue;
        if (gl)
            for (int k = 0; k < NG; k++) {
                char buf[96];
                img[k] = realloc(img[k], (size_t)n * 16);
                sl_harness *h = ibl_sphere(path, mat, size, glacc[k]);
                snprintf(buf, sizeof buf, "material.m.alpha=%g", al);
                if (!h || !ibl_set(h, glset[k]) || !ibl_set(h, buf) || !sl_harness_render(h, img[k])) return 1;
                sl_harness_destroy(h);
            }
        double se[NM] = {0}, sx[NM] = {0}, sr = 0, bx[NM][NB] = {{0}}, br[NB] = {0}, bse[NM][NB] = {{0}};
        long cnt = 0;
        for (int i = 0; i < n; i++) {
            double nn[3], v[3];
            if (!pixel(i, nn, v)) continue;
            double T[3], Lb[3], A, B, r[3], dm[3], P[NCPU][3];
            truth(nn, v, al, T, Lb, &A, &B);
            double nv = dot(nn, v);
            for (int k = 0; k < 3; k++) r[k] = 2 * nv * nn[k] - v[k];
            double s = 1 - al, f = s * (sqrt(s) + al);
            for (int k = 0; k < 3; k++) dm[k] = nn[k] + f * (r[k] - nn[k]);
            norm(dm);
            memcpy(P[0], Lb, sizeof Lb);
            prefilter(r, al, 1, P[1]);
            prefilter(dm, al, 1, P[2]);
            prefilter(dm, al, 0, P[3]);
            for (int m = M_T2; m < NCPU && !notaps; m++) taps(nn, v, al, tapk[m - M_T2], m >= M_S2, P[m]);
            int bin = nv < 0.25 ? 0 : nv < 0.5 ? 1 : 2;
            for (int c = 0; c < 3; c++) {
                double ab = f0m[c] * A + B, x[NM];
                for (int m = 0; m < NCPU; m++) x[m] = ab * P[m][c];
                for (int m = NCPU; m < NM; m++) x[m] = gl ? img[m - NCPU][i * 4 + c] : 0;
                for (int m = 0; m < NM; m++) se[m] += (x[m] - T[c]) * (x[m] - T[c]), sx[m] += x[m], bx[m][bin] += x[m], bse[m][bin] += (x[m] - T[c]) * (x[m] - T[c]);
                sr += T[c], br[bin] += T[c];
            }
            cnt += 3;
        }
        for (int m = 0; m < (gl ? NM : NCPU); m++) {
            if (notaps && m >= M_T2 && m < NCPU) continue;
            printf("%s,%.2f,%s,%.5f,%+.5f", envname, al, mname[m], sqrt(se[m] / cnt) / (sr / cnt), sx[m] / sr - 1);
            for (int b = 0; b < NB; b++) printf(",%.4f", br[b] > 0 ? bx[m][b] / br[b] : 0);
            for (int b = 0; b < NB; b++) printf(",%.3f", se[m] > 0 ? bse[m][b] / se[m] : 0);
            printf("\n");
            fflush(stdout);
        }
    }
    return 0;
}
