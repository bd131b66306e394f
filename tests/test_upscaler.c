/* The upscaler (ABI 1.18, pass.h SL_SIZE_OUTPUT): a pass whose "color" output has the output size
 * reads "color" at the render size (core.render_scale of the output) and writes it at the output
 * size, passes after it see the output size, and the image read back and shown is at the output
 * size, not scaled again. Test plugin tp-upscale: its upscaler writes the render texel each output
 * pixel falls in (nearest) and the render width it read; its pass after writes the sl_frame.width
 * it was given. When the upscaler does not run, the core scales "color" up bilinearly: compared
 * with a bilinear scale-up computed here of the same scene rendered at the render size. */
#include "check.h"
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 64
#define H 48

static sl_harness *open_h(int w, int h, const char *const *settings) {
    char err[4096] = "";
    const char *plugins[] = {SL_TEST_PLUGIN_DIR "/tp-upscale/tp-upscale.so", NULL};
    sl_harness *hh = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = w, .height = h,
                                                          .plugins = plugins, .settings = settings, .strict = true},
                                       err, sizeof err);
    CHECK_MSG(hh != NULL, "harness: %s", err);
    return hh;
}

static bool ran(sl_harness *h, const char *pass) {
    sl_harness_structure s;
    sl_harness_structure_of(h, &s);
    for (int i = 0; i < s.pass_count; i++)
        if (!strcmp(s.passes[i], pass)) return true;
    return false;
}

/* Each output pixel holds the render texel it falls in, the render width, and the width the pass
 * after the upscaler saw; rows top first, texel rows from the bottom. */
static long wrong_texels(const float *img, int scale_down, int render_w) {
    long wrong = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const float *p = img + ((size_t)y * W + x) * 4;
            int tx = x / scale_down, ty = (H - 1 - y) / scale_down;
            wrong += p[0] != tx || p[1] != ty || p[2] != render_w || p[3] != W;
        }
    return wrong;
}

static void test_sizes(void) {
    sl_harness *h = open_h(W, H, (const char *[]){"aa.enabled=false", "core.render_scale=0.5", NULL});
    if (!h) return;
    static float img[W * H * 4];
    CHECK(sl_harness_render(h, img) && ran(h, "tp-upscale") && ran(h, "tp-after"));
    long wrong = wrong_texels(img, 2, W / 2);
    CHECK_MSG(wrong == 0, "scale 0.5: %ld pixels do not hold their render texel, the render width %d and the output "
              "width %d (first pixel: %g %g %g %g)", wrong, W / 2, W, img[0], img[1], img[2], img[3]);
    /* the display written on the fly by the passes from the upscaler on, at the output size:
     * texel 0 (values 0) in columns 0-1, texels >= 1 (values >= 1, shown as 1) after */
    CHECK(sl_harness_render(h, NULL) && sl_harness_read_display(h, img));
    long off = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) off += fabsf(img[((size_t)y * W + x) * 4] - (x < 2 ? 0.0f : 1.0f)) > 1e-6f;
    CHECK_MSG(off == 0, "the display is not the upscaler's output at the output size in %ld pixels", off);
    /* a new render scale: the same plan at another render size */
    char err[256];
    CHECK(sl_harness_set(h, "core.render_scale=1", err, sizeof err) && sl_harness_render(h, img));
    wrong = wrong_texels(img, 1, W);
    CHECK_MSG(wrong == 0, "scale 1: %ld pixels wrong", wrong);
    sl_harness_destroy(h);
}

/* Bilinear at pixel centres, clamped to the edges: what the window's GL_LINEAR present shows. */
static void bilinear(const float *src, int w, int h, float *dst) {
    for (int y = 0; y < H; y++) {
        double fy = fmin(fmax((y + 0.5) * h / H - 0.5, 0), h - 1);
        int y0 = (int)fy, y1 = y0 + 1 < h ? y0 + 1 : y0;
        for (int x = 0; x < W; x++) {
            double fx = fmin(fmax((x + 0.5) * w / W - 0.5, 0), w - 1);
            int x0 = (int)fx, x1 = x0 + 1 < w ? x0 + 1 : x0;
            double ax = fx - x0, ay = fy - y0;
            for (int c = 0; c < 3; c++) {
                double top = src[((size_t)y0 * w + x0) * 4 + c] * (1 - ax) + src[((size_t)y0 * w + x1) * 4 + c] * ax;
                double bot = src[((size_t)y1 * w + x0) * 4 + c] * (1 - ax) + src[((size_t)y1 * w + x1) * 4 + c] * ax;
                dst[((size_t)y * W + x) * 4 + c] = (float)(top * (1 - ay) + bot * ay);
            }
        }
    }
}

static void test_inactive_upscaler(void) {
    static float small[W / 2 * H / 2 * 4], expect[W * H * 4], img[W * H * 4];
    sl_harness *h = open_h(W / 2, H / 2, (const char *[]){"aa.enabled=false", "tp-upscale.active=false", NULL});
    if (!h) return;
    CHECK(sl_harness_render(h, small));
    sl_harness_destroy(h);
    bilinear(small, W / 2, H / 2, expect);
    h = open_h(W, H, (const char *[]){"aa.enabled=false", "tp-upscale.active=false", "core.render_scale=0.5", NULL});
    if (!h) return;
    CHECK(sl_harness_render(h, img) && !ran(h, "tp-upscale") && ran(h, "tp-after"));
    sl_harness_destroy(h);
    double worst = 0, range = 0;
    for (int i = 0; i < W * H * 4; i++) {
        if (i % 4 == 3) continue;
        worst = fmax(worst, fabs((double)img[i] - expect[i]));
        range = fmax(range, fabs((double)expect[i]));
    }
    printf("upscaler off: the core's bilinear scale-up against this test's, largest difference %.2g (values up to %.2g)\n",
           worst, range);
    CHECK_MSG(range > 0.1, "the scene is black: the test cannot fail");
    CHECK_MSG(worst <= 2e-3 * fmax(range, 1), "the core's scale-up differs from bilinear by %g", worst);
}

int main(void) {
    test_sizes();
    test_inactive_upscaler();
    return check_result();
}
