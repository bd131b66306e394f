/* ggx end to end: a plane under a directional light against the BRDF evaluated per pixel in C
 * from the camera rays; world vs camera space; zero-specular equals Lambert; stability renders;
 * a Lambert material's program is untouched by loading ggx. */
#include "check.h"
#include "camera_rays.h"
#include "disk_highlight.h"
#include "view_guard.h"
#include <shadelab/harness.h>
#include <stdlib.h>

#define W 96
#define H 72
static float img[W * H * 4], img2[W * H * 4];
static const test_camera cam = {{0, 3, 4}, {0, 0, 0}, 50, W, H};

#define SCENE(MODEL_KEYS, LIGHTS) \
    "{\"plugins\": [\"ggx\"],\n" \
    " \"cameras\": [{\"name\": \"c\", \"position\": [0, 3, 4], \"target\": [0, 0, 0], \"fov_y\": 50, \"near\": 0.1, \"far\": 100}],\n" \
    " \"materials\": [{\"name\": \"m\", \"base_color\": [0.4, 0.3, 0.2], " MODEL_KEYS "}],\n" \
    " \"nodes\": [{\"name\": \"floor\", \"mesh\": {\"primitive\": \"plane\", \"size\": 20}, \"material\": \"m\"}],\n" \
    " \"lights\": [" LIGHTS "]}"

static const char *sun = "{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0.1, -0.6, 0.8], \"intensity\": 3}";

/* `plugins`: loaded besides the scene's own list (NULL: none). */
static sl_harness *make_with(const char *json, const char *const *plugins, const char *const *settings) {
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                          .scene_json = json, .plugins = plugins, .settings = settings,
                                                          .float32 = true, .strict = true},
                                      err, sizeof err);
    if (!h) fprintf(stderr, "harness: %s\n", err);
    return h;
}
static sl_harness *make(const char *json, const char *const *settings) { return make_with(json, NULL, settings); }

static double fresnel_exact(double c, double eta) {
    double b2 = 1 / (eta * eta) + c * c - 1;
    if (b2 < 0) return 1;
    double b = sqrt(b2), rs = (c - b) / (c + b), rp = (eta * eta * b - c) / (eta * eta * b + c);
    return 0.5 * (rs * rs + rp * rp);
}

static double g1(double xn, double xh, double a) {
    if (xn == 0 || xh / xn <= 0) return 0;
    return 2 / (1 + sqrt(1 + a * a * (1 - xn * xn) / (xn * xn)));
}

static void normalize3(double v[3]) {
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++) v[i] /= l;
}

/* The closed form of one channel under a directional light of irradiance E from l, shading
 * normal n: L = (k_d/π + k_s F D G/(4 n·l n·v)) E n·l; *spec gets the specular part. */
static double ggx_closed(const double n[3], const double v[3], const double l[3], double kd, double ks, double a, double eta,
                         double E, double *spec) {
    double hh[3] = {l[0] + v[0], l[1] + v[1], l[2] + v[2]};
    normalize3(hh);
    double nl = vg_dot(n, l), nv = vg_dot(n, v), nh = vg_dot(n, hh), lh = vg_dot(l, hh), vh = vg_dot(v, hh);
    double t2 = (1 - nh * nh) / (nh * nh);
    double D = nh > 0 ? a * a / (M_PI * pow(nh, 4) * pow(a * a + t2, 2)) : 0;
    double fs = fresnel_exact(lh, eta) * D * g1(nv, vh, a) * g1(nl, lh, a) / (4 * nl * nv);
    *spec = ks * fs * E * nl;
    return (kd / M_PI + ks * fs) * E * nl;
}

/* Specular AA on a 40 m bumpy GGX plane (α = 0.05, the bumps32 normal map) seen from (0, cam_y, 19):
 * renders AA on, AA off and the 8×8 supersampled reference (no AA, normal map at level 0, no
 * anisotropic taps) at
 * 160×90 and returns the far-field means m = {on, off, ref} of the green channel and the RMSEs
 * against the reference. Far field: hit points farther than min_dist from the camera, or, with
 * min_dist = 0, the rows 0.37–0.6 H (between the horizon and mid-screen in the first view). */
static bool aa_case(float cam_y, const float sun_dir[3], float min_dist, double m[3], double *e_on, double *e_off) {
    enum { AW = 160, AH = 90 };
    static float on[AW * AH * 4], off[AW * AH * 4], ref[AW * AH * 4];
    char json[2048], err[4096];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"ggx\", \"normal-map\"],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, %g, 19], \"target\": [0, 0, 0], \"fov_y\": 40}],\n"
             " \"materials\": [{\"name\": \"bumpy\", \"model\": \"ggx\", \"alpha\": 0.05, \"base_color\": [0.18, 0.2, 0.24],\n"
             "   \"normal_map\": \"%s/../plugins/phong/assets/bumps32_tangent.png\"}],\n"
             " \"nodes\": [{\"name\": \"p\", \"mesh\": {\"primitive\": \"plane\", \"size\": 40}, \"material\": \"bumpy\"}],\n"
             " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [%g, %g, %g], \"intensity\": 4}]}",
             cam_y, SL_SCENES_DIR, sun_dir[0], sun_dir[1], sun_dir[2]);
    /* on and off filter the map as a GPU does by default (anisotropy 8): with a CPU renderer's
     * default of 1 the mip is chosen by the footprint's long axis and blurs the map across it too,
     * and in the known failure case (6 m, side sun) AA's RMSE is 0.312 against 0.306 off. */
    const char *const *sets[3] = {(const char *[]){"ggx.specular_aa=true", "core.anisotropy=8", NULL},
                                  (const char *[]){"ggx.specular_aa=false", "core.anisotropy=8", NULL},
                                  (const char *[]){"ggx.specular_aa=false", "core.ssaa=8", "core.anisotropy=1", "normal-map.lod_bias=-16", NULL}};
    float *outs[3] = {on, off, ref};
    for (int k = 0; k < 3; k++) {
        sl_harness *hh = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = AW,
                                                               .height = AH, .scene_json = json, .settings = sets[k],
                                                               .float32 = true, .strict = true}, err, sizeof err);
        if (!hh) { fprintf(stderr, "harness: %s\n", err); return false; }
        bool ok = sl_harness_render(hh, outs[k]) && sl_harness_count_nonfinite(outs[k], AW, AH) == 0;
        sl_harness_destroy(hh);
        if (!ok) { fprintf(stderr, "specular AA render %d failed or not finite\n", k); return false; }
    }
    const test_camera c = {{0, cam_y, 19}, {0, 0, 0}, 40, AW, AH};
    double s[3] = {0, 0, 0}, eon = 0, eoff = 0;
    int cnt = 0;
    for (int y = 0; y < AH; y++)
        for (int x = 0; x < AW; x++) {
            if (min_dist > 0) {
                float p[3];
                if (!test_camera_hit_ground(&c, x, y, 20, p)) continue;
                float dx = p[0], dy = p[1] - cam_y, dz = p[2] - 19;
                if (sqrtf(dx * dx + dy * dy + dz * dz) <= min_dist) continue;
            } else if (y < (int)(0.37 * AH) || y >= (int)(0.6 * AH)) continue;
            int i = (y * AW + x) * 4 + 1;
            for (int k = 0; k < 3; k++) s[k] += outs[k][i];
            eon += (on[i] - ref[i]) * (on[i] - ref[i]);
            eoff += (off[i] - ref[i]) * (off[i] - ref[i]);
            cnt++;
        }
    if (cnt == 0) return false;
    for (int k = 0; k < 3; k++) m[k] = s[k] / cnt;
    *e_on = sqrt(eon / cnt), *e_off = sqrt(eoff / cnt);
    return true;
}

/* A light's disk in a polished sphere (the core's angular_radius, sl_light_spread): a white metal
 * sphere (radius R = 1) lit along the view by a directional light (E = 3) of angular radius r,
 * seen from 40 m (nearly parallel rays), aa off. On paper a mirror sphere shows the disk where the
 * normal is within r/2 of the view (the reflected ray within r of the light): a spot of radius
 * R sin(r/2). Polished (roughness 0.05, α = 0.0025) and zoomed on the spot (fov 0.4°), r = 3° and
 * 6°: the half-maximum spot's radius is R sin(r/2), 0.026 and 0.052 (9 and 18 px), where the lobe
 * of a delta light is 0.6436 α R = 0.0016. The disk keeps the energy: on a rougher sphere
 * (roughness 0.3), the whole sphere in view, r = 3° changes the highlight's flux Σ L·(pixel area)
 * by less than 1 % from r = 0. */
static const char *metal_keys(double roughness) {
    static char keys[256];
    snprintf(keys, sizeof keys, "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 1, "
             "\"base_color\": [1, 1, 1], \"roughness\": %g", roughness);
    return keys;
}

static void test_disk_highlight(void) {
    sl_test_disk_radius("ggx", "polished sphere", metal_keys(0.05), 3, 0.4);
    sl_test_disk_radius("ggx", "polished sphere", metal_keys(0.05), 6, 0.4);
    sl_test_disk_flux("ggx", "roughness 0.3", metal_keys(0.3), 3, 3.2);
}

/* The disk's image, pixel by pixel: a white metal plane (F = 1) lit by a directional light (E = 3)
 * of angular radius 6°, placed so that the camera sees its mirror image (θ_d = 53°), 64×64 px at
 * 24° (0.38° a pixel), aa off. Per pixel the radiance on paper: the disk of uniform radiance
 * E/(π sin²r) integrated against the point-light BRDF D G/(4 n·l n·v) (n·l) over 24×96 directions
 * (uniform in solid angle), with GGX's D and G written here. Roughness 0.1 (α = 0.01, the disk's
 * ρ = r/2 five times wider: a flat image with a sharp edge), 0.2 and 0.3 (α = 0.04, 0.09: lobe and
 * disk alike): the flux in view within 2 % of the integral's and the per-pixel error, RMS over the
 * pixels above 1 % of the peak, within 8 % of the peak (measured 0.030 / 0.029 / 0.025, flux 0.998 /
 * 0.988 / 0.992). A GGX lobe widened to the disk's half maximum instead (ggx_disk_alpha, its long
 * tails outside the image) fails both: 0.215 / 0.112 / 0.051, flux 0.78 / 0.83 / 0.93. */
static void test_disk_profile(double roughness, double *rms, double *flux_ratio) {
    enum { PW = 64, PH = 64, NT = 24, NP = 96 };
    static float pimg[PW * PH * 4];
    const double r = 6 * M_PI / 180, E = 3, a = roughness * roughness;
    const double to_light[3] = {0, 0.6, -0.8};
    char json[2048], err[4096];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"ggx\"],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 3, 4], \"target\": [0, 0, 0], \"fov_y\": 24}],\n"
             " \"materials\": [{\"name\": \"m\", %s}],\n"
             " \"nodes\": [{\"name\": \"p\", \"mesh\": {\"primitive\": \"plane\", \"size\": 20}, \"material\": \"m\"}],\n"
             " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -0.6, 0.8], \"intensity\": 3,"
             " \"angular_radius\": 6}]}", metal_keys(roughness));
    const char *const settings[] = {"aa.enabled=false", NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = PW, .height = PH,
                                                          .scene_json = json, .settings = settings, .float32 = true,
                                                          .strict = true}, err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    *rms = *flux_ratio = 1e9;
    if (!h) return;
    CHECK(sl_harness_render(h, pimg));
    sl_harness_destroy(h);
    /* an orthonormal frame about the disk's centre, for its directions */
    double e1[3] = {1, 0, 0}, e2[3] = {0, 0.8, 0.6}, Ls = E / (M_PI * sin(r) * sin(r));
    static double expect[PW * PH];
    const test_camera c = {{0, 3, 4}, {0, 0, 0}, 24, PW, PH};
    double peak = 0;
    for (int y = 0; y < PH; y++)
        for (int x = 0; x < PW; x++) {
            float p[3], o[3], d[3];
            expect[y * PW + x] = -1;
            if (!test_camera_hit_ground(&c, x, y, 9.5f, p)) continue;
            test_camera_ray(&c, x, y, o, d);
            double v[3] = {-d[0], -d[1], -d[2]}, sum = 0;
            for (int i = 0; i < NT; i++)
                for (int j = 0; j < NP; j++) {
                    double ct = 1 - (1 - cos(r)) * (i + 0.5) / NT, st = sqrt(1 - ct * ct), ph = 2 * M_PI * (j + 0.5) / NP;
                    double l[3], hh[3];
                    for (int k = 0; k < 3; k++) l[k] = ct * to_light[k] + st * (cos(ph) * e1[k] + sin(ph) * e2[k]);
                    for (int k = 0; k < 3; k++) hh[k] = l[k] + v[k];
                    normalize3(hh);
                    double nl = l[1], nv = v[1], nh = hh[1], lh = l[0] * hh[0] + l[1] * hh[1] + l[2] * hh[2];
                    if (nl <= 0 || nv <= 0) continue;
                    double t2 = (1 - nh * nh) / (nh * nh), D = a * a / (M_PI * pow(nh, 4) * pow(a * a + t2, 2));
                    sum += D * g1(nv, lh, a) * g1(nl, lh, a) / (4 * nl * nv) * nl;
                }
            double Lo = Ls * 2 * M_PI * (1 - cos(r)) * sum / (NT * NP);
            expect[y * PW + x] = Lo;
            peak = fmax(peak, Lo);
        }
    double se = 0, fs = 0, fe = 0;
    int n = 0;
    for (int i = 0; i < PW * PH; i++) {
        if (expect[i] < 0) continue;
        fs += pimg[i * 4], fe += expect[i];
        if (expect[i] < 0.01 * peak && pimg[i * 4] < 0.01 * peak) continue;
        se += (pimg[i * 4] - expect[i]) * (pimg[i * 4] - expect[i]);
        n++;
    }
    *rms = sqrt(se / fmax(n, 1)) / peak;
    *flux_ratio = fs / fe;
    printf("disk image, roughness %g: %d pixels, peak %.2f on paper, RMS error %.4f of it, flux ratio %.4f\n", roughness, n,
           peak, *rms, *flux_ratio);
    CHECK_MSG(n > 100, "the highlight covers only %d pixels", n);
    CHECK_MSG(*rms < 0.08, "roughness %g: the disk's image is %.3f of its peak off", roughness, *rms);
    CHECK_MSG(fabs(*flux_ratio - 1) < 0.02, "roughness %g: the image's flux is %.4f of the integral", roughness, *flux_ratio);
}

/* A glint smaller than a pixel keeps its energy (the pixel's footprint of normals,
 * sl_normal_footprint): the polished sphere of sl_test_disk_highlight under a 0.5° disk, its spot
 * 0.0044 in radius, resolved at a field of view of 0.4° (1.5 pixels, aa off) and seen whole at 40°
 * (a 6.6-pixel sphere, the spot 0.015 pixels) in aa's 16-frame still, at five positions across a
 * pixel (its centre, an edge, a corner, two between): the flux Σ L·(pixel area) of each within
 * 10 % of the resolved one (measured 0.91–1.05). Point samples of D (no footprint): 58.7 / 0.04 /
 * 0.007 / 0.007 / 0.31 of it. One frame of the footprint alone finds no glint at a pixel's
 * corner (outside the four pixels' disks of their area) and twice it on an edge: TAA's jitter,
 * moving the footprint over the pixel, is what makes it a partition of unity. */
static void test_subpixel_glint_of(double disk_deg, double roughness) {
    double near_flux, r;
    sl_test_disk_highlight("ggx", metal_keys(roughness), disk_deg, 0.4, &near_flux, &r);
    const double px = 2 * 40 * tan(20 * M_PI / 180) / 96; /* a pixel at 40°, in m at the sphere */
    const double at[5][2] = {{0.5, 0.5}, {0.5, 0}, {0, 0}, {0.3, 0.1}, {0.15, 0.4}}; /* from a corner */
    const char *const still[] = {"aa.enabled=true", NULL};
    for (int i = 0; i < 5; i++) {
        double far_flux;
        sl_test_disk_highlight_at("ggx", metal_keys(roughness), disk_deg, 40, still, 16, at[i][0] * px, at[i][1] * px,
                                  &far_flux, &r);
        printf("glint of a %g deg disk, roughness %g, at (%.2f, %.2f) of a pixel: flux %.6f, resolved %.6f (ratio %.4f)\n",
               disk_deg, roughness, at[i][0], at[i][1], far_flux, near_flux, far_flux / near_flux);
        CHECK_MSG(near_flux > 0 && fabs(far_flux / near_flux - 1) < 0.1,
                  "a sub-pixel glint (disk %g deg) at (%.2f, %.2f) of a pixel has %.4f of its flux", disk_deg, at[i][0],
                  at[i][1], far_flux / near_flux);
    }
}
/* The same for a light without a disk (angular_radius 0, a point at infinity: the light loop's
 * point and spot lights alike, ABI 1.25): roughness 0.1, its spot about 0.01 in radius, 3 pixels
 * at 0.4° and 0.03 of a pixel at 40°, filtered over the footprint alone (measured 0.94–1.07; point
 * samples of D, as before 1.25: 15.7 / 0.47 / 0.099 / 0.098 / 2.08). */
static void test_subpixel_glint(void) {
    test_subpixel_glint_of(0.5, 0.05);
    test_subpixel_glint_of(0, 0.1);
}

/* A glint about a pixel wide, the default scene's gold (roughness 0.18, α = 0.032) under its
 * 1.5° sun, its lobe half a pixel across (8.9° over 96 pixels at 40 m): a TAA still of 4 frames
 * (the default scene's) against the pixel's box filter of it, 8×8 supersampled without aa (what
 * a path tracer's 1-pixel box gives), at four positions across a pixel. Pixels above 1 % of the
 * peak: relative RMS and flux. With the footprint's disk where the jitter put it in every frame
 * (before ABI 1.28) the still was that disk moved over the pixel, two pixels wide: 0.12–0.21;
 * centred by ggx_footprint_normal: 0.025–0.054, flux 1.002–1.017; with aa's jitter averaging to
 * the pixel's centre too: 0.010–0.036, flux 1.002–1.017. */
#define GLINT_FOV 8.9
static void render_glint(const char *const *settings, int frames, double dx, float *px, int w) {
    char json[2048];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"ggx\"],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 40], \"target\": [0, 0, 0], \"fov_y\": %g}],\n"
             " \"materials\": [{\"name\": \"m\", %s}],\n"
             " \"nodes\": [{\"name\": \"s\", \"translate\": [%g, %g, 0],"
             "   \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1, \"segments\": 256, \"rings\": 128},"
             "   \"material\": \"m\"}],\n"
             " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0.2, -0.15, -1], \"intensity\": 3,"
             "   \"angular_radius\": 1.5}]}", GLINT_FOV, metal_keys(0.18), dx, 0.6 * dx);
    sl_test_render_frames(json, settings, w, w, frames, px);
}
static void test_pixel_wide_glint(void) {
    enum { GW = 96 };
    static float still[GW * GW * 4], box[GW * GW * 4];
    const double pixel = 2 * 40 * tan(GLINT_FOV / 2 * M_PI / 180) / GW;
    for (int i = 0; i < 4; i++) {
        double at = 0.25 * i * pixel; /* moved by (at, 0.6 at) m */
        render_glint((const char *[]){"aa.enabled=true", "aa.taa_frames=4", NULL}, 4, at, still, GW);
        render_glint((const char *[]){"aa.enabled=false", "core.ssaa=8", NULL}, 1, at, box, GW);
        double peak = 0, se = 0, s2 = 0, fs = 0, fb = 0;
        for (int k = 0; k < GW * GW; k++) peak = fmax(peak, box[k * 4]);
        for (int k = 0; k < GW * GW; k++) {
            if (box[k * 4] < 0.01 * peak && still[k * 4] < 0.01 * peak) continue;
            double d = still[k * 4] - box[k * 4];
            se += d * d, s2 += (double)box[k * 4] * box[k * 4], fs += still[k * 4], fb += box[k * 4];
        }
        double rel = sqrt(se / fmax(s2, 1e-30));
        printf("glint half a pixel wide, moved %.2f pixel: 4-frame still against the box filter: relative RMS %.4f, "
               "flux ratio %.4f (peak %.2f)\n", at / pixel, rel, fs / fb, peak);
        CHECK_MSG(peak > 1, "no glint in view (peak %.3f)", peak);
        CHECK_MSG(rel < 0.08, "the still's glint is %.3f (relative RMS) from the pixel's box filter", rel);
        CHECK_MSG(fabs(fs / fb - 1) < 0.03, "the still's glint has %.4f of the box filter's flux", fs / fb);
    }
}

/* Specular AA in a TAA still (SDK 1.30 sl_texture_lod_bias): only the still's first frame, at the
 * pixel's own footprint, widens the lobe; its jittered frames read the normal map at their share
 * of the pixel (aa's taa_lod_bias) and resolve the bumps themselves. So, per pixel, the 16-frame
 * still with AA less the still without it is 1/16 of the same difference in a single frame (aa
 * off). Widened in every frame (before 1.30) it was about the whole difference. */
static void test_specular_aa_still(void) {
    enum { SW = 96, SH = 54, N = 16 };
    static float still_on[SW * SH * 4], still_off[SW * SH * 4], one_on[SW * SH * 4], one_off[SW * SH * 4];
    char json[2048];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"ggx\", \"normal-map\"],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 1.2, 19], \"target\": [0, 0, 0], \"fov_y\": 40}],\n"
             " \"materials\": [{\"name\": \"bumpy\", \"model\": \"ggx\", \"alpha\": 0.05, \"base_color\": [0.18, 0.2, 0.24],\n"
             "   \"normal_map\": \"%s/../plugins/phong/assets/bumps32_tangent.png\"}],\n"
             " \"nodes\": [{\"name\": \"p\", \"mesh\": {\"primitive\": \"plane\", \"size\": 40}, \"material\": \"bumpy\"}],\n"
             " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -0.6, 0.8], \"intensity\": 4}]}",
             SL_SCENES_DIR);
    bool ok = sl_test_render_frames(json, (const char *[]){"ggx.specular_aa=true", "aa.taa_frames=16", NULL}, SW, SH, N, still_on) &&
              sl_test_render_frames(json, (const char *[]){"ggx.specular_aa=false", "aa.taa_frames=16", NULL}, SW, SH, N, still_off) &&
              sl_test_render_frames(json, (const char *[]){"ggx.specular_aa=true", "aa.enabled=false", NULL}, SW, SH, 1, one_on) &&
              sl_test_render_frames(json, (const char *[]){"ggx.specular_aa=false", "aa.enabled=false", NULL}, SW, SH, 1, one_off);
    if (!ok) return;
    double se = 0, s1 = 0;
    for (int k = 0; k < SW * SH; k++)
        for (int c = 0; c < 3; c++) {
            double d1 = one_on[k * 4 + c] - one_off[k * 4 + c], ds = still_on[k * 4 + c] - still_off[k * 4 + c];
            se += (N * ds - d1) * (N * ds - d1), s1 += d1 * d1;
        }
    double rel = sqrt(se / fmax(s1, 1e-30)); /* widening every frame: 5.72 */
    printf("specular AA in a 16-frame still: 16 x (still on - off) against one frame's on - off: relative RMS %.4f "
           "(one frame's RMS difference %.4f)\n", rel, sqrt(s1 / (3.0 * SW * SH)));
    CHECK_MSG(s1 > 1e-4 * SW * SH, "specular AA changes nothing in a single frame (%.3g)", s1);
    CHECK_MSG(rel < 0.05, "the still's difference is not the first frame's share: relative RMS %.4f", rel);
}

int main(void) {
    /* 1. per-pixel closed form: L = (k_d/π + k_s F D G/(4 n·l n·v)) E n·l */
    char json[4096];
    snprintf(json, sizeof json, SCENE("\"model\": \"ggx\", \"alpha\": 0.25, \"specular\": 0.8, \"eta\": 0.6667", "%s"), sun);
    sl_harness *h = make(json, NULL);
    CHECK(h != NULL);
    if (!h) return check_result();
    CHECK(sl_harness_render(h, img));
    double ld[3] = {-0.1, 0.6, -0.8};
    normalize3(ld);
    const double kd[3] = {0.4, 0.3, 0.2}, a = 0.25, ks = 0.8, eta = 0.6667, E = 3;
    double worst = 0, peak = 0;
    int checked = 0;
    for (int y = 0; y < H; y += 3)
        for (int x = 0; x < W; x += 3) {
            float p[3], o[3], d[3];
            if (!test_camera_hit_ground(&cam, x, y, 9.5f, p)) continue;
            test_camera_ray(&cam, x, y, o, d);
            double v[3] = {-d[0], -d[1], -d[2]}, n[3] = {0, 1, 0}, spec;
            for (int c = 0; c < 3; c++) {
                double expect = ggx_closed(n, v, ld, kd[c], ks, a, eta, E, &spec);
                double rel = fabs(img[(y * W + x) * 4 + c] - expect) / expect;
                if (rel > worst) worst = rel;
                if (spec > peak) peak = spec;
            }
            checked++;
        }
    printf("ggx plane: %d pixels, worst relative error %.2e, peak specular radiance %.3f\n", checked, worst, peak);
    CHECK_MSG(worst < 5e-3, "worst relative error %.5f", worst);
    CHECK(checked > 100);
    /* the highlight is in view, so a wrong specular term could not pass */
    CHECK_MSG(peak > 0.2, "no visible highlight (specular peak %.3f)", peak);

    /* 2. lighting in camera space agrees with world space to 1e-4 */
    sl_harness_destroy(h);
    h = make(json, (const char *[]){"ggx.space=camera", NULL});
    CHECK(h && sl_harness_render(h, img2));
    sl_compare cmp;
    sl_harness_compare(img, img2, W, H, 1e-4, &cmp);
    printf("world vs camera space: max difference %.2e\n", cmp.max_abs);
    CHECK_MSG(cmp.max_abs < 1e-4, "world and camera space differ by %g", cmp.max_abs);
    sl_harness_destroy(h);

    /* 3. zero specular is exactly the Lambert image */
    h = make(json, (const char *[]){"ggx.zero_specular=true", NULL});
    CHECK(h && sl_harness_render(h, img));
    sl_harness_destroy(h);
    snprintf(json, sizeof json, SCENE("\"model\": \"lambert\"", "%s"), sun);
    h = make(json, NULL);
    CHECK(h && sl_harness_render(h, img2));
    sl_harness_compare(img, img2, W, H, 1e-6, &cmp);
    CHECK_MSG(cmp.max_abs < 1e-6, "zero-specular differs from Lambert by %g", cmp.max_abs);
    sl_harness_structure lambert_with_ggx;
    sl_harness_structure_of(h, &lambert_with_ggx);
    sl_harness_destroy(h);
    /* a Lambert material's program does not change when ggx is loaded */
    char err[2048];
    char *plain = strdup(json);
    char *pl = strstr(plain, "\"plugins\": [\"ggx\"],");
    memcpy(pl, "                   ", 19);
    h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                             .scene_json = plain, .float32 = true}, err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (h) {
        sl_harness_structure none;
        CHECK(sl_harness_render(h, NULL));
        sl_harness_structure_of(h, &none);
        CHECK(none.program_hashes[0] == lambert_with_ggx.program_hashes[0]);
        sl_harness_destroy(h);
    }
    free(plain);

    /* 4. debug view F at the plane: F(l·h) per pixel; 0 where the light is below the horizon */
    snprintf(json, sizeof json, SCENE("\"model\": \"ggx\", \"alpha\": 0.25, \"eta\": 0.6667", "%s"), sun);
    h = make(json, NULL);
    CHECK(h && sl_harness_set_debug_view(h, "ggx-f", err, sizeof err));
    CHECK(h && sl_harness_render(h, img));
    worst = 0;
    for (int y = 0; y < H; y += 5)
        for (int x = 0; x < W; x += 5) {
            float p[3], o[3], d[3];
            if (!test_camera_hit_ground(&cam, x, y, 9.5f, p)) continue;
            test_camera_ray(&cam, x, y, o, d);
            double v[3] = {-d[0], -d[1], -d[2]}, hh[3] = {ld[0] + v[0], ld[1] + v[1], ld[2] + v[2]};
            normalize3(hh);
            double lh = ld[0] * hh[0] + ld[1] * hh[1] + ld[2] * hh[2];
            double e = fresnel_exact(lh, 0.6667);
            if (fabs(img[(y * W + x) * 4] - e) > worst) worst = fabs(img[(y * W + x) * 4] - e);
        }
    CHECK_MSG(worst < 1e-4, "F view differs by %g", worst);
    sl_harness_destroy(h);

    /* 5. stability: roughness 0 and 1, light grazing and behind; no NaN/Inf/negative, lit where expected */
    const char *stab =
        "{\"plugins\": [\"ggx\"],\n"
        " \"cameras\": [{\"name\": \"c\", \"position\": [0, 1.2, 6], \"target\": [0, 0.8, 0], \"fov_y\": 45}],\n"
        " \"materials\": [{\"name\": \"smooth\", \"model\": \"ggx\", \"roughness\": 0, \"base_color\": [0.5, 0.5, 0.5]},\n"
        "                 {\"name\": \"rough\", \"model\": \"ggx\", \"roughness\": 1, \"base_color\": [0.5, 0.5, 0.5]},\n"
        "                 {\"name\": \"floor\", \"model\": \"ggx\", \"alpha\": 0.3}],\n"
        " \"nodes\": [{\"name\": \"a\", \"translate\": [-1.1, 0.8, 0], \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"smooth\"},\n"
        "           {\"name\": \"b\", \"translate\": [1.1, 0.8, 0], \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"rough\"},\n"
        "           {\"name\": \"f\", \"mesh\": {\"primitive\": \"plane\", \"size\": 10}, \"material\": \"floor\"}],\n"
        " \"lights\": [{\"name\": \"grazing\", \"type\": \"directional\", \"direction\": [-1, -0.0005, 0], \"intensity\": 50},\n"
        "            {\"name\": \"behind\", \"type\": \"directional\", \"direction\": [0, 0.2, 1], \"intensity\": 5},\n"
        "            {\"name\": \"key\", \"type\": \"point\", \"position\": [0, 3, 3], \"intensity\": 20}]}";
    h = make(stab, NULL);
    CHECK(h && sl_harness_render(h, img));
    CHECK_MSG(sl_harness_count_nonfinite(img, W, H) == 0, "NaN/Inf in the stability render");
    CHECK_MSG(sl_harness_count_negative(img, W, H) == 0, "negative radiance");
    double maxv = 0;
    for (int i = 0; i < W * H * 4; i++) if (img[i] > maxv) maxv = img[i];
    printf("stability render: max radiance %.2f\n", maxv);
    CHECK(maxv > 0.5);
    sl_harness_destroy(h);
    /* 6. specular antialiasing: a bumpy GGX plane at grazing angles against an 8×8 supersampled
     * render without AA (normal map at level 0) */
    {
        double m[3], e_on, e_off;
        CHECK(aa_case(1.2f, (const float[3]){0, -0.25f, 0.968f}, 0, m, &e_on, &e_off));
        printf("ggx specular AA, far field: mean AA on %.4f, off %.4f, reference %.4f; RMSE on %.4f, off %.4f\n", m[0], m[1],
               m[2], e_on, e_off);
        /* Toksvig removes most of the aliasing: RMSE against the supersampled render 3× lower.
         * The far-field mean is printed, not asserted, in this view: it is the grid's first row,
         * where the reference's glint is carried by normals bent back to a valid reflection (see
         * section 7). */
        CHECK_MSG(e_on < 0.6 * e_off, "AA does not reduce the far-field error enough (%.3f vs %.3f)", e_on, e_off);
    }
    /* 7. the same plane over a grid of grazing views and suns (far field: hit points more than
     * 25 m from the camera), for the README's table: antialiasing must lower the RMSE against the
     * reference in every configuration, and bring the mean closer in every configuration but
     * three, the known failures of a one-variance lobe on this map (README): with the side sun at
     * 6 m the reference needs the map's actual slopes, which come in two rings (tan θ 0.30–0.40
     * and 0.60–0.70), where Toksvig's Gaussian puts light on flatter normals the map does not
     * have; with the low sun ahead at 1.2 and 3 m, half the reference's glint comes from normals
     * that lean away from the camera and are bent back until their reflection rises just above
     * the horizon (normal-map's guard, Cycles' convention), a spike of normals the lobe about
     * the mean normal does not have (AA on: 0.63 and 0.62, as with masking).
     * There the mean is printed, not asserted. */
    {
        static const float heights[3] = {1.2f, 3.0f, 6.0f};
        static const float suns[3][3] = {{0, -0.25f, 0.968f}, {0, -0.6f, 0.8f}, {0.5f, -0.5f, 0.7071f}};
        int better = 0;
        printf("ggx specular AA grid (alpha 0.05): camera height, sun direction: far-field mean reference / off / on\n");
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                double m[3], e_on, e_off;
                CHECK(aa_case(heights[i], suns[j], 25, m, &e_on, &e_off));
                bool ok = fabs(m[0] - m[2]) < fabs(m[1] - m[2]);
                better += ok;
                bool known_failure = (i == 2 && j == 2) || (i < 2 && j == 0);
                CHECK_MSG(ok || known_failure, "camera %.1f m, sun %d: AA mean %.3f is not closer to the reference %.3f than off %.3f",
                          heights[i], j, m[0], m[2], m[1]);
                CHECK_MSG(e_on < e_off, "camera %.1f m, sun %d: AA raises the RMSE (%.3f vs %.3f)", heights[i], j, e_on, e_off);
                printf("  %.1f m, (%.2f, %.2f, %.2f): %.3f / %.3f / %.3f  |on - ref| %s |off - ref|; RMSE on %.3f, off %.3f\n",
                       heights[i], suns[j][0], suns[j][1], suns[j][2], m[2], m[1], m[0], ok ? "<" : ">=", e_on, e_off);
            }
        printf("ggx specular AA grid: the AA mean is closer to the reference in %d of 9 configurations\n", better);
    }
    /* 8. mapped normals whose reflection falls below the plane: normal-map tilts them back as
     * Cycles' Normal Map node does (sl_valid_reflection), for ggx as for every model. A constant
     * map leans every normal 20° away from the camera: n = (0, cos 20°, −sin 20°) (T = +X, image
     * up = −Z on the plane primitive; normal-map's orientation test checks this); across the
     * image its reflection is valid at some pixels, below the plane at others, and the normal
     * faces away from the viewer at some of those. A light ahead lights what the bent normals
     * reflect. Per pixel the render is the closed form of the normal the C guard gives
     * (tests/view_guard.h): continuous across both boundaries, where a model that masked
     * facing-away normals had a step (the default scene's dark wedge in the gold sphere's
     * shadow). */
    {
        const double s20 = sin(20 * M_PI / 180), c20 = cos(20 * M_PI / 180), nt[3] = {0, s20, c20};
        double l[3] = {0, 0.5, -0.866025};
        normalize3(l);
        char keys[512];
        snprintf(keys, sizeof keys,
                 "\"model\": \"ggx\", \"alpha\": 0.3, \"specular\": 1, \"eta\": 0.6667, \"normal_map\": \"constant:%.9g,%.9g,%.9g\"",
                 nt[0] * 0.5 + 0.5, nt[1] * 0.5 + 0.5, nt[2] * 0.5 + 0.5);
        snprintf(json, sizeof json, SCENE("%s", "{\"name\": \"ahead\", \"type\": \"directional\", \"direction\": [0, -0.5, 0.866025], \"intensity\": 2}"), keys);
        h = make_with(json, (const char *[]){"normal-map", NULL}, NULL);
        CHECK(h && sl_harness_render(h, img));
        const double kd[3] = {0.4, 0.3, 0.2}, g[3] = {0, 1, 0};
        double worst_rel = 0, peak = 0;
        int count = 0, bent = 0, away = 0;
        for (int y = 0; y < H; y += 3)
            for (int x = 0; x < W; x += 3) {
                float pt[3], o[3], d[3];
                if (!test_camera_hit_ground(&cam, x, y, 9.5f, pt)) continue;
                test_camera_ray(&cam, x, y, o, d);
                const float vf[3] = {-d[0], -d[1], -d[2]};
                double v[3] = {vf[0], vf[1], vf[2]}, n[3] = {0, c20, -s20}, spec;
                away += vg_dot(n, v) < 0;
                vg_view_guard(n, vf, g);
                bent += n[2] != -s20;
                for (int c = 0; c < 3; c++) {
                    double expect = ggx_closed(n, v, l, kd[c], 1, 0.3, 0.6667, 2, &spec);
                    double rel = fabs(img[(y * W + x) * 4 + c] - expect) / expect;
                    if (rel > worst_rel) worst_rel = rel;
                    if (spec > peak) peak = spec;
                }
                count++;
            }
        printf("mapped normals leaning 20 deg away: %d px (%d bent, %d facing away before), worst relative error %.2g, peak "
               "specular %.3f\n", count, bent, away, worst_rel, peak);
        CHECK_MSG(bent > 50 && count - bent > 50 && away > 50, "%d of %d pixels bent, %d facing away", bent, count, away);
        CHECK_MSG(count > 100 && worst_rel < 5e-3, "bent mapped normals: worst relative error %g against the closed form", worst_rel);
        CHECK_MSG(peak > 0.2, "no visible highlight (specular peak %.3f)", peak);
        sl_harness_destroy(h);
    }
    test_disk_highlight();
    double rms, flux;
    test_disk_profile(0.1, &rms, &flux);
    test_disk_profile(0.2, &rms, &flux);
    test_disk_profile(0.3, &rms, &flux);
    test_subpixel_glint();
    test_pixel_wide_glint();
    test_specular_aa_still();
    return check_result();
}
