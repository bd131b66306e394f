/* envmap's image-based lighting term by term against its Monte Carlo reference (issue 16): the
 * diffuse and the specular parts of a GGX sphere separately (diffuse = the render with
 * ggx.zero_specular=true, specular = full − diffuse, in the split sum and in the reference alike),
 * and a Lambert sphere (the irradiance alone: SH and convolved against cosine-sampled Monte
 * Carlo), per α, metal and dielectric, per environment. The diffuse is also binned by μ = n·v
 * (mean ratio split sum / reference per bin), which tells a view-angle weighting error (it grows
 * towards the rim) from an irradiance error (it follows the environment).
 * Output: CSV on stdout, one row per (environment, material, α, term, method):
 *   env,material,alpha,term,method,rel_rms,rel_mean,ratio_mu<0.25,ratio_mu0.25-0.5,ratio_mu>0.5,flip,noise,noisy
 * rel_rms = √(mean |x − ref|²) / mean ref over the sphere's pixels (all three channels), each
 * term against the reference's same term. flip, noise, noisy: shadelab-bench's measures over the
 * sphere's pixels as bench/ibl_methods.c takes them (bench/ibl_metrics.h: the mean LDR-FLIP of the
 * image against the reference; the spread of samples 0 … n−1 of an n-frame still, n =
 * --noise-samples, SL_NOISE_SAMPLES unless told, 0 = not measured; noisy above SL_NOISE_VISIBLE),
 * for the whole image (terms "all" and "irradiance"); empty for the diffuse and specular terms,
 * which are differences of images.
 * Usage: envmap_bench_terms [--size N] [--reference-frames N] [--accumulate N] [--specular METHOD] [--set "ID=V ..."]
 *                           [--material metal|dielectric|lambert] [--env PATH|sky[:E]]...
 *                           [--sweep "LABEL=ID=V ID=V;LABEL=…"] [--noise-samples N]
 * --sweep: instead of the terms, the whole sphere ("all") for each labelled group of settings
 * (applied after --set), against one reference per environment and material (bench/levels.sh).
 * (plugins/envmap/bench/terms.sh runs it.) */
#include "ibl_sphere.h"
#include "ibl_metrics.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *materials[3][2] = {
    {"metal", "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 1, \"base_color\": [0.95, 0.64, 0.54]"},
    {"dielectric", "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 0, \"base_color\": [0.5, 0.5, 0.5]"},
    {"lambert", "\"model\": \"lambert\", \"base_color\": [0.5, 0.5, 0.5]"},
};
enum { NA = sizeof ibl_alphas / sizeof *ibl_alphas, NB = 3 };

/* μ = n·v of pixel i's sphere point (camera at (0, 0, 3.1) looking at the unit sphere, 40°), −1 off it */
static double pixel_mu(int i, int size) {
    double t = tan(20 * M_PI / 180);
    double dx = (2 * ((i % size) + 0.5) / size - 1) * t, dy = (1 - 2 * ((i / size) + 0.5) / size) * t, dz = -1;
    double l = sqrt(dx * dx + dy * dy + 1);
    dx /= l, dy /= l, dz /= l;
    double oz = 3.1, b = oz * dz, c = oz * oz - 1, disc = b * b - c;
    if (disc <= 0) return -1;
    double s = -b - sqrt(disc);
    double nx = s * dx, ny = s * dy, nz = oz + s * dz;
    return -(nx * dx + ny * dy + nz * dz);
}
/* x, ref: a term of the method and of the reference, each (a − b) when b is given; flip, noise:
 * NaN = empty */
static void row(const char *env, const char *mat, double alpha, const char *term, const char *method, const float *xa,
                const float *xb, const float *ra, const float *rb, const unsigned char *mask, int size, double flip,
                double noise) {
    int n = size * size;
    double se = 0, sr = 0, sx = 0, bx[NB] = {0}, br[NB] = {0};
    long count = 0;
    for (int i = 0; i < n; i++) {
        if (!mask[i]) continue;
        double mu = pixel_mu(i, size);
        int bin = mu < 0.25 ? 0 : mu < 0.5 ? 1 : 2;
        for (int c = 0; c < 3; c++) {
            double x = xa[i * 4 + c] - (xb ? xb[i * 4 + c] : 0), r = ra[i * 4 + c] - (rb ? rb[i * 4 + c] : 0);
            se += (x - r) * (x - r), sr += r, sx += x;
            bx[bin] += x, br[bin] += r;
        }
        count += 3;
    }
    printf("%s,%s,%.2f,%s,%s,%.5f,%+.5f", env, mat, alpha, term, method, sqrt(se / count) / (sr / count), sx / sr - 1);
    for (int b = 0; b < NB; b++) printf(",%.4f", br[b] > 0 ? bx[b] / br[b] : 0);
    if (isnan(flip)) printf(",");
    else printf(",%.5f", flip);
    if (isnan(noise)) printf(",,\n");
    else printf(",%.6f,%d\n", noise, noise > SL_NOISE_VISIBLE);
    fflush(stdout);
}

int main(int argc, char **argv) {
    int size = 48, ref_frames = 32, accumulate = 1, noise_samples = SL_NOISE_SAMPLES;
    const char *envs[8], *spec = "dominant", *extra = "", *only = NULL, *sweep = NULL;
    int ne = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--size") && i + 1 < argc) size = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--reference-frames") && i + 1 < argc) ref_frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--accumulate") && i + 1 < argc) accumulate = atoi(argv[++i]); /* frames per method render */
        else if (!strcmp(argv[i], "--specular") && i + 1 < argc) spec = argv[++i];
        else if (!strcmp(argv[i], "--set") && i + 1 < argc) extra = argv[++i];     /* more settings of the method */
        else if (!strcmp(argv[i], "--material") && i + 1 < argc) only = argv[++i]; /* metal, dielectric or lambert */
        else if (!strcmp(argv[i], "--sweep") && i + 1 < argc) sweep = argv[++i];
        else if (!strcmp(argv[i], "--env") && i + 1 < argc && ne < 8) envs[ne++] = argv[++i];
        else if (!strcmp(argv[i], "--noise-samples") && i + 1 < argc) noise_samples = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: %s [--size N] [--reference-frames N] [--specular METHOD] [--set \"ID=V ...\"] "
                    "[--material NAME] [--env PATH|sky[:E]]... [--sweep ...] [--noise-samples N]\n", argv[0]);
            return 2;
        }
    }
    if (!ne) envs[ne++] = "sky:0";
    if (noise_samples == 1) noise_samples = 0; /* one frame has no spread */
    int n = size * size;
    size_t img = (size_t)n * 4;
    float *refF = malloc(NA * img * 4), *refD = malloc(NA * img * 4), *x = malloc(img * 4), *xd = malloc(img * 4);
    float *scratch = malloc(img * 4), *map = malloc((size_t)n * sizeof *map);
    unsigned char *mask = malloc((size_t)n);
    if (!refF || !refD || !x || !xd || !scratch || !map || !mask) return 1;
    char buf[160];
    printf("env,material,alpha,term,method,rel_rms,rel_mean,ratio_mu<0.25,ratio_mu0.25-0.5,ratio_mu>0.5,flip,noise,noisy\n");
    for (int e = 0; e < ne; e++) {
        const char *envname = strrchr(envs[e], '/') ? strrchr(envs[e], '/') + 1 : envs[e];
        for (int m = 0; m < 3; m++) {
            if (only && strcmp(only, materials[m][0])) continue;
            bool lambert = m == 2;
            int na = lambert ? 1 : NA;
            sl_harness *h = ibl_sphere(envs[e], materials[m][1], size, ref_frames);
            if (!h || !ibl_set(h, "envmap.mode=reference envmap.reference_samples=64")) return 1;
            for (int a = 0; a < na; a++) {
                snprintf(buf, sizeof buf, "material.m.alpha=%g", ibl_alphas[a]);
                if (!ibl_set(h, buf) || !sl_harness_render(h, refF + a * img)) return 1;
                if (m == 0) memset(refD + a * img, 0, img * 4); /* metal: no diffuse */
                else if (!lambert && (!ibl_set(h, "ggx.zero_specular=true") || !sl_harness_render(h, refD + a * img) ||
                                      !ibl_set(h, "ggx.zero_specular=false")))
                    return 1;
            }
            sl_harness_destroy(h);
            for (int i = 0; i < n; i++) mask[i] = refF[i * 4] + refF[i * 4 + 1] + refF[i * 4 + 2] > 0 && pixel_mu(i, size) > 0;
            h = ibl_sphere(envs[e], materials[m][1], size, accumulate > 1 ? accumulate : 1);
            snprintf(buf, sizeof buf, "envmap.specular=%s %s", spec, extra);
            if (!h || !ibl_set(h, buf)) return 1;
            if (lambert) {
                const char *irr[2] = {"sh", "convolved"};
                for (int k = 0; k < 2; k++) {
                    snprintf(buf, sizeof buf, "envmap.irradiance=%s", irr[k]);
                    if (!ibl_set(h, buf) || !sl_harness_render(h, x)) return 1;
                    double flip = ibl_flip_over(x, refF, mask, size, map), noise = NAN;
                    if (noise_samples && isnan(noise = ibl_noise_over(h, noise_samples, mask, size, scratch, map))) return 1;
                    row(envname, "lambert", 0, "irradiance", irr[k], x, NULL, refF, NULL, mask, size, flip, noise);
                }
            }
            char list[4096];
            snprintf(list, sizeof list, "%s", sweep ? sweep : "");
            for (char *item = sweep ? list : NULL, *next; item && *item && !lambert; item = next) {
                next = strchr(item, ';');
                if (next) *next++ = 0;
                else next = item + strlen(item);
                char *eq = strchr(item, '=');
                if (!eq || !ibl_set(h, eq + 1)) return 1;
                *eq = 0;
                for (int a = 0; a < na; a++) {
                    snprintf(buf, sizeof buf, "material.m.alpha=%g", ibl_alphas[a]);
                    if (!ibl_set(h, buf) || !sl_harness_render(h, x)) return 1;
                    double flip = ibl_flip_over(x, refF + a * img, mask, size, map), noise = NAN;
                    if (noise_samples && isnan(noise = ibl_noise_over(h, noise_samples, mask, size, scratch, map))) return 1;
                    row(envname, materials[m][0], ibl_alphas[a], "all", item, x, NULL, refF + a * img, NULL, mask, size, flip,
                        noise);
                }
            }
            for (int a = 0; a < na && !lambert && !sweep; a++) {
                snprintf(buf, sizeof buf, "material.m.alpha=%g", ibl_alphas[a]);
                if (!ibl_set(h, buf) || !sl_harness_render(h, x)) return 1;
                double flip = ibl_flip_over(x, refF + a * img, mask, size, map), noise = NAN;
                if (noise_samples && isnan(noise = ibl_noise_over(h, noise_samples, mask, size, scratch, map))) return 1;
                row(envname, materials[m][0], ibl_alphas[a], "all", spec, x, NULL, refF + a * img, NULL, mask, size, flip, noise);
                if (m == 0) continue; /* metal: all specular */
                if (!ibl_set(h, "ggx.zero_specular=true") || !sl_harness_render(h, xd) || !ibl_set(h, "ggx.zero_specular=false")) return 1;
                row(envname, materials[m][0], ibl_alphas[a], "diffuse", spec, xd, NULL, refD + a * img, NULL, mask, size, NAN, NAN);
                row(envname, materials[m][0], ibl_alphas[a], "specular", spec, x, xd, refF + a * img, refD + a * img, mask, size, NAN,
                    NAN);
            }
            sl_harness_destroy(h);
        }
    }
    free(refF), free(refD), free(x), free(xd), free(scratch), free(map), free(mask);
    return 0;
}
