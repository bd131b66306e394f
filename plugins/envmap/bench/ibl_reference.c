/* How fast envmap's reference converges (issue 42, item 4): a row of six unit-radius spheres —
 * a white Lambert one and GGX metal (F0 = the benches' copper) at α = 0.05, 0.2, 0.4, 0.7, 1 —
 * under a lat-long environment, `--reference envmap` as the viewer renders it (its declared
 * settings and frames, or --frames/--samples), SIZE² (default 512²), aa off, background off.
 * The same render is repeated with envmap.reference_seed = 0 … SEEDS − 1: independent estimates,
 * so the spread of each sphere's mean radiance across seeds is the reference's noise on sphere
 * means (relative standard deviation of one render's mean), and the per-pixel noise of one render
 * (√(mean (a − b)²/2) over a sphere's pixels of seeds 0 and 1, over the sphere's mean: what a chart
 * against this reference sees as its floor), printed with the wall and CPU time of one render. `--no-env-sampling` renders the same with envmap.reference_env_sampling=false
 * (BRDF sampling alone, the reference before issue 42) for comparison.
 * Usage: envmap_bench_reference --env PATH [--size N] [--frames N] [--samples N] [--seeds N]
 *        [--no-env-sampling]
 * Output: CSV env,sampling,frames,samples,seconds,cpu_seconds,sphere,mean,rel_noise,pixel_noise */
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

enum { SPHERES = 6, MAX_SEEDS = 16 };
static const char *const names[SPHERES] = {"lambert", "metal0.05", "metal0.2", "metal0.4", "metal0.7", "metal1"};

static double wall_s(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}
static double cpu_s(void) {
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_utime.tv_sec + u.ru_stime.tv_sec + (u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6;
}

static sl_harness *make(const char *env, int size, int frames, int samples, int seed, bool env_sampling) {
    char json[8192], err[4096];
    int n = snprintf(json, sizeof json,
                     "{\"plugins\": [\"envmap\"],\n"
                     " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 7.5], \"target\": [0, 0, 0], \"fov_y\": 48}],\n"
                     " \"materials\": [{\"name\": \"m0\", \"model\": \"lambert\", \"base_color\": [1, 1, 1]}");
    const double alphas[5] = {0.05, 0.2, 0.4, 0.7, 1.0};
    for (int i = 0; i < 5; i++)
        n += snprintf(json + n, sizeof json - n,
                      ", {\"name\": \"m%d\", \"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 1, "
                      "\"base_color\": [0.95, 0.64, 0.54], \"alpha\": %g}", i + 1, alphas[i]);
    n += snprintf(json + n, sizeof json - n, "],\n \"nodes\": [");
    for (int i = 0; i < SPHERES; i++)
        n += snprintf(json + n, sizeof json - n,
                      "%s{\"name\": \"s%d\", \"translate\": [%g, 0, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.46, "
                      "\"segments\": 128, \"rings\": 64}, \"material\": \"m%d\"}",
                      i ? ", " : "", i, (i - 2.5) * 1.0, i);
    snprintf(json + n, sizeof json - n, "],\n \"environment\": {\"map\": \"%s\"}}", env);
    char seed_s[64], samples_s[64];
    snprintf(seed_s, sizeof seed_s, "envmap.reference_seed=%d", seed);
    snprintf(samples_s, sizeof samples_s, "envmap.reference_samples=%d", samples);
    const char *settings[] = {"envmap.mode=reference", samples_s, seed_s, "envmap.background=false", "aa.enabled=false",
                              env_sampling ? "envmap.reference_env_sampling=true" : "envmap.reference_env_sampling=false", NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = size, .height = size,
                                                          .scene_json = json, .settings = settings, .float32 = true,
                                                          .strict = true, .accumulate = frames},
                                      err, sizeof err);
    if (!h) fprintf(stderr, "harness: %s\n", err);
    return h;
}

/* each sphere's mean radiance (all channels) over the pixels of its column band that are not
 * black; with `other` (another seed's image), also √(mean (a − b)²/2) over them in `noise` */
static void sphere_means(const float *img, const float *other, int size, double out[SPHERES], double noise[SPHERES]) {
    for (int s = 0; s < SPHERES; s++) {
        double sum = 0, se = 0;
        long count = 0;
        int x0 = size * s / SPHERES, x1 = size * (s + 1) / SPHERES;
        for (int y = 0; y < size; y++)
            for (int x = x0; x < x1; x++) {
                size_t i = ((size_t)y * size + x) * 4;
                const float *p = img + i;
                if (p[0] + p[1] + p[2] <= 0) continue;
                sum += p[0] + p[1] + p[2], count++;
                for (int c = 0; other && c < 3; c++) se += (p[c] - other[i + c]) * (p[c] - other[i + c]) / 2;
            }
        out[s] = count ? sum / (3.0 * count) : 0;
        if (noise) noise[s] = count ? sqrt(se / (3.0 * count)) : 0;
    }
}

int main(int argc, char **argv) {
    const char *env = NULL;
    int size = 512, frames = 16, samples = 64, seeds = 4;
    bool env_sampling = true;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--env") && i + 1 < argc) env = argv[++i];
        else if (!strcmp(argv[i], "--size") && i + 1 < argc) size = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc) frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--samples") && i + 1 < argc) samples = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--seeds") && i + 1 < argc) seeds = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--no-env-sampling")) env_sampling = false;
        else {
            fprintf(stderr, "usage: %s --env PATH [--size N] [--frames N] [--samples N] [--seeds N] [--no-env-sampling]\n", argv[0]);
            return 2;
        }
    }
    if (!env || seeds < 2 || seeds > MAX_SEEDS || size < 16 || frames < 1 || samples < 1) {
        fprintf(stderr, "%s: --env is required; 2 <= seeds <= %d\n", argv[0], MAX_SEEDS);
        return 2;
    }
    float *img = malloc((size_t)size * size * 16), *first = malloc((size_t)size * size * 16);
    double means[MAX_SEEDS][SPHERES], noise[SPHERES], seconds = 1e30, cpu = 1e30;
    for (int s = 0; s < seeds; s++) {
        sl_harness *h = make(env, size, frames, samples, s, env_sampling);
        if (!h) return 1;
        /* the first render compiles and uploads: time the second (same seed, same image) */
        if (!sl_harness_render(h, img)) return 1;
        double w = wall_s(), c = cpu_s();
        if (!sl_harness_render(h, img)) return 1;
        w = wall_s() - w, c = cpu_s() - c;
        if (w < seconds) seconds = w, cpu = c;
        sphere_means(img, s == 1 ? first : NULL, size, means[s], s == 1 ? noise : NULL);
        if (s == 0) memcpy(first, img, (size_t)size * size * 16);
        sl_harness_destroy(h);
    }
    const char *envname = strrchr(env, '/') ? strrchr(env, '/') + 1 : env;
    printf("env,sampling,frames,samples,seconds,cpu_seconds,sphere,mean,rel_noise,pixel_noise\n");
    for (int k = 0; k < SPHERES; k++) {
        double m = 0, v = 0;
        for (int s = 0; s < seeds; s++) m += means[s][k] / seeds;
        for (int s = 0; s < seeds; s++) v += (means[s][k] - m) * (means[s][k] - m) / (seeds - 1);
        printf("%s,%s,%d,%d,%.1f,%.1f,%s,%.5f,%.5f,%.4f\n", envname, env_sampling ? "mis" : "brdf", frames, samples, seconds,
               cpu, names[k], m, m > 0 ? sqrt(v) / m : 0, m > 0 ? noise[k] / m : 0);
    }
    free(img), free(first);
    return 0;
}
