#include "backend/backend.h"
#include "log.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool sl_backend_parse(const char *name, sl_backend_kind *out) {
    static const struct { const char *n; sl_backend_kind k; } names[] = {
        {"auto", SL_BACKEND_AUTO}, {"headless", SL_BACKEND_HEADLESS}, {"glfw", SL_BACKEND_GLFW},
        {"osmesa", SL_BACKEND_OSMESA}, {"egl", SL_BACKEND_EGL}};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (!strcmp(name, names[i].n)) { *out = names[i].k; return true; }
    return false;
}

static void append(char *err, size_t n, const char *what, const char *why) {
    size_t used = strlen(err);
    snprintf(err + used, n - used, "%s  %s: %s", used ? "\n" : "", what, why);
}

bool sl_backend_create(sl_backend *b, sl_backend_kind kind, int w, int h, const char *title,
                       char *err, size_t n) {
    memset(b, 0, sizeof *b);
    char tried[2048] = "", why[1024];
    if (kind == SL_BACKEND_AUTO) {
        const char *d = getenv("DISPLAY"), *wl = getenv("WAYLAND_DISPLAY");
        if ((d && *d) || (wl && *wl)) {
            why[0] = 0;
            if (sl_backend_glfw_create(b, w, h, title, why, sizeof why)) return true;
            append(tried, sizeof tried, "glfw", why);
        } else {
            append(tried, sizeof tried, "glfw", "no DISPLAY or WAYLAND_DISPLAY set");
        }
        kind = SL_BACKEND_HEADLESS;
    }
    if (kind == SL_BACKEND_HEADLESS) {
        why[0] = 0;
        if (sl_backend_egl_gpu_available()) {
            if (sl_backend_egl_create(b, true, w, h, why, sizeof why)) return true;
            append(tried, sizeof tried, "egl (GPU device)", why);
        } else {
            append(tried, sizeof tried, "egl (GPU device)", "no GPU EGL device found");
        }
        why[0] = 0;
        if (sl_backend_osmesa_create(b, w, h, why, sizeof why)) return true;
        append(tried, sizeof tried, "osmesa", why);
        why[0] = 0;
        if (sl_backend_egl_create(b, false, w, h, why, sizeof why)) return true;
        append(tried, sizeof tried, "egl (surfaceless)", why);
    } else {
        bool ok = false;
        why[0] = 0;
        if (kind == SL_BACKEND_GLFW) ok = sl_backend_glfw_create(b, w, h, title, why, sizeof why);
        if (kind == SL_BACKEND_OSMESA) ok = sl_backend_osmesa_create(b, w, h, why, sizeof why);
        if (kind == SL_BACKEND_EGL) ok = sl_backend_egl_create(b, false, w, h, why, sizeof why);
        if (ok) return true;
        append(tried, sizeof tried, kind == SL_BACKEND_GLFW ? "glfw" : kind == SL_BACKEND_OSMESA ? "osmesa" : "egl", why);
    }
    snprintf(err, n, "no OpenGL 4.5 core context could be created; tried:\n%s", tried);
    return false;
}

void sl_backend_osmesa_destroy(sl_backend *b);
void sl_backend_egl_destroy(sl_backend *b);
void sl_backend_glfw_destroy(sl_backend *b);

void sl_backend_destroy(sl_backend *b) {
    if (b->kind == SL_BACKEND_OSMESA) sl_backend_osmesa_destroy(b);
    if (b->kind == SL_BACKEND_EGL) sl_backend_egl_destroy(b);
    if (b->kind == SL_BACKEND_GLFW) sl_backend_glfw_destroy(b);
    b->kind = SL_BACKEND_AUTO;
}
