/* envmap: screen-space reflections (envmap.reflections=screen), against closed forms:
 *   mirror   a mirror floor under a uniform environment (L = 1) with a white-ish Lambert ball
 *            (albedo ρ = 0.5) above it: the ball's radiance is ρ L everywhere (the furnace), so
 *            a floor pixel whose mirrored ray meets the ball shows ρ L and one whose ray goes
 *            to the sky shows L — worked out per pixel from the camera's rays (tests/camera_rays.h),
 *            not from a render; at reflections_scale 1 and 0.5 (the default). With
 *            reflections=sky the floor shows L where the ball should be (the test can fail).
 *   rough    lobes as rough as reflections_alpha or rougher are the environment alone: a rough
 *            GGX ball's image is the same bit for bit with reflections on and off.
 *   live     switching reflections on in a running harness gives what a fresh start gives. */
#include "check.h"
#include "camera_rays.h"
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 128
#define H 96
static float img_a[W * H * 4], img_b[W * H * 4];
static const test_camera CAM = {.pos = {0, 2.2f, 6}, .target = {0, 0.4f, 0}, .fov_deg = 45, .width = W, .height = H};
static const float BALL[3] = {0, 1.0f, 0}, BALL_R = 0.6f, RHO = 0.5f;

static const char *const mirror_json =
    "{\"plugins\": [\"envmap\"], \"environment\": {\"color\": [1, 1, 1], \"intensity\": 1},"
    " \"cameras\": [{\"name\": \"c\", \"position\": [0, 2.2, 6], \"target\": [0, 0.4, 0], \"fov_y\": 45}],"
    " \"materials\": [{\"name\": \"floor\", \"model\": \"mirror\"},"
    "                 {\"name\": \"ball\", \"model\": \"lambert\", \"base_color\": [0.5, 0.5, 0.5]}],"
    " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 40}, \"material\": \"floor\"},"
    "           {\"name\": \"ball\", \"translate\": [0, 1.0, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.6,"
    "            \"segments\": 96}, \"material\": \"ball\"}]}";

static const char *const rough_json =
    "{\"plugins\": [\"ggx\", \"envmap\"],"
    " \"cameras\": [{\"name\": \"c\", \"position\": [0, 2.2, 6], \"target\": [0, 0.4, 0], \"fov_y\": 45}],"
    " \"materials\": [{\"name\": \"floor\", \"model\": \"lambert\", \"base_color\": [0.5, 0.5, 0.5]},"
    "                 {\"name\": \"ball\", \"model\": \"ggx\", \"base_color\": [0.9, 0.6, 0.3], \"roughness\": 0.8}],"
    " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 40}, \"material\": \"floor\"},"
    "           {\"name\": \"ball\", \"translate\": [0, 1.0, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.6},"
    "            \"material\": \"ball\"}]}";

static sl_harness *open_scene(const char *json, const char *const *extra) {
    const char *settings[16] = {"aa.enabled=false", "envmap.cache=false"};
    int n = 2;
    for (int i = 0; extra && extra[i] && n < 15; i++) settings[n++] = extra[i];
    settings[n] = NULL;
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                          .scene_json = json, .settings = settings, .float32 = true,
                                                          .strict = true},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    return h;
}

static bool render_scene(const char *json, const char *const *extra, float *img) {
    sl_harness *h = open_scene(json, extra);
    if (!h) return false;
    bool ok = sl_harness_render(h, img);
    CHECK(ok);
    sl_harness_destroy(h);
    return ok;
}

/* The ray's first hit with the ball (t > 0), or -1. */
static float hit_ball(const float o[3], const float d[3]) {
    float oc[3] = {o[0] - BALL[0], o[1] - BALL[1], o[2] - BALL[2]};
    float b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
    float c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - BALL_R * BALL_R, disc = b * b - c;
    if (disc < 0) return -1;
    float t = -b - sqrtf(disc);
    return t > 1e-4f ? t : -1;
}

/* What the closed form says a pixel shows: 0 the ball itself (or nothing), 1 the floor mirroring
 * the sky (L), 2 the floor mirroring a part of the ball the camera sees (ρ L), 3 one it does not
 * (the ball's underside: not in the image, so not reflected by a screen-space method; README). */
static int pixel_class(int px, int py) {
    float o[3], d[3], p[3];
    test_camera_ray(&CAM, px, py, o, d);
    if (hit_ball(o, d) > 0 || !test_camera_hit_ground(&CAM, px, py, 20, p)) return 0;
    float r[3] = {d[0], -d[1], d[2]}, t = hit_ball(p, r);
    if (t < 0) return 1;
    float q[3], n = 0;
    for (int i = 0; i < 3; i++) q[i] = p[i] + t * r[i];
    for (int i = 0; i < 3; i++) n += (q[i] - BALL[i]) * (CAM.pos[i] - q[i]); /* the normal towards the camera */
    return n > 0 ? 2 : 3;
}

/* Mean |shown − closed form| over the pixels whose 5×5 neighbourhood is all one class (the edges
 * of the reflection, at the image's texel size, are not judged), per class. */
static void mirror_errors(const float *img, double err[4], int count[4]) {
    for (int k = 0; k < 4; k++) err[k] = 0, count[k] = 0;
    for (int y = 2; y < H - 2; y++)
        for (int x = 2; x < W - 2; x++) {
            int c = pixel_class(x, y);
            bool uniform = c != 0;
            for (int j = -2; j <= 2 && uniform; j++)
                for (int i = -2; i <= 2 && uniform; i++) uniform = pixel_class(x + i, y + j) == c;
            if (!uniform) continue;
            double want = c >= 2 ? RHO : 1.0, got = img[(y * W + x) * 4 + 1];
            err[c] += fabs(got - want), count[c]++;
        }
    for (int k = 1; k < 4; k++) err[k] = count[k] ? err[k] / count[k] : 1e9;
}

static void test_mirror(void) {
    static const char *const cases[][3] = {{"envmap.reflections=screen", "envmap.reflections_scale=1", NULL},
                                           {"envmap.reflections=screen", "envmap.reflections_scale=0.5", NULL},
                                           {"envmap.reflections=sky", NULL, NULL}};
    static const double tolerance[] = {0.02, 0.04, 0};
    for (int k = 0; k < 3; k++) {
        if (!render_scene(mirror_json, cases[k], img_a)) return;
        double err[4];
        int count[4];
        mirror_errors(img_a, err, count);
        printf("mirror %s %s: sky %d px, mean error %.4f; ball %d px, mean error %.4f\n", cases[k][0],
               cases[k][1] ? cases[k][1] : "", count[1], err[1], count[2], err[2]);
        CHECK_MSG(count[1] > 500 && count[2] > 100, "the closed form's regions: %d, %d px", count[1], count[2]);
        CHECK_MSG(err[1] < 0.01, "the floor mirrors the sky: mean error %.4f", err[1]);
        if (k < 2)
            CHECK_MSG(err[2] < tolerance[k], "the floor mirrors the ball: mean error %.4f", err[2]);
        else /* the environment alone: L where the ball should be, 1 − ρ off */
            CHECK_MSG(fabs(err[2] - (1 - RHO)) < 0.01, "reflections=sky: %.4f", err[2]);
    }
}

static void test_rough(void) {
    const char *const on[] = {"envmap.reflections=screen", NULL}, *const off[] = {"envmap.reflections=sky", NULL};
    if (!render_scene(rough_json, on, img_a) || !render_scene(rough_json, off, img_b)) return;
    double most = 0;
    for (int i = 0; i < W * H * 4; i++) most = fmax(most, fabs(img_a[i] - img_b[i]));
    printf("rough ball (alpha 0.64): largest difference with reflections on %.3g\n", most);
    CHECK_MSG(most == 0, "a rough lobe is the environment alone: %.3g", most);
}

static void test_live(void) {
    const char *const on[] = {"envmap.reflections=screen", NULL};
    if (!render_scene(mirror_json, on, img_b)) return;
    sl_harness *h = open_scene(mirror_json, NULL);
    if (!h) return;
    CHECK(sl_harness_render(h, img_a));
    char err[512];
    CHECK_MSG(sl_harness_set(h, "envmap.reflections=screen", err, sizeof err), "%s", err);
    CHECK(sl_harness_render(h, img_a));
    sl_harness_destroy(h);
    double most = 0;
    for (int i = 0; i < W * H * 4; i++) most = fmax(most, fabs(img_a[i] - img_b[i]));
    printf("switched on live against a fresh start: largest difference %.3g\n", most);
    CHECK_MSG(most < 1e-6, "live = fresh start: %.3g", most);
}

int main(void) {
    test_mirror();
    test_rough();
    test_live();
    return check_result();
}
