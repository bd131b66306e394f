/* OSMesa: Mesa's off-screen CPU renderer (llvmpipe). libOSMesa is dlopen'ed, and GL entry
 * points come from OSMesaGetProcAddress; rendering goes to the core's own framebuffers, so the
 * OSMesa colour buffer is only a 1×1 placeholder. */
#include "backend/backend.h"
#include <GL/osmesa.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef OSMesaContext (*create_attribs_fn)(const int *, OSMesaContext);
typedef GLboolean (*make_current_fn)(OSMesaContext, void *, GLenum, GLsizei, GLsizei);
typedef void (*destroy_fn)(OSMesaContext);
typedef OSMESAproc (*get_proc_fn)(const char *);

static struct {
    void *lib;
    OSMesaContext ctx;
    get_proc_fn get_proc;
    destroy_fn destroy;
    unsigned char pixel[16];
} osm;

static void *osmesa_get_proc(const char *name) { return (void *)osm.get_proc(name); }

static void osmesa_destroy(sl_backend *b) {
    if (osm.ctx) osm.destroy(osm.ctx);
    osm.ctx = NULL;
}

bool sl_backend_osmesa_create(sl_backend *b, int w, int h, char *err, size_t n) {
    if (!osm.lib) {
        const char *names[] = {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"};
        for (int i = 0; i < 3 && !osm.lib; i++) osm.lib = dlopen(names[i], RTLD_NOW | RTLD_LOCAL);
        if (!osm.lib) {
            snprintf(err, n, "cannot load libOSMesa (install libosmesa6): %s", dlerror());
            return false;
        }
    }
    create_attribs_fn create = (create_attribs_fn)dlsym(osm.lib, "OSMesaCreateContextAttribs");
    make_current_fn make_current = (make_current_fn)dlsym(osm.lib, "OSMesaMakeCurrent");
    osm.destroy = (destroy_fn)dlsym(osm.lib, "OSMesaDestroyContext");
    osm.get_proc = (get_proc_fn)dlsym(osm.lib, "OSMesaGetProcAddress");
    if (!create || !make_current || !osm.destroy || !osm.get_proc) {
        snprintf(err, n, "libOSMesa lacks OSMesaCreateContextAttribs (Mesa too old)");
        return false;
    }
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    osm.ctx = create(attribs, NULL);
    if (!osm.ctx) {
        snprintf(err, n, "OSMesaCreateContextAttribs failed for a 4.5 core context");
        return false;
    }
    if (!make_current(osm.ctx, osm.pixel, GL_UNSIGNED_BYTE, 1, 1)) {
        snprintf(err, n, "OSMesaMakeCurrent failed");
        osmesa_destroy(b);
        return false;
    }
    b->kind = SL_BACKEND_OSMESA;
    b->name = "osmesa";
    b->is_gpu = false;
    b->width = w;
    b->height = h;
    b->get_proc_address = osmesa_get_proc;
    b->impl = &osm;
    return true;
}

void sl_backend_osmesa_destroy(sl_backend *b) { osmesa_destroy(b); }
