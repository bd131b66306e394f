/* Reading input files: one implementation for the core (scene files, shader sources), the bench
 * tool and the tests, and the one check every reader of an untrusted path uses. */
#ifndef SL_FILEIO_H
#define SL_FILEIO_H
#include <shadelab/input.h>
#include <stddef.h>

/* The most sl_read_file reads (scene JSON, shader sources, tables): 256 MiB. */
#define SL_READ_FILE_MAX_BYTES (256u << 20)

/* sl_input_file_problem (why a path cannot be read as an input file, without opening it) and
 * sl_open_input_file (open only a regular file, without blocking) are the SDK's
 * <shadelab/input.h>: one implementation for the core, the plugins and the tools. */

/* The whole file as a malloc'd, NUL-terminated buffer; *len (when given) gets the number of
 * bytes read. Only regular files are read (a FIFO or device is refused without blocking), at most
 * SL_READ_FILE_MAX_BYTES. On failure returns NULL and, when err is given, writes "PATH: cause";
 * errno holds open()'s error when the file could not be opened. */
char *sl_read_file(const char *path, size_t *len, char *err, size_t err_size);

#endif
