/* envmap lights every shading model through the lobe contract (issue 41; sl_model_lobes): the
 * split sum, built from a model's lobes, against the Monte Carlo reference, which integrates the
 * model's own f (sl_shading_model) and uses the lobes only to choose samples. 32 × 32 images of
 * a unit sphere under the band environment (1, and 10 in a band of polar angle), 3 × 3 block
 * means over the sphere (n·v > 0.2):
 *   blinn-gloss (phong plugin, gloss 0.3 / 0.5 / 0.7) and ggx (glTF dielectric, the same α),
 *   coloured (diffuse + specular: one bound for both) and black (the specular lobe alone: the
 *   bounds below); the figures are printed.
 *   furnace: a uniform environment 1 and blinn-gloss: the reference gives the model's
 *   directional albedo, (1 − F)·albedo + F·k_s·R(μ), R(μ) = ∫ (p+1)/(2π)(n·h)^p (n·l) dl
 *   integrated here in C (a closed form at the sphere centre is not available; the midpoint
 *   quadrature over the hemisphere is independent of the GLSL); then black blinn-gloss spheres
 *   at gloss 0.3 / 0.5 / 0.7, split sum against that reference (the lobe's weight alone). */
#include "check.h"
#include "camera_rays.h"
#include "envmap/io.h"
#include "envmap/prefilter.h"
#include "test_tmp.h"
#include <shadelab/harness.h>
#include <stdlib.h>
#include <string.h>

#define W 32
#define H 32
/* relative RMS of the split sum (envmap's default specular, fitted; a Blinn-Phong lobe reads its
 * chain along the dominant direction) vs the reference (block means), margin over what was
 * measured (phong README, "Lobes"): with a diffuse albedo both models share one bound (measured
 * 0.007–0.010); the specular lobe alone (black), one bound for both: ggx 0.043–0.052 (0.083–0.105
 * under specular=dominant: the split sum's own error), blinn-gloss 0.049 / 0.076 / 0.039 at gloss
 * 0.3 / 0.5 / 0.7 (a Blinn-Phong lobe, ABI 1.19: envmap's Blinn-Phong chain read at power p/n·v;
 * described as one GGX lobe of Blinn's median α it measured 0.085 / 0.179 / 0.145) */
#define SPLIT_BOUND 0.03
#define SPLIT_BOUND_SPECULAR 0.12
/* a uniform environment (the lobe's weight alone): blinn-gloss's lobe carries the model's
 * directional albedo (measured 0.4–0.8 % relative RMS; the centre-of-lobe weight 10.6 / 4.3 /
 * 1.0 % at gloss 0.3 / 0.5 / 0.7) */
#define FURNACE_BOUND 0.02
static float img[W * H * 4], ref[W * H * 4];
static const test_camera cam = {{0, 0, 4}, {0, 0, 0}, 40, W, H};
static char dir[256];

static sl_harness *make(const char *map, const char *material, const char *mode, int accumulate) {
    char json[4096], err[4096];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"envmap\", \"ggx\", \"phong\"],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y\": 40, \"near\": 0.1, \"far\": 100}],\n"
             " \"materials\": [{\"name\": \"m\", %s}],\n"
             " \"nodes\": [{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1, \"segments\": 256, \"rings\": 128}, \"material\": \"m\"}],\n"
             " \"environment\": {\"map\": \"%s\"}}",
             material, map);
    const char *settings[] = {"envmap.cube_size=64", "envmap.samples=256", "envmap.lut_size=64", "envmap.cache=false",
                              "envmap.background=false", "aa.enabled=false", mode, "envmap.reference_samples=64", NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                          .scene_json = json, .settings = settings, .float32 = true,
                                                          .strict = true, .accumulate = accumulate},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "harness: %s", err);
    return h;
}

static bool sphere_pixel(int x, int y, double n[3], double v[3], double min_mu) {
    float o[3], d[3];
    test_camera_ray(&cam, x, y, o, d);
    double b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2], c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - 1;
    double disc = b * b - c;
    if (disc <= 0) return false;
    double t = -b - sqrt(disc), l = 0;
    for (int i = 0; i < 3; i++) n[i] = o[i] + t * d[i], v[i] = -d[i], l += n[i] * n[i];
    for (int i = 0; i < 3; i++) n[i] /= sqrt(l);
    return n[0] * v[0] + n[1] * v[1] + n[2] * v[2] > min_mu;
}

typedef double (*env_fn)(const double d[3]);
static void write_latlong(const char *path, int w, int h, env_fn f) {
    float *px = malloc((size_t)w * h * 16);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double d[3];
            em_latlong_dir((x + 0.5) / w, (y + 0.5) / h, d);
            float c = (float)f(d);
            float *p = px + ((size_t)y * w + x) * 4;
            p[0] = p[1] = p[2] = c, p[3] = 1;
        }
    char err[1024];
    CHECK_MSG(em_io_write_exr(path, px, w, h, NULL, err, sizeof err), "%s", err);
    free(px);
}
static double one_fn(const double d[3]) { (void)d; return 1; }
static double band_fn(const double d[3]) {
    double theta = acos(fmax(-1, fmin(1, d[1])));
    return 1 + (theta >= 39 * M_PI / 128 && theta < 53 * M_PI / 128 ? 9 : 0);
}

static bool render(const char *map, const char *material, const char *mode, int accumulate, float *out) {
    sl_harness *h = make(map, material, mode, accumulate);
    if (!h) return false;
    bool ok = sl_harness_render(h, out);
    CHECK(ok);
    sl_harness_destroy(h);
    return ok;
}

static double block(const float *im, int px, int py, int c) {
    double s = 0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) s += im[((py + dy) * W + px + dx) * 4 + c];
    return s / 9;
}

/* relative RMS and max of split vs reference over 3 × 3 blocks wholly on the sphere (n·v > 0.2) */
static void compare(const char *what, double *rms_out) {
    double rms = 0, worst = 0, mean = 0;
    int count = 0;
    for (int py = 1; py < H - 1; py += 3)
        for (int px = 1; px < W - 1; px += 3) {
            bool all = true;
            for (int dy = -1; dy <= 1 && all; dy++)
                for (int dx = -1; dx <= 1 && all; dx++) {
                    double n[3], v[3];
                    all = sphere_pixel(px + dx, py + dy, n, v, 0.2);
                }
            if (!all) continue;
            for (int c = 0; c < 3; c++) {
                double r = block(ref, px, py, c), e = block(img, px, py, c) / r - 1;
                rms += e * e, mean += e, worst = fmax(worst, fabs(e)), count++;
            }
        }
    rms = sqrt(rms / count);
    printf("%-40s split sum vs reference, %d block channels: relative rms %.4f, mean %+.4f, max %.4f\n", what, count, rms,
           mean / count, worst);
    CHECK(count > 30);
    *rms_out = rms;
}

static void test_band(void) {
    char path[512];
    snprintf(path, sizeof path, "%s/band.exr", dir);
    write_latlong(path, 256, 128, band_fn);
    const double gloss[] = {0.3, 0.5, 0.7};
    /* coloured: diffuse + specular; black: the specular lobe alone (the contract's hard part) */
    const char *colours[2] = {"[0.7, 0.5, 0.3]", "[0, 0, 0]"};
    for (int k = 0; k < 2; k++)
    for (int g = 0; g < 3; g++) {
        double p = exp2(12 * gloss[g]), alpha = sqrt(2 / (p + 2));
        char phong[256], ggx[256], what[128];
        snprintf(phong, sizeof phong, "\"model\": \"blinn-gloss\", \"base_color\": %s, \"gloss\": %g", colours[k], gloss[g]);
        snprintf(ggx, sizeof ggx,
                 "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 0, \"base_color\": %s, "
                 "\"alpha\": %g", colours[k], alpha);
        const char *mats[2] = {phong, ggx};
        for (int m = 0; m < 2; m++) {
            if (!render(path, mats[m], "envmap.mode=reference", 16, ref)) continue;
            if (!render(path, mats[m], "envmap.mode=split-sum", 1, img)) continue;
            snprintf(what, sizeof what, "band %s %s gloss %.1f (alpha %.3f)", m ? "ggx        " : "blinn-gloss", k ? "black " : "colour",
                     gloss[g], alpha);
            double rms;
            compare(what, &rms);
            double bound = !k ? SPLIT_BOUND : SPLIT_BOUND_SPECULAR;
            CHECK_MSG(rms < bound, "%s: rms %.4f over the bound %.3f", what, rms, bound);
        }
    }
}

/* R(μ) = ∫ (p+1)/(2π)(n·h)^p (n·l) dl over the hemisphere of l, n = +z, v in the xz plane */
static double blinn_albedo(double mu, double p) {
    const int NT = 400, NP = 200;
    double v[3] = {sqrt(1 - mu * mu), 0, mu}, sum = 0;
    for (int i = 0; i < NT; i++) {
        double th = (i + 0.5) * (M_PI / 2) / NT;
        for (int j = 0; j < NP; j++) {
            double ph = (j + 0.5) * 2 * M_PI / NP;
            double l[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)}, h[3], len = 0;
            for (int k = 0; k < 3; k++) h[k] = l[k] + v[k], len += h[k] * h[k];
            double ndh = h[2] / sqrt(len);
            sum += (p + 1) / (2 * M_PI) * pow(ndh, p) * l[2] * sin(th);
        }
    }
    return sum * (M_PI / 2 / NT) * (2 * M_PI / NP);
}

static void test_furnace(void) {
    char path[512];
    snprintf(path, sizeof path, "%s/one.exr", dir);
    write_latlong(path, 64, 32, one_fn);
    const char *mat = "\"model\": \"blinn-gloss\", \"base_color\": [0.7, 0.5, 0.3], \"gloss\": 0.5";
    if (!render(path, mat, "envmap.mode=reference", 16, ref)) return;
    /* the sphere centre pixel: n = v, μ = 1 (up to the pixel's offset) */
    int cx = W / 2, cy = H / 2;
    double n[3], v[3];
    CHECK(sphere_pixel(cx, cy, n, v, 0.9));
    double mu = n[0] * v[0] + n[1] * v[1] + n[2] * v[2], m5 = pow(1 - mu, 5), F = 0.04 + 0.96 * m5;
    double R = blinn_albedo(mu, 64), want = (1 - F) * 0.7 + F * R;
    double got = ref[(cy * W + cx) * 4];
    printf("furnace blinn-gloss gloss 0.5, mu %.4f: reference %.4f, C quadrature of the model %.4f (R = %.4f)\n", mu, got,
           want, R);
    CHECK_MSG(fabs(got / want - 1) < 0.01, "furnace: %.4f vs %.4f", got, want);
    /* the lobe's weight alone (no environment detail): the specular lobe's split sum vs the
     * reference in the furnace, per gloss: the weight gives the model's directional albedo */
    const double gloss[] = {0.3, 0.5, 0.7};
    for (int g = 0; g < 3; g++) {
        char black[160], what[96];
        snprintf(black, sizeof black, "\"model\": \"blinn-gloss\", \"base_color\": [0, 0, 0], \"gloss\": %g", gloss[g]);
        if (!render(path, black, "envmap.mode=reference", 16, ref) || !render(path, black, "envmap.mode=split-sum", 1, img)) continue;
        snprintf(what, sizeof what, "furnace blinn-gloss black gloss %.1f", gloss[g]);
        double rms;
        compare(what, &rms);
        CHECK_MSG(rms < FURNACE_BOUND, "%s: rms %.4f over the bound %.2f", what, rms, FURNACE_BOUND);
    }
}

/* A clear coat's own normal (KHR_materials_clearcoat's clearcoatNormalTexture; lobe normals, ABI
 * 1.26): a black metal (no base lobe) under a full coat of roughness 0.3 whose normal texture
 * tilts it by 15° along the tangent, in the band environment. The split sum must integrate the coat
 * about that normal, as the reference does (it evaluates the model's own f, which follows the coat
 * normal). Measured: 0.26 relative RMS; integrated about the surface's normal instead (before 1.26)
 * 0.54; a base lobe tilted by the same texture through normal-map 0.18 (the split sum's own error
 * where a shading normal leans from the geometric one: the reference cuts its light at the
 * geometric horizon); flat, 0.09. The flat coat's split sum against the tilted reference: 0.29 (the
 * tilt must show). */
#define COAT_TILT_BOUND 0.35
#define COAT_TILT_MIN_CHANGE 0.2
static void test_coat_normal(void) {
    char path[512];
    snprintf(path, sizeof path, "%s/band.exr", dir);
    write_latlong(path, 256, 128, band_fn);
    const char *coat = "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 1, \"base_color\": [0, 0, 0], "
                       "\"clearcoat\": 1, \"clearcoat_roughness\": 0.3, \"clearcoat_normal_map\": \"constant:%s\"";
    char tilted[512], flat[512];
    /* (sin 15°, 0, cos 15°) encoded as (n + 1)/2 */
    snprintf(tilted, sizeof tilted, coat, "0.629410,0.5,0.982963");
    snprintf(flat, sizeof flat, coat, "0.5,0.5,1");
    if (!render(path, tilted, "envmap.mode=reference", 16, ref) || !render(path, tilted, "envmap.mode=split-sum", 1, img)) return;
    double rms;
    compare("band, clear coat tilted 15 deg", &rms);
    CHECK_MSG(rms < COAT_TILT_BOUND, "the tilted coat: rms %.4f over the bound %.3f", rms, COAT_TILT_BOUND);
    /* the flat coat's split sum against the tilted coat's reference: the tilt is there to see */
    if (!render(path, flat, "envmap.mode=split-sum", 1, img)) return;
    double change;
    compare("band, clear coat flat vs the tilted reference", &change);
    CHECK_MSG(change > COAT_TILT_MIN_CHANGE, "the coat's tilt changes the image by only %.4f", change);
}

int main(void) {
    snprintf(dir, sizeof dir, "%s", sl_test_dir());
    test_furnace();
    test_band();
    test_coat_normal();
    return check_result();
}
