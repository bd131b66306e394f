/* ggx's KHR_materials_dispersion (README "Layers") against the extension's formula, through the
 * render. A smooth transmissive wall (the plane y = 0, IOR 1.5, transmission 1, a volume of
 * thickness τ) over an unlit black floor with a white unlit stripe across the view below it:
 * the scene behind, with edges that are sharp per pixel (geometry, not a filtered texture).
 *
 * The test computes, per wall pixel and colour channel c, the extension's index of refraction
 *   n(λ) = max(n_d + (n_d − 1)/V_d · (523655/λ² − 1.5168), 1),  V_d = 20/dispersion,
 * at λ = 656.27 (red), 587.56 (green, n_d) and 486.13 nm (blue), the ray refracted by Snell's law,
 * r_c = refract(−v, n, 1/n_c), where it leaves the volume, p + τ·r_c, and where that lands on the
 * screen (the camera's projection, cglm). Then:
 *  1. the "ggx-dispersion" view equals, per pixel, the distances (pixels) of the red and blue
 *     landing points from the green one, red and blue on either side of it, blue's the farther
 *     (2.05–2.14 times here; (n_B − n_d)/(n_d − n_R) = 2.3: the Cauchy fit is not symmetric about n_d);
 *  2. the render equals, per pixel and channel, (1 − F(n·v)) × the scene behind at channel c's own
 *     landing point: the bilinear mix of the four pixel centres around it, each black or white as
 *     the camera ray through it meets the floor or the stripe (the capture's level 0). Pixels where
 *     red and blue land on different sides of an edge (the colour fringes) must exist and agree too;
 *  3. dispersion 0, and the layer switched off, render bit for bit the wall without the key.
 * Tolerance for 2: 2·10⁻³ of the stripe's contrast (found 1.7·10⁻⁴; bilinear weights of the
 * capture may be fixed point in a driver); a channel read at another's landing point is off by up to 1. Mutations tried, each caught: red and blue's IORs exchanged (1, 2); the
 * extension's non-normative symmetric split n_d ± (n_d − 1)/(2V_d) (1, 2); blue from the green
 * lookup (2). */
#include "check.h"
#include "camera_rays.h"
#include "ggx_layer_test.h"
#include <shadelab/harness.h>
#include <stdlib.h>
#include <string.h>

#define W 128
#define H 96
static float img[W * H * 4], img2[W * H * 4];
static const test_camera cam = {{0, 3, 4}, {0, 0, 0}, 50, W, H};
static const double ior = 1.5, thickness = 2, dispersion = 5, floor_y = -3, stripe_half = 0.8;

static bool render(const char *keys, const char *const *settings, const char *view, float *out) {
    char json[4096];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"ggx\"], \"environment\": {\"color\": [0, 0, 0]},\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 3, 4], \"target\": [0, 0, 0], \"fov_y\": 50, \"near\": 0.1, \"far\": 100}],\n"
             " \"materials\": [{\"name\": \"wall\", \"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 0,\n"
             "                  \"base_color\": [1, 1, 1], \"roughness\": 0, \"transmission\": 1, \"ior\": %g, \"thickness\": %g%s},\n"
             "                 {\"name\": \"floor\", \"unlit\": true, \"base_color\": [0, 0, 0]},\n"
             "                 {\"name\": \"stripe\", \"unlit\": true, \"base_color\": [1, 1, 1]}],\n"
             " \"nodes\": [{\"name\": \"wall\", \"mesh\": {\"primitive\": \"plane\", \"size\": 10}, \"material\": \"wall\"},\n"
             "           {\"name\": \"floor\", \"translate\": [0, %g, 0], \"mesh\": {\"primitive\": \"plane\", \"size\": 80}, \"material\": \"floor\"},\n"
             "           {\"name\": \"stripe\", \"translate\": [0, %g, 0], \"scale\": [40, 1, %g], \"mesh\": {\"primitive\": \"plane\", \"size\": 1},\n"
             "            \"material\": \"stripe\"}]}",
             ior, thickness, keys, floor_y, floor_y + 0.01, 2 * stripe_half);
    sl_harness *h = ggx_test_harness(json, W, H, settings, view);
    if (!h) return false;
    char what[600];
    snprintf(what, sizeof what, "{%s}", keys);
    bool ok = ggx_test_render(h, W, H, out, what);
    sl_harness_destroy(h);
    return ok;
}

/* The extension's n(λ), λ in nm */
static double cauchy_ior(double lambda) {
    double vd = 20 / dispersion;
    return fmax(ior + (ior - 1) / vd * (523655 / (lambda * lambda) - 1.5168), 1);
}

static mat4 view_proj, inv_view_proj;
static void camera_matrices(void) {
    mat4 view, proj;
    glm_lookat((float *)cam.pos, (float *)cam.target, (vec3){0, 1, 0}, view);
    glm_perspective(glm_rad(cam.fov_deg), (float)W / H, 0.1f, 100.f, proj);
    glm_mat4_mul(proj, view, view_proj);
    glm_mat4_inv(view_proj, inv_view_proj);
}
/* World point → image position in pixels (x right, y down; pixel centres at +0.5). */
static void project(const double p[3], double px[2]) {
    vec4 a = {(float)p[0], (float)p[1], (float)p[2], 1}, c;
    glm_mat4_mulv(view_proj, a, c);
    px[0] = (c[0] / c[3] * 0.5 + 0.5) * W;
    px[1] = (1 - (c[1] / c[3] * 0.5 + 0.5)) * H;
}
/* The scene behind at the centre of pixel (i, j): 1 where its camera ray meets the stripe. */
static double behind_at_pixel(int i, int j) {
    i = i < 0 ? 0 : i >= W ? W - 1 : i, j = j < 0 ? 0 : j >= H ? H - 1 : j; /* clamp to edge */
    float nx = (i + 0.5f) / W * 2 - 1, ny = 1 - (j + 0.5f) / H * 2;
    vec4 a = {nx, ny, -1, 1}, b = {nx, ny, 1, 1}, wa, wb;
    glm_mat4_mulv(inv_view_proj, a, wa);
    glm_mat4_mulv(inv_view_proj, b, wb);
    double o[3], d[3];
    for (int k = 0; k < 3; k++) o[k] = wa[k] / wa[3], d[k] = wb[k] / wb[3] - o[k];
    if (d[1] >= 0) return 0;
    double t = (floor_y + 0.01 - o[1]) / d[1], x = o[0] + t * d[0], z = o[2] + t * d[2];
    return fabs(x) < 20 && fabs(z) < stripe_half ? 1 : 0;
}
/* The capture at image position px (bilinear between pixel centres) */
static double behind_at(const double px[2]) {
    double fx = px[0] - 0.5, fy = px[1] - 0.5;
    int i = (int)floor(fx), j = (int)floor(fy);
    double ax = fx - i, ay = fy - j;
    return (1 - ay) * ((1 - ax) * behind_at_pixel(i, j) + ax * behind_at_pixel(i + 1, j)) +
           ay * ((1 - ax) * behind_at_pixel(i, j + 1) + ax * behind_at_pixel(i + 1, j + 1));
}
/* Where channel c's path (IOR n) from wall point p, view v, lands on the image. */
static void landing(const double p[3], const double v[3], double n, double px[2]) {
    double eta = 1 / n, cosi = v[1], k = 1 - eta * eta * (1 - cosi * cosi), r[3];
    for (int i = 0; i < 3; i++) r[i] = -eta * v[i] + (eta * cosi - sqrt(k)) * (i == 1 ? 1 : 0);
    double len = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]), q[3];
    for (int i = 0; i < 3; i++) q[i] = p[i] + thickness * r[i] / len;
    project(q, px);
}

static bool wall_pixel(int x, int y, double p[3], double v[3]) {
    float hit[3], o[3], d[3];
    if (!test_camera_hit_ground(&cam, x, y, 4.5f, hit)) return false;
    test_camera_ray(&cam, x, y, o, d);
    for (int i = 0; i < 3; i++) p[i] = hit[i], v[i] = -d[i];
    return true;
}

#define DISPERSION_KEYS ", \"dispersion\": 5"
static void test_offsets_and_render(void) {
    const double n[3] = {cauchy_ior(656.27), cauchy_ior(587.56), cauchy_ior(486.13)};
    printf("IORs at the C, d, F lines for dispersion %g: %.5f %.5f %.5f\n", dispersion, n[0], n[1], n[2]);
    CHECK(n[0] < n[1] && n[1] < n[2]);
    if (!render(DISPERSION_KEYS, NULL, "ggx-dispersion", img2) || !render(DISPERSION_KEYS, NULL, NULL, img)) return;
    double worst_view = 0, worst = 0, ratio_lo = 1e9, ratio_hi = 0;
    int checked = 0, fringes = 0, order_bad = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double p[3], v[3], land[3][2];
            if (!wall_pixel(x, y, p, v)) continue;
            for (int c = 0; c < 3; c++) landing(p, v, n[c], land[c]);
            double dr = hypot(land[0][0] - land[1][0], land[0][1] - land[1][1]);
            double db = hypot(land[2][0] - land[1][0], land[2][1] - land[1][1]);
            /* the order along the line: red and blue on opposite sides of green */
            double dot = (land[0][0] - land[1][0]) * (land[2][0] - land[1][0]) + (land[0][1] - land[1][1]) * (land[2][1] - land[1][1]);
            order_bad += dot >= 0 || db <= dr;
            if (dr > 0.05) ratio_lo = fmin(ratio_lo, db / dr), ratio_hi = fmax(ratio_hi, db / dr);
            const float *vw = img2 + (y * W + x) * 4;
            worst_view = fmax(worst_view, fmax(fabs(vw[0] - dr), fabs(vw[2] - db)));
            double keep = 1 - (0.04 + 0.96 * pow(1 - v[1], 5)), want[3];
            for (int c = 0; c < 3; c++) {
                want[c] = keep * behind_at(land[c]);
                worst = fmax(worst, fabs(img[(y * W + x) * 4 + c] - want[c]));
            }
            fringes += fabs(want[0] - want[2]) > 0.5 * keep;
            checked++;
        }
    printf("%d wall pixels: the ggx-dispersion view against the closed form, worst %.2e px; blue's offset / red's "
           "%.2f..%.2f; %d fringe pixels (red and blue across an edge); render worst absolute error %.2e\n",
           checked, worst_view, ratio_lo, ratio_hi, fringes, worst);
    CHECK(checked > 4000);
    CHECK_MSG(order_bad == 0, "%d pixels: red, green, blue not in order along the line", order_bad);
    CHECK_MSG(worst_view < 1e-2, "ggx-dispersion view: worst %.2e px", worst_view);
    CHECK_MSG(fringes > 100, "the colours must separate at the stripe's edges (%d pixels)", fringes);
    CHECK_MSG(worst < 2e-3, "render: worst absolute error %.2e", worst);
}

static void test_no_dispersion_is_exact(void) {
    if (!render("", NULL, NULL, img)) return;
    const char *off[] = {"ggx.layer_dispersion=false", NULL};
    const struct { const char *keys; const char *const *settings; const char *what; } cases[] = {
        {", \"dispersion\": 0", NULL, "dispersion 0"},
        {DISPERSION_KEYS, off, "ggx.layer_dispersion=false"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        if (!render(cases[k].keys, cases[k].settings, NULL, img2)) continue;
        int differ = 0;
        for (int i = 0; i < W * H * 4; i++) differ += img[i] != img2[i];
        printf("%s: %d channel values differ from the wall without the key\n", cases[k].what, differ);
        CHECK_MSG(differ == 0, "%s must render exactly plain transmission (%d values differ)", cases[k].what, differ);
    }
}

int main(void) {
    camera_matrices();
    test_offsets_and_render();
    test_no_dispersion_is_exact();
    return check_result();
}
