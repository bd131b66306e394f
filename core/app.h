/* The application: one context, one scene, the plugins, the parameters, the renderer.
 * main.c (CLI), the GUI and the test harness all drive this. */
#ifndef SL_APP_H
#define SL_APP_H
#include "state.h"

/* Loads the scene, loads and creates plugins, applies scene and command-line parameters.
 * No GL yet (--dump-params and --list-plugins stop here). */
bool sl_app_init(sl_app *app, const sl_app_options *opt, char *err, size_t n);
/* Creates the GL context, activates plugins, uploads the scene, plans the render graph. */
bool sl_app_start_gl(sl_app *app, char *err, size_t n);
/* Renders one output frame (accumulating opt.accumulate sub-frames). */
bool sl_app_render_frame(sl_app *app);
/* Reads the last frame: linear HDR "color" (RGBA float) or display-encoded RGBA floats in
 * [0,1]; rows top to bottom. */
bool sl_app_read_color(sl_app *app, float *rgba);
bool sl_app_read_display(sl_app *app, float *rgba);
/* Writes the last frame: .png (display-encoded) or .exr (linear HDR). */
bool sl_app_save(sl_app *app, const char *path, char *err, size_t n);
/* Applies "id=value" for globals, material.NAME.key and light.NAME.key. */
bool sl_app_set(sl_app *app, const char *assignment, sl_param_source src, char *err, size_t n);
bool sl_app_set_debug_view(sl_app *app, const char *name, char *err, size_t n);
void sl_app_resize(sl_app *app, int width, int height);
void sl_app_shutdown(sl_app *app);

extern const char sl_default_scene_json[]; /* scenes/default.json: the showcase (issue 19) */
extern const char sl_basic_scene_json[];   /* scenes/basic.json: the bare scene, the harness's default */
#endif
