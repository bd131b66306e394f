/* shadelab-skip-bench: frame times of a scene while nothing changes, while the camera orbits, while
 * a parameter of a plugin without shader chunks (tonemap's exposure) changes every frame, and while
 * a light changes every frame (everything re-runs): what declared pass dependencies (pass.h,
 * sl_depends) save. Prints the median wall time per frame of each case and the passes that ran in
 * its last frame. A benchmark: it prints, it asserts nothing.
 *
 *   shadelab-skip-bench SCENE.json [WxH] [FRAMES] [LIGHT]      (defaults 1280x720, 5, key)
 *   SHADELAB_DATA=../shared/assets ./build/shadelab-skip-bench scenes/skin_head.json 1280x720 5 key
 */
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int cmp(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static void passes_ran(sl_harness *h, char *out, size_t n) {
    sl_harness_structure s;
    sl_harness_structure_of(h, &s);
    out[0] = 0;
    for (int i = 0; i < s.pass_count; i++)
        snprintf(out + strlen(out), n - strlen(out), "%s%s", i ? " " : "", s.passes[i]);
}

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: shadelab-skip-bench SCENE.json [WxH] [FRAMES] [LIGHT]\n");
        return 2;
    }
    int w = 1280, hh = 720, frames = argc > 3 ? atoi(argv[3]) : 5;
    if (argc > 2 && sscanf(argv[2], "%dx%d", &w, &hh) != 2) return fprintf(stderr, "bad size %s\n", argv[2]), 2;
    if (frames < 1 || frames > 1000 || w < 1 || hh < 1 || w > 8192 || hh > 8192) return fprintf(stderr, "bad numbers\n"), 2;
    const char *light = argc > 4 ? argv[4] : "key";
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = w, .height = hh,
                                                          .scene_file = argv[1],
                                                          .plugins = (const char *[]){"tonemap", NULL}},
                                      err, sizeof err);
    if (!h) return fprintf(stderr, "%s\n", err), 1;
    double t0 = now_ms();
    sl_harness_set_frame(h, 0);
    if (!sl_harness_render(h, NULL)) return 1;
    printf("%s at %dx%d: first frame %.0f ms\n", argv[1], w, hh, now_ms() - t0);
    const char *cases[] = {"nothing changes", "camera orbits", "tonemap.exposure changes", "a light changes"};
    for (int c = 0; c < 4; c++) {
        double *ms = calloc(frames, sizeof *ms);
        for (int f = 0; f < frames; f++) {
            if (c == 1) {
                float a = 0.2f * (f + 1), eye[3] = {13 * sinf(a), 1.2f, 13 * cosf(a)}, target[3] = {0, 0.9f, 0};
                sl_harness_set_camera(h, eye, target);
            } else if (c == 2) {
                snprintf(err, sizeof err, "tonemap.exposure=%g", 0.1 * ((f % 2) + 1));
                sl_harness_set(h, err, err, sizeof err);
            } else if (c == 3) {
                char set[256];
                snprintf(set, sizeof set, "light.%s.intensity=%g", light, 2.0 + 0.1 * (f % 2));
                if (!sl_harness_set(h, set, err, sizeof err)) fprintf(stderr, "%s\n", err);
            }
            sl_harness_set_frame(h, 0);
            double t = now_ms();
            sl_harness_render(h, NULL);
            ms[f] = now_ms() - t;
        }
        char ran[2048];
        passes_ran(h, ran, sizeof ran);
        qsort(ms, frames, sizeof *ms, cmp);
        printf("%-26s median %8.1f ms/frame (min %.1f, %d frames); last frame ran: %s\n", cases[c], ms[frames / 2], ms[0],
               frames, ran);
        free(ms);
    }
    sl_harness_destroy(h);
    return 0;
}
