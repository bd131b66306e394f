/* What the viewer shows at rest (issue 16's default target): envmap's specular methods as a TAA
 * still — the aa plugin on with its defaults, `taa_frames` (16) jittered frames averaged, fis's
 * sample sequence continuing over them (sl_sample_index, ABI 1.9) — against the plugin's Monte
 * Carlo reference rendered **the same way**: aa on, the same still, each of its frames R × 64 spp
 * (`--reference-accumulate` R; reference_samples = 64 R, one render per frame: the aa plugin's TAA
 * pass runs before the post stage, i.e. inside an `accumulate` render's sub-frame loop, so an
 * accumulated render with aa on is not a TAA still). The reference's R2 sequence continues over the
 * still's frames (sl_sample_index): taa_frames × R × 64 spp a pixel, at the same Halton jitter
 * positions, so both images are the same pixel-footprint average and differ only by shading.
 * Also the first frame of each still alone (pixel centre, no jitter: what a frame in motion shows,
 * TAA's history aside) against a pixel-centre reference (aa off, taa_frames × R sub-frames).
 * Relative RMS and mean per sphere as bench/ibl_methods.c. The bench's spheres (ibl_sphere.h).
 * FLIP and noise as bench/ibl_methods.c (shadelab-bench's measures, tools/bench/include/bench/
 * metrics.h, over the sphere's pixels): still_flip, the still's against the reference still;
 * noise, the spread of the still's frames 0 … taa_frames−1, each rendered on its own
 * (sl_harness_render_sample: TAA restarts, so each is a pixel-centre frame), the sparkle while the
 * still settles; noisy = 1 above SL_NOISE_VISIBLE.
 * Output: CSV env,material,alpha,method,ms,still_rms,still_mean,frame_rms,frame_mean,still_flip,
 * noise,noisy (ms: the fastest frame of the still, read-back included).
 * Usage: envmap_bench_still [--size N] [--reference-accumulate R] [--env PATH|sky:E]...
 *        [--method NAME=SETTINGS]... (default: the list below). bench/still.sh runs it. */
#include "ibl_sphere.h"
#include "ibl_metrics.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { NA = sizeof ibl_alphas / sizeof *ibl_alphas, MAXM = 32 };
static const char *default_methods[] = {
    "mirror=envmap.specular=mirror", "dominant=envmap.specular=dominant",
    "fis4=envmap.specular=fis envmap.fis_samples=4", "fis8=envmap.specular=fis envmap.fis_samples=8",
    "fis16=envmap.specular=fis envmap.fis_samples=16",
    "hybrid8=envmap.specular=hybrid envmap.fis_samples=8", "hybrid16=envmap.specular=hybrid envmap.fis_samples=16",
    NULL};

/* renders a still of `frames` frames after `settings`; first = the first frame, img = the still */
static bool still(sl_harness *h, int frames, float *first, float *img, double *best) {
    *best = 1e30;
    for (int f = 0; f < frames; f++) {
        double t = ibl_now_ms();
        if (!sl_harness_render(h, f == 0 && first ? first : img)) return false;
        t = ibl_now_ms() - t;
        if (f > 0 && t < *best) *best = t;
    }
    return true;
}

int main(int argc, char **argv) {
    int size = 48, racc = 8, taa = 16;
    const char *envs[8], *methods[MAXM];
    int ne = 0, nm = 0;
    const char *only = NULL; /* --material metal|dielectric: one of the two */
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--size") && i + 1 < argc) size = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--reference-accumulate") && i + 1 < argc) racc = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--env") && i + 1 < argc && ne < 8) envs[ne++] = argv[++i];
        else if (!strcmp(argv[i], "--method") && i + 1 < argc && nm < MAXM) methods[nm++] = argv[++i];
        else if (!strcmp(argv[i], "--material") && i + 1 < argc) only = argv[++i];
        else {
            fprintf(stderr, "usage: %s [--size N] [--reference-accumulate R] [--env PATH|sky:E]... [--method NAME=SETTINGS]... [--material metal|dielectric]\n", argv[0]);
            return 2;
        }
    }
    if (!ne) envs[ne++] = "sky:0";
    if (!nm)
        for (; default_methods[nm]; nm++) methods[nm] = default_methods[nm];
    int n = size * size;
    size_t img_bytes = (size_t)n * 4 * sizeof(float);
    float *sref = malloc(NA * img_bytes), *fref = malloc(NA * img_bytes), *img = malloc(img_bytes), *first = malloc(img_bytes);
    unsigned char *mask = malloc((size_t)NA * n);
    float *map = malloc((size_t)n * sizeof *map);
    printf("env,material,alpha,method,ms,still_rms,still_mean,frame_rms,frame_mean,still_flip,noise,noisy\n");
    for (int e = 0; e < ne; e++)
        for (int m = 0; m < 2; m++) {
            if (only && strcmp(only, ibl_materials[m][0])) continue;
            const char *envname = strrchr(envs[e], '/') ? strrchr(envs[e], '/') + 1 : envs[e];
            char buf[512];
            /* the still reference (aa on) and the pixel-centre one (aa off), one harness at a time;
             * $ENVMAP_STILL_CACHE (a directory): kept there between runs (exploring methods) */
            const char *cache = getenv("ENVMAP_STILL_CACHE");
            char cpath[1024];
            snprintf(cpath, sizeof cpath, "%s/still-%s-%s-%d-%d.bin", cache ? cache : ".", envname, ibl_materials[m][0], size, racc);
            FILE *cf = cache ? fopen(cpath, "rb") : NULL;
            bool cached = cf && fread(&taa, sizeof taa, 1, cf) == 1 && fread(sref, img_bytes, NA, cf) == NA &&
                          fread(fref, img_bytes, NA, cf) == NA && fread(mask, (size_t)n, NA, cf) == NA;
            if (cf) fclose(cf);
            for (int pass = 0; pass < 2 && !cached; pass++) {
                sl_harness *h = ibl_sphere_aa(envs[e], ibl_materials[m][1], size, pass ? racc * taa : 1, pass == 0);
                snprintf(buf, sizeof buf, "envmap.mode=reference envmap.reference_samples=%d", pass ? 64 : 64 * racc);
                if (!h || !ibl_set(h, buf)) return 1;
                if (pass == 0) {
                    char v[32];
                    if (!sl_harness_get(h, "aa.taa_frames", v, sizeof v)) return 1;
                    taa = atoi(v); /* the aa plugin's default still */
                }
                for (int a = 0; a < NA; a++) {
                    snprintf(buf, sizeof buf, "material.m.alpha=%g", ibl_alphas[a]);
                    double best;
                    float *dst = (pass ? fref : sref) + (size_t)a * n * 4;
                    if (!ibl_set(h, buf) || !still(h, pass ? 1 : taa, NULL, dst, &best)) return 1;
                    if (pass == 0)
                        for (int i = 0; i < n; i++) mask[(size_t)a * n + i] = dst[i * 4] + dst[i * 4 + 1] + dst[i * 4 + 2] > 0;
                }
                sl_harness_destroy(h);
            }
            if (cache && !cached && (cf = fopen(cpath, "wb"))) {
                fwrite(&taa, sizeof taa, 1, cf), fwrite(sref, img_bytes, NA, cf), fwrite(fref, img_bytes, NA, cf);
                fwrite(mask, (size_t)n, NA, cf);
                fclose(cf);
            }
            sl_harness *h = ibl_sphere_aa(envs[e], ibl_materials[m][1], size, 1, true);
            if (!h) return 1;
            /* each method starts from the plugin's defaults: the settings of the one before are undone */
            static const char *const knobs[] = {"specular", "fis_samples", "fis_lod_bias", "hybrid_alpha"};
            char reset[256] = "";
            for (int i = 0; i < 4; i++) {
                char id[64], val[64];
                snprintf(id, sizeof id, "envmap.%s", knobs[i]);
                if (!sl_harness_get(h, id, val, sizeof val)) return 1;
                snprintf(reset + strlen(reset), sizeof reset - strlen(reset), "%s=%s ", id, val);
            }
            for (int a = 0; a < NA; a++)
                for (int k = 0; k < nm; k++) {
                    const char *eq = strchr(methods[k], '=');
                    if (!eq) return 2;
                    /* each method from the defaults: the settings of the one before are undone */
                    snprintf(buf, sizeof buf, "material.m.alpha=%g %s%s", ibl_alphas[a], reset, eq + 1);
                    double best, sr, sm, fr, fm;
                    if (!ibl_set(h, buf)) return 1;
                    /* compile, prefilter (one frame at a turned environment); then a still from a
                     * cut: the frame after yaw=0 sees an edit (a change of the values the last frame
                     * saw; a set and reset between two frames is none), so it is sample 0 with TAA
                     * restarted, what a frame in motion shows */
                    if (!ibl_set(h, "envmap.yaw=1") || !sl_harness_render(h, img) || !ibl_set(h, "envmap.yaw=0")) return 1;
                    if (!still(h, taa, first, img, &best)) return 1;
                    ibl_compare(img, sref + (size_t)a * n * 4, mask + (size_t)a * n, n, &sr, &sm);
                    ibl_compare(first, fref + (size_t)a * n * 4, mask + (size_t)a * n, n, &fr, &fm);
                    double flip = ibl_flip_over(img, sref + (size_t)a * n * 4, mask + (size_t)a * n, size, map);
                    double noise = ibl_noise_over(h, taa, mask + (size_t)a * n, size, img, map);
                    if (isnan(noise)) return 1;
                    printf("%s,%s,%.2f,%.*s,%.2f,%.5f,%+.5f,%.5f,%+.5f,%.5f,%.6f,%d\n", envname, ibl_materials[m][0], ibl_alphas[a],
                           (int)(eq - methods[k]), methods[k], best, sr, sm, fr, fm, flip, noise, noise > SL_NOISE_VISIBLE);
                    fflush(stdout);
                }
            sl_harness_destroy(h);
        }
    free(sref), free(fref), free(img), free(first), free(mask), free(map);
    return 0;
}
