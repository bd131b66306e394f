/* envmap's specular methods against its Monte Carlo reference, per sphere (issue 16): relative RMS
 * error and frame time for split-sum, dominant, fis N = 1 … 32 (and fis N = 32 with
 * irradiance=convolved accumulated over many frames: the highest setting's remaining bias), on a real HDR (Blender's courtyard.exr, Debian blender-data) and
 * the procedural sky without its sun ("sky:0"), metal (copper-like) and dielectric, α = 0.05 … 1.
 *
 * Relative RMS of a sphere = √(mean over its pixels of |x − ref|²) / mean over its pixels of ref
 * (luminance-free: all three channels), the sphere's pixels given by the depth of the frame (not
 * background). Milliseconds: the fastest of `--frames` single-frame renders with read-back.
 * FLIP and noise, shadelab-bench's measures (tools/bench/include/bench/metrics.h, library
 * shadelab_metrics), over the sphere's pixels: flip = the mean over them of the per-pixel LDR-FLIP
 * map of the timed frame against the reference (the whole images enter the filters); noise = the
 * RMS over them of the per-pixel spread of samples k = 0 … n−1 of an n-frame still, each rendered
 * on its own (sl_harness_render_sample; n = --noise-samples, SL_NOISE_SAMPLES unless told, 0 = not
 * measured: empty), measured for every method, deterministic ones included; noisy = 1 when the
 * noise exceeds SL_NOISE_VISIBLE (shadelab-bench's "noisy setting": on no Pareto front).
 * Output: CSV on stdout, one row per (environment, material, α, method).
 * Usage: envmap_bench_methods [--size N] [--frames N] [--reference-frames N] [--env PATH|sky]...
 *        [--method NAME="id=value ..."]... [--material NAME="JSON keys"]... [--plugin NAME]... [--alphas A,B,...]
 *        [--min-nv X] [--blocks] [--no-accumulated] [--noise-samples N]
 * --material replaces the two GGX spheres (any model: the reference integrates the model's own f;
 * α is set through the material key `alpha`, which ggx's surface hook writes to s.alpha for every
 * model that reads it), --plugin adds a plugin to the scene's list (a model's), --alphas the
 * roughness list, --min-nv X compares only the sphere's pixels with n·v > X at the pixel centre
 * (the lobe tests' region: the split sum's grazing rim left out), --blocks measures as the lobe
 * tests do (tests/test_envmap_lobes.c): the relative RMS of 3 × 3 block means, each block's error
 * relative to its own reference value, over the blocks wholly inside the compared pixels
 * (rel_mean: the mean of those relative errors).
 * (plugins/envmap/bench/methods.sh runs it and draws the charts; bench/lobes.sh, the lobe
 * contract's chart, runs it with phong's blinn-gloss beside ggx). */
#include "ibl_sphere.h"
#include "ibl_metrics.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const char *default_methods[][2] = {
    {"mirror", "envmap.specular=mirror"}, {"dominant", "envmap.specular=dominant"},
    {"fis1", "envmap.specular=fis envmap.fis_samples=1"}, {"fis2", "envmap.specular=fis envmap.fis_samples=2"},
    {"fis4", "envmap.specular=fis envmap.fis_samples=4"}, {"fis8", "envmap.specular=fis envmap.fis_samples=8"},
    {"fis16", "envmap.specular=fis envmap.fis_samples=16"}, {"fis32", "envmap.specular=fis envmap.fis_samples=32"},
    {"hybrid8", "envmap.specular=hybrid envmap.fis_samples=8"}, {"hybrid16", "envmap.specular=hybrid envmap.fis_samples=16"},
    {"filtered8", "envmap.specular=filtered envmap.filtered_samples=8"},
    {"filtered16", "envmap.specular=filtered envmap.filtered_samples=16"},
    {"filtered32", "envmap.specular=filtered envmap.filtered_samples=32"},
};
enum { MAX_METHODS = 64, MAX_ALPHAS = 32, MAX_MATERIALS = 8 };
static const char *methods[MAX_METHODS][2];
static int NM;
static double alphas[MAX_ALPHAS];
static int NA;
static const char *materials[MAX_MATERIALS][2];
static int NMAT;

/* ",flip,noise,noisy": noise and noisy empty when not measured */
static void print_flip_noise(double flip, double noise) {
    if (isnan(noise)) printf(",%.5f,,\n", flip);
    else printf(",%.5f,%.6f,%d\n", flip, noise, noise > SL_NOISE_VISIBLE);
}

int main(int argc, char **argv) {
    int size = 96, frames = 5, ref_frames = 64, noise_samples = SL_NOISE_SAMPLES;
    const char *envs[8];
    int ne = 0;
    bool accumulated = true;
    double min_nv = -2; /* -2: every pixel of the sphere */
    bool blocks = false;
    char *method_args[MAX_METHODS];
    int nmethod_args = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--size") && i + 1 < argc) size = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--method") && i + 1 < argc && nmethod_args < MAX_METHODS) method_args[nmethod_args++] = argv[++i];
        else if (!strcmp(argv[i], "--no-accumulated")) accumulated = false;
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc) frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--reference-frames") && i + 1 < argc) ref_frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--env") && i + 1 < argc && ne < 8) envs[ne++] = argv[++i];
        else if (!strcmp(argv[i], "--material") && i + 1 < argc && NMAT < MAX_MATERIALS) {
            char *eq = strchr(argv[++i], '=');
            if (!eq) {
                fprintf(stderr, "--material %s: expected NAME=\"JSON keys\"\n", argv[i]);
                return 2;
            }
            *eq = 0;
            materials[NMAT][0] = argv[i], materials[NMAT++][1] = eq + 1;
        }
        else if (!strcmp(argv[i], "--plugin") && i + 1 < argc) {
            size_t len = strlen(ibl_scene_plugins);
            snprintf(ibl_scene_plugins + len, sizeof ibl_scene_plugins - len, ", \"%s\"", argv[++i]);
        }
        else if (!strcmp(argv[i], "--min-nv") && i + 1 < argc) min_nv = atof(argv[++i]);
        else if (!strcmp(argv[i], "--blocks")) blocks = true;
        else if (!strcmp(argv[i], "--noise-samples") && i + 1 < argc) noise_samples = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--alphas") && i + 1 < argc) {
            NA = 0;
            for (char *tok = strtok(argv[++i], ","); tok && NA < MAX_ALPHAS; tok = strtok(NULL, ",")) alphas[NA++] = atof(tok);
        }
        else {
            fprintf(stderr, "usage: %s [--size N] [--frames N] [--reference-frames N] [--env PATH|sky]... "
                            "[--method NAME=\"id=value ...\"]... [--material NAME=\"JSON keys\"]... [--plugin NAME]... [--alphas A,B,...] "
                            "[--min-nv X] [--blocks] [--no-accumulated] [--noise-samples N]\n", argv[0]);
            return 2;
        }
    }
    if (!NMAT)
        for (int m = 0; m < 2; m++) materials[NMAT][0] = ibl_materials[m][0], materials[NMAT++][1] = ibl_materials[m][1];
    if (!NA)
        for (size_t a = 0; a < sizeof ibl_alphas / sizeof *ibl_alphas; a++) alphas[NA++] = ibl_alphas[a];
    if (!ne) envs[ne++] = "sky";
    for (int k = 0; k < nmethod_args; k++) { /* NAME=SETTINGS replaces the default list */
        char *eq = strchr(method_args[k], '=');
        if (!eq) {
            fprintf(stderr, "--method %s: expected NAME=\"id=value ...\"\n", method_args[k]);
            return 2;
        }
        *eq = 0;
        methods[NM][0] = method_args[k], methods[NM++][1] = eq + 1;
    }
    if (!nmethod_args)
        for (size_t k = 0; k < sizeof default_methods / sizeof *default_methods; k++)
            methods[NM][0] = default_methods[k][0], methods[NM++][1] = default_methods[k][1];
    int n = size * size;
    float *ref = malloc((size_t)NA * n * 16), *img = malloc((size_t)n * 16);
    unsigned char *mask = malloc((size_t)NA * n);
    float *map = malloc((size_t)n * sizeof *map);
    if (noise_samples == 1) noise_samples = 0; /* one frame has no spread */
    printf("env,material,alpha,method,ms,rel_rms,rel_mean,flip,noise,noisy\n");
    for (int e = 0; e < ne; e++)
        for (int m = 0; m < NMAT; m++) {
            const char *envname = strrchr(envs[e], '/') ? strrchr(envs[e], '/') + 1 : envs[e];
            /* one harness at a time (one GL context per process): the references of every α,
             * the single-frame methods, then fis N = 32 accumulated as long as the reference */
            char buf[128];
            sl_harness *h = ibl_sphere(envs[e], materials[m][1], size, ref_frames);
            if (!h || !ibl_set(h, "envmap.mode=reference envmap.reference_samples=64")) return 1;
            for (int a = 0; a < NA; a++) {
                snprintf(buf, sizeof buf, "material.m.alpha=%g", alphas[a]);
                double t0 = ibl_now_ms();
                if (!ibl_set(h, buf) || !sl_harness_render(h, ref + (size_t)a * n * 4)) return 1;
                printf("%s,%s,%.2f,reference,%.2f,0,0,0,,\n", envname, materials[m][0], alphas[a], (ibl_now_ms() - t0) / ref_frames);
                for (int i = 0; i < n; i++) {
                    const float *r = ref + ((size_t)a * n + i) * 4;
                    mask[(size_t)a * n + i] = r[0] + r[1] + r[2] > 0 && (min_nv < -1 || ibl_sphere_nv(i % size, i / size, size) > min_nv);
                }
            }
            sl_harness_destroy(h);
            h = ibl_sphere(envs[e], materials[m][1], size, 1);
            if (!h) return 1;
            for (int a = 0; a < NA; a++) {
                snprintf(buf, sizeof buf, "material.m.alpha=%g", alphas[a]);
                if (!ibl_set(h, buf)) return 1;
                for (int k = 0; k < NM; k++) {
                    if (!ibl_set(h, methods[k][1])) return 1;
                    double best = 1e30;
                    sl_harness_render(h, img); /* compile, prefilter */
                    for (int f = 0; f < frames; f++) {
                        double t = ibl_now_ms();
                        sl_harness_render(h, img);
                        t = ibl_now_ms() - t;
                        if (t < best) best = t;
                    }
                    double rr, rm;
                    if (blocks) ibl_compare_blocks(img, ref + (size_t)a * n * 4, mask + (size_t)a * n, size, &rr, &rm);
                    else ibl_compare(img, ref + (size_t)a * n * 4, mask + (size_t)a * n, n, &rr, &rm);
                    double flip = ibl_flip_over(img, ref + (size_t)a * n * 4, mask + (size_t)a * n, size, map);
                    double noise = noise_samples ? ibl_noise_over(h, noise_samples, mask + (size_t)a * n, size, img, map) : NAN;
                    if (noise_samples && isnan(noise)) return 1;
                    printf("%s,%s,%.2f,%s,%.2f,%.5f,%+.5f", envname, materials[m][0], alphas[a], methods[k][0], best, rr, rm);
                    print_flip_noise(flip, noise);
                    fflush(stdout);
                }
            }
            sl_harness_destroy(h);
            if (!accumulated) continue;
            h = ibl_sphere(envs[e], materials[m][1], size, ref_frames);
            /* the highest setting: fis N = 32 and the convolved irradiance (SH is band-limited) */
            /* (fis_lod_bias −1: the setting measured for this target before the default became 0 for
             * the TAA still, bench/still.sh) */
            if (!h || !ibl_set(h, "envmap.specular=fis envmap.fis_samples=32 envmap.fis_lod_bias=-1 envmap.irradiance=convolved")) return 1;
            for (int a = 0; a < NA; a++) {
                snprintf(buf, sizeof buf, "material.m.alpha=%g", alphas[a]);
                if (!ibl_set(h, buf) || !sl_harness_render(h, img)) return 1;
                double rr, rm;
                if (blocks) ibl_compare_blocks(img, ref + (size_t)a * n * 4, mask + (size_t)a * n, size, &rr, &rm);
                else ibl_compare(img, ref + (size_t)a * n * 4, mask + (size_t)a * n, n, &rr, &rm);
                printf("%s,%s,%.2f,fis32-accumulated,0,%.5f,%+.5f", envname, materials[m][0], alphas[a], rr, rm);
                print_flip_noise(ibl_flip_over(img, ref + (size_t)a * n * 4, mask + (size_t)a * n, size, map), NAN);
                fflush(stdout);
            }
            sl_harness_destroy(h);
        }
    free(ref), free(img), free(mask), free(map);
    return 0;
}
