/* Opens the Draco module (shadelab-draco.so, gltf_draco.cpp) on the first Draco primitive. */
#include "module.h"
#include "scene/gltf_draco.h"

#include <pthread.h>
#include <stdio.h>

#ifndef SL_BUILD_DRACO_MODULE
#define SL_BUILD_DRACO_MODULE NULL
#endif

static pthread_once_t once = PTHREAD_ONCE_INIT;
static const sl_draco_api *api;
static char why[2048];

static void load(void) {
    api = sl_module_open("shadelab-draco.so", "SHADELAB_DRACO_MODULE", SL_BUILD_DRACO_MODULE, "sl_draco_module_api",
                         sizeof(sl_draco_api), why, sizeof why);
}

const sl_draco_api *sl_draco(char *err, size_t err_size) {
    pthread_once(&once, load);
    if (!api && err && err_size) snprintf(err, err_size, "%s", why);
    return api;
}
