/* shadelab SDK — umbrella header. Plugins include this and nothing from core/.
 *
 * ABI rules (see sdk/docs/plugin-guide.md):
 *  - one exported symbol, shadelab_plugin_entry(), returns a const sl_plugin_desc;
 *  - the host refuses a plugin whose ABI major differs from its own, or whose minor is newer;
 *  - every struct crossing the boundary starts with `uint32_t struct_size`; fields are only ever
 *    appended; the host zero-fills what an older plugin did not know about.
 */
#ifndef SHADELAB_SHADELAB_H
#define SHADELAB_SHADELAB_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* The ABI this header describes. Bump MINOR when appending fields or host functions,
 * MAJOR when anything changes meaning or layout. */
#ifndef SL_ABI_MAJOR
#define SL_ABI_MAJOR 1
#endif
#ifndef SL_ABI_MINOR
#define SL_ABI_MINOR 30
#endif

/* The one limit on decoded image size, for the core's loader and every plugin's or tool's own:
 * 64 Mpixel (8192², 1 GiB as RGBA float), checked from the file's header before any pixel is
 * decoded, so a small file that decompresses to gigabytes is refused at once. */
#define SL_IMAGE_MAX_PIXELS (8192L * 8192L)

#ifdef __cplusplus
extern "C" {
#endif

/* Result of every registration and lifecycle call. */
typedef enum sl_status {
    SL_OK = 0,
    SL_ERR_INVALID = 1,     /* a descriptor is malformed (the log says which field) */
    SL_ERR_DUPLICATE = 2,   /* id/name already registered (by this or another plugin) */
    SL_ERR_UNSUPPORTED = 3, /* the host cannot do this (backend, GL version, extension) */
    SL_ERR_IO = 4,          /* a file could not be read */
    SL_ERR_GL = 5,          /* a GL object could not be created */
    SL_ERR_FAILED = 6       /* anything else; the log carries the cause */
} sl_status;

typedef enum sl_log_level { SL_LOG_DEBUG, SL_LOG_INFO, SL_LOG_WARN, SL_LOG_ERROR } sl_log_level;

#ifdef __cplusplus
}
#endif

#include "params.h"
#include "shader.h"
#include "pass.h"
#include "host.h"
#include "plugin.h"

#endif
