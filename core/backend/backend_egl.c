/* EGL headless contexts: the device platform (EGL_EXT_platform_device) on a real GPU, or Mesa's
 * surfaceless platform (llvmpipe) — the path that keeps working as newer Mesa drops OSMesa.
 * libEGL is dlopen'ed; the context renders only into the core's framebuffers (no surface). */
#define EGL_EGL_PROTOTYPES 0
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include "backend/backend.h"
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

static struct {
    void *lib;
    PFNEGLGETPROCADDRESSPROC get_proc;
    EGLDisplay dpy;
    EGLContext ctx;
} egl;

#define EGLFN(type, name) type name = (type)egl.get_proc(#name)

static bool egl_open(char *err, size_t n) {
    if (egl.lib) return true;
    egl.lib = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!egl.lib) { snprintf(err, n, "cannot load libEGL.so.1: %s", dlerror()); return false; }
    egl.get_proc = (PFNEGLGETPROCADDRESSPROC)dlsym(egl.lib, "eglGetProcAddress");
    if (!egl.get_proc) { snprintf(err, n, "libEGL has no eglGetProcAddress"); return false; }
    return true;
}

static bool has_ext(const char *list, const char *ext) {
    if (!list) return false;
    size_t len = strlen(ext);
    for (const char *p = list; (p = strstr(p, ext)); p += len)
        if ((p == list || p[-1] == ' ') && (p[len] == ' ' || p[len] == 0)) return true;
    return false;
}

/* Finds a non-software EGL device; NULL if none. */
static EGLDeviceEXT find_gpu_device(void) {
    EGLFN(PFNEGLQUERYDEVICESEXTPROC, eglQueryDevicesEXT);
    EGLFN(PFNEGLQUERYDEVICESTRINGEXTPROC, eglQueryDeviceStringEXT);
    if (!eglQueryDevicesEXT || !eglQueryDeviceStringEXT) return NULL;
    EGLDeviceEXT devs[16];
    EGLint count = 0;
    if (!eglQueryDevicesEXT(16, devs, &count)) return NULL;
    for (int i = 0; i < count; i++) {
        const char *exts = eglQueryDeviceStringEXT(devs[i], EGL_EXTENSIONS);
        if (!has_ext(exts, "EGL_MESA_device_software")) return devs[i];
    }
    return NULL;
}

bool sl_backend_egl_gpu_available(void) {
    char err[256];
    if (!egl_open(err, sizeof err)) return false;
    return find_gpu_device() != NULL;
}

static void *egl_get_proc(const char *name) { return (void *)egl.get_proc(name); }

bool sl_backend_egl_create(sl_backend *b, bool require_gpu, int w, int h, char *err, size_t n) {
    if (!egl_open(err, n)) return false;
    EGLFN(PFNEGLGETPLATFORMDISPLAYEXTPROC, eglGetPlatformDisplayEXT);
    EGLFN(PFNEGLINITIALIZEPROC, eglInitialize);
    EGLFN(PFNEGLBINDAPIPROC, eglBindAPI);
    EGLFN(PFNEGLCHOOSECONFIGPROC, eglChooseConfig);
    EGLFN(PFNEGLCREATECONTEXTPROC, eglCreateContext);
    EGLFN(PFNEGLMAKECURRENTPROC, eglMakeCurrent);
    EGLFN(PFNEGLQUERYSTRINGPROC, eglQueryString);
    EGLFN(PFNEGLGETERRORPROC, eglGetError);
    if (!eglGetPlatformDisplayEXT || !eglInitialize) {
        snprintf(err, n, "EGL lacks eglGetPlatformDisplayEXT");
        return false;
    }
    EGLDeviceEXT dev = find_gpu_device();
    bool gpu = dev != NULL;
    if (require_gpu && !gpu) { snprintf(err, n, "no GPU EGL device"); return false; }
    egl.dpy = gpu ? eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, dev, NULL)
                  : eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    EGLint major, minor;
    if (egl.dpy == EGL_NO_DISPLAY || !eglInitialize(egl.dpy, &major, &minor)) {
        snprintf(err, n, "eglInitialize failed on the %s platform (error 0x%x)",
                 gpu ? "device" : "surfaceless", eglGetError());
        return false;
    }
    if (!has_ext(eglQueryString(egl.dpy, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
        snprintf(err, n, "EGL display lacks EGL_KHR_surfaceless_context");
        return false;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) { snprintf(err, n, "eglBindAPI(EGL_OPENGL_API) failed"); return false; }
    const EGLint cfg_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig cfg = NULL;
    EGLint ncfg = 0;
    eglChooseConfig(egl.dpy, cfg_attribs, &cfg, 1, &ncfg);
    const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_NONE};
    egl.ctx = eglCreateContext(egl.dpy, ncfg ? cfg : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, ctx_attribs);
    if (egl.ctx == EGL_NO_CONTEXT) {
        snprintf(err, n, "eglCreateContext for OpenGL 4.5 core failed (error 0x%x)", eglGetError());
        return false;
    }
    if (!eglMakeCurrent(egl.dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, egl.ctx)) {
        snprintf(err, n, "eglMakeCurrent failed (error 0x%x)", eglGetError());
        return false;
    }
    b->kind = SL_BACKEND_EGL;
    b->name = gpu ? "egl-device" : "egl-surfaceless";
    b->is_gpu = gpu;
    b->width = w;
    b->height = h;
    b->get_proc_address = egl_get_proc;
    b->impl = &egl;
    return true;
}

void sl_backend_egl_destroy(sl_backend *b) {
    if (!egl.lib || !egl.dpy) return;
    EGLFN(PFNEGLMAKECURRENTPROC, eglMakeCurrent);
    EGLFN(PFNEGLDESTROYCONTEXTPROC, eglDestroyContext);
    EGLFN(PFNEGLTERMINATEPROC, eglTerminate);
    eglMakeCurrent(egl.dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (egl.ctx) eglDestroyContext(egl.dpy, egl.ctx);
    eglTerminate(egl.dpy);
    egl.ctx = NULL;
    egl.dpy = NULL;
}
