/* Plugin loader and the registry of everything plugins (and the core itself, registered as the
 * built-in plugin "core") contribute: shader chunks, passes, keys, references.
 *
 * Discovery, in order, for `--plugin NAME` and scene "plugins": [NAME]:
 *   each directory of SHADELAB_PLUGIN_PATH (colon-separated), then the built-in directories
 *   <exe dir>/plugins and <exe dir>/../lib/shadelab/plugins; the file is DIR/NAME/NAME.so.
 * `--plugin PATH` (contains '/' or ends in .so) loads that file; scene files may only name
 * plugins. A plugin that fails is kept as a disabled record with its reason. */
#ifndef SL_PLUGINS_H
#define SL_PLUGINS_H
#include <shadelab/shadelab.h>
#include "params.h"

struct sl_app;

typedef struct sl_chunk_reg { int owner; sl_shader_chunk_desc d; } sl_chunk_reg;
typedef struct sl_pass_reg { int owner; sl_pass_desc d; sl_target_desc *outputs; const char **inputs; } sl_pass_reg;
typedef struct sl_key_reg { int owner; sl_key_desc d; } sl_key_reg;

typedef struct sl_host_impl {
    sl_host host;          /* first member: plugins get &impl->host */
    struct sl_app *app;
    int plugin;            /* index into sl_plugins.items */
} sl_host_impl;

typedef struct sl_plugin_rec {
    char *id;              /* descriptor id (or the requested name when loading failed) */
    char *path;            /* .so path; "(built-in)" for the core */
    char *resource_dir;
    char *requested_by;    /* "command line", "scene", "required by X" */
    void *dl;
    sl_plugin_desc desc;   /* copy, zero-filled past the plugin's struct_size */
    bool ok;               /* loaded and created */
    bool active;           /* activate() succeeded */
    bool creating;         /* inside create(): registrations allowed */
    char *disabled_reason; /* why it is not ok */
    void *user;
    sl_host_impl *host;
    void (*bind)(void *user, unsigned program, int material, const sl_frame *frame);
    void *bind_user;
    sl_reference_desc reference; bool has_reference;
    char *reference_settings, *reference_description;
    int next_texture_unit;
} sl_plugin_rec;

typedef struct sl_plugins {
    sl_plugin_rec **items; int count;
    sl_chunk_reg *chunks; int chunk_count;
    sl_pass_reg *passes; int pass_count;
    sl_key_reg *keys; int key_count;
    int texture_units_used; /* plugin units are handed out from the top of the range down */
} sl_plugins;

/* Registers the built-in "core" plugin (index 0) from a static descriptor. */
bool sl_plugins_add_builtin(struct sl_app *app, const sl_plugin_desc *desc);
/* Loads NAME or PATH; returns the record index (also for a disabled record). */
int sl_plugins_load(struct sl_app *app, const char *name_or_path, const char *requested_by, bool allow_path);
/* Resolves requires/conflicts, creates every loaded plugin in dependency order, rolls back the
 * registrations of plugins whose create() fails or whose shading models clash. */
void sl_plugins_create_all(struct sl_app *app);
int sl_plugins_find(sl_plugins *p, const char *id);
bool sl_plugin_enabled(struct sl_app *app, int index); /* ok && "<id>.enabled" */
void sl_plugins_print(struct sl_app *app, FILE *f);  /* --list-plugins */
void sl_plugins_shutdown(struct sl_app *app);        /* deactivate (GL current) + destroy + dlclose */
/* The directories searched for NAME (for messages and --list-plugins). */
int sl_plugin_search_dirs(char dirs[][1024], int max);
#endif
