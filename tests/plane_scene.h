/* Test support shared by plugin tests (tests/ belongs to no module; every sl_add_test sees it):
 * a plane scene seen by a known camera, per-pixel camera rays (so expected radiance is computed
 * in C, independently of the renderer), harness shortcuts, scratch files for generated maps,
 * and small vector maths. Used by the normal-map and phong tests. */
#ifndef SL_TEST_PLANE_SCENE_H
#define SL_TEST_PLANE_SCENE_H

#include "check.h"
#include "image/image.h"
#include "test_tmp.h"
#include "view_guard.h"
#include <cglm/cglm.h>
#include <errno.h>
#include <shadelab/harness.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Camera of the plane scenes: position, target, vertical fov. */
static const float pt_cam_pos[3] = {0, 5, 5}, pt_cam_target[3] = {0, 0, 0}, pt_fov_deg = 50;

/* Ray through pixel (px, py) of a w×h image (py = 0 is the top row, as the harness returns
 * images) hits the plane y = 0 at hit[] (|x|, |z| < half); false when it misses. */
static inline bool pt_plane_hit(int px, int py, int w, int h, float half, float hit[3]) {
    mat4 view, proj, vp, inv;
    glm_lookat((float *)pt_cam_pos, (float *)pt_cam_target, (vec3){0, 1, 0}, view);
    glm_perspective(glm_rad(pt_fov_deg), (float)w / h, 0.1f, 100.f, proj);
    glm_mat4_mul(proj, view, vp);
    glm_mat4_inv(vp, inv);
    float nx = (px + 0.5f) / w * 2 - 1, ny = 1 - (py + 0.5f) / h * 2;
    vec4 a = {nx, ny, -1, 1}, b = {nx, ny, 1, 1}, wa, wb;
    glm_mat4_mulv(inv, a, wa);
    glm_mat4_mulv(inv, b, wb);
    vec3 o = {wa[0] / wa[3], wa[1] / wa[3], wa[2] / wa[3]}, e = {wb[0] / wb[3], wb[1] / wb[3], wb[2] / wb[3]}, d;
    glm_vec3_sub(e, o, d);
    if (d[1] >= 0) return false;
    float t = -o[1] / d[1];
    for (int i = 0; i < 3; i++) hit[i] = o[i] + t * d[i];
    return fabsf(hit[0]) < half && fabsf(hit[2]) < half;
}

/* Unit vector from p to the camera. */
static inline void pt_view_dir(const float p[3], float v[3]) {
    float d[3] = {pt_cam_pos[0] - p[0], pt_cam_pos[1] - p[1], pt_cam_pos[2] - p[2]};
    float l = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int i = 0; i < 3; i++) v[i] = d[i] / l;
}

static inline void pt_normalize(double v[3]) {
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++) v[i] /= l;
}
static inline double pt_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* The plane primitive's tangent frame (core/scene/primitives.c, scenes/README.md): T = +X,
 * N = +Y, bitangent w·cross(N, T) = −Z = image up (v grows along +Z and v = 0 is the image's
 * top row). A +Y tangent-space normal (x, y, z) is therefore the world normal x·X − y·Z + z·Y. */
static inline void pt_plane_tangent_to_world(const double nt[3], double out[3]) {
    out[0] = nt[0], out[1] = nt[2], out[2] = -nt[1];
    pt_normalize(out);
}

/* Scratch directory for generated files: <test directory>/<name>/ (created; tests/test_tmp.h). */
static inline const char *pt_scratch(const char *name) {
    static char dir[1024];
    snprintf(dir, sizeof dir, "%s/%s", sl_test_dir(), name);
    mkdir(dir, 0777);
    return dir;
}

/* Writes a float RGBA image as PNG (8-bit, values as they are) or EXR (half) by extension. */
static inline bool pt_write(const char *path, const sl_image *img) {
    char err[1024];
    bool ok = sl_image_write(path, img->pixels, img->width, img->height, true, err, sizeof err);
    if (!ok) fprintf(stderr, "%s\n", err);
    return ok;
}

/* A constant-colour image (for 8-bit maps written as PNG). */
static inline bool pt_constant_image(sl_image *img, int size, float r, float g, float b) {
    memset(img, 0, sizeof *img);
    img->pixels = malloc((size_t)size * size * 4 * sizeof(float));
    if (!img->pixels) return false;
    img->width = img->height = size, img->channels = 4, img->source_bits = 32;
    for (int i = 0; i < size * size; i++) {
        float *p = img->pixels + i * 4;
        p[0] = r, p[1] = g, p[2] = b, p[3] = 1;
    }
    return true;
}

static inline sl_harness *pt_harness(const char *json, int w, int h, const char *const *plugins, const char *const *settings,
                              const char *debug_view) {
    char err[8192];
    sl_harness *hs = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = w, .height = h,
                                                           .scene_json = json, .plugins = plugins, .settings = settings,
                                                           .debug_view = debug_view, .float32 = true, .strict = true},
                                       err, sizeof err);
    if (!hs) fprintf(stderr, "harness: %s\n", err);
    return hs;
}

/* Renders json once into img (w*h*4 floats); false (and a message) on failure. */
static inline bool pt_render(const char *json, int w, int h, const char *const *plugins, const char *const *settings,
                      const char *debug_view, float *img) {
    sl_harness *hs = pt_harness(json, w, h, plugins, settings, debug_view);
    if (!hs) return false;
    bool ok = sl_harness_render(hs, img);
    sl_harness_destroy(hs);
    return ok;
}

/* One 32×32 frame of `scene`: its structure (passes, draw calls, program hashes per material),
 * for the "a material pays only for what it uses" checks. */
static inline bool pt_structure(const char *scene, const char *const *plugins, const char *const *settings,
                                sl_harness_structure *st) {
    sl_harness *h = pt_harness(scene, 32, 32, plugins, settings, NULL);
    if (!h) return false;
    bool ok = sl_harness_render(h, NULL);
    sl_harness_structure_of(h, st);
    sl_harness_destroy(h);
    return ok;
}

static inline double pt_srgb_encode(double x) {
    x = x < 0 ? 0 : x > 1 ? 1 : x;
    return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1 / 2.4) - 0.055;
}

#endif
