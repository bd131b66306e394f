/* envmap end to end, on OSMesa through the harness: every environment is generated here (no
 * data files), written with the plugin's own writer, and loaded through the scene.
 *   furnace      white Lambert → 1 within 1% (SH and convolved); ggx with F = 1 → E(μ, α)
 *                integrated in C within 2%, nothing above 1; multiple scattering → 1; the Monte
 *                Carlo reference → E(μ, α)
 *   facing away  a normal map turning every normal away from the viewer, bent back by
 *                normal-map's guard: the split sum agrees with the reference, nothing blows up
 *   linear       L = 1 + ω_y: white Lambert → 1 + ⅔ n_y within 2% (both irradiance methods)
 *   convention   a colour-coded map (colour = 0.5 + 0.5·direction) on mirror and environment
 *                spheres and the background, as lat-long, cube cross (EXR and RGBE8 PNG from
 *                shadelab-cube) and six face files; yaw turns it
 *   probe        a marked quadrant of a lat-long at the pixels the convention puts it (on paper),
 *                on a mirror sphere and in the background
 *   bad input    NaN/Inf/negative texels: finite output, one warning naming file and count
 *   chains       a shadelab-cube --ggx chain loads and matches the plugin's own prefilter
 *   cache        the second load reads the disk cache and renders the same image
 *   cost         a mirror-only scene never prefilters; envmap disabled changes no program
 *   mirror sun   the sky's sun seen in a mirror floor carries the disk's energy, E = 3, within 2 %
 *   constant     a colour as the environment: the general path's image from a "constant:" map,
 *                nothing prefiltered
 *   poles        looking straight up and down at a lat-long: finite and smooth */
#include "check.h"
#include "camera_rays.h"
#include "envmap/io.h"
#include "envmap/prefilter.h"
#include "ggx_ref.h"
#include "log.h"
#include "test_tmp.h"
#include <shadelab/harness.h>
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define W 64
#define H 64
static float img[W * H * 4], img2[W * H * 4];
static const test_camera cam = {{0, 0, 4}, {0, 0, 0}, 40, W, H};
static char dir[256];
static char logbuf[1 << 16];

static void normalize3(double v[3]) {
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++) v[i] /= l;
}

/* A unit sphere at the origin with material `mat` (JSON keys), the environment `env` (the JSON
 * object's keys), seen from (0, 0, 4) with a vertical field of view of `fov_y` degrees (`cam`'s 40
 * but where a test zooms in) in a `size`² image (at most W); `more_plugins` (JSON list items after
 * "envmap", "" for none) loads others. */
static sl_harness *make_env(const char *more_plugins, double fov_y, int size, const char *env, const char *mat,
                            const char *const *settings, int accumulate) {
    char json[4096], err[4096];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"envmap\"%s],\n"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y\": %g, \"near\": 0.1, \"far\": 100}],\n"
             " \"materials\": [{\"name\": \"m\", %s}],\n"
             " \"nodes\": [{\"name\": \"ball\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 1, \"segments\": 128, \"rings\": 64}, \"material\": \"m\"}],\n"
             " \"environment\": {%s}}",
             more_plugins, fov_y, mat, env);
    const char *base[24];
    int n = 0;
    base[n++] = "envmap.cube_size=16";
    base[n++] = "envmap.samples=128";
    base[n++] = "envmap.lut_size=32";
    base[n++] = "envmap.cache=false";
    for (const char *const *s = settings; s && *s && n < 23; s++) base[n++] = *s;
    base[n] = NULL;
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = size, .height = size,
                                                          .scene_json = json, .settings = base, .float32 = true,
                                                          .strict = true, .accumulate = accumulate},
                                      err, sizeof err);
    if (!h) fprintf(stderr, "harness: %s\n", err);
    return h;
}
/* make_env with the given environment map (NULL: none) */
static sl_harness *make_with(const char *more_plugins, double fov_y, const char *map, const char *mat,
                             const char *const *settings, int accumulate) {
    char env[1024] = "";
    if (map) snprintf(env, sizeof env, "\"map\": \"%s\"", map);
    return make_env(more_plugins, fov_y, W, env, mat, settings, accumulate);
}
static sl_harness *make(const char *map, const char *mat, const char *const *settings, int accumulate) {
    return make_with("", 40, map, mat, settings, accumulate);
}

/* Pixel (x, y) on the sphere: normal and view; false on the background or near the rim. */
static bool sphere_pixel(int x, int y, double n[3], double v[3], double min_mu) {
    float o[3], d[3];
    test_camera_ray(&cam, x, y, o, d);
    double b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2], c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - 1;
    double disc = b * b - c;
    if (disc <= 0) return false;
    double t = -b - sqrt(disc);
    for (int i = 0; i < 3; i++) n[i] = o[i] + t * d[i], v[i] = -d[i];
    normalize3(n);
    return n[0] * v[0] + n[1] * v[1] + n[2] * v[2] > min_mu;
}
static bool background_pixel(int x, int y, double d[3]) {
    float o[3], df[3];
    test_camera_ray(&cam, x, y, o, df);
    double b = o[0] * df[0] + o[1] * df[1] + o[2] * df[2], c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - 1;
    for (int i = 0; i < 3; i++) d[i] = df[i];
    return b * b - c < -0.05; /* clearly off the sphere */
}

/* ---------------------------------------------------------------- environments as files */

typedef void (*env_fn)(const double d[3], double out[3]);
static void write_latlong(const char *path, int w, int h, env_fn f) {
    float *px = malloc((size_t)w * h * 16);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double d[3], c[3] = {0, 0, 0}, s = 0;
            for (int j = 0; j < 4; j++)
                for (int i = 0; i < 4; i++) { /* solid-angle-weighted texel mean */
                    double v = (y + (j + 0.5) / 4) / h, cc[3];
                    em_latlong_dir((x + (i + 0.5) / 4) / w, v, d);
                    f(d, cc);
                    for (int q = 0; q < 3; q++) c[q] += cc[q] * sin(v * M_PI);
                    s += sin(v * M_PI);
                }
            for (int q = 0; q < 3; q++) px[((size_t)y * w + x) * 4 + q] = (float)(c[q] / s);
            px[((size_t)y * w + x) * 4 + 3] = 1;
        }
    char err[1024];
    if (!em_io_write_exr(path, px, w, h, NULL, err, sizeof err)) fprintf(stderr, "%s\n", err);
    free(px);
}
static void one_fn(const double d[3], double out[3]) { out[0] = out[1] = out[2] = 1; }
static void linear_fn(const double d[3], double out[3]) { out[0] = out[1] = out[2] = 1 + d[1]; }
static void colour_fn(const double d[3], double out[3]) {
    for (int i = 0; i < 3; i++) out[i] = 0.5 + 0.5 * d[i];
}

static int run(const char *cmd) {
    int rc = system(cmd);
    if (rc) fprintf(stderr, "command failed (%d): %s\n", rc, cmd);
    return rc;
}

/* ---------------------------------------------------------------- furnace */

/* E(mu, alpha) from ref_albedo tabulated in mu (smooth: linear interpolation is exact to 1e-5). */
static double albedo_table[257];
static double table_alpha = -1;
static double albedo(double mu, double a) {
    if (a != table_alpha) {
        for (int i = 0; i <= 256; i++) albedo_table[i] = ref_albedo(fmax(i / 256.0, 1e-3), a);
        table_alpha = a;
    }
    double x = fmin(fmax(mu, 0), 1) * 256;
    int i = (int)fmin(x, 255);
    return albedo_table[i] + (x - i) * (albedo_table[i + 1] - albedo_table[i]);
}

static void test_furnace(void) {
    char constant[512];
    snprintf(constant, sizeof constant, "%s/one.exr", dir);
    write_latlong(constant, 64, 32, one_fn);
    const char *maps[2] = {"constant:1,1,1", constant};
    const char *irr[2] = {"envmap.irradiance=sh", "envmap.irradiance=convolved"};
    for (int m = 0; m < 2; m++)
        for (int k = 0; k < 2; k++) {
            sl_harness *h = make(maps[m], "\"model\": \"lambert\", \"base_color\": [1, 1, 1]", (const char *[]){irr[k], NULL}, 1);
            CHECK(h && sl_harness_render(h, img));
            double worst = 0;
            for (int i = 0; i < W * H; i++)
                for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(img[i * 4 + c] - 1));
            printf("furnace, white Lambert, %s, %s: max |L - 1| = %.4f\n", m ? "EXR file" : "constant:1,1,1", irr[k], worst);
            CHECK_MSG(worst < 0.01, "white furnace off by %.4f", worst);
            sl_harness_destroy(h);
        }
    /* ggx with F = 1 (metallic-roughness, metallic 1, white): the directional albedo */
    const double alphas[5] = {0.0, 0.05, 0.2, 0.5, 1.0}; /* 0: clamped to GGX_MIN_ALPHA, a mirror */
    for (int a = 0; a < 5; a++) {
        char mat[256], alpha[64];
        snprintf(mat, sizeof mat, "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 1, \"base_color\": [1, 1, 1], \"alpha\": %g", alphas[a]);
        for (int mode = 0; mode < 3; mode++) { /* split sum, + multiple scattering, reference */
            const char *s0 = mode == 1 ? "envmap.multiscatter=true" : mode == 2 ? "envmap.mode=reference" : "envmap.multiscatter=false";
            snprintf(alpha, sizeof alpha, "envmap.reference_samples=%d", 64);
            sl_harness *h = make(constant, mat, (const char *[]){s0, alpha, NULL}, mode == 2 ? 4 : 1);
            CHECK(h && sl_harness_render(h, img));
            double worst = 0, mean = 0, over = 0;
            int count = 0;
            for (int y = 0; y < H; y++)
                for (int x = 0; x < W; x++) {
                    double n[3], v[3];
                    for (int c = 0; c < 3; c++) over = fmax(over, img[(y * W + x) * 4 + c]);
                    if (!sphere_pixel(x, y, n, v, 0.2)) continue;
                    double mu = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
                    double want = mode == 1 ? 1.0 : albedo(mu, fmax(alphas[a], 2e-3));
                    double rel = fabs(img[(y * W + x) * 4] / want - 1);
                    worst = fmax(worst, rel);
                    mean += rel;
                    count++;
                }
            mean /= count;
            printf("furnace, ggx F = 1, alpha %.2f, %-13s: %d pixels (n.v > 0.2), max rel. error %.4f, mean %.4f, max value %.4f\n",
                   alphas[a], mode == 0 ? "split sum" : mode == 1 ? "multiscatter" : "reference", count, worst, mean, over);
            CHECK(count > 500);
            CHECK(sl_harness_count_nonfinite(img, W, H) == 0); /* the grazing rim included */
            if (mode == 2) CHECK_MSG(mean < 0.01 && worst < 0.06, "reference: mean %.4f max %.4f", mean, worst);
            else CHECK_MSG(worst < 0.02, "alpha %.2f: %.4f", alphas[a], worst);
            CHECK_MSG(over <= 1.0 + 1e-3, "energy gained: %.4f", over); /* nothing above the furnace */
            sl_harness_destroy(h);
        }
    }
}

/* A normal-mapped ggx sphere whose every mapped normal faces away from the viewer (object-space
 * constant map n = −Z, camera on +Z): normal-map bends each back until its reflection rises
 * just above the surface (Cycles' convention; a normal below the surface is first laid onto
 * it), so both integrators shade the same valid normal, whose specular lobe the geometric
 * horizon cuts (the split sum fades its lookup there, the reference blocks each sample: they
 * differ by 0.020 on average, 0.072 at most). In the white furnace the split sum agrees with
 * the Monte Carlo reference within that, and nothing exceeds k_d + 1 = 1.5 (F exact, k_s = 1):
 * a split sum that shaded an unguarded normal at n·v → 0 would blow up. */
static void test_facing_away(void) {
    const char *mat = "\"model\": \"ggx\", \"alpha\": 0.3, \"specular\": 1, \"base_color\": [0.5, 0.5, 0.5], "
                      "\"normal_map\": \"constant:0.5,0.5,0\", \"normal_space\": \"object\"";
    static float modes[2][W * H * 4];
    for (int mode = 0; mode < 2; mode++) {
        sl_harness *h = make_with(", \"normal-map\"", 40, "constant:1,1,1", mat,
                                  (const char *[]){mode ? "envmap.mode=reference" : "envmap.mode=split-sum", NULL}, 1);
        CHECK(h && sl_harness_render(h, modes[mode]));
        CHECK(sl_harness_count_nonfinite(modes[mode], W, H) == 0);
        sl_harness_destroy(h);
    }
    double worst = 0, mean = 0, lo = 1e9, hi = 0;
    int count = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double n[3], v[3];
            if (!sphere_pixel(x, y, n, v, 0.2)) continue;
            for (int c = 0; c < 3; c++) {
                double s = modes[0][(y * W + x) * 4 + c], r = modes[1][(y * W + x) * 4 + c];
                worst = fmax(worst, fabs(s - r));
                mean += fabs(s - r) / 3;
                lo = fmin(lo, fmin(s, r)), hi = fmax(hi, fmax(s, r));
            }
            count++;
        }
    mean /= count;
    printf("furnace, ggx with a normal map facing away: %d pixels in [%.4f, %.4f], split sum - reference: max %.4f, mean %.4f\n",
           count, lo, hi, worst, mean);
    CHECK(count > 500);
    CHECK_MSG(lo > 0 && hi < 1.5, "facing-away normals: values in [%.4f, %.4f]", lo, hi);
    CHECK_MSG(worst < 0.1 && mean < 0.03, "split sum against the reference: max %.4f, mean %.4f", worst, mean);
}

/* ---------------------------------------------------------------- direction of the lobe */

/* A small disk next to the view direction at the centre of the sphere (n = v = +Z): the
 * reference must integrate the exact BRDF over it, ∫_disk D G1(v) G1(l)/(4 n·v) dl with F = 1,
 * computed here in C; the split sum must come close (its n = v = r assumption is exact here
 * apart from dropping G). A sampler pointing its lobe the wrong way fails. */
static double disk_dir[3];
static const double disk_cos = 0.99619469809; /* cos 5° */
static void small_disk_fn(const double d[3], double out[3]) {
    double c = d[0] * disk_dir[0] + d[1] * disk_dir[1] + d[2] * disk_dir[2];
    out[0] = out[1] = out[2] = c >= disk_cos ? 10.0 : 0.1;
}

static void test_lobe(void) {
    const double a = 0.1, off = 9 * M_PI / 180;
    disk_dir[0] = sin(off), disk_dir[1] = 0, disk_dir[2] = cos(off);
    char path[512];
    snprintf(path, sizeof path, "%s/small_disk.exr", dir);
    write_latlong(path, 1024, 512, small_disk_fn);
    /* C: the disk's share, on a polar grid around its centre */
    double t[3] = {0, 1, 0}, b[3] = {disk_dir[2], 0, -disk_dir[0]}, s = 0, rmax = acos(disk_cos);
    int nr = 200, np = 400;
    for (int i = 0; i < nr; i++)
        for (int j = 0; j < np; j++) {
            double th = (i + 0.5) / nr * rmax, ph = 2 * M_PI * (j + 0.5) / np, l[3], h[3];
            for (int q = 0; q < 3; q++) l[q] = cos(th) * disk_dir[q] + sin(th) * (cos(ph) * t[q] + sin(ph) * b[q]);
            for (int q = 0; q < 3; q++) h[q] = l[q] + (q == 2);
            normalize3(h);
            s += ref_ggx_D(h[2], a) * ref_ggx_G1(1, h[2], a) * ref_ggx_G1(l[2], l[0] * h[0] + l[1] * h[1] + l[2] * h[2], a) / 4 *
                 sin(th);
        }
    s *= (rmax / nr) * (2 * M_PI / np);
    double want = 0.1 * ref_albedo(1, a) + (10 - 0.1) * s;
    const char *mat = "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 1, \"base_color\": [1, 1, 1], \"alpha\": 0.1";
    char env[600];
    snprintf(env, sizeof env, "\"map\": \"%s\"", path);
    double got[2];
    for (int mode = 0; mode < 2; mode++) {
        /* the four centre pixels of `cam`'s 64² view (n within 1.5° of +Z) as an 8² image zoomed in
         * 8× (the reference's cost is per pixel) */
        const int n = 8;
        sl_harness *h = make_env("", 2 * atan(tan(20 * M_PI / 180) * n / W) * 180 / M_PI, n, env, mat,
                                 (const char *[]){mode ? "envmap.mode=reference" : "envmap.mode=split-sum",
                                                  "envmap.reference_samples=256", "envmap.cube_size=128", "envmap.samples=512",
                                                  NULL}, mode ? 8 : 1);
        CHECK(h && sl_harness_render(h, img));
        got[mode] = 0;
        for (int y = n / 2 - 1; y <= n / 2; y++)
            for (int x = n / 2 - 1; x <= n / 2; x++) got[mode] += img[(y * n + x) * 4] / 4;
        sl_harness_destroy(h);
    }
    printf("lobe direction: disk 9° off the view at the sphere centre, alpha 0.1: C integral %.4f, reference %.4f "
           "(%+.1f%%), split sum %.4f (%+.1f%%)\n", want, got[1], 100 * (got[1] / want - 1), got[0], 100 * (got[0] / want - 1));
    CHECK_MSG(fabs(got[1] / want - 1) < 0.03, "reference %.4f vs %.4f", got[1], want);
    CHECK_MSG(fabs(got[0] / want - 1) < 0.15, "split sum %.4f vs %.4f", got[0], want);
}

/* ---------------------------------------------------------------- the reference under a sun */

/* The Monte Carlo reference must converge where a small, very bright source dominates (issue 42):
 * a 4° disk of radiance 1000 on a background of 0.1. With environment importance sampling and
 * MIS a few samples find the disk; BRDF sampling alone hits it with probability ≈ Ω·cos/π ≈ 0.5 %
 * per cosine sample. Closed forms at every 2nd pixel of the sphere, 4 frames × 16 samples:
 *   white Lambert   E/π = bg + (L − bg) sin²ρ cos θ (the disk wholly above the horizon,
 *                   θ ≤ 90° − ρ − 2°), bg where it is wholly below (θ ≥ 90° + ρ + 2°);
 *   white metal α = 0.3 (F = 1)  bg·E(μ, α) + (L − bg) ∫_disk D G1(v) G1(l) / (4 n·v) dl, the
 *                   integral on a 24 × 48 polar grid over the disk in C (ggx_ref.h). */
static double ref_sun_dir[3], ref_sun_radius, ref_sun_L, ref_sun_bg; /* set by each test */
static void ref_sun_fn(const double d[3], double out[3]) {
    double c = d[0] * ref_sun_dir[0] + d[1] * ref_sun_dir[1] + d[2] * ref_sun_dir[2];
    out[0] = out[1] = out[2] = c >= cos(ref_sun_radius) ? ref_sun_L : ref_sun_bg;
}
static double disk_ggx(const double n[3], const double v[3], double a) {
    double t[3] = {0, 1, 0}, b[3], nv = n[0] * v[0] + n[1] * v[1] + n[2] * v[2], sum = 0;
    double *s = ref_sun_dir;
    /* t ⟂ s: y minus its component along s */
    for (int q = 0; q < 3; q++) t[q] -= s[1] * s[q];
    normalize3(t);
    b[0] = s[1] * t[2] - s[2] * t[1], b[1] = s[2] * t[0] - s[0] * t[2], b[2] = s[0] * t[1] - s[1] * t[0];
    int nr = 24, np = 48;
    for (int i = 0; i < nr; i++)
        for (int j = 0; j < np; j++) {
            double th = (i + 0.5) / nr * ref_sun_radius, ph = 2 * M_PI * (j + 0.5) / np, l[3], h[3];
            for (int q = 0; q < 3; q++) l[q] = cos(th) * s[q] + sin(th) * (cos(ph) * t[q] + sin(ph) * b[q]);
            double nl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
            if (nl <= 0) continue;
            for (int q = 0; q < 3; q++) h[q] = l[q] + v[q];
            normalize3(h);
            double nh = n[0] * h[0] + n[1] * h[1] + n[2] * h[2], vh = v[0] * h[0] + v[1] * h[1] + v[2] * h[2];
            sum += ref_ggx_D(nh, a) * ref_ggx_G1(nv, vh, a) * ref_ggx_G1(nl, vh, a) / (4 * nv) * sin(th);
        }
    return sum * (ref_sun_radius / nr) * (2 * M_PI / np);
}
static void test_reference_sun(void) {
    ref_sun_radius = 4 * M_PI / 180, ref_sun_L = 1000, ref_sun_bg = 0.1;
    ref_sun_dir[0] = 0.45, ref_sun_dir[1] = 0.55, ref_sun_dir[2] = 0.7;
    normalize3(ref_sun_dir);
    char path[512];
    snprintf(path, sizeof path, "%s/ref_sun.exr", dir);
    write_latlong(path, 512, 256, ref_sun_fn);
    const char *mats[2] = {"\"model\": \"lambert\", \"base_color\": [1, 1, 1]",
                           "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 1, \"base_color\": [1, 1, 1], \"alpha\": 0.3"};
    const double s2 = sin(ref_sun_radius) * sin(ref_sun_radius);
    for (int m = 0; m < 2; m++) {
        sl_harness *h = make(path, mats[m], (const char *[]){"envmap.mode=reference", "envmap.reference_samples=16", NULL}, 4);
        CHECK(h && sl_harness_render(h, img));
        double se = 0, sum_got = 0, sum_want = 0;
        int count = 0;
        for (int y = 0; y < H; y += 2)
            for (int x = 0; x < W; x += 2) {
                double n[3], v[3], want;
                if (!sphere_pixel(x, y, n, v, 0.2)) continue;
                double c = n[0] * ref_sun_dir[0] + n[1] * ref_sun_dir[1] + n[2] * ref_sun_dir[2];
                double limit = sin(ref_sun_radius + 2 * M_PI / 180);
                if (m == 0) {
                    if (c >= limit) want = ref_sun_bg + (ref_sun_L - ref_sun_bg) * s2 * c;
                    else if (c <= -limit) want = ref_sun_bg;
                    else continue;
                } else {
                    double mu = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
                    want = ref_sun_bg * ref_albedo(mu, 0.3) + (ref_sun_L - ref_sun_bg) * disk_ggx(n, v, 0.3);
                }
                double got = img[(y * W + x) * 4 + 1];
                se += (got - want) * (got - want), sum_got += got, sum_want += want;
                count++;
            }
        double rel_rms = sqrt(se / count) / (sum_want / count), rel_mean = sum_got / sum_want - 1;
        printf("reference under a 4° sun of 1000 on 0.1, %s, 4 frames x 16 spp: %d pixels vs the closed form: relative RMS "
               "%.4f, sphere mean %+.2f %%\n", m ? "metal alpha 0.3" : "white Lambert", count, rel_rms, 100 * rel_mean);
        CHECK(count > 150);
        CHECK_MSG(fabs(rel_mean) < 0.02, "sphere mean off by %+.2f %%", 100 * rel_mean);
        CHECK_MSG(rel_rms < 0.1, "relative RMS %.4f", rel_rms);
        sl_harness_destroy(h);
    }
}

/* ---------------------------------------------------------------- filtered under a small sun */

/* specular=filtered reads one sample set shared by every pixel: under a small bright sun a
 * frame's highlight is one dot per sub-lobe (issue 42). Frame k of a still or an accumulated
 * render turns the set (sl_sample_index), so the frames' dots fall between each other's and their
 * mean fills the lobe in. A 1.5° disk of 2000 on 0.1, white metal α = 0.2, the camera zoomed on
 * the highlight (fov 10°, every pixel on the sphere). Against the closed form bg·E(μ, α) +
 * (L − bg)·∫_disk (test_reference_sun's), over the pixels whose disk term is at least 10 % of its
 * peak: the relative RMS, and the lumpiness — the RMS of the error less its own 5 × 5 mean,
 * relative to the highlight's mean: what is left of the dots, without the smooth error of the
 * lobe's width that no number of frames changes. The 16-frame accumulation's lumpiness must be at
 * most a third of a single frame's, and its first frame the single frame exactly (a view in
 * motion shows what is charted against Cycles). */
static void sun_highlight_error(const float *im, double *rel_rms, double *lumpy, int *count) {
    static double want[W * H], disk[W * H], err[W * H];
    const test_camera zoom = {{0, 0, 4}, {0, 0, 0}, 10, W, H};
    double peak = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x;
            float o[3], d[3];
            test_camera_ray(&zoom, x, y, o, d);
            double b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2], c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - 1;
            double t = -b - sqrt(fmax(b * b - c, 0)), n[3], v[3];
            for (int q = 0; q < 3; q++) n[q] = o[q] + t * d[q], v[q] = -d[q];
            normalize3(n);
            disk[i] = (ref_sun_L - ref_sun_bg) * disk_ggx(n, v, 0.2);
            want[i] = ref_sun_bg * albedo(n[0] * v[0] + n[1] * v[1] + n[2] * v[2], 0.2) + disk[i];
            err[i] = im[i * 4 + 1] - want[i];
            peak = fmax(peak, disk[i]);
        }
    double se = 0, sh = 0, sw = 0;
    int k = 0;
    for (int y = 2; y < H - 2; y++)
        for (int x = 2; x < W - 2; x++) {
            int i = y * W + x;
            if (disk[i] < 0.1 * peak) continue;
            double local = 0;
            for (int dy = -2; dy <= 2; dy++)
                for (int dx = -2; dx <= 2; dx++) local += err[i + dy * W + dx] / 25;
            se += err[i] * err[i], sh += (err[i] - local) * (err[i] - local), sw += want[i], k++;
        }
    *count = k;
    *rel_rms = k ? sqrt(se / k) / (sw / k) : -1;
    *lumpy = k ? sqrt(sh / k) / (sw / k) : -1;
}
static void test_filtered_sun(void) {
    ref_sun_radius = 1.5 * M_PI / 180, ref_sun_L = 2000, ref_sun_bg = 0.1;
    ref_sun_dir[0] = 0.1, ref_sun_dir[1] = 0.12, ref_sun_dir[2] = 1;
    normalize3(ref_sun_dir);
    char path[512];
    snprintf(path, sizeof path, "%s/small_sun.exr", dir);
    write_latlong(path, 1024, 512, ref_sun_fn);
    const char *mat = "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 1, "
                      "\"base_color\": [1, 1, 1], \"alpha\": 0.2";
    const char *const settings[] = {"envmap.specular=filtered", "envmap.cube_size=64", "envmap.background=false",
                                    "aa.enabled=false", NULL};
    sl_harness *h = make_with("", 10, path, mat, settings, 1);
    CHECK(h != NULL);
    if (!h) return;
    /* frame k of a 16-frame still, each on its own; a lone frame is frame 0 */
    static float lone[W * H * 4], mean[W * H * 4];
    CHECK(sl_harness_render(h, lone));
    for (int k = 0; k < 16; k++) {
        CHECK(sl_harness_render_sample(h, k, 16, img));
        for (int i = 0; i < W * H * 4; i++) mean[i] += img[i] / 16;
        if (k == 0) {
            long differ = 0;
            for (int i = 0; i < W * H * 4; i++) differ += img[i] != lone[i];
            CHECK_MSG(differ == 0, "frame 0 of a 16-frame still differs from a lone frame in %ld values", differ);
        }
    }
    sl_harness_destroy(h);
    double rms[2], lumpy[2];
    int count[2];
    sun_highlight_error(lone, &rms[0], &lumpy[0], &count[0]);
    sun_highlight_error(mean, &rms[1], &lumpy[1], &count[1]);
    printf("filtered under a 1.5° sun of 2000, metal alpha 0.2, %d highlight pixels vs the closed form: one frame "
           "relative RMS %.4f, lumpiness %.4f; the mean of a still's 16 frames %.4f, %.4f\n", count[0], rms[0], lumpy[0], rms[1], lumpy[1]);
    CHECK(count[0] > 100 && lumpy[0] > 0 && lumpy[1] > 0);
    CHECK_MSG(lumpy[1] <= lumpy[0] / 3, "the still keeps the frame's sub-lobes: lumpiness %.4f vs one frame %.4f", lumpy[1],
              lumpy[0]);
}

/* ---------------------------------------------------------------- the default scene's horizon */

/* The built-in default scene (scenes/default.json) ends its sunlit floor 30 m out; beyond it, up
 * to the horizon, the sky's ground shows. With the sky's old fixed dim ground that was a flat
 * dark band between the floor's far end and the sky (issue 42); the scene now sets
 * envmap.ground_color to what its floor looks like there. Every pixel is classified from the
 * scene's camera (tests/camera_rays.h): rays that point below the horizon and miss the floor
 * (|x|, |z| < 30) see the sky's ground ("band"); rays that hit the floor more than 25 m away see
 * the far floor (above every object in the image). The band's mean radiance, and its darkest
 * row's, against the far floor's: today 0.37 and 0.24 of it before the fix. */
static void test_default_horizon(void) {
    enum { DW = 256, DH = 144 };
    char path[1024], err[4096];
    snprintf(path, sizeof path, "%s/default.json", SL_SCENES_DIR);
    /* (the sun's shadow map at 512², not 2048²: it darkens no pixel this test reads) */
    const char *const settings[] = {"aa.enabled=false", "tonemap.enabled=false", "spotlight-shadow.map_size=512", NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = DW, .height = DH,
                                                          .scene_file = path, .settings = settings, .float32 = true},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return;
    float *im = malloc((size_t)DW * DH * 16);
    CHECK(sl_harness_render(h, im));
    const test_camera c = {{0.3f, 2.3f, 6.9f}, {0, 0.65f, 0}, 38, DW, DH};
    double band = 0, floor_far = 0, row_sum[DH] = {0};
    int nb = 0, nf = 0, row_n[DH] = {0};
    for (int y = 0; y < DH; y++)
        for (int x = 0; x < DW; x++) {
            float o[3], d[3], hit[3] = {0, 0, 0};
            test_camera_ray(&c, x, y, o, d);
            const float *p = im + ((size_t)y * DW + x) * 4;
            double L = (p[0] + p[1] + p[2]) / 3;
            bool on_floor = test_camera_hit_ground(&c, x, y, 30, hit);
            if (d[1] < 0 && !on_floor) band += L, nb++, row_sum[y] += L, row_n[y]++;
            double dist = sqrt((hit[0] - o[0]) * (hit[0] - o[0]) + (hit[2] - o[2]) * (hit[2] - o[2]));
            if (on_floor && dist > 25) floor_far += L, nf++;
        }
    band /= nb, floor_far /= nf;
    double darkest = 1e30;
    for (int y = 0; y < DH; y++)
        if (row_n[y] > DW / 2) darkest = fmin(darkest, row_sum[y] / row_n[y]);
    printf("default scene: the band between the floor's end and the horizon (%d px) %.3f, its darkest row %.3f, the far "
           "floor (%d px) %.3f: ratios %.2f, %.2f\n", nb, band, darkest, nf, floor_far, band / floor_far, darkest / floor_far);
    CHECK(nb > 500 && nf > 500);
    CHECK_MSG(band / floor_far > 0.8 && band / floor_far < 1.25, "a band of %.2f x the far floor between floor and sky",
              band / floor_far);
    CHECK_MSG(darkest / floor_far > 0.7, "a row of the band at %.2f x the far floor", darkest / floor_far);
    free(im);
    sl_harness_destroy(h);
}

/* ---------------------------------------------------------------- the procedural sky's background */

/* The procedural sky as background is em_sky_radiance along each pixel's ray, with the sun disk
 * box-filtered over the pixel. Looking at the sun (elevation 30°, azimuth 0, E = 3, radius 1.5°)
 * with a 12° field of view, 64 × 64: every pixel farther than one pixel from the disk's edge
 * equals the C function within 0.1 % — inside, the disk's E/Ω times its colour; outside, the sky
 * and the halo (the sky sampled from a 1024-wide lat-long smeared the disk over two to three
 * pixels beyond its edge). The pixels along the edge equal the box filter of em_sky_radiance over
 * the pixel (16 × 16 rays), relative to the disk's radiance: in one frame without antialiasing,
 * and in a 16-frame TAA still, whose frames are jittered (the disk is filtered over the
 * unjittered pixel: the jitter's sign turned measured rms 0.114). Point samples (the disk's edge
 * as a step, as it was drawn before) measured rms 0.156 in one frame and 0.030 in the still. */
static const double sky_sun[3] = {0, 0.5, 0.8660254}, sky_sun_r = 1.5 * M_PI / 180, sky_pixel = 12 * M_PI / 180 / H;
static const test_camera sky_cam = {{0, 0, 0}, {0, 5, 8.660254f}, 12, W, H};

static double sun_angle(const float df[3]) {
    return acos(fmin(1, df[0] * sky_sun[0] + df[1] * sky_sun[1] + df[2] * sky_sun[2]));
}

/* The procedural sky (its sun at 30° elevation, azimuth 0, 3 W/m²) seen through `c`, with
 * `objects` (the scene's "materials" and "nodes" members), aa on or off. */
static sl_harness *sky_harness_with(bool aa, const test_camera *c, const char *objects) {
    char json[2048];
    snprintf(json, sizeof json,
             "{\"plugins\": [\"envmap\"],"
             " \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 0], \"target\": [%.9g, %.9g, %.9g], \"fov_y\": %g}], %s}",
             c->target[0], c->target[1], c->target[2], c->fov_deg, objects);
    const char *const settings[] = {aa ? "aa.enabled=true" : "aa.enabled=false", "aa.taa_frames=16",
                                    "envmap.sun_elevation=30", "envmap.sun_azimuth=0", "envmap.sun_irradiance=3",
                                    "envmap.cache=false", NULL};
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                          .scene_json = json, .settings = settings, .float32 = true,
                                                          .strict = true},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    return h;
}
/* the sky alone but for a small ball far below the view */
static sl_harness *sky_harness(bool aa, const test_camera *c) {
    return sky_harness_with(aa, c,
                            "\"materials\": [{\"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5]}],"
                            " \"nodes\": [{\"name\": \"n\", \"translate\": [0, 0, -50], \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.1},"
                            "             \"material\": \"m\"}]");
}
/* Pixels whose centre lies within 1.5 pixels of the disk's edge: relative RMS and largest error of
 * red against the box filter of em_sky_radiance over the pixel, over the disk's radiance. */
static void sun_edge_error(const em_sky *sky, const float *im, double *rms, double *worst, int *count) {
    double dir[3], r, Ls[3], sum = 0;
    em_sky_sun(sky, dir, &r, Ls);
    *worst = 0, *count = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float o[3], df[3];
            test_camera_ray(&sky_cam, x, y, o, df);
            if (fabs(sun_angle(df) - sky_sun_r) > 1.5 * sky_pixel) continue;
            double box = 0;
            for (int j = 0; j < 16; j++)
                for (int i = 0; i < 16; i++) {
                    test_camera_ray_at(&sky_cam, x + (i + 0.5f) / 16, y + (j + 0.5f) / 16, o, df);
                    double d[3] = {df[0], df[1], df[2]}, L[3];
                    em_sky_radiance(sky, d, L);
                    box += L[0] / 256;
                }
            double e = (im[((size_t)y * W + x) * 4] - box) / Ls[0];
            sum += e * e, *worst = fmax(*worst, fabs(e)), ++*count;
        }
    *rms = sqrt(sum / fmax(*count, 1));
}


/* The disk's energy at any size on screen: one frame without antialiasing, the pixels' radiance
 * less the sky's (em_sky_radiance without the sun) times their solid angles sums to the sun's
 * irradiance E = 3 (red: colour 1).
 * mirror = false: looking at the sun (a third of a pixel off a pixel corner), every pixel summed.
 * Fields of view 120°, 60°, 30° on 64 pixels put the disk's radius at 0.5, 1.4 and 3.2 pixels: the
 * small disk drawn as a square of its area, the blend, the straight edge. A point-sampled disk lit
 * whole pixels (+36 % at 120°, measured before the filter).
 * mirror = true: the sun seen in a mirror floor (the sky's sun a light of its own: the mirror model
 * adds the disk filtered over the lookup's footprint, envmap_sun_disk), within 6° of the disk's
 * reflection; at 120° (a pixel 3.1°, wider than the 1.5° disk: the footprint sets the spread) a
 * footprint-wide ramp about a disk of the footprint's half width carried 4/3 of it. */
static void test_sun_energy(double fov, bool mirror) {
    double t = tan(fov * M_PI / 360), px = 2 * t / H, off = px / 3, flip = mirror ? -1 : 1;
    test_camera c = {{0, 0, 0}, {(float)(sky_sun[0] + off), (float)(flip * sky_sun[1] + off), (float)sky_sun[2]}, (float)fov, W, H};
    sl_harness *h = mirror ? sky_harness_with(false, &c,
                                              "\"materials\": [{\"name\": \"m\", \"model\": \"mirror\"}],"
                                              " \"nodes\": [{\"name\": \"n\", \"translate\": [0, -1, 0],"
                                              " \"mesh\": {\"primitive\": \"plane\", \"size\": 400}, \"material\": \"m\"}]")
                           : sky_harness(false, &c);
    if (!h) return;
    CHECK(sl_harness_render(h, img));
    em_sky no_sun;
    em_sky_default(&no_sun);
    no_sun.sun_elevation_deg = 30, no_sun.sun_azimuth_deg = 0, no_sun.sun_irradiance = 0;
    double fwd[3] = {c.target[0], c.target[1], c.target[2]}, E = 0;
    normalize3(fwd);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float o[3], df[3];
            test_camera_ray(&c, x, y, o, df);
            double d[3] = {df[0], flip * df[1], df[2]}, L[3], mu = df[0] * fwd[0] + df[1] * fwd[1] + df[2] * fwd[2];
            if (mirror && d[0] * sky_sun[0] + d[1] * sky_sun[1] + d[2] * sky_sun[2] < cos(6 * M_PI / 180)) continue;
            em_sky_radiance(&no_sun, d, L);
            E += (img[((size_t)y * W + x) * 4] - L[0]) * px * px * mu * mu * mu;
        }
    printf("  %s with a %g° field of view (disk radius %.2f px): irradiance in the image %.4f (E = 3)\n",
           mirror ? "the sun in a mirror floor" : "looking at the sun", fov, sky_sun_r / px, E);
    CHECK_MSG(fabs(E / 3 - 1) < (mirror ? 0.02 : 0.01), "the sun's energy %s: %.4f against 3",
              mirror ? "in a mirror" : "in the background", E);
    sl_harness_destroy(h);
}

static void test_sky_background(void) {
    sl_harness *h = sky_harness(false, &sky_cam);
    if (!h) return;
    CHECK(sl_harness_render(h, img));
    em_sky sky;
    em_sky_default(&sky);
    sky.sun_elevation_deg = 30, sky.sun_azimuth_deg = 0, sky.sun_irradiance = 3;
    double worst = 0;
    int inside = 0, outside = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float o[3], df[3];
            test_camera_ray(&sky_cam, x, y, o, df);
            double d[3] = {df[0], df[1], df[2]}, L[3];
            double angle = sun_angle(df);
            if (fabs(angle - sky_sun_r) < sky_pixel) continue; /* a pixel the edge may cross */
            em_sky_radiance(&sky, d, L);
            angle < sky_sun_r ? inside++ : outside++;
            for (int k = 0; k < 3; k++)
                worst = fmax(worst, fabs(img[((size_t)y * W + x) * 4 + k] - L[k]) / (L[k] + 1e-3));
        }
    printf("procedural sky as background, looking at the sun: %d pixels in the disk, %d around it, largest relative "
           "difference from em_sky_radiance %.2g\n", inside, outside, worst);
    CHECK(inside > 100 && outside > 2000);
    CHECK_MSG(worst < 1e-3, "the sky's background differs from em_sky_radiance by %.3g (relative)", worst);

    double rms, edge_worst;
    int count;
    sun_edge_error(&sky, img, &rms, &edge_worst, &count);
    printf("the disk's edge, %d pixels, against the box filter over the pixel (of the disk's radiance): one frame "
           "without aa: rms %.4f, largest %.4f\n", count, rms, edge_worst);
    CHECK(count > 50);
    CHECK_MSG(rms < 0.01 && edge_worst < 0.03, "the disk's edge: rms %.4f, largest %.4f", rms, edge_worst);
    sl_harness_destroy(h);

    h = sky_harness(true, &sky_cam);
    if (!h) return;
    for (int k = 0; k < 16; k++) CHECK(sl_harness_render(h, img));
    sun_edge_error(&sky, img, &rms, &edge_worst, &count);
    printf("  the still (16 frames): rms %.4f, largest %.4f\n", rms, edge_worst);
    CHECK_MSG(rms < 0.01 && edge_worst < 0.03, "the still's disk edge: rms %.4f, largest %.4f", rms, edge_worst);
    sl_harness_destroy(h);
    for (int i = 0; i < 3; i++) test_sun_energy((const double[]){120, 60, 30}[i], false);
    for (int i = 0; i < 2; i++) test_sun_energy((const double[]){120, 60}[i], true);
}

/* The background under TAA over supersampling: the core divides a TAA's jitter by core.ssaa = k
 * (each of the forward pass's k × k samples stays in its cell), and the background, one sample per
 * pixel, moves its sample k times as far, so a still's frames sweep the whole pixel as they do
 * without supersampling: the background of a 16-frame still is the same with core.ssaa=2 as with 1
 * (the same sample positions; a stripe map 2° a stripe, where half a pixel's sweep differs). */
static void stripes_fn(const double d[3], double out[3]) {
    double a = atan2(d[0], -d[2]) * 180 / M_PI + 90 * d[1];
    double t = fmod(a + 720, 4) < 2 ? 1.0 : 0.1;
    out[0] = t, out[1] = 0.5 * t + 0.2, out[2] = 0.3;
}
static void test_background_over_ssaa(void) {
    char path[512];
    snprintf(path, sizeof path, "%s/stripes.exr", dir);
    write_latlong(path, 2048, 1024, stripes_fn);
    static float one[W * H * 4], two[W * H * 4];
    float *out[2] = {one, two};
    for (int k = 0; k < 2; k++) {
        const char *settings[] = {"aa.method=taa", "aa.taa_frames=16", k ? "core.ssaa=2" : "core.ssaa=1", NULL};
        sl_harness *h = make_with(", \"aa\"", 40, path, "\"base_color\": [0.5, 0.5, 0.5]", settings, 0);
        if (!h) return;
        for (int f = 0; f < 16; f++) CHECK(sl_harness_render(h, out[k]));
        sl_harness_destroy(h);
    }
    double worst = 0, mean = 0;
    int n = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double d[3];
            bool clear = true; /* two pixels from the silhouette: a pixel the jitter carries over it differs */
            for (int j = -2; j <= 2; j += 4)
                for (int i = -2; i <= 2; i += 4) clear = clear && background_pixel(x + i, y + j, d);
            if (!clear || !background_pixel(x, y, d)) continue;
            for (int c = 0; c < 3; c++) {
                size_t i = ((size_t)y * W + x) * 4 + c;
                worst = fmax(worst, fabs(one[i] - two[i])), mean += one[i];
            }
            n++;
        }
    mean /= 3.0 * (n ? n : 1);
    printf("background of a 16-frame TAA still, core.ssaa=2 against 1: %d pixels, largest difference %.2g (mean %.3f)\n",
           n, worst, mean);
    CHECK(n > 1000);
    CHECK_MSG(worst < 1e-3 * mean, "the background under core.ssaa=2 differs from core.ssaa=1 by %.3g", worst);
}

/* ---------------------------------------------------------------- the default has no speckle */

/* scenes/ibl_spheres.json with every default, 320 × 180: shadelab-bench's noise measure
 * (tools/bench/include/bench/metrics.h) on the rough spheres (roughness 0.55 and 0.8, dielectric
 * and gold): frames k = 0..15 of a 16-frame still, each rendered on its own
 * (sl_harness_render_sample: no TAA history), the per-pixel standard deviation of the display
 * value (sRGB, [0,1]), RMS over R, G, B and the pixels whose 3 × 3 neighbourhood lies on one
 * rough sphere (n·v > 0.3). What a still averages away shows as speckle while it settles and
 * in motion. The default (specular=fitted) must stay within 0.002 (half an 8-bit step);
 * specular=hybrid (Monte Carlo in a still's frames) is measured beside it and must exceed it,
 * so the measure does see speckle. */
static int rough_sphere_at(const test_camera *c, int x, int y, const float centres[][3], int count) {
    float o[3], d[3];
    test_camera_ray(c, x, y, o, d);
    int which = -1;
    for (int k = 0; k < count; k++) {
        double oc[3] = {o[0] - centres[k][0], o[1] - centres[k][1], o[2] - centres[k][2]};
        double b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
        double disc = b * b - (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - 0.45 * 0.45);
        if (disc <= 0) continue;
        double t = -b - sqrt(disc), nv = 0;
        for (int i = 0; i < 3; i++) nv -= (o[i] + t * d[i] - centres[k][i]) / 0.45 * d[i];
        if (nv > 0.3) which = k;
    }
    return which;
}
static bool inside_one_sphere(const int *label, int w, int x, int y) {
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++)
            if (label[(y + dy) * w + x + dx] != label[y * w + x]) return false;
    return label[y * w + x] >= 0;
}
/* the noise of `samples` frames on the masked pixels; -1 when a frame fails */
static double still_noise(sl_harness *h, int samples, const int *label, int w, int hgt, float *im) {
    size_t n = (size_t)w * hgt * 4;
    double *mean = calloc(n, sizeof *mean), *m2 = calloc(n, sizeof *m2);
    bool ok = mean && m2;
    for (int k = 0; k < samples && ok; k++) {
        ok = sl_harness_render_sample(h, k, samples, NULL) && sl_harness_read_display(h, im);
        for (size_t i = 0; ok && i < n; i++) { /* Welford */
            double d = im[i] - mean[i];
            mean[i] += d / (k + 1);
            m2[i] += d * (im[i] - mean[i]);
        }
    }
    double sum = 0;
    long count = 0;
    for (int y = 1; ok && y < hgt - 1; y++)
        for (int x = 1; x < w - 1; x++)
            if (inside_one_sphere(label, w, x, y))
                for (int c = 0; c < 3; c++) sum += m2[((size_t)y * w + x) * 4 + c] / (samples - 1), count++;
    free(mean), free(m2);
    return ok && count > 200 ? sqrt(sum / count) : -1;
}
static void test_default_speckle(void) {
    enum { SW = 320, SH = 180, SAMPLES = 16 };
    char path[1024], err[4096];
    snprintf(path, sizeof path, "%s/ibl_spheres.json", SL_SCENES_DIR);
    const test_camera c = {{0, 1.3f, 7.2f}, {0, 0.65f, 0}, 40, SW, SH};
    const float rough[4][3] = {{0.6f, 1.55f, -0.6f}, {1.8f, 1.55f, -0.6f}, {0.6f, 0.5f, -0.6f}, {1.8f, 0.5f, -0.6f}};
    float *im = malloc((size_t)SW * SH * 16);
    int *label = malloc((size_t)SW * SH * sizeof *label);
    for (int y = 0; y < SH; y++)
        for (int x = 0; x < SW; x++) label[y * SW + x] = rough_sphere_at(&c, x, y, rough, 4);
    double noise[2] = {-1, -1};
    for (int k = 0; k < 2; k++) {
        const char *const hybrid[] = {"envmap.specular=hybrid", NULL};
        sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = SW, .height = SH,
                                                              .scene_file = path, .settings = k ? hybrid : NULL},
                                          err, sizeof err);
        CHECK_MSG(h != NULL, "%s", err);
        if (!h) continue;
        if (!k) {
            char v[32];
            CHECK(sl_harness_get(h, "envmap.specular", v, sizeof v) && !strcmp(v, "fitted"));
        }
        noise[k] = still_noise(h, SAMPLES, label, SW, SH, im);
        sl_harness_destroy(h);
    }
    free(im), free(label);
    printf("ibl_spheres, rough spheres, noise over a %d-frame still (display values): default %.5f, "
           "specular=hybrid %.5f\n", SAMPLES, noise[0], noise[1]);
    CHECK(noise[0] >= 0 && noise[1] >= 0);
    CHECK_MSG(noise[0] <= 0.002, "the default's frames scatter: noise %.5f", noise[0]);
    CHECK_MSG(noise[1] > 0.002, "the measure does not see hybrid's Monte Carlo: %.5f", noise[1]);
}

/* specular=hybrid's sample 0 (every frame in motion, a still's first) is the dominant lookup
 * alone (README, "hybrid"): with aa on, sample 0 of a 16-frame still (sl_harness_render_sample)
 * and the first frame after an edit (a still's first) equal specular=dominant's bit for bit, at
 * α = 0.2, 0.4 and 1 (β(α) > 0: hybrid samples there); sample 1 differs, so the comparison sees
 * hybrid's samples. Procedural sky with its sun. */
static void test_hybrid_sample0(void) {
    const char *mat = "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 1, "
                      "\"base_color\": [0.95, 0.64, 0.54], \"alpha\": 0.3";
    static const char *const dom[] = {"aa.enabled=true", "envmap.specular=dominant", "envmap.background=false", NULL};
    static const char *const hyb[] = {"aa.enabled=true", "envmap.specular=hybrid", "envmap.fis_samples=16",
                                      "envmap.background=false", NULL};
    enum { NA = 3 };
    const double alphas[NA] = {0.2, 0.4, 1.0};
    static float d[NA][W * H * 4], y0[W * H * 4], yc[W * H * 4], y1[W * H * 4];
    for (int k = 0; k < 2; k++) { /* one harness a process: dominant's frames, then hybrid's */
        sl_harness *h = make_with(", \"aa\"", 40, NULL, mat, k ? hyb : dom, 1);
        CHECK(h != NULL);
        if (!h) return;
        for (int a = 0; a < NA; a++) {
            char buf[64], err[256];
            snprintf(buf, sizeof buf, "material.m.alpha=%g", alphas[a]);
            CHECK_MSG(sl_harness_set(h, buf, err, sizeof err), "%s", err);
            /* the first frame after the edit: a still's first */
            CHECK(sl_harness_render(h, k ? yc : d[a]));
            if (!k) continue;
            CHECK(sl_harness_render_sample(h, 0, 16, y0) && sl_harness_render_sample(h, 1, 16, y1));
            long differ0 = 0, differc = 0, differ1 = 0, lit = 0;
            for (int i = 0; i < W * H * 4; i++) {
                differ0 += y0[i] != d[a][i], differc += yc[i] != d[a][i], differ1 += y1[i] != d[a][i];
                lit += i % 4 != 3 && d[a][i] > 0;
            }
            printf("hybrid vs dominant, alpha %.1f: %ld lit values; differing: sample 0 %ld, a still's first frame "
                   "%ld, sample 1 %ld\n", alphas[a], lit, differ0, differc, differ1);
            CHECK(lit > W * H / 2);
            CHECK_MSG(differ0 == 0, "hybrid's sample 0 differs from dominant in %ld values (alpha %.1f)", differ0, alphas[a]);
            CHECK_MSG(differc == 0, "hybrid's first frame of a still differs from dominant in %ld values (alpha %.1f)",
                      differc, alphas[a]);
            CHECK_MSG(differ1 > lit / 4, "hybrid's sample 1 takes no sample: %ld values differ (alpha %.1f)", differ1, alphas[a]);
        }
        sl_harness_destroy(h);
    }
}

/* ---------------------------------------------------------------- SH ringing */

/* A sun-only environment (a bright 3° disk on black): order-2 SH rings negative on the far
 * side; the shader clamps the irradiance to 0. Checked in C that the unclamped projection
 * really goes negative there (the guard is reached), and that the render is finite, never
 * negative, and within 2% of the exact irradiance on the lit side. */
static double sun_dir[3] = {0, 0.6, 0.8};
static void sun_fn(const double d[3], double out[3]) {
    double c = d[0] * sun_dir[0] + d[1] * sun_dir[1] + d[2] * sun_dir[2];
    out[0] = out[1] = out[2] = c >= cos(3 * M_PI / 180) ? 1000.0 : 0.0;
}
static void test_sh_ringing(void) {
    char path[512];
    snprintf(path, sizeof path, "%s/sun.exr", dir);
    write_latlong(path, 512, 256, sun_fn);
    /* C: SH of the (point-like) disk, evaluated where the band-limited clamped cosine
     * 0.375 + 2c + 1.875c² (c = n·s) is lowest: c = −8/15 */
    double omega = 2 * M_PI * (1 - cos(3 * M_PI / 180)), sh[9][3] = {{0}}, back[3], c0 = -8.0 / 15, s0 = sqrt(1 - c0 * c0);
    double anti[3] = {c0 * sun_dir[0] + s0, c0 * sun_dir[1], c0 * sun_dir[2]}; /* (1,0,0) ⟂ sun_dir */
    double y[9] = {0.282094791773878, 0.488602511902920 * sun_dir[1], 0.488602511902920 * sun_dir[2], 0.488602511902920 * sun_dir[0],
                   1.092548430592079 * sun_dir[0] * sun_dir[1], 1.092548430592079 * sun_dir[1] * sun_dir[2],
                   0.315391565252520 * (3 * sun_dir[2] * sun_dir[2] - 1), 1.092548430592079 * sun_dir[0] * sun_dir[2],
                   0.546274215296040 * (sun_dir[0] * sun_dir[0] - sun_dir[1] * sun_dir[1])};
    for (int k = 0; k < 9; k++) sh[k][0] = sh[k][1] = sh[k][2] = 1000 * omega * y[k];
    em_sh9_diffuse(sh, anti, back);
    printf("SH ringing: unclamped E/pi at 122° from a 3° sun of radiance 1000 = %.3f (negative: the clamp is reached)\n", back[0]);
    CHECK(back[0] < -0.05);
    sl_harness *h = make(path, "\"model\": \"lambert\", \"base_color\": [1, 1, 1]",
                         (const char *[]){"envmap.irradiance=sh", "envmap.cube_size=32", NULL}, 1);
    CHECK(h && sl_harness_render(h, img));
    long neg = 0, bad = sl_harness_count_nonfinite(img, W, H);
    double worst = 0, darkest = 1e9;
    for (int py = 0; py < H; py++)
        for (int px = 0; px < W; px++) {
            double n[3], v[3];
            if (!sphere_pixel(px, py, n, v, 0.1)) continue;
            double c = n[0] * sun_dir[0] + n[1] * sun_dir[1] + n[2] * sun_dir[2], L = img[(py * W + px) * 4];
            neg += L < 0;
            darkest = fmin(darkest, L);
            if (c > 0.5) worst = fmax(worst, fabs(L / (1000 * omega * c / M_PI) - 1) - 0);
        }
    printf("  rendered: %ld non-finite, %ld negative, darkest %.4f; lit side (n.s > 0.5) vs E = L_sun Omega cos/pi: max "
           "relative error %.3f (SH band limit)\n", bad, neg, darkest, worst);
    CHECK(bad == 0 && neg == 0);
    CHECK(darkest == 0); /* clamped, not merely small */
    /* order-2 SH cannot follow a point-like source: stated, measured bound on the lit side */
    CHECK_MSG(worst < 0.1, "SH irradiance on the lit side off by %.3f", worst); /* band limit: ≤ 8% for c > 0.5 */
    sl_harness_destroy(h);
}

/* ---------------------------------------------------------------- linear environment */

static void test_linear(void) {
    char path[512];
    snprintf(path, sizeof path, "%s/linear.exr", dir);
    write_latlong(path, 128, 64, linear_fn);
    const char *irr[2] = {"envmap.irradiance=sh", "envmap.irradiance=convolved"};
    for (int k = 0; k < 2; k++) {
        sl_harness *h = make(path, "\"model\": \"lambert\", \"base_color\": [1, 1, 1]", (const char *[]){irr[k], NULL}, 1);
        CHECK(h && sl_harness_render(h, img));
        double worst = 0, worst_bg = 0;
        int count = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double n[3], v[3], d[3];
                if (sphere_pixel(x, y, n, v, 0.1)) {
                    worst = fmax(worst, fabs(img[(y * W + x) * 4 + 1] / (1 + 2.0 / 3 * n[1]) - 1));
                    count++;
                } else if (background_pixel(x, y, d)) {
                    worst_bg = fmax(worst_bg, fabs(img[(y * W + x) * 4 + 1] - (1 + d[1])));
                }
            }
        printf("L = 1 + y, white Lambert, %s: %d pixels, max relative error vs 1 + 2/3 n_y %.4f; background max |err| %.4f\n",
               irr[k], count, worst, worst_bg);
        CHECK_MSG(worst < 0.02, "%s: %.4f", irr[k], worst);
        CHECK_MSG(worst_bg < 0.01, "background: %.4f", worst_bg);
        sl_harness_destroy(h);
    }
}

/* ---------------------------------------------------------------- conventions */

static double colour_check(const float *im, int model, double yaw_deg, double *worst_other) {
    double worst = 0;
    *worst_other = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double n[3], v[3], d[3], dm[3];
            if (sphere_pixel(x, y, n, v, 0.3)) {
                if (model == 0) {
                    double nv = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
                    for (int i = 0; i < 3; i++) d[i] = 2 * nv * n[i] - v[i];
                } else {
                    memcpy(d, n, sizeof d);
                }
            } else if (!background_pixel(x, y, d)) {
                continue;
            }
            em_rotate_y(d, -yaw_deg, dm); /* world → map */
            for (int c = 0; c < 3; c++) {
                worst = fmax(worst, fabs(im[(y * W + x) * 4 + c] - (0.5 + 0.5 * dm[c])));
                *worst_other = fmax(*worst_other, fabs(im[(y * W + x) * 4 + c] - (0.5 + 0.5 * d[c])));
            }
        }
    return worst;
}

static void test_conventions(void) {
    char latlong[512], cross_exr[512], cross_png[512], cmd[4096];
    snprintf(latlong, sizeof latlong, "%s/colour.exr", dir);
    write_latlong(latlong, 256, 128, colour_fn);
    snprintf(cross_exr, sizeof cross_exr, "%s/colour_cross.exr", dir);
    snprintf(cross_png, sizeof cross_png, "%s/colour_cross.png", dir);
    snprintf(cmd, sizeof cmd, "'%s' '%s' --convert '%s' --size 64 -q && '%s' '%s' --convert '%s' --size 64 -q", SHADELAB_CUBE,
             latlong, cross_exr, SHADELAB_CUBE, latlong, cross_png);
    CHECK(run(cmd) == 0);
    /* six face files from the cross */
    char faces[512];
    snprintf(faces, sizeof faces, "%s/colour_px.exr", dir);
    em_env cube;
    char err[4096];
    CHECK_MSG(em_env_load(cross_exr, &em_io_reader, &cube, err, sizeof err), "%s", err);
    static const char *names[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    for (int f = 0; f < 6; f++) {
        char p[512];
        snprintf(p, sizeof p, "%s/colour_%s.exr", dir, names[f]);
        CHECK(em_io_write_exr(p, cube.faces[f], cube.size, cube.size, NULL, err, sizeof err));
    }
    em_env_free(&cube);
    const char *maps[4] = {latlong, cross_exr, cross_png, faces};
    const char *what[4] = {"lat-long EXR", "cross EXR", "cross RGBE8 PNG", "six face EXRs"};
    for (int m = 0; m < 4; m++)
        for (int model = 0; model < 2; model++) {
            sl_harness *h = make(maps[m], model == 0 ? "\"model\": \"mirror\"" : "\"model\": \"environment\"", NULL, 1);
            CHECK(h && sl_harness_render(h, img));
            double other, worst = colour_check(img, model, 0, &other);
            printf("colour-coded %s, %s sphere + background: max |err| %.4f\n", what[m], model ? "environment" : "mirror", worst);
            CHECK_MSG(worst < 0.03, "%s: %.4f", what[m], worst);
            if (m == 0 && model == 0) {
                char err2[256];
                CHECK(sl_harness_set(h, "envmap.yaw=90", err2, sizeof err2));
                CHECK(sl_harness_render(h, img2));
                double unrotated, rotated = colour_check(img2, 0, 90, &unrotated);
                printf("  yaw 90: max |err| %.4f against the turned map, %.4f against the unturned one\n", rotated, unrotated);
                CHECK_MSG(rotated < 0.03, "yaw: %.4f", rotated);
                CHECK_MSG(unrotated > 0.3, "yaw did not turn the map (%.4f)", unrotated);
            }
            sl_harness_destroy(h);
        }
}

/* The orientation, from the convention on paper (sdk/docs/conventions.md), not from a render:
 * an asymmetric probe, a lat-long that is dark (0.02) except one marked quadrant (1, 0.5, 0.1)
 * at u ∈ [¼, ½), v ∈ [¼, ½). The image is made from texel indices alone (no code under test).
 *
 * Where the mark is. The convention (Blender's and three.js': u = atan2(d.z, d.x)/2π + ½)
 * states: u = ¼ faces −Z, u = ½ faces +X, u grows to the right as seen from inside; v = θ/π,
 * θ from +Y, so v = ¼ is 45° above the horizon and v = ½ the horizon. Hence the mark covers the
 * directions d with
 *     d.x > 0, d.z < 0 (between −Z and +X), and 0 < elevation < 45°  (elevation = asin d.y).
 * The camera sits at (0, 0, 4) looking at the origin (down −Z), +Y up, 40° vertical field of
 * view: its right hand is +X, so the right half of the image sees d.x > 0, the upper half
 * d.y > 0, and every view ray has d.z < 0 and |elevation| ≤ 20° + a little (the corners).
 *   background  → the mark fills the upper-right quadrant of the image, nothing elsewhere.
 *   mirror sphere (unit, at the origin): a pixel's ray hits n, reflects to r = 2(n·v)n − v.
 *     With v ≈ +Z, n = (sinβ cosγ, sinβ sinγ, cosβ) (β from the view axis, γ the angle in the
 *     image, counter-clockwise from "right"), r ≈ (sin2β cosγ, sin2β sinγ, cos2β): r.z < 0 only
 *     in the ring β > 45°, and there r.x has the sign of cosγ, r.y of sinγ. The mark shows in
 *     the outer ring, upper-right quarter (cut off where r rises above 45°) — on the same side
 *     as in the background, as a real mirror ball shows what is beside it. The previous
 *     convention (u = ½ at −Z) put u ∈ [¼, ½) between −X and −Z, on the left; a mirrored map
 *     (φ = atan2(x, z), before ABI 1.6) likewise.
 * The test classifies every pixel with that rule (exact ray and reflection, directions within
 * 4° of the mark's edges skipped) and requires the marked/unmarked colour. */
static bool probe_marked(const double d[3], bool *near_edge) {
    double hz = sqrt(d[0] * d[0] + d[2] * d[2]), elev = atan2(d[1], hz) * 180 / M_PI;
    double az = atan2(d[0], -d[2]) * 180 / M_PI; /* 0 at −Z, 90 at +X: the mark spans 0..90 */
    const double m = 4;
    *near_edge = fabs(az) < m || fabs(az - 90) < m || fabs(elev) < m || fabs(elev - 45) < m;
    return az > 0 && az < 90 && elev > 0 && elev < 45;
}
static void test_probe(void) {
    enum { PW = 256, PH = 128 };
    char path[512], err[1024];
    snprintf(path, sizeof path, "%s/probe.exr", dir);
    float *px = malloc((size_t)PW * PH * 16);
    for (int y = 0; y < PH; y++)
        for (int x = 0; x < PW; x++) {
            bool mark = x >= PW / 4 && x < PW / 2 && y >= PH / 4 && y < PH / 2;
            float *p = px + ((size_t)y * PW + x) * 4;
            p[0] = mark ? 1.0f : 0.02f, p[1] = mark ? 0.5f : 0.02f, p[2] = mark ? 0.1f : 0.02f, p[3] = 1;
        }
    CHECK_MSG(em_io_write_exr(path, px, PW, PH, NULL, err, sizeof err), "%s", err);
    free(px);
    for (int model = 0; model < 2; model++) {
        const char *const yaw[] = {"envmap.yaw=180", NULL};
        /* model 0: mirror sphere + background; model 1: background only, turned by yaw 180°
         * (the mark then spans −Z…+X turned half a turn: d.x < 0, d.z > 0, behind the camera,
         * so the background must be all dark — yaw turns, it does not mirror) */
        sl_harness *h = make(path, "\"model\": \"mirror\"", model ? yaw : NULL, 1);
        CHECK(h && sl_harness_render(h, img));
        int counted = 0, wrong = 0, quad[2][2] = {{0, 0}, {0, 0}}, ring_right_up = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double n[3], v[3], d[3];
                bool on_sphere = sphere_pixel(x, y, n, v, 0.05);
                if (on_sphere) {
                    double nv = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
                    for (int i = 0; i < 3; i++) d[i] = 2 * nv * n[i] - v[i];
                } else if (!background_pixel(x, y, d)) {
                    continue;
                }
                if (model) d[0] = -d[0], d[2] = -d[2]; /* world → map: R_y(−180°) */
                bool edge, mark = probe_marked(d, &edge);
                const float *p = img + (y * W + x) * 4;
                bool seen = p[0] > 0.5 && p[2] < 0.3;
                if (seen && !on_sphere) quad[y < H / 2][x >= W / 2]++;
                if (seen && on_sphere && x >= W / 2 && y < H / 2) ring_right_up++;
                if (edge) continue;
                counted++;
                if (seen != mark) wrong++;
            }
        printf("probe (marked quadrant u in [1/4, 1/2), v in [1/4, 1/2))%s: %d pixels classified on paper, %d wrong; "
               "marked background pixels: upper-left %d, upper-right %d, lower-left %d, lower-right %d; "
               "marked sphere pixels upper-right %d\n",
               model ? ", yaw 180" : "", counted, wrong, quad[1][0], quad[1][1], quad[0][0], quad[0][1], ring_right_up);
        CHECK(counted > 1500);
        CHECK_MSG(wrong == 0, "%d pixels disagree with the convention", wrong);
        CHECK(quad[1][0] == 0 && quad[0][0] == 0 && quad[0][1] == 0);
        if (!model) CHECK(quad[1][1] > 200 && ring_right_up > 20);
        else CHECK(quad[1][1] == 0);
        sl_harness_destroy(h);
    }
}

/* A sun placed by the convention, found on a mirror sphere where geometry says. The map (made
 * from texel indices alone: 4 × 4 texels of radiance 1000 on black, centred on u = 0.625,
 * v = 0.25 of a 512 × 256 image) puts the sun, worked out by hand from the convention
 * (u = atan2(d.z, d.x)/2π + ½, v = θ/π from +Y):
 *     v = ¼  → θ = 45°:  d.y = cos 45° = √½, horizontal part sin 45° = √½;
 *     u = ⅝  → atan2(d.z, d.x) = 2π(⅝ − ½) = 45°: d.x = d.z = √½ · √½ = ½;
 *     s = (½, √½, ½) — up, to the right and towards the camera.
 * A unit mirror sphere seen from (0, 0, 4) shows it where its normal bisects s and the
 * direction to the camera: n = normalize(s + normalize(c − n)), solved by iterating from
 * n = normalize(s + ẑ) (≈ (0.29, 0.41, 0.87), the upper right of the sphere). The highlight's
 * centroid must be within 1.5 pixels of n's projection. The previous convention (u = ½ at −Z)
 * put this texel at (½, √½, −½), behind the sphere: its highlight lay 5 pixels away, near the
 * upper-right rim; a mirrored map puts it on the left. */
static void test_sun_highlight(void) {
    enum { SW = 512, SH = 256 };
    char path[512], err[1024];
    snprintf(path, sizeof path, "%s/sun_probe.exr", dir);
    float *px = calloc((size_t)SW * SH * 4, sizeof(float));
    for (int y = 0; y < SH; y++)
        for (int x = 0; x < SW; x++) {
            bool sun = x >= 318 && x < 322 && y >= 62 && y < 66; /* centre (320/512, 64/256) = (0.625, 0.25) */
            float *p = px + ((size_t)y * SW + x) * 4;
            p[0] = p[1] = p[2] = sun ? 1000.0f : 0.0f, p[3] = 1;
        }
    CHECK_MSG(em_io_write_exr(path, px, SW, SH, NULL, err, sizeof err), "%s", err);
    free(px);
    const double s[3] = {0.5, sqrt(0.5), 0.5}, cam_z = 4;
    double n[3] = {s[0], s[1], s[2] + 1};
    normalize3(n);
    for (int it = 0; it < 50; it++) { /* n bisects s and the direction from n (on the sphere) to the camera */
        double v[3] = {-n[0], -n[1], cam_z - n[2]};
        normalize3(v);
        for (int i = 0; i < 3; i++) n[i] = s[i] + v[i];
        normalize3(n);
    }
    double f = 1 / tan(20 * M_PI / 180); /* 40° vertical field of view, square image */
    double want_x = (f * n[0] / (cam_z - n[2]) + 1) / 2 * W - 0.5, want_y = (1 - f * n[1] / (cam_z - n[2])) / 2 * H - 0.5;
    sl_harness *h = make(path, "\"model\": \"mirror\"", NULL, 1);
    CHECK(h && sl_harness_render(h, img));
    double sum = 0, cx = 0, cy = 0, peak = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double L = img[(y * W + x) * 4 + 1];
            peak = fmax(peak, L);
            if (L > 1) sum += L, cx += L * x, cy += L * y;
        }
    cx /= fmax(sum, 1e-30), cy /= fmax(sum, 1e-30);
    printf("sun at (u, v) = (0.625, 0.25) -> s = (0.5, 0.707, 0.5) on a mirror sphere: highlight centroid (%.2f, %.2f), "
           "expected (%.2f, %.2f) from n = (%.3f, %.3f, %.3f); peak %.1f\n", cx, cy, want_x, want_y, n[0], n[1], n[2], peak);
    CHECK_MSG(sum > 0, "no highlight at all");
    CHECK_MSG(hypot(cx - want_x, cy - want_y) < 1.5, "highlight at (%.2f, %.2f), expected (%.2f, %.2f)", cx, cy, want_x, want_y);
    sl_harness_destroy(h);
}

/* The core's procedural specs as environments; "uv" encodes the convention itself: an
 * environment-model sphere shows red = u, green = v of its normal. */
static void test_procedural(void) {
    sl_harness *h = make("uv", "\"model\": \"environment\"", NULL, 1);
    CHECK(h && sl_harness_render(h, img));
    double worst = 0;
    int count = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double n[3], v[3], u, vv;
            if (!sphere_pixel(x, y, n, v, 0.3)) continue;
            em_dir_latlong(n, &u, &vv);
            if (u < 0.03 || u > 0.97) continue; /* the seam: bilinear blends 0 and 1 there */
            worst = fmax(worst, fmax(fabs(img[(y * W + x) * 4] - u), fabs(img[(y * W + x) * 4 + 1] - vv)));
            count++;
        }
    printf("\"uv\" environment on an environment sphere: %d pixels, max |(r, g) - (u, v)| %.4f\n", count, worst);
    CHECK(count > 300);
    CHECK_MSG(worst < 0.01, "uv map: %.4f", worst);
    sl_harness_destroy(h);
    const char *specs[] = {"gradient", "checker:8:1,0.5,0.2:0.1,0.1,0.1", "grid:64:1,1,1:0,0,0", "constant:0.5,0.25,1"};
    for (int i = 0; i < 4; i++) {
        h = make(specs[i], "\"model\": \"ggx\", \"roughness\": 0.5", NULL, 1);
        CHECK_MSG(h && sl_harness_render(h, img), "%s", specs[i]);
        CHECK(sl_harness_count_nonfinite(img, W, H) == 0);
        sl_harness_destroy(h);
    }
}

/* ---------------------------------------------------------------- bad input */

static void test_bad_input(void) {
    enum { BW = 64, BH = 32 };
    float *px = malloc(BW * BH * 16);
    for (int y = 0; y < BH; y++)
        for (int x = 0; x < BW; x++) {
            float *p = px + (y * BW + x) * 4;
            p[0] = p[1] = p[2] = 1 + (float)cos((y + 0.5) / BH * M_PI), p[3] = 1;
        }
    px[(5 * BW + 7) * 4 + 0] = NAN;
    px[(9 * BW + 30) * 4 + 1] = INFINITY;
    px[(20 * BW + 3) * 4 + 2] = -INFINITY;
    px[(25 * BW + 50) * 4 + 0] = -2;
    px[(2 * BW + 40) * 4 + 1] = 60000; /* a real value: kept */
    char path[512], err[1024];
    snprintf(path, sizeof path, "%s/bad.exr", dir);
    CHECK(em_io_write_exr(path, px, BW, BH, NULL, err, sizeof err));
    free(px);
    const char *mats[3] = {"\"model\": \"lambert\", \"base_color\": [1, 1, 1]", "\"model\": \"mirror\"",
                           "\"model\": \"ggx\", \"roughness\": 0.4, \"base_color\": [0.5, 0.5, 0.5]"};
    for (int m = 0; m < 3; m++) {
        sl_log_capture(logbuf, sizeof logbuf);
        sl_harness *h = make(path, mats[m], (const char *[]){m == 2 ? "envmap.irradiance=convolved" : "envmap.irradiance=sh", NULL}, 1);
        CHECK(h && sl_harness_render(h, img));
        sl_log_capture(NULL, 0);
        long bad = sl_harness_count_nonfinite(img, W, H), neg = sl_harness_count_negative(img, W, H);
        CHECK_MSG(bad == 0 && neg == 0, "%ld non-finite, %ld negative values out", bad, neg);
        char want[600];
        snprintf(want, sizeof want, "%s: replaced 4 invalid values (1 NaN, 2 infinite, 1 negative)", path);
        CHECK_CONTAINS(logbuf, want);
        const char *first = strstr(logbuf, "replaced 4");
        CHECK_MSG(first && !strstr(first + 1, "replaced 4"), "the warning should come once:\n%s", logbuf);
        sl_harness_destroy(h);
    }
    printf("bad input: NaN/+Inf/-Inf/negative texels replaced, one warning, finite output\n");
}

/* ---------------------------------------------------------------- chains, cache, cost */

static void test_chain_and_cache(void) {
    char src[512], chain[512], head[512], cmd[4096];
    snprintf(src, sizeof src, "%s/colour.exr", dir);
    snprintf(chain, sizeof chain, "%s/colour_ggx.exr", dir);
    snprintf(head, sizeof head, "%s/colour_ggx.1.exr", dir);
    snprintf(cmd, sizeof cmd, "'%s' '%s' --ggx '%s' --size 16 --samples 128 --levels 3 -q", SHADELAB_CUBE, src, chain);
    CHECK(run(cmd) == 0);
    const char *mat = "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 1, \"base_color\": [1, 1, 1], \"roughness\": 0.6";
    const char *own[] = {"envmap.mip_count=3", NULL};
    sl_log_capture(logbuf, sizeof logbuf);
    sl_harness *h = make(head, mat, own, 1);
    CHECK(h && sl_harness_render(h, img));
    sl_log_capture(NULL, 0);
    CHECK_CONTAINS(logbuf, "using its 3 precomputed specular levels");
    CHECK(!strstr(logbuf, "prefiltering the specular chain"));
    sl_harness_destroy(h);
    h = make(src, mat, own, 1);
    CHECK(h && sl_harness_render(h, img2));
    sl_harness_destroy(h);
    sl_compare cmp;
    sl_harness_compare(img, img2, W, H, 0.02, &cmp);
    printf("shadelab-cube --ggx chain vs the plugin's own prefilter: max |diff| %.4f, rms %.5f\n", cmp.max_abs, cmp.rmse);
    CHECK_MSG(cmp.max_abs < 0.02, "chain differs by %.4f", cmp.max_abs);

    /* the disk cache */
    char cache[512];
    snprintf(cache, sizeof cache, "%s/cache", dir);
    setenv("SHADELAB_CACHE", cache, 1);
    const char *cached[] = {"envmap.cache=true", "envmap.mip_count=3", NULL};
    h = make(src, mat, cached, 1);
    CHECK(h && sl_harness_render(h, img));
    sl_harness_destroy(h);
    char sub[600];
    snprintf(sub, sizeof sub, "%s/envmap", cache);
    DIR *d = opendir(sub);
    int files = 0;
    for (struct dirent *e; d && (e = readdir(d));) files += !strncmp(e->d_name, "spec-", 5);
    if (d) closedir(d);
    CHECK_MSG(files == 1, "%d cache files in %s", files, sub);
    sl_log_capture(logbuf, sizeof logbuf);
    h = make(src, mat, cached, 1);
    CHECK(h && sl_harness_render(h, img2));
    sl_log_capture(NULL, 0);
    CHECK_CONTAINS(logbuf, "prefilter cache hit");
    sl_harness_compare(img, img2, W, H, 0, &cmp);
    CHECK_MSG(cmp.max_abs == 0, "cached render differs by %g", cmp.max_abs);
    sl_harness_destroy(h);
    /* another parameter, another entry */
    const char *other[] = {"envmap.cache=true", "envmap.mip_count=3", "envmap.samples=64", NULL};
    sl_log_capture(logbuf, sizeof logbuf);
    h = make(src, mat, other, 1);
    CHECK(h && sl_harness_render(h, NULL));
    sl_log_capture(NULL, 0);
    CHECK_CONTAINS(logbuf, "prefiltering the specular chain");
    sl_harness_destroy(h);
    unsetenv("SHADELAB_CACHE");
    printf("cache: stored, hit on reload with an identical image, missed after a parameter change\n");
}

static void test_cost(void) {
    char src[512];
    snprintf(src, sizeof src, "%s/colour.exr", dir);
    sl_log_capture(logbuf, sizeof logbuf);
    sl_harness *h = make(src, "\"model\": \"mirror\"", NULL, 1);
    CHECK(h && sl_harness_render(h, NULL));
    sl_log_capture(NULL, 0);
    CHECK_MSG(!strstr(logbuf, "prefiltering"), "a mirror-only scene prefiltered:\n%s", logbuf);
    sl_harness_destroy(h);
    /* envmap loaded but off: the same programs and passes as without it */
    const char *scene = "{\"plugins\": [%s], \"materials\": [{\"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5]}],"
                        " \"nodes\": [{\"name\": \"b\", \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"m\"}]}";
    char with[1024], without[1024], err[1024];
    snprintf(with, sizeof with, scene, "\"envmap\"");
    snprintf(without, sizeof without, scene, "");
    sl_harness_structure a, b;
    h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 16, .height = 16, .scene_json = with,
                                             .settings = (const char *[]){"envmap.enabled=false", NULL}}, err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    CHECK(h && sl_harness_render(h, NULL));
    if (h) sl_harness_structure_of(h, &a);
    sl_harness_destroy(h);
    h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 16, .height = 16, .scene_json = without},
                          err, sizeof err);
    CHECK(h && sl_harness_render(h, NULL));
    if (h) sl_harness_structure_of(h, &b);
    sl_harness_destroy(h);
    CHECK(a.pass_count == b.pass_count && a.program_count == b.program_count && a.draw_calls == b.draw_calls);
    CHECK(a.program_count > 0 && !memcmp(a.program_hashes, b.program_hashes, a.program_count * sizeof(uint64_t)));
    printf("cost: mirror-only scene did not prefilter; envmap disabled: %d passes, %d programs, identical hashes\n",
           a.pass_count, a.program_count);
}

/* A constant environment (a colour, no map: SL_ENVIRONMENT_CONSTANT) renders what the general
 * path renders from the same radiance as a "constant:" map, per specular mode and for a dielectric,
 * a metal and a mirror, and prefilters nothing. */
static void test_constant_environment(void) {
    const char *mats[3] = {"\"model\": \"ggx\", \"base_color\": [0.6, 0.08, 0.05], \"roughness\": 0.3",
                           "\"model\": \"ggx\", \"fresnel\": \"metallic-roughness\", \"metallic\": 1, "
                           "\"base_color\": [1, 0.77, 0.34], \"roughness\": 0.35",
                           "\"model\": \"mirror\""};
    const char *modes[3] = {"envmap.specular=fitted", "envmap.specular=fis", "envmap.specular=filtered"};
    for (int m = 0; m < 3; m++)
        for (int k = 0; k < (m < 2 ? 3 : 1); k++) {
            const char *const settings[] = {modes[k], NULL};
            sl_log_capture(logbuf, sizeof logbuf);
            sl_harness *h = make_env("", 40, W, "\"color\": [0.3, 0.35, 0.45], \"intensity\": 0.5", mats[m], settings, 1);
            CHECK(h && sl_harness_render(h, img));
            sl_log_capture(NULL, 0);
            sl_harness_destroy(h);
            CHECK_MSG(!strstr(logbuf, "prefiltering"), "a constant environment prefiltered:\n%s", logbuf);
            sl_log_capture(logbuf, sizeof logbuf);
            h = make_env("", 40, W, "\"map\": \"constant:0.3,0.35,0.45\", \"intensity\": 0.5", mats[m], settings, 1);
            CHECK(h && sl_harness_render(h, img2));
            sl_log_capture(NULL, 0);
            sl_harness_destroy(h);
            /* the general path it is compared with does read the chain */
            CHECK_MSG(m == 2 || strstr(logbuf, "prefiltering"), "the \"constant:\" map did not prefilter:\n%s", logbuf);
            double worst = 0, mean = 0;
            for (int i = 0; i < W * H * 4; i++)
                if (i % 4 != 3) worst = fmax(worst, fabs(img[i] - img2[i]) / fmax(img2[i], 0.05)), mean += img2[i];
            printf("constant environment, material %d, %s: max rel. difference to the general path %.2g (mean %.3f)\n", m,
                   modes[k], worst, mean / (W * H * 3));
            CHECK_MSG(worst < 2e-3 && mean > 0, "material %d, %s: %.4f", m, modes[k], worst);
        }
}

/* ---------------------------------------------------------------- poles */

static void test_poles(void) {
    char path[512], json[2048], err[1024];
    snprintf(path, sizeof path, "%s/colour.exr", dir);
    for (int up = 0; up < 2; up++) {
        snprintf(json, sizeof json,
                 "{\"plugins\": [\"envmap\"], \"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 0], \"target\": [0, %d, 0],"
                 " \"up\": [0, 0, 1], \"fov_y\": 60}], \"environment\": {\"map\": \"%s\"}}",
                 up ? 1 : -1, path);
        sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                              .scene_json = json, .float32 = true}, err, sizeof err);
        CHECK_MSG(h != NULL, "%s", err);
        if (!h) continue;
        CHECK(sl_harness_render(h, img));
        double step = 0;
        for (int y = 0; y + 1 < H; y++)
            for (int x = 0; x + 1 < W; x++)
                for (int c = 0; c < 3; c++) {
                    const float *p = img + (y * W + x) * 4;
                    step = fmax(step, fmax(fabs(p[c] - p[4 + c]), fabs(p[c] - p[W * 4 + c])));
                }
        /* colour = 0.5 + 0.5 d changes by at most ~0.5·(pixel angle) ≈ 0.009 per pixel here */
        printf("pole %s: %ld non-finite values, max step between neighbouring pixels %.4f\n", up ? "up" : "down",
               sl_harness_count_nonfinite(img, W, H), step);
        CHECK(sl_harness_count_nonfinite(img, W, H) == 0);
        CHECK_MSG(step < 0.03, "pole not smooth: step %.4f", step);
        sl_harness_destroy(h);
    }
}

int main(void) {
    snprintf(dir, sizeof dir, "%s", sl_test_dir()); /* removed at exit when every check passed */
    test_furnace();
    test_facing_away();
    test_linear();
    test_lobe();
    test_reference_sun();
    test_filtered_sun();
    test_sh_ringing();
    test_conventions();
    test_probe();
    test_default_horizon();
    test_sky_background();
    test_background_over_ssaa();
    test_default_speckle();
    test_hybrid_sample0();
    test_sun_highlight();
    test_procedural();
    test_bad_input();
    test_chain_and_cache();
    test_cost();
    test_constant_environment();
    test_poles();
    return check_result();
}
