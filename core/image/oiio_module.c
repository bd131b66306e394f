/* Opens the OpenImageIO adapter module (shadelab-oiio.so, image_oiio.cpp) on first use and
 * forwards image.h's internal sl_oiio_* calls to it. Why a module: see image.h. Where it is
 * looked for, in order:
 *   $SHADELAB_OIIO_MODULE (a path to the .so);
 *   beside the object holding this code, and in its ../LIBDIR/shadelab/ (installed: bin/shadelab
 *   → lib/shadelab/, lib/libshadelab_harness.so → lib/shadelab/);
 *   the build tree's copy (SL_BUILD_OIIO_MODULE), for tools and tests built in subfolders. */
#define _GNU_SOURCE
#define SL_IMAGE_INTERNAL
#include "image/image.h"
#include "log.h"

#include <dlfcn.h>
#include <libgen.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define MODULE_NAME "shadelab-oiio.so"

static pthread_once_t once = PTHREAD_ONCE_INIT;
static const sl_oiio_api *api;
static char why[2048];

static void *try_open(const char *path, char *tried, size_t n) {
    size_t used = strlen(tried);
    snprintf(tried + used, n - used, "%s%s", used ? ", " : "", path);
    if (access(path, R_OK) != 0) return NULL;
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (h) SL_DEBUG("OpenImageIO module: %s", path);
    else {
        used = strlen(tried);
        snprintf(tried + used, n - used, " (%s)", dlerror());
    }
    return h;
}

static void load(void) {
    char tried[1500] = "", path[1200];
    void *h = NULL;
    const char *env = getenv("SHADELAB_OIIO_MODULE");
    if (env && *env) h = try_open(env, tried, sizeof tried);
    Dl_info self;
    if (!h && dladdr((void *)&load, &self) && self.dli_fname && self.dli_fname[0]) {
        char copy[1024];
        /* the executable's own entry may be a bare name: /proc/self/exe is the real file */
        if (!strchr(self.dli_fname, '/')) {
            ssize_t l = readlink("/proc/self/exe", copy, sizeof copy - 1);
            copy[l > 0 ? l : 0] = 0;
        } else {
            snprintf(copy, sizeof copy, "%s", self.dli_fname);
        }
        const char *dir = dirname(copy);
        snprintf(path, sizeof path, "%s/" MODULE_NAME, dir);
        h = try_open(path, tried, sizeof tried);
        if (!h) {
            snprintf(path, sizeof path, "%s/shadelab/" MODULE_NAME, dir);
            h = try_open(path, tried, sizeof tried);
        }
        if (!h) {
            snprintf(path, sizeof path, "%s/../%s/shadelab/" MODULE_NAME, dir, SL_INSTALL_LIBDIR);
            h = try_open(path, tried, sizeof tried);
        }
    }
#ifdef SL_BUILD_OIIO_MODULE
    if (!h) h = try_open(SL_BUILD_OIIO_MODULE, tried, sizeof tried);
#endif
    const sl_oiio_api *(*get)(void) = NULL;
    if (h) *(void **)&get = dlsym(h, "sl_oiio_module_api");
    const sl_oiio_api *a = get ? get() : NULL;
    if (a && a->struct_size >= sizeof *a) {
        api = a;
        return;
    }
    if (h && !a) snprintf(why, sizeof why, "%s has no sl_oiio_module_api", MODULE_NAME);
    else if (h) snprintf(why, sizeof why, "%s is from another build (its table is smaller)", MODULE_NAME);
    else snprintf(why, sizeof why, "cannot open the OpenImageIO module %s (looked in: %s; SHADELAB_OIIO_MODULE names "
                  "it)", MODULE_NAME, tried);
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
