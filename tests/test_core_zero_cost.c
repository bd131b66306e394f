/* "Unused costs nothing", checked structurally: with a plugin loaded but disabled, the composed
 * programs (hashes), the passes that run and the draw calls are identical to not loading it; and
 * a material that does not carry a plugin's key gets none of its code. */
#include "check.h"
#include <shadelab/harness.h>
#include <stdlib.h>
#include <string.h>

static const char *scene =
    "{\"materials\": [{\"name\": \"plain\", \"base_color\": [0.5, 0.5, 0.5]},\n"
    "                 {\"name\": \"marked\", \"base_color\": [0.5, 0.5, 0.5], \"tp_mark\": true}],\n"
    " \"nodes\": [{\"name\": \"a\", \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"plain\"},\n"
    "           {\"name\": \"b\", \"translate\": [2, 0, 0], \"mesh\": {\"primitive\": \"sphere\"}, \"material\": \"marked\"}],\n"
    " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [0, -1, -1]}]}\n";

static bool structure(const char *const *plugins, const char *const *settings, sl_harness_structure *st) {
    char err[4096];
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = 32, .height = 32,
                                                          .scene_json = scene, .plugins = plugins, .settings = settings},
                                      err, sizeof err);
    if (!h) { fprintf(stderr, "%s\n", err); return false; }
    bool ok = sl_harness_render(h, NULL);
    sl_harness_structure_of(h, st);
    sl_harness_destroy(h);
    return ok;
}

int main(void) {
    setenv("SHADELAB_PLUGIN_PATH", SL_TEST_PLUGIN_DIR, 1);
    sl_harness_structure none, disabled, enabled, active_pass;
    CHECK(structure((const char *[]){NULL}, NULL, &none));
    CHECK(structure((const char *[]){"tp-good", NULL}, (const char *[]){"tp-good.enabled=false", "tp-good.gain=3", NULL}, &disabled));
    CHECK(structure((const char *[]){"tp-good", NULL}, NULL, &enabled));
    CHECK(structure((const char *[]){"tp-good", NULL}, (const char *[]){"tp-good.gain=3", NULL}, &active_pass));
    CHECK(none.program_count == 2);
    /* loaded but disabled: identical to not loading it */
    CHECK_MSG(sl_harness_structure_equal(&none, &disabled), "disabled plugin changed programs, passes or draw calls");
    /* enabled: the marked material's program changes, the plain one's does not */
    CHECK(enabled.program_hashes[0] == none.program_hashes[0]);
    CHECK(enabled.program_hashes[1] != none.program_hashes[1]);
    /* an inactive pass (gain 1) does not run; an active one does — the check can fail */
    CHECK(enabled.pass_count == none.pass_count);
    /* its pass, and the core's display pass after it: tp-good's pass does not declare
     * display_on_write (ABI 1.8), so it cannot end the chain that writes the display itself */
    CHECK(active_pass.pass_count == none.pass_count + 2);
    CHECK(!sl_harness_structure_equal(&none, &active_pass));
    printf("passes without plugin: %d, draw calls %d\n", none.pass_count, none.draw_calls);
    return check_result();
}
