/* area-light chart: the LTC against the Monte Carlo reference per roughness, and the cost of one
 * rectangle light against one point light. Headless (harness), figures measured in one run:
 *
 *   area_light_chart [--size WxH] [--frames N] [--accumulate N] [--out PREFIX]
 *
 * Error: a GGX plane and sphere (base colour 0.2, dielectric η = 1/1.5) under a 2 m × 1 m
 * rectangle light, roughness 0.05 … 1; relative RMSE of the LTC image against the plugin's
 * reference (Monte Carlo over the light's surface through the ggx model itself, --accumulate
 * frames of 64 stratified points), and the same for the diffuse-only case (lambert: exact, so its
 * curve is the reference's noise), with the ggx reference's own noise estimated from its first
 * quarter (q − ref = ¾(q − rest): rms = √3 σ). The same for phong's blinn-gloss (normalised
 * Blinn-Phong, lit through the lobe contract by the Blinn-Phong LTC table) at the power of the same
 * GGX α by Walter et al.'s equivalence, p = 2/α² − 2 (α = roughness², gloss = log2(p)/12; only
 * where gloss ∈ [0, 1], the model's range: roughness 0.2 … 0.9), against its own reference (the
 * blinn-gloss model itself per point). Cost: the
 * same scene with the rectangle light and with one point light at its centre, rendered in turn
 * (interleaved, median of --frames each) on the same harness build. Beside each relative RMSE,
 * the mean FLIP (Andersson et al. 2020, shadelab-bench's sl_metric_flip from the SDK's
 * shadelab::metrics) of the same pair; the LTC is deterministic (no noise of its own), the
 * references' noise is the estimate above, and in FLIP the first quarter's FLIP against the whole.
 * Writes PREFIX.csv, PREFIX.png and PREFIX-flip.png (gnuplot). Not a test: it prints figures. */
#include <shadelab/harness.h>
#include <shadelab/bench/metrics.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <math.h>

static int W = 256, H = 144;

#define SCENE_HEAD                                                                                                   \
    "{ \"cameras\": [{\"name\": \"c\", \"position\": [0, 2.2, 4.5], \"target\": [0, 0.4, 0], \"fov_y\": 45}],"       \
    "  \"materials\": [{\"name\": \"m\", \"model\": \"%s\", \"base_color\": [0.2, 0.2, 0.2], \"%s\": %g}],"        \
    "  \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 12}, \"material\": \"m\"},"   \
    "             {\"name\": \"ball\", \"translate\": [0, 0.6, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.6}, \"material\": \"m\"}],"
#define RECT_LIGHT                                                                                                   \
    "  \"lights\": [{\"name\": \"L\", \"type\": \"area\", \"position\": [0, 2.0, -1.5], \"direction\": [0, -0.6, 1],"  \
    " \"color\": [1, 1, 1], \"intensity\": 4, \"width\": 2, \"height\": 1}] }"
#define POINT_LIGHT                                                                                                  \
    "  \"lights\": [{\"name\": \"L\", \"type\": \"point\", \"position\": [0, 2.0, -1.5], \"color\": [1, 1, 1], \"intensity\": 8}] }"

static sl_harness *make(const char *json, const char *const *settings, int accumulate) {
    char err[4096];
    const char *plugins[] = {AREA_LIGHT_PLUGIN, "ggx", "phong", NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
        .scene_json = json, .plugins = plugins, .settings = settings, .float32 = true, .strict = true,
        .accumulate = accumulate}, err, sizeof err);
    if (!h) { fprintf(stderr, "area_light_chart: %s\n", err); exit(1); }
    return h;
}

static double rel_rmse(const float *a, const float *ref) {
    double s = 0, r = 0;
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++) {
            double d = a[i * 4 + c] - ref[i * 4 + c];
            s += d * d;
            r += ref[i * 4 + c] * ref[i * 4 + c];
        }
    return sqrt(s / fmax(r, 1e-30));
}

static double flip(const float *a, const float *ref) { return sl_metric_flip(a, ref, W, H, 0, NULL); }

/* one frame of json (accumulating `accumulate` frames) into img, on a harness of its own */
static void render_once(const char *json, const char *const *settings, int accumulate, float *img) {
    sl_harness *h = make(json, settings, accumulate);
    sl_harness_render(h, img);
    sl_harness_destroy(h);
}

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}
static int cmp_d(const void *a, const void *b) { double x = *(const double *)a, y = *(const double *)b; return (x > y) - (x < y); }

int main(int argc, char **argv) {
    setvbuf(stdout, NULL, _IOLBF, 0); /* progress as it goes */
    int frames = 15, accumulate = 64;
    const char *out = "area-light-chart";
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--size") && i + 1 < argc) sscanf(argv[++i], "%dx%d", &W, &H);
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc) frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--accumulate") && i + 1 < argc) accumulate = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) out = argv[++i];
        else { fprintf(stderr, "usage: area_light_chart [--size WxH] [--frames N] [--accumulate N] [--out PREFIX]\n"); return 2; }
    }
    if (W < 16 || H < 16 || W > 4096 || H > 4096 || frames < 1 || accumulate < 1) { fprintf(stderr, "area_light_chart: bad arguments\n"); return 2; }
    float *img = malloc(sizeof(float) * 4 * W * H), *ref = malloc(sizeof(float) * 4 * W * H);
    char csv[1024], png[1024], pngf[1024], json[4096];
    snprintf(csv, sizeof csv, "%s.csv", out);
    snprintf(png, sizeof png, "%s.png", out);
    snprintf(pngf, sizeof pngf, "%s-flip.png", out);
    FILE *f = fopen(csv, "w");
    if (!f) { fprintf(stderr, "area_light_chart: cannot write %s\n", csv); return 1; }
    fprintf(f, "roughness,ggx_ltc_relrmse,lambert_relrmse,ggx_reference_noise,ggx_ltc_vs_shadowed_relrmse,"
               "blinn_gloss,blinn_gloss_ltc_relrmse,blinn_gloss_reference_noise,"
               "ggx_ltc_flip,lambert_flip,ggx_reference_quarter_flip,ggx_ltc_vs_shadowed_flip,blinn_gloss_ltc_flip,"
               "blinn_gloss_reference_quarter_flip\n");
    const char *const refset[] = {"area-light.method=reference", "area-light.reference_samples=8",
                                  "area-light.reference_visibility=false", NULL};
    /* the declared reference: with visibility (the ball shadows the floor; the LTC has no shadows) */
    const char *const shadowset[] = {"area-light.method=reference", "area-light.reference_visibility=true",
                                     "area-light.reference_map_size=1024", NULL};
    const double rough[] = {0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
    printf("roughness  ggx LTC vs reference  lambert vs reference  ggx reference noise  ggx LTC vs shadowed reference  "
           "blinn-gloss (gloss)  LTC vs reference  reference noise "
           "(relative RMSE; reference: %d frames x 64 points, unshadowed; shadowed: %d frames x 1 point + cube map); "
           "then FLIP: ggx, lambert, ggx reference's quarter, ggx vs shadowed, blinn-gloss, its reference's quarter\n",
           accumulate, accumulate);
    float *quarter = malloc(sizeof(float) * 4 * W * H);
    for (size_t k = 0; k < sizeof rough / sizeof *rough; k++) {
        double e[2], noise = 0, shadowed = 0, fl[2], fl_quarter = NAN, fl_shadowed = NAN;
        for (int m = 0; m < 2; m++) {
            snprintf(json, sizeof json, SCENE_HEAD RECT_LIGHT, m ? "lambert" : "ggx", "roughness", rough[k]);
            render_once(json, NULL, 1, img);
            render_once(json, refset, accumulate, ref);
            e[m] = rel_rmse(img, ref);
            fl[m] = flip(img, ref);
            if (m == 0 && accumulate >= 4) {
                /* the reference's own noise: its first quarter against it, rms(q - ref) = √3 σ */
                render_once(json, refset, accumulate / 4, quarter);
                noise = rel_rmse(quarter, ref) / sqrt(3.0);
                fl_quarter = flip(quarter, ref);
                render_once(json, shadowset, accumulate, ref);
                shadowed = rel_rmse(img, ref);
                fl_shadowed = flip(img, ref);
            }
        }
        /* blinn-gloss at Walter's power of the same α = roughness² (NaN outside the gloss range) */
        double alpha = rough[k] * rough[k], gloss = log2(2 / (alpha * alpha) - 2) / 12, eb = NAN, noise_b = NAN,
               fl_b = NAN, fl_b_quarter = NAN;
        if (gloss >= 0 && gloss <= 1) {
            snprintf(json, sizeof json, SCENE_HEAD RECT_LIGHT, "blinn-gloss", "gloss", gloss);
            render_once(json, NULL, 1, img);
            render_once(json, refset, accumulate, ref);
            eb = rel_rmse(img, ref);
            fl_b = flip(img, ref);
            if (accumulate >= 4) {
                render_once(json, refset, accumulate / 4, quarter);
                noise_b = rel_rmse(quarter, ref) / sqrt(3.0);
                fl_b_quarter = flip(quarter, ref);
            }
        }
        else gloss = NAN;
        printf("%9.2f  %20.4f  %20.4f  %19.4f  %29.4f  %19.3f  %16.4f  %15.4f  FLIP %.4f %.4f %.4f %.4f %.4f %.4f\n", rough[k],
               e[0], e[1], noise, shadowed, gloss, eb, noise_b, fl[0], fl[1], fl_quarter, fl_shadowed, fl_b, fl_b_quarter);
        fprintf(f, "%g,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g\n", rough[k], e[0], e[1], noise, shadowed, gloss, eb, noise_b,
                fl[0], fl[1], fl_quarter, fl_shadowed, fl_b, fl_b_quarter);
    }
    fclose(f);

    /* cost: rectangle vs point light, interleaved on two harnesses (one GL context at a time:
     * re-created per round, the first frame after creation not timed) */
    double *t_rect = calloc(frames, sizeof(double)), *t_point = calloc(frames, sizeof(double)),
           *t_shadow = calloc(frames, sizeof(double));
    char json_rect[4096], json_point[4096];
    snprintf(json_rect, sizeof json_rect, SCENE_HEAD RECT_LIGHT, "ggx", "roughness", 0.4);
    snprintf(json_point, sizeof json_point, SCENE_HEAD POINT_LIGHT, "ggx", "roughness", 0.4);
    for (int i = 0; i < frames; i++)
        for (int m = 0; m < 3; m++) {
            /* m = 2: one frame of the shadowed reference (a new light point: cube map + shading) */
            /* (4 accumulated frames, each from its own point, timed together and divided by 4) */
            int acc = m == 2 ? 4 : 1;
            sl_harness *h = make(m == 1 ? json_point : json_rect, m == 2 ? shadowset : NULL, acc);
            sl_harness_render(h, img); /* compile, warm */
            double t0 = now();
            sl_harness_render(h, img);
            double t = (now() - t0) * 1000 / acc;
            sl_harness_destroy(h);
            (m == 0 ? t_rect : m == 1 ? t_point : t_shadow)[i] = t;
        }
    qsort(t_rect, frames, sizeof(double), cmp_d);
    qsort(t_point, frames, sizeof(double), cmp_d);
    qsort(t_shadow, frames, sizeof(double), cmp_d);
    double mr = t_rect[frames / 2], mp = t_point[frames / 2], ms = t_shadow[frames / 2];
    printf("cost at %dx%d (render + read-back, median of %d, interleaved): rectangle light %.2f ms, point light %.2f ms, "
           "ratio %.2f; one frame of the shadowed reference (6 faces of 1024^2 + one point) %.2f ms\n", W, H, frames, mr,
           mp, mr / mp, ms);
    snprintf(csv, sizeof csv, "%s-cost.csv", out);
    f = fopen(csv, "w");
    if (f) {
        fprintf(f, "light,median_ms\nrectangle (LTC),%g\npoint,%g\nshadowed ref. (a frame),%g\n", mr, mp, ms);
        fclose(f);
    }

    /* the chart */
    char cmd[8192];
    snprintf(cmd, sizeof cmd,
             "gnuplot -e \"set terminal pngcairo size 1100,540 font ',10'; set output '%s'; set datafile separator ',';"
             " set multiplot;"
             " set origin 0,0; set size 0.64,1;"
             " set title 'area-light: LTC vs Monte Carlo reference'; set xlabel 'roughness (blinn-gloss: power 2/roughness^4 - 2)';"
             " set ylabel 'relative RMSE';"
             " set key outside bottom center vertical maxrows 3 font ',8'; set grid; set logscale y;"
             " plot '%s.csv' using 1:2 skip 1 with linespoints lc rgb 'dark-violet' pt 1 title 'ggx (LTC specular + Lambert)',"
             " '' using 1:3 skip 1 with linespoints lc rgb 'dark-green' pt 2 title 'lambert (exact formula)',"
             " '' using 1:4 skip 1 with lines lc rgb 'dark-violet' dashtype 2 title 'ggx reference noise (estimated)',"
             " '' using 1:5 skip 1 with linespoints lc rgb 'dark-orange' pt 4 title 'ggx (LTC, no shadows) vs shadowed reference',"
             " '' using 1:7 skip 1 with linespoints lc rgb 'red' lw 2 pt 7 ps 0.8 title 'blinn-gloss (Blinn-Phong LTC + Lambert)',"
             " '' using 1:8 skip 1 with lines lc rgb 'red' dashtype 3 title 'blinn-gloss reference noise (estimated)';"
             " unset logscale y;"
             " set origin 0.64,0; set size 0.36,1;"
             " set title 'cost per frame, %dx%d, llvmpipe'; set xlabel ''; set ylabel 'ms'; set style fill solid 0.5;"
             " set boxwidth 0.5; set yrange [0:*]; unset key; set xtics font ',8';"
             " plot '%s-cost.csv' using 0:2:xtic(1) skip 1 with boxes;"
             " unset multiplot\"",
             png, out, W, H, out);
    if (system(cmd) != 0) fprintf(stderr, "area_light_chart: gnuplot failed (CSV written)\n");
    else printf("wrote %s.csv, %s-cost.csv, %s\n", out, out, png);
    /* the FLIP chart: the same pairs, mean FLIP at 67 pixels per degree */
    snprintf(cmd, sizeof cmd,
             "gnuplot -e \"set terminal pngcairo size 800,540 font ',10'; set output '%s'; set datafile separator ',';"
             " set title 'area-light: LTC vs Monte Carlo reference, %dx%d'; set xlabel 'roughness (blinn-gloss: power 2/roughness^4 - 2)';"
             " set ylabel 'mean FLIP (perceptual, 67 px/degree)';"
             " set key outside bottom center vertical maxrows 3 font ',8'; set grid; set logscale y;"
             " plot '%s.csv' using 1:9 skip 1 with linespoints lc rgb 'dark-violet' pt 1 title 'ggx (LTC specular + Lambert)',"
             " '' using 1:10 skip 1 with linespoints lc rgb 'dark-green' pt 2 title 'lambert (exact formula)',"
             " '' using 1:11 skip 1 with lines lc rgb 'dark-violet' dashtype 2 title 'ggx reference: its first quarter vs it',"
             " '' using 1:12 skip 1 with linespoints lc rgb 'dark-orange' pt 4 title 'ggx (LTC, no shadows) vs shadowed reference',"
             " '' using 1:13 skip 1 with linespoints lc rgb 'red' lw 2 pt 7 ps 0.8 title 'blinn-gloss (Blinn-Phong LTC + Lambert)',"
             " '' using 1:14 skip 1 with lines lc rgb 'red' dashtype 3 title 'blinn-gloss reference: its first quarter vs it'\"",
             pngf, W, H, out);
    if (system(cmd) != 0) fprintf(stderr, "area_light_chart: gnuplot failed for %s\n", pngf);
    else printf("wrote %s\n", pngf);
    free(img), free(ref), free(quarter), free(t_rect), free(t_point), free(t_shadow);
    return 0;
}
