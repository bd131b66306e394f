/* Reading whole files: one implementation for the core (scene files, shader sources), the bench
 * tool and the tests. */
#ifndef SL_FILEIO_H
#define SL_FILEIO_H
#include <stddef.h>

/* The whole file as a malloc'd, NUL-terminated buffer; *len (when given) gets the number of
 * bytes read. Reads in chunks, so pipes and /proc files work too. On failure returns NULL and,
 * when err is given, writes "PATH: cause" (the system's message, "out of memory" or "read error");
 * errno still holds fopen's error when the file could not be opened. */
char *sl_read_file(const char *path, size_t *len, char *err, size_t err_size);

#endif
