/* The GUI toolkit seen from C: a thin adapter over Dear ImGui (gui_imgui.cpp, the only C++
 * here) so that the panel itself (panel.c) is plain C and never sees an ImGui type.
 *
 * Debian's Dear ImGui 1.86 OpenGL 3 backend loads libGL by itself (its own gl3w loader), so the
 * GUI exists only in the GLFW window: headless runs (OSMesa, EGL) never call any of this.
 * Every function below runs on the main thread with the window's GL context current.
 *
 * Widgets follow ImGui's immediate mode: call them every frame between sl_gui_new_frame() and
 * sl_gui_render(); the ones returning bool return true on the frame the user changed the value.
 * Labels are ImGui labels: text after "##" is an id that is not shown. */
#ifndef SL_GUI_H
#define SL_GUI_H
#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- lifecycle (window backend only) ---- */
/* window: the GLFWwindow. Installs ImGui's GLFW callbacks, chained to the ones already set.
 * False (err filled) when ImGui is unavailable or its GL loader failed; the viewer runs on
 * without a panel then. */
bool sl_gui_init(void *glfw_window, char *err, size_t err_size);
void sl_gui_shutdown(void);
void sl_gui_new_frame(void);
/* Draws the frame's widgets into the currently bound framebuffer. */
void sl_gui_render(void);
/* True when ImGui uses the mouse / keyboard this frame (the viewer then ignores it). */
bool sl_gui_wants_mouse(void);
bool sl_gui_wants_keyboard(void);

/* ---- windows and layout ---- */
/* A window at (x, y) of size (w, h) on its first use (the user may move/resize it later).
 * Returns false when collapsed: still call sl_ui_end(). */
bool sl_ui_begin(const char *title, float x, float y, float w, float h, float alpha);
/* A borderless, non-interactive window anchored at the bottom of the display (overlays); with
 * right = true at the bottom right, beside the panel rather than under it (status lines). */
bool sl_ui_begin_overlay(const char *id, float r, float g, float b, float alpha);
bool sl_ui_begin_overlay_right(const char *id, float r, float g, float b, float alpha);
void sl_ui_end(void);
bool sl_ui_header(const char *label, bool default_open);   /* collapsing header */
bool sl_ui_tree_push(const char *label, bool default_open); /* true: open, call sl_ui_tree_pop */
void sl_ui_tree_pop(void);
void sl_ui_push_id(const char *id);
void sl_ui_pop_id(void);
void sl_ui_same_line(void);
void sl_ui_separator(void);
void sl_ui_indent(void);
void sl_ui_unindent(void);

/* ---- text ---- */
void sl_ui_text(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void sl_ui_text_disabled(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void sl_ui_text_colored(float r, float g, float b, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
void sl_ui_text_wrapped(const char *text);
/* Tooltip for the previous widget while it is hovered. */
void sl_ui_tooltip(const char *text);

/* ---- widgets (true = changed this frame) ---- */
bool sl_ui_checkbox(const char *label, bool *v);
/* Slider when min < max, otherwise an unbounded drag with the given speed. fmt as printf
 * ("%d px", "%.3f ms"). */
bool sl_ui_int(const char *label, int *v, int min, int max, float speed, const char *fmt);
bool sl_ui_float(const char *label, float *v, float min, float max, float speed, const char *fmt);
bool sl_ui_combo(const char *label, int *current, const char *const *items, int count);
bool sl_ui_color3(const char *label, float rgb[3]);  /* linear, HDR values allowed */
bool sl_ui_float3(const char *label, float v[3], float speed, const char *fmt);
/* Single-line text field; true when Enter was pressed (the edit is then committed). */
bool sl_ui_input_text(const char *label, char *buf, size_t size);
bool sl_ui_button(const char *label);
bool sl_ui_small_button(const char *label);
bool sl_ui_selectable(const char *label, bool selected);

/* ---- tables ---- */
bool sl_ui_begin_table(const char *id, int columns);
void sl_ui_table_header(const char *const *names, int count);
void sl_ui_table_next_column(void); /* first call of a row starts the row */
void sl_ui_table_next_row(void);
void sl_ui_end_table(void);

#ifdef __cplusplus
}
#endif
#endif
