/* --turntable's cameras (core/turntable.h), against closed forms: every frame's camera lies on
 * the circle about the vertical axis through the bounds' centre, at the start camera's height
 * and distance, looking at the axis; consecutive frames are 2π/N apart; the camera at angle 2π
 * (frame N) equals frame 0, so the loop is seamless; frame 0 is the start camera when its target
 * is on the axis. Frame names: the output's stem, the frame number, the extension. */
#include "check.h"
#include "turntable.h"
#include <math.h>

static void position(const sl_camera_state *c, double p[3]) {
    float f[3];
    sl_camera_position(c, f);
    for (int i = 0; i < 3; i++) p[i] = f[i];
}

static void test_orbit(void) {
    /* start: the default scene's camera, target (0, 0.65, 0), position (0.3, 2.3, 6.9) */
    sl_camera_state start = {.target = {0, 0.65f, 0}, .fov_y_deg = 38, .znear = 0.05f, .zfar = 100, .aspect = 16.f / 9};
    double sp[3] = {0.3, 2.3, 6.9};
    double d[3] = {sp[0] - 0, sp[1] - 0.65, sp[2] - 0};
    start.distance = (float)sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    start.pitch = (float)asin(d[1] / start.distance);
    start.yaw = (float)atan2(d[0], d[2]);
    float bmin[3] = {-12, 0, -12}, bmax[3] = {12, 1.3f, 12}; /* centred on the y axis */
    const int n = 7;
    double r0 = hypot(sp[0], sp[2]);
    sl_camera_state cam[8];
    for (int k = 0; k <= n; k++) {
        sl_turntable_camera(&start, bmin, bmax, k, n, &cam[k]);
        double p[3];
        position(&cam[k], p);
        CHECK_NEAR(hypot(p[0], p[2]), r0, 1e-5);          /* on the circle about the axis */
        CHECK_NEAR(p[1], sp[1], 1e-5);                    /* at the start height */
        CHECK_NEAR(cam[k].target[0], 0, 0);               /* looking at the axis */
        CHECK_NEAR(cam[k].target[1], 0.65, 1e-7);
        CHECK_NEAR(cam[k].target[2], 0, 0);
        CHECK_NEAR(cam[k].distance, start.distance, 1e-5);
        CHECK(cam[k].fov_y_deg == 38 && cam[k].aspect == start.aspect && cam[k].znear == start.znear);
        /* the angle about the axis: 2π·k/N from the start's */
        double want = atan2(sp[0], sp[2]) + 2 * M_PI * k / n, got = atan2(p[0], p[2]);
        CHECK_NEAR(remainder(got - want, 2 * M_PI), 0, 1e-5);
    }
    /* frame 0 is the start camera; frame N (angle 2π) is frame 0: a seamless loop */
    double p0[3], pn[3], p1[3];
    position(&cam[0], p0);
    position(&cam[n], pn);
    position(&cam[1], p1);
    for (int i = 0; i < 3; i++) {
        CHECK_NEAR(p0[i], sp[i], 1e-5);
        CHECK_NEAR(pn[i], p0[i], 1e-6);
    }
    CHECK_NEAR(cam[n].yaw, cam[0].yaw, 1e-6);
    /* the start camera looks at the axis: frame 0 is it exactly (bit for bit, the same image) */
    CHECK(cam[0].yaw == start.yaw && cam[0].pitch == start.pitch && cam[0].distance == start.distance &&
          !memcmp(cam[0].target, start.target, sizeof start.target));
    CHECK_NEAR(cam[n].pitch, cam[0].pitch, 0);
    /* and the frames really move: a chord of 2·r·sin(π/N) between neighbours */
    CHECK_NEAR(hypot(p1[0] - p0[0], p1[2] - p0[2]), 2 * r0 * sin(M_PI / n), 1e-5);
    CHECK(cam[1].version != cam[0].version); /* the renderer sees a new view */

    /* off-centre bounds: the axis moves to their centre, the target with it (x, z) */
    float omin[3] = {2, 0, -1}, omax[3] = {4, 1, 3};
    sl_camera_state c;
    sl_turntable_camera(&start, omin, omax, 3, 4, &c);
    CHECK_NEAR(c.target[0], 3, 1e-6);
    CHECK_NEAR(c.target[2], 1, 1e-6);
    double p[3];
    position(&c, p);
    CHECK_NEAR(hypot(p[0] - 3, p[2] - 1), hypot(sp[0] - 3, sp[2] - 1), 1e-5);
    /* empty bounds (min > max): the start target is the axis */
    float emin[3] = {1, 1, 1}, emax[3] = {-1, -1, -1};
    sl_turntable_camera(&start, emin, emax, 0, 4, &c);
    position(&c, p);
    for (int i = 0; i < 3; i++) CHECK_NEAR(p[i], sp[i], 1e-5);
    /* a camera straight above the axis stays finite */
    sl_camera_state top = start;
    top.pitch = (float)(M_PI / 2);
    sl_turntable_camera(&top, bmin, bmax, 1, 4, &c);
    CHECK(isfinite(c.yaw) && isfinite(c.pitch) && isfinite(c.distance) && c.distance > 0);
}

static void test_names(void) {
    char p[256];
    CHECK(sl_turntable_frame_path("out.png", 0, 4, p, sizeof p) && !strcmp(p, "out-000.png"));
    CHECK(sl_turntable_frame_path("dir.d/x.exr", 12, 120, p, sizeof p) && !strcmp(p, "dir.d/x-012.exr"));
    CHECK(sl_turntable_frame_path("dir.d/x", 3, 4, p, sizeof p) && !strcmp(p, "dir.d/x-003.png"));
    CHECK(sl_turntable_frame_path("spin.mp4", 7, 8, p, sizeof p) && !strcmp(p, "spin-007.png"));
    CHECK(sl_turntable_frame_path("a/b", 1234, 2000, p, sizeof p) && !strcmp(p, "a/b-1234.png"));
    CHECK(sl_turntable_frame_path("t.png", 999, 1000, p, sizeof p) && !strcmp(p, "t-999.png"));
    CHECK(sl_turntable_frame_path("t.png", 5, 1001, p, sizeof p) && !strcmp(p, "t-0005.png"));
    CHECK(!sl_turntable_frame_path("long-name.png", 1, 4, p, 8)); /* does not fit: refused */
}

int main(void) {
    test_orbit();
    test_names();
    return check_result();
}
