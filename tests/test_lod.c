/* Levels of detail by projected size (core.lod_pixels, core/render/lod.h):
 *   1. the levels: a sphere of 65 024 triangles gets coarser index lists, each at most two thirds
 *      of the one before, with errors growing from 0 (meshoptimizer's simplifier);
 *   2. the choice: a level is drawn only when its error projects to at most the given pixels
 *      (sl_lod_pick on a perspective and an orthographic projection, in closed form);
 *   3. rendered: the sphere far away (about 12 pixels across) is drawn with under a quarter of its
 *      triangles at 1 px, close up (filling the view) with more than far away, each with an image
 *      that differs from the full mesh's by a mean under 1/255; core.lod_pixels = 0 draws every
 *      triangle. */
#include "app.h"
#include "check.h"
#include "render/lod.h"
#include "render/renderer.h"
#include "test_tmp.h"
#include <cglm/cglm.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 64
#define H 64

static void test_levels(void) {
    sl_mesh_data m;
    CHECK(sl_mesh_sphere(&m, 1, 256, 128));
    sl_lod_levels l;
    int total = 0;
    uint32_t *idx = sl_lod_build(&m, &l, &total);
    printf("levels of a %d-triangle sphere:", m.index_count / 3);
    for (int k = 0; k < l.count; k++) printf(" %d (error %.4f)", l.index_count[k] / 3, l.error[k]);
    printf("\n");
    CHECK_MSG(idx && l.count >= 3, "%d levels", l.count);
    CHECK(l.index_count[0] == m.index_count && l.error[0] == 0 && l.first[0] == 0);
    for (int k = 1; idx && k < l.count; k++) {
        CHECK(l.index_count[k] * 3 <= l.index_count[k - 1] * 2 && l.index_count[k] % 3 == 0);
        CHECK(l.error[k] > l.error[k - 1] && l.error[k] < 1); /* a unit sphere: below its radius */
        CHECK(l.first[k] == l.first[k - 1] + l.index_count[k - 1]);
        for (int i = 0; i < l.index_count[k]; i++) CHECK_MSG(idx[l.first[k] + i] < (uint32_t)(m.vertex_count), "index");
    }
    CHECK(total == l.first[l.count - 1] + l.index_count[l.count - 1]);
    free(idx);
    sl_mesh_data small;
    CHECK(sl_mesh_sphere(&small, 1, 16, 8));
    CHECK_MSG(!sl_lod_build(&small, &l, &total) && l.count == 1, "a small mesh keeps one level");
    sl_mesh_free(&m);
    sl_mesh_free(&small);
}

static void test_pick(void) {
    sl_lod_levels l = {.count = 3, .index_count = {300, 90, 30}, .error = {0, 0.01f, 0.1f}};
    mat4 proj, ortho;
    glm_perspective(glm_rad(60), 1, 0.1f, 100, proj);
    glm_ortho(-2, 2, -2, 2, 0.1f, 100, ortho);
    /* 1 px at depth z on 100 px: e * cot(30 deg) * 50 / z; level 1 (0.01) is 1 px at z = 0.866 * ... */
    float f = 1 / tanf(glm_rad(30)) * 50; /* pixels per unit at depth 1 */
    float at1 = 0.01f * f, at2 = 0.1f * f;  /* level 1 and 2 in pixels at depth 1 */
    float c[3] = {0, 0, 0};
    c[2] = -(at1 * 1.01f); /* level 1 projects just under 1 px, level 2 ten times more */
    CHECK(sl_lod_pick(&l, (float *)proj, c, 0, 1, 100, 1) == 1);
    c[2] = -(at2 * 1.01f);
    CHECK(sl_lod_pick(&l, (float *)proj, c, 0, 1, 100, 1) == 2);
    c[2] = -(at1 * 0.99f);
    CHECK(sl_lod_pick(&l, (float *)proj, c, 0, 1, 100, 1) == 0);
    CHECK_MSG(sl_lod_pick(&l, (float *)proj, c, 0, 1, 100, 0) == 0, "0 px: off");
    c[2] = -(at2 * 1.01f) - 0.5f; /* a radius of 0.5 brings the nearest point to where level 2 is 1 px */
    CHECK(sl_lod_pick(&l, (float *)proj, c, 0.5f, 1, 100, 1) == 2);
    CHECK(sl_lod_pick(&l, (float *)proj, c, 0.5f, 2, 100, 1) == 1); /* scaled twice: errors twice */
    /* orthographic: 25 px per unit on 100 px whatever the depth: level 1 is 0.25 px, level 2 2.5 */
    c[2] = -50;
    CHECK(sl_lod_pick(&l, (float *)ortho, c, 0, 1, 100, 1) == 1);
    CHECK(sl_lod_pick(&l, (float *)ortho, c, 0, 1, 100, 3) == 2);
}

static const char *scene(float z) {
    static char path[2][512];
    static int slot;
    char *p = path[slot++ % 2], text[1024];
    snprintf(p, 512, "%s", sl_test_path(z > 5 ? "far.json" : "near.json"));
    int n = snprintf(text, sizeof text,
        "{\"cameras\": [{\"name\": \"main\", \"position\": [0, 0, %g], \"target\": [0, 0, 0], \"fov_y\": 40}],\n"
        " \"materials\": [{\"name\": \"red\", \"base_color\": [0.8, 0.2, 0.1]}],\n"
        " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [-0.4, -1, -0.6], \"intensity\": 3}],\n"
        " \"nodes\": [{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1, \"segments\": 256, "
        "\"rings\": 128}, \"material\": \"red\"}]}\n", z);
    sl_test_write_file(p, text, (size_t)n);
    return p;
}

static bool render(const char *path, float pixels, float *rgba, long *triangles) {
    sl_app app;
    char err[4096], set[64];
    snprintf(set, sizeof set, "core.lod_pixels=%g", pixels);
    sl_app_options o = {.scene_path = path, .backend = SL_BACKEND_OSMESA, .width = W, .height = H};
    o.settings[o.setting_count++] = set;
    o.settings[o.setting_count++] = "aa.enabled=false";
    bool ok = sl_app_init(&app, &o, err, sizeof err) && sl_app_start_gl(&app, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    ok = ok && sl_app_render_frame(&app);
    *triangles = ok ? sl_renderer_stats(&app)->triangles : -1;
    ok = ok && sl_app_read_display(&app, rgba);
    sl_app_shutdown(&app);
    return ok;
}

static double mean_diff(const float *a, const float *b) {
    double s = 0;
    for (int i = 0; i < W * H * 4; i++) s += fabs((double)a[i] - b[i]);
    return s / (W * H * 3);
}

static void test_rendered(void) {
    static float full[W * H * 4], lod[W * H * 4], near_full[W * H * 4], near_lod[W * H * 4];
    long t_full, t_lod, t_near_full, t_near_lod;
    const char *far = scene(16), *near = scene(1.3f);
    bool ok = render(far, 0, full, &t_full) && render(far, 1, lod, &t_lod) && render(near, 0, near_full, &t_near_full) &&
              render(near, 1, near_lod, &t_near_lod);
    CHECK(ok);
    if (!ok) return;
    double d = mean_diff(full, lod);
    printf("far: %ld triangles in full, %ld with 1 px (mean difference %.5f); near: %ld and %ld\n", t_full, t_lod, d,
           t_near_full, t_near_lod);
    CHECK_MSG(t_full >= 65024 && t_lod * 4 < t_full, "far: %ld of %ld triangles", t_lod, t_full);
    CHECK_MSG(d < 1.0 / 255, "far: the levels' image differs by a mean of %g", d);
    CHECK_MSG(t_near_full >= 65024 && t_near_lod > t_lod, "near: %ld triangles, far %ld", t_near_lod, t_lod);
    double dn = mean_diff(near_full, near_lod);
    printf("near: mean difference %.5f\n", dn);
    CHECK_MSG(dn < 1.0 / 255, "near: the levels' image differs by a mean of %g", dn);
}

int main(void) {
    test_levels();
    test_pick();
    test_rendered();
    return check_result();
}
