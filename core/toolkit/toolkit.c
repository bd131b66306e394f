/* shadelab_toolkit (see toolkit.h): the renderer facts tools need, without their including
 * core/render. */
#include "toolkit.h"
#include "budget/budget.h"
#include "render/composer.h"
#include "render/renderer.h"
#include <string.h>

uint64_t sl_tool_hash64(const void *data, size_t len, uint64_t seed) { return sl_hash64(data, len, seed); }

void sl_tool_frame_times_of(sl_app *app, sl_tool_frame_times *out) {
    memset(out, 0, sizeof *out);
    const sl_frame_stats *st = app ? sl_renderer_stats(app) : NULL;
    if (!st) return;
    int n = st->pass_count < 64 ? st->pass_count : 64;
    for (int i = 0; i < n; i++)
        out->passes[i] = (sl_tool_pass_time){.name = st->passes[i].name, .owner = st->passes[i].owner,
                                             .ms = st->passes[i].ms, .ran = st->passes[i].ran};
    out->pass_count = n;
    out->frame_ms = st->frame_ms;
    out->timing_mode = st->timing_mode;
}

bool sl_tool_render_sample(sl_app *app, int index, int count) {
    if (!app || count < 1 || index < 0 || index >= count) return false;
    sl_renderer_force_sample(app, index, count);
    return sl_app_render_frame(app);
}

int sl_tool_still_frames(sl_app *app) { return sl_renderer_still_frames(app); }

void sl_tool_budget_settle(sl_app *app) { sl_budget_settle(app); }

sl_program *sl_tool_program_from_files(const char *dir, const char *vs, const char *fs, const char *defines,
                                       char *err, size_t n) {
    return sl_program_from_files(dir, vs, fs, defines, err, n);
}

unsigned sl_tool_program_id(const sl_program *p) { return p ? p->id : 0; }

void sl_tool_program_free(sl_program *p) {
    if (p) sl_program_free(p);
}
