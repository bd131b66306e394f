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
        enum { AW = 160, AH = 90 };
        static float on[AW * AH * 4], off[AW * AH * 4], ref[AW * AH * 4];
        char aa_scene[2048];
        snprintf(aa_scene, sizeof aa_scene,
                 "{\"plugins\": [\"ggx\", \"normal-map\"],\n"
                 " \"cameras\": [{\"name\": \"c\", \"position\": [0, 1.2, 19], \"target\": [0, 0, 0], \"fov_y\": 40}],\n"
                 " \"materials\": [{\"name\": \"bumpy\", \"model\": \"ggx\", \"alpha\": 0.05, \"base_color\": [0.18, 0.2, 0.24],\n"
                 "   \"normal_map\": \"%s/../plugins/phong/assets/bumps32_tangent.png\"}],\n"
                 " \"nodes\": [{\"name\": \"p\", \"mesh\": {\"primitive\": \"plane\", \"size\": 40}, \"material\": \"bumpy\"}],\n"
                 " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -0.25, 0.968], \"intensity\": 4}]}",
                 SL_SCENES_DIR);
        const char *const *sets[3] = {(const char *[]){"ggx.specular_aa=true", NULL},
                                      (const char *[]){"ggx.specular_aa=false", NULL},
                                      (const char *[]){"ggx.specular_aa=false", "core.ssaa=8", "normal-map.lod_bias=-16", NULL}};
        float *outs[3] = {on, off, ref};
        for (int k = 0; k < 3; k++) {
            sl_harness *hh = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = AW,
                                                                   .height = AH, .scene_json = aa_scene, .settings = sets[k],
                                                                   .float32 = true, .strict = true}, err, sizeof err);
            CHECK_MSG(hh != NULL, "%s", err);
            if (!hh) return check_result();
            CHECK(sl_harness_render(hh, outs[k]));
            CHECK(sl_harness_count_nonfinite(outs[k], AW, AH) == 0);
            sl_harness_destroy(hh);
        }
        /* far field: rows between the horizon (about 0.36 H) and 0.6 H, where pixels cover many bumps */
        double m[3] = {0, 0, 0}, e_on = 0, e_off = 0;
        int cnt = 0;
        for (int y = (int)(0.37 * AH); y < (int)(0.6 * AH); y++)
            for (int x = 0; x < AW; x++) {
                int i = (y * AW + x) * 4;
                for (int k = 0; k < 3; k++) m[k] += outs[k][i + 1];
                e_on += (on[i + 1] - ref[i + 1]) * (on[i + 1] - ref[i + 1]);
                e_off += (off[i + 1] - ref[i + 1]) * (off[i + 1] - ref[i + 1]);
                cnt++;
            }
        for (int k = 0; k < 3; k++) m[k] /= cnt;
        printf("ggx specular AA, far field: mean AA on %.4f, off %.4f, reference %.4f; RMSE on %.4f, off %.4f\n", m[0], m[1],
               m[2], sqrt(e_on / cnt), sqrt(e_off / cnt));
        /* Toksvig removes most of the aliasing (RMSE against the supersampled render 2.4× lower);
         * the far-field MEAN is darker than the reference (README: widened α also widens Smith
         * masking, which a normal-mapped reference does not have), so the mean is not asserted. */
        CHECK_MSG(e_on < 0.6 * e_off, "AA does not reduce the far-field error enough (%.3f vs %.3f)", sqrt(e_on / cnt),
                  sqrt(e_off / cnt));
    }
    return check_result();
}
