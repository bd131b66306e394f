/* many-lights chart: ms per frame against light count (1 … 4096) for the four methods, on the
 * spheres scene (five spheres and a ground plane, as scenes/spheres.json) or, with --head DIR,
 * the head model, with N animated point lights (every 8th a spot) spread over the scene. Writes
 * PREFIX.csv and PREFIX.png (gnuplot). Not a test: it prints figures.
 *
 *   many_lights_chart [--size 1280x720] [--frames 5] [--max-brute 256] [--head PATH.obj|.glb]
 *     (--max-brute: brute force and plain deferred, both every light at every pixel, only up to it)
 *                     [--counts 1,4,16,...] [--methods brute,deferred,tiled,clustered]
 *                     [--set plugin.param=value ...] [--out bench/many-lights-ms]
 *                     [--lists]   (also the mean list length and in-range count per pixel)
 *                     [--plugin PATH.so]   (another build of the plugin: profiling variants)
 *   many_lights_chart --write-scene N PATH [--head MESH]   the N-light scene as JSON
 *   many_lights_chart --interleave R [--counts 1,1024] [--methods ...] [--plugin-b PATH.so] ...
 *     the target's ratio measured interleaved (below): one harness per (count, method[, plugin]),
 *     all created first, then R rounds each rendering one frame of every harness in turn
 *
 * Timing: wall clock and CPU time of the whole process (getrusage: every llvmpipe thread) of
 * sl_harness_render (render + glFinish + read-back of the float image, the same overhead for
 * every method) over --frames after one warm-up frame: the median wall clock and the smallest
 * CPU time (the frame least disturbed by other work); lights animate (each frame is a new time
 * step). The chart plots the CPU time, which a machine shared with other work moves much less
 * than the wall clock; the CSV has both.
 *
 * --interleave: on a shared machine the CPU time of a frame moves with other work too (up to 2×
 * between runs minutes apart, more for long frames than short ones), so the ratio of two figures
 * taken at different moments is not robust. This mode renders the one-light and the N-light
 * frames alternately in the same rounds: per round, the cheapest one-light frame and the cheapest
 * N-light frame (over the methods) give one ratio; it prints the median and the range of the
 * per-round ratios and each configuration's median and smallest CPU ms. With --plugin-b every
 * configuration runs with a second build of the plugin as well (A/B of a change, same rounds). */
#include <shadelab/harness.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}
/* CPU time of the whole process (every llvmpipe thread), ms: on a machine shared with other
 * work this moves much less than the wall clock */
static double cpu_ms(void) {
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return (u.ru_utime.tv_sec + u.ru_stime.tv_sec) * 1e3 + (u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-3;
}
static int cmpd(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* N lights at 0.2-1.7 m over the 14 m ground, each of intensity I = 0.03 (colour up to 1): at the
 * default epsilon 0.01 a range of sqrt(0.03/0.01) = 1.73 m, so a point of the ground is within
 * range of about N/18 lights (the same kind of light, more of them) */
static char *scene(int n, const char *head, bool file) {
    size_t cap = 4096 + (size_t)n * 300;
    char *b = malloc(cap);
    /* a file names many-lights too; the charts load it (or another build of it) by path */
    int k = snprintf(b, cap, "{ \"plugins\": [%s\"ggx\", \"spotlight-shadow\"],\n", file ? "\"many-lights\", " : "");
    k += snprintf(b + k, cap - k,
        "  \"cameras\": [{\"name\": \"main\", \"position\": [0, 2.5, 7.5], \"target\": [0, 0.7, 0], \"fov_y\": 40}],\n"
        "  \"environment\": {\"color\": [1, 1, 1], \"intensity\": 0.05},\n"
        "  \"materials\": [ {\"name\": \"ground\", \"base_color_map\": \"checker:16:0.8,0.8,0.8:0.3,0.3,0.3\"},\n"
        "    {\"name\": \"red\", \"model\": \"ggx\", \"base_color\": [0.85, 0.2, 0.15], \"roughness\": 0.4},\n"
        "    {\"name\": \"blue\", \"model\": \"ggx\", \"base_color\": [0.15, 0.3, 0.85], \"roughness\": 0.6},\n"
        "    {\"name\": \"yellow\", \"base_color\": [0.9, 0.75, 0.2]}, {\"name\": \"white\", \"base_color\": [0.8, 0.8, 0.8]} ],\n"
        "  \"nodes\": [ {\"name\": \"ground\", \"mesh\": {\"primitive\": \"plane\", \"size\": 14}, \"material\": \"ground\"}");
    if (head)
        k += snprintf(b + k, cap - k, ",\n    {\"name\": \"head\", \"translate\": [0, 1.0, 0], \"scale\": 0.25, \"mesh\": {\"file\": \"%s\"}, \"material\": \"white\"}", head);
    else
        k += snprintf(b + k, cap - k,
            ",\n    {\"name\": \"a\", \"translate\": [-2.4, 0.7, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.7}, \"material\": \"red\"},\n"
            "    {\"name\": \"b\", \"translate\": [-0.8, 0.7, -0.8], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.7}, \"material\": \"blue\"},\n"
            "    {\"name\": \"c\", \"translate\": [0.8, 0.7, -0.8], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.7}, \"material\": \"white\"},\n"
            "    {\"name\": \"d\", \"translate\": [2.4, 0.7, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.7}, \"material\": \"yellow\"},\n"
            "    {\"name\": \"e\", \"translate\": [0, 0.35, 1.2], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.35}, \"material\": \"white\"}");
    k += snprintf(b + k, cap - k, " ],\n  \"lights\": [");
    unsigned seed = 777;
#define RND() ((seed = seed * 1103515245u + 12345u) >> 8 & 0xffff) / 65535.0f
    const float I = 0.03f;
    for (int i = 0; i < n; i++) {
        float x = -6.5f + 13 * RND(), z = -6.5f + 13 * RND(), y = 0.2f + 1.5f * RND();
        bool spot = i % 8 == 7;
        k += snprintf(b + k, cap - k,
                      "%s\n    {\"name\": \"l%d\", \"type\": \"%s\", \"position\": [%.3f, %.3f, %.3f], \"color\": [%.3f, %.3f, %.3f], "
                      "\"intensity\": %.4f, \"animate\": \"orbit\", \"animate_speed\": %.3f%s}",
                      i ? "," : "", i, spot ? "spot" : "point", x, y, z, 0.4f + 0.6f * RND(), 0.4f + 0.6f * RND(),
                      0.4f + 0.6f * RND(), I, 0.1f + 0.3f * RND(), spot ? ", \"direction\": [0, -1, 0], \"cone_angle\": 45" : "");
    }
    snprintf(b + k, cap - k, "\n  ]\n}\n");
    return b;
}

/* --interleave (header comment): R rounds over every (count, method, plugin) configuration, each
 * in its own process (the harness's GL context is per process): the parent asks each child in
 * turn for one frame over a pipe, so only one renders at any time */
static int interleave(int rounds, int W, int H, const int *counts, int nc, const bool run[4], int max_brute,
                      const char *head, const char *const *extra, int nset, const char *plug_a, const char *plug_b) {
    static const char *const methods[] = {"brute", "deferred", "tiled", "clustered"};
    enum { MAXC = 32 };
    struct cfg { int count, method, plugin, to, from; pid_t pid; double cpu[100], wall[100]; } *cf = calloc(MAXC, sizeof *cf);
    int n = 0;
    for (int c = 0; c < nc; c++)
        for (int m = 0; m < 4; m++)
            for (int pb = 0; pb < (plug_b ? 2 : 1); pb++) {
                if (!run[m] || (m <= 1 && counts[c] > max_brute) || n >= MAXC) continue;
                int down[2], up[2];
                if (pipe(down) || pipe(up)) return 1;
                fflush(stdout), fflush(stderr);
                pid_t pid = fork();
                if (pid < 0) return 1;
                if (pid == 0) { /* child: one harness, one frame per request */
                    close(down[1]), close(up[0]);
                    for (int i = 0; i < n; i++) close(cf[i].to), close(cf[i].from); /* the other children's pipes */
                    char *json = scene(counts[c], head, false);
                    char set[96], err[4096];
                    snprintf(set, sizeof set, "many-lights.method=%s", methods[m]);
                    const char *settings[18] = {set};
                    for (int k = 0; k < nset; k++) settings[1 + k] = extra[k];
                    settings[1 + nset] = NULL;
                    const char *plugins[] = {pb ? plug_b : plug_a, "ggx", "spotlight-shadow", NULL};
                    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W,
                                                                         .height = H, .scene_json = json, .plugins = plugins,
                                                                         .settings = settings, .strict = true},
                                                      err, sizeof err);
                    if (!h) { fprintf(stderr, "%s\n", err); _exit(1); }
                    char v[64];
                    if (sl_harness_get(h, "aa.enabled", v, sizeof v)) sl_harness_set(h, "aa.enabled=false", err, sizeof err);
                    float *img = malloc(sizeof(float) * W * H * 4);
                    sl_harness_render(h, img); /* warm-up: compiles */
                    char cmd;
                    double res[2] = {0, 0};
                    if (write(up[1], res, sizeof res) != sizeof res) _exit(1); /* ready */
                    while (read(down[0], &cmd, 1) == 1 && cmd == 'r') {
                        double t0 = now_ms(), u0 = cpu_ms();
                        sl_harness_render(h, img);
                        res[0] = cpu_ms() - u0, res[1] = now_ms() - t0;
                        if (write(up[1], res, sizeof res) != sizeof res) break;
                    }
                    sl_harness_destroy(h);
                    _exit(0);
                }
                close(down[0]), close(up[1]);
                double ready[2];
                if (read(up[0], ready, sizeof ready) != sizeof ready) { fprintf(stderr, "a configuration failed to start\n"); return 1; }
                cf[n++] = (struct cfg){.count = counts[c], .method = m, .plugin = pb, .to = down[1], .from = up[0], .pid = pid};
            }
    double ratio[2][100];
    for (int r = 0; r < rounds; r++) {
        double best[2][2] = {{INFINITY, INFINITY}, {INFINITY, INFINITY}}; /* [plugin][first count / last count] */
        for (int i = 0; i < n; i++) {
            double res[2];
            if (write(cf[i].to, "r", 1) != 1 || read(cf[i].from, res, sizeof res) != sizeof res) { fprintf(stderr, "a configuration died\n"); return 1; }
            cf[i].cpu[r] = res[0], cf[i].wall[r] = res[1];
            int slot = cf[i].count == counts[0] ? 0 : cf[i].count == counts[nc - 1] ? 1 : -1;
            if (slot >= 0 && res[0] < best[cf[i].plugin][slot]) best[cf[i].plugin][slot] = res[0];
        }
        for (int pb = 0; pb < 2; pb++) ratio[pb][r] = best[pb][1] / best[pb][0];
    }
    for (int i = 0; i < n; i++) { /* 'q': stop */
        if (write(cf[i].to, "q", 1) != 1) fprintf(stderr, "a configuration died\n");
        close(cf[i].to), close(cf[i].from), waitpid(cf[i].pid, NULL, 0);
    }
    printf("interleaved, %d rounds, %dx%d; CPU ms per frame (median, smallest), wall ms (median)\n", rounds, W, H);
    double med[MAXC];
    for (int i = 0; i < n; i++) {
        double u[100], t[100];
        memcpy(u, cf[i].cpu, rounds * sizeof *u), memcpy(t, cf[i].wall, rounds * sizeof *t);
        qsort(u, rounds, sizeof *u, cmpd), qsort(t, rounds, sizeof *t, cmpd);
        med[i] = u[rounds / 2];
        printf("  %5d lights %-9s %s  cpu %7.1f  min %7.1f  wall %7.1f\n", cf[i].count, methods[cf[i].method],
               cf[i].plugin ? "B" : "A", u[rounds / 2], u[0], t[rounds / 2]);
    }
    for (int pb = 0; pb < (plug_b ? 2 : 1); pb++) {
        qsort(ratio[pb], rounds, sizeof **ratio, cmpd);
        printf("%d lights / %d light%s (plugin %s), cheapest method of each per round: median %.2fx CPU time, range %.2f-%.2fx\n",
               counts[nc - 1], counts[0], counts[0] == 1 ? "" : "s", pb ? "B" : "A", ratio[pb][rounds / 2],
               ratio[pb][0], ratio[pb][rounds - 1]);
    }
    for (int i = 0; i < n; i++)
        if (plug_b && cf[i].plugin == 0)
            for (int j = 0; j < n; j++)
                if (cf[j].plugin == 1 && cf[j].count == cf[i].count && cf[j].method == cf[i].method)
                    printf("  B / A %5d lights %-9s %.3f (medians)\n", cf[i].count, methods[cf[i].method], med[j] / med[i]);
    free(cf);
    return 0;
}

int main(int argc, char **argv) {
    int W = 1280, H = 720, frames = 5, max_brute = 256, nset = 0;
    bool lists = false;
    const char *plugin = MANY_LIGHTS_PLUGIN, *plugin_b = NULL;
    int rounds = 0;
    const char *out = "many-lights-ms", *head = NULL, *counts_s = "1,4,16,64,256,1024,2048,4096";
    const char *methods_s = "brute,deferred,tiled,clustered", *extra[16];
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--write-scene") && i + 2 < argc) {
            char *s = scene(atoi(argv[i + 1]), i + 3 < argc && !strcmp(argv[i + 3], "--head") && i + 4 < argc ? argv[i + 4] : NULL, true);
            FILE *f = fopen(argv[i + 2], "w");
            if (!f) return 1;
            fputs(s, f);
            fclose(f);
            free(s);
            return 0;
        }
        if (!strcmp(argv[i], "--size") && i + 1 < argc) sscanf(argv[++i], "%dx%d", &W, &H);
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc) frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--max-brute") && i + 1 < argc) max_brute = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--head") && i + 1 < argc) head = argv[++i];
        else if (!strcmp(argv[i], "--counts") && i + 1 < argc) counts_s = argv[++i];
        else if (!strcmp(argv[i], "--methods") && i + 1 < argc) methods_s = argv[++i];
        else if (!strcmp(argv[i], "--set") && i + 1 < argc && nset < 15) extra[nset++] = argv[++i];
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) out = argv[++i];
        else if (!strcmp(argv[i], "--lists")) lists = true;
        else if (!strcmp(argv[i], "--plugin") && i + 1 < argc) plugin = argv[++i];
        else if (!strcmp(argv[i], "--plugin-b") && i + 1 < argc) plugin_b = argv[++i];
        else if (!strcmp(argv[i], "--interleave") && i + 1 < argc) rounds = atoi(argv[++i]);
        else { fprintf(stderr, "unknown argument %s\n", argv[i]); return 2; }
    }
    if (frames < 1 || frames > 100 || W < 16 || H < 16 || W > 4096 || H > 4096) { fprintf(stderr, "bad size/frames\n"); return 2; }
    int counts[32], nc = 0;
    for (const char *p = counts_s; *p && nc < 32;) {
        counts[nc++] = atoi(p);
        p = strchr(p, ',');
        if (!p) break;
        p++;
    }
    static const char *const methods[] = {"brute", "deferred", "tiled", "clustered"};
    bool run[4];
    for (int m = 0; m < 4; m++) {
        const char *p = strstr(methods_s, methods[m]);
        run[m] = p && (p == methods_s || p[-1] == ',') && (p[strlen(methods[m])] == ',' || !p[strlen(methods[m])]);
    }
    if (rounds) {
        if (rounds < 1 || rounds > 100 || nc < 2) { fprintf(stderr, "--interleave: 1-100 rounds and two or more counts\n"); return 2; }
        return interleave(rounds, W, H, counts, nc, run, max_brute, head, extra, nset, plugin, plugin_b);
    }
    char csv[1024], png[1024];
    snprintf(csv, sizeof csv, "%s.csv", out);
    snprintf(png, sizeof png, "%s.png", out);
    FILE *f = fopen(csv, "w");
    if (!f) { fprintf(stderr, "cannot write %s\n", csv); return 1; }
    fprintf(f, "lights,brute_ms,deferred_ms,tiled_ms,clustered_ms,brute_cpu_ms,deferred_cpu_ms,tiled_cpu_ms,clustered_cpu_ms\n");
    float *img = malloc(sizeof(float) * W * H * 4);
    double best_cpu[32], best_wall[32];
    for (int c = 0; c < nc; c++) {
        int n = counts[c];
        best_cpu[c] = best_wall[c] = INFINITY;
        if (n < 1 || n > 4096) continue;
        char *json = scene(n, head, false);
        double wall[4] = {NAN, NAN, NAN, NAN}, cpu[4] = {NAN, NAN, NAN, NAN};
        printf("%5d lights:", n);
        for (int m = 0; m < 4; m++) {
            if (!run[m]) continue;
            if (m <= 1 && n > max_brute) { /* brute and plain deferred: every light at every pixel */ printf("  %s -", methods[m]); continue; }
            char set[96], err[4096];
            snprintf(set, sizeof set, "many-lights.method=%s", methods[m]);
            const char *settings[18] = {set};
            for (int k = 0; k < nset; k++) settings[1 + k] = extra[k];
            settings[1 + nset] = NULL;
            const char *plugins[] = {plugin, "ggx", "spotlight-shadow", NULL};
            sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W,
                                                                 .height = H, .scene_json = json, .plugins = plugins,
                                                                 .settings = settings, .strict = true},
                                              err, sizeof err);
            if (!h) { fprintf(stderr, "%s\n", err); return 1; }
            char v[64];
            if (sl_harness_get(h, "aa.enabled", v, sizeof v)) sl_harness_set(h, "aa.enabled=false", err, sizeof err);
            sl_harness_render(h, img); /* warm-up: compiles */
            double t[100], u[100];
            for (int k = 0; k < frames; k++) {
                double t0 = now_ms(), u0 = cpu_ms();
                sl_harness_render(h, img);
                t[k] = now_ms() - t0, u[k] = cpu_ms() - u0;
            }
            qsort(t, frames, sizeof *t, cmpd);
            qsort(u, frames, sizeof *u, cmpd);
            wall[m] = t[frames / 2], cpu[m] = u[0]; /* CPU: the least disturbed frame */
            if (cpu[m] < best_cpu[c]) best_cpu[c] = cpu[m];
            if (wall[m] < best_wall[c]) best_wall[c] = wall[m];
            printf("  %s %.0f (cpu %.0f)", methods[m], wall[m], cpu[m]);
            if (lists && m >= 2 && sl_harness_set_debug_view(h, "many-lights-count", err, sizeof err)) {
                /* the count view: r = lights in the pixel's list, g = lights within range there,
                 * b = lights with a range (= n on the scene's surfaces) */
                sl_harness_render(h, img);
                double listed = 0, inrange = 0;
                long px = 0;
                for (long p = 0; p < (long)W * H; p++)
                    if (fabsf(img[4 * p + 2] - n) < 0.5f) listed += img[4 * p], inrange += img[4 * p + 1], px++;
                if (px) printf(" [per pixel: %.1f listed, %.1f in range]", listed / px, inrange / px);
            }
            fflush(stdout);
            sl_harness_destroy(h);
        }
        fprintf(f, "%d", n);
        for (int m = 0; m < 8; m++) {
            double x = m < 4 ? wall[m] : cpu[m - 4];
            if (isnan(x)) fprintf(f, ",");
            else fprintf(f, ",%.2f", x);
        }
        fprintf(f, "\n");
        printf(" ms\n");
        fflush(f);
        free(json);
    }
    fclose(f);
    free(img);
    for (int c = 0; c < nc; c++) /* the target: the best method's frame against the best one-light frame */
        if (counts[c] > 1 && counts[0] == 1 && isfinite(best_cpu[c]) && isfinite(best_cpu[0]))
            printf("%d lights / 1 light, best methods: %.1fx CPU time, %.1fx wall clock\n", counts[c],
                   best_cpu[c] / best_cpu[0], best_wall[c] / best_wall[0]);
    char cmd[4096];
    snprintf(cmd, sizeof cmd,
             "gnuplot -e \"set terminal pngcairo size 800,480 font ',10'; set output '%s'; set datafile separator ',';"
             " set logscale xy; set xlabel 'lights'; set ylabel 'CPU ms per frame (%dx%d, llvmpipe, all threads)'; set key top left; set grid;"
             " plot '%s' using 1:6 skip 1 with linespoints title 'brute force', '' using 1:7 skip 1 with linespoints title 'deferred',"
             " '' using 1:8 skip 1 with linespoints title 'tiled deferred', '' using 1:9 skip 1 with linespoints title 'clustered forward'\"",
             png, W, H, csv);
    if (system(cmd) != 0) printf("gnuplot failed: %s only\n", csv);
    else printf("wrote %s, %s\n", csv, png);
    return 0;
}
