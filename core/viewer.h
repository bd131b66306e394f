/* The interactive window viewer (GLFW backend only): camera controls, keys, the GUI panel,
 * hot reload, screenshots.
 *
 * Keys. The viewer owns W A S D Q E (fly; Shift = faster, so Shift+W… are taken too), C, P,
 * F1, F5 and Esc. Plugins declare keys with host->add_key(). Conflicts are resolved in a fixed,
 * documented order and always reported (stderr, --help-keys and the panel):
 *   1. plugins are considered in load order (the core, then --plugin order, then the scene's
 *      "plugins" list), each plugin's keys in registration order;
 *   2. a binding gets its key when nobody (viewer or an earlier binding) has it;
 *   3. otherwise it moves to Shift+key, with a warning naming both owners;
 *   4. when Shift+key is taken too (or the key name is not one of 0-9, A-Z, F1-F12) it stays
 *      unbound: still listed in the panel, where clicking it triggers it.
 *
 * Test hook: SHADELAB_VIEWER_SCRIPT runs commands separated by ';', one per frame, before that
 * frame is rendered, through the same functions the panel widgets and the keyboard use:
 *   set ID=VALUE   as a panel widget change (sl_panel_apply: the --set path, source GUI)
 *   view NAME      debug view, as the panel's selector ("final" for none)
 *   key NAME       a key press: "P", "F5", "1", "Shift+2"
 *   orbit YAW [PITCH]  the camera orbits by these radians, as a left drag does
 *   wait N         render N frames
 *   waitfile PATH  render frames until PATH exists (gives up after 120 s)
 *   grab FILE      write the window's framebuffer, panel included, to FILE (PNG); prints the frame's scene time
 *   quit           close the window
 * SHADELAB_NO_GUI=1 runs the window without the panel. */
#ifndef SL_VIEWER_H
#define SL_VIEWER_H
#include "app.h"
#include "gui/panel.h" /* sl_key_binding */
#include <stdio.h>

/* Runs until the window closes; returns the exit code. */
int sl_viewer_run(sl_app *app, double start_time);
/* --help-keys: the viewer's keys and every plugin's key bindings after conflict resolution. */
void sl_viewer_print_keys(sl_app *app, FILE *f);


/* Resolves every plugin key as documented above; writes one warning per clash to `warn`
 * (may be NULL). Returns the number of bindings (= app->plugins.key_count, at most max). */
int sl_viewer_resolve_keys(sl_app *app, sl_key_binding *out, int max, FILE *warn);
/* Runs a binding: its on_press callback, or toggles/cycles its parameter through the panel's
 * apply function. GL context current. */
void sl_viewer_trigger_binding(sl_app *app, const sl_key_binding *b);
#endif
