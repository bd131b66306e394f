/* Lights that plugins add to the scene (SDK ABI 1.22, host add_light / set_light): scene lights
 * named "<plugin id>.<name>", lit, shadowed and addressed (light.NAME.KEY) like the scene's own,
 * whose state their plugin sets, and which are off while their plugin is. */
#ifndef SL_PLUGIN_LIGHTS_H
#define SL_PLUGIN_LIGHTS_H
#include "state.h"
#include <shadelab/host.h>

/* create() time only (before the scene's light values are applied): the new light's index in
 * app->scene.lights, or -1 with err. */
int sl_plugin_light_add(sl_app *app, int plugin, const sl_plugin_light_desc *d, char *err, size_t n);
/* Sets the state of light `light` (an index add_light returned) of plugin `plugin`; marks
 * app->plugin_lights_moved when anything changed. false: not that plugin's light. */
bool sl_plugin_light_set(sl_app *app, int plugin, int light, const sl_plugin_light_state *s);
/* Whether a scene light lights the frame: enabled (the user's switch), and for a plugin's light
 * its plugin on and the light on by that plugin's last set_light; --shadows' stand-in key light
 * not while a plugin's shadow-casting directional light shines. */
bool sl_light_on(const sl_app *app, const sl_light *L);
/* The plugins' lights' owners' switches as bits, to notice a plugin switched on or off. */
uint64_t sl_plugin_lights_owners_on(const sl_app *app);
#endif
