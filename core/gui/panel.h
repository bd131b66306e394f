/* The viewer's panel, generated from the parameter schema and the plugin registry (C, over the
 * widget API of gui.h). Nothing here describes a parameter by hand: every widget comes from an
 * sl_param_desc (type, range, step, unit, group, description, flags).
 *
 * Every change a widget makes goes through sl_panel_apply(), which is sl_app_set() with source
 * SL_SRC_GUI: the same parser, validation and precedence as --set and scene files. */
#ifndef SL_PANEL_H
#define SL_PANEL_H
#include "app.h"

typedef struct sl_panel sl_panel;

/* A plugin key binding after the viewer's conflict resolution (sl_viewer_resolve_keys); the panel
 * lists them and triggers unbound ones. */
typedef struct sl_key_binding {
    int reg;                 /* index into app->plugins.keys */
    char key[16];            /* normalised name: "A", "7", "F3" ("" when invalid) */
    int code;                /* GLFW key code; -1 when the name is not a valid key */
    bool shift;              /* moved to Shift+key: the plain key was taken */
    bool unbound;            /* no key at all: trigger it from the panel */
    char clash[200];         /* who took the plain key ("viewer (fly)", "plugin ggx"); "" = none */
} sl_key_binding;

/* What the user asked for through the panel this frame (the viewer performs it). */
typedef struct sl_panel_actions {
    bool reload_shaders;
    bool screenshot;
    int trigger_binding;     /* index into the bindings, -1 = none */
} sl_panel_actions;

sl_panel *sl_panel_create(sl_app *app, const sl_key_binding *bindings, int binding_count);
void sl_panel_destroy(sl_panel *p);
/* Builds this frame's widgets (between sl_gui_new_frame and sl_gui_render). frame_dt: seconds
 * since the previous frame (for the fps readout). */
void sl_panel_draw(sl_panel *p, double frame_dt, sl_panel_actions *actions);
void sl_panel_toggle(sl_panel *p);
/* A status line over the image ("compiling shaders …"; a static string); NULL clears it. */
void sl_panel_set_status(sl_panel *p, const char *text);
/* The error overlay, shown whether or not the panel is, until dismissed: a shader compile error
 * (file:line …), or what loading logged (text starting "Loading reported:"); NULL clears it. */
void sl_panel_set_shader_error(sl_panel *p, const char *text);

/* "id=value" (plugin.param, material.NAME.key, light.NAME.key) from the GUI. On failure the
 * message goes to stderr and, with a panel, is shown in it. */
bool sl_panel_apply(sl_app *app, const char *assignment, char *err, size_t n);
/* Debug view from the GUI ("final" = none), same as --debug-view. */
bool sl_panel_set_debug_view(sl_app *app, const char *name, char *err, size_t n);
#endif
