/* ggx end to end: a plane under a directional light against the BRDF evaluated per pixel in C
 * from the camera rays; world vs camera space; zero-specular equals Lambert; stability renders;
 * a Lambert material's program is untouched by loading ggx. */
#include "check.h"
#include "camera_rays.h"
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

static sl_harness *make(const char *json, const char *const *settings) {
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                          .scene_json = json, .settings = settings, .float32 = true, .strict = true},
                                      err, sizeof err);
    if (!h) fprintf(stderr, "harness: %s\n", err);
    return h;
}

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
    const char *const *sets[3] = {(const char *[]){"ggx.specular_aa=true", NULL},
                                  (const char *[]){"ggx.specular_aa=false", NULL},
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
            double v[3] = {-d[0], -d[1], -d[2]}, hh[3] = {ld[0] + v[0], ld[1] + v[1], ld[2] + v[2]};
            normalize3(hh);
            double nl = ld[1], nv = v[1], nh = hh[1], lh = ld[0] * hh[0] + ld[1] * hh[1] + ld[2] * hh[2];
            double vh = v[0] * hh[0] + v[1] * hh[1] + v[2] * hh[2];
            double t2 = (1 - nh * nh) / (nh * nh);
            double D = a * a / (M_PI * pow(nh, 4) * pow(a * a + t2, 2));
            double fs = fresnel_exact(lh, eta) * D * g1(nv, vh, a) * g1(nl, lh, a) / (4 * nl * nv);
            for (int c = 0; c < 3; c++) {
                double expect = (kd[c] / M_PI + ks * fs) * E * nl;
                double rel = fabs(img[(y * W + x) * 4 + c] - expect) / expect;
                if (rel > worst) worst = rel;
                if (ks * fs * E * nl > peak) peak = ks * fs * E * nl;
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
        /* Toksvig removes most of the aliasing (RMSE against the supersampled render 3× lower);
         * the far-field MEAN is darker than the reference (README: in this forward glint the
         * normal-mapped reference is dominated by normals nearly perpendicular to the view, and
         * depends on the normal map's n·v guard), so the mean is not asserted here. */
        CHECK_MSG(e_on < 0.6 * e_off, "AA does not reduce the far-field error enough (%.3f vs %.3f)", e_on, e_off);
    }
    /* 7. the same plane over a grid of grazing views and suns (far field: hit points more than
     * 25 m from the camera), for the README's table: antialiasing must lower the RMSE against the
     * reference in every configuration; whether the mean gets closer is counted and printed (6 of
     * 9 at this writing: not in the forward glints at 1.2 and 3 m, see the README) */
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
                CHECK_MSG(e_on < e_off, "camera %.1f m, sun %d: AA raises the RMSE (%.3f vs %.3f)", heights[i], j, e_on, e_off);
                printf("  %.1f m, (%.2f, %.2f, %.2f): %.3f / %.3f / %.3f  |on - ref| %s |off - ref|; RMSE on %.3f, off %.3f\n",
                       heights[i], suns[j][0], suns[j][1], suns[j][2], m[2], m[1], m[0], ok ? "<" : ">=", e_on, e_off);
            }
        printf("ggx specular AA grid: the AA mean is closer to the reference in %d of 9 configurations\n", better);
    }
    return check_result();
}
