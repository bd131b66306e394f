/* Built instead of gui_imgui.cpp when Dear ImGui (libimgui-dev) is not installed: the
 * viewer then runs its window without a panel and says why. */
#include "gui/gui.h"
#include <stdio.h>

bool sl_gui_init(void *window, char *err, size_t n) {
    snprintf(err, n, "shadelab was built without Dear ImGui (install libimgui-dev and reconfigure)");
    return false;
}
void sl_gui_shutdown(void) {}
void sl_gui_new_frame(void) {}
void sl_gui_render(void) {}
bool sl_gui_wants_mouse(void) { return false; }
bool sl_gui_wants_keyboard(void) { return false; }
bool sl_ui_begin(const char *t, float x, float y, float w, float h, float a) { return false; }
bool sl_ui_begin_overlay(const char *id, float r, float g, float b, float a) { return false; }
bool sl_ui_begin_overlay_right(const char *id, float r, float g, float b, float a) { return false; }
void sl_ui_end(void) {}
bool sl_ui_header(const char *l, bool o) { return false; }
bool sl_ui_tree_push(const char *l, bool o) { return false; }
void sl_ui_tree_pop(void) {}
void sl_ui_push_id(const char *id) {}
void sl_ui_pop_id(void) {}
void sl_ui_same_line(void) {}
void sl_ui_separator(void) {}
void sl_ui_indent(void) {}
void sl_ui_unindent(void) {}
void sl_ui_text(const char *fmt, ...) {}
void sl_ui_text_disabled(const char *fmt, ...) {}
void sl_ui_text_colored(float r, float g, float b, const char *fmt, ...) {}
void sl_ui_text_wrapped(const char *t) {}
void sl_ui_tooltip(const char *t) {}
bool sl_ui_checkbox(const char *l, bool *v) { return false; }
bool sl_ui_int(const char *l, int *v, int a, int b, float s, const char *f) { return false; }
bool sl_ui_float(const char *l, float *v, float a, float b, float s, const char *f) { return false; }
bool sl_ui_combo(const char *l, int *c, const char *const *i, int n) { return false; }
bool sl_ui_color3(const char *l, float c[3]) { return false; }
bool sl_ui_float3(const char *l, float v[3], float s, const char *f) { return false; }
bool sl_ui_input_text(const char *l, char *b, size_t n) { return false; }
bool sl_ui_button(const char *l) { return false; }
bool sl_ui_small_button(const char *l) { return false; }
bool sl_ui_selectable(const char *l, bool s) { return false; }
bool sl_ui_begin_table(const char *id, int c) { return false; }
void sl_ui_table_header(const char *const *n, int c) {}
void sl_ui_table_next_column(void) {}
void sl_ui_table_next_row(void) {}
void sl_ui_end_table(void) {}
