/* Fused full-screen passes (sdk/include/shadelab/ext/post.h): tonemap's per-pixel map runs inside
 * TAA's one draw (history and output together) instead of as a pass of its own. The same frames
 * are rendered twice, fused and with SHADELAB_NO_FUSION=1 (every pass on its own): a first frame,
 * a still accumulating, the camera moving (the resolve), the still again until it converges.
 * Checked per frame: the displayed images agree within 1/255 (the fused map sees TAA's value
 * before it is stored in 16 bits, so rounding may differ by one code value), the final linear
 * colours within 2e-3 relative; tonemap did not run as a pass but is in effect when fused, ran
 * when not; the fused frame has one draw call less. With FXAA or no antialiasing nothing is fused
 * (no pass accepts), and tonemap's identity setting is neither run nor fused. */
#include "check.h"
#include <shadelab/harness.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 48
#define H 32
#define FRAMES 10
enum { MOVE_AT = 3, MOVE_FRAMES = 2 };

static const char *SCENE =
    "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 0.4, 4], \"target\": [0, 0, 0], \"fov_y\": 40}],"
    " \"materials\": [{\"name\": \"m\", \"model\": \"ggx\", \"base_color\": [0.8, 0.3, 0.1], \"roughness\": 0.3},"
    "  {\"name\": \"f\", \"base_color\": [0.5, 0.5, 0.5]}],"
    " \"nodes\": [{\"name\": \"s\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.8}, \"material\": \"m\"},"
    "  {\"name\": \"g\", \"translate\": [0, -0.8, 0], \"mesh\": {\"primitive\": \"plane\", \"size\": 6}, \"material\": \"f\"}],"
    " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [-1, -1, -1], \"intensity\": 6}]}";

typedef struct run_result {
    float display[FRAMES][W * H * 4], color[FRAMES][W * H * 4];
    bool tonemap_ran[FRAMES], tonemap_in_effect[FRAMES];
    int draws[FRAMES];
} run_result;

static bool listed(const char *const *names, int n, const char *name) {
    for (int i = 0; i < n; i++)
        if (!strcmp(names[i], name)) return true;
    return false;
}

static sl_harness *make(const char *const *settings) {
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                          .scene_json = SCENE, .settings = settings, .strict = true,
                                                          .plugins = (const char *[]){"ggx", "tonemap", NULL}},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    return h;
}

/* keep: read the linear colour after each frame (the core's display pass then encodes) */
static void run(bool fused, bool keep, run_result *out) {
    setenv("SHADELAB_NO_FUSION", fused ? "0" : "1", 1);
    sl_harness *h = make((const char *[]){"aa.taa_frames=4", "tonemap.operator=aces", "tonemap.exposure=0.5", NULL});
    if (!h) return;
    for (int f = 0; f < FRAMES; f++) {
        if (f >= MOVE_AT && f < MOVE_AT + MOVE_FRAMES)
            CHECK(sl_harness_set_camera(h, (const float[]){0.3f * (float)(f - MOVE_AT + 1), 0.4f, 4}, (const float[]){0, 0, 0}));
        sl_harness_set_frame(h, 0);
        CHECK(sl_harness_render(h, keep ? out->color[f] : NULL) && sl_harness_read_display(h, out->display[f]));
        sl_harness_structure s;
        sl_harness_structure_of(h, &s);
        out->tonemap_ran[f] = listed(s.passes, s.pass_count, "tonemap");
        out->tonemap_in_effect[f] = listed(s.in_effect, s.effect_count, "tonemap");
        out->draws[f] = s.draw_calls;
    }
    sl_harness_destroy(h);
}

static void compare(bool keep) {
    static run_result a, b;
    run(true, keep, &a);
    run(false, keep, &b);
    for (int f = 0; f < FRAMES; f++) {
        double disp = 0, rel = 0;
        for (int i = 0; i < W * H * 4; i++) {
            if (i % 4 == 3) continue;
            disp = fmax(disp, fabs(a.display[f][i] - b.display[f][i]));
            if (keep) rel = fmax(rel, fabs(a.color[f][i] - b.color[f][i]) / fmax(fabs(b.color[f][i]), 0.05));
        }
        printf("%s frame %d: display max %.2f/255%s, tonemap %s fused, %s unfused; draws %d fused, %d unfused\n",
               keep ? "kept colour," : "on the fly,", f, disp * 255, keep ? "" : "", a.tonemap_ran[f] ? "ran" : "not run",
               b.tonemap_ran[f] ? "ran" : "not run", a.draws[f], b.draws[f]);
        CHECK_MSG(disp <= 1.0 / 255 + 1e-6, "frame %d: fused and unfused displays differ by %.2f/255", f, disp * 255);
        CHECK_MSG(rel <= 2e-3, "frame %d: linear colours differ by %.2g relative", f, rel);
        CHECK_MSG(!a.tonemap_ran[f] && a.tonemap_in_effect[f] && b.tonemap_ran[f], "frame %d: fusion", f);
        CHECK_MSG(a.draws[f] == b.draws[f] - 1, "frame %d: %d draws fused, %d unfused", f, a.draws[f], b.draws[f]);
    }
    setenv("SHADELAB_NO_FUSION", "0", 1);
}

/* no pass accepts: nothing is fused */
static void not_fused(const char *what, const char *const *settings, bool tonemap_runs) {
    sl_harness *h = make(settings);
    if (!h) return;
    CHECK(sl_harness_render(h, NULL));
    sl_harness_structure s;
    sl_harness_structure_of(h, &s);
    bool ran = listed(s.passes, s.pass_count, "tonemap"), effect = listed(s.in_effect, s.effect_count, "tonemap");
    printf("%s: tonemap %s\n", what, ran ? "ran" : effect ? "in effect" : "not in effect");
    CHECK_MSG(ran == tonemap_runs && effect == tonemap_runs, "%s", what);
    sl_harness_destroy(h);
}

int main(void) {
    compare(false);
    compare(true);
    not_fused("fxaa", (const char *[]){"aa.method=fxaa", NULL}, true);
    not_fused("no antialiasing", (const char *[]){"aa.method=none", NULL}, true);
    not_fused("tonemap's identity", (const char *[]){"tonemap.operator=linear", "tonemap.dither=false", NULL}, false);
    return check_result();
}
