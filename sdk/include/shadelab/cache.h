/* shadelab's on-disk caches (header only: nothing to link, no ABI). The core keeps Mesa's shader
 * cache and decoded images there, plugins their derived data (envmap's prefiltered cubes, sss's
 * texture-space result); each in a folder of its own under one root, so that one variable moves
 * or clears them all:
 *   $SHADELAB_CACHE/NAME, else $XDG_CACHE_HOME/shadelab/NAME, else $HOME/.cache/shadelab/NAME.
 * Write entries under a temporary name in the same folder and rename them into place (a reader
 * never sees half a file); name the temporary ones with ".tmp" in them so that sl_cache_prune can
 * clear what a writer that died left. POSIX only. */
#ifndef SHADELAB_CACHE_H
#define SHADELAB_CACHE_H

#include <dirent.h>
#include <errno.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* The folder NAME of the cache root into out; made (mkdir -p) when create. false when no variable
 * names a root, the path does not fit, or (create) it cannot be made a directory. */
static inline bool sl_cache_dir(const char *name, char *out, size_t n, bool create) {
    const char *c = getenv("SHADELAB_CACHE"), *x = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    int len;
    if (c && *c) len = snprintf(out, n, "%s/%s", c, name);
    else if (x && *x) len = snprintf(out, n, "%s/shadelab/%s", x, name);
    else if (home && *home) len = snprintf(out, n, "%s/.cache/shadelab/%s", home, name);
    else return false;
    if (len < 0 || (size_t)len >= n) return false;
    if (!create) return true;
    for (char *s = out + 1; *s; s++) {
        if (*s != '/') continue;
        *s = 0;
        mkdir(out, 0755); /* an existing parent fails with EEXIST: the final check decides */
        *s = '/';
    }
    struct stat st;
    return (mkdir(out, 0755) == 0 || errno == EEXIST) && stat(out, &st) == 0 && S_ISDIR(st.st_mode);
}

/* In dir: deletes the regular files PREFIX*.bin beyond the `keep` most recently modified (touch an
 * entry when it is used to make this least-recently-used), and PREFIX* files with ".tmp" in their
 * name older than ten minutes (left by a writer that died). */
static inline void sl_cache_prune(const char *dir, const char *prefix, int keep) {
    DIR *d = opendir(dir);
    if (!d) return;
    struct sl_cache_item {
        char name[256];
        struct timespec t;
    } *items = NULL;
    size_t n = 0, cap = 0, lp = strlen(prefix);
    time_t now = time(NULL);
    for (struct dirent *de; (de = readdir(d));) {
        const char *nm = de->d_name;
        size_t l = strlen(nm);
        if (strncmp(nm, prefix, lp) || l >= sizeof items[0].name) continue;
        char p[4400];
        struct stat st;
        if (snprintf(p, sizeof p, "%s/%s", dir, nm) >= (int)sizeof p || lstat(p, &st) != 0 || !S_ISREG(st.st_mode))
            continue;
        if (strstr(nm, ".tmp")) {
            if (now - st.st_mtim.tv_sec > 600) unlink(p);
            continue;
        }
        if (l < lp + 4 || strcmp(nm + l - 4, ".bin")) continue;
        if (n == cap) {
            size_t nc = cap ? cap * 2 : 16;
            struct sl_cache_item *grown = (struct sl_cache_item *)realloc(items, nc * sizeof *items);
            if (!grown) break;
            items = grown, cap = nc;
        }
        memcpy(items[n].name, nm, l + 1);
        items[n++].t = st.st_mtim;
    }
    closedir(d);
    while (n > (size_t)(keep > 0 ? keep : 0)) {
        size_t old = 0;
        for (size_t i = 1; i < n; i++)
            if (items[i].t.tv_sec < items[old].t.tv_sec ||
                (items[i].t.tv_sec == items[old].t.tv_sec && items[i].t.tv_nsec < items[old].t.tv_nsec))
                old = i;
        char p[4400];
        snprintf(p, sizeof p, "%s/%s", dir, items[old].name);
        unlink(p);
        items[old] = items[--n];
    }
    free(items);
}
#endif
