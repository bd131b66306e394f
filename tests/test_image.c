/* core/image tests: sRGB transfer functions at known points, write→load round trips per
 * format, files written here by hand (16-bit, grey, gAMA 1.0, absurd dimensions) so the
 * loader is not only checked against its own writer, comparison metrics on image pairs with
 * closed-form answers, procedural textures, and every bad-input path's message.
 * Fixtures are written at run time into a mkdtemp directory that is removed at the end. */
#include "check.h"
#include "image/image.h"
#include "log.h"

#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Sanitizer builds (SL_SANITIZE): OpenImageIO 2.4's PNG reader leaks a std::string when libpng
 * longjmps out of PNGInput::PngReadCallback on a truncated file (the destructor is skipped);
 * the leak is theirs and only on that error path, so LeakSanitizer is told to ignore exactly
 * that frame. Both hooks are unused in normal builds. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void) { return "leak:PngReadCallback\n"; }
/* libstdc++ has no frame pointers: without slow unwinding the leak's stack stops there and
 * the suppression above cannot see the OIIO frame. */
const char *__asan_default_options(void);
const char *__asan_default_options(void) { return "fast_unwind_on_malloc=0"; }

static char tmpdir[256];

static const char *tmp_path(const char *name) {
    static char bufs[4][512];
    static int next;
    char *b = bufs[next++ % 4];
    snprintf(b, 512, "%s/%s", tmpdir, name);
    return b;
}

static void write_bytes(const char *path, const void *data, size_t n) {
    FILE *f = fopen(path, "wb");
    if (!f) { perror(path); exit(2); }
    if (n) fwrite(data, 1, n, f);
    fclose(f);
}

static long file_size(const char *path) {
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/* ---- a minimal PNG writer (stored deflate blocks), independent of OpenImageIO ----------- */

static uint32_t crc_table[256];
static void crc_init(void) {
    for (uint32_t n = 0; n < 256; n++) {
        uint32_t c = n;
        for (int k = 0; k < 8; k++) c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
        crc_table[n] = c;
    }
}
static uint32_t crc(const uint8_t *p, size_t n) {
    uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; i++) c = crc_table[(c ^ p[i]) & 0xff] ^ (c >> 8);
    return c ^ 0xffffffffu;
}
static void put32(uint8_t *p, uint32_t v) { p[0] = v >> 24, p[1] = v >> 16, p[2] = v >> 8, p[3] = v; }
static void chunk(FILE *f, const char *type, const uint8_t *data, uint32_t len) {
    uint8_t *buf = malloc(len + 8);
    put32(buf, len);
    memcpy(buf + 4, type, 4);
    if (len) memcpy(buf + 8, data, len);
    uint8_t c[4];
    put32(c, crc(buf + 4, len + 4));
    fwrite(buf, 1, len + 8, f);
    fwrite(c, 1, 4, f);
    free(buf);
}
/* rows: h rows of row_bytes raw sample bytes (big-endian for 16-bit); gamma_1e5 > 0 adds gAMA.
 * idat_limit > 0 truncates the zlib stream (for the absurd-size header test). */
static void write_png(const char *path, uint32_t w, uint32_t h, int depth, int colour_type,
                      const uint8_t *rows, size_t row_bytes, uint32_t gamma_1e5, size_t idat_limit) {
    FILE *f = fopen(path, "wb");
    if (!f) { perror(path); exit(2); }
    static const uint8_t sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    fwrite(sig, 1, 8, f);
    uint8_t ihdr[13];
    put32(ihdr, w), put32(ihdr + 4, h);
    ihdr[8] = (uint8_t)depth, ihdr[9] = (uint8_t)colour_type, ihdr[10] = ihdr[11] = ihdr[12] = 0;
    chunk(f, "IHDR", ihdr, 13);
    if (gamma_1e5) {
        uint8_t g[4];
        put32(g, gamma_1e5);
        chunk(f, "gAMA", g, 4);
    }
    size_t raw_n = idat_limit ? 0 : (row_bytes + 1) * h;
    uint8_t *raw = malloc(raw_n + 1);
    for (size_t y = 0; y < (idat_limit ? 0 : h); y++) {
        raw[y * (row_bytes + 1)] = 0; /* filter: none */
        memcpy(raw + y * (row_bytes + 1) + 1, rows + y * row_bytes, row_bytes);
    }
    size_t blocks = raw_n / 65535 + 1;
    uint8_t *z = malloc(2 + raw_n + blocks * 5 + 4);
    size_t zn = 0;
    z[zn++] = 0x78, z[zn++] = 0x01;
    uint32_t s1 = 1, s2 = 0;
    for (size_t off = 0;;) {
        size_t n = raw_n - off > 65535 ? 65535 : raw_n - off;
        z[zn++] = off + n == raw_n;
        z[zn++] = n & 0xff, z[zn++] = n >> 8, z[zn++] = ~n & 0xff, z[zn++] = (~n >> 8) & 0xff;
        memcpy(z + zn, raw + off, n);
        for (size_t i = 0; i < n; i++) s1 = (s1 + raw[off + i]) % 65521, s2 = (s2 + s1) % 65521;
        zn += n, off += n;
        if (off == raw_n) break;
    }
    put32(z + zn, (s2 << 16) | s1), zn += 4;
    chunk(f, "IDAT", z, (uint32_t)(idat_limit && idat_limit < zn ? idat_limit : zn));
    chunk(f, "IEND", NULL, 0);
    fclose(f);
    free(raw);
    free(z);
}

static bool same_colour(const float *p, float r, float g, float b, float a) {
    return p[0] == r && p[1] == g && p[2] == b && p[3] == a;
}

/* ---- sRGB -------------------------------------------------------------------------------- */

static void test_srgb(void) {
    CHECK_NEAR(sl_srgb_encode(0.0f), 0.0, 0.0);
    CHECK_NEAR(sl_srgb_encode(1.0f), 1.0, 0.0);
    CHECK_NEAR(sl_srgb_encode(0.0031308f), 12.92 * 0.0031308, 1e-7); /* knee: 0.0404500 */
    CHECK_NEAR(sl_srgb_encode(0.5f), 0.735357, 1e-6);
    CHECK_NEAR(sl_srgb_encode(0.001f), 0.01292, 1e-7);                /* linear segment */
    CHECK_NEAR(sl_srgb_encode(0.18f), 0.4613561, 1e-6);               /* mid grey */
    CHECK_NEAR(sl_srgb_decode(0.0f), 0.0, 0.0);
    CHECK_NEAR(sl_srgb_decode(1.0f), 1.0, 0.0);
    CHECK_NEAR(sl_srgb_decode(0.04045f), 0.04045 / 12.92, 1e-8);
    CHECK_NEAR(sl_srgb_decode(0.735357f), 0.5, 1e-6);
    CHECK_NEAR(sl_srgb_decode(0.5f), 0.2140411, 1e-6);
    CHECK_NEAR(sl_srgb_decode(128.0f / 255.0f), 0.2158605, 1e-6);
    /* the two pieces meet at the knee (within the standard's own 1e-7 mismatch) */
    CHECK_NEAR(sl_srgb_encode(0.00313079f), sl_srgb_encode(0.00313081f), 1e-6);
    double worst = 0, worst_byte = 0;
    for (int i = 0; i <= 1000; i++) {
        float x = i / 1000.0f;
        double e = fabs(sl_srgb_decode(sl_srgb_encode(x)) - x);
        if (e > worst) worst = e;
    }
    CHECK_NEAR(worst, 0.0, 2e-7);
    for (int k = 0; k <= 255; k++) { /* every 8-bit code survives decode → encode */
        double e = fabs(sl_srgb_encode(sl_srgb_decode(k / 255.0f)) * 255.0 - k);
        if (e > worst_byte) worst_byte = e;
    }
    CHECK_NEAR(worst_byte, 0.0, 1e-4);
    /* monotonic */
    bool mono = true;
    for (int i = 1; i <= 4096; i++) mono &= sl_srgb_encode(i / 4096.0f) > sl_srgb_encode((i - 1) / 4096.0f);
    CHECK(mono);
    /* non-finite and out-of-range inputs give finite, clamped outputs */
    CHECK(sl_srgb_encode(NAN) == 0.0f);
    CHECK(sl_srgb_encode(INFINITY) == 1.0f);
    CHECK(sl_srgb_encode(-INFINITY) == 0.0f);
    CHECK(sl_srgb_encode(-0.5f) == 0.0f);
    CHECK(sl_srgb_encode(7.0f) == 1.0f);
    CHECK(sl_srgb_decode(NAN) == 0.0f);
    CHECK(sl_srgb_decode(INFINITY) == 1.0f);
    CHECK(sl_srgb_decode(-1.0f) == 0.0f);
}

/* ---- PNG / JPEG / EXR / HDR round trips ---------------------------------------------------- */

static float *make_test_pattern(int w, int h) {
    float *p = malloc((size_t)w * h * 4 * sizeof(float));
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float *d = p + ((size_t)y * w + x) * 4;
            d[0] = (float)x / (w - 1);                        /* 0..1 */
            d[1] = (float)y / (h - 1) * 1.5f - 0.25f;         /* goes out of [0,1] both ways */
            d[2] = 0.001f * (x + y * w);                      /* small values: linear segment */
            d[3] = (float)(x + y) / (w + h - 2);
        }
    return p;
}

static double clamp01(double v) { return v > 0 ? (v < 1 ? v : 1) : 0; }

static void test_png_roundtrip(void) {
    const int w = 16, h = 8;
    float *src = make_test_pattern(w, h);
    src[5 * 4 + 2] = NAN; /* a NaN is written as 0 */
    char err[512] = "";
    const char *path = tmp_path("pattern.png");
    CHECK_MSG(sl_image_write(path, src, w, h, false, err, sizeof err), "%s", err);
    sl_image img;
    CHECK_MSG(sl_image_load(&img, path, err, sizeof err), "%s", err);
    CHECK(img.width == w && img.height == h && img.channels == 4);
    CHECK(img.source_bits == 8);
    CHECK(img.source_srgb);
    CHECK(!img.source_float);
    if (img.pixels) {
        int bad_tol = 0, bad_exact = 0, bad_alpha = 0;
        for (int i = 0; i < w * h; i++)
            for (int c = 0; c < 4; c++) {
                double v = src[i * 4 + c];
                if (isnan(v)) v = 0;
                double enc = c == 3 ? clamp01(v) : sl_srgb_encode((float)v);
                double got = img.pixels[i * 4 + c];
                if (c < 3 && fabs(got - enc) > 0.5 / 255 + 1e-6) bad_tol++;
                if (fabs(got * 255.0 - floor(enc * 255.0 + 0.5)) > 1e-3) (*(c < 3 ? &bad_exact : &bad_alpha))++;
            }
        CHECK_MSG(bad_tol == 0, "%d values off by more than 0.5/255 in encoded space", bad_tol);
        CHECK_MSG(bad_exact == 0, "%d values not rounded to the nearest 8-bit code", bad_exact);
        CHECK_MSG(bad_alpha == 0, "%d alpha values not stored linear, rounded", bad_alpha);
        /* row 0 = top: the green ramp starts (clamped) at 0 in the first row */
        CHECK_NEAR(img.pixels[1], 0.0, 0.0);
        CHECK_NEAR(img.pixels[((size_t)(h - 1) * w) * 4 + 1], 1.0, 0.0);
        CHECK_NEAR(img.pixels[5 * 4 + 2], 0.0, 0.0);
        /* decoding gives back the linear value to within 8-bit quantisation */
        sl_image_srgb_to_linear(&img);
        CHECK_NEAR(img.pixels[(3 * w + 7) * 4 + 0], src[(3 * w + 7) * 4 + 0], 0.004);
        CHECK_NEAR(img.pixels[(3 * w + 7) * 4 + 3], src[(3 * w + 7) * 4 + 3], 0.5 / 255 + 1e-6);
        CHECK(img.source_srgb); /* describes the file, unchanged */
    }
    sl_image_free(&img);
    CHECK(img.pixels == NULL);

    /* display_encoded: values are written as they are, rounded to nearest */
    float enc[4 * 4] = {0.5f, 0.2f, 1.0f, 1.0f,   0.0f, 2.0f, -1.0f, 0.0f,
                        0.501f, 0.499f, 0.003f, 0.5f,   10.0f / 255, 10.4f / 255, 10.6f / 255, 1.0f};
    path = tmp_path("encoded.png");
    CHECK_MSG(sl_image_write(path, enc, 2, 2, true, err, sizeof err), "%s", err);
    static const int want[16] = {128, 51, 255, 255, 0, 255, 0, 0, 128, 127, 1, 128, 10, 10, 11, 255};
    if (sl_image_load(&img, path, err, sizeof err)) {
        int bad = 0;
        for (int i = 0; i < 16; i++) bad += fabs(img.pixels[i] * 255.0 - want[i]) > 1e-3;
        CHECK_MSG(bad == 0, "%d display-encoded values were not written as round(v*255)", bad);
        sl_image_free(&img);
    } else CHECK_MSG(false, "%s", err);

    /* overwrite an existing file; no temporary files are left behind */
    CHECK_MSG(sl_image_write(path, enc, 2, 2, true, err, sizeof err), "%s", err);
    DIR *d = opendir(tmpdir);
    int leftovers = 0;
    for (struct dirent *e; d && (e = readdir(d));) leftovers += strstr(e->d_name, ".tmp-") != NULL;
    if (d) closedir(d);
    CHECK(leftovers == 0);
    free(src);
}

static void test_exr_roundtrip(void) {
    const int w = 8, h = 4;
    float *src = make_test_pattern(w, h);
    /* exactly representable in half */
    static const float exact[] = {0.0f, 0.5f, -2.0f, 1000.0f, 65504.0f, 1.0f / 1024, 0.25f, -0.125f};
    for (int i = 0; i < 8; i++) src[i] = exact[i];
    src[8] = 3.14159265f;    /* rounds to the nearest half: relative error ≤ 2^-11 */
    src[9] = 1e6f;           /* beyond half's range → +Inf */
    src[10] = INFINITY;
    src[11] = NAN;           /* an alpha channel: kept as is */
    src[12] = 1e-5f;         /* subnormal half: absolute error ≤ 2^-25 */
    char err[512] = "";
    const char *path = tmp_path("pattern.exr");
    CHECK_MSG(sl_image_write(path, src, w, h, false, err, sizeof err), "%s", err);
    sl_image img;
    char log[2048];
    sl_log_capture(log, sizeof log);
    CHECK_MSG(sl_image_load(&img, path, err, sizeof err), "%s", err);
    sl_log_capture(NULL, 0);
    CHECK_CONTAINS(log, "pattern.exr: 3 samples are NaN or Inf"); /* 1e6→Inf, Inf, NaN */
    CHECK(img.width == w && img.height == h);
    CHECK(img.source_bits == 16);
    CHECK(img.source_float);
    CHECK(!img.source_srgb);
    if (img.pixels) {
        for (int i = 0; i < 8; i++) CHECK_NEAR(img.pixels[i], exact[i], 0.0);
        CHECK_NEAR(img.pixels[8], 3.140625, 0.0);
        CHECK(isinf(img.pixels[9]) && img.pixels[9] > 0);
        CHECK(isinf(img.pixels[10]) && img.pixels[10] > 0);
        CHECK(isnan(img.pixels[11]));
        CHECK_NEAR(img.pixels[12], 1e-5, pow(2, -25));
        int bad = 0;
        for (int i = 16; i < w * h * 4; i++) {
            double v = src[i], got = img.pixels[i];
            double tol = fabs(v) >= pow(2, -14) ? fabs(v) * pow(2, -11) : pow(2, -25);
            bad += fabs(got - v) > tol;
        }
        CHECK_MSG(bad == 0, "%d values differ by more than half-float rounding", bad);
    }
    sl_image_free(&img);
    free(src);
}

static void test_hdr_jpg(void) {
    const int w = 8, h = 8;
    float *src = malloc(w * h * 4 * sizeof(float));
    for (int i = 0; i < w * h; i++) {
        src[i * 4 + 0] = 0.5f;
        src[i * 4 + 1] = 2.0f + i;  /* HDR keeps values above 1 */
        src[i * 4 + 2] = 0.01f;
        src[i * 4 + 3] = 0.3f;      /* dropped: both formats are RGB */
    }
    char err[512] = "";
    sl_image img;
    const char *path = tmp_path("pattern.hdr");
    CHECK_MSG(sl_image_write(path, src, w, h, false, err, sizeof err), "%s", err);
    if (sl_image_load(&img, path, err, sizeof err)) {
        CHECK(!img.source_srgb && img.source_float && img.source_bits == 32);
        /* RGBE: 8-bit mantissas under one shared exponent, so the quantum is set by the
         * pixel's largest component m: error < m/128 (0.01 next to 2.0 may become 0) */
        int bad = 0;
        for (int p = 0; p < w * h; p++) {
            const float *s = src + p * 4;
            double m = fmax(s[0], fmax(s[1], s[2]));
            for (int c = 0; c < 3; c++) bad += fabs(img.pixels[p * 4 + c] - s[c]) > m / 128;
            bad += img.pixels[p * 4 + 3] != 1.0f;
        }
        CHECK_MSG(bad == 0, "%d HDR values differ by more than RGBE precision", bad);
        CHECK_NEAR(img.pixels[1], 2.0, 0.0);    /* powers of two are exact */
        CHECK_NEAR(img.pixels[0], 0.5, 0.0);
        sl_image_free(&img);
    } else CHECK_MSG(false, "%s", err);

    path = tmp_path("pattern.JPG"); /* extension is case-insensitive */
    CHECK_MSG(sl_image_write(path, src, w, h, false, err, sizeof err), "%s", err);
    if (sl_image_load(&img, path, err, sizeof err)) {
        CHECK(img.source_srgb && !img.source_float && img.source_bits == 8);
        /* a flat colour survives JPEG to within 2 codes; green clamps to 1, alpha becomes 1 */
        CHECK_NEAR(img.pixels[0], sl_srgb_encode(0.5f), 2.0 / 255);
        CHECK_NEAR(img.pixels[1], 1.0, 2.0 / 255);
        CHECK_NEAR(img.pixels[2], sl_srgb_encode(0.01f), 2.0 / 255);
        CHECK_NEAR(img.pixels[3], 1.0, 0.0);
        sl_image_free(&img);
    } else CHECK_MSG(false, "%s", err);
    free(src);
}

/* ---- files written by hand: 16-bit, grey, grey+alpha, gAMA 1.0, absurd size -------------- */

static void test_handmade_pngs(void) {
    char err[512] = "";
    sl_image img;
    /* 16-bit RGB, 2×2 */
    static const uint16_t v16[12] = {0, 65535, 32768, 1234, 40000, 1, 65535, 65535, 65535, 7, 8, 9};
    uint8_t rows[24];
    for (int i = 0; i < 12; i++) rows[i * 2] = v16[i] >> 8, rows[i * 2 + 1] = v16[i] & 0xff;
    const char *path = tmp_path("rgb16.png");
    write_png(path, 2, 2, 16, 2, rows, 12, 0, 0);
    if (sl_image_load(&img, path, err, sizeof err)) {
        CHECK(img.source_bits == 16);
        CHECK(img.source_srgb);
        CHECK(!img.source_float);
        for (int p = 0; p < 4; p++) {
            for (int c = 0; c < 3; c++) CHECK_NEAR(img.pixels[p * 4 + c], v16[p * 3 + c] / 65535.0, 1e-7);
            CHECK_NEAR(img.pixels[p * 4 + 3], 1.0, 0.0);
        }
        sl_image_free(&img);
    } else CHECK_MSG(false, "%s", err);

    /* 8-bit grey 3×1: replicated to RGB, alpha 1 */
    static const uint8_t grey[3] = {0, 100, 255};
    path = tmp_path("grey.png");
    write_png(path, 3, 1, 8, 0, grey, 3, 0, 0);
    if (sl_image_load(&img, path, err, sizeof err)) {
        CHECK(img.source_bits == 8 && img.source_srgb);
        for (int p = 0; p < 3; p++) {
            for (int c = 0; c < 3; c++) CHECK_NEAR(img.pixels[p * 4 + c], grey[p] / 255.0, 1e-7);
            CHECK_NEAR(img.pixels[p * 4 + 3], 1.0, 0.0);
        }
        sl_image_free(&img);
    } else CHECK_MSG(false, "%s", err);

    /* 8-bit grey + alpha 2×1 */
    static const uint8_t ga[4] = {51, 204, 255, 0};
    path = tmp_path("grey_alpha.png");
    write_png(path, 2, 1, 8, 4, ga, 4, 0, 0);
    if (sl_image_load(&img, path, err, sizeof err)) {
        CHECK_NEAR(img.pixels[0], 0.2, 1e-7);
        CHECK_NEAR(img.pixels[1], 0.2, 1e-7);
        CHECK_NEAR(img.pixels[2], 0.2, 1e-7);
        CHECK_NEAR(img.pixels[3], 0.8, 1e-7);
        CHECK_NEAR(img.pixels[4], 1.0, 0.0);
        CHECK_NEAR(img.pixels[7], 0.0, 0.0);
        sl_image_free(&img);
    } else CHECK_MSG(false, "%s", err);

    /* gAMA 1.0: OIIO tags it linear, so it is not sRGB */
    static const uint8_t rgb[3] = {10, 20, 30};
    path = tmp_path("linear_gama.png");
    write_png(path, 1, 1, 8, 2, rgb, 3, 100000, 0);
    if (sl_image_load(&img, path, err, sizeof err)) {
        CHECK_MSG(!img.source_srgb, "a PNG with gAMA 1.0 was taken as sRGB");
        CHECK(img.source_bits == 8);
        sl_image_free(&img);
    } else CHECK_MSG(false, "%s", err);

    /* committed fixture: R,G,B,Z,A float TIFF, alpha after a non-colour channel */
    path = SL_TEST_DATA_DIR "/images/rgbza_float.tif";
    if (sl_image_load(&img, path, err, sizeof err)) {
        CHECK(img.width == 2 && img.height == 2 && img.source_float && img.source_bits == 32);
        CHECK(same_colour(img.pixels + 12, 0.1f, 0.2f, 0.3f, 0.9f));
        sl_image_free(&img);
    } else CHECK_MSG(false, "%s", err);

    /* a header claiming 20000×20000: refused before any pixel memory is allocated */
    path = tmp_path("huge.png");
    write_png(path, 20000, 20000, 8, 0, NULL, 0, 0, 16);
    CHECK(!sl_image_load(&img, path, err, sizeof err));
    CHECK_CONTAINS(err, path);
    CHECK_CONTAINS(err, "20000x20000");
    CHECK_CONTAINS(err, "limit of 16384 per side and 64 Mpixel");
    CHECK(img.pixels == NULL && img.width == 0);
    write_png(path, 16385, 1, 8, 0, NULL, 0, 0, 16); /* each side is checked on its own */
    CHECK(!sl_image_load(&img, path, err, sizeof err));
    CHECK_CONTAINS(err, "16385x1 (from its header), over the limit");
    write_png(path, 1, 16385, 8, 0, NULL, 0, 0, 16);
    CHECK(!sl_image_load(&img, path, err, sizeof err));
    CHECK_CONTAINS(err, "1x16385 (from its header), over the limit");
    /* and the pixel count: 8193×8192 is within each side's limit but over 64 Mpixel (a small
     * file that would decode to gigabytes is refused from its header) */
    write_png(path, 8193, 8192, 8, 0, NULL, 0, 0, 16);
    CHECK(!sl_image_load(&img, path, err, sizeof err));
    CHECK_CONTAINS(err, "8193x8192 (from its header), over the limit");
}

/* ---- bad inputs ------------------------------------------------------------------------- */

static void expect_load_error(const char *path, const char *fragment) {
    char err[512] = "";
    sl_image img = {.width = 7, .pixels = (float *)&img}; /* garbage: must be zeroed */
    CHECK_MSG(!sl_image_load(&img, path, err, sizeof err), "loading %s succeeded", path);
    CHECK_CONTAINS(err, path);
    CHECK_CONTAINS(err, fragment);
    CHECK(img.pixels == NULL && img.width == 0 && img.height == 0);
}

static void test_load_errors(void) {
    expect_load_error(tmp_path("does_not_exist.png"), "no such file");
    expect_load_error(tmp_path("does_not_exist/x.png"), "no such file");
    expect_load_error(tmpdir, "is a directory");

    write_bytes(tmp_path("empty.png"), "", 0);
    expect_load_error(tmp_path("empty.png"), "empty file");

    const char *text = "this is not an image, just text pretending to be one\n";
    write_bytes(tmp_path("text.png"), text, strlen(text));
    expect_load_error(tmp_path("text.png"), "not a valid .png file");
    write_bytes(tmp_path("text.xyz"), text, strlen(text));
    expect_load_error(tmp_path("text.xyz"), "unsupported format '.xyz'");
    write_bytes(tmp_path("text"), text, strlen(text));
    expect_load_error(tmp_path("text"), "unsupported format");

    /* a real, non-trivially compressible PNG, then truncated at several lengths */
    const int w = 64, h = 64;
    float *noise = malloc(w * h * 4 * sizeof(float));
    uint32_t s = 12345;
    for (int i = 0; i < w * h * 4; i++) s = s * 1664525u + 1013904223u, noise[i] = (s >> 8) / 16777216.0f;
    char err[512] = "";
    const char *full = tmp_path("noise.png");
    CHECK_MSG(sl_image_write(full, noise, w, h, true, err, sizeof err), "%s", err);
    long n = file_size(full);
    CHECK(n > 1000);
    FILE *f = fopen(full, "rb");
    uint8_t *bytes = malloc(n > 0 ? n : 1);
    CHECK(f && fread(bytes, 1, n, f) == (size_t)n);
    if (f) fclose(f);
    write_bytes(tmp_path("half.png"), bytes, n / 2);
    expect_load_error(tmp_path("half.png"), "corrupt");
    write_bytes(tmp_path("cut_end.png"), bytes, n - 20); /* loses the IEND and part of IDAT */
    expect_load_error(tmp_path("cut_end.png"), "corrupt");
    write_bytes(tmp_path("header_only.png"), bytes, 20);
    expect_load_error(tmp_path("header_only.png"), "corrupt");
    /* a flipped byte in the middle of the compressed data */
    bytes[n / 2] ^= 0x5a;
    write_bytes(tmp_path("flipped.png"), bytes, n);
    {
        sl_image img;
        bool ok = sl_image_load(&img, tmp_path("flipped.png"), err, sizeof err);
        /* libpng may or may not notice (CRC checks on ancillary data differ): only require
         * no crash, and a message naming the file when it fails */
        if (!ok) CHECK_CONTAINS(err, "flipped.png");
        sl_image_free(&img);
    }
    free(bytes);
    free(noise);

    if (geteuid() != 0) { /* root reads anything */
        const char *locked = tmp_path("locked.png");
        write_bytes(locked, text, strlen(text));
        chmod(locked, 0);
        expect_load_error(locked, "permission denied");
        chmod(locked, 0600);
    }
    char e2[64];
    sl_image img;
    CHECK(!sl_image_load(&img, NULL, e2, sizeof e2));
    CHECK(!sl_image_load(&img, "", e2, sizeof e2));
    CHECK(!sl_image_load(&img, tmp_path("nope.png"), NULL, 0)); /* no err buffer: no crash */
    char tiny[8];
    CHECK(!sl_image_load(&img, tmp_path("nope.png"), tiny, sizeof tiny));
    CHECK(strlen(tiny) == 7); /* truncated, terminated */
}

static void test_write_errors(void) {
    float px[4] = {0.5f, 0.5f, 0.5f, 1.0f};
    char err[512] = "";
    const char *p = tmp_path("missing_dir/out.png");
    CHECK(!sl_image_write(p, px, 1, 1, false, err, sizeof err));
    CHECK_CONTAINS(err, p);
    CHECK_CONTAINS(err, "does not exist");

    p = tmp_path("out.bmp");
    CHECK(!sl_image_write(p, px, 1, 1, false, err, sizeof err));
    CHECK_CONTAINS(err, p);
    CHECK_CONTAINS(err, "unknown extension '.bmp'");
    CHECK(file_size(p) < 0);

    p = tmp_path("noextension");
    CHECK(!sl_image_write(p, px, 1, 1, false, err, sizeof err));
    CHECK_CONTAINS(err, "no file extension");

    p = tmp_path("empty_image.png");
    CHECK(!sl_image_write(p, px, 0, 1, false, err, sizeof err));
    CHECK_CONTAINS(err, p);
    CHECK(!sl_image_write(p, NULL, 1, 1, false, err, sizeof err));
    CHECK_CONTAINS(err, "no pixels");

    const char *file_as_dir = tmp_path("text.png/out.png"); /* text.png is a file */
    CHECK(!sl_image_write(file_as_dir, px, 1, 1, false, err, sizeof err));
    CHECK_CONTAINS(err, "not a directory");

    CHECK(!sl_image_write(tmpdir, px, 1, 1, false, err, sizeof err)); /* no extension */
    mkdir(tmp_path("dir.png"), 0700);
    CHECK(!sl_image_write(tmp_path("dir.png"), px, 1, 1, false, err, sizeof err));
    CHECK_CONTAINS(err, "is a directory");
    rmdir(tmp_path("dir.png"));
}

/* ---- comparison ------------------------------------------------------------------------- */

static void test_compare(void) {
    const int w = 8, h = 4, n = w * h;
    float a[8 * 4 * 4], b[8 * 4 * 4];
    for (int i = 0; i < n * 4; i++) a[i] = 0.25f + 0.5f * (i % 7) / 7.0f, b[i] = a[i];
    sl_image_diff d;

    sl_image_compare(a, b, w, h, 4, 0.0, &d);
    CHECK_NEAR(d.rmse, 0.0, 0.0);
    CHECK(isinf(d.psnr) && d.psnr > 0);
    CHECK_NEAR(d.max_abs, 0.0, 0.0);
    CHECK(d.pixels_over == 0 && d.nonfinite_a == 0 && d.nonfinite_b == 0);
    CHECK(d.pixels_compared == n);

    /* constant offset 0.1 on RGB; alpha differs too but is not part of the metrics */
    for (int i = 0; i < n * 4; i++) b[i] = a[i] + (i % 4 == 3 ? 0.5f : 0.1f);
    sl_image_compare(a, b, w, h, 4, 0.05, &d);
    CHECK_NEAR(d.rmse, 0.1, 1e-6);
    CHECK_NEAR(d.psnr, 20.0, 1e-4);
    CHECK_NEAR(d.max_abs, 0.1, 1e-6);
    CHECK_NEAR(d.mean_abs, 0.1, 1e-6);
    CHECK(d.pixels_over == n);
    sl_image_compare(a, b, w, h, 4, 0.2, &d);
    CHECK(d.pixels_over == 0);

    /* one NaN pixel in b: counted, excluded from the sums (which stay exactly the same) */
    b[5 * 4 + 1] = NAN;
    sl_image_compare(a, b, w, h, 4, 0.2, &d);
    CHECK(d.nonfinite_b == 1 && d.nonfinite_a == 0);
    CHECK(d.pixels_compared == n - 1);
    CHECK(d.pixels_over == 1);
    CHECK_NEAR(d.rmse, 0.1, 1e-6);
    CHECK_NEAR(d.max_abs, 0.1, 1e-6);
    CHECK(isfinite(d.rmse) && isfinite(d.psnr));
    /* an Inf in a's alpha makes that pixel non-finite too */
    a[9 * 4 + 3] = INFINITY;
    sl_image_compare(a, b, w, h, 4, 0.2, &d);
    CHECK(d.nonfinite_a == 1 && d.nonfinite_b == 1 && d.pixels_compared == n - 2);

    /* one channel of one pixel off by 0.4 (3-channel images): rmse = sqrt(0.16 / (n*3)) */
    float c[8 * 4 * 3], e[8 * 4 * 3];
    for (int i = 0; i < n * 3; i++) c[i] = e[i] = 0.5f;
    e[7 * 3 + 2] = 0.1f;
    sl_image_compare(c, e, w, h, 3, 0.3, &d);
    CHECK_NEAR(d.rmse, sqrt(0.16 / (n * 3)), 1e-7);
    CHECK_NEAR(d.psnr, -20 * log10(sqrt(0.16 / (n * 3))), 1e-5);
    CHECK_NEAR(d.max_abs, 0.4, 1e-7);
    CHECK_NEAR(d.mean_abs, 0.4 / (n * 3), 1e-8);
    CHECK(d.pixels_over == 1);

    /* nothing comparable: metrics undefined (NaN), not a false "perfect match" */
    for (int i = 0; i < n * 3; i++) e[i] = NAN;
    sl_image_compare(c, e, w, h, 3, 0.3, &d);
    CHECK(d.pixels_compared == 0 && d.nonfinite_b == n && d.pixels_over == n);
    CHECK(isnan(d.rmse) && isnan(d.psnr));
    sl_image_compare(NULL, e, w, h, 3, 0.3, &d); /* no crash */
    CHECK(isnan(d.rmse));
}

/* ---- procedural textures ---------------------------------------------------------------- */

/* Connected regions of identical colour (4-neighbour flood fill). */
static int count_regions(const sl_image *img) {
    int w = img->width, h = img->height, regions = 0;
    int *label = calloc((size_t)w * h, sizeof(int)), *stack = malloc((size_t)w * h * sizeof(int));
    for (int start = 0; start < w * h; start++) {
        if (label[start]) continue;
        regions++;
        int sp = 0;
        stack[sp++] = start;
        label[start] = regions;
        while (sp) {
            int i = stack[--sp], x = i % w, y = i / w;
            const int nb[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
            for (int k = 0; k < 4; k++) {
                int nx = nb[k][0], ny = nb[k][1];
                if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                int j = ny * w + nx;
                if (!label[j] && !memcmp(img->pixels + (size_t)i * 4, img->pixels + (size_t)j * 4, 16))
                    label[j] = regions, stack[sp++] = j;
            }
        }
    }
    free(label);
    free(stack);
    return regions;
}

#define PX(img, x, y) ((img).pixels + ((size_t)(y) * (img).width + (x)) * 4)

static void test_procedural(void) {
    char err[512] = "";
    sl_image img;
    CHECK_MSG(sl_image_procedural(&img, "checker:8:0.9,0.9,0.9:0.2,0.3,0.8", 64, err, sizeof err), "%s", err);
    if (img.pixels) {
        CHECK(img.width == 64 && img.height == 64 && img.channels == 4);
        CHECK(!img.source_srgb && img.source_bits == 32);
        CHECK(same_colour(PX(img, 0, 0), 0.9f, 0.9f, 0.9f, 1));
        CHECK(same_colour(PX(img, 7, 7), 0.9f, 0.9f, 0.9f, 1));
        CHECK(same_colour(PX(img, 8, 0), 0.2f, 0.3f, 0.8f, 1));
        CHECK(same_colour(PX(img, 0, 8), 0.2f, 0.3f, 0.8f, 1));
        CHECK(same_colour(PX(img, 8, 8), 0.9f, 0.9f, 0.9f, 1));
        CHECK(same_colour(PX(img, 63, 0), 0.2f, 0.3f, 0.8f, 1));
        CHECK(same_colour(PX(img, 63, 63), 0.9f, 0.9f, 0.9f, 1));
        CHECK(count_regions(&img) == 64);
        long a_count = 0;
        for (int i = 0; i < 64 * 64; i++) a_count += img.pixels[i * 4 + 2] == 0.9f;
        CHECK(a_count == 64 * 64 / 2);
    }
    sl_image_free(&img);
    /* size not a multiple of N: still N×N squares, sizes differ by at most one texel */
    CHECK_MSG(sl_image_procedural(&img, "checker:3:1,1,1:0,0,0", 10, err, sizeof err), "%s", err);
    if (img.pixels) {
        CHECK(count_regions(&img) == 9);
        int run = 0, min_run = 99, max_run = 0;
        for (int x = 0; x < 10; x++) {
            run++;
            if (x == 9 || PX(img, x, 0)[0] != PX(img, x + 1, 0)[0]) {
                if (run < min_run) min_run = run;
                if (run > max_run) max_run = run;
                run = 0;
            }
        }
        CHECK(min_run == 3 && max_run == 4);
    }
    sl_image_free(&img);
    CHECK(sl_image_procedural(&img, "checker:1:0.5,0.5,0.5:0,0,0", 4, err, sizeof err));
    if (img.pixels) CHECK(count_regions(&img) == 1);
    sl_image_free(&img);

    CHECK_MSG(sl_image_procedural(&img, "grid:4:1,1,1:0,0,0", 64, err, sizeof err), "%s", err);
    if (img.pixels) {
        CHECK(same_colour(PX(img, 0, 0), 1, 1, 1, 1));
        CHECK(same_colour(PX(img, 16, 5), 1, 1, 1, 1));
        CHECK(same_colour(PX(img, 5, 48), 1, 1, 1, 1));
        CHECK(same_colour(PX(img, 5, 5), 0, 0, 0, 1));
        CHECK(same_colour(PX(img, 15, 15), 0, 0, 0, 1));
        CHECK(same_colour(PX(img, 63, 63), 0, 0, 0, 1));
        long lines = 0;
        for (int i = 0; i < 64 * 64; i++) lines += img.pixels[i * 4] == 1.0f;
        CHECK(lines == 4 * 64 + 4 * 64 - 16); /* 1-texel lines: 4 rows + 4 columns − crossings */
        CHECK(count_regions(&img) == 16 + 1);  /* 16 cells + the connected line network */
    }
    sl_image_free(&img);
    CHECK(sl_image_procedural(&img, "grid:2:1,1,1:0,0,0", 256, err, sizeof err));
    if (img.pixels) { /* width 256/32 = 8 */
        CHECK(same_colour(PX(img, 7, 100), 1, 1, 1, 1));
        CHECK(same_colour(PX(img, 8, 100), 0, 0, 0, 1));
        CHECK(same_colour(PX(img, 135, 100), 1, 1, 1, 1));
    }
    sl_image_free(&img);

    CHECK(sl_image_procedural(&img, "gradient", 16, err, sizeof err));
    if (img.pixels) {
        CHECK(same_colour(PX(img, 0, 0), 0, 0, 0, 1));
        CHECK(same_colour(PX(img, 15, 0), 1, 0, 0, 1));
        CHECK(same_colour(PX(img, 0, 15), 0, 1, 0, 1));
        CHECK_NEAR(PX(img, 5, 10)[0], 5 / 15.0, 1e-7);
        CHECK_NEAR(PX(img, 5, 10)[1], 10 / 15.0, 1e-7);
    }
    sl_image_free(&img);
    CHECK(sl_image_procedural(&img, "uv", 16, err, sizeof err));
    if (img.pixels) {
        CHECK(same_colour(PX(img, 0, 0), 0.5f / 16, 0.5f / 16, 0, 1));
        CHECK(same_colour(PX(img, 15, 3), 15.5f / 16, 3.5f / 16, 0, 1));
    }
    sl_image_free(&img);
    CHECK(sl_image_procedural(&img, "constant:0.1,0.2,0.3,0.5", 4, err, sizeof err));
    if (img.pixels) CHECK(same_colour(PX(img, 3, 3), 0.1f, 0.2f, 0.3f, 0.5f));
    sl_image_free(&img);
    CHECK(sl_image_procedural(&img, "constant:2,0,0", 1, err, sizeof err)); /* HDR allowed */
    if (img.pixels) CHECK(same_colour(PX(img, 0, 0), 2, 0, 0, 1));
    sl_image_free(&img);
}

static void expect_spec_error(const char *spec, int size, const char *fragment) {
    char err[512] = "";
    sl_image img = {.width = 3};
    CHECK_MSG(!sl_image_procedural(&img, spec, size, err, sizeof err), "spec '%s' was accepted", spec);
    if (spec && *spec) CHECK_CONTAINS(err, spec);
    CHECK_CONTAINS(err, fragment);
    CHECK(img.pixels == NULL && img.width == 0);
}

static void test_procedural_errors(void) {
    const char *checker_form = "expected 'checker:N:r,g,b:r,g,b'";
    expect_spec_error("checker:8", 64, checker_form);
    expect_spec_error("checker", 64, checker_form);
    expect_spec_error("checker:8:1,1,1", 64, "missing fields");
    expect_spec_error("checker:8:1,1,1:0,0,0:1,1,1", 64, "too many fields");
    expect_spec_error("checker:x:1,1,1:0,0,0", 64, "N 'x'");
    expect_spec_error("checker:0:1,1,1:0,0,0", 64, "from 1 to the size 64");
    expect_spec_error("checker:-2:1,1,1:0,0,0", 64, "N '-2'");
    expect_spec_error("checker:65:1,1,1:0,0,0", 64, "N '65'");
    expect_spec_error("checker:8.5:1,1,1:0,0,0", 64, "whole number");
    expect_spec_error("checker:99999999999999999999:1,1,1:0,0,0", 64, "whole number");
    expect_spec_error("checker:8:1,1:0,0,0", 64, "has 2 components");
    expect_spec_error("checker:8:1,1,1:", 64, "colour is empty");
    expect_spec_error("checker:8:1,a,1:0,0,0", 64, "not a list of numbers");
    expect_spec_error("checker:8:1,,1:0,0,0", 64, "not a list of numbers");
    expect_spec_error("checker:8:1,1,1,:0,0,0", 64, "not a list of numbers");
    expect_spec_error("checker:8:nan,1,1:0,0,0", 64, "not finite");
    expect_spec_error("checker:8:1,1,1:0,inf,0", 64, "not finite");
    expect_spec_error("checker:8:1,1,1:0,-1,0", 64, "negative");
    expect_spec_error("checker:8:1,1,1:0,1e39,0", 64, "not finite");
    expect_spec_error("grid:4:1,1,1", 64, "expected 'grid:N:r,g,b:r,g,b'");
    expect_spec_error("constant:1,2,3,4,5", 4, "more than 4 components");
    expect_spec_error("constant", 4, "expected 'constant:r,g,b'");
    expect_spec_error("gradient:3", 4, "too many fields");
    expect_spec_error("uv:", 4, "too many fields");
    expect_spec_error("wood:3", 4, "unknown kind 'wood'");
    expect_spec_error("Checker:8:1,1,1:0,0,0", 4, "unknown kind 'Checker'");
    expect_spec_error("", 4, "empty spec");
    expect_spec_error(NULL, 4, "empty spec");
    expect_spec_error("gradient", 0, "size 0 out of range");
    expect_spec_error("gradient", 100000, "size 100000 out of range");
    char longspec[1200];
    memset(longspec, 'c', sizeof longspec - 1);
    longspec[sizeof longspec - 1] = 0;
    char err[64];
    sl_image img;
    CHECK(!sl_image_procedural(&img, longspec, 4, err, sizeof err)); /* truncated, no overflow */
    CHECK(strlen(err) == sizeof err - 1);
    CHECK(!sl_image_procedural(&img, "checker:2:1,1,1:0,0,0:", 4, NULL, 0));
}

/* Procedural tangent-space normal maps against their closed forms: texel (x, y) has its centre
 * at X = (x+0.5)/size, Y = 1 − (y+0.5)/size (image up); n = (−h_X, −h_Y, 1)/|…| stored as n/2+1/2. */
static void test_procedural_normals(void) {
    char err[512] = "";
    sl_image img;
    const int S = 64;
    CHECK_MSG(sl_image_procedural(&img, "bumps:4:0.8", S, err, sizeof err), "%s", err);
    double worst = 0;
    for (int y = 0; y < S && img.pixels; y++)
        for (int x = 0; x < S; x++) {
            double X = (x + 0.5) / S, Y = 1 - (y + 0.5) / S, w = 2 * M_PI * 4;
            double hx = 0.8 * cos(w * X) * sin(w * Y), hy = 0.8 * sin(w * X) * cos(w * Y), l = sqrt(hx * hx + hy * hy + 1);
            double n[3] = {-hx / l, -hy / l, 1 / l};
            for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(PX(img, x, y)[c] - (n[c] * 0.5 + 0.5)));
        }
    CHECK_MSG(worst < 1e-6, "bumps: worst texel error %g", worst);
    sl_image_free(&img);
    CHECK(sl_image_procedural(&img, "tilt:0.6,-0.8", 8, err, sizeof err));
    if (img.pixels) CHECK(same_colour(PX(img, 3, 5), 0.8f, 0.1f, 0.5f, 1));
    sl_image_free(&img);
    CHECK(sl_image_procedural(&img, "flat", 4, err, sizeof err));
    if (img.pixels) CHECK(same_colour(PX(img, 1, 2), 0.5f, 0.5f, 1, 1));
    sl_image_free(&img);
    /* waves: unit normals, tileable (integer frequencies: the left and right columns' neighbours
     * across the seam differ as much as neighbours inside) */
    CHECK(sl_image_procedural(&img, "waves:12:0.7:5", 128, err, sizeof err));
    double len_err = 0;
    for (int i = 0; i < 128 * 128 && img.pixels; i++) {
        double v[3];
        for (int c = 0; c < 3; c++) v[c] = img.pixels[i * 4 + c] * 2.0 - 1.0;
        len_err = fmax(len_err, fabs(sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - 1));
    }
    CHECK_MSG(len_err < 1e-5, "waves: |n| - 1 up to %g", len_err);
    sl_image_free(&img);
    expect_spec_error("bumps:0:1", 16, "expected 'bumps:N:A'");
    expect_spec_error("bumps:4:nan", 16, "expected 'bumps:N:A'");
    expect_spec_error("bumps:4", 16, "missing fields");
    expect_spec_error("tilt:1,1", 16, "X^2 + Y^2 <= 1");
    expect_spec_error("waves:1:0.5:3", 16, "expected 'waves:N:A:SEED'");
    expect_spec_error("waves:8:0.5:-3", 16, "SEED");
    CHECK(sl_image_is_procedural("bumps:16:0.8") && sl_image_is_procedural("flat") && sl_image_is_procedural("uv"));
    CHECK(!sl_image_is_procedural("bumps.png") && !sl_image_is_procedural("flat.png") && !sl_image_is_procedural("textures/uv"));
}

/* ---- small conversions ------------------------------------------------------------------ */

static void test_conversions(void) {
    float px[3 * 2 * 4];
    for (int i = 0; i < 24; i++) px[i] = (float)i;
    sl_image_flip_rows(px, 2, 3, 4);
    CHECK(px[0] == 16 && px[7] == 23);   /* last row now first */
    CHECK(px[8] == 8 && px[15] == 15);   /* middle row stays */
    CHECK(px[16] == 0 && px[23] == 7);
    sl_image_flip_rows(px, 2, 3, 4);
    bool back = true;
    for (int i = 0; i < 24; i++) back &= px[i] == (float)i;
    CHECK(back);
    unsigned char rows[4] = {1, 2, 3, 4};
    sl_image_flip_rows_raw(rows, 1, 4);
    CHECK(rows[0] == 4 && rows[1] == 3 && rows[2] == 2 && rows[3] == 1);

    float rgba[8] = {0.5f, NAN, -1.0f, 0.5f, INFINITY, 0.0031308f, 1.0f, 2.0f};
    unsigned char out[8];
    sl_image_to_rgba8(rgba, 2, 1, false, out);
    CHECK(out[0] == 188 && out[1] == 0 && out[2] == 0 && out[3] == 128);
    CHECK(out[4] == 255 && out[5] == 10 && out[6] == 255 && out[7] == 255);
    sl_image_to_rgba8(rgba, 2, 1, true, out);
    CHECK(out[0] == 128 && out[5] == 1);

    sl_image img = {0};
    CHECK(sl_image_procedural(&img, "constant:0.2140411,1,0", 2, NULL, 0));
    for (int i = 0; i < 4; i++) img.pixels[i * 4] = 0.5f; /* as if sRGB-encoded 0.5 */
    sl_image_srgb_to_linear(&img);
    CHECK_NEAR(img.pixels[0], 0.2140411, 1e-6);
    CHECK_NEAR(img.pixels[1], 1.0, 0.0);
    CHECK_NEAR(img.pixels[3], 1.0, 0.0); /* alpha untouched */
    sl_image_free(&img);
    /* the whole-image conversion agrees with the scalar formula on 8-bit codes and between */
    CHECK(sl_image_procedural(&img, "gradient", 256, NULL, 0));
    for (int i = 0; i < 256; i++) img.pixels[i * 4 + 0] = i / 255.0f, img.pixels[i * 4 + 1] = (i + 0.37f) / 255.0f;
    img.pixels[2] = NAN, img.pixels[6] = -3.0f, img.pixels[10] = 4.0f;
    float expect_b[3] = {0.0f, 0.0f, 1.0f};
    sl_image_srgb_to_linear(&img);
    double worst = 0;
    for (int i = 0; i < 256; i++) {
        worst = fmax(worst, fabs(img.pixels[i * 4 + 0] - sl_srgb_decode(i / 255.0f)));
        worst = fmax(worst, fabs(img.pixels[i * 4 + 1] - sl_srgb_decode((i + 0.37f) / 255.0f)));
    }
    CHECK_NEAR(worst, 0.0, 1e-6);
    for (int i = 0; i < 3; i++) CHECK_NEAR(img.pixels[i * 4 + 2], expect_b[i], 0.0);
    sl_image_free(&img);
    sl_image_free(NULL);
    sl_image_srgb_to_linear(NULL);
}

static void remove_tmpdir(void) {
    DIR *d = opendir(tmpdir);
    if (!d) return;
    for (struct dirent *e; (e = readdir(d));) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        char p[600];
        snprintf(p, sizeof p, "%s/%s", tmpdir, e->d_name);
        if (unlink(p) != 0) rmdir(p);
    }
    closedir(d);
    rmdir(tmpdir);
}

/* The mip filter's weights from their definition: destination texel i of a side of `size`
 * (→ n = max(1, size/2) texels) covers source [i·size/n, (i+1)·size/n); source texel k weighs the
 * length of [k, k + 1) inside it over the interval's length. */
static double mip_weight(int size, int i, int k) {
    int n = size > 1 ? size / 2 : 1;
    double a = (double)i * size / n, b = (double)(i + 1) * size / n;
    double lo = a > k ? a : k, hi = b < k + 1 ? b : k + 1;
    return hi > lo ? (hi - lo) / (b - a) : 0.0;
}
static int srgb_code_of_linear(double v) {
    double e = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
    return (int)floor(e * 255.0 + 0.5);
}
static double srgb_linear_of_code(int k) {
    double x = k / 255.0;
    return x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4);
}

/* sl_image_mip_rgba8 (the CPU mip chain of 8-bit textures) against the area-weighted box computed
 * here in double: sRGB channels averaged in linear light and encoded to the nearest code, alpha
 * and linear images averaged as codes. 5x3 → 2x1: odd sides, each texel covering parts of 3
 * columns and all 3 rows (a 2×2 box that drops the last column and row fails); 4x2 → 2x1 even. */
static void test_mip_rgba8(void) {
    static const int sizes[][2] = {{5, 3}, {4, 2}};
    for (int t = 0; t < 2; t++) {
        int W = sizes[t][0], H = sizes[t][1], W2 = W / 2, H2 = H / 2;
        unsigned char src[5 * 3 * 4], dst[2 * 1 * 4];
        for (int i = 0; i < W * H * 4; i++) src[i] = (unsigned char)((i * 97 + 13) % 256);
        for (int srgb = 0; srgb < 2; srgb++) {
            memset(dst, 0xAB, sizeof dst);
            sl_image_mip_rgba8(src, W, H, dst, srgb);
            int bad = 0;
            for (int y = 0; y < H2; y++)
                for (int x = 0; x < W2; x++)
                    for (int c = 0; c < 4; c++) {
                        double lin = 0, codes = 0;
                        for (int j = 0; j < H; j++)
                            for (int i = 0; i < W; i++) {
                                double wgt = mip_weight(W, x, i) * mip_weight(H, y, j);
                                int k = src[(j * W + i) * 4 + c];
                                lin += wgt * srgb_linear_of_code(k), codes += wgt * k;
                            }
                        int want = srgb && c < 3 ? srgb_code_of_linear(lin) : (int)floor(codes + 0.5);
                        int got = dst[(y * W2 + x) * 4 + c];
                        /* a mean that lands within 1e-4 of a rounding boundary may round either way in float */
                        double edge = srgb && c < 3 ? 1.0 : fabs(codes - floor(codes) - 0.5) < 1e-4 ? 1.0 : 0.0;
                        if (abs(got - want) > (int)edge) {
                            bad++;
                            fprintf(stderr, "mip rgba8 %dx%d (srgb %d): texel %d,%d channel %d = %d, expected %d\n", W, H,
                                    srgb, x, y, c, got, want);
                        }
                    }
            CHECK(bad == 0);
        }
    }
    /* black and white: linear mean 0.5 → code 188 in sRGB (not the codes' mean 128) */
    unsigned char bw[2 * 2 * 4] = {0, 0, 0, 255, 255, 255, 255, 255, 0, 0, 0, 255, 255, 255, 255, 255}, one[4];
    sl_image_mip_rgba8(bw, 2, 2, one, true);
    CHECK(one[0] == 188 && one[1] == 188 && one[2] == 188 && one[3] == 255);
    sl_image_mip_rgba8(bw, 2, 2, one, false);
    CHECK(one[0] == 128 && one[3] == 255);
    /* 1x4 → 1x2: pairs along v only */
    unsigned char col[1 * 4 * 4] = {10, 20, 30, 40, 12, 22, 32, 42, 100, 0, 0, 0, 200, 0, 0, 0}, col2[1 * 2 * 4];
    sl_image_mip_rgba8(col, 1, 4, col2, false);
    CHECK(col2[0] == 11 && col2[1] == 21 && col2[3] == 41 && col2[4] == 150 && col2[5] == 0);
}

/* sl_image_mip_rgbaf (float textures: procedural, 16-bit, float files): the same area-weighted box
 * in float, every channel as stored; and where each level's content sits. A ramp f(u) = u along a
 * 211-texel row (u at texel centres, BoxTextured.glb's logo is 211²) keeps, 1 to 3 levels down,
 * f at each texel's own centre within 0.02 source texels: the filter is linear and the level's
 * texels sit where their source intervals do. A box that drops odd sides' last texel puts level 2
 * 1.5 texels off in the middle and 3 at the end. The mean of every level is the source's. */
static void test_mip_rgbaf(void) {
    enum { W = 5, H = 3 };
    float src[W * H * 4], dst[2 * 1 * 4];
    for (int i = 0; i < W * H * 4; i++) src[i] = (float)((i * 97 + 13) % 256) * 0.125f - 3.0f;
    sl_image_mip_rgbaf(src, W, H, dst);
    int bad = 0;
    for (int x = 0; x < 2; x++)
        for (int c = 0; c < 4; c++) {
            double want = 0;
            for (int j = 0; j < H; j++)
                for (int i = 0; i < W; i++) want += mip_weight(W, x, i) * mip_weight(H, 0, j) * src[(j * W + i) * 4 + c];
            if (fabs(dst[x * 4 + c] - want) > 1e-4 * (1 + fabs(want))) {
                bad++;
                fprintf(stderr, "mip rgbaf: texel %d channel %d = %g, expected %g\n", x, c, dst[x * 4 + c], want);
            }
        }
    CHECK(bad == 0);
    enum { R = 211 };
    float *a = malloc(R * 4 * sizeof(float)), *b = malloc(R * 4 * sizeof(float));
    for (int x = 0; x < R; x++)
        for (int c = 0; c < 4; c++) a[x * 4 + c] = ((float)x + 0.5f) / R;
    int w = R;
    for (int level = 1; level <= 3; level++) {
        sl_image_mip_rgbaf(a, w, 1, b);
        w /= 2;
        double worst = 0, mean = 0;
        for (int x = 0; x < w; x++) {
            double off = fabs(b[x * 4] - (x + 0.5) / w) * R; /* in source texels */
            worst = off > worst ? off : worst;
            mean += b[x * 4 + 1] / w;
        }
        printf("mip rgbaf: ramp of 211, level %d (%d texels): content off its texel centres by at most %.4f "
               "source texels; mean %.6f (source 0.5)\n", level, w, worst, mean);
        CHECK(worst < 0.02);
        CHECK(fabs(mean - 0.5) < 1e-5);
        float *t = a;
        a = b, b = t;
    }
    free(a), free(b);
    /* 1x4 → 1x2: pairs along v only; HDR values and negatives pass through (no clamp) */
    float col[1 * 4 * 4] = {10, 20, 30, 40, 12, 22, 32, 42, 1000, -2, 0, 1, 3000, 2, 0, 1}, col2[1 * 2 * 4];
    sl_image_mip_rgbaf(col, 1, 4, col2);
    CHECK(col2[0] == 11 && col2[1] == 21 && col2[3] == 41 && col2[4] == 2000 && col2[5] == 0 && col2[7] == 1);
    /* 1x1 stays 1x1 */
    float px[4] = {0.5f, 0.25f, 2.0f, 1.0f}, px2[4];
    sl_image_mip_rgbaf(px, 1, 1, px2);
    CHECK(px2[0] == 0.5f && px2[1] == 0.25f && px2[2] == 2.0f && px2[3] == 1.0f);
}

int main(void) {
    crc_init();
    const char *base = getenv("TMPDIR");
    snprintf(tmpdir, sizeof tmpdir, "%s/sl_test_image_XXXXXX", base && *base ? base : "/tmp");
    if (!mkdtemp(tmpdir)) {
        perror("mkdtemp");
        return 2;
    }
    test_srgb();
    test_png_roundtrip();
    test_exr_roundtrip();
    test_hdr_jpg();
    test_mip_rgbaf();
    test_handmade_pngs();
    test_load_errors();
    test_write_errors();
    test_compare();
    test_procedural();
    test_procedural_errors();
    test_procedural_normals();
    test_conversions();
    test_mip_rgba8();
    remove_tmpdir();
    return check_result();
}
