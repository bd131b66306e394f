/* Headless test of the example plugin with the SDK's harness (link shadelab::harness).
 * Each feature is checked against its closed form on the harness's default scene (scenes/basic.json: Lambert, so
 * outgoing radiance is linear in the base colour):
 *   tint     (SURFACE hook)  every surface pixel = baseline × (1 - s + s·tint_color), per channel;
 *                            background pixels unchanged
 *   vignette (POST pass)     every pixel = input × max(0, 1 - strength·|d|²/2), d = pixel centre
 *                            in [-1,1]²
 *   disabled                 example.enabled=false renders exactly like not loading it
 * Tolerance: 1% relative + 2e-3 absolute (RGBA16F colour target: 11-bit mantissa). */
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define W 96
#define H 64
static int failures;
#define CHECK(cond, ...) do { if (!(cond)) { failures++; printf("FAIL %s:%d: ", __FILE__, __LINE__); printf(__VA_ARGS__); printf("\n"); } } while (0)

static float *render(const char *const *plugins, const char *const *settings) {
    char err[4096];
    sl_harness_desc d = {.struct_size = sizeof d, .width = W, .height = H, .plugins = plugins, .settings = settings,
                         .strict = true};
    sl_harness *h = sl_harness_create(&d, err, sizeof err);
    if (!h) { printf("FAIL: harness: %s\n", err); exit(1); }
    float *img = malloc(sizeof(float) * W * H * 4);
    if (!sl_harness_render(h, img)) { printf("FAIL: render\n"); exit(1); }
    sl_harness_destroy(h);
    return img;
}

static bool close_to(float got, float want) { return fabsf(got - want) <= 0.01f * fabsf(want) + 2e-3f; }

int main(void) {
    const char *plugins[] = {EXAMPLE_PLUGIN_PATH, NULL};
    const char *off[] = {"example.enabled=false", NULL};
    const char *tint_only[] = {"example.vignette=false", "example.tint_strength=0.75", NULL};
    const char *vignette_only[] = {"example.tint=false", "example.vignette_strength=1.2", NULL};
    float *none = render(NULL, NULL);
    float *base = render(plugins, off);
    float *tint = render(plugins, tint_only);
    float *vig = render(plugins, vignette_only);
    float *both = render(plugins, NULL);

    sl_compare c;
    sl_harness_compare(none, base, W, H, 0.0, &c);
    CHECK(c.max_abs == 0, "loaded but disabled must render exactly like not loaded (max diff %g)", c.max_abs);

    const float s = 0.75f, t[3] = {1.0f, 0.55f, 0.2f}; /* example.tint_color default */
    long tinted = 0, bad = 0;
    for (int i = 0; i < W * H; i++) {
        bool is_bg = true, is_tint = true;
        for (int k = 0; k < 3; k++) {
            float b = base[i * 4 + k], g = tint[i * 4 + k];
            is_bg &= close_to(g, b);
            is_tint &= close_to(g, b * (1 - s + s * t[k]));
        }
        tinted += is_tint && !is_bg;
        bad += !is_tint && !is_bg;
    }
    CHECK(bad == 0, "tint: %ld pixels are neither untouched background nor baseline x (1-s+s*tint)", bad);
    CHECK(tinted > W * H / 3, "tint: only %ld of %d pixels tinted (the hook did not run?)", tinted, W * H);

    const float vs = 1.2f;
    long vbad = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            /* rows top to bottom; v_uv.y = 0 at the bottom row */
            float dx = (x + 0.5f) / W * 2 - 1, dy = (H - 1 - y + 0.5f) / H * 2 - 1;
            float k = fmaxf(0.f, 1.f - 0.5f * vs * (dx * dx + dy * dy));
            for (int ch = 0; ch < 3; ch++) {
                int i = (y * W + x) * 4 + ch;
                if (!close_to(vig[i], base[i] * k)) vbad++;
            }
        }
    CHECK(vbad == 0, "vignette: %ld channel values differ from input x max(0, 1 - strength*r^2/2)", vbad);
    sl_harness_compare(vig, base, W, H, 0.01, &c);
    CHECK(c.pixels_over > W * H / 4, "vignette: only %ld pixels changed", c.pixels_over);

    sl_harness_compare(both, base, W, H, 0.01, &c);
    CHECK(c.pixels_over > W * H / 2, "defaults (tint + vignette): only %ld pixels changed", c.pixels_over);
    CHECK(sl_harness_count_nonfinite(both, W, H) == 0, "non-finite values");

    free(none); free(base); free(tint); free(vig); free(both);
    if (failures) { printf("%d check(s) failed\n", failures); return 1; }
    printf("example plugin: tint, vignette and off all match their closed forms\n");
    return 0;
}
