/* Compiled only into the installed harness library (libshadelab_harness.so), which runs inside
 * a third party's test executable: the core looks for its GLSL and built-in plugins relative to
 * the running executable (or the source tree it was built from), which for such a test is
 * neither. Before anything else runs, point SHADELAB_SHADER_DIR at the shaders installed beside
 * this library and add its built-in plugin directory to SHADELAB_PLUGIN_PATH, unless the
 * caller set them. Paths come from this library's own location, so the install is relocatable. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

__attribute__((constructor)) static void sl_harness_locate(void) {
    Dl_info info;
    if (!dladdr((void *)sl_harness_locate, &info) || !info.dli_fname) return;
    char path[4096], libdir[4096], buf[8300];
    snprintf(path, sizeof path, "%s", info.dli_fname);
    snprintf(libdir, sizeof libdir, "%s", dirname(path));       /* <prefix>/<libdir> */
    struct stat st;
    const char *shaders = getenv("SHADELAB_SHADER_DIR");
    if (!shaders || !*shaders) {
        /* <prefix>/<libdir> → <prefix>/<datadir>/shadelab/shaders */
        snprintf(buf, sizeof buf, "%s/%s/%s/shadelab/shaders", libdir, SL_LIB_TO_PREFIX, SL_INSTALL_DATADIR);
        if (stat(buf, &st) == 0) setenv("SHADELAB_SHADER_DIR", buf, 1);
    }
    const char *plugins = getenv("SHADELAB_PLUGIN_PATH");
    snprintf(buf, sizeof buf, "%s/shadelab/plugins", libdir);
    if (stat(buf, &st) == 0) {
        if (plugins && *plugins) {
            char both[16384];
            snprintf(both, sizeof both, "%s:%s", plugins, buf);
            setenv("SHADELAB_PLUGIN_PATH", both, 1);
        } else {
            setenv("SHADELAB_PLUGIN_PATH", buf, 1);
        }
    }
}
