/* shadelab_toolkit: the core as shadelab's own tools see it.
 *
 * The public header of the library `shadelab_toolkit` (core/toolkit/): the one header from
 * core/ that a tool (tools/<name>/, a plugin's tools/ folder) includes, besides the SDK's
 * <shadelab/...> (the harness among them) and the documented header of a library it uses
 * (core/quality/autoquality.h, a plugin's include/ folder). Tools link `shadelab_toolkit`,
 * never `shadelab_core`, and include nothing else of core/: tests/module_rule.sh checks it.
 *
 * What it gives, by including them (their contracts are in those headers):
 *   app.h          the application a tool drives: sl_app_init / start_gl / render_frame /
 *                  read_color / set / shutdown, and the state a tool may read (state.h:
 *                  options, the parameter store params.h, the plugin records plugin/plugins.h,
 *                  the context backend backend/backend.h, the scene)
 *   image/image.h  image files and pixels (sl_image_load / sl_image_write, sRGB, comparison)
 *   scene/scene.h  scene files (sl_scene_load_file, materials, meshes with tangent frames)
 *   fileio.h       whole-file reads;  log.h  logging with the viewer's threshold
 * and, declared here, the few facts of the renderer a tool needs, as functions: a tool never
 * includes core/render/. Add what a tool lacks here (a small documented function), not an
 * include of the core's private headers. */
#ifndef SL_TOOLKIT_H
#define SL_TOOLKIT_H
#include <shadelab/shadelab.h>
#include "app.h"
#include "fileio.h"
#include "image/image.h"
#include "log.h"
#include "scene/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* FNV-1a 64 over `len` bytes, continuing from `seed` (0 to start): the hash the core keys its
 * programs by, for cache keys that must change when content does. */
uint64_t sl_tool_hash64(const void *data, size_t len, uint64_t seed);

/* ------------------------------------------------------------- timing of the last frame -- */

typedef struct sl_tool_pass_time {
    const char *name, *owner;   /* the pass and its plugin ("core"); valid until the next frame */
    double ms;                  /* its time in the last frame (the core's honest timing) */
    bool ran;                   /* false: skipped (inactive, or its signature did not change) */
} sl_tool_pass_time;

typedef struct sl_tool_frame_times {
    sl_tool_pass_time passes[64]; int pass_count;   /* in the order they were planned */
    double frame_ms;            /* CPU wall time of the whole frame */
    const char *timing_mode;    /* "glfinish" (CPU rasterisers) or "timer-query" */
} sl_tool_frame_times;

/* The times of the frame sl_app_render_frame rendered last (zeros before the first). */
void sl_tool_frame_times_of(sl_app *app, sl_tool_frame_times *out);

/* ------------------------------------------------------------- samples of a still ------- */

/* Renders one frame as sample `index` of `count` (sl_frame.sample_index/count: what the frames
 * of a `count`-frame still or accumulation each see), as a fresh start: temporal methods (TAA)
 * restart their history, so the frame is shown as rendered, and nothing is accumulated.
 * shadelab-bench's noise measure renders index 0..count-1 this way. False when the frame fails
 * or index is not in [0, count). */
bool sl_tool_render_sample(sl_app *app, int index, int count);
/* The frames a still needs that the plugins asked for in the last frame (TAA's history), >= 1. */
int sl_tool_still_frames(sl_app *app);
/* The frame-time budget (core.budget, docs/budget.md) sets every knob it chose to its best now, as
 * the window does once the view is still: the next frames render the still the window converges
 * to. Nothing when the budget is off. */
void sl_tool_budget_settle(sl_app *app);

/* ------------------------------------------------------------- stand-alone GL programs --- */

/* Compiles and links a program from files: `vs` and `fs` relative to `dir`, or "sl:NAME" for
 * the core's shader library (e.g. "sl:fullscreen.vert"); `defines` are "NAME VALUE" lines or
 * NULL. Needs a current GL context whose entry points the core loaded (sl_gl_load). Returns the
 * program even when it does not compile: its id is 0 then and err holds the driver's message
 * mapped to file and line. Free it with sl_tool_program_free. */
sl_program *sl_tool_program_from_files(const char *dir, const char *vs, const char *fs, const char *defines,
                                       char *err, size_t n);
/* The GL program name, 0 when it never compiled (or p is NULL). */
unsigned sl_tool_program_id(const sl_program *p);
void sl_tool_program_free(sl_program *p);

#ifdef __cplusplus
}
#endif
#endif
