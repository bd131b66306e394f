/* shadelab-tonemap-curves: draws every tone-mapping operator's curve to a PNG (and CSV) by
 * evaluating the plugin's own GLSL (tonemap_ops.glsl) on the GPU or llvmpipe through the test
 * harness, so the picture shows exactly what the post pass does. Chart by gnuplot. */
#include "toolkit.h" /* sl_srgb_encode: the core's display encoding */
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *names[] = {"linear", "reinhard", "reinhard-extended", "aces", "agx", "pbr-neutral"};
enum { OPS = 6, N = 256 };

static const char *usage =
    "usage: shadelab-tonemap-curves OUT.png [--csv OUT.csv] [--exposure EV] [--white W]\n"
    "Plots display value (after the sRGB encoding) against scene radiance in stops from middle grey\n"
    "(0.18) for every operator of the tonemap plugin, evaluated from its GLSL. Needs gnuplot.\n";

int main(int argc, char **argv) {
    const char *png = NULL, *csv = NULL;
    float exposure = 0, white = 4;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) { fputs(usage, stdout); return 0; }
        else if (!strcmp(argv[i], "--csv") && i + 1 < argc) csv = argv[++i];
        else if (!strcmp(argv[i], "--exposure") && i + 1 < argc) exposure = (float)atof(argv[++i]);
        else if (!strcmp(argv[i], "--white") && i + 1 < argc) white = (float)atof(argv[++i]);
        else if (argv[i][0] != '-' && !png) png = argv[i];
        else { fprintf(stderr, "%s", usage); return 2; }
    }
    if (!png) { fprintf(stderr, "%s", usage); return 2; }
    char err[8192];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 8, .height = 8,
                                                          .scene_json = "{}", .plugins = (const char *[]){"tonemap", NULL},
                                                          .strict = true}, err, sizeof err);
    if (!h) { fprintf(stderr, "shadelab-tonemap-curves: %s\n", err); return 1; }
    static float in[N * OPS * 4], out[N * OPS * 4];
    for (int o = 0; o < OPS; o++)
        for (int i = 0; i < N; i++) {
            float *p = in + (o * N + i) * 4;
            p[0] = 0.18f * exp2f(-10 + 20.0f * i / (N - 1)), p[1] = (float)o, p[2] = exposure, p[3] = white;
        }
    const char *files[] = {"tonemap_ops.glsl", NULL};
    sl_glsl_eval_desc e = {.struct_size = sizeof e, .plugin = "tonemap", .files = files, .width = N, .height = OPS,
                           .expression = "vec4(tonemap_apply(vec3(in0.x), int(in0.y), in0.z, in0.w), 1.0)", .in0 = in};
    if (!sl_harness_eval_glsl(h, &e, out, err, sizeof err)) { fprintf(stderr, "shadelab-tonemap-curves: %s\n", err); return 1; }
    sl_harness_destroy(h);
    char csv_tmp[4096];
    if (!csv) {
        const char *dot = strrchr(png, '.');
        snprintf(csv_tmp, sizeof csv_tmp, "%.*s.csv", dot ? (int)(dot - png) : (int)strlen(png), png);
        csv = csv_tmp;
    }
    FILE *f = fopen(csv, "w");
    if (!f) { perror(csv); return 1; }
    fprintf(f, "stops,radiance");
    for (int o = 0; o < OPS; o++) fprintf(f, ",%s", names[o]);
    fprintf(f, "\n");
    for (int i = 0; i < N; i++) {
        fprintf(f, "%.5f,%.6g", -10 + 20.0 * i / (N - 1), in[i * 4]);
        for (int o = 0; o < OPS; o++) fprintf(f, ",%.6f", sl_srgb_encode(out[(o * N + i) * 4]));
        fprintf(f, "\n");
    }
    fclose(f);
    char cmd[16384];
    int n = snprintf(cmd, sizeof cmd,
                     "gnuplot -e \"if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 900,560 font 'sans,11' }"
                     " else { set terminal png size 900,560 }; set output '%s'; set datafile separator ',';"
                     " set key top left; set grid; set xlabel 'scene radiance, stops from middle grey 0.18 (exposure %+g EV)';"
                     " set ylabel 'display value (sRGB encoded)'; set yrange [0:1.05]; set xrange [-10:10];"
                     " set title 'shadelab tonemap operators (white point %g for reinhard-extended)'; plot",
                     png, exposure, white);
    for (int o = 0; o < OPS; o++) n += snprintf(cmd + n, sizeof cmd - n, "%s '%s' using 1:%d with lines lw 2 title '%s'", o ? "," : "", csv, o + 3, names[o]);
    snprintf(cmd + n, sizeof cmd - n, "\"");
    if (system(cmd) != 0) { fprintf(stderr, "shadelab-tonemap-curves: gnuplot failed (is it installed? tools/install-deps.sh)\n"); return 1; }
    fprintf(stderr, "wrote %s and %s\n", png, csv);
    return 0;
}
