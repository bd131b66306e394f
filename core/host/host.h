/* The host module: implements the sl_host table (sdk/include/shadelab/host.h) each plugin gets.
 * It is the only module that knows both the plugin registry and the renderer: registrations go to
 * the registry (core/plugin), GL work to the renderer (core/render). Above both, below the app. */
#ifndef SL_HOST_H
#define SL_HOST_H
#include <shadelab/shadelab.h>

struct sl_app;

/* A new host table for plugin `index` of app's registry (sl_plugins.make_host; ctx is the app). */
sl_host *sl_host_make(struct sl_app *app, int index);
/* The app whose GL context is current (one per process): plugins' gl_get_proc_address. */
void sl_host_set_gl_app(struct sl_app *app);
#endif
