/* The decoded-image cache for files only OpenImageIO reads: see image.h (SL_IMAGE_INTERNAL section). */
#define _GNU_SOURCE
#define SL_IMAGE_INTERNAL
#include "image/image.h"
#include <shadelab/cache.h>

#include <errno.h>
#include <fcntl.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#ifndef SL_OIIO_VERSION
#define SL_OIIO_VERSION "unknown"
#endif

/* Bump when the header or the meaning of the pixels changes (decode()'s channel expansion, the
 * source_* rules): every older file then misses, by name and by its header. */
#define CACHE_VERSION 1u
static const char CACHE_MAGIC[8] = "SLIMGC\r\n";

/* The file: this header, then width*height*4 floats (native byte order: a cache is per machine). */
typedef struct cache_header {
    char magic[8];
    uint32_t version;
    uint32_t header_bytes;  /* sizeof(cache_header): catches a struct layout change too */
    uint64_t key;
    uint64_t source_bytes;  /* the encoded image's byte count */
    int32_t width, height;
    int32_t source_bits, source_channels;
    uint8_t source_float, source_srgb, pad[6];
    char source_description[128];
    char source_format[32];
} cache_header;
_Static_assert(sizeof(((cache_header *)0)->source_description) == sizeof(((sl_image *)0)->source_description),
               "cache header and sl_image disagree on source_description");
_Static_assert(sizeof(((cache_header *)0)->source_format) == sizeof(((sl_image *)0)->source_format),
               "cache header and sl_image disagree on source_format");

#define CACHE_KEEP 8 /* image files kept; the least recently used go first */

/* ---- the key ---------------------------------------------------------------------------- */

#define FNV_PRIME 0x100000001b3ull

/* Whole 8-byte words: xor the word in, multiply by the FNV-1a 64-bit prime, then fold the high bits
 * down (a multiply only carries upward, so without the fold the top bits of a word would never reach
 * the low bits of the result). */
static uint64_t hash_words(const unsigned char *p, size_t words, uint64_t h) {
    for (size_t i = 0; i < words; i++) {
        uint64_t w;
        memcpy(&w, p + i * 8, 8);
        h = (h ^ w) * FNV_PRIME;
        h ^= h >> 31;
    }
    return h;
}

static uint64_t hash_tail(const unsigned char *p, size_t n, uint64_t h) {
    for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * FNV_PRIME;
    return h;
}

static uint64_t hash_finish(uint64_t h, uint64_t bytes) {
    h = (h ^ bytes) * FNV_PRIME; /* the length: a zero tail is not the same as no tail */
    h ^= h >> 29;
    h *= FNV_PRIME;
    return h ^ (h >> 32);
}

/* The seed: the cache version, the OpenImageIO version the module was built against and the
 * name's extension (it picks the reader OpenImageIO tries first, so in principle the same bytes
 * could decode differently under another name). */
static uint64_t key_seed(const char *name) {
    uint64_t h = 0xcbf29ce484222325ull; /* FNV-1a offset basis */
    char buf[96], ext[16];
    sl_image_path_extension(name ? name : "", ext, sizeof ext);
    int n = snprintf(buf, sizeof buf, "v%u|oiio %s|%s", CACHE_VERSION, SL_OIIO_VERSION, ext);
    if (n < 0 || n >= (int)sizeof buf) n = (int)sizeof buf - 1;
    return hash_tail((const unsigned char *)buf, (size_t)n, h);
}

uint64_t sl_image_cache_hash(const void *data, size_t size, uint64_t seed) {
    const unsigned char *p = data;
    uint64_t h = hash_words(p, size / 8, seed);
    h = hash_tail(p + size / 8 * 8, size % 8, h);
    return hash_finish(h, size);
}

/* Reads fd to its end, hashing as it goes: blocks of a multiple of 8 bytes, so the words are those
 * of the whole file and the result equals sl_image_cache_hash over its bytes. */
static bool hash_fd(int fd, uint64_t expected, uint64_t seed, uint64_t *key, uint64_t *bytes) {
    /* 1 MiB, or the file's size rounded up to whole words when smaller (no page faults for nothing);
     * any multiple of 8 gives the same hash */
    size_t BLOCK = expected < (1u << 20) ? (size_t)(expected / 8 + 1) * 8 : (size_t)1 << 20;
    unsigned char *buf = malloc(BLOCK);
    if (!buf) return false;
    uint64_t h = seed, total = 0;
    for (;;) {
        size_t got = 0;
        while (got < BLOCK) { /* fill the block: a short read mid-file would misalign the words */
            ssize_t r = read(fd, buf + got, BLOCK - got);
            if (r < 0 && errno == EINTR) continue;
            if (r < 0) {
                free(buf);
                return false;
            }
            if (r == 0) break;
            got += (size_t)r;
        }
        total += got;
        if (got < BLOCK) { /* the end */
            h = hash_words(buf, got / 8, h);
            h = hash_tail(buf + got / 8 * 8, got % 8, h);
            break;
        }
        h = hash_words(buf, BLOCK / 8, h);
    }
    free(buf);
    *key = hash_finish(h, total);
    *bytes = total;
    return true;
}

/* ---- where ------------------------------------------------------------------------------- */

bool sl_image_cache_enabled(void) {
    const char *v = getenv("SHADELAB_IMAGE_CACHE");
    return !(v && !strcmp(v, "0"));
}

/* The directory (sdk cache.h), created when create. */
static bool cache_dir(char *out, size_t n, bool create) { return sl_cache_dir("images", out, n, create); }

static bool entry_path(const sl_image_cache_entry *e, char *out, size_t n) {
    char dir[3800];
    if (!cache_dir(dir, sizeof dir, false)) return false;
    int len = snprintf(out, n, "%s/img-%016llx.bin", dir, (unsigned long long)e->key);
    return len > 0 && (size_t)len < n;
}

/* ---- lookup -------------------------------------------------------------------------------- */

static bool read_full(int fd, void *dst, size_t n) {
    unsigned char *p = dst;
    while (n) {
        ssize_t r = read(fd, p, n);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) return false;
        p += r;
        n -= (size_t)r;
    }
    return true;
}

static bool has_nul(const char *s, size_t n) { return memchr(s, 0, n) != NULL; }

bool sl_image_cache_lookup(sl_image *img, const char *path, const void *data, size_t size,
                           sl_image_cache_entry *e) {
    memset(e, 0, sizeof *e);
    uint64_t seed = key_seed(path);
    if (data) {
        e->key = sl_image_cache_hash(data, size, seed);
        e->source_bytes = size;
    } else {
        int fd = open(path, O_RDONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
        if (fd < 0) return false;
        struct stat st;
        bool ok = fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && hash_fd(fd, (uint64_t)st.st_size, seed, &e->key, &e->source_bytes) &&
                  e->source_bytes == (uint64_t)st.st_size;
        close(fd);
        if (!ok) return false;
        e->file = true;
        e->dev = (uint64_t)st.st_dev, e->ino = (uint64_t)st.st_ino;
        e->mtime_s = (int64_t)st.st_mtim.tv_sec, e->mtime_ns = (int64_t)st.st_mtim.tv_nsec;
    }
    e->valid = true;

    char cpath[4096];
    if (!entry_path(e, cpath, sizeof cpath)) return false;
    int fd = open(cpath, O_RDONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return false;
    struct stat st;
    cache_header h;
    float *px = NULL;
    bool hit = false;
    if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && read_full(fd, &h, sizeof h) &&
        !memcmp(h.magic, CACHE_MAGIC, sizeof h.magic) && h.version == CACHE_VERSION &&
        h.header_bytes == sizeof h && h.key == e->key && h.source_bytes == e->source_bytes && h.width > 0 &&
        h.height > 0 && h.width <= SL_IMAGE_MAX_DIM && h.height <= SL_IMAGE_MAX_DIM &&
        (long long)h.width * h.height <= (long long)SL_IMAGE_MAX_PIXELS && h.source_bits >= 1 &&
        h.source_bits <= 32 && h.source_channels >= 1 && h.source_float <= 1 && h.source_srgb <= 1 &&
        has_nul(h.source_description, sizeof h.source_description) &&
        has_nul(h.source_format, sizeof h.source_format)) {
        size_t bytes = (size_t)h.width * (size_t)h.height * 4 * sizeof(float);
        if ((uint64_t)st.st_size == sizeof h + (uint64_t)bytes && (px = malloc(bytes)) && read_full(fd, px, bytes))
            hit = true;
    }
    close(fd);
    if (!hit) {
        free(px);
        return false;
    }
    utimensat(AT_FDCWD, cpath, NULL, 0); /* recently used: pruned last */
    img->width = h.width;
    img->height = h.height;
    img->channels = 4;
    img->pixels = px;
    img->source_bits = h.source_bits;
    img->source_float = h.source_float;
    img->source_srgb = h.source_srgb;
    img->source_channels = h.source_channels;
    memcpy(img->source_description, h.source_description, sizeof img->source_description);
    memcpy(img->source_format, h.source_format, sizeof img->source_format);
    return true;
}

/* ---- store --------------------------------------------------------------------------------- */

static bool write_full(int fd, const void *src, size_t n) {
    const unsigned char *p = src;
    while (n) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return false;
        p += w;
        n -= (size_t)w;
    }
    return true;
}

void sl_image_cache_store(const sl_image_cache_entry *e, const char *path, const sl_image *img) {
    if (!e->valid || !img->pixels || img->width <= 0 || img->height <= 0 || img->channels != 4) return;
    if (e->file) { /* the file changed while it was decoded: the pixels may not be those of the hashed bytes */
        struct stat st;
        if (stat(path, &st) != 0 || (uint64_t)st.st_dev != e->dev || (uint64_t)st.st_ino != e->ino ||
            (uint64_t)st.st_size != e->source_bytes || (int64_t)st.st_mtim.tv_sec != e->mtime_s ||
            (int64_t)st.st_mtim.tv_nsec != e->mtime_ns)
            return;
    }
    char dir[3800], cpath[4096], tmp[4200];
    if (!cache_dir(dir, sizeof dir, true) || !entry_path(e, cpath, sizeof cpath)) return;
    static atomic_uint counter;
    snprintf(tmp, sizeof tmp, "%s.tmp-%ld-%u", cpath, (long)getpid(), atomic_fetch_add(&counter, 1));
    int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) return;
    cache_header h;
    memset(&h, 0, sizeof h);
    memcpy(h.magic, CACHE_MAGIC, sizeof h.magic);
    h.version = CACHE_VERSION;
    h.header_bytes = sizeof h;
    h.key = e->key;
    h.source_bytes = e->source_bytes;
    h.width = img->width, h.height = img->height;
    h.source_bits = img->source_bits, h.source_channels = img->source_channels;
    h.source_float = img->source_float, h.source_srgb = img->source_srgb;
    memcpy(h.source_description, img->source_description, sizeof h.source_description);
    memcpy(h.source_format, img->source_format, sizeof h.source_format);
    h.source_description[sizeof h.source_description - 1] = 0;
    h.source_format[sizeof h.source_format - 1] = 0;
    size_t bytes = (size_t)img->width * (size_t)img->height * 4 * sizeof(float);
    bool ok = write_full(fd, &h, sizeof h) && write_full(fd, img->pixels, bytes);
    ok = close(fd) == 0 && ok;
    if (!ok || rename(tmp, cpath) != 0) {
        unlink(tmp);
        return;
    }
    sl_cache_prune(dir, "img-", CACHE_KEEP);
}
