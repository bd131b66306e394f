#include "fileio.h"
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

const char *sl_input_file_problem(const char *path, char *buf, size_t n) {
    struct stat st;
    if (stat(path, &st) != 0) return snprintf(buf, n, "%s", strerror(errno)), buf;
    if (S_ISDIR(st.st_mode)) return snprintf(buf, n, "is a directory"), buf;
    /* a FIFO blocks in open() until a writer comes; a device never ends: never open them */
    if (!S_ISREG(st.st_mode))
        return snprintf(buf, n, "is not a regular file (a %s)",
                        S_ISFIFO(st.st_mode) ? "FIFO" : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "device"
                                                        : S_ISSOCK(st.st_mode) ? "socket" : "special file"),
               buf;
    if (access(path, R_OK) != 0) return snprintf(buf, n, "%s", strerror(errno)), buf;
    return NULL;
}

char *sl_read_file(const char *path, size_t *len, char *err, size_t err_size) {
    /* O_NONBLOCK: a FIFO swapped in after a check must not block the open; fstat then decides */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        int e = errno;
        if (err && err_size) snprintf(err, err_size, "%s: %s", path, strerror(e));
        errno = e;
        return NULL;
    }
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        char why[128];
        sl_input_file_problem(path, why, sizeof why);
        if (err && err_size) snprintf(err, err_size, "%s: %s; refusing to read it", path, why);
        close(fd);
        errno = EINVAL;
        return NULL;
    }
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
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
