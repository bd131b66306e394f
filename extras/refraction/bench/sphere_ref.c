/* refraction_sphere_ref: error of refraction's methods against the CPU sphere reference
 * (tests/sphere_ref.h: analytic ray paths through the sphere, every internal bounce weighted by
 * Fresnel) on scenes/sphere.json's camera and environment.
 *
 *   refraction_sphere_ref SCENE W H LABEL "SETTINGS" [LABEL "SETTINGS" …]
 *
 * For each setting (space-separated --set assignments) prints one CSV line
 *   label,rmse,max_abs,pixels,flip
 * over every pixel whose ray hits the sphere: channels green (v, continuous everywhere) and red
 * (u) where every contributing lookup stays 0.03 away from the map's u seam; blue (0) too.
 * Settings with "material.glass.ior_rgb=" are compared channel by channel with their own η.
 * flip: the mean FLIP (Andersson et al. 2020; shadelab-bench's sl_metric_flip, the SDK's
 * shadelab::metrics) over the same pixels, of the whole image against the image with the
 * sphere's pixels replaced by the reference (red kept where it is not compared: near the seam). */
#include <shadelab/harness.h>
#include <shadelab/bench/metrics.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sphere_ref.h"

static char *slurp(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    s[fread(s, 1, (size_t)n, f)] = 0;
    fclose(f);
    return s;
}

int main(int argc, char **argv) {
    if (argc < 6 || (argc - 4) % 2) {
        fprintf(stderr, "usage: %s SCENE W H LABEL \"SETTINGS\" [LABEL \"SETTINGS\" ...]\n", argv[0]);
        return 2;
    }
    int w = atoi(argv[2]), h = atoi(argv[3]);
    if (w < 8 || h < 8 || w > 4096 || h > 4096) return fprintf(stderr, "size out of range\n"), 2;
    char *json = slurp(argv[1]);
    if (!json) return fprintf(stderr, "%s: cannot read\n", argv[1]), 1;
    const double cam_pos[3] = {0, 0, 4}, target[3] = {0, 0, 0}; /* scenes/sphere.json */
    rf_camera cam = rf_camera_make(cam_pos, target, 40, w, h);
    rf_sphere S = {{0, 0, 0}, 1};
    float *img = malloc(sizeof(float) * 4 * w * h), *refimg = malloc(sizeof(float) * 4 * w * h),
          *fmap = malloc(sizeof(float) * w * h);
    unsigned char *on = malloc((size_t)w * h);
    printf("label,rmse,max_abs,pixels,flip\n");
    for (int a = 4; a + 1 < argc; a += 2) {
        const char *settings[64];
        int ns = 0;
        char *copy = strdup(argv[a + 1]);
        for (char *t = strtok(copy, " "); t && ns < 63; t = strtok(NULL, " ")) settings[ns++] = t;
        settings[ns] = NULL;
        double ior[3] = {1.5, 1.5, 1.5};
        for (int i = 0; i < ns; i++) {
            if (!strncmp(settings[i], "material.glass.ior_rgb=", 23))
                sscanf(settings[i] + 23, "%lf,%lf,%lf", &ior[0], &ior[1], &ior[2]);
            else if (!strncmp(settings[i], "material.glass.ior=", 19))
                ior[0] = ior[1] = ior[2] = atof(settings[i] + 19);
        }
        const char *plugins[] = {RF_PLUGIN_PATH, NULL};
        char err[4096];
        sl_harness_desc d = {.struct_size = sizeof d, .width = w, .height = h, .scene_json = json, .plugins = plugins,
                             .settings = settings, .strict = true};
        sl_harness *hh = sl_harness_create(&d, err, sizeof err);
        if (!hh) return fprintf(stderr, "harness: %s\n", err), 1;
        sl_harness_set_frame(hh, 0);
        if (!sl_harness_render(hh, img)) return fprintf(stderr, "render failed\n"), 1;
        sl_harness_destroy(hh);
        double se = 0, worst = 0;
        long n = 0, px = 0;
        memcpy(refimg, img, sizeof(float) * 4 * w * h);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                double dir[3], ref[3], ci;
                on[(size_t)y * w + x] = 0;
                rf_camera_ray(&cam, x, y, w, h, dir);
                rf_seam_margin = 1;
                rf_trace(&S, cam_pos, dir, ior, false, ref, &ci);
                if (ci < 0) continue;
                px++;
                on[(size_t)y * w + x] = 1;
                const float *p = img + ((size_t)y * w + x) * 4;
                float *q = refimg + ((size_t)y * w + x) * 4;
                for (int k = 0; k < 3; k++) {
                    if (k == 0 && rf_seam_margin < 0.03) continue;
                    double e = p[k] - ref[k];
                    se += e * e, n++;
                    worst = fmax(worst, fabs(e));
                    q[k] = (float)ref[k];
                }
            }
        double fsum = 0;
        if (!isfinite(sl_metric_flip(img, refimg, w, h, 0, fmap))) return fprintf(stderr, "flip failed\n"), 1;
        for (size_t i = 0; i < (size_t)w * h; i++)
            if (on[i]) fsum += fmap[i];
        printf("%s,%.6f,%.6f,%ld,%.6f\n", argv[a], sqrt(se / (n ? n : 1)), worst, px, fsum / (px ? px : 1));
        fflush(stdout);
        free(copy);
    }
    free(img), free(refimg), free(fmap), free(on), free(json);
    return 0;
}
