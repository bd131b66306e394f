#include "fileio.h"
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

char *sl_read_file(const char *path, size_t *len, char *err, size_t err_size) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        int e = errno;
        if (err && err_size) snprintf(err, err_size, "%s: %s", path, strerror(e));
        errno = e;
        return NULL;
    }
    enum { CHUNK = 65536 };
    char *buf = NULL;
    size_t cap = 0, n = 0;
    for (;;) {
        if (n + CHUNK + 1 > cap) {
            cap = cap ? cap * 2 : 2 * CHUNK;
            char *grown = realloc(buf, cap);
            if (!grown) {
                free(buf);
                fclose(f);
                if (err && err_size) snprintf(err, err_size, "%s: out of memory", path);
                return NULL;
            }
            buf = grown;
        }
        size_t got = fread(buf + n, 1, CHUNK, f);
        n += got;
        if (got < CHUNK) break;
    }
    int failed = ferror(f);
    fclose(f);
    if (failed) {
        free(buf);
        if (err && err_size) snprintf(err, err_size, "%s: read error", path);
        return NULL;
    }
    buf[n] = 0;
    if (len) *len = n;
    return buf;
}
