/* C++ adapters built as modules of their own and opened on first use (core/image/image_modules.c
 * says where they are looked for): a process that never reads such a file never loads the
 * library behind it. */
#ifndef SL_MODULE_H
#define SL_MODULE_H
#include <stddef.h>

/* dlopen()s module `name` ("shadelab-oiio.so"; $env_var, when set, names its path; build_copy: the
 * build tree's path, or NULL) and returns the table its `symbol` function returns, which starts
 * with its struct size (at least min_size); NULL with why it could not in `why`. */
const void *sl_module_open(const char *name, const char *env_var, const char *build_copy, const char *symbol,
                           unsigned min_size, char *why, size_t why_size);
#endif
