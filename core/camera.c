#include "camera.h"
#include "scene/scene.h"
#include <cglm/cglm.h>
#include <math.h>

void sl_camera_from_scene(sl_camera_state *c, const sl_camera *sc) {
    float d[3] = {sc->position[0] - sc->target[0], sc->position[1] - sc->target[1],
                  sc->position[2] - sc->target[2]};
    float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(len > 1e-6f)) { d[2] = 1; len = 1; }
    c->target[0] = sc->target[0]; c->target[1] = sc->target[1]; c->target[2] = sc->target[2];
    c->distance = len;
    c->pitch = asinf(fmaxf(-1.f, fminf(1.f, d[1] / len)));
    c->yaw = atan2f(d[0], d[2]);
    c->fov_y_deg = sc->fov_y_deg > 0 ? sc->fov_y_deg : 45.f;
    c->znear = sc->znear > 0 ? sc->znear : 0.05f;
    c->zfar = sc->zfar > c->znear ? sc->zfar : 100.f;
    c->orthographic = sc->orthographic;
    c->ymag = sc->ymag > 0 ? sc->ymag : 1.f;
    c->version++;
}

void sl_camera_position(const sl_camera_state *c, float out[3]) {
    float cp = cosf(c->pitch);
    out[0] = c->target[0] + c->distance * cp * sinf(c->yaw);
    out[1] = c->target[1] + c->distance * sinf(c->pitch);
    out[2] = c->target[2] + c->distance * cp * cosf(c->yaw);
}

void sl_camera_matrices(const sl_camera_state *c, float view[16], float proj[16]) {
    vec3 eye, target = {c->target[0], c->target[1], c->target[2]}, up = {0, 1, 0};
    sl_camera_position(c, eye);
    glm_lookat(eye, target, up, (vec4 *)view);
    float aspect = c->aspect > 0 ? c->aspect : 1.f;
    if (c->orthographic) /* glTF 2.0 orthographic: x, y in [−xmag, xmag] × [−ymag, ymag] */
        glm_ortho(-c->ymag * aspect, c->ymag * aspect, -c->ymag, c->ymag, c->znear, c->zfar, (vec4 *)proj);
    else
        glm_perspective(glm_rad(c->fov_y_deg), aspect, c->znear, c->zfar, (vec4 *)proj);
}

void sl_camera_orbit(sl_camera_state *c, float dyaw, float dpitch) {
    c->yaw += dyaw;
    c->pitch = fmaxf(-1.55f, fminf(1.55f, c->pitch + dpitch));
    c->version++;
}

void sl_camera_pan(sl_camera_state *c, float dx, float dy) {
    /* camera right and up vectors from yaw/pitch */
    float right[3] = {cosf(c->yaw), 0, -sinf(c->yaw)};
    float up[3] = {-sinf(c->pitch) * sinf(c->yaw), cosf(c->pitch), -sinf(c->pitch) * cosf(c->yaw)};
    for (int i = 0; i < 3; i++) c->target[i] += (right[i] * dx + up[i] * dy) * c->distance;
    c->version++;
}

void sl_camera_zoom(sl_camera_state *c, float factor) {
    c->distance = fmaxf(1e-3f, c->distance * factor);
    if (c->orthographic) c->ymag = fmaxf(1e-6f, c->ymag * factor); /* a parallel view zooms by its extent */
    c->version++;
}

void sl_camera_fly(sl_camera_state *c, float forward, float right, float up) {
    float cp = cosf(c->pitch);
    float fwd[3] = {-cp * sinf(c->yaw), -sinf(c->pitch), -cp * cosf(c->yaw)};
    float r[3] = {cosf(c->yaw), 0, -sinf(c->yaw)};
    for (int i = 0; i < 3; i++) c->target[i] += fwd[i] * forward + r[i] * right;
    c->target[1] += up;
    c->version++;
}

void sl_camera_print(const sl_camera_state *c, FILE *f) {
    float p[3];
    sl_camera_position(c, p);
    fprintf(f, "{ \"name\": \"saved\", \"position\": [%.4f, %.4f, %.4f], \"target\": [%.4f, %.4f, %.4f], "
               "\"fov_y\": %.2f, \"near\": %g, \"far\": %g }\n",
            p[0], p[1], p[2], c->target[0], c->target[1], c->target[2], c->fov_y_deg, c->znear, c->zfar);
    if (c->orthographic) fprintf(f, "  (orthographic: add \"type\": \"orthographic\", \"ymag\": %g)\n", c->ymag);
}
