/* many-lights chart: ms per frame against light count (1 … 4096) for the four methods, on the
 * spheres scene (five spheres and a ground plane, as scenes/spheres.json) or, with --head DIR,
 * the head model, with N animated point lights (every 8th a spot) spread over the scene. Writes
 * PREFIX.csv and PREFIX.png (gnuplot). Not a test: it prints figures.
 *
 *   many_lights_chart [--size 1280x720] [--frames 5] [--max-brute 256] [--head PATH.obj]
 *     (--max-brute: brute force and plain deferred, both every light at every pixel, only up to it)
 *                     [--counts 1,4,16,...] [--out bench/many-lights-ms]
 *   many_lights_chart --write-scene N PATH      the N-light spheres scene as JSON
 *
 * Timing: wall clock of sl_harness_render (render + glFinish + read-back of the float image,
 * the same overhead for every method), median of --frames after one warm-up frame; lights
 * animate (each frame is a new time step). */
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}
static int cmpd(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* N lights at 0.2-1.7 m over the 14 m ground, each of intensity I = 0.03 (colour up to 1): at the
 * default epsilon 0.01 a range of sqrt(0.03/0.01) = 1.73 m, so a point of the ground is within
 * range of about N/18 lights (the same kind of light, more of them) */
static char *scene(int n, const char *head) {
    size_t cap = 4096 + (size_t)n * 300;
    char *b = malloc(cap);
    int k = snprintf(b, cap,
        "{ \"plugins\": [\"ggx\", \"spotlight-shadow\"],\n  \"cameras\": [{\"name\": \"main\", \"position\": [0, 2.5, 7.5], \"target\": [0, 0.7, 0], \"fov_y\": 40}],\n"
        "  \"environment\": {\"color\": [1, 1, 1], \"intensity\": 0.05},\n"
        "  \"materials\": [ {\"name\": \"ground\", \"base_color_map\": \"checker:16:0.8,0.8,0.8:0.3,0.3,0.3\"},\n"
        "    {\"name\": \"red\", \"model\": \"ggx\", \"base_color\": [0.85, 0.2, 0.15], \"roughness\": 0.4},\n"
        "    {\"name\": \"blue\", \"model\": \"ggx\", \"base_color\": [0.15, 0.3, 0.85], \"roughness\": 0.6},\n"
        "    {\"name\": \"yellow\", \"base_color\": [0.9, 0.75, 0.2]}, {\"name\": \"white\", \"base_color\": [0.8, 0.8, 0.8]} ],\n"
        "  \"nodes\": [ {\"name\": \"ground\", \"mesh\": {\"primitive\": \"plane\", \"size\": 14}, \"material\": \"ground\"}");
    if (head)
        k += snprintf(b + k, cap - k, ",\n    {\"name\": \"head\", \"translate\": [0, 0.9, 0], \"mesh\": {\"file\": \"%s\"}, \"material\": \"white\"}", head);
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

int main(int argc, char **argv) {
    int W = 1280, H = 720, frames = 5, max_brute = 256;
    const char *out = "many-lights-ms", *head = NULL, *counts_s = "1,4,16,64,256,1024,2048,4096";
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--write-scene") && i + 2 < argc) {
            char *s = scene(atoi(argv[i + 1]), NULL);
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
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) out = argv[++i];
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
    char csv[1024], png[1024];
    snprintf(csv, sizeof csv, "%s.csv", out);
    snprintf(png, sizeof png, "%s.png", out);
    FILE *f = fopen(csv, "w");
    if (!f) { fprintf(stderr, "cannot write %s\n", csv); return 1; }
    fprintf(f, "lights,brute_ms,deferred_ms,tiled_ms,clustered_ms\n");
    float *img = malloc(sizeof(float) * W * H * 4);
    for (int c = 0; c < nc; c++) {
        int n = counts[c];
        if (n < 1 || n > 4096) continue;
        char *json = scene(n, head);
        fprintf(f, "%d", n);
        printf("%5d lights:", n);
        for (int m = 0; m < 4; m++) {
            if (m <= 1 && n > max_brute) { /* brute and plain deferred: every light at every pixel */ fprintf(f, ","); printf("  %s -", methods[m]); continue; }
            char set[96], err[4096];
            snprintf(set, sizeof set, "many-lights.method=%s", methods[m]);
            const char *settings[] = {set, NULL};
            const char *plugins[] = {MANY_LIGHTS_PLUGIN, "ggx", "spotlight-shadow", NULL};
            sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W,
                                                                 .height = H, .scene_json = json, .plugins = plugins,
                                                                 .settings = settings, .strict = true},
                                              err, sizeof err);
            if (!h) { fprintf(stderr, "%s\n", err); return 1; }
            char v[64];
            if (sl_harness_get(h, "aa.enabled", v, sizeof v)) sl_harness_set(h, "aa.enabled=false", err, sizeof err);
            sl_harness_render(h, img); /* warm-up: compiles */
            double t[100];
            for (int k = 0; k < frames; k++) {
                double t0 = now_ms();
                sl_harness_render(h, img);
                t[k] = now_ms() - t0;
            }
            qsort(t, frames, sizeof *t, cmpd);
            fprintf(f, ",%.2f", t[frames / 2]);
            printf("  %s %.1f", methods[m], t[frames / 2]);
            fflush(stdout);
            sl_harness_destroy(h);
        }
        fprintf(f, "\n");
        printf(" ms\n");
        fflush(f);
        free(json);
    }
    fclose(f);
    free(img);
    char cmd[4096];
    snprintf(cmd, sizeof cmd,
             "gnuplot -e \"set terminal pngcairo size 800,480 font ',10'; set output '%s'; set datafile separator ',';"
             " set logscale xy; set xlabel 'lights'; set ylabel 'ms per frame (%dx%d, llvmpipe)'; set key top left; set grid;"
             " plot '%s' using 1:2 skip 1 with linespoints title 'brute force', '' using 1:3 skip 1 with linespoints title 'deferred',"
             " '' using 1:4 skip 1 with linespoints title 'tiled deferred', '' using 1:5 skip 1 with linespoints title 'clustered forward'\"",
             png, W, H, csv);
    if (system(cmd) != 0) printf("gnuplot failed: %s only\n", csv);
    else printf("wrote %s, %s\n", csv, png);
    return 0;
}
