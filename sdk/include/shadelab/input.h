/* Untrusted input, read safely: the checks the core makes on every file and command-line number,
 * for plugins, tools and extras to make the same way (header only: nothing to link, no ABI).
 *
 * Files. A FIFO blocks in open() until a writer comes; a device (/dev/zero, /dev/urandom) never
 * ends; a symlink to either looks like a file. So a path named by a user is never opened unless
 * it is a regular file: sl_input_file_problem checks without opening (call it before handing a
 * path to a library that opens it itself: OpenImageIO, assimp), sl_open_input_file opens with
 * O_NONBLOCK and checks the descriptor it got (fstat), so a FIFO swapped in after the check
 * cannot block either. Bound what you then read (SL_IMAGE_MAX_PIXELS for images).
 *
 * Numbers. sl_parse_long / sl_parse_double / sl_parse_size read a whole argument strictly: the
 * text is one number (no trailing characters: "2abc" is refused), finite (no nan, inf), within
 * the given range and without overflow (4294967297 is not 1). Name the range in the message.
 *
 * The core uses these very functions (scene files, textures, meshes, plugins, the command line),
 * so a plugin that uses them refuses the same inputs with the same words. POSIX only. */
#ifndef SHADELAB_INPUT_H
#define SHADELAB_INPUT_H

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Why `path` cannot be read as an input file, written into buf and returned: the system's
 * words when it is missing or unreadable ("No such file or directory"), "is a directory", or
 * "is not a regular file (a FIFO)" / "(a device)" / "(a socket)"; NULL when it is a readable
 * regular file. Follows symlinks (a link to /dev/zero is a device). Never opens the path. */
static inline const char *sl_input_file_problem(const char *path, char *buf, size_t buf_size) {
    struct stat st;
    if (!path || !*path) return snprintf(buf, buf_size, "no path given"), buf;
    if (stat(path, &st) != 0) return snprintf(buf, buf_size, "%s", strerror(errno)), buf;
    if (S_ISDIR(st.st_mode)) return snprintf(buf, buf_size, "is a directory"), buf;
    if (!S_ISREG(st.st_mode))
        return snprintf(buf, buf_size, "is not a regular file (a %s)",
                        S_ISFIFO(st.st_mode) ? "FIFO"
                        : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "device"
                        : S_ISSOCK(st.st_mode) ? "socket" : "special file"),
               buf;
    if (access(path, R_OK) != 0) return snprintf(buf, buf_size, "%s", strerror(errno)), buf;
    return NULL;
}

/* Opens `path` for reading only if it is a regular file: open(O_RDONLY | O_NONBLOCK), fstat of
 * the descriptor, then O_NONBLOCK cleared. Returns the descriptor (close() it; fdopen() it for
 * a FILE *), or -1 with "PATH: cause" in err (when given) and errno set (EINVAL for a file that
 * is not regular). */
static inline int sl_open_input_file(const char *path, char *err, size_t err_size) {
#ifdef O_CLOEXEC
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
#else
    int fd = open(path, O_RDONLY | O_NONBLOCK);
#endif
    if (fd < 0) {
        int e = errno;
        if (err && err_size) snprintf(err, err_size, "%s: %s", path, strerror(e));
        errno = e;
        return -1;
    }
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        char why[128];
        if (!sl_input_file_problem(path, why, sizeof why)) snprintf(why, sizeof why, "is not a regular file");
        if (err && err_size) snprintf(err, err_size, "%s: %s; refusing to read it", path, why);
        close(fd);
        errno = EINVAL;
        return -1;
    }
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    return fd;
}

/* The whole of `s` is a whole number within [lo, hi] (decimal, optional sign). */
static inline bool sl_parse_long(const char *s, long lo, long hi, long *out) {
    if (!s || !*s) return false;
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end || errno == ERANGE || v < lo || v > hi) return false;
    *out = v;
    return true;
}

/* The whole of `s` is a finite number within [lo, hi] (nan, inf, overflow and trailing text
 * refused). */
static inline bool sl_parse_double(const char *s, double lo, double hi, double *out) {
    if (!s || !*s) return false;
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end || errno == ERANGE || !isfinite(v) || v < lo || v > hi) return false;
    *out = v;
    return true;
}

/* "WxH", each a whole number 1..max. */
static inline bool sl_parse_size(const char *s, long max, int *w, int *h) {
    const char *x = s ? strchr(s, 'x') : NULL;
    char left[32];
    long lw, lh;
    if (!x || x - s >= (long)sizeof left) return false;
    snprintf(left, sizeof left, "%.*s", (int)(x - s), s);
    if (!sl_parse_long(left, 1, max, &lw) || !sl_parse_long(x + 1, 1, max, &lh)) return false;
    *w = (int)lw, *h = (int)lh;
    return true;
}

#ifdef __cplusplus
}
#endif
#endif
