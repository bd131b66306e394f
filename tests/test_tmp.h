/* Where a C test writes its files: never the build tree, which may be read-only or a copy.
 *
 *   sl_test_dir()  the test's output directory, created on first use, once per process:
 *                  $SL_TEST_OUT/NAME when SL_TEST_OUT is set (kept), else a fresh mkdtemp
 *                  directory $TMPDIR/shadelab-test-NAME.XXXXXX (TMPDIR unset: /tmp). NAME is
 *                  the test's name (its executable's, less "test_"), as tests/run_in_tmpdir.sh
 *                  names the command-line tests' directories.
 *                  The temporary one is removed at exit when every CHECK passed and kept (its
 *                  path on stderr) when one failed; SL_TEST_KEEP=1 keeps it always. To look at
 *                  the images a test writes: SL_TEST_OUT=/some/dir ctest ...
 *
 * Includes check.h (the exit handler reads its failure count). A test that cannot get its
 * directory stops there: the reason on stderr, exit status 1. */
#ifndef SL_TEST_TMP_H
#define SL_TEST_TMP_H
#include "check.h"
#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char sl_test_dir_[PATH_MAX];
static pid_t sl_test_dir_owner_; /* the process that made the temporary directory, 0 when kept */

/* rm -rf path (no symlinks followed). */
static inline void sl_test_remove_tree_(const char *path) {
    struct stat st;
    if (lstat(path, &st) != 0) return;
    if (S_ISDIR(st.st_mode)) {
        DIR *d = opendir(path);
        for (struct dirent *e; d && (e = readdir(d));) {
            if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
            char sub[PATH_MAX];
            if (snprintf(sub, sizeof sub, "%s/%s", path, e->d_name) < (int)sizeof sub) sl_test_remove_tree_(sub);
        }
        if (d) closedir(d);
        rmdir(path);
    } else {
        unlink(path);
    }
}

static inline void sl_test_dir_cleanup_(void) {
    if (!sl_test_dir_owner_ || getpid() != sl_test_dir_owner_) return; /* kept, or a forked child */
    const char *keep = getenv("SL_TEST_KEEP");
    if (check_failures_ || (keep && *keep && strcmp(keep, "0")))
        fprintf(stderr, "test files kept in %s\n", sl_test_dir_);
    else
        sl_test_remove_tree_(sl_test_dir_);
}

/* mkdir -p; false (errno set) on failure. */
static inline int sl_test_mkdirs_(const char *path) {
    char p[PATH_MAX];
    if (snprintf(p, sizeof p, "%s", path) >= (int)sizeof p) return errno = ENAMETOOLONG, 0;
    for (char *s = p + 1; *s; s++)
        if (*s == '/') {
            *s = 0;
            if (mkdir(p, 0777) != 0 && errno != EEXIST) return 0;
            *s = '/';
        }
    return mkdir(p, 0777) == 0 || errno == EEXIST;
}

static inline const char *sl_test_dir(void) {
    if (sl_test_dir_[0]) return sl_test_dir_;
    char exe[PATH_MAX] = "test";
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) exe[n] = 0;
    const char *name = strrchr(exe, '/') ? strrchr(exe, '/') + 1 : exe;
    if (!strncmp(name, "test_", 5) && name[5]) name += 5;
    const char *out = getenv("SL_TEST_OUT");
    if (out && *out) {
        snprintf(sl_test_dir_, sizeof sl_test_dir_, "%s/%s", out, name);
        if (!sl_test_mkdirs_(sl_test_dir_)) {
            fprintf(stderr, "cannot create the test directory %s: %s\n", sl_test_dir_, strerror(errno));
            exit(1);
        }
        return sl_test_dir_;
    }
    const char *tmp = getenv("TMPDIR");
    snprintf(sl_test_dir_, sizeof sl_test_dir_, "%s/shadelab-test-%s.XXXXXX", tmp && *tmp ? tmp : "/tmp", name);
    if (!mkdtemp(sl_test_dir_)) {
        fprintf(stderr, "cannot create a temporary directory %s: %s\n", sl_test_dir_, strerror(errno));
        exit(1);
    }
    sl_test_dir_owner_ = getpid();
    atexit(sl_test_dir_cleanup_);
    return sl_test_dir_;
}

/* A path in the test's directory (one of 8 rotating buffers: valid until the 8th call after). */
static inline const char *sl_test_path(const char *name) {
    static char bufs[8][PATH_MAX];
    static int next;
    char *b = bufs[next++ % 8];
    snprintf(b, PATH_MAX, "%s/%s", sl_test_dir(), name);
    return b;
}

/* A whole file into malloc'd memory (*n its size; NULL and 0 when it cannot be read). */
static inline unsigned char *sl_test_read_file(const char *path, size_t *n) {
    *n = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    rewind(f);
    unsigned char *d = malloc(len > 0 ? (size_t)len : 1);
    *n = d ? fread(d, 1, (size_t)len, f) : 0;
    fclose(f);
    return d;
}

/* Writes n bytes to path (a failed CHECK when it cannot). */
static inline void sl_test_write_file(const char *path, const void *d, size_t n) {
    FILE *f = fopen(path, "wb");
    CHECK_MSG(f != NULL, "cannot write %s", path);
    if (f) {
        CHECK(fwrite(d, 1, n, f) == n);
        fclose(f);
    }
}

/* Whether a file whose path contains `name` is mapped into this process (a shared object that was
 * loaded: /proc/self/maps). */
static inline bool sl_test_mapped(const char *name) {
    FILE *f = fopen("/proc/self/maps", "r");
    char line[4096];
    bool found = false;
    while (f && fgets(line, sizeof line, f))
        if (strstr(line, name)) found = true;
    if (f) fclose(f);
    return found;
}
#endif
