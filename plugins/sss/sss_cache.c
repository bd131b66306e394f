/* sss's on-disk cache of the texture-space result: see sss_cache.h. */
#define _GNU_SOURCE
#include "sss_cache.h"
#include <shadelab/cache.h>
#include <shadelab/input.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef struct header {
    char magic[8];
    uint64_t key;
    int32_t size, result;
} header;
static const char MAGIC[8] = "SLSSSC1";

/* 8 bytes at a time (the maps are megabytes): xor, multiply by the FNV-1a 64-bit prime, fold the
 * high half down; the tail byte by byte. */
uint64_t sss_hash(const void *data, size_t bytes, uint64_t h) {
    const unsigned char *p = data;
    size_t i = 0;
    for (; i + 8 <= bytes; i += 8) {
        uint64_t w;
        memcpy(&w, p + i, 8);
        h = (h ^ w) * 1099511628211ull;
        h ^= h >> 29;
    }
    for (; i < bytes; i++) h = (h ^ p[i]) * 1099511628211ull;
    return h ^ (h >> 32);
}

uint64_t sss_hash_files(const char *dir, const char *const *names, uint64_t h) {
    for (; *names; names++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir ? dir : ".", *names);
        FILE *f = fopen(path, "rb");
        h = sss_hash(*names, strlen(*names), h);
        if (!f) continue;
        char buf[8192];
        size_t got;
        while ((got = fread(buf, 1, sizeof buf, f)) > 0) h = sss_hash(buf, got, h);
        fclose(f);
    }
    return h;
}

static void file_path(const char *dir, uint64_t key, char *out, size_t n) {
    snprintf(out, n, "%s/ts-%016llx.bin", dir, (unsigned long long)key);
}

float *sss_cache_load(uint64_t key, int size, int *result) {
    char dir[2048], path[2300];
    if (size <= 0 || !sl_cache_dir("sss", dir, sizeof dir, false)) return NULL;
    file_path(dir, key, path, sizeof path);
    int fd = sl_open_input_file(path, NULL, 0); /* a regular file only: never blocks on a FIFO */
    FILE *f = fd >= 0 ? fdopen(fd, "rb") : NULL;
    if (!f) {
        if (fd >= 0) close(fd);
        return NULL;
    }
    header h;
    float *px = NULL;
    size_t bytes = (size_t)size * size * 4 * sizeof(float);
    if (fread(&h, sizeof h, 1, f) == 1 && !memcmp(h.magic, MAGIC, 8) && h.key == key && h.size == size &&
        h.result >= 0 && h.result < 16) {
        px = malloc(bytes);
        if (px && fread(px, 1, bytes, f) != bytes) {
            free(px);
            px = NULL;
        }
        *result = h.result;
    }
    fclose(f);
    return px;
}

bool sss_cache_store(uint64_t key, int size, int result, const float *texels, char *err, size_t n) {
    char dir[2048], path[2300], tmp[2400];
    if (!sl_cache_dir("sss", dir, sizeof dir, true)) {
        snprintf(err, n, "no cache directory (SHADELAB_CACHE, XDG_CACHE_HOME and HOME unset or not writable)");
        return false;
    }
    file_path(dir, key, path, sizeof path);
    snprintf(tmp, sizeof tmp, "%s.%d.tmp", path, (int)getpid());
    FILE *f = fopen(tmp, "wb");
    if (!f) {
        snprintf(err, n, "%s: %s", tmp, strerror(errno));
        return false;
    }
    header h = {.key = key, .size = size, .result = result};
    memcpy(h.magic, MAGIC, 8);
    size_t bytes = (size_t)size * size * 4 * sizeof(float);
    bool ok = fwrite(&h, sizeof h, 1, f) == 1 && fwrite(texels, 1, bytes, f) == bytes;
    ok = fclose(f) == 0 && ok;
    if (!ok || rename(tmp, path) != 0) {
        snprintf(err, n, "%s: %s", path, strerror(errno));
        unlink(tmp);
        return false;
    }
    sl_cache_prune(dir, "ts-", SSS_CACHE_FILES);
    return true;
}
