/* Per-pixel camera rays for closed-form image tests, computed with cglm from a scene camera's
 * position, target and vertical field of view — independently of the renderer's camera code.
 * Pixel (px, py) counts from the top-left, as the harness returns images. */
#ifndef SL_TEST_CAMERA_RAYS_H
#define SL_TEST_CAMERA_RAYS_H
#include <cglm/cglm.h>
#include <stdbool.h>

typedef struct test_camera { float pos[3], target[3], fov_deg; int width, height; } test_camera;

/* The ray through window position (fx, fy) in pixels from the top-left corner (a pixel's centre is
 * at +0.5). */
static inline void test_camera_ray_at(const test_camera *c, float fx, float fy, float origin[3], float dir[3]) {
    mat4 view, proj, vp, inv;
    glm_lookat((float *)c->pos, (float *)c->target, (vec3){0, 1, 0}, view);
    glm_perspective(glm_rad(c->fov_deg), (float)c->width / c->height, 0.1f, 100.f, proj);
    glm_mat4_mul(proj, view, vp);
    glm_mat4_inv(vp, inv);
    float nx = fx / c->width * 2 - 1, ny = 1 - fy / c->height * 2;
    vec4 a = {nx, ny, -1, 1}, b = {nx, ny, 1, 1}, wa, wb;
    glm_mat4_mulv(inv, a, wa);
    glm_mat4_mulv(inv, b, wb);
    for (int i = 0; i < 3; i++) {
        origin[i] = wa[i] / wa[3];
        dir[i] = wb[i] / wb[3] - origin[i];
    }
    glm_vec3_normalize(dir);
}

static inline void test_camera_ray(const test_camera *c, int px, int py, float origin[3], float dir[3]) {
    test_camera_ray_at(c, px + 0.5f, py + 0.5f, origin, dir);
}

/* Hit point on the plane y = 0 within |x|, |z| < half_size; false when missed. */
static inline bool test_camera_hit_ground(const test_camera *c, int px, int py, float half_size, float hit[3]) {
    float o[3], d[3];
    test_camera_ray(c, px, py, o, d);
    if (d[1] >= 0) return false;
    float t = -o[1] / d[1];
    for (int i = 0; i < 3; i++) hit[i] = o[i] + t * d[i];
    return fabsf(hit[0]) < half_size && fabsf(hit[2]) < half_size;
}
#endif
