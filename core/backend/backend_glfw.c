/* GLFW window backend. GLFW loads libGL itself; GL entry points come from
 * glfwGetProcAddress. */
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include "backend/backend.h"
#include <stdio.h>
#include <string.h>

static char glfw_error[512];
static void on_glfw_error(int code, const char *msg) { snprintf(glfw_error, sizeof glfw_error, "%s", msg); }

static void *glfw_get_proc(const char *name) { return (void *)glfwGetProcAddress(name); }

bool sl_backend_glfw_create(sl_backend *b, int w, int h, const char *title, char *err, size_t n) {
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) { snprintf(err, n, "glfwInit failed: %s", glfw_error); return false; }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    GLFWwindow *win = glfwCreateWindow(w, h, title ? title : "shadelab", NULL, NULL);
    if (!win) {
        snprintf(err, n, "cannot open a window with OpenGL 4.5 core: %s", glfw_error);
        glfwTerminate();
        return false;
    }
    glfwMakeContextCurrent(win);
    glfwSwapInterval(1);
    b->kind = SL_BACKEND_GLFW;
    b->name = "glfw";
    b->has_window = true;
    b->window = (struct GLFWwindow *)win;
    glfwGetFramebufferSize(win, &b->width, &b->height);
    b->get_proc_address = glfw_get_proc;
    /* Whether the driver is a CPU rasteriser is decided from GL_RENDERER after loading. */
    b->is_gpu = true;
    return true;
}

void sl_backend_swap(sl_backend *b) {
    if (b->window) glfwSwapBuffers((GLFWwindow *)b->window);
}

bool sl_backend_should_close(sl_backend *b) {
    return b->window && glfwWindowShouldClose((GLFWwindow *)b->window);
}

void sl_backend_glfw_destroy(sl_backend *b) {
    if (!b->window) return;
    glfwDestroyWindow((GLFWwindow *)b->window);
    glfwTerminate();
    b->window = NULL;
}
