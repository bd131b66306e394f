/* The interactive window viewer: camera controls, keys, hot reload, screenshots. */
#include "viewer.h"
#include "log.h"
#include "render/renderer.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>


typedef struct viewer { sl_app *app; double last_x, last_y; bool dragging[3]; bool screenshot; } viewer;

void sl_viewer_print_keys(sl_app *app, FILE *f) {
    fprintf(f, "viewer keys:\n"
           "  left drag     orbit            right/middle drag  pan\n"
           "  wheel         zoom             W A S D Q E        fly\n"
           "  C             print camera     F5                 reload shaders\n"
           "  P             screenshot       Esc                quit\n");
    if (app->plugins.key_count) fprintf(f, "plugin keys:\n");
    for (int i = 0; i < app->plugins.key_count; i++) {
        const sl_key_reg *k = &app->plugins.keys[i];
        fprintf(f, "  %-13s %s [%s]\n", k->d.key, k->d.description ? k->d.description : "", app->plugins.items[k->owner]->id);
    }
}

static void on_key(GLFWwindow *w, int key, int sc, int action, int mods) {
    viewer *v = glfwGetWindowUserPointer(w);
    if (action != GLFW_PRESS) return;
    sl_app *app = v->app;
    if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(w, 1);
    else if (key == GLFW_KEY_C) sl_camera_print(&app->camera, stdout);
    else if (key == GLFW_KEY_F5) {
        int failed = sl_renderer_reload_shaders(app);
        fprintf(stderr, "shaders reloaded%s\n", failed ? " with errors (last good programs kept)" : "");
    } else if (key == GLFW_KEY_P) v->screenshot = true;
    const char *name = glfwGetKeyName(key, sc);
    char buf[8];
    if (key >= GLFW_KEY_F1 && key <= GLFW_KEY_F12) { snprintf(buf, sizeof buf, "F%d", key - GLFW_KEY_F1 + 1); name = buf; }
    for (int i = 0; name && i < app->plugins.key_count; i++) {
        const sl_key_reg *k = &app->plugins.keys[i];
        if (strcasecmp(k->d.key, name) || !sl_plugin_enabled(app, k->owner)) continue;
        if (k->d.on_press) k->d.on_press(k->d.user);
        else if (k->d.param) {
            char id[300], err[512];
            snprintf(id, sizeof id, "%s.%s", app->plugins.items[k->owner]->id, k->d.param);
            sl_param *q = sl_params_find(&app->params, id);
            if (!q) continue;
            sl_value val = q->value;
            if (q->desc.type == SL_PARAM_BOOL) val.b = !val.b;
            else if (q->desc.type == SL_PARAM_ENUM) {
                int nv = 0;
                while (q->desc.enum_values[nv]) nv++;
                val.i = (val.i + 1) % nv;
            }
            sl_params_set_value(&app->params, q, val, SL_SRC_GUI);
            char text[256];
            sl_param_format(q, &val, text, sizeof text);
            fprintf(stderr, "%s = %s\n", id, text);
            (void)err;
        }
    }
}

static void on_cursor(GLFWwindow *w, double x, double y) {
    viewer *v = glfwGetWindowUserPointer(w);
    double dx = x - v->last_x, dy = y - v->last_y;
    v->last_x = x;
    v->last_y = y;
    if (v->dragging[0]) sl_camera_orbit(&v->app->camera, (float)-dx * 0.005f, (float)dy * 0.005f);
    if (v->dragging[1] || v->dragging[2]) sl_camera_pan(&v->app->camera, (float)-dx * 0.0015f, (float)dy * 0.0015f);
}

static void on_button(GLFWwindow *w, int button, int action, int mods) {
    viewer *v = glfwGetWindowUserPointer(w);
    if (button < 3) v->dragging[button] = action == GLFW_PRESS;
}

static void on_scroll(GLFWwindow *w, double dx, double dy) {
    viewer *v = glfwGetWindowUserPointer(w);
    sl_camera_zoom(&v->app->camera, powf(0.9f, (float)dy));
}

bool sl_renderer_poll_reload(sl_app *app);

int sl_viewer_run(sl_app *app, double start_time) {
    GLFWwindow *w = (GLFWwindow *)app->backend.window;
    viewer v = {.app = app};
    glfwSetWindowUserPointer(w, &v);
    glfwSetKeyCallback(w, on_key);
    glfwSetCursorPosCallback(w, on_cursor);
    glfwSetMouseButtonCallback(w, on_button);
    glfwSetScrollCallback(w, on_scroll);
    double t0 = glfwGetTime(), last_poll = t0, last = t0;
    int shots = 0;
    while (!glfwWindowShouldClose(w)) {
        glfwPollEvents();
        double t = glfwGetTime(), dt = t - last;
        last = t;
        float speed = 2.0f * (float)dt * (glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) ? 4.f : 1.f);
        float fwd = (glfwGetKey(w, GLFW_KEY_W) - glfwGetKey(w, GLFW_KEY_S)) * speed;
        float right = (glfwGetKey(w, GLFW_KEY_D) - glfwGetKey(w, GLFW_KEY_A)) * speed;
        float up = (glfwGetKey(w, GLFW_KEY_E) - glfwGetKey(w, GLFW_KEY_Q)) * speed;
        if (fwd || right || up) sl_camera_fly(&app->camera, fwd, right, up);
        int fw, fh;
        glfwGetFramebufferSize(w, &fw, &fh);
        if (fw > 0 && fh > 0) sl_app_resize(app, fw, fh);
        if (t - last_poll > 0.5) { sl_renderer_poll_reload(app); last_poll = t; }
        app->time = start_time + (t - t0);
        sl_app_render_frame(app);
        if (v.screenshot) {
            char name[64], err[512];
            snprintf(name, sizeof name, "shadelab-%03d.png", shots);
            if (sl_app_save(app, name, err, sizeof err)) fprintf(stderr, "saved %s\n", name);
            snprintf(name, sizeof name, "shadelab-%03d.exr", shots++);
            if (sl_app_save(app, name, err, sizeof err)) fprintf(stderr, "saved %s\n", name);
            v.screenshot = false;
        }
        sl_backend_swap(&app->backend);
    }
    return 0;
}

