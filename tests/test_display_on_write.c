/* Display encoding on the fly (issue 18 item 3, sl_pass_desc.display_on_write, ABI 1.8): when the
 * last writers of "color" declare display_on_write, they write the sRGB "display" themselves and
 * the core's display pass does not run. For each configuration two harnesses render the same
 * frames: one asks for the final linear "color" (sl_harness_render with a buffer: the display pass
 * runs as before), the other does not (the last passes write "display"). Checked:
 *   - the display pass ran in the first and not in the second (the full-screen pass is gone);
 *   - both displays agree within 1/255 (plus rounding);
 *   - the second display equals the IEC 61966-2-1 encoding of the first's final linear colour,
 *     clamped to [0,1], computed here on the CPU (an independent closed form), within 1/255;
 *   - alpha is 1.
 * Configurations: the forward pass alone, the forward pass with envmap's background drawn in place,
 * TAA, TAA with tonemap fused into its draw (ext/post.h), tonemap (dithered), tonemap + FXAA, supersampling (the resolve pass writes the display),
 * accumulated frames (only post passes may write it), and RGBA32F colour. */
#include "check.h"
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 48
#define H 32

static double srgb_encode(double c) {
    c = c != c ? 0 : c < 0 ? 0 : c > 1 ? 1 : c;
    return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1 / 2.4) - 0.055;
}

static bool ran(sl_harness *h, const char *pass) {
    sl_harness_structure s;
    sl_harness_structure_of(h, &s);
    for (int i = 0; i < s.pass_count; i++)
        if (!strcmp(s.passes[i], pass)) return true;
    return false;
}

typedef struct config {
    const char *name, *scene;       /* scene file under scenes/, NULL = the bare scene */
    const char *plugins[4], *settings[6];
    int frames, accumulate;
    bool float32;
    const char *must_run;           /* a pass that must have run in the routed frame */
} config;

static sl_harness *make(const config *c, char *err, size_t n) {
    char path[4096];
    if (c->scene) snprintf(path, sizeof path, "%s/%s", SL_SCENES_DIR, c->scene);
    return sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                .scene_file = c->scene ? path : NULL, .plugins = c->plugins,
                                                .settings = c->settings, .accumulate = c->accumulate,
                                                .float32 = c->float32, .strict = true},
                             err, n);
}

/* One harness at a time: a harness's GL context is the current one only until the next is made. */
static bool render(const config *c, bool keep, float *color, float *display, bool *display_ran, bool *must_ran) {
    char err[4096];
    sl_harness *h = make(c, err, sizeof err);
    if (!h) {
        printf("%s: %s\n", c->name, err);
        return false;
    }
    bool ok = true;
    for (int f = 0; f < (c->frames > 0 ? c->frames : 1); f++) ok = ok && sl_harness_render(h, keep ? color : NULL);
    ok = ok && sl_harness_read_display(h, display);
    *display_ran = ran(h, "display");
    *must_ran = !c->must_run || ran(h, c->must_run);
    sl_harness_destroy(h);
    return ok;
}

static void run(const config *c) {
    static float color[W * H * 4], d_kept[W * H * 4], d_direct[W * H * 4];
    bool kept_display, direct_display, kept_must, direct_must;
    CHECK_MSG(render(c, true, color, d_kept, &kept_display, &kept_must), "%s", c->name);
    CHECK_MSG(render(c, false, NULL, d_direct, &direct_display, &direct_must), "%s", c->name);
    CHECK_MSG(kept_display, "%s: the display pass runs when the final colour is kept", c->name);
    CHECK_MSG(!direct_display, "%s: no display pass when the last passes write it", c->name);
    CHECK_MSG(direct_must, "%s: %s ran", c->name, c->must_run);
    double between = 0, encode = 0, alpha = 0;
    for (int i = 0; i < W * H; i++) {
        for (int k = 0; k < 3; k++) {
            between = fmax(between, fabs(d_kept[i * 4 + k] - d_direct[i * 4 + k]));
            encode = fmax(encode, fabs(srgb_encode(color[i * 4 + k]) - d_direct[i * 4 + k]));
        }
        alpha = fmax(alpha, fabs(d_direct[i * 4 + 3] - 1.0));
    }
    printf("%-22s display pass vs on the fly: max %.2f/255; on the fly vs CPU sRGB of the final colour: max %.2f/255\n",
           c->name, between * 255, encode * 255);
    CHECK_MSG(between <= 1.0 / 255 + 1e-6, "%s", c->name);
    CHECK_MSG(encode <= 1.0 / 255 + 1e-6, "%s", c->name);
    CHECK_MSG(alpha <= 1e-6, "%s", c->name);
}

int main(void) {
    const config configs[] = {
        {.name = "forward only", .settings = {"aa.method=none"}, .must_run = "forward"},
        {.name = "envmap background", .scene = "env_sky.json", .settings = {"aa.method=none", "tonemap.enabled=false"},
         .must_run = "envmap-background"},
        {.name = "taa", .frames = 3, .must_run = "aa-taa"},
        {.name = "taa + tonemap (fused)", .plugins = {"tonemap"}, .frames = 3, .must_run = "aa-taa"},
        {.name = "tonemap (dither)", .plugins = {"tonemap"}, .settings = {"aa.method=none", "tonemap.exposure=1"},
         .frames = 2, .must_run = "tonemap"},
        {.name = "tonemap + fxaa", .plugins = {"tonemap"}, .settings = {"aa.method=fxaa"}, .must_run = "aa-fxaa"},
        {.name = "ssaa resolve", .settings = {"aa.method=none", "core.ssaa=2"}, .must_run = "ssaa-resolve"},
        {.name = "accumulate + tonemap", .plugins = {"tonemap"}, .settings = {"aa.method=none"}, .accumulate = 3,
         .must_run = "tonemap"},
        {.name = "float32 colour", .settings = {"aa.method=none"}, .float32 = true},
    };
    for (size_t i = 0; i < sizeof configs / sizeof *configs; i++) run(&configs[i]);
    /* accumulated frames without a post pass: the forward pass runs once per sub-frame before
     * the mean, so the display pass must run */
    {
        char err[4096];
        const char *s[] = {"aa.method=none", NULL};
        sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W,
                                                              .height = H, .settings = s, .accumulate = 2},
                                          err, sizeof err);
        CHECK(h && sl_harness_render(h, NULL) && ran(h, "display"));
        sl_harness_destroy(h);
    }
    return check_result();
}
