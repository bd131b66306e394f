/* voronoi-tiles against independent C computations (harness, OSMesa):
 *  1. bisector distance: voronoi_tiles_search (the GLSL the hook runs) over 4096 points against a
 *     brute-force C evaluation (every seed of an 11x11 block, sorted) written from the README's
 *     definition (the pcg3d hash re-implemented in C from the paper): exact and radius modes equal
 *     it, the latter with the assignment's √3.25 rule applied to the brute force too; the
 *     nearest cell matches; how often 3x3 and radius differ from the exact three nearest is
 *     printed (they are the approximations the benchmark charts).
 *  2. AO: exactly 0.5 at a seam base (d = 0), exactly 1 on a tile top (at a seed); within 0.01 of
 *     0.5 at a bisector's midpoint found in C.
 *  3. image: under an overhead light, on a plane of one tile colour, every seam pixel near the
 *     base (debug view: d < w/5) is darker than every tile-top pixel (d > w).
 *  4. stability: no NaN/Inf at grazing angles, jitter 0 (a square grid: equidistant seeds),
 *     seam width 0 and 1, scale 256, α at its limits.
 *  5. costs nothing: a material without the key, or the plugin off, compiles what no plugin does.
 *  6. live equals fresh for scale, search, samples, seam_width. */
#include <shadelab/harness.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures;
#define CHECK(cond, ...) do { if (!(cond)) { failures++; printf("FAIL %s:%d: ", __FILE__, __LINE__); printf(__VA_ARGS__); printf("\n"); } } while (0)

/* ---- the tiling, from its definition ---- */
static void pcg3d(uint32_t v[3]) {
    for (int k = 0; k < 3; k++) v[k] = v[k] * 1664525u + 1013904223u;
    v[0] += v[1] * v[2]; v[1] += v[2] * v[0]; v[2] += v[0] * v[1];
    for (int k = 0; k < 3; k++) v[k] ^= v[k] >> 16;
    v[0] += v[1] * v[2]; v[1] += v[2] * v[0]; v[2] += v[0] * v[1];
}
static void seed_of(int cx, int cy, int seed, double jitter, double s[2]) {
    uint32_t h[3] = {(uint32_t)cx, (uint32_t)cy, (uint32_t)seed};
    pcg3d(h);
    s[0] = cx + 0.5 + jitter * ((double)(h[0] >> 8) / 16777216.0 - 0.5);
    s[1] = cy + 0.5 + jitter * ((double)(h[1] >> 8) / 16777216.0 - 0.5);
}
typedef struct { double d2, s[2]; int c[2]; } cand;
static int by_d2(const void *a, const void *b) {
    double x = ((const cand *)a)->d2, y = ((const cand *)b)->d2;
    return x < y ? -1 : x > y;
}
/* brute force: all seeds of the 11x11 block, sorted; max_r2 > 0 keeps only seeds within it.
 * Returns the seam distance, the nearest cell in c1. */
static double brute(const double x[2], int seed, double jitter, double max_r2, int c1[2]) {
    cand all[121];
    int n = 0, fx = (int)floor(x[0]), fy = (int)floor(x[1]);
    for (int j = -5; j <= 5; j++)
        for (int i = -5; i <= 5; i++) {
            cand c = {.c = {fx + i, fy + j}};
            seed_of(fx + i, fy + j, seed, jitter, c.s);
            c.d2 = (c.s[0] - x[0]) * (c.s[0] - x[0]) + (c.s[1] - x[1]) * (c.s[1] - x[1]);
            if (max_r2 > 0 && c.d2 > max_r2) continue;
            all[n++] = c;
        }
    qsort(all, n, sizeof *all, by_d2);
    c1[0] = all[0].c[0], c1[1] = all[0].c[1];
    double best = 1e30;
    for (int k = 1; k <= 2 && k < n; k++) {
        double e[2] = {all[k].s[0] - all[0].s[0], all[k].s[1] - all[0].s[1]}, l = hypot(e[0], e[1]);
        double m[2] = {0.5 * (all[0].s[0] + all[k].s[0]), 0.5 * (all[0].s[1] + all[k].s[1])};
        double d = ((m[0] - x[0]) * e[0] + (m[1] - x[1]) * e[1]) / l;
        best = fmin(best, d);
    }
    return fmax(best, 0);
}

#define N 64
static const char *defines(const char *search, int seed, double jitter, double seam) {
    static char buf[1024];
    snprintf(buf, sizeof buf,
             "voronoi_tiles_seed %d\nvoronoi_tiles_jitter %.9g\nvoronoi_tiles_seam_width %.9g\n"
             "VORONOI_TILES_SEARCH_3X3 0\nVORONOI_TILES_SEARCH_RADIUS 1\nVORONOI_TILES_SEARCH_EXACT 2\nVORONOI_TILES_SEARCH %s",
             seed, jitter, seam, search);
    return buf;
}

static sl_harness *make(int w, int h, const char *json, const char *const *settings, const char *view, bool with) {
    const char *plugins[] = {VT_PLUGIN_PATH, NULL};
    char err[4096];
    sl_harness_desc d = {.struct_size = sizeof d, .width = w, .height = h, .scene_json = json, .plugins = with ? plugins : NULL,
                         .settings = settings, .debug_view = view, .strict = true};
    sl_harness *hh = sl_harness_create(&d, err, sizeof err);
    if (!hh) { printf("FAIL: harness: %s\n", err); exit(1); }
    return hh;
}
static float *render(int w, int h, const char *json, const char *const *settings, const char *view, bool with) {
    sl_harness *hh = make(w, h, json, settings, view, with);
    float *img = malloc(sizeof(float) * w * h * 4);
    if (!sl_harness_render(hh, img)) { printf("FAIL: render\n"); exit(1); }
    sl_harness_destroy(hh);
    return img;
}

/* a tiled plane seen from above (orbit angle `tilt` degrees from vertical), overhead light, and
 * (ball) a plain sphere above it */
static void plane_scene(char *out, size_t n, double tilt, const char *model, bool ball) {
    double t = tilt * 3.14159265358979 / 180;
    snprintf(out, n,
             "{\"cameras\": [{\"name\": \"c\", \"position\": [0, %.6f, %.6f], \"target\": [0, 0, 0], \"fov_y\": 40}],"
             " \"materials\": [{\"name\": \"tiles\", \"model\": \"%s\", \"base_color\": [1, 1, 1], \"voronoi_tiles\": true},"
             "                 {\"name\": \"plain\", \"base_color\": [0.5, 0.5, 0.5]}],"
             " \"nodes\": [{\"name\": \"p\", \"mesh\": {\"primitive\": \"plane\", \"size\": 2}, \"material\": \"tiles\"}%s],"
             " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, 0], \"intensity\": 3}]}",
             2.6 * cos(t), 2.6 * sin(t) + 1e-3, model,
             ball ? ", {\"name\": \"b\", \"translate\": [0, 0.3, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.2}, \"material\": \"plain\"}" : "");
}

int main(void) {
    /* ---- 1, 2: GLSL unit tests ---- */
    sl_harness *h = make(16, 16, NULL, NULL, NULL, true);
    const char *files[] = {"voronoi_cells.glsl", NULL};
    static float in0[N * N * 4], out[N * N * 4], out_cell[N * N * 4];
    for (int i = 0; i < N * N; i++) {
        /* quasi-random points over a 40x40-cell window, negative cells included */
        in0[i * 4 + 0] = (float)(-20 + 40 * fmod(i * 0.7548776662466927, 1.0));
        in0[i * 4 + 1] = (float)(-20 + 40 * fmod(i * 0.5698402909980532, 1.0));
    }
    const int seed = 7;
    const double jitter = 1.0, seam = 0.2;
    const char *modes[] = {"VORONOI_TILES_SEARCH_EXACT", "VORONOI_TILES_SEARCH_RADIUS", "VORONOI_TILES_SEARCH_3X3"};
    char err[4096];
    for (int mi = 0; mi < 3; mi++) {
        sl_glsl_eval_desc d = {.struct_size = sizeof d, .plugin = "voronoi-tiles", .files = files, .width = N, .height = N, .in0 = in0,
                               .defines = defines(modes[mi], seed, jitter, seam),
                               .expression = "vec4(voronoi_tiles_seam_distance(in0.xy), 0.0, 0.0, 0.0)"};
        if (!sl_harness_eval_glsl(h, &d, out, err, sizeof err)) { printf("FAIL: eval: %s\n", err); return 1; }
        d.expression = "vec4(voronoi_tiles_cell_of(in0.xy), 0.0, 0.0)";
        if (!sl_harness_eval_glsl(h, &d, out_cell, err, sizeof err)) { printf("FAIL: eval: %s\n", err); return 1; }
        double worst = 0;
        long differ = 0, cell_bad = 0;
        for (int i = 0; i < N * N; i++) {
            double x[2] = {in0[i * 4], in0[i * 4 + 1]};
            int c1[2], ce[2];
            double want = brute(x, seed, jitter, mi == 1 ? 3.25 : 0, c1);
            double exact = brute(x, seed, jitter, 0, ce);
            double e = fabs(out[i * 4] - want);
            worst = fmax(worst, e);
            differ += fabs(out[i * 4] - exact) > 1e-4;
            cell_bad += (int)out_cell[i * 4] != c1[0] || (int)out_cell[i * 4 + 1] != c1[1];
        }
        if (mi < 2) {
            printf("%s: max |GLSL - brute force| = %.3g cells over %d points; nearest cell wrong at %ld\n", modes[mi], worst, N * N, cell_bad);
            CHECK(worst < 2e-4, "%s: bisector distance off by %g cells", modes[mi], worst);
            CHECK(cell_bad == 0, "%s: nearest cell wrong at %ld points", modes[mi], cell_bad);
        }
        printf("  %s differs from the exact three nearest at %ld of %d points (%.2f%%)\n", modes[mi], differ, N * N, 100.0 * differ / (N * N));
        if (mi == 0) CHECK(differ == 0, "exact mode differs from the brute force at %ld points", differ);
    }
    {
        /* AO: the closed-form ends, and at the midpoints of nearest pairs */
        float one[4 * 4] = {0};
        sl_glsl_eval_desc d = {.struct_size = sizeof d, .plugin = "voronoi-tiles", .files = files, .width = 2, .height = 2, .in0 = one,
                               .defines = defines("VORONOI_TILES_SEARCH_EXACT", seed, jitter, seam),
                               .expression = "vec4(voronoi_tiles_ao(0.0), voronoi_tiles_ao(0.1), voronoi_tiles_ao(0.5), 0.0)"};
        float o[16];
        if (!sl_harness_eval_glsl(h, &d, o, err, sizeof err)) { printf("FAIL: eval: %s\n", err); return 1; }
        printf("AO at the seam base %.9g, at the seam edge %.9g, on the tile top %.9g\n", o[0], o[1], o[2]);
        CHECK(o[0] == 0.5f, "AO at the seam base must be exactly 0.5, got %.9g", o[0]);
        CHECK(o[1] == 1.0f && o[2] == 1.0f, "AO on the tile top must be exactly 1, got %.9g, %.9g", o[1], o[2]);
        /* full path at seeds (tile tops) and at midpoints between a seed and its nearest neighbour */
        static float pts[N * N * 4];
        int np = 0;
        for (int i = 0; i < N * N / 2; i++) {
            int cx = i % 40 - 20, cy = i / 40 - 20;
            double s[2], x[2];
            seed_of(cx, cy, seed, jitter, s);
            int cs[2];
            if (brute(s, seed, jitter, 0, cs) > 0.5 * seam + 1e-4) /* a tile top: the seed is farther than w from its seams */
                pts[np * 4] = (float)s[0], pts[np * 4 + 1] = (float)s[1], np++;
            /* nearest other seed → midpoint; keep it if brute force says those two are nearest there */
            double best = 1e30, m[2] = {0, 0};
            for (int j = -2; j <= 2; j++)
                for (int k = -2; k <= 2; k++) {
                    if (!j && !k) continue;
                    double o2[2];
                    seed_of(cx + k, cy + j, seed, jitter, o2);
                    double dd = hypot(o2[0] - s[0], o2[1] - s[1]);
                    if (dd < best) best = dd, m[0] = 0.5 * (s[0] + o2[0]), m[1] = 0.5 * (s[1] + o2[1]);
                }
            x[0] = m[0], x[1] = m[1];
            int c1[2];
            if (brute(x, seed, jitter, 0, c1) < 1e-9) pts[np * 4] = (float)m[0], pts[np * 4 + 1] = (float)m[1], pts[np * 4 + 2] = 1, np++;
        }
        sl_glsl_eval_desc e = {.struct_size = sizeof e, .plugin = "voronoi-tiles", .files = files, .width = N, .height = N, .in0 = pts,
                               .defines = d.defines,
                               .expression = "vec4(voronoi_tiles_ao(voronoi_tiles_seam_distance(in0.xy)), 0.0, 0.0, 0.0)"};
        if (!sl_harness_eval_glsl(h, &e, out, err, sizeof err)) { printf("FAIL: eval: %s\n", err); return 1; }
        double worst_top = 0, worst_base = 0;
        int tops = 0, bases = 0;
        for (int i = 0; i < np; i++) {
            if (pts[i * 4 + 2] == 0) tops++, worst_top = fmax(worst_top, fabs(out[i * 4] - 1.0));
            else bases++, worst_base = fmax(worst_base, fabs(out[i * 4] - 0.5));
        }
        printf("AO at %d seeds: max |ao - 1| = %.3g; at %d bisector midpoints: max |ao - 0.5| = %.3g\n", tops, worst_top, bases, worst_base);
        CHECK(tops > 1000 && worst_top == 0, "AO at a tile top must be exactly 1 (off by %g, %d points)", worst_top, tops);
        CHECK(bases > 100 && worst_base < 0.01, "AO at seam bases off 0.5 by %g (%d points)", worst_base, bases);
    }
    sl_harness_destroy(h);

    /* ---- 3. seam darker than tile top under an overhead light ---- */
    enum { W = 160, H = 120 };
    char scene[4096];
    plane_scene(scene, sizeof scene, 0, "lambert", false);
    const char *uni[] = {"voronoi-tiles.color_a=0.8,0.8,0.8", "voronoi-tiles.color_b=0.8,0.8,0.8", "voronoi-tiles.scale=4",
                         "voronoi-tiles.seam_width=0.2", NULL};
    float *img = render(W, H, scene, uni, NULL, true), *view = render(W, H, scene, uni, "voronoi-tiles", true);
    double max_seam = 0, min_top = 1e30;
    int nseam = 0, ntop = 0;
    const double w = 0.1;
    for (int i = 0; i < W * H; i++) {
        double d = view[i * 4];
        if (view[i * 4 + 1] <= 0) continue; /* background */
        if (d < 0.2 * w) nseam++, max_seam = fmax(max_seam, img[i * 4]);
        else if (d > w) ntop++, min_top = fmin(min_top, img[i * 4]);
    }
    printf("overhead light: %d seam-base pixels, brightest %.4g; %d tile-top pixels, darkest %.4g\n", nseam, max_seam, ntop, min_top);
    CHECK(nseam > 20 && ntop > 1000, "too few seam (%d) or tile (%d) pixels", nseam, ntop);
    CHECK(max_seam < min_top, "a seam pixel (%g) is not darker than every tile top (%g)", max_seam, min_top);
    /* tile tops: flat normal, Lambert 0.8 · 3 / π exactly (the closed form of the tile top) */
    CHECK(fabs(min_top - 0.8 * 3 / 3.14159265358979) < 2e-3, "tile top radiance %g, expected %g", min_top, 0.8 * 3 / 3.14159265358979);
    free(img), free(view);

    /* ---- 4. stability ---- */
    const char *extreme[][4] = {{"voronoi-tiles.jitter=0", "voronoi-tiles.seam_width=1", NULL},
                                {"voronoi-tiles.seam_width=0", "voronoi-tiles.scale=256", "voronoi-tiles.samples=3", NULL},
                                {"voronoi-tiles.alpha_min=0.002", "voronoi-tiles.alpha_max=1", "voronoi-tiles.search=3x3", NULL}};
    for (int k = 0; k < 3; k++)
        for (int tilt = 0; tilt < 2; tilt++) {
            plane_scene(scene, sizeof scene, tilt ? 89.5 : 20, "ggx", true);
            float *im = render(64, 48, scene, extreme[k], NULL, true);
            long bad = sl_harness_count_nonfinite(im, 64, 48) + sl_harness_count_negative(im, 64, 48);
            CHECK(bad == 0, "settings %d tilt %d: %ld non-finite or negative values", k, tilt, bad);
            free(im);
        }

    /* ---- 5. costs nothing ---- */
    {
        char plain[4096];
        snprintf(plain, sizeof plain, "%s", "{\"materials\": [{\"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5]}],"
                 " \"nodes\": [{\"name\": \"n\", \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"m\"}],"
                 " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\"}]}");
        sl_harness_structure a, b, c, d;
        sl_harness *x = make(32, 32, plain, NULL, NULL, false);
        float tmp[32 * 32 * 4];
        sl_harness_render(x, tmp), sl_harness_structure_of(x, &a), sl_harness_destroy(x);
        x = make(32, 32, plain, NULL, NULL, true);
        sl_harness_render(x, tmp), sl_harness_structure_of(x, &b), sl_harness_destroy(x);
        CHECK(sl_harness_structure_equal(&a, &b), "a material without the key compiles voronoi-tiles code");
        plane_scene(scene, sizeof scene, 20, "lambert", true);
        const char *off[] = {"voronoi-tiles.enabled=false", NULL};
        x = make(32, 32, scene, off, NULL, true);
        sl_harness_render(x, tmp), sl_harness_structure_of(x, &c), sl_harness_destroy(x);
        /* without the plugin the key is unknown: the same scene minus the key */
        char nokey[4096];
        snprintf(nokey, sizeof nokey, "%s", scene);
        char *p = strstr(nokey, ", \"voronoi_tiles\": true");
        memmove(p, p + strlen(", \"voronoi_tiles\": true"), strlen(p + strlen(", \"voronoi_tiles\": true")) + 1);
        x = make(32, 32, nokey, NULL, NULL, false);
        sl_harness_render(x, tmp), sl_harness_structure_of(x, &d), sl_harness_destroy(x);
        CHECK(sl_harness_structure_equal(&c, &d), "switched off, the plugin still changes the frame's structure");
    }

    /* ---- 6. live equals fresh ---- */
    {
        plane_scene(scene, sizeof scene, 35, "ggx", true);
        sl_harness *x = make(W, H, scene, NULL, NULL, true);
        float *tmp = malloc(sizeof(float) * W * H * 4), *fresh;
        sl_harness_render(x, tmp);
        const char *changes[] = {"voronoi-tiles.scale=5.5", "voronoi-tiles.search=exact", "voronoi-tiles.samples=2",
                                 "voronoi-tiles.seam_width=0.3", NULL};
        for (int i = 0; changes[i]; i++) CHECK(sl_harness_set(x, changes[i], err, sizeof err), "set %s: %s", changes[i], err);
        sl_harness_render(x, tmp);
        sl_harness_destroy(x);
        fresh = render(W, H, scene, changes, NULL, true);
        sl_compare c;
        sl_harness_compare(tmp, fresh, W, H, 0, &c);
        CHECK(c.max_abs == 0, "live change differs from a fresh start (max %g)", c.max_abs);
        free(tmp), free(fresh);
    }
    printf(failures ? "FAILED (%d)\n" : "all voronoi-tiles checks passed\n", failures);
    return failures ? 1 : 0;
}
