/* GL context backends behind one interface: GLFW window, OSMesa (headless CPU, llvmpipe),
 * EGL (headless: device platform on GPUs, surfaceless on Mesa). The libraries behind OSMesa
 * and EGL are dlopen'ed so one binary runs wherever any of them exists. */
#ifndef SL_BACKEND_H
#define SL_BACKEND_H
#include <stdbool.h>
#include <stddef.h>

typedef enum sl_backend_kind {
    SL_BACKEND_AUTO = 0, /* window if a display exists, else headless */
    SL_BACKEND_HEADLESS, /* EGL when a GPU device exists, else OSMesa */
    SL_BACKEND_GLFW,
    SL_BACKEND_OSMESA,
    SL_BACKEND_EGL
} sl_backend_kind;

typedef struct sl_backend {
    sl_backend_kind kind;     /* the one actually in use */
    const char *name;         /* "glfw", "osmesa", "egl-device", "egl-surfaceless" */
    bool has_window;
    bool is_gpu;              /* false for llvmpipe/softpipe: use glFinish timing */
    int width, height;        /* window framebuffer size (headless: requested size) */
    void *(*get_proc_address)(const char *name);
    void *impl;               /* backend private */
    struct GLFWwindow *window;/* GLFW only */
} sl_backend;

/* Parses "auto", "headless", "glfw", "osmesa", "egl". */
bool sl_backend_parse(const char *name, sl_backend_kind *out);
/* Creates a context and makes it current. On failure, err lists every backend tried and why. */
bool sl_backend_create(sl_backend *b, sl_backend_kind kind, int width, int height,
                       const char *title, char *err, size_t err_size);
void sl_backend_destroy(sl_backend *b);

/* Window backends only. */
void sl_backend_swap(sl_backend *b);
bool sl_backend_should_close(sl_backend *b);

/* Per-backend implementations (backend_*.c). */
bool sl_backend_osmesa_create(sl_backend *b, int w, int h, char *err, size_t n);
bool sl_backend_egl_create(sl_backend *b, bool require_gpu, int w, int h, char *err, size_t n);
bool sl_backend_egl_gpu_available(void);
bool sl_backend_glfw_create(sl_backend *b, int w, int h, const char *title, char *err, size_t n);
#endif
