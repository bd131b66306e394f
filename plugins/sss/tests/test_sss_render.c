/* sss: rendered tests of the diffusion methods against closed forms computed here.
 *   stripe         a thin white stripe of albedo on a flat skin patch (pre-scatter albedo, so the
 *                  stripe is what scatters) spreads into the six-Gaussian line response
 *                  (texture space and screen space); with no blur the same check fails
 *   normalisation  a uniformly lit flat patch is unchanged by every method (1e-3)
 *   strength 0     exactly the ggx model's image, every method
 *   leak           screen space: light does not cross a depth discontinuity
 *   seam           texture space: no step across a UV seam facing the camera
 *   interior       texture space: the interior (branch-free) blur path equals the full program
 *   cache          texture space: the on-disk result cache gives exactly the computed image, is
 *                  read (a tampered file shows), misses when the lighting changed, survives a
 *                  truncated file
 * Scenes are in millimetres (sss_radius = 1) unless stated. */
#include "sss_test.h"
#include "image/image.h"
#include "test_tmp.h"
#include <dirent.h>
#include <unistd.h>

static const char *const PLUGINS[] = {"sss", NULL};
static const char *const METHODS[] = {"none", "wrap", "translucency", "texture-space", "screen-space", "pre-integrated"};

/* ------------------------------------------------------------------ stripe ----------------- */
/* 128×32 px over a 64 mm wide patch seen head-on (0.5 mm per pixel), lit by E = π at normal
 * incidence so a white Lambert texel shows radiance 1. The albedo map is black with a white
 * stripe of width STRIPE mm down the middle. */
#define SW 128
#define SH 32
#define STRIPE 1.0

/* The middle rows' profile, compared with the expected line response in 1 mm bins (2 px: the
 * screen-space kernel's sparse taps make a comb at single pixels) from 1.5 to 8.5 mm on both
 * sides; the stripe and its edges (narrow Gaussians, texture filtering) are left out. */
static bool stripe_profile(sl_harness *h, const char *label, double tol_abs, double tol_rel, bool expect_pass) {
    static float img[SW * SH * 4];
    if (!sl_harness_render(h, img)) return false;
    CHECK(sl_harness_count_nonfinite(img, SW, SH) == 0);
    double v[SW][3], energy[3] = {0, 0, 0};
    for (int j = 0; j < SW; j++)
        for (int c = 0; c < 3; c++) {
            v[j][c] = 0;
            for (int y = SH / 2 - 2; y < SH / 2 + 2; y++) v[j][c] += sss_t_px(img, SW, j, y)[c] / 4.0;
            energy[c] += v[j][c] * 0.5;
        }
    int failures = 0;
    double worst = 0;
    printf("%s: bin (mm)   R rendered/expected   G   B\n", label);
    for (int side = -1; side <= 1; side += 2)
        for (int b = 0; b < 7; b++) {
            double x0 = 1.5 + b; /* bin [x0, x0 + 1] mm on this side */
            int j0 = SW / 2 + (side > 0 ? (int)(x0 * 2) : -(int)(x0 * 2) - 2);
            double got[3], want[3];
            for (int c = 0; c < 3; c++) {
                got[c] = 0.5 * (v[j0][c] + v[j0 + 1][c]);
                want[c] = 0;
                for (int k = 0; k < 16; k++) want[c] += sss_t_stripe(x0 + (k + 0.5) / 16, STRIPE, c) / 16;
                double err = fabs(got[c] - want[c]), tol = tol_abs + tol_rel * want[c];
                if (err > tol) failures++;
                worst = fmax(worst, err / tol);
            }
            if (side > 0)
                printf("  %3.1f-%3.1f   %.4f/%.4f   %.4f/%.4f   %.4f/%.4f\n", x0, x0 + 1, got[0], want[0], got[1],
                       want[1], got[2], want[2]);
        }
    printf("%s: %d of 42 bin-channels outside |err| <= %.3g + %.2f*expected (worst err/tol %.2f); energy %.4f %.4f "
           "%.4f (stripe %.2f)\n",
           label, failures, tol_abs, tol_rel, worst, energy[0], energy[1], energy[2], STRIPE);
    if (expect_pass) {
        CHECK_MSG(failures == 0, "%s: the line response differs from the profile", label);
        for (int c = 0; c < 3; c++) CHECK_MSG(fabs(energy[c] - STRIPE) < 0.02 * STRIPE, "%s: energy %f", label, energy[c]);
    } else {
        CHECK_MSG(failures >= 8, "%s: the stripe check does not catch an image without scattering", label);
    }
    return true;
}

static void test_stripe(void) {
    /* the albedo map: 512×4, white for 8 texels (1 mm) around the middle */
    char tex[1024];
    snprintf(tex, sizeof tex, "%s/sss_stripe.exr", sl_test_dir());
    enum { TW = 512, TH = 4 };
    static float map[TW * TH * 4];
    for (int y = 0; y < TH; y++)
        for (int x = 0; x < TW; x++) {
            float v = fabs(x + 0.5 - TW / 2) < STRIPE / 64.0 * TW / 2 ? 1.0f : 0.0f;
            for (int c = 0; c < 3; c++) map[4 * (y * TW + x) + c] = v;
            map[4 * (y * TW + x) + 3] = 1;
        }
    char err[1024];
    CHECK_MSG(sl_image_write(tex, map, TW, TH, false, err, sizeof err), "%s", err);
    char scene[4096];
    double d = 8.0 / tan(15.0 * M_PI / 180);
    snprintf(scene, sizeof scene,
             "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 0, %.6f], \"target\": [0, 0, 0], \"fov_y\": 30,"
             " \"near\": 1, \"far\": 200}],\n"
             " \"materials\": [{\"name\": \"skin\", \"model\": \"skin\", \"base_color_map\": \"%s\", \"sss_radius\": 1,"
             " \"alpha\": 0.3, \"specular\": 0}],\n"
             " \"nodes\": [{\"name\": \"patch\", \"mesh\": {\"primitive\": \"plane\", \"size\": 64}, \"rotate\": [90, 0, 0],"
             " \"material\": \"skin\"}],\n"
             " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": %.9f}]}\n",
             d, tex, M_PI);
    sl_harness *h = sss_t_harness(scene, SW, SH, PLUGINS,
                                  (const char *[]){"sss.albedo=pre-scatter", "sss.ts_size=256",
                                                   /* the 512×4 map is minified 4× along x only: an
                                                    * isotropic mip (a CPU renderer's default) blurs
                                                    * the stripe into the first bins; the test reads
                                                    * the scattering, not the texture filter */
                                                   "core.anisotropy=8", NULL});
    if (!h) return;
    /* tolerance: 0.001 (2 % of the first bin's value) + 25 % of the expected value */
    sss_t_set(h, "sss.method=texture-space");
    stripe_profile(h, "texture space, 7 taps", 0.001, 0.25, true);
    sss_t_set(h, "sss.ts_taps=15");
    stripe_profile(h, "texture space, 15 taps", 0.001, 0.10, true);
    sss_t_set(h, "sss.method=screen-space");
    sss_t_set(h, "sss.ss_taps=41");
    stripe_profile(h, "screen space, 41 taps", 0.001, 0.25, true);
    sss_t_set(h, "sss.ss_taps=17");
    stripe_profile(h, "screen space, 17 taps", 0.001, 0.25, true);
    sss_t_set(h, "sss.method=none");
    stripe_profile(h, "no scattering (must fail)", 0.001, 0.25, false);
    sl_harness_destroy(h);
}

/* ------------------------------------------------------------------ normalisation -------- */
/* A 48 mm patch of constant albedo seen head-on (64×64 px over 64 mm), lit by E = π at normal
 * incidence, no specular: every method, every albedo split gives exactly k_d (1e-3 relative) on
 * every pixel of the patch, its edges included (coverage renormalisation). */
static void test_normalisation(void) {
    char scene[4096];
    snprintf(scene, sizeof scene,
             "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 0, %.6f], \"target\": [0, 0, 0], \"fov_y\": 30,"
             " \"near\": 1, \"far\": 500}],\n"
             " \"materials\": [{\"name\": \"skin\", \"model\": \"skin\", \"base_color\": [0.8, 0.5, 0.3],"
             " \"sss_radius\": 1, \"alpha\": 0.3, \"specular\": 0}],\n"
             " \"nodes\": [{\"name\": \"patch\", \"mesh\": {\"primitive\": \"plane\", \"size\": 48}, \"rotate\": [90, 0, 0],"
             " \"material\": \"skin\"}],\n"
             " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": %.9f}]}\n",
             32.0 / tan(15.0 * M_PI / 180), M_PI);
    enum { N = 64 };
    sl_harness *h = sss_t_harness(scene, N, N, PLUGINS, (const char *[]){"sss.ts_size=128", NULL});
    if (!h) return;
    static float img[N * N * 4];
    const double kd[3] = {0.8, 0.5, 0.3};
    const char *albedo[] = {"post-scatter", "pre-scatter", "mixed"};
    for (int m = 0; m < 6; m++)
        for (int a = 0; a < 3; a++) {
            if (a && m != 3 && m != 4) continue; /* the albedo split only matters in texture/screen space */
            sss_t_set(h, "sss.method=%s", METHODS[m]);
            sss_t_set(h, "sss.albedo=%s", albedo[a]);
            if (!sl_harness_render(h, img)) continue;
            double worst = 0;
            int n = 0;
            for (int y = 9; y < N - 9; y++) /* the patch covers pixels 8..55 */
                for (int x = 9; x < N - 9; x++, n++)
                    for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(sss_t_px(img, N, x, y)[c] / kd[c] - 1));
            printf("normalisation: %-14s %-12s max relative deviation %.2e over %d pixels\n", METHODS[m], albedo[a],
                   worst, n);
            CHECK_MSG(worst < 1e-3, "%s/%s: a uniformly lit patch changed by %g", METHODS[m], albedo[a], worst);
            CHECK(sl_harness_count_nonfinite(img, N, N) == 0);
        }
    sl_harness_destroy(h);

    /* with an environment plugin's AMBIENT hook in the skin's programs (envmap) the scattered
     * diffuse still arrives (the core calls MODEL_AMBIENT with zero ambient there): texture and
     * screen space equal Lambert on the patch, the environment's own term included in both */
    char err[8192];
    h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = N, .height = N,
                                             .scene_json = scene, .float32 = true, .strict = true,
                                             .plugins = (const char *[]){"sss", "envmap", NULL},
                                             .settings = (const char *[]){"sss.ts_size=128", NULL}},
                          err, sizeof err);
    if (!h) {
        printf("SKIP normalisation under envmap: the envmap plugin did not load: %s\n", err);
        return;
    }
    static float none[N * N * 4];
    sss_t_set(h, "sss.method=none");
    CHECK(sl_harness_render(h, none));
    for (int m = 3; m <= 4; m++) {
        sss_t_set(h, "sss.method=%s", METHODS[m]);
        if (!sl_harness_render(h, img)) continue;
        double worst = 0;
        for (int y = 9; y < N - 9; y++)
            for (int x = 9; x < N - 9; x++)
                for (int c = 0; c < 3; c++)
                    worst = fmax(worst, fabs(sss_t_px(img, N, x, y)[c] / sss_t_px(none, N, x, y)[c] - 1));
        printf("normalisation under envmap: %-14s max relative deviation from none %.2e\n", METHODS[m], worst);
        CHECK_MSG(worst < 1e-3, "%s with envmap loaded: %g", METHODS[m], worst);
    }
    sl_harness_destroy(h);
}

/* ------------------------------------------------------------------ strength 0 ------------- */
/* A textured sphere in metres with two directional lights, a point light behind it and ambient
 * light: sss_strength = 0 renders exactly (bit for bit) the ggx model of the same material in a
 * scene without the sss plugin, for every method. */
static const char *strength_scene(bool skin) {
    static char scene[4096];
    snprintf(scene, sizeof scene,
             "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 0.02, 0.3], \"target\": [0, 0, 0], \"fov_y\": 40,"
             " \"near\": 0.01, \"far\": 10}],\n"
             " \"environment\": {\"color\": [0.3, 0.35, 0.4], \"intensity\": 0.5},\n"
             " \"materials\": [{\"name\": \"m\", \"model\": \"%s\", \"base_color_map\": \"checker:8:0.8,0.5,0.4:0.5,0.3,0.25\","
             " \"alpha\": 0.3, \"eta\": 0.7143, \"specular\": 0.8%s}],\n"
             " \"nodes\": [{\"name\": \"s\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.08}, \"material\": \"m\"}],\n"
             " \"lights\": [{\"name\": \"key\", \"type\": \"directional\", \"direction\": [-0.6, -0.3, -0.7], \"intensity\": 3},\n"
             "            {\"name\": \"fill\", \"type\": \"directional\", \"direction\": [0.7, 0.1, -0.5], \"intensity\": 0.7},\n"
             "            {\"name\": \"back\", \"type\": \"point\", \"position\": [0.05, 0.1, -0.2], \"intensity\": 0.2}]}\n",
             skin ? "skin" : "ggx", skin ? ", \"sss_radius\": 0.001, \"sss_strength\": 0" : "");
    return scene;
}

static void test_strength_zero(void) {
    enum { N = 64 };
    static float ref[N * N * 4], img[N * N * 4];
    sl_harness *g = sss_t_harness(strength_scene(false), N, N, (const char *[]){"ggx", NULL}, NULL);
    if (!g) return;
    CHECK(sl_harness_render(g, ref));
    sl_harness_destroy(g);
    long lit = 0;
    for (int i = 0; i < N * N; i++) lit += ref[4 * i] > 0.01f;
    CHECK(lit > N * N / 4); /* the sphere is there */
    sl_harness *h = sss_t_harness(strength_scene(true), N, N, PLUGINS, (const char *[]){"sss.ts_size=128", NULL});
    if (!h) return;
    for (int m = 0; m < 6; m++) {
        sss_t_set(h, "sss.method=%s", METHODS[m]);
        if (!sl_harness_render(h, img)) continue;
        sl_compare cmp;
        sl_harness_compare(img, ref, N, N, 0.0, &cmp);
        printf("strength 0, %-14s vs ggx without sss: max |difference| %.3g, %ld pixels differ\n", METHODS[m],
               cmp.max_abs, cmp.pixels_over);
        CHECK_MSG(cmp.max_abs == 0 && cmp.nonfinite == 0, "%s: strength 0 differs from ggx by %g", METHODS[m], cmp.max_abs);
    }
    /* and strength 1 does change the image (the comparison can fail) */
    sss_t_set(h, "material.m.sss_strength=1");
    sss_t_set(h, "sss.method=texture-space");
    CHECK(sl_harness_render(h, img));
    sl_compare cmp;
    sl_harness_compare(img, ref, N, N, 0.0, &cmp);
    CHECK(cmp.max_abs > 1e-3);
    sl_harness_destroy(h);
}

/* ------------------------------------------------------------------ leak ------------------- */
/* Screen space. A black patch 20 mm in front of a white one; they meet at the middle column on
 * screen. Pre-scatter albedo, so the black patch's own diffuse light is 0 and anything on it is
 * light leaked from the white patch behind. Bound: 1e-3 of the white patch's radiance (1); the
 * white patch keeps its radiance up to the edge (1 %). With ss_follow_surface off (a plain
 * blur) the leak is far above the bound. */
static void test_leak(void) {
    char scene[4096];
    snprintf(scene, sizeof scene,
             "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 0, %.6f], \"target\": [0, 0, 0], \"fov_y\": 30,"
             " \"near\": 1, \"far\": 500}],\n"
             " \"materials\": [{\"name\": \"black\", \"model\": \"skin\", \"base_color\": [0, 0, 0], \"sss_radius\": 1,"
             " \"specular\": 0},\n"
             "   {\"name\": \"white\", \"model\": \"skin\", \"base_color\": [1, 1, 1], \"sss_radius\": 1, \"specular\": 0}],\n"
             " \"nodes\": [{\"name\": \"near\", \"translate\": [-20, 0, 20], \"mesh\": {\"primitive\": \"plane\", \"size\": 40},"
             " \"rotate\": [90, 0, 0], \"material\": \"black\"},\n"
             "   {\"name\": \"far\", \"translate\": [15, 0, 0], \"mesh\": {\"primitive\": \"plane\", \"size\": 60},"
             " \"rotate\": [90, 0, 0], \"material\": \"white\"}],\n"
             " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": %.9f}]}\n",
             32.0 / tan(15.0 * M_PI / 180), M_PI);
    enum { N = 64 };
    sl_harness *h = sss_t_harness(scene, N, N, PLUGINS,
                                  (const char *[]){"sss.method=screen-space", "sss.albedo=pre-scatter", NULL});
    if (!h) return;
    static float img[N * N * 4];
    for (int follow = 1; follow >= 0; follow--) {
        sss_t_set(h, "sss.ss_follow_surface=%s", follow ? "true" : "false");
        if (!sl_harness_render(h, img)) break;
        double leak = 0, darkest = 1;
        for (int y = 16; y < 48; y++) {
            for (int x = 16; x < N / 2; x++) leak = fmax(leak, sss_t_px(img, N, x, y)[0]);
            for (int x = N / 2; x < N / 2 + 8; x++) darkest = fmin(darkest, sss_t_px(img, N, x, y)[0]);
        }
        CHECK(sl_harness_count_nonfinite(img, N, N) == 0);
        printf("leak across a 20 mm depth step, follow surface %s: max on the near patch %.3g, white side down to %.4f\n",
               follow ? "on" : "off", leak, darkest);
        if (follow) {
            CHECK_MSG(leak < 1e-3, "light leaks across the depth discontinuity: %g", leak);
            CHECK_MSG(darkest > 0.99, "the far patch darkens at the discontinuity: %g", darkest);
        } else {
            CHECK_MSG(leak > 0.05, "a plain blur should leak (the test must be able to fail): %g", leak);
        }
    }
    sl_harness_destroy(h);
}

/* ------------------------------------------------------------------ seam ------------------- */
/* Texture space on a UV sphere (radius 40 mm, the profile scaled ×2) whose seam u = 0/1 faces
 * the camera (the middle of the image), lit from the side so that the lighting has a gradient
 * across the seam. In the rows near the equator the step between the two columns astride the
 * seam must not exceed 1.2× the larger of the two neighbouring column steps plus 1e-3 of the
 * value (a blur that renormalises at the chart edge gives 1.5×); and the blur must have changed
 * the image (by > 0.01 against no scattering). */
#ifndef SEAM_RADIUS
#define SEAM_RADIUS "2"
#endif
static void test_seam(void) {
    const char *scene =
        "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 160], \"target\": [0, 0, 0], \"fov_y\": 35, \"near\": 1,"
        " \"far\": 1000}],\n"
        " \"materials\": [{\"name\": \"skin\", \"model\": \"skin\", \"base_color\": [0.7, 0.7, 0.7], \"sss_radius\": " SEAM_RADIUS ","
        " \"specular\": 0}],\n"
        " \"nodes\": [{\"name\": \"s\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 40, \"segments\": 128,"
        " \"rings\": 64}, \"material\": \"skin\"}],\n"
        " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [-1, 0, -0.4], \"intensity\": 3}]}\n";
    enum { N = 64 };
    sl_harness *h = sss_t_harness(scene, N, N, PLUGINS, (const char *[]){"sss.ts_size=256", NULL});
    if (!h) return;
    static float img[N * N * 4], plain[N * N * 4];
    sss_t_set(h, "sss.method=none");
    CHECK(sl_harness_render(h, plain));
    sss_t_set(h, "sss.method=texture-space");
    CHECK(sl_harness_render(h, img));
    CHECK(sl_harness_count_nonfinite(img, N, N) == 0);
    double worst = 0, changed = 0;
    for (int y = 24; y < 40; y++) {
        const int c = N / 2; /* the seam lies between columns c − 1 and c */
        double I[4];
        for (int k = 0; k < 4; k++) I[k] = sss_t_px(img, N, c - 2 + k, y)[0];
        double seam = fabs(I[2] - I[1]), side = fmax(fabs(I[1] - I[0]), fabs(I[3] - I[2]));
        double ratio = seam / (1.2 * side + 1e-3 * I[1]);
        worst = fmax(worst, ratio);
        for (int x = 0; x < N; x++) changed = fmax(changed, fabs(sss_t_px(img, N, x, y)[0] - sss_t_px(plain, N, x, y)[0]));
        if (y == 32) {
            printf("seam row %d, columns %d..%d: texture space %.4f %.4f | %.4f %.4f; no scattering", y, c - 3, c + 2,
                   I[0], I[1], I[2], I[3]);
            for (int k = 0; k < 6; k++) printf(" %.4f", sss_t_px(plain, N, c - 3 + k, y)[0]);
            printf("\n");
        }
    }
    printf("seam: worst step / (1.2 x neighbouring step + 1e-3 I) = %.3f; largest change by the blur %.3f\n", worst,
           changed);
    CHECK_MSG(worst <= 1.0, "a step at the UV seam: %.3f", worst);
    CHECK(changed > 0.01);
    sl_harness_destroy(h);
}

/* ------------------------------------------------------------------ interior ------------- */
/* The texture-space blurs draw a branch-free program on texels whose taps cannot reach a chart
 * edge (sss.c: ts_classify) and the full program elsewhere; the full program alone
 * (SHADELAB_SSS_FULL_BLUR=1) must give the same image, on a UV sphere whose seam faces the camera,
 * whose stretch varies from the equator to the poles (degenerate there) and whose atlas edges
 * are chart edges, in two sizes of the profile. Equal within 1e-6 (the same sums in the same order).
 * Live changes: the split harness moves the light, then changes the profile's size from 0.5 mm
 * to 2 (a classification kept from 0.5 mm would send texels whose 2 mm taps reach an edge to
 * the interior program: 0.0445 when tried), each compared with a fresh start of that state under
 * the full program. */
#define INTERIOR_SCENE(RADIUS, LIGHT_DIR) \
    "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 30, 160], \"target\": [0, 0, 0], \"fov_y\": 35," \
    " \"near\": 1, \"far\": 1000}],\n" \
    " \"materials\": [{\"name\": \"skin\", \"model\": \"skin\", \"base_color\": [0.7, 0.7, 0.7]," \
    " \"sss_radius\": " RADIUS ", \"specular\": 0}],\n" \
    " \"nodes\": [{\"name\": \"s\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 40, \"segments\": 64," \
    " \"rings\": 32}, \"material\": \"skin\"}],\n" \
    " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": " LIGHT_DIR "," \
    " \"intensity\": 3}]}\n"

enum { IN = 64 };
static bool interior_render(const char *scene, bool full, float *img) {
    if (full) setenv("SHADELAB_SSS_FULL_BLUR", "1", 1);
    sl_harness *h = sss_t_harness(scene, IN, IN, PLUGINS, (const char *[]){"sss.ts_size=256", NULL});
    bool ok = h && sl_harness_render(h, img);
    sl_harness_destroy(h);
    unsetenv("SHADELAB_SSS_FULL_BLUR");
    return ok;
}

static double interior_diff(const float *a, const float *b) {
    double worst = 0;
    for (int i = 0; i < IN * IN * 4; i++) worst = fmax(worst, fabs(a[i] - b[i]));
    return worst;
}

static void test_interior(void) {
    static const char *const scenes[] = {INTERIOR_SCENE("2", "[-1, -0.3, -0.4]"), INTERIOR_SCENE("0.5", "[-1, -0.3, -0.4]")};
    static float split[IN * IN * 4], full[IN * IN * 4];
    for (int r = 0; r < 2; r++) {
        bool ok = interior_render(scenes[r], false, split) && interior_render(scenes[r], true, full);
        CHECK(ok);
        if (!ok) continue;
        double worst = interior_diff(split, full);
        printf("interior split, sss_radius %s: largest difference to the full program %.3g\n", r ? "0.5" : "2", worst);
        CHECK_MSG(worst <= 1e-6, "the interior path differs from the full program by %g", worst);
        CHECK(sl_harness_count_nonfinite(split, IN, IN) == 0);
    }
    /* live: 0.5 mm, then the light moved, then 2 mm; the fresh starts first (one harness at a
     * time per process) */
    static const struct {
        const char *set, *scene, *what;
    } steps[] = {
        {"light.sun.direction=0.3,-0.5,-1", INTERIOR_SCENE("0.5", "[0.3, -0.5, -1]"), "light moved"},
        {"material.skin.sss_radius=2", INTERIOR_SCENE("2", "[0.3, -0.5, -1]"), "profile 0.5 -> 2 mm"},
    };
    enum { STEPS = sizeof steps / sizeof *steps };
    static float fresh[STEPS][IN * IN * 4];
    for (int k = 0; k < STEPS; k++)
        if (!interior_render(steps[k].scene, true, fresh[k])) {
            CHECK_MSG(false, "fresh start: %s", steps[k].what);
            return;
        }
    sl_harness *h = sss_t_harness(scenes[1], IN, IN, PLUGINS, (const char *[]){"sss.ts_size=256", NULL});
    if (!h) return;
    CHECK(sl_harness_render(h, split));
    for (int k = 0; k < STEPS; k++) {
        sss_t_set(h, steps[k].set);
        CHECK(sl_harness_render(h, split));
        double worst = interior_diff(split, fresh[k]);
        printf("interior split, live, %s: largest difference to a fresh start (full program) %.3g\n", steps[k].what, worst);
        CHECK_MSG(worst <= 1e-6, "%s: differs from a fresh start by %g", steps[k].what, worst);
    }
    sl_harness_destroy(h);
}

/* ------------------------------------------------------------------ cache ------------------ */
/* The one ts-*.bin file in dir (its path into out); how many there are. */
static int cache_files(const char *dir, char *out, size_t n) {
    DIR *d = opendir(dir);
    int count = 0;
    for (struct dirent *e; d && (e = readdir(d));)
        if (!strncmp(e->d_name, "ts-", 3) && strstr(e->d_name, ".bin") && !strstr(e->d_name, ".tmp")) {
            snprintf(out, n, "%s/%s", dir, e->d_name);
            count++;
        }
    if (d) closedir(d);
    return count;
}

static bool render_once(const char *scene, const char *cache, const char *light, float *img, int n) {
    sl_harness *h = sss_t_harness(scene, n, n, PLUGINS, (const char *[]){"sss.ts_size=256", cache, light, NULL});
    if (!h) return false;
    bool ok = sl_harness_render(h, img);
    sl_harness_destroy(h); /* deactivate: the pending result is written then */
    return ok;
}

static double max_diff(const float *a, const float *b, size_t count) {
    double worst = 0;
    for (size_t i = 0; i < count; i++) worst = fmax(worst, fabs((double)a[i] - b[i]));
    return worst;
}

static void test_cache(void) {
    const char *scene =
        "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 30, 160], \"target\": [0, 0, 0], \"fov_y\": 35,"
        " \"near\": 1, \"far\": 1000}],\n"
        " \"materials\": [{\"name\": \"skin\", \"model\": \"skin\", \"base_color\": [0.7, 0.6, 0.5],"
        " \"sss_radius\": 2, \"specular\": 0}],\n"
        " \"nodes\": [{\"name\": \"s\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 40, \"segments\": 64,"
        " \"rings\": 32}, \"material\": \"skin\"}],\n"
        " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [-1, -0.3, -0.4],"
        " \"intensity\": 3}]}\n";
    enum { N = 64 };
    const size_t count = (size_t)N * N * 4;
    static float ref[N * N * 4], img[N * N * 4], ref2[N * N * 4];
    char root[4200], dir[4300], file[4600];
    snprintf(root, sizeof root, "%s/cache", sl_test_dir());
    snprintf(dir, sizeof dir, "%s/sss", root);
    char *saved = getenv("SHADELAB_CACHE") ? strdup(getenv("SHADELAB_CACHE")) : NULL;
    setenv("SHADELAB_CACHE", root, 1);
    const char *on = "sss.cache=true", *off = "sss.cache=false", *dim = "light.sun.intensity=2";
    /* 1. computed with the cache on = computed without; one file written */
    CHECK(render_once(scene, off, NULL, ref, N));
    CHECK(cache_files(dir, file, sizeof file) == 0);
    CHECK(render_once(scene, on, NULL, img, N));
    double d1 = max_diff(img, ref, count);
    int files = cache_files(dir, file, sizeof file);
    printf("cache: first start (stores) vs no cache: largest difference %g; %d file(s)\n", d1, files);
    CHECK(d1 == 0 && files == 1);
    /* 2. loaded: the same image, bit for bit */
    CHECK(render_once(scene, on, NULL, img, N));
    double d2 = max_diff(img, ref, count);
    printf("cache: second start (loads) vs no cache: largest difference %g\n", d2);
    CHECK_MSG(d2 == 0, "the cached result differs from the computed one by %g", d2);
    CHECK(cache_files(dir, file, sizeof file) == 1);
    /* 3. it is read: a file whose texels were replaced shows in the image */
    FILE *f = fopen(file, "r+b");
    CHECK(f != NULL);
    if (f) {
        long header = 24; /* magic, key, size, result */
        float fill[4] = {0.5f, 0.0f, 0.5f, 1.0f};
        fseek(f, header, SEEK_SET);
        for (int i = 0; i < 256 * 256; i++) fwrite(fill, sizeof fill, 1, f);
        fclose(f);
    }
    CHECK(render_once(scene, on, NULL, img, N));
    double d3 = max_diff(img, ref, count);
    printf("cache: a tampered file's texels show: largest difference %g\n", d3);
    CHECK_MSG(d3 > 0.05, "the cache file is not what the frame shows (%g)", d3);
    /* 4. other lighting: no stale hit (the image of that lighting without the cache) */
    CHECK(render_once(scene, off, dim, ref2, N));
    CHECK(render_once(scene, on, dim, img, N));
    double d4 = max_diff(img, ref2, count), d4b = max_diff(ref2, ref, count);
    printf("cache: dimmer light: vs its own computed image %g (vs the first lighting %g); %d file(s)\n", d4, d4b,
           cache_files(dir, file, sizeof file));
    CHECK(d4 == 0 && d4b > 0.01);
    CHECK(cache_files(dir, file, sizeof file) == 2);
    /* 5. a truncated file: computed again, the same image */
    if (cache_files(dir, file, sizeof file) >= 1) {
        DIR *d = opendir(dir);
        for (struct dirent *e; d && (e = readdir(d));)
            if (!strncmp(e->d_name, "ts-", 3)) {
                char p[4600];
                snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
                CHECK(truncate(p, 1000) == 0);
            }
        if (d) closedir(d);
    }
    CHECK(render_once(scene, on, NULL, img, N));
    double d5 = max_diff(img, ref, count);
    printf("cache: truncated files: vs computed %g\n", d5);
    CHECK(d5 == 0);
    if (saved) setenv("SHADELAB_CACHE", saved, 1);
    else unsetenv("SHADELAB_CACHE");
    free(saved);
}

int main(void) {
    test_cache();
    test_leak();
    test_seam();
    test_interior();
    test_stripe();
    test_normalisation();
    test_strength_zero();
    return check_result();
}
