/* envmap: the procedural sky's sun as a light of its own (envmap.sun_light, light envmap.sun: the
 * SDK's plugin lights, ABI 1.22), against closed forms:
 *   state    the light's direction is the sky's sun turned by the yaw, on paper: azimuth a + yaw
 *            (0 towards +Z, 90 towards +X), elevation e; its irradiance the disk's,
 *            ∫ (E/Ω) cos over the disk = E (1 + cos r)/2; off with sun_light=false;
 *   energy   a white Lambert floor (no shadow plugin): the sky without its disk plus the light
 *            gives what the sky with its disk gave (the SH irradiance of the disk is not exact:
 *            within 3 %), where leaving the disk in the sky as well would add E sin e / π; the
 *            user's light.envmap.sun.enabled=false takes exactly the light's term away;
 *   shadow   with spotlight-shadow: a ball's umbra on the floor (6° inside its edge: past the
 *            penumbra) is darker than the same pixels with the light's cast_shadows off by exactly ρ/π · E (1 + cos r)/2 · sin e (the sky's
 *            lighting has no visibility, so only the sun's direct term goes), and the floor
 *            far from the shadow does not change. */
#include "check.h"
#include "camera_rays.h"
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 96
#define H 96
static float img_a[W * H * 4], img_b[W * H * 4];
static const double E_SUN = 3, ELEVATION = 30, AZIMUTH = 40, RADIUS = 1.5; /* degrees */

static const char *const scene_json =
    "{\"plugins\": [\"envmap\"],"
    " \"cameras\": [{\"name\": \"c\", \"position\": [0, 8, 5], \"target\": [0, 0, 0], \"fov_y\": 50}],"
    " \"materials\": [{\"name\": \"floor\", \"model\": \"lambert\", \"base_color\": [0.5, 0.5, 0.5]},"
    "                 {\"name\": \"ball\", \"model\": \"lambert\", \"base_color\": [0.5, 0.5, 0.5]}],"
    " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 40}, \"material\": \"floor\"},"
    "           {\"name\": \"ball\", \"translate\": [0, 1.2, 0], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.6},"
    "            \"material\": \"ball\"}]}";
static const float BALL[3] = {0, 1.2f, 0}, BALL_R = 0.6f;

static sl_harness *open_scene(const char *const *extra, const char *plugin) {
    const char *settings[16] = {"aa.enabled=false", "envmap.sun_elevation=30", "envmap.sun_azimuth=40",
                                "envmap.sun_irradiance=3", "envmap.cache=false", "envmap.irradiance=convolved",
                                "envmap.sun_light=true"};
    int n = 7;
    for (int i = 0; extra && extra[i] && n < 15; i++) settings[n++] = extra[i];
    settings[n] = NULL;
    const char *plugins[] = {plugin, NULL};
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                          .scene_json = scene_json, .settings = settings,
                                                          .plugins = plugin ? plugins : NULL, .float32 = true,
                                                          .strict = true},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    return h;
}

/* One harness per process: open, render one frame into img, close. */
static bool render_scene(const char *const *extra, const char *plugin, float *img) {
    sl_harness *h = open_scene(extra, plugin);
    if (!h) return false;
    bool ok = sl_harness_render(h, img);
    CHECK(ok);
    sl_harness_destroy(h);
    return ok;
}

static void sun_world(double yaw_deg, double d[3]) {
    double e = ELEVATION * M_PI / 180, a = (AZIMUTH + yaw_deg) * M_PI / 180;
    d[0] = cos(e) * sin(a), d[1] = sin(e), d[2] = cos(e) * cos(a);
}

static double disk_irradiance(void) { return E_SUN * (1 + cos(RADIUS * M_PI / 180)) / 2; }

static void test_state(void) {
    const char *const yaw[] = {"envmap.yaw=25", NULL};
    sl_harness *h = open_scene(yaw, NULL);
    if (!h) return;
    CHECK(sl_harness_render(h, img_a));
    char text[256];
    double sun[3], dir[3] = {0}, e = 0;
    sun_world(25, sun);
    CHECK(sl_harness_get(h, "light.envmap.sun.enabled", text, sizeof text) && !strcmp(text, "true"));
    CHECK(sl_harness_get(h, "light.envmap.sun.direction", text, sizeof text) &&
          sscanf(text, "%lf,%lf,%lf", &dir[0], &dir[1], &dir[2]) == 3);
    CHECK(sl_harness_get(h, "light.envmap.sun.intensity", text, sizeof text) && sscanf(text, "%lf", &e) == 1);
    double worst = 0;
    for (int i = 0; i < 3; i++) worst = fmax(worst, fabs(dir[i] + sun[i]));
    printf("light envmap.sun: direction (%.5f, %.5f, %.5f), on paper (%.5f, %.5f, %.5f); E %.5f, on paper %.5f\n", dir[0],
           dir[1], dir[2], -sun[0], -sun[1], -sun[2], e, disk_irradiance());
    CHECK_MSG(worst < 1e-5, "the sun light's direction is %.2g off the sky's sun turned by the yaw", worst);
    CHECK_NEAR(e, disk_irradiance(), 1e-4);
    char err[512];
    CHECK(sl_harness_set(h, "envmap.sun_light=false", err, sizeof err));
    CHECK(sl_harness_render(h, img_a));
    CHECK(sl_harness_get(h, "light.envmap.sun.intensity", text, sizeof text) && sscanf(text, "%lf", &e) == 1 && e == 0);
    sl_harness_destroy(h);
}

/* Mean of channel 0 over the floor pixels `pick` selects (hit: the floor point). */
typedef int (*pick_fn)(const float hit[3]);
static double floor_mean(const float *img, pick_fn pick, int *count) {
    const test_camera c = {{0, 8, 5}, {0, 0, 0}, 50, W, H};
    double sum = 0;
    int n = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float hit[3];
            if (!test_camera_hit_ground(&c, x, y, 20, hit) || !pick(hit)) continue;
            sum += img[((size_t)y * W + x) * 4];
            n++;
        }
    *count = n;
    return n ? sum / n : 0;
}

/* The angle between the sun and the ball's centre seen from a floor point, less the ball's
 * angular radius there: < 0 inside its shadow cone (degrees). */
static double shadow_margin(const float p[3]) {
    double sun[3], to[3] = {BALL[0] - p[0], BALL[1] - p[1], BALL[2] - p[2]};
    sun_world(0, sun);
    double d = sqrt(to[0] * to[0] + to[1] * to[1] + to[2] * to[2]);
    double c = (to[0] * sun[0] + to[1] * sun[1] + to[2] * sun[2]) / d;
    return (acos(fmin(1, c)) - asin(BALL_R / d)) * 180 / M_PI;
}
static int in_umbra(const float p[3]) { return shadow_margin(p) < -6; }
static int far_from_ball(const float p[3]) {
    double dx = p[0] - BALL[0], dz = p[2] - BALL[2];
    return shadow_margin(p) > 10 && dx * dx + dz * dz > 9;
}

static void test_energy(void) {
    const char *const off[] = {"envmap.sun_light=false", NULL};
    if (!render_scene(NULL, NULL, img_a) || !render_scene(off, NULL, img_b)) return;
    int n;
    double lit = floor_mean(img_a, far_from_ball, &n), in_sky = floor_mean(img_b, far_from_ball, &n);
    double sun_term = 0.5 / M_PI * disk_irradiance() * sin(ELEVATION * M_PI / 180);
    printf("floor far from the ball (%d px): sun as a light %.4f, the disk in the sky %.4f (ratio %.4f); the sun's "
           "term %.4f\n", n, lit, in_sky, lit / in_sky, sun_term);
    CHECK(n > 1000);
    CHECK_MSG(fabs(lit / in_sky - 1) < 0.03, "the sky without its disk plus the light gives %.4f, the sky with it %.4f",
              lit, in_sky);
    /* the user's switch of the light (light.envmap.sun.enabled, as the panel sets it) holds: the
     * floor keeps the sky without its disk */
    const char *const user_off[] = {"light.envmap.sun.enabled=false", NULL};
    if (!render_scene(user_off, NULL, img_b)) return;
    double dark = floor_mean(img_b, far_from_ball, &n);
    printf("the light switched off by the user: %.4f, the sky without the sun on paper %.4f\n", dark, lit - sun_term);
    CHECK_MSG(fabs(dark - (lit - sun_term)) < 1e-3, "light.envmap.sun.enabled=false gives %.4f, not %.4f", dark,
              lit - sun_term);
}

static void test_shadow(void) {
    const char *const unshadowed[] = {"light.envmap.sun.cast_shadows=false", NULL};
    if (!render_scene(NULL, "spotlight-shadow", img_a) || !render_scene(unshadowed, "spotlight-shadow", img_b)) return;
    int nu, nf;
    double umbra = floor_mean(img_a, in_umbra, &nu) - floor_mean(img_b, in_umbra, &nu);
    double far = floor_mean(img_a, far_from_ball, &nf) - floor_mean(img_b, far_from_ball, &nf);
    double expect = -0.5 / M_PI * disk_irradiance() * sin(ELEVATION * M_PI / 180);
    printf("the ball's umbra (%d px): shadowed minus unshadowed %.5f, on paper %.5f; far from it (%d px) %.5f\n", nu,
           umbra, expect, nf, far);
    CHECK(nu > 50 && nf > 1000);
    CHECK_MSG(fabs(umbra - expect) < 0.005 * fabs(expect), "the umbra lost %.5f, not the sun's %.5f", umbra, expect);
    CHECK_MSG(fabs(far) < 1e-4, "the floor far from the shadow changed by %.5f", far);
}

int main(void) {
    test_state();
    test_energy();
    test_shadow();
    return check_result();
}
