#ifndef SL_CORE_PLUGIN_H
#define SL_CORE_PLUGIN_H
#include "scene/scene.h"
#include <shadelab/shadelab.h>
extern const sl_plugin_desc sl_core_plugin;

/* The light keys every light has (enabled, intensity, color, …), each a field of sl_light of the
 * same name, declared once in core_plugin.c. A key of a light type (spot's cone_angle) is a
 * plugin's and lives in the light's parameter slots instead. */
bool sl_core_light_key(const char *key);
/* The key's field of L as a value of its schema; false when key is not a core light key. */
bool sl_core_light_get(const sl_light *L, const char *key, sl_value *out);
/* Writes v (already parsed and range-checked by the key's schema) into L; false with a message
 * that starts with `what` when the value cannot be stored (a zero direction). */
bool sl_core_light_set(sl_light *L, const char *key, const sl_value *v, const char *what, char *err, size_t n);
#endif
