/* Frustum culling (core/render/scene_gpu.c): a mesh whose bounds lie wholly outside the view's
 * side planes is not drawn, and costs nothing.
 *   1. the scene with 40 sphere instances added outside the view (left, right, above, below and
 *      behind the camera) renders the same image, bit for bit, with the same draw calls as the
 *      scene without them;
 *   2. one more instance straddling the view's left edge is drawn: more draw calls, a different
 *      image (culling keeps what may touch the view);
 *   3. with culling's reach checked from the other side: the instances placed in view instead
 *      add their draws (the 40 are real meshes, not dropped by the loader). */
#include "app.h"
#include "check.h"
#include "render/renderer.h"
#include "test_tmp.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 64
#define H 48

/* The base scene (a lit teapot and sphere on a floor, the camera at z = 6 looking at the origin)
 * plus `extra` (JSON nodes, each starting with a comma, or ""). */
static const char *write_scene(const char *name, const char *extra) {
    static char path[4][512];
    static int slot;
    char *p = path[slot++ % 4];
    snprintf(p, 512, "%s", sl_test_path(name));
    char *text = malloc(64 * 1024);
    int n = snprintf(text, 64 * 1024,
        "{\"cameras\": [{\"name\": \"main\", \"position\": [0, 1, 6], \"target\": [0, 0.5, 0], \"fov_y\": 40}],\n"
        " \"materials\": [{\"name\": \"red\", \"base_color\": [0.8, 0.2, 0.1]}, {\"name\": \"grey\", \"base_color\": [0.5, 0.5, 0.5]}],\n"
        " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [-0.4, -1, -0.3], \"intensity\": 3}],\n"
        " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 6}, \"material\": \"grey\"},\n"
        "  {\"name\": \"teapot\", \"mesh\": {\"primitive\": \"teapot\", \"size\": 1}, \"material\": \"red\"},\n"
        "  {\"name\": \"ball\", \"translate\": [1.4, 0.5, 0.5], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.5}, \"material\": \"red\"}"
        "%s]}\n", extra);
    sl_test_write_file(p, text, (size_t)n);
    free(text);
    return p;
}

/* 40 spheres of radius 0.5: 8 each left, right, above, below (x or y at ±(12 + k), z from 0 to
 * -7), and behind the camera (z = 8 + k); or, in_view, the same 40 in a grid in front of the
 * teapot. */
static void instances(char *out, size_t n, bool in_view) {
    size_t len = 0;
    out[0] = 0;
    for (int i = 0; i < 40; i++) {
        int side = i / 8, k = i % 8;
        float x = 0, y = 0.5f, z = -k;
        if (in_view) x = -1.75f + 0.5f * k, y = 0.3f + 0.3f * side, z = 2;
        else if (side == 0) x = -12 - k;
        else if (side == 1) x = 12 + k;
        else if (side == 2) y = 12 + k;
        else if (side == 3) y = -12 - k;
        else z = 8 + k, x = 0.3f * k;
        len += snprintf(out + len, n - len,
                        ",\n  {\"name\": \"i%d\", \"translate\": [%g, %g, %g], \"mesh\": {\"primitive\": \"sphere\", "
                        "\"radius\": 0.5, \"segments\": 16, \"rings\": 8}, \"material\": \"red\"}", i, x, y, z);
    }
}

typedef struct frame { float rgba[W * H * 4]; int draws; } frame;

static bool render(const char *scene, frame *out) {
    sl_app app;
    char err[4096];
    sl_app_options o = {.scene_path = scene, .backend = SL_BACKEND_OSMESA, .width = W, .height = H};
    bool ok = sl_app_init(&app, &o, err, sizeof err) && sl_app_start_gl(&app, err, sizeof err);
    CHECK_MSG(ok, "%s: %s", scene, err);
    ok = ok && sl_app_render_frame(&app) && sl_app_render_frame(&app);
    const sl_frame_stats *st = ok ? sl_renderer_stats(&app) : NULL;
    out->draws = st ? st->draw_calls + st->reused_draw_calls : -1;
    ok = ok && sl_app_read_display(&app, out->rgba);
    sl_app_shutdown(&app);
    return ok;
}

static double max_diff(const frame *a, const frame *b) {
    double m = 0;
    for (int i = 0; i < W * H * 4; i++) m = fmax(m, fabs((double)a->rgba[i] - b->rgba[i]));
    return m;
}

int main(void) {
    static char outside[16384], inside[16384], edge[17000];
    static frame base, culled, straddle, shown;
    instances(outside, sizeof outside, false);
    instances(inside, sizeof inside, true);
    snprintf(edge, sizeof edge, "%s,\n  {\"name\": \"edge\", \"translate\": [-2.9, 0.5, 0], \"mesh\": {\"primitive\": "
             "\"sphere\", \"radius\": 0.5}, \"material\": \"red\"}", outside);
    bool ok = render(write_scene("base.json", ""), &base) && render(write_scene("outside.json", outside), &culled) &&
              render(write_scene("edge.json", edge), &straddle) && render(write_scene("inside.json", inside), &shown);
    CHECK(ok);
    if (!ok) return check_result();
    double d = max_diff(&base, &culled);
    printf("draw calls: base %d, 40 instances outside %d, one more on the left edge %d, the 40 in view %d; "
           "largest difference base/outside %g, base/edge %g\n", base.draws, culled.draws, straddle.draws, shown.draws, d,
           max_diff(&base, &straddle));
    CHECK_MSG(d == 0, "40 instances outside the view change the image by up to %g", d);
    CHECK_MSG(culled.draws == base.draws, "40 instances outside the view cost %d draw calls", culled.draws - base.draws);
    CHECK_MSG(straddle.draws > base.draws, "an instance on the view's edge is drawn");
    CHECK_MSG(max_diff(&base, &straddle) > 0.05, "an instance on the view's edge shows");
    CHECK_MSG(shown.draws >= base.draws + 40, "the 40 instances in view are drawn (%d draw calls more)", shown.draws - base.draws);
    return check_result();
}
