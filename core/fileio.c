#include "fileio.h"
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

char *sl_read_file(const char *path, size_t *len, char *err, size_t err_size) {
    /* O_NONBLOCK open + fstat: a FIFO or device is refused without blocking (<shadelab/input.h>) */
    int fd = sl_open_input_file(path, err, err_size);
    if (fd < 0) return NULL;
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        close(fd);
        if (err && err_size) snprintf(err, err_size, "%s: out of memory", path);
        return NULL;
    }
    enum { CHUNK = 65536 };
    char *buf = NULL;
    size_t cap = 0, n = 0;
    for (;;) {
        if (n > SL_READ_FILE_MAX_BYTES) { /* /proc-like files report size 0: the cap is on bytes read */
            free(buf);
            fclose(f);
            if (err && err_size)
                snprintf(err, err_size, "%s: larger than the %u MiB limit for a whole-file read", path,
                         SL_READ_FILE_MAX_BYTES >> 20);
            errno = EFBIG;
            return NULL;
        }
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
