/* Opens the image modules on first use and forwards image.h's internal calls to them: the
 * OpenImageIO adapter (shadelab-oiio.so, image_oiio.cpp: the sl_oiio_* calls) and the OpenEXR C++
 * adapter (shadelab-exr.so, image_exr.cpp: sl_exr_read). Why modules: see image.h. Where a module
 * (these, and the glTF reader's Draco adapter: sl_module_open, module.h) is looked for, in order:
 *   $SHADELAB_OIIO_MODULE / $SHADELAB_EXR_MODULE (a path to the .so);
 *   beside the object holding this code, and in its ../LIBDIR/shadelab/ (installed: bin/shadelab
 *   → lib/shadelab/, lib/libshadelab_harness.so → lib/shadelab/);
 *   the build tree's copy (SL_BUILD_OIIO_MODULE, SL_BUILD_EXR_MODULE), for tools and tests built in
 *   subfolders. */
#define _GNU_SOURCE
#define SL_IMAGE_INTERNAL
#include "image/image.h"
#include "log.h"
#include "module.h"

#include <dlfcn.h>
#include <libgen.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef SL_BUILD_OIIO_MODULE
#define SL_BUILD_OIIO_MODULE NULL
#endif
#ifndef SL_BUILD_EXR_MODULE
#define SL_BUILD_EXR_MODULE NULL
#endif

static void *try_open(const char *path, char *tried, size_t n) {
    size_t used = strlen(tried);
    snprintf(tried + used, n - used, "%s%s", used ? ", " : "", path);
    if (access(path, R_OK) != 0) return NULL;
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (h) SL_DEBUG("image module: %s", path);
    else {
        used = strlen(tried);
        snprintf(tried + used, n - used, " (%s)", dlerror());
    }
    return h;
}

const void *sl_module_open(const char *name, const char *env_var, const char *build_copy, const char *symbol,
                               unsigned min_size, char *why, size_t why_size) {
    char tried[1500] = "", path[1200];
    void *h = NULL;
    const char *env = getenv(env_var);
    if (env && *env) h = try_open(env, tried, sizeof tried);
    Dl_info self;
    if (!h && dladdr((void *)&sl_module_open, &self) && self.dli_fname && self.dli_fname[0]) {
        char copy[1024];
        /* the executable's own entry may be a bare name: /proc/self/exe is the real file */
        if (!strchr(self.dli_fname, '/')) {
            ssize_t l = readlink("/proc/self/exe", copy, sizeof copy - 1);
            copy[l > 0 ? l : 0] = 0;
        } else {
            snprintf(copy, sizeof copy, "%s", self.dli_fname);
        }
        const char *dir = dirname(copy);
        snprintf(path, sizeof path, "%s/%s", dir, name);
        h = try_open(path, tried, sizeof tried);
        if (!h) {
            snprintf(path, sizeof path, "%s/shadelab/%s", dir, name);
            h = try_open(path, tried, sizeof tried);
        }
        if (!h) {
            snprintf(path, sizeof path, "%s/../%s/shadelab/%s", dir, SL_INSTALL_LIBDIR, name);
            h = try_open(path, tried, sizeof tried);
        }
    }
    if (!h && build_copy) h = try_open(build_copy, tried, sizeof tried);
    const void *(*get)(void) = NULL;
    if (h) *(void **)&get = dlsym(h, symbol);
    const unsigned *table = get ? get() : NULL; /* every table starts with its struct_size */
    if (table && *table >= min_size) return table;
    if (h && !table) snprintf(why, why_size, "%s has no %s", name, symbol);
    else if (h) snprintf(why, why_size, "%s is from another build (its table is smaller)", name);
    else snprintf(why, why_size, "cannot open the module %s (looked in: %s; %s names it)", name, tried, env_var);
    return NULL;
}

static pthread_once_t once = PTHREAD_ONCE_INIT, exr_once = PTHREAD_ONCE_INIT;
static const sl_oiio_api *api;
static const sl_exr_api *exr_api;
static char why[2048], exr_why[2048];

static void load(void) {
    api = sl_module_open("shadelab-oiio.so", "SHADELAB_OIIO_MODULE", SL_BUILD_OIIO_MODULE, "sl_oiio_module_api",
                      sizeof(sl_oiio_api), why, sizeof why);
}

static void load_exr(void) {
    exr_api = sl_module_open("shadelab-exr.so", "SHADELAB_EXR_MODULE", SL_BUILD_EXR_MODULE, "sl_exr_module_api",
                          sizeof(sl_exr_api), exr_why, sizeof exr_why);
}

bool sl_exr_read(const char *path, const void *data, size_t size, int x0, int y0, int w, int h, int nch,
                 const char *const *names, bool half, void *out, char *err, size_t n) {
    pthread_once(&exr_once, load_exr);
    if (!exr_api) {
        if (err && n) snprintf(err, n, "%s", exr_why);
        return false;
    }
    return exr_api->read(path, data, size, x0, y0, w, h, nch, names, half, out, err, n);
}

static const sl_oiio_api *module(char *err, size_t n) {
    pthread_once(&once, load);
    if (!api && err && n) snprintf(err, n, "%s", why);
    return api;
}

sl_oiio_input *sl_oiio_open(const char *path, sl_oiio_info *info, char *err, size_t n) {
    const sl_oiio_api *a = module(err, n);
    return a ? a->open(path, info, err, n) : NULL;
}

sl_oiio_input *sl_oiio_open_memory(const void *data, size_t size, const char *name, sl_oiio_info *info, char *err,
                                   size_t n) {
    const sl_oiio_api *a = module(err, n);
    return a ? a->open_memory(data, size, name, info, err, n) : NULL;
}

bool sl_oiio_read(sl_oiio_input *in, int chbegin, int chend, float *out, char *err, size_t n) {
    const sl_oiio_api *a = module(err, n);
    return a && a->read(in, chbegin, chend, out, err, n);
}

void sl_oiio_close(sl_oiio_input *in) {
    const sl_oiio_api *a = module(NULL, 0);
    if (a && in) a->close(in);
}

bool sl_oiio_write(const char *path, const char *format, const unsigned char *pixels8, const float *pixelsf, int width,
                   int height, int channels, const char *file_type, int jpeg_quality, char *err, size_t n) {
    const sl_oiio_api *a = module(err, n);
    return a && a->write(path, format, pixels8, pixelsf, width, height, channels, file_type, jpeg_quality, err, n);
}

bool sl_oiio_extension_known(const char *ext) {
    const sl_oiio_api *a = module(NULL, 0);
    return a && a->extension_known(ext);
}
