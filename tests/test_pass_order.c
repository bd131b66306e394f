/* Pass order and plugin dependencies (issue 13):
 * - a post pass a third party writes at SL_STAGE_POST (tp-good's gain, standing in for a bloom)
 *   runs before tonemap's pass (SL_STAGE_TONEMAP) whichever plugin loads first;
 * - a plugin is off while a plugin it requires (`dependencies`) is switched off, live or at start,
 *   and back on with it;
 * - a plugin's vertex hook (tp-good's tp_vertex, gated on the material key tp_lift) moves the
 *   geometry, and switching the plugin off live gives the fresh start's programs and pixels. */
#include "check.h"
#include <shadelab/harness.h>
#include <stdlib.h>
#include <string.h>

static int index_of(const sl_harness_structure *s, const char *name) {
    for (int i = 0; i < s->pass_count; i++)
        if (!strcmp(s->passes[i], name)) return i;
    return -1;
}

static sl_harness *make(const char *const *plugins, const char *const *settings) {
    char err[2048];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 32, .height = 32,
                                                          .plugins = plugins, .settings = settings, .strict = true},
                                      err, sizeof err);
    if (!h) fprintf(stderr, "harness: %s\n", err);
    return h;
}

int main(void) {
    setenv("SHADELAB_PLUGIN_PATH", SL_TEST_PLUGIN_DIR, 1);
    const char *const *orders[2] = {(const char *[]){"tonemap", "tp-good", NULL}, (const char *[]){"tp-good", "tonemap", NULL}};
    for (int o = 0; o < 2; o++) {
        sl_harness *h = make(orders[o], (const char *[]){"tp-good.gain=2", NULL});
        CHECK(h != NULL);
        if (!h) continue;
        /* with the final colour kept, the core's display pass runs (without, tonemap writes the
         * display itself: tests/test_display_on_write.c) */
        static float color[32 * 32 * 4];
        CHECK(sl_harness_render(h, color));
        sl_harness_structure s;
        sl_harness_structure_of(h, &s);
        int gain = index_of(&s, "tp-good-gain"), tone = index_of(&s, "tonemap"), display = index_of(&s, "display");
        printf("load order %s, %s: gain pass %d, tonemap %d, display %d\n", orders[o][0], orders[o][1], gain, tone, display);
        CHECK_MSG(gain >= 0 && tone > gain && display > tone, "load order %d: gain %d, tonemap %d, display %d", o, gain, tone,
                  display);
        sl_harness_destroy(h);
    }

    /* tp-requires-good requires tp-good: off with it, on with it; its gain pass shows it */
    char err[512];
    const char *const deps[] = {"tp-requires-good", NULL};
    const char *const gains[] = {"tp-good.gain=2", "tp-requires-good.gain=2", NULL};
    sl_harness *h = make(deps, gains);
    CHECK(h != NULL);
    if (!h) return check_result();
    sl_harness_structure s;
    CHECK(sl_harness_render(h, NULL));
    sl_harness_structure_of(h, &s);
    CHECK(index_of(&s, "tp-requires-good-gain") >= 0 && index_of(&s, "tp-good-gain") >= 0);
    CHECK(sl_harness_set(h, "tp-good.enabled=false", err, sizeof err));
    CHECK(sl_harness_render(h, NULL));
    sl_harness_structure_of(h, &s);
    CHECK_MSG(index_of(&s, "tp-requires-good-gain") < 0, "a plugin whose dependency is off still runs its pass");
    CHECK(index_of(&s, "tp-good-gain") < 0);
    CHECK(sl_harness_set(h, "tp-good.enabled=true", err, sizeof err));
    CHECK(sl_harness_render(h, NULL));
    sl_harness_structure_of(h, &s);
    CHECK(index_of(&s, "tp-requires-good-gain") >= 0);
    sl_harness_destroy(h);

    /* vertex hook: a sphere lifted by 0.5 renders differently; off live == off from the start */
    const char *scene = "{\"cameras\": [{\"name\": \"c\", \"position\": [0, 0, 4], \"target\": [0, 0, 0]}],"
                        " \"materials\": [{\"name\": \"m\", \"tp_lift\": 0.5}],"
                        " \"nodes\": [{\"name\": \"s\", \"mesh\": {\"primitive\": \"sphere\", \"radius\": 0.5}, \"material\": \"m\"}],"
                        " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, 0, -1], \"intensity\": 3}]}";
    static float on[32 * 32 * 4], live[32 * 32 * 4], fresh[32 * 32 * 4];
    sl_harness_structure s_live, s_fresh;
    const char *const tp[] = {"tp-good", NULL};
    h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 32, .height = 32,
                                             .scene_json = scene, .plugins = tp, .strict = true},
                          err, sizeof err);
    CHECK_MSG(h != NULL, "%s", err);
    if (!h) return check_result();
    CHECK(sl_harness_render(h, on));
    CHECK(sl_harness_set(h, "tp-good.enabled=false", err, sizeof err));
    sl_harness_set_frame(h, 0);
    CHECK(sl_harness_render(h, live));
    sl_harness_structure_of(h, &s_live);
    sl_harness_destroy(h);
    h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 32, .height = 32,
                                             .scene_json = scene, .plugins = tp, .strict = true,
                                             .settings = (const char *[]){"tp-good.enabled=false", NULL}},
                          err, sizeof err);
    CHECK(h && sl_harness_render(h, fresh));
    if (h) sl_harness_structure_of(h, &s_fresh);
    sl_harness_destroy(h);
    sl_compare c;
    sl_harness_compare(on, live, 32, 32, 1e-3, &c);
    CHECK_MSG(c.pixels_over > 20, "the vertex hook moved nothing (%ld pixels differ)", c.pixels_over);
    sl_harness_compare(live, fresh, 32, 32, 1e-6, &c);
    CHECK_MSG(c.max_abs <= 1e-6 && sl_harness_structure_equal(&s_live, &s_fresh),
              "vertex hook off live differs from the fresh start (max %g)", c.max_abs);
    return check_result();
}
