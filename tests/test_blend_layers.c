/* 100 000 overlapping blended quads (glTF alphaMode BLEND, the core's forward-blend pass) under
 * TAA: the headless still completes (sl_still: converged or its frames done; the test's timeout
 * bounds the time, nothing here times it) and every layer is composited: an orthographic camera,
 * one pixel per metre, sees 8 x 8 cells of 4 x 4 pixels; cell i holds k_i unlit quads of colour c
 * and coverage a stacked exactly on it (k_i = i for the first 63 cells, the remaining 98 047 on the
 * last), so the centre pixels of a cell (out of reach of TAA's half-pixel jitter) are in closed form
 *     c + (bg - c) (1 - a)^k_i,
 * bg the background, read in the cell of no quad. Checked within 2/255 (the blend accumulates in
 * a half-float target) on every cell's four centre pixels, no NaN/Inf anywhere, and no pixel
 * outside [min(bg, c), max(bg, c)] (each blend is a convex combination). The passes' times of the
 * last frame are printed, not asserted. */
#include "app.h"
#include "check.h"
#include "render/renderer.h"
#include "still.h"
#include "test_tmp.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define S 32          /* image side, pixels = metres */
#define CELLS 8       /* per side */
#define CELL (S / CELLS)
#define QUADS 100000
static const float c[3] = {0.9f, 0.5f, 0.1f}, a = 0.25f;

static int layers(int cell) {
    int last = CELLS * CELLS - 1, below = last * (last - 1) / 2; /* 0 + 1 + ... + 62 */
    return cell < last ? cell : QUADS - below;
}

/* The quads as one OBJ mesh: cell (cx, cy), cy counted from the image's top, spans x in
 * [-S/2 + CELL cx, + CELL] and y in [S/2 - CELL (cy + 1), + CELL], at z = 0. */
static bool write_mesh(const char *path) {
    FILE *f = fopen(path, "w");
    if (!f) return false;
    fprintf(f, "vn 0 0 1\n");
    long v = 0;
    for (int cell = 0; cell < CELLS * CELLS; cell++) {
        float x0 = -S / 2.0f + CELL * (cell % CELLS), y0 = S / 2.0f - CELL * (cell / CELLS + 1);
        for (int k = 0; k < layers(cell); k++, v += 4) {
            fprintf(f, "v %g %g 0\nv %g %g 0\nv %g %g 0\nv %g %g 0\n", x0, y0, x0 + CELL, y0, x0 + CELL, y0 + CELL, x0,
                    y0 + CELL);
            fprintf(f, "f %ld//1 %ld//1 %ld//1 %ld//1\n", v + 1, v + 2, v + 3, v + 4);
        }
    }
    return fclose(f) == 0;
}

static bool write_scene(const char *path, const char *mesh) {
    FILE *f = fopen(path, "w");
    if (!f) return false;
    fprintf(f, "{\"cameras\": [{\"name\": \"top\", \"type\": \"orthographic\", \"ymag\": %g, \"xmag\": %g, "
               "\"position\": [0, 0, 5], \"target\": [0, 0, 0]}],\n"
               " \"materials\": [{\"name\": \"glass\", \"base_color\": [%g, %g, %g], \"opacity\": %g, "
               "\"alpha_blend\": true, \"unlit\": true}],\n"
               " \"nodes\": [{\"name\": \"quads\", \"mesh\": {\"file\": \"%s\"}, \"material\": \"glass\"}]}\n",
            S / 2.0, S / 2.0, c[0], c[1], c[2], a, mesh);
    return fclose(f) == 0;
}

static void print_passes(sl_app *app) {
    const sl_frame_stats *st = sl_renderer_stats(app);
    if (!st) return;
    printf("last frame's passes:");
    for (int i = 0; i < st->pass_count; i++) printf(" %s %.1f ms", st->passes[i].name, st->passes[i].ms);
    printf("; %d draw calls\n", st->draw_calls);
}

int main(void) {
    char mesh[600], scene[600], err[4096];
    snprintf(mesh, sizeof mesh, "%s", sl_test_path("quads.obj"));
    snprintf(scene, sizeof scene, "%s", sl_test_path("quads.json"));
    CHECK(write_mesh(mesh) && write_scene(scene, "quads.obj"));
    sl_app app;
    sl_app_options o = {.scene_path = scene, .backend = SL_BACKEND_OSMESA, .width = S, .height = S, .keep_color = true,
                     .timings = true};
    bool ok = sl_app_init(&app, &o, err, sizeof err) && sl_app_start_gl(&app, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    if (!ok) return check_result();
    sl_still still;
    sl_still_begin(&still, 0);
    for (bool done = false; ok && !done;) {
        ok = sl_app_render_frame(&app);
        done = sl_still_done(&still, &app);
    }
    printf("still: %d of %d frames, %s\n", still.frames, still.needed, still.stopped);
    CHECK_MSG(ok && still.frames <= still.needed, "the still: %d of %d frames", still.frames, still.needed);
    print_passes(&app);
    float *px = malloc(sizeof(float) * S * S * 4);
    ok = ok && sl_app_read_color(&app, px);
    sl_still_end(&still);
    sl_app_shutdown(&app);
    CHECK(ok);
    if (!ok) return free(px), check_result();
    long bad = 0, outside = 0;
    for (int i = 0; i < S * S * 4; i++) bad += !isfinite(px[i]);
    CHECK_MSG(bad == 0, "%ld non-finite values", bad);
    /* the background: the centre of cell 0 (no quad) */
    int mid = CELL / 2;
    const float *bg = px + ((size_t)mid * S + mid) * 4;
    double worst = 0;
    int worst_cell = -1;
    for (int cell = 0; cell < CELLS * CELLS; cell++) {
        int x0 = CELL * (cell % CELLS), y0 = CELL * (cell / CELLS);
        for (int dy = mid - 1; dy <= mid; dy++)
            for (int dx = mid - 1; dx <= mid; dx++)
                for (int ch = 0; ch < 3; ch++) {
                    double want = c[ch] + (bg[ch] - c[ch]) * pow(1 - a, layers(cell));
                    double d = fabs(px[((size_t)(y0 + dy) * S + x0 + dx) * 4 + ch] - want);
                    if (d > worst) worst = d, worst_cell = cell;
                }
    }
    for (int i = 0; i < S * S; i++)
        for (int ch = 0; ch < 3; ch++) {
            double lo = fmin(bg[ch], c[ch]) - 1e-3, hi = fmax(bg[ch], c[ch]) + 1e-3;
            outside += px[i * 4 + ch] < lo || px[i * 4 + ch] > hi;
        }
    printf("background (%.4f, %.4f, %.4f); largest difference from c + (bg - c)(1 - a)^k: %.5f (cell %d, %d layers)\n",
           bg[0], bg[1], bg[2], worst, worst_cell, worst_cell >= 0 ? layers(worst_cell) : 0);
    CHECK_MSG(worst <= 2.0 / 255, "a cell's centre is %g from the closed form", worst);
    CHECK_MSG(outside == 0, "%ld values outside [min(bg, c), max(bg, c)]", outside);
    free(px);
    return check_result();
}
