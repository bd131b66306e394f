/* envmap: the procedural sky's start-up path on the CPU (issue 19), against independent
 * computations:
 *   - em_sky_latlong (row-cached sines, one halo per texel) against em_sky_radiance evaluated
 *     at every texel centre outside the sub-sampled ring round the sun: equal to the last bit;
 *   - em_latlong_mips + em_latlong_to_cube_levels against the GPU path they replace
 *     (em_upload_latlong's glGenerateMipmap + em_make_base_cube: envmap_to_cube.frag and
 *     envmap_downsample.frag) on the same sky with a sun disk, every level of a 64² cube:
 *     within half-float rounding; and a wrong mapping (faces swapped) shown to fail the check. */
#include "check.h"
#include "envmap/prefilter.h"
#include "program_loader.h"
#include <shadelab/gl.h>
#include <shadelab/harness.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>


static void test_latlong(void) {
    em_sky s;
    em_sky_default(&s);
    s.sun_elevation_deg = 32, s.sun_azimuth_deg = -105, s.sun_irradiance = 3;
    const int w = 256, h = 128;
    em_image img = {0};
    em_sky_latlong(&s, w, h, &img);
    double r = s.sun_radius_deg * M_PI / 180, e = s.sun_elevation_deg * M_PI / 180, a = s.sun_azimuth_deg * M_PI / 180;
    double sd[3] = {cos(e) * sin(a), sin(e), cos(e) * cos(a)};
    long checked = 0, equal = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double d[3], v[3];
            em_latlong_dir((x + 0.5) / w, (y + 0.5) / h, d);
            double cs = d[0] * sd[0] + d[1] * sd[1] + d[2] * sd[2];
            if (acos(fmax(-1, fmin(1, cs))) < r + 4 * M_PI / h / fmax(sin((y + 0.5) / h * M_PI), 0.05)) continue;
            em_sky_radiance(&s, d, v);
            const float *p = img.px + ((size_t)y * w + x) * 4;
            checked++;
            equal += p[0] == (float)v[0] && p[1] == (float)v[1] && p[2] == (float)v[2] && p[3] == 1.0f;
        }
    CHECK_MSG(checked > w * h * 9 / 10 && equal == checked, "sky lat-long: %ld of %ld texels equal em_sky_radiance", equal,
              checked);
    em_image_free(&img);
}

/* |a − b| / max(|b|, 0.05) over a level's RGB: the largest and the mean */
static double level_error(const float *a, const float *b, int texels, double *mean) {
    double m = 0, sum = 0;
    for (int i = 0; i < texels; i++)
        for (int c = 0; c < 3; c++) {
            double e = fabs(a[i * 4 + c] - b[i * 4 + c]) / fmax(fabs(b[i * 4 + c]), 0.05);
            sum += e;
            m = fmax(m, e);
        }
    if (mean) *mean = sum / (3.0 * texels);
    return m;
}

/* ∫ L dω of channel 0 over the sphere, from a cube level and from a lat-long */
static double cube_integral(const float *faces, int n) {
    double sum = 0;
    for (int f = 0; f < 6; f++)
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++) sum += faces[(((size_t)f * n + y) * n + x) * 4] * em_texel_solid_angle(n, x, y);
    return sum;
}
static double latlong_integral(const em_image *img) {
    double sum = 0;
    for (int y = 0; y < img->h; y++) {
        double w = (2 * M_PI / img->w) * (cos(M_PI * y / img->h) - cos(M_PI * (y + 1) / img->h));
        for (int x = 0; x < img->w; x++) sum += img->px[((size_t)y * img->w + x) * 4] * w;
    }
    return sum;
}

static void test_base_cube(em_gpu *g, float sun) {
    em_sky s;
    em_sky_default(&s);
    s.sun_elevation_deg = 20, s.sun_azimuth_deg = 40, s.sun_irradiance = sun;
    em_image img = {0};
    em_sky_latlong(&s, 512, 256, &img);
    const int size = 64, levels = em_max_levels(size);
    unsigned src = em_upload_latlong(&img);
    unsigned gpu = em_make_base_cube(g, src, false, img.w, img.h, size);
    em_image mips[16];
    int n = 0;
    em_latlong_mips(&img, mips, 16, &n);
    CHECK_MSG(n == em_max_levels(512), "lat-long mips: %d levels, GL has %d", n, em_max_levels(512));
    float *cpu[16] = {0};
    em_latlong_to_cube_levels(mips, n, size, levels, cpu);
    for (int l = 0; l < levels; l++) {
        int s2 = size >> l;
        float *ref = em_read_cube(gpu, l, s2);
        double mean, err = level_error(cpu[l], ref, 6 * s2 * s2, &mean);
        double want = latlong_integral(&img), got = cube_integral(cpu[l], s2), gl = cube_integral(ref, s2);
        /* The CPU levels keep the source's energy (solid-angle-weighted means, in float and
         * double); the GL path rounds every level to half floats, and llvmpipe's rounding loses
         * ~3e-4 of the integral per level (measured: 2.6464 → 2.6392 over 7 levels, the CPU path
         * 2.6463 at every level). Per texel the two agree to half-float precision and that drift,
         * except right at a sun disk, whose texels hold a 600:1 step that each path filters
         * with its own precision of the mip level (max 12 % at one texel there; mean 6e-4). */
        CHECK_MSG(fabs(got - want) < (sun > 0 ? 1e-3 : 1e-4) * want,
                  "sun %g, level %d: CPU cube integral %.6f vs the lat-long's %.6f (GL path %.6f)", sun, l, got, want, gl);
        if (sun > 0) CHECK_MSG(mean < 3e-3, "sun %g, level %d (%d²): CPU vs GL mean relative error %.2e", sun, l, s2, mean);
        else CHECK_MSG(err < 5e-3, "sun %g, level %d (%d²): CPU vs GL largest relative error %.2e", sun, l, s2, err);
        if (l == 0) { /* the comparison can fail: faces +X and −X swapped */
            float *swapped = malloc((size_t)6 * s2 * s2 * 16);
            memcpy(swapped, cpu[0], (size_t)6 * s2 * s2 * 16);
            memcpy(swapped, cpu[0] + (size_t)s2 * s2 * 4, (size_t)s2 * s2 * 16);
            memcpy(swapped + (size_t)s2 * s2 * 4, cpu[0], (size_t)s2 * s2 * 16);
            double bad_mean, bad = level_error(swapped, ref, 6 * s2 * s2, &bad_mean);
            CHECK_MSG(bad > 5e-3 && bad_mean > 3e-3, "a swapped-face cube passes the check (%.2e, mean %.2e)", bad, bad_mean);
            free(swapped);
        }
        free(ref);
        free(cpu[l]);
    }
    for (int l = 1; l < n; l++) free(mips[l].px);
    glDeleteTextures(1, &gpu);
    glDeleteTextures(1, &src);
    em_image_free(&img);
}

int main(void) {
    test_latlong();
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 16, .height = 16,
                                                          .scene_json = "{}"}, err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return check_result();
    em_gpu g = {.load = loader, .unit = 20};
    CHECK_MSG(em_gpu_init(&g, err, sizeof err), "%s", err);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    test_base_cube(&g, 0);
    test_base_cube(&g, 3);
    em_gpu_free(&g);
    free_programs();
    sl_harness_destroy(h);
    return check_result();
}
