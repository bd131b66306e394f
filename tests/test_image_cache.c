/* core/image/image_cache.c: files only OpenImageIO reads are kept decoded, keyed by their bytes.
 * With SHADELAB_CACHE pointed at a directory of this test's own:
 *  - a float TIFF (with NaN and Inf samples), a Radiance .hdr and a 1.2 MB TIFF (hashed in two
 *    blocks) load once through OIIO, which leaves exactly one cache file; blender-data's DWAB
 *    courtyard.exr (when installed) is decoded natively (the OpenEXR module) and leaves none; a child process
 *    (this executable re-run, so that no module is inherited) then loads each again, from the file and
 *    from memory, and must get every float bit for bit and every source_* field of an OIIO-forced
 *    decode (SHADELAB_IMAGE_DECODER=oiio) — with OIIO's NaN/Inf message — while /proc/self/maps shows
 *    no shadelab-oiio.so until the forced decode;
 *  - a cache file whose pixels were changed is what the next load returns (the cache is read); a
 *    source file with one byte changed (same name, same size) misses and decodes its new content;
 *  - truncated, garbage, over-the-limits and wrong-key cache files are misses with the right pixels;
 *    SHADELAB_IMAGE_CACHE=0 and SHADELAB_IMAGE_DECODER=oiio write nothing; a cache directory that
 *    cannot be made only means no cache;
 *  - a damaged JPEG OIIO recovers with a warning is never cached (the warning comes at every load);
 *  - at most 8 files are kept. */
#define SL_IMAGE_INTERNAL
#include "image/image.h"
#include "log.h"
#include "test_tmp.h"

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#define COURTYARD "/usr/share/blender/datafiles/studiolights/world/courtyard.exr"

static char cache_images[1024]; /* $SHADELAB_CACHE/images */

/* The img-*.bin files in the cache: how many, and the name of the last one seen. */
static int cache_files(char *last, size_t n) {
    int count = 0;
    DIR *d = opendir(cache_images);
    for (struct dirent *e; d && (e = readdir(d));) {
        size_t l = strlen(e->d_name);
        if (strncmp(e->d_name, "img-", 4) || l < 8 || strcmp(e->d_name + l - 4, ".bin")) continue;
        count++;
        if (last) snprintf(last, n, "%s/%s", cache_images, e->d_name);
    }
    if (d) closedir(d);
    return count;
}

static void clear_cache(void) { sl_test_remove_tree_(cache_images); }

static void force_oiio(bool on) {
    if (on) setenv("SHADELAB_IMAGE_DECODER", "oiio", 1);
    else unsetenv("SHADELAB_IMAGE_DECODER");
}

static bool load(sl_image *img, const char *path) {
    char err[1024] = "";
    bool ok = sl_image_load(img, path, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    return ok;
}

static bool load_reference(sl_image *img, const char *path) {
    force_oiio(true);
    bool ok = load(img, path);
    force_oiio(false);
    return ok;
}

/* Same size, every float's bits and every source_* field. */
static bool same_image(const sl_image *a, const sl_image *b, const char *what) {
    bool same = a->width == b->width && a->height == b->height && a->channels == b->channels && a->pixels &&
                b->pixels && !memcmp(a->pixels, b->pixels, (size_t)a->width * a->height * 4 * sizeof(float)) &&
                a->source_bits == b->source_bits && a->source_float == b->source_float &&
                a->source_srgb == b->source_srgb && a->source_channels == b->source_channels &&
                !strcmp(a->source_description, b->source_description) && !strcmp(a->source_format, b->source_format);
    CHECK_MSG(same, "%s: differs from OpenImageIO's decode (%dx%d %s vs %dx%d %s)", what, a->width, a->height,
              a->source_format, b->width, b->height, b->source_format);
    return same;
}

static bool oiio_mapped(void) { return sl_test_mapped("shadelab-oiio"); }

/* ---- fixtures ---------------------------------------------------------------------------- */

static float *pattern(int w, int h, float salt) {
    float *p = malloc((size_t)w * h * 16);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float *q = p + ((size_t)y * w + x) * 4;
            q[0] = (float)x / (float)w * 3.0f + salt;
            q[1] = (float)y / (float)h + 0.25f;
            q[2] = 0.1f + 0.01f * (float)((x * 7 + y * 13) % 17);
            q[3] = 0.5f + 0.5f * (float)(x & 1);
        }
    return p;
}

/* A float RGBA TIFF (only OIIO reads TIFF) with a NaN and an Inf sample, through the module's writer. */
static void write_tiff(const char *path, float salt) {
    int w = 24, h = 16;
    float *p = pattern(w, h, salt);
    p[5] = NAN;
    p[42] = INFINITY;
    char err[1024] = "";
    CHECK_MSG(sl_oiio_write(path, "tiff", NULL, p, w, h, 4, "float", 0, err, sizeof err), "%s", err);
    free(p);
}

/* Over 1 MiB of noise (no compression shrinks it), so that hashing the file takes several blocks: its
 * key must equal the one of the same bytes in memory. */
static void write_big_tiff(const char *path) {
    int w = 300, h = 290;
    float *p = malloc((size_t)w * h * 16);
    uint32_t x = 12345;
    for (size_t i = 0; i < (size_t)w * h * 4; i++) {
        x ^= x << 13, x ^= x >> 17, x ^= x << 5;
        p[i] = (float)(x >> 8) / 16777216.0f;
    }
    char err[1024] = "";
    CHECK_MSG(sl_oiio_write(path, "tiff", NULL, p, w, h, 4, "float", 0, err, sizeof err), "%s", err);
    free(p);
}

static void write_hdr(const char *path, float salt) {
    int w = 20, h = 10;
    float *p = pattern(w, h, salt);
    char err[1024] = "";
    CHECK_MSG(sl_image_write(path, p, w, h, false, err, sizeof err), "%s", err);
    free(p);
}

/* A Radiance file written here without run-length encoding, so that each pixel is 4 known bytes at
 * the end of the file (OIIO's writer run-length encodes scanlines, where one changed byte could be a
 * run count). */
static void write_flat_hdr(const char *path, int w, int h) {
    char head[128];
    int hl = snprintf(head, sizeof head, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n", h, w);
    size_t n = (size_t)hl + (size_t)w * h * 4;
    unsigned char *d = malloc(n);
    memcpy(d, head, (size_t)hl);
    for (int i = 0; i < w * h; i++) {
        unsigned char *q = d + hl + (size_t)i * 4;
        q[0] = (unsigned char)(64 + i % 128), q[1] = (unsigned char)(200 - i % 100), q[2] = 150, q[3] = 129;
    }
    sl_test_write_file(path, d, n);
    free(d);
}

/* ---- the child: a fresh process, so that a hit shows in /proc/self/maps ------------------- */

static int child_hits(int argc, char **argv) {
    enum { MAX = 4 };
    int count = argc - 2 < MAX ? argc - 2 : MAX;
    sl_image img[MAX], mem[MAX];
    bool ok[MAX], mok[MAX];
    /* every file first, from the file and from memory (the same bytes under the same name: the
     * same key), before anything may open the module */
    for (int i = 0; i < count; i++) {
        const char *path = argv[i + 2];
        char logbuf[4096] = "", err[1024] = "";
        size_t n = 0;
        unsigned char *bytes = sl_test_read_file(path, &n);
        sl_log_capture(logbuf, sizeof logbuf);
        ok[i] = load(&img[i], path);
        sl_log_capture(NULL, 0);
        mok[i] = bytes && sl_image_load_memory(&mem[i], bytes, n, path, err, sizeof err);
        CHECK_MSG(mok[i], "%s (memory): %s", path, err);
        free(bytes);
        if (strstr(path, "float.tif")) CHECK_CONTAINS(logbuf, "2 samples are NaN or Inf");
        CHECK_MSG(!oiio_mapped(), "%s: shadelab-oiio.so was opened to load a cached image", path);
    }
    for (int i = 0; i < count; i++) {
        sl_image ref;
        if (load_reference(&ref, argv[i + 2])) {
            if (ok[i]) same_image(&img[i], &ref, argv[i + 2]);
            if (mok[i]) same_image(&mem[i], &ref, "from memory");
            sl_image_free(&ref);
        }
        if (ok[i]) sl_image_free(&img[i]);
        if (mok[i]) sl_image_free(&mem[i]);
    }
    CHECK_MSG(count == 0 || oiio_mapped(), "the forced OIIO decodes did not open the module?");
    printf("cache-hit child: %d files, from file and memory, without shadelab-oiio.so\n", count);
    return check_result();
}

/* ---- the cases ------------------------------------------------------------------------------ */

/* Loads each file once (a miss: one new cache file each, the same image as OIIO's), then re-runs this
 * executable on them, where every load must hit. */
static void test_hits(void) {
    clear_cache();
    const char *files[4] = {sl_test_path("float.tif"), sl_test_path("sky.hdr"), sl_test_path("big.tif"), NULL};
    write_tiff(files[0], 0.0f);
    write_hdr(files[1], 0.0f);
    write_big_tiff(files[2]);
    struct stat st;
    CHECK_MSG(stat(files[2], &st) == 0 && st.st_size > (1 << 20), "big.tif: %lld bytes",
              (long long)st.st_size);
    int expected = 0;
    /* a file the native decoders read is not cached (it never needed the module) */
    if (access(COURTYARD, R_OK) == 0) {
        sl_image img;
        if (load(&img, COURTYARD)) sl_image_free(&img);
        CHECK_MSG(cache_files(NULL, 0) == 0, "%s (decoded natively) left a cache file", COURTYARD);
    } else {
        printf("note: %s not installed (Debian blender-data): its case is skipped\n", COURTYARD);
    }
    for (int i = 0; i < 4 && files[i]; i++) {
        sl_image ref, img;
        if (!load_reference(&ref, files[i])) continue;
        CHECK_MSG(cache_files(NULL, 0) == expected, "a forced OIIO decode wrote a cache file (%s)", files[i]);
        char logbuf[4096] = "";
        sl_log_capture(logbuf, sizeof logbuf);
        bool ok = load(&img, files[i]);
        sl_log_capture(NULL, 0);
        if (strstr(files[i], "float.tif")) CHECK_CONTAINS(logbuf, "2 samples are NaN or Inf");
        if (ok) same_image(&img, &ref, files[i]);
        expected++;
        CHECK_MSG(cache_files(NULL, 0) == expected, "%s: %d cache files, expected %d", files[i], cache_files(NULL, 0),
                  expected);
        sl_image_free(&img);
        sl_image_free(&ref);
    }
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        char *args[7] = {"test_image_cache", "--hit-child", (char *)files[0], (char *)files[1], (char *)files[2],
                         (char *)files[3], NULL};
        execv("/proc/self/exe", args);
        _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 0, "the cache-hit child failed (status %d)", status);
}

/* The cache file's pixels changed, header kept: the next load returns them. Then the source changed
 * (one byte, same name and size): a miss that decodes the new content. */
static void test_tamper(void) {
    clear_cache();
    const char *path = sl_test_path("tamper.hdr");
    write_flat_hdr(path, 20, 10);
    sl_image img, ref;
    if (!load(&img, path)) return;
    sl_image_free(&img);
    char entry[2048] = "";
    CHECK(cache_files(entry, sizeof entry) == 1);
    size_t n = 0;
    unsigned char *d = sl_test_read_file(entry, &n);
    size_t pixel_bytes = 20 * 10 * 4 * sizeof(float);
    CHECK_MSG(d && n > pixel_bytes, "cache file %s: %zu bytes", entry, n);
    if (!d || n <= pixel_bytes) return;
    float marker = 12345.5f;
    memcpy(d + n - pixel_bytes, &marker, sizeof marker); /* pixel 0, red */
    sl_test_write_file(entry, d, n);
    free(d);
    if (load(&img, path)) {
        CHECK_MSG(img.pixels[0] == marker, "the tampered cache file was not read (red %g)", img.pixels[0]);
        sl_image_free(&img);
    }

    /* the source: the same size, one byte of pixel data changed (the last pixel's green mantissa) */
    sl_image before;
    if (!load_reference(&before, path)) return;
    unsigned char *src = sl_test_read_file(path, &n);
    CHECK(src && n > 16);
    if (!src || n <= 16) return;
    src[n - 3] ^= 0x10;
    sl_test_write_file(path, src, n);
    free(src);
    if (load_reference(&ref, path) && load(&img, path)) {
        same_image(&img, &ref, "changed source");
        CHECK(img.pixels[0] != marker);
        size_t last_green = (size_t)(20 * 10 - 1) * 4 + 1;
        CHECK_MSG(img.pixels[last_green] != before.pixels[last_green], "the changed byte changed no pixel");
        sl_image_free(&img);
        sl_image_free(&ref);
    }
    sl_image_free(&before);
    CHECK_MSG(cache_files(NULL, 0) == 2, "the changed source left %d cache files, expected 2", cache_files(NULL, 0));
}

/* Broken cache files are misses: the right pixels, no crash (and the entry written again). */
static void test_broken_entries(void) {
    clear_cache();
    const char *path = sl_test_path("broken.tif");
    write_tiff(path, 0.5f);
    sl_image ref, img;
    if (!load_reference(&ref, path) || !load(&img, path)) return;
    sl_image_free(&img);
    char entry[2048] = "";
    CHECK(cache_files(entry, sizeof entry) == 1);
    size_t n = 0;
    unsigned char *good = sl_test_read_file(entry, &n);
    CHECK(good && n > 256);
    if (!good || n <= 256) return;
    unsigned char *bad = malloc(n);
    static const char *const kinds[] = {"truncated in the pixels", "truncated in the header", "empty",
                                        "garbage",  "over the limits",        "wrong key",
                                        "one byte longer"};
    for (int k = 0; k < 7; k++) {
        memcpy(bad, good, n);
        size_t len = n;
        if (k == 0) len = n - 100;
        if (k == 1) len = 40;
        if (k == 2) len = 0;
        if (k == 3)
            for (size_t i = 0; i < n; i++) bad[i] = (unsigned char)(i * 131 + 7);
        if (k == 4) { /* width and height 65536 (after magic 8, version 4, header bytes 4, key 8, byte count 8) */
            int32_t big = 65536;
            memcpy(bad + 32, &big, 4);
            memcpy(bad + 36, &big, 4);
        }
        if (k == 5) bad[16] ^= 1; /* the key's low byte */
        FILE *f = fopen(entry, "wb");
        CHECK(f != NULL);
        if (!f) break;
        if (len) fwrite(bad, 1, len, f);
        if (k == 6) fputc(0, f);
        fclose(f);
        if (load(&img, path)) {
            same_image(&img, &ref, kinds[k]);
            sl_image_free(&img);
        }
        size_t m = 0;
        unsigned char *now = sl_test_read_file(entry, &m);
        CHECK_MSG(now && m == n && !memcmp(now, good, n), "%s: the entry was not written again", kinds[k]);
        free(now);
    }
    free(bad);
    free(good);
    sl_image_free(&ref);

    /* off: nothing written; a forced OIIO decode writes nothing either */
    clear_cache();
    setenv("SHADELAB_IMAGE_CACHE", "0", 1);
    if (load(&img, path)) sl_image_free(&img);
    unsetenv("SHADELAB_IMAGE_CACHE");
    CHECK_MSG(cache_files(NULL, 0) == 0, "SHADELAB_IMAGE_CACHE=0 wrote a cache file");
    if (load_reference(&img, path)) sl_image_free(&img);
    CHECK_MSG(cache_files(NULL, 0) == 0, "SHADELAB_IMAGE_DECODER=oiio wrote a cache file");

    /* a cache directory that cannot be made (its parent is a file): loads as usual */
    const char *saved = getenv("SHADELAB_CACHE");
    char keep[1024];
    snprintf(keep, sizeof keep, "%s", saved);
    sl_test_write_file(sl_test_path("not_a_dir"), "x", 1);
    char below[1100];
    snprintf(below, sizeof below, "%s/sub", sl_test_path("not_a_dir"));
    setenv("SHADELAB_CACHE", below, 1);
    if (load(&img, path)) sl_image_free(&img);
    setenv("SHADELAB_CACHE", keep, 1);
}

/* A truncated JPEG: the native decoder leaves it to OIIO, which fills the rest and warns. Not cached,
 * so the warning is given again at the next load. */
static void test_damaged(void) {
    clear_cache();
    int w = 64, h = 64;
    float *p = pattern(w, h, 0.0f);
    char err[1024] = "";
    CHECK_MSG(sl_image_write(sl_test_path("whole.jpg"), p, w, h, true, err, sizeof err), "%s", err);
    free(p);
    size_t n = 0;
    unsigned char *d = sl_test_read_file(sl_test_path("whole.jpg"), &n);
    CHECK(d && n > 100);
    if (!d) return;
    const char *path = sl_test_path("damaged.jpg");
    sl_test_write_file(path, d, n * 6 / 10);
    free(d);
    for (int round = 0; round < 2; round++) {
        int before = sl_log_count(SL_LOG_WARN);
        sl_image img;
        if (load(&img, path)) sl_image_free(&img);
        CHECK_MSG(sl_log_count(SL_LOG_WARN) == before + 1, "load %d of a truncated JPEG: %d warnings, expected 1",
                  round + 1, sl_log_count(SL_LOG_WARN) - before);
        CHECK_MSG(cache_files(NULL, 0) == 0, "a damaged image was cached");
    }
}

/* The cap: ten different files leave the eight most recently used. */
static void test_cap(void) {
    clear_cache();
    char first[2048] = "";
    for (int i = 0; i < 10; i++) {
        char name[64];
        snprintf(name, sizeof name, "cap%d.hdr", i);
        write_hdr(sl_test_path(name), (float)i);
        sl_image img;
        if (load(&img, sl_test_path(name))) sl_image_free(&img);
        if (i == 0) cache_files(first, sizeof first);
        usleep(20000); /* distinct mtimes on coarse file systems */
    }
    CHECK_MSG(cache_files(NULL, 0) == 8, "%d cache files after 10 images, expected 8", cache_files(NULL, 0));
    CHECK_MSG(access(first, F_OK) != 0, "the oldest entry %s was kept", first);
}

/* The key's hash: the same for the same bytes, another for one bit changed anywhere (a word, the tail),
 * another for the same bytes and a zero byte more. */
static void test_hash(void) {
    unsigned char b[67];
    for (size_t i = 0; i < sizeof b; i++) b[i] = (unsigned char)(i * 37 + 1);
    uint64_t k = sl_image_cache_hash(b, sizeof b, 7);
    CHECK(k == sl_image_cache_hash(b, sizeof b, 7));
    CHECK(k != sl_image_cache_hash(b, sizeof b, 8));
    for (size_t i = 0; i < sizeof b; i++)
        for (int bit = 0; bit < 8; bit++) {
            b[i] ^= (unsigned char)(1u << bit);
            uint64_t k2 = sl_image_cache_hash(b, sizeof b, 7);
            b[i] ^= (unsigned char)(1u << bit);
            CHECK_MSG(k2 != k, "flipping bit %d of byte %zu left the hash unchanged", bit, i);
        }
    unsigned char z[16] = {0};
    CHECK(sl_image_cache_hash(z, 15, 7) != sl_image_cache_hash(z, 16, 7));
    CHECK(sl_image_cache_hash(z, 8, 7) != sl_image_cache_hash(z, 0, 7));
}

int main(int argc, char **argv) {
    if (argc >= 2 && !strcmp(argv[1], "--hit-child")) return child_hits(argc, argv);
    snprintf(cache_images, sizeof cache_images, "%s/cache/images", sl_test_dir());
    setenv("SHADELAB_CACHE", sl_test_path("cache"), 1);
    unsetenv("SHADELAB_IMAGE_CACHE");
    force_oiio(false);
    test_hash();
    test_hits();
    test_tamper();
    test_broken_entries();
    test_damaged();
    test_cap();
    return check_result();
}
