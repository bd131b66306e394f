/* refraction against independent C computations (harness, OSMesa; sphere_ref.h is the reference,
 * which shares no code with the GLSL). Scene: a unit sphere (256×128 segments) at the origin seen
 * from (0, 0, 4), fov 40°, 128×128, envmap's procedural "uv" environment, no lights.
 *  0. the C reference conserves energy: in a constant environment its weights sum to 1.
 *  1. η = 1 shows the background through the object exactly: the sphere's pixels equal the same
 *     pixels rendered without the sphere (envmap's background pass) and the C lookup along the
 *     view ray, for method single and two-interface; with envmap.yaw = 90 too (the extension's
 *     rotation: the sphere must match the background turned the same way).
 *  2. single interface, η = 1.5: every tested pixel equals F·L(r) + (1 − F)·L(t) from C.
 *  3. total internal reflection where Snell says: η = 0.75 (a bubble); beyond the critical angle
 *     (sin θ > 0.75) the pixel is L(r) exactly, inside it the C formula with F < 1 (a band of
 *     ±0.03 in sin θ around the critical angle is left out: there the tessellated sphere's
 *     interpolated normals decide which side a pixel falls on).
 *  4. dispersion: ior_rgb = (1.4, 1.5, 1.6): red and green each follow their own η; with
 *     refraction.dispersion=false both follow green's.
 *  5. the sphere reference (every internal bounce): pixel values printed for single and
 *     two-interface; two-interface must be closer to it than single.
 * Tests 1-4 read the environment at level 0 (refraction.filter=false): the C side point-samples.
 *  6. stability: η at its limits gives finite, non-negative pixels; live equals fresh for
 *     method, steps and dispersion.
 *  7. a scene without glass costs nothing: no back-face pass, the frame's structure (passes, draw
 *     calls, programs) equals the one without the plugin. */
#include <shadelab/harness.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sphere_ref.h"

static int failures;
#define CHECK(cond, ...) do { if (!(cond)) { failures++; printf("FAIL %s:%d: ", __FILE__, __LINE__); printf(__VA_ARGS__); printf("\n"); } } while (0)

#define W 128
#define H 128
#define FOV 40.0
static const double CAM[3] = {0, 0, 4}, TARGET[3] = {0, 0, 0};
/* Tolerances (absolute, channel values in [0, 1]): RGBA16F cube texels (2^-11 relative), the cube
 * resampled from the 512×256 lat-long source, trilinear filtering at the footprint's mip level,
 * the 256×128 tessellation's interpolated normals. Measured maxima are printed. */
#define TOL 0.002

static char *scene(bool sphere, const char *material_extra) {
    static char buf[2048];
    snprintf(buf, sizeof buf,
             "{\"plugins\": [\"envmap\"],"
             " \"cameras\": [{\"name\": \"main\", \"position\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y\": %g}],"
             " \"materials\": [{\"name\": \"glass\", \"model\": \"dielectric\", \"ior\": 1.5%s}],"
             " \"nodes\": [{\"name\": \"ball\", \"translate\": [0, 0, %s], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1,"
             " \"segments\": 256, \"rings\": 128}, \"material\": \"glass\"}],"
             " \"lights\": [], \"environment\": {\"map\": \"uv\"}}",
             FOV, material_extra ? material_extra : "", sphere ? "0" : "100");
    return buf;
}

static sl_harness *make(const char *json, const char *const *settings) {
    const char *plugins[] = {RF_PLUGIN_PATH, NULL};
    char err[4096];
    sl_harness_desc d = {.struct_size = sizeof d, .width = W, .height = H, .scene_json = json, .plugins = plugins,
                         .settings = settings, .strict = true};
    sl_harness *h = sl_harness_create(&d, err, sizeof err);
    if (!h) { printf("FAIL: harness: %s\n", err); exit(1); }
    return h;
}
static void set(sl_harness *h, const char *a) {
    char err[1024];
    if (!sl_harness_set(h, a, err, sizeof err)) { printf("FAIL: set %s: %s\n", a, err); exit(1); }
}
static float *render(sl_harness *h) {
    float *img = malloc(sizeof(float) * W * H * 4);
    sl_harness_set_frame(h, 0);
    if (!sl_harness_render(h, img)) { printf("FAIL: render\n"); exit(1); }
    return img;
}

/* the C value at pixel (x, y); returns the first cos θ (−1: background) */
static double reference(int x, int y, const double ior[3], bool single, double out[3]) {
    rf_camera c = rf_camera_make(CAM, TARGET, FOV, W, H);
    double w[3], ci;
    rf_camera_ray(&c, x, y, W, H, w);
    rf_sphere S = {{0, 0, 0}, 1};
    rf_seam_margin = 1;
    rf_trace(&S, CAM, w, ior, single, out, &ci);
    return ci;
}

/* compares img with the C computation at every 4th pixel where cos θ ≥ 0.2 (red only away from the
 * u seam); returns the largest error */
static double compare(const char *what, const float *img, const double ior[3], bool single, bool red, int *count) {
    double worst = 0;
    int n = 0;
    for (int y = 2; y < H; y += 4)
        for (int x = 2; x < W; x += 4) {
            double ref[3];
            if (reference(x, y, ior, single, ref) < 0.2) continue;
            const float *p = img + ((size_t)y * W + x) * 4;
            double e = fabs(p[1] - ref[1]);
            if (red && rf_seam_margin > 0.03) e = fmax(e, fabs(p[0] - ref[0]));
            if (e > worst) worst = e;
            if (e > TOL && what[0] != ' ' && n < 1000) printf("  %s: pixel (%d, %d): GPU (%.4f, %.4f) C (%.4f, %.4f)\n", what, x, y, p[0], p[1], ref[0], ref[1]);
            n++;
        }
    if (count) *count = n;
    printf("%s: %d pixels, max |GPU - C| = %.5f\n", what, n, worst);
    return worst;
}

int main(void) {
    /* 0. the reference conserves energy (a constant environment: weights sum to 1) */
    {
        double worst = 0;
        for (double c = 0.01; c <= 1.0; c += 0.01) {
            for (int b = 0; b < 2; b++) {
                double ior = b ? 1.5 : 0.75, F = rf_fresnel(c, ior), sum = F;
                if (F < 1) { /* inside a sphere every inner hit has the refraction angle: F' from it */
                    double s = sqrt(1 - c * c) / ior, ct = sqrt(1 - s * s), F2 = rf_fresnel(ct, 1 / ior), wgt = 1 - F;
                    for (int k = 0; k < 100000 && wgt > 1e-15; k++) sum += wgt * (1 - F2), wgt *= F2;
                }
                worst = fmax(worst, fabs(sum - 1));
            }
        }
        printf("reference: energy |sum of weights - 1| <= %.2e\n", worst);
        CHECK(worst < 1e-9, "reference loses energy: %g", worst);
        CHECK(fabs(rf_fresnel(1, 1.5) - 0.04) < 1e-12, "F(normal, 1.5) = %g, expected 0.04", rf_fresnel(1, 1.5));
    }

    /* 1. η = 1: the background, exactly */
    float *bg;
    {
        sl_harness *h = make(scene(false, NULL), NULL);
        bg = render(h);
        sl_harness_destroy(h);
    }
    /* level 0 (no footprint filtering): the C side point-samples */
    sl_harness *h = make(scene(true, NULL), (const char *const[]){"refraction.method=single", "refraction.filter=false", NULL});
    const double one[3] = {1, 1, 1}, glass[3] = {1.5, 1.5, 1.5}, bubble[3] = {0.75, 0.75, 0.75};
    for (int m = 0; m < 2; m++) {
        set(h, m ? "refraction.method=two-interface" : "refraction.method=single");
        set(h, "material.glass.ior=1");
        float *img = render(h);
        double worst_bg = 0;
        int n = 0;
        for (int y = 2; y < H; y += 4)
            for (int x = 2; x < W; x += 4) {
                double ref[3];
                if (reference(x, y, one, true, ref) < 0.2) continue;
                const float *p = img + ((size_t)y * W + x) * 4, *q = bg + ((size_t)y * W + x) * 4;
                worst_bg = fmax(worst_bg, fmax(fabs(p[0] - q[0]), fabs(p[1] - q[1])));
                n++;
            }
        printf("eta = 1 (%s): %d pixels, max |sphere - background| = %.5f\n", m ? "two-interface" : "single", n, worst_bg);
        CHECK(n > 300 && worst_bg < TOL, "eta = 1 does not show the background (%s): %.5f", m ? "two-interface" : "single", worst_bg);
        CHECK(compare(m ? "eta = 1, two-interface vs C" : "eta = 1, single vs C", img, one, true, true, NULL) < TOL,
              "eta = 1 differs from the environment along the view ray");
        free(img);
    }

    /* 1b. the extension's rotation: the environment turned by envmap.yaw = 90 (+Z towards +X), η = 1
     * still shows the background exactly (both read the map through envmap's yaw) */
    {
        sl_harness_destroy(h);
        sl_harness *hb = make(scene(false, NULL), (const char *const[]){"envmap.yaw=90", NULL});
        float *bg90 = render(hb);
        sl_harness_destroy(hb);
        h = make(scene(true, NULL), (const char *const[]){"refraction.method=single", "refraction.filter=false",
                                                          "material.glass.ior=1", "envmap.yaw=90", NULL});
        float *img = render(h), worst = 0, moved = 0;
        for (int y = 2; y < H; y += 4)
            for (int x = 2; x < W; x += 4) {
                double ref[3];
                if (reference(x, y, one, true, ref) < 0.2) continue;
                const float *p = img + ((size_t)y * W + x) * 4, *q = bg90 + ((size_t)y * W + x) * 4;
                worst = fmaxf(worst, fmaxf(fabsf(p[0] - q[0]), fabsf(p[1] - q[1])));
                moved = fmaxf(moved, fabsf(p[0] - (float)ref[0])); /* u moved by a quarter turn */
            }
        printf("eta = 1, envmap.yaw = 90: max |sphere - background| = %.5f (red moved by up to %.3f from yaw 0)\n", worst, moved);
        CHECK(worst < TOL && moved > 0.2, "the environment extension's rotation");
        free(img), free(bg90);
        set(h, "envmap.yaw=0");
    }

    /* 2. single interface, η = 1.5 */
    set(h, "refraction.method=single");
    set(h, "material.glass.ior=1.5");
    float *single_img = render(h);
    CHECK(compare("single, eta 1.5 vs C single interface", single_img, glass, true, true, NULL) < TOL, "single interface");
    {   /* the test can fail: the C value for a slightly different η is out of tolerance somewhere */
        const double wrong[3] = {1.4, 1.4, 1.4};
        double e = compare("  (sensitivity: the same image vs C with eta 1.4)", single_img, wrong, true, false, NULL);
        CHECK(e > 2 * TOL, "the comparison cannot tell eta 1.4 from 1.5 (%.4f)", e);
    }

    /* 3. total internal reflection: η = 0.75 */
    set(h, "material.glass.ior=0.75");
    {
        float *img = render(h);
        int tir = 0, partial = 0, distinct = 0;
        double worst = 0;
        for (int y = 2; y < H; y += 4)
            for (int x = 2; x < W; x += 4) {
                double ref[3], ci = reference(x, y, bubble, true, ref);
                if (ci < 0.2) continue;
                double si = sqrt(1 - ci * ci);
                const float *p = img + ((size_t)y * W + x) * 4;
                double e = fabs(p[1] - ref[1]);
                if (rf_seam_margin > 0.03) e = fmax(e, fabs(p[0] - ref[0]));
                if (si > 0.75 - 0.03 && si < 0.75 + 0.03) continue; /* the band where the tessellation decides */
                worst = fmax(worst, e);
                if (si > 0.75) {
                    CHECK(rf_fresnel(ci, 0.75) == 1, "C: no total reflection at sin %.3f", si);
                    tir++;
                } else {
                    partial++;
                    /* there F < 1: the pixel is not the reflection alone */
                    rf_camera c = rf_camera_make(CAM, TARGET, FOV, W, H);
                    double w[3], n[3], r[3], er[3];
                    rf_camera_ray(&c, x, y, W, H, w);
                    rf_sphere S = {{0, 0, 0}, 1};
                    double s = rf_hit(&S, CAM, w);
                    for (int j = 0; j < 3; j++) n[j] = CAM[j] + s * w[j];
                    for (int j = 0; j < 3; j++) r[j] = w[j] + 2 * ci * n[j];
                    rf_env(r, 1, er);
                    if (fabs(p[1] - er[1]) > 3 * TOL) distinct++;
                }
                if (e > TOL) printf("  TIR: pixel (%d, %d) sin %.3f: GPU %.4f C %.4f\n", x, y, si, p[1], ref[1]);
            }
        printf("total internal reflection (eta 0.75): %d pixels beyond the critical angle, %d inside (%d visibly not a "
               "pure reflection), max |GPU - C| = %.5f\n", tir, partial, distinct, worst);
        CHECK(tir > 50 && partial > 50 && distinct > 20 && worst < TOL, "total internal reflection");
        free(img);
    }

    /* 4. dispersion */
    set(h, "material.glass.ior=1.5");
    set(h, "material.glass.ior_rgb=1.4,1.5,1.6");
    {
        const double disp[3] = {1.4, 1.5, 1.6};
        float *img = render(h);
        CHECK(compare("dispersion, per channel vs C", img, disp, true, true, NULL) < TOL, "dispersion");
        double e = compare("  (sensitivity: red vs C with green's eta)", img, glass, true, true, NULL);
        CHECK(e > TOL, "dispersion invisible in red (%.4f)", e);
        free(img);
        set(h, "refraction.dispersion=false");
        img = render(h);
        CHECK(compare("dispersion off: all channels green's eta", img, glass, true, true, NULL) < TOL, "dispersion off");
        free(img);
        set(h, "refraction.dispersion=true");
    }
    sl_harness_destroy(h);

    /* 5. against the sphere reference (every internal bounce) */
    h = make(scene(true, NULL), NULL);
    {
        double rms[3] = {0};
        int n = 0;
        const char *names[] = {"single", "two-interface steps=0", "two-interface steps=2"};
        float *img[3];
        set(h, "refraction.method=single");
        img[0] = render(h);
        set(h, "refraction.method=two-interface");
        set(h, "refraction.steps=0");
        img[1] = render(h);
        set(h, "refraction.steps=2");
        img[2] = render(h);
        for (int y = 2; y < H; y += 4)
            for (int x = 2; x < W; x += 4) {
                double ref[3];
                if (reference(x, y, glass, false, ref) < 0.2) continue;
                for (int k = 0; k < 3; k++) {
                    double e = img[k][((size_t)y * W + x) * 4 + 1] - ref[1];
                    rms[k] += e * e;
                }
                n++;
            }
        for (int k = 0; k < 3; k++) printf("vs the sphere reference (green, %d pixels): %s RMS %.5f\n", n, names[k], sqrt(rms[k] / n));
        int px[][2] = {{64, 64}, {80, 64}, {64, 40}, {90, 90}};
        for (int i = 0; i < 4; i++) {
            double ref[3];
            reference(px[i][0], px[i][1], glass, false, ref);
            const float *a = img[0] + ((size_t)px[i][1] * W + px[i][0]) * 4, *b = img[2] + ((size_t)px[i][1] * W + px[i][0]) * 4;
            printf("  pixel (%d, %d): reference (%.4f, %.4f)  single (%.4f, %.4f)  two-interface (%.4f, %.4f)\n", px[i][0],
                   px[i][1], ref[0], ref[1], a[0], a[1], b[0], b[1]);
        }
        CHECK(rms[2] < rms[0], "two-interface is not closer to the sphere reference than single");
        for (int k = 0; k < 3; k++) free(img[k]);
    }

    /* 6. stability and live = fresh */
    for (int i = 0; i < 3; i++) {
        const char *a[] = {"material.glass.ior=0.2", "material.glass.ior=4", "material.glass.ior_rgb=0.2,1,4"};
        set(h, a[i]);
        float *img = render(h);
        CHECK(sl_harness_count_nonfinite(img, W, H) == 0 && sl_harness_count_negative(img, W, H) == 0, "%s: non-finite or negative", a[i]);
        free(img);
    }
    set(h, "refraction.method=single");
    set(h, "refraction.dispersion=false");
    float *live = render(h);
    sl_harness_destroy(h);
    h = make(scene(true, ", \"ior_rgb\": [0.2, 1, 4]"),
             (const char *const[]){"material.glass.ior=4", "refraction.method=single", "refraction.dispersion=false", NULL});
    float *fresh = render(h);
    sl_compare cmp;
    sl_harness_compare(live, fresh, W, H, 0, &cmp);
    CHECK(cmp.max_abs == 0, "live differs from fresh: max %g", cmp.max_abs);
    sl_harness_destroy(h);

    /* 7. a scene without glass pays nothing: no back-face pass, same structure as without the plugin */
    {
        const char *json = "{\"plugins\": [\"envmap\"], \"cameras\": [{\"name\": \"main\", \"position\": [0, 0, 4], "
                           "\"target\": [0, 0, 0], \"fov_y\": 40}], \"materials\": [{\"name\": \"m\", \"model\": \"lambert\"}], "
                           "\"nodes\": [{\"name\": \"b\", \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"m\"}], "
                           "\"lights\": [], \"environment\": {\"map\": \"uv\"}}";
        sl_harness_structure with, without;
        static char names[64][128]; /* the pass names live as long as their plugins: copied */
        h = make(json, NULL);
        free(render(h));
        sl_harness_structure_of(h, &with);
        bool back = false;
        for (int i = 0; i < with.pass_count && i < 64; i++) {
            back = back || !strcmp(with.passes[i], "refraction-back");
            snprintf(names[i], sizeof names[i], "%s", with.passes[i]);
            with.passes[i] = names[i];
        }
        sl_harness_destroy(h);
        char err[4096];
        sl_harness_desc d = {.struct_size = sizeof d, .width = W, .height = H, .scene_json = json, .strict = true};
        h = sl_harness_create(&d, err, sizeof err);
        if (!h) { printf("FAIL: harness: %s\n", err); return 1; }
        free(render(h));
        sl_harness_structure_of(h, &without);
        static char names2[64][128];
        for (int i = 0; i < without.pass_count && i < 64; i++) {
            snprintf(names2[i], sizeof names2[i], "%s", without.passes[i]);
            without.passes[i] = names2[i];
        }
        sl_harness_destroy(h);
        printf("no glass: %d passes (%s), structure %s the frame without the plugin\n", with.pass_count,
               back ? "refraction-back ran" : "no refraction-back", sl_harness_structure_equal(&with, &without) ? "equals" : "differs from");
        if (!sl_harness_structure_equal(&with, &without)) {
            printf("  with: %d draws, %d passes, %d programs; without: %d draws, %d passes, %d programs\n", with.draw_calls,
                   with.pass_count, with.program_count, without.draw_calls, without.pass_count, without.program_count);
            for (int i = 0; i < with.pass_count && i < without.pass_count; i++) printf("  pass %s / %s\n", with.passes[i], without.passes[i]);
            for (int i = 0; i < with.program_count && i < without.program_count; i++)
                printf("  program %016llx / %016llx\n", (unsigned long long)with.program_hashes[i], (unsigned long long)without.program_hashes[i]);
        }
        CHECK(!back && sl_harness_structure_equal(&with, &without), "a scene without glass pays for refraction");
    }
    free(live), free(fresh), free(single_img), free(bg);

    /* The environment envmap serves (shadelab.environment/1) is the sky as it is, its sun disk
     * included, whether or not envmap lights with the sun as a light of its own
     * (envmap.sun_light): glass ignores lights, so it looks the same both ways, the sun's glint
     * reflected on its front included. */
    {
        static char json[1024];
        snprintf(json, sizeof json,
                 "{\"plugins\": [\"envmap\"],"
                 " \"cameras\": [{\"name\": \"main\", \"position\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y\": %g}],"
                 " \"materials\": [{\"name\": \"glass\", \"model\": \"dielectric\", \"ior\": 1.5}],"
                 " \"nodes\": [{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1,"
                 " \"segments\": 256, \"rings\": 128}, \"material\": \"glass\"}],"
                 " \"lights\": []}", FOV);
        const char *sky[] = {"envmap.sun_elevation=20", "envmap.sun_azimuth=10", "envmap.sun_light=true", NULL};
        sl_harness *h = make(json, sky);
        float *as_light = render(h);
        set(h, "envmap.sun_light=false");
        float *in_sky = render(h);
        sl_harness_destroy(h);
        double sum = 0, peak = 0;
        for (int i = 0; i < W * H; i++) {
            sum += fabs(as_light[i * 4 + 1] - in_sky[i * 4 + 1]);
            peak = fmax(peak, in_sky[i * 4 + 1]);
        }
        printf("glass under the sky: mean |sun_light on - off| %.2e, the glint's peak %.1f\n", sum / (W * H), peak);
        CHECK(peak > 5 && sum / (W * H) < 1e-3, "the glass sees another sky when the sun is a light");
        free(as_light), free(in_sky);
    }

    printf(failures ? "FAILED: %d\n" : "PASS\n", failures);
    return failures ? 1 : 0;
}
