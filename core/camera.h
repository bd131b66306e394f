/* Orbit / pan / zoom / fly camera. Right-handed, Y up, looking down −Z in view space. */
#ifndef SL_CAMERA_H
#define SL_CAMERA_H
#include <stdbool.h>
#include <stdio.h>

struct sl_camera;

typedef struct sl_camera_state {
    float target[3];
    float yaw, pitch;      /* radians; yaw 0 = camera on +Z looking towards −Z */
    float distance;
    float fov_y_deg, znear, zfar;
    float aspect;
    unsigned long long version; /* bumps on every change */
    bool orthographic;     /* parallel projection, ymag = half the view's height (zoom scales it) */
    float ymag;
} sl_camera_state;

void sl_camera_from_scene(sl_camera_state *c, const struct sl_camera *sc);
void sl_camera_position(const sl_camera_state *c, float out[3]);
void sl_camera_matrices(const sl_camera_state *c, float view[16], float proj[16]);
void sl_camera_orbit(sl_camera_state *c, float dyaw, float dpitch);
void sl_camera_pan(sl_camera_state *c, float dx, float dy);   /* in units of distance */
void sl_camera_zoom(sl_camera_state *c, float factor);
void sl_camera_fly(sl_camera_state *c, float forward, float right, float up);
/* Prints the camera in scene-file syntax (the C key). */
void sl_camera_print(const sl_camera_state *c, FILE *f);
#endif
