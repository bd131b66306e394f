/* The plugin descriptor and its lifecycle.
 *
 *   load (dlopen, entry symbol, ABI check)
 *     → create(host)        no GL context. Register parameters, chunks, passes, keys here.
 *     → activate()          GL context current. Create GL objects.
 *     → per frame:
 *          begin_frame()    GL current, before any pass; only while the plugin is enabled
 *          pass execute()   GL current (see pass.h)
 *          bind callback    GL current, when a program with this plugin's chunks is bound
 *     → resize(w, h)        GL current, after the viewport changed
 *     → deactivate()        GL current. Delete GL objects.
 *     → destroy()           no GL context. Free memory.
 * All callbacks run on the main thread. A plugin that is loaded but disabled
 * ("<id>.enabled" = false) gets no per-frame calls and none of its chunks or passes are used.
 */
#ifndef SHADELAB_PLUGIN_H
#define SHADELAB_PLUGIN_H

#ifdef __cplusplus
extern "C" {
#endif

#define SL_PLUGIN_ENTRY_SYMBOL "shadelab_plugin_entry"

typedef struct sl_plugin_desc {
    uint32_t abi_major;         /* SL_ABI_MAJOR the plugin was built with */
    uint32_t abi_minor;         /* SL_ABI_MINOR the plugin was built with */
    uint32_t struct_size;       /* sizeof(sl_plugin_desc) */
    const char *id;             /* [a-z0-9-]; prefix of the plugin's parameters */
    const char *version;
    const char *description;
    /* NULL-terminated plugin ids that must load first, or NULL. While one of them is switched off
     * (its "enabled"), this plugin is off too. (Named `requires` before ABI 1.5; renamed because
     * `requires` is a C++20 keyword; same position, so the ABI is unchanged.) */
    const char *const *dependencies;
    const char *const *conflicts; /* NULL-terminated plugin ids that must not be loaded */

    /* Returns SL_OK and sets *user, or an error (logged; the plugin becomes disabled). When it
     * fails after setting *user, the host calls destroy(*user); registrations are rolled back. */
    sl_status (*create)(const sl_host *host, void **user);
    sl_status (*activate)(void *user);
    void (*begin_frame)(void *user, const sl_frame *frame);
    void (*resize)(void *user, int width, int height);
    void (*deactivate)(void *user);
    void (*destroy)(void *user);
    /* Extensions this plugin offers to others, by id with revision ("shadelab.shadow-maps/1");
     * NULL when not provided. May be NULL. */
    const void *(*get_extension)(void *user, const char *id);
    /* ABI 1.6: NULL-terminated standard material inputs (params.h) that this plugin's material
     * keys receive, or NULL. The host reads it from the descriptor without calling create(), to
     * load the plugins an imported material needs, and no more. It must be the set of the keys'
     * material_input: the host refuses a plugin whose list and keys disagree, naming the input. */
    const char *const *material_inputs;
    /* ABI 1.6: when the host loads this plugin without being asked (SL_PLUGIN_DEFAULT_* bits; 0 =
     * only when named), read from the descriptor without calling create(). The core names no
     * plugin: what is on by default is what installed plugins declare here. */
    unsigned default_for;
    /* ABI 1.15: NULL-terminated names of the shading models this plugin's SHADING_MODEL chunks
     * provide, or NULL. The host reads it from the descriptor without calling create(), to name
     * the plugin that provides a model a material asks for and to list models in --list-plugins.
     * It must be the set of those chunks' names: the host refuses a plugin (built for 1.15 or
     * later) whose list and chunks disagree, naming the model. */
    const char *const *shading_models;
} sl_plugin_desc;

/* sl_plugin_desc.default_for bits (ABI 1.6). */
#define SL_PLUGIN_DEFAULT_EVERY_SCENE 1u        /* loaded for every scene (aa: antialiasing on) */
#define SL_PLUGIN_DEFAULT_MODEL_FILE 2u         /* loaded when a model file is opened directly */
#define SL_PLUGIN_DEFAULT_MODEL_ENVIRONMENT 4u  /* ... and it lights it (envmap's sky); without one
                                                   the core adds a neutral studio light; also
                                                   loaded for --env FILE */
#define SL_PLUGIN_DEFAULT_SHADOWS 8u            /* loaded for --shadows: it draws the shadows of lights
                                                   with cast_shadows (hosts before it ignore the bit) */

#if defined(__GNUC__)
#define SL_EXPORT __attribute__((visibility("default")))
#else
#define SL_EXPORT
#endif

/* The one symbol a plugin exports. Use once per plugin:
 *   static const sl_plugin_desc desc = { SL_PLUGIN_HEADER, .id = "my-plugin", … };
 *   SL_DEFINE_PLUGIN(desc)                                                       */
#define SL_PLUGIN_HEADER \
    .abi_major = SL_ABI_MAJOR, .abi_minor = SL_ABI_MINOR, .struct_size = sizeof(sl_plugin_desc)
#define SL_DEFINE_PLUGIN(desc) \
    SL_EXPORT const sl_plugin_desc *shadelab_plugin_entry(void) { return &(desc); }

typedef const sl_plugin_desc *(*sl_plugin_entry_fn)(void);

#ifdef __cplusplus
}
#endif
#endif
