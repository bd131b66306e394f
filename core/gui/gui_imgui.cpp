// The C API of gui.h over Dear ImGui 1.86 (Debian's libimgui-dev: libimgui.a carries the GLFW
// and OpenGL 3 backends; the GL3 backend loads libGL itself). Only pass-through code lives here:
// what the panel shows is decided in panel.c.
#include "gui.h"
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <cstdarg>
#include <cstdio>

static bool g_ready;

bool sl_gui_init(void *window, char *err, size_t n) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO &io = ImGui::GetIO();
    io.IniFilename = nullptr;  // no imgui.ini littered into the working directory
    ImGui::StyleColorsDark();
    ImGui::GetStyle().WindowRounding = 3.0f;
    if (!ImGui_ImplGlfw_InitForOpenGL(static_cast<GLFWwindow *>(window), true)) {
        snprintf(err, n, "Dear ImGui: GLFW backend failed to initialise");
        ImGui::DestroyContext();
        return false;
    }
    if (!ImGui_ImplOpenGL3_Init("#version 410 core")) {
        snprintf(err, n, "Dear ImGui: OpenGL 3 backend failed to initialise (it loads libGL.so.1 itself)");
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
        return false;
    }
    g_ready = true;
    return true;
}

void sl_gui_shutdown(void) {
    if (!g_ready) return;
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    g_ready = false;
}

void sl_gui_new_frame(void) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void sl_gui_render(void) {
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

bool sl_gui_wants_mouse(void) { return g_ready && ImGui::GetIO().WantCaptureMouse; }
bool sl_gui_wants_keyboard(void) { return g_ready && ImGui::GetIO().WantCaptureKeyboard; }

bool sl_ui_begin(const char *title, float x, float y, float w, float h, float alpha) {
    ImGui::SetNextWindowPos(ImVec2(x, y), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(w, h), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(alpha);
    bool open = ImGui::Begin(title);
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 9.0f); // room for the labels on the right
    return open;
}

static bool begin_overlay(const char *id, float r, float g, float b, float alpha, bool right) {
    const ImGuiViewport *vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->WorkPos.x + (right ? vp->WorkSize.x - 8 : 8), vp->WorkPos.y + vp->WorkSize.y - 8),
                            ImGuiCond_Always, ImVec2(right ? 1.0f : 0.0f, 1));
    ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(vp->WorkSize.x - 16, vp->WorkSize.y * 0.5f));
    ImGui::SetNextWindowBgAlpha(alpha);
    ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(r, g, b, alpha));
    bool open = ImGui::Begin(id, nullptr,
                             ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                 ImGuiWindowFlags_NoNav);
    ImGui::PopStyleColor();
    ImGui::PushItemWidth(-1.0f);
    return open;
}
bool sl_ui_begin_overlay(const char *id, float r, float g, float b, float alpha) {
    return begin_overlay(id, r, g, b, alpha, false);
}
bool sl_ui_begin_overlay_right(const char *id, float r, float g, float b, float alpha) {
    return begin_overlay(id, r, g, b, alpha, true);
}

void sl_ui_end(void) {
    ImGui::PopItemWidth();
    ImGui::End();
}
bool sl_ui_header(const char *label, bool open) {
    return ImGui::CollapsingHeader(label, open ? ImGuiTreeNodeFlags_DefaultOpen : 0);
}
bool sl_ui_tree_push(const char *label, bool open) {
    return ImGui::TreeNodeEx(label, open ? ImGuiTreeNodeFlags_DefaultOpen : 0);
}
void sl_ui_tree_pop(void) { ImGui::TreePop(); }
void sl_ui_push_id(const char *id) { ImGui::PushID(id); }
void sl_ui_pop_id(void) { ImGui::PopID(); }
void sl_ui_same_line(void) { ImGui::SameLine(); }
void sl_ui_separator(void) { ImGui::Separator(); }
void sl_ui_indent(void) { ImGui::Indent(); }
void sl_ui_unindent(void) { ImGui::Unindent(); }

void sl_ui_text(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    ImGui::TextV(fmt, ap);
    va_end(ap);
}
void sl_ui_text_disabled(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    ImGui::TextDisabledV(fmt, ap);
    va_end(ap);
}
void sl_ui_text_colored(float r, float g, float b, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    ImGui::TextColoredV(ImVec4(r, g, b, 1), fmt, ap);
    va_end(ap);
}
void sl_ui_text_wrapped(const char *text) { ImGui::TextWrapped("%s", text); }
void sl_ui_tooltip(const char *text) {
    if (text && *text && ImGui::IsItemHovered()) {
        ImGui::BeginTooltip();
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 32.0f);
        ImGui::TextUnformatted(text);
        ImGui::PopTextWrapPos();
        ImGui::EndTooltip();
    }
}

bool sl_ui_checkbox(const char *label, bool *v) { return ImGui::Checkbox(label, v); }
bool sl_ui_int(const char *label, int *v, int mn, int mx, float speed, const char *fmt) {
    if (mn < mx) return ImGui::SliderInt(label, v, mn, mx, fmt, ImGuiSliderFlags_AlwaysClamp);
    return ImGui::DragInt(label, v, speed > 0 ? speed : 1.0f, 0, 0, fmt);
}
bool sl_ui_float(const char *label, float *v, float mn, float mx, float speed, const char *fmt) {
    if (mn < mx) {
        // wide ranges (0..1e6 W/m²) are unusable as linear sliders: drag with clamping instead
        if (mx - mn > 1000.0f)
            return ImGui::DragFloat(label, v, speed > 0 ? speed : 0.01f, mn, mx, fmt, ImGuiSliderFlags_AlwaysClamp);
        return ImGui::SliderFloat(label, v, mn, mx, fmt, ImGuiSliderFlags_AlwaysClamp);
    }
    return ImGui::DragFloat(label, v, speed > 0 ? speed : 0.01f, 0, 0, fmt);
}
bool sl_ui_combo(const char *label, int *current, const char *const *items, int count) {
    return ImGui::Combo(label, current, items, count);
}
bool sl_ui_color3(const char *label, float rgb[3]) {
    return ImGui::ColorEdit3(label, rgb, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
}
bool sl_ui_float3(const char *label, float v[3], float speed, const char *fmt) {
    return ImGui::DragFloat3(label, v, speed > 0 ? speed : 0.01f, 0, 0, fmt);
}
bool sl_ui_input_text(const char *label, char *buf, size_t size) {
    return ImGui::InputText(label, buf, size, ImGuiInputTextFlags_EnterReturnsTrue);
}
bool sl_ui_button(const char *label) { return ImGui::Button(label); }
bool sl_ui_small_button(const char *label) { return ImGui::SmallButton(label); }
bool sl_ui_selectable(const char *label, bool selected) { return ImGui::Selectable(label, selected); }

bool sl_ui_begin_table(const char *id, int columns) {
    return ImGui::BeginTable(id, columns, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_SizingFixedFit);
}
void sl_ui_table_header(const char *const *names, int count) {
    for (int i = 0; i < count; i++) ImGui::TableSetupColumn(names[i]);
    ImGui::TableHeadersRow();
}
void sl_ui_table_next_column(void) { ImGui::TableNextColumn(); }
void sl_ui_table_next_row(void) { ImGui::TableNextRow(); }
void sl_ui_end_table(void) { ImGui::EndTable(); }
