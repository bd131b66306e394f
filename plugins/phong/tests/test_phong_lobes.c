/* blinn-gloss under an environment, through the lobe contract, against envmap's Monte Carlo
 * reference, which integrates blinn-gloss's own f (sl_shading_model) and uses the lobes only to
 * choose samples (README, "Lobes"). The specular lobe alone (base colour black), gloss 0.5 and
 * 0.7, a 32 × 32 unit sphere under the band environment (radiance 1, and 10 in a band of polar
 * angle: light reaches the dark parts of the sphere only through the lobe's shape), envmap's
 * split sum along the dominant direction (specular=dominant, set here: the lookup a Blinn-Phong
 * lobe is read with under every split-sum setting, so ggx is compared on the same): relative RMS over 3 × 3 block means with n·v > 0.2, within
 * ggx's bound for the same split sum (test_envmap_lobes: 0.12, ggx measured 0.105 / 0.097;
 * blinn-gloss 0.076 / 0.039). The lobe as one GGX lobe (the description before the
 * Blinn-Phong shape) measured 0.179 / 0.145 and fails. Also: the Blinn-Phong chain is prefiltered only where a material's lobes are Blinn-Phong
 * (the log of a ggx scene names none).
 *   test_phong_lobes MAP.exr   prints the same comparison under a lat-long map (no bounds):
 *                              blinn-gloss and ggx (Walter's α of the same power), gloss 0.3 / 0.5
 *                              / 0.7, specular alone (README, "Lobes"). */
#include "camera_rays.h"
#include "check.h"
#include "envmap/io.h"
#include "envmap/prefilter.h"
#include "log.h"
#include "test_tmp.h"
#include <shadelab/harness.h>
#include <stdlib.h>
#include <string.h>

#define W 32
#define H 32
#define SPECULAR_BOUND 0.12 /* ggx's, test_envmap_lobes.c SPLIT_BOUND_SPECULAR */
static float img[W * H * 4], ref[W * H * 4];
static const test_camera cam = {{0, 0, 4}, {0, 0, 0}, 40, W, H};
static char band_path[512], log_buf[1 << 16];

static const char *env_path = band_path;
static bool render(const char *material, const char *mode, int accumulate, float *out) {
    char json[4096], err[4096];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"envmap\", \"ggx\", \"phong\"],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y\": 40, \"near\": 0.1, \"far\": 100}],\n"
             " \"materials\": [{\"name\": \"m\", %s}],\n"
             " \"nodes\": [{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1, \"segments\": 256, \"rings\": 128}, \"material\": \"m\"}],\n"
             " \"environment\": {\"map\": \"%s\"}}",
             material, env_path);
    const char *settings[] = {"envmap.cube_size=64", "envmap.samples=256", "envmap.lut_size=64", "envmap.cache=false",
                              "envmap.background=false", "aa.enabled=false", "envmap.specular=dominant", mode,
                              "envmap.reference_samples=64", NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                          .scene_json = json, .settings = settings, .float32 = true,
                                                          .strict = true, .accumulate = accumulate},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "harness: %s", err);
    if (!h) return false;
    bool ok = sl_harness_render(h, out);
    CHECK(ok);
    sl_harness_destroy(h);
    return ok;
}

/* the unit sphere's pixel with n·v > min_mu */
static bool on_sphere(int x, int y, double min_mu) {
    float o[3], d[3];
    test_camera_ray(&cam, x, y, o, d);
    double b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2], c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - 1;
    if (b * b - c <= 0) return false;
    double t = -b - sqrt(b * b - c), mu = 0;
    for (int i = 0; i < 3; i++) mu -= (o[i] + t * d[i]) * d[i];
    return mu > min_mu;
}
static double block(const float *im, int px, int py, int c) {
    double s = 0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) s += im[((py + dy) * W + px + dx) * 4 + c];
    return s / 9;
}
/* relative RMS of img against ref over the 3 × 3 blocks wholly on the sphere with n·v > 0.2 */
static double relative_rms(void) {
    double sum = 0;
    int count = 0;
    for (int py = 1; py < H - 1; py += 3)
        for (int px = 1; px < W - 1; px += 3) {
            bool all = true;
            for (int k = 0; k < 9 && all; k++) all = on_sphere(px + k % 3 - 1, py + k / 3 - 1, 0.2);
            if (!all) continue;
            for (int c = 0; c < 3; c++) {
                double e = block(img, px, py, c) / block(ref, px, py, c) - 1;
                sum += e * e, count++;
            }
        }
    CHECK(count > 30);
    return sqrt(sum / (count > 0 ? count : 1));
}

static double band_fn(const double d[3]) {
    double theta = acos(fmax(-1, fmin(1, d[1])));
    return 1 + (theta >= 39 * M_PI / 128 && theta < 53 * M_PI / 128 ? 9 : 0);
}
static void write_band(void) {
    enum { LW = 256, LH = 128 };
    static float px[LW * LH * 4];
    for (int y = 0; y < LH; y++)
        for (int x = 0; x < LW; x++) {
            double d[3];
            em_latlong_dir((x + 0.5) / LW, (y + 0.5) / LH, d);
            float *p = px + (y * LW + x) * 4;
            p[0] = p[1] = p[2] = (float)band_fn(d), p[3] = 1;
        }
    char err[1024];
    CHECK_MSG(em_io_write_exr(band_path, px, LW, LH, NULL, err, sizeof err), "%s", err);
}

static void test_specular(void) {
    const double gloss[2] = {0.5, 0.7};
    for (int g = 0; g < 2; g++) {
        char mat[160];
        snprintf(mat, sizeof mat, "\"model\": \"blinn-gloss\", \"base_color\": [0, 0, 0], \"gloss\": %g", gloss[g]);
        sl_log_capture(log_buf, sizeof log_buf);
        bool ok = render(mat, "envmap.mode=split-sum", 1, img);
        sl_log_capture(NULL, 0);
        /* the chain of the contract's Blinn-Phong shape is made for this material */
        CHECK_CONTAINS(log_buf, "prefiltering the Blinn-Phong chain");
        if (!ok || !render(mat, "envmap.mode=reference", 8, ref)) continue;
        double rms = relative_rms();
        printf("band, blinn-gloss black gloss %.1f: split sum vs reference relative rms %.4f (bound %.2f)\n", gloss[g], rms,
               SPECULAR_BOUND);
        CHECK_MSG(rms < SPECULAR_BOUND, "gloss %.1f: relative rms %.4f over ggx's bound %.2f", gloss[g], rms, SPECULAR_BOUND);
    }
    /* a scene pays only for what it uses: ggx's lobes are GGX, no Blinn-Phong chain */
    sl_log_capture(log_buf, sizeof log_buf);
    render("\"model\": \"ggx\", \"base_color\": [0.5, 0.5, 0.5], \"alpha\": 0.2", "envmap.mode=split-sum", 1, img);
    sl_log_capture(NULL, 0);
    CHECK_MSG(!strstr(log_buf, "Blinn-Phong"), "a ggx scene made the Blinn-Phong chain:\n%s", log_buf);
    CHECK_CONTAINS(log_buf, "prefiltering the specular chain");
}

/* the figures under another map: both models, specular alone */
static void measure_map(void) {
    const double gloss[3] = {0.3, 0.5, 0.7};
    for (int g = 0; g < 3; g++) {
        double p = exp2(12 * gloss[g]);
        char mats[2][256];
        snprintf(mats[0], sizeof mats[0], "\"model\": \"blinn-gloss\", \"base_color\": [0, 0, 0], \"gloss\": %g", gloss[g]);
        snprintf(mats[1], sizeof mats[1], "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 0, "
                 "\"base_color\": [0, 0, 0], \"alpha\": %g", sqrt(2 / (p + 2)));
        for (int m = 0; m < 2; m++)
            if (render(mats[m], "envmap.mode=split-sum", 1, img) && render(mats[m], "envmap.mode=reference", 16, ref))
                printf("%s: %s black gloss %.1f: split sum vs reference relative rms %.4f\n", env_path,
                       m ? "ggx        " : "blinn-gloss", gloss[g], relative_rms());
    }
}

int main(int argc, char **argv) {
    if (argc > 1) {
        env_path = argv[1];
        measure_map();
        return check_result();
    }
    /* envmap's C twin of the contract's power (the Blinn-Phong chain's levels): the inverse of
     * Blinn's median α, √(2^(2/(p+2)) − 1) */
    for (double p = 1; p < 1e5; p *= 3) {
        double a = sqrt(exp2(2 / (p + 2)) - 1);
        CHECK_MSG(fabs(em_blinn_power(a) / p - 1) < 1e-6, "em_blinn_power(%g) = %g, not %g", a, em_blinn_power(a), p);
    }
    snprintf(band_path, sizeof band_path, "%s/band.exr", sl_test_dir());
    write_band();
    test_specular();
    return check_result();
}
