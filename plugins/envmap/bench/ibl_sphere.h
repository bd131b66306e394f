/* The envmap benches' shared scene (ibl_methods.c, ibl_terms.c): one GGX or Lambert unit sphere
 * seen from (0, 0, 3.1) with a 40° lens, lit only by the environment `env` ("sky", "sky:E" with
 * E the procedural sun's irradiance, or an image path), background off, aa off, float32 read-back.
 * aa off: the aa plugin (loaded by default) jitters the frames of an accumulated render, so a
 * reference or accumulated fis render was a pixel-box average while single-frame methods sample
 * the pixel centre — a mismatch that added 0.02–0.08 to every single-frame row (sky metal
 * dominant α = 0.05: 0.080 with aa, 0.057 without). */
#ifndef ENVMAP_BENCH_IBL_SPHERE_H
#define ENVMAP_BENCH_IBL_SPHERE_H
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

/* The benches' sphere materials (ibl_methods.c, ibl_still.c), roughnesses and clock. */
static const char *const ibl_materials[2][2] = {
    {"metal", "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 1, \"base_color\": [0.95, 0.64, 0.54]"},
    {"dielectric", "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 0, \"base_color\": [0.5, 0.5, 0.5]"},
};
static const double ibl_alphas[] = {0.05, 0.2, 0.4, 0.7, 1.0};
static inline double ibl_now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

/* n·v at the centre of pixel (x, y) of the size × size image of the scene below (camera at
 * (0, 0, 3.1) looking at the unit sphere's centre, 40° lens), −1 off the sphere; symmetric in x
 * and y, so the image's row order does not matter */
static inline double ibl_sphere_nv(int x, int y, int size) {
    double t = tan(20 * M_PI / 180), d[3] = {((x + 0.5) / size * 2 - 1) * t, ((y + 0.5) / size * 2 - 1) * t, -1};
    double l = sqrt(d[0] * d[0] + d[1] * d[1] + 1);
    for (int k = 0; k < 3; k++) d[k] /= l;
    double b = 3.1 * d[2], c = 3.1 * 3.1 - 1, disc = b * b - c; /* |o + s d|² = 1, o = (0, 0, 3.1) */
    if (disc <= 0) return -1;
    double s = -b - sqrt(disc), n[3] = {s * d[0], s * d[1], 3.1 + s * d[2]};
    return -(n[0] * d[0] + n[1] * d[1] + n[2] * d[2]);
}

/* relative RMS and relative mean difference of x against ref over the sphere's pixels (mask: the
 * reference's alpha channel is no coverage mask; the sphere is where the reference is non-zero,
 * background off) */
static inline void ibl_compare(const float *x, const float *ref, const unsigned char *mask, int n, double *rel_rms,
                               double *rel_mean) {
    double se = 0, sr = 0, sx = 0;
    long count = 0;
    for (int i = 0; i < n; i++) {
        if (!mask[i]) continue;
        for (int c = 0; c < 3; c++) {
            double d = x[i * 4 + c] - ref[i * 4 + c];
            se += d * d, sr += ref[i * 4 + c], sx += x[i * 4 + c];
        }
        count += 3;
    }
    *rel_rms = sqrt(se / count) / (sr / count);
    *rel_mean = sx / sr - 1;
}

/* the scene's "plugins" list (JSON strings, comma-separated): envmap; a bench may name more
 * (ibl_methods.c --plugin: phong for its blinn-gloss) */
static char ibl_scene_plugins[512] = "\"envmap\"";

/* the lobe tests' measure (tests/test_envmap_lobes.c): 3 × 3 block means of x and ref at block
 * centres (1 + 3i, 1 + 3j), blocks wholly inside the mask; the RMS and the mean of
 * block(x)/block(ref) − 1 over the blocks and channels */
static inline void ibl_compare_blocks(const float *x, const float *ref, const unsigned char *mask, int size,
                                      double *rel_rms, double *rel_mean) {
    double se = 0, sm = 0;
    long count = 0;
    for (int py = 1; py < size - 1; py += 3)
        for (int px = 1; px < size - 1; px += 3) {
            bool all = true;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) all = all && mask[(py + dy) * size + px + dx];
            if (!all) continue;
            for (int c = 0; c < 3; c++) {
                double bx = 0, br = 0;
                for (int dy = -1; dy <= 1; dy++)
                    for (int dx = -1; dx <= 1; dx++) {
                        size_t i = ((size_t)(py + dy) * size + px + dx) * 4 + c;
                        bx += x[i], br += ref[i];
                    }
                if (br <= 0) continue;
                double e = bx / br - 1;
                se += e * e, sm += e, count++;
            }
        }
    *rel_rms = count ? sqrt(se / count) : NAN;
    *rel_mean = count ? sm / count : NAN;
}

/* `mat`: the material's JSON keys; `aa`: leave the aa plugin on (its defaults: a TAA still of
 * taa_frames jittered frames), as the viewer runs (bench/ibl_still.c) */
static sl_harness *ibl_sphere_aa(const char *env, const char *mat, int size, int accumulate, bool aa) {
    char json[4096], err[4096], envjson[1200];
    char sun[64] = "";
    if (!strncmp(env, "sky", 3)) {
        snprintf(envjson, sizeof envjson, "{}");
        if (env[3] == ':') snprintf(sun, sizeof sun, "envmap.sun_irradiance=%s", env + 4);
    }
    else snprintf(envjson, sizeof envjson, "{\"map\": \"%s\"}", env);
    snprintf(json, sizeof json,
             "{\"plugins\": [%s],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 3.1], \"target\": [0, 0, 0], \"fov_y\": 40}],\n"
             " \"materials\": [{\"name\": \"m\", %s, \"alpha\": 0.2}],\n"
             " \"nodes\": [{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1, \"segments\": 192, \"rings\": 96}, \"material\": \"m\"}],\n"
             " \"environment\": %s}",
             ibl_scene_plugins, mat, envjson);
    const char *settings[] = {"envmap.background=false", aa ? "aa.enabled=true" : "aa.enabled=false", sun[0] ? sun : NULL, NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = size, .height = size,
                                                          .scene_json = json, .settings = settings, .float32 = true,
                                                          .strict = true, .accumulate = accumulate},
                                      err, sizeof err);
    if (!h) fprintf(stderr, "harness: %s\n", err);
    return h;
}

static inline sl_harness *ibl_sphere(const char *env, const char *mat, int size, int accumulate) {
    return ibl_sphere_aa(env, mat, size, accumulate, false);
}

/* applies space-separated "id=value" settings; false (with the message on stderr) at the first refused */
static bool ibl_set(sl_harness *h, const char *text) {
    char buf[1024], err[512];
    snprintf(buf, sizeof buf, "%s", text);
    for (char *tok = strtok(buf, " "); tok; tok = strtok(NULL, " "))
        if (!sl_harness_set(h, tok, err, sizeof err)) {
            fprintf(stderr, "%s: %s\n", tok, err);
            return false;
        }
    return true;
}
#endif
