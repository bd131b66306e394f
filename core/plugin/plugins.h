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

/* Plugins a process loads, the core included: the sets of plugins a program draws on are 64-bit
 * masks. A plugin beyond is a disabled record saying so. */
#define SL_MAX_PLUGINS 64

typedef struct sl_chunk_reg { int owner; sl_shader_chunk_desc d; } sl_chunk_reg;
typedef struct sl_pass_reg { int owner; sl_pass_desc d; sl_target_desc *outputs; const char **inputs; } sl_pass_reg;
typedef struct sl_key_reg { int owner; sl_key_desc d; } sl_key_reg;

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
    bool live;             /* create() succeeded: destroy() is owed at shutdown, also after the
                            * plugin was disabled later (activate() or a lazy compile failed) */
    char *disabled_reason; /* why it is not ok */
    bool not_found;        /* no such plugin: the name found no file (or is not a valid name), or
                            * the path does not exist */
    bool glsl_failed;      /* switched off because its GLSL did not compile (a hot reload retries it) */
    void *user;
    sl_host *host;         /* made by sl_plugins.make_host (core/host), freed with the record */
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
    int texture_units_used; /* units handed out by reserve_texture_unit (host.h, SL_TEXTURE_UNIT_*) */
    /* Set by the owner before loading: the parameter store plugins register into, and the maker
     * of each plugin's host table (core/host), so the registry calls nothing above it. */
    sl_params *params;
    sl_host *(*make_host)(void *ctx, int index);
    void *host_ctx;
} sl_plugins;

/* Registers the built-in "core" plugin (index 0) from a static descriptor. */
bool sl_plugins_add_builtin(sl_plugins *P, const sl_plugin_desc *desc);
/* Loads NAME or PATH; returns the record index (also for a disabled record). */
int sl_plugins_load(sl_plugins *P, const char *name_or_path, const char *requested_by, bool allow_path);
/* Creates plugin `index` (and what it requires) now, unless it was created already. */
void sl_plugins_create(sl_plugins *P, int index);
/* Resolves requires/conflicts, creates every loaded plugin in dependency order, rolls back the
 * registrations of plugins whose create() fails or whose shading models clash. */
void sl_plugins_create_all(sl_plugins *P);
int sl_plugins_find(sl_plugins *p, const char *id);
/* ok, "<id>.enabled" on, and every dependency enabled */
bool sl_plugin_enabled(const sl_plugins *P, int index);
void sl_plugins_print(const sl_plugins *P, FILE *f); /* --list-plugins */
void sl_plugins_shutdown(sl_plugins *P);             /* deactivate (GL current) + destroy + dlclose */

/* Registrations of plugin `owner` (only inside its create(); the host module forwards the
 * sl_host calls here). Each logs its refusal and returns a status. */
sl_status sl_plugins_add_param(sl_plugins *P, int owner, const sl_param_desc *d);
sl_status sl_plugins_add_chunk(sl_plugins *P, int owner, const sl_shader_chunk_desc *d);
sl_status sl_plugins_add_pass(sl_plugins *P, int owner, const sl_pass_desc *d);
/* Asks pass i for its inputs and outputs now (sl_pass_desc.io, ABI 1.13) and keeps copies; true
 * when they changed (the graph must be planned again). */
bool sl_plugins_update_pass_io(sl_plugins *P, int i);
sl_status sl_plugins_add_key(sl_plugins *P, int owner, const sl_key_desc *d);
sl_status sl_plugins_set_reference(sl_plugins *P, int owner, const sl_reference_desc *d);
int sl_plugins_reserve_unit(sl_plugins *P, int owner);
/* The first enabled plugin offering extension `id` ("shadelab.shadow-maps/1"), or NULL. */
const void *sl_plugins_extension(const sl_plugins *P, const char *id);
/* The directories searched for NAME (for messages and --list-plugins). */
int sl_plugin_search_dirs(char dirs[][1024], int max);
/* Discovery (discover.c): whether a plugin of this id is in the search directories, and the id
 * of the first one (directory order, then by name) whose descriptor lists the standard material
 * input `input` in material_inputs (read without create()). */
bool sl_plugin_available(const char *id);
/* The ids (up to max, sorted, one per id) of the plugins in the search directories whose
 * descriptor's default_for has any of `bits` (SL_PLUGIN_DEFAULT_*); returns how many. */
int sl_plugin_defaults(unsigned bits, char ids[][64], int max);
bool sl_plugin_for_input(const char *input, char *id, size_t n);
/* The id of the first plugin (directory order, then by name) whose descriptor lists the shading
 * model `model` in shading_models (ABI 1.15, read without create()). */
bool sl_plugin_for_model(const char *model, char *id, size_t n);
/* A descriptor's NULL-terminated list as "a, b, c" (empty for NULL). */
void sl_plugin_models_text(const char *const *list, char *out, size_t n);
/* --list-plugins: the plugins in the search directories that P has not loaded, with the
 * description their descriptor gives (read without create()). */
void sl_plugin_print_available(const sl_plugins *P, FILE *f);
#endif
