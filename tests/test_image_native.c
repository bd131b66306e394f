/* core/image/image_native.c: the native JPEG/PNG/EXR decoders give exactly what OpenImageIO gives.
 * Every image is loaded twice, natively and with SHADELAB_IMAGE_DECODER=oiio, from its file and from
 * memory, and every float is compared bit for bit, with every source_* field. Cases the native path
 * must decode assert that it did (sl_image_decode_native returned true); cases it must leave to OIIO
 * assert that it did not. Fixtures are written here: with OIIO (sl_image_write, the module's writer,
 * oiiotool for compressions and channel layouts), and with libpng/libjpeg directly for what OIIO does
 * not write (palette, tRNS, interlacing, 16-bit, gAMA, text chunks, comments, Exif, progressive).
 * Real files from Debian packages and the shared assets are compared when present (a note when not).
 * A child process (this executable re-run) checks that loading JPEG, PNG and EXR files opens no
 * shadelab-oiio.so, and that a .hdr still loads (through it). Truncated and corrupted files must fall
 * back to OIIO and give OIIO's message. */
#define SL_IMAGE_INTERNAL
#include "image/image.h"
#include "test_tmp.h"

#include <glob.h>
#include <jpeglib.h>
#include <png.h>
#include <setjmp.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

static void use_oiio(bool on) {
    if (on) setenv("SHADELAB_IMAGE_DECODER", "oiio", 1);
    else unsetenv("SHADELAB_IMAGE_DECODER");
}

static int compared, native_count;

/* The two images are the same: size, every float's bits, every source_* field. */
static void check_same(const char *what, const sl_image *a, const sl_image *b) {
    CHECK_MSG(a->width == b->width && a->height == b->height, "%s: %dx%d vs %dx%d", what, a->width, a->height,
              b->width, b->height);
    if (a->width != b->width || a->height != b->height) return;
    size_t n = (size_t)a->width * a->height * 4, diff = 0, first = 0;
    for (size_t i = 0; i < n; i++)
        if (memcmp(&a->pixels[i], &b->pixels[i], sizeof(float)) && !diff++) first = i;
    CHECK_MSG(diff == 0, "%s: %zu of %zu samples differ, first at %zu: %.9g vs %.9g", what, diff, n, first,
              diff ? a->pixels[first] : 0.0, diff ? b->pixels[first] : 0.0);
    CHECK_MSG(a->channels == b->channels, "%s: channels", what);
    CHECK_MSG(a->source_bits == b->source_bits, "%s: source_bits %d vs %d", what, a->source_bits, b->source_bits);
    CHECK_MSG(a->source_float == b->source_float, "%s: source_float", what);
    CHECK_MSG(a->source_srgb == b->source_srgb, "%s: source_srgb %d vs %d", what, a->source_srgb, b->source_srgb);
    CHECK_MSG(a->source_channels == b->source_channels, "%s: source_channels %d vs %d", what, a->source_channels,
              b->source_channels);
    CHECK_MSG(!strcmp(a->source_description, b->source_description), "%s: description '%s' vs '%s'", what,
              a->source_description, b->source_description);
    CHECK_MSG(!strcmp(a->source_format, b->source_format), "%s: format '%s' vs '%s'", what, a->source_format,
              b->source_format);
}

enum { DEFER = 0, NATIVE = 1, EITHER = 2 };

/* Loads path natively and through OIIO, from the file and from memory (under the same name), and
 * compares. expect: NATIVE (the native decoder must take it), DEFER (it must not) or EITHER (real
 * files: whichever, the results must agree). Returns whether the native decoder took the file. */
static bool compare_file(const char *path, int expect) {
    sl_image nat, ora, viaload, mem_nat, mem_ora;
    char err[1024] = "", err2[1024] = "";
    use_oiio(true);
    bool ok_oiio = sl_image_load(&ora, path, err, sizeof err);
    use_oiio(false);
    bool took = sl_image_decode_native(&nat, path, NULL, 0);
    bool ok_load = sl_image_load(&viaload, path, err2, sizeof err2);
    if (expect == NATIVE) CHECK_MSG(took, "%s: the native decoder did not take it", path);
    if (expect == DEFER) CHECK_MSG(!took, "%s: the native decoder took it", path);
    CHECK_MSG(ok_load == ok_oiio, "%s: loads %d, through OIIO %d (%s | %s)", path, ok_load, ok_oiio, err2, err);
    if (!ok_load || !ok_oiio) CHECK_MSG(!strcmp(err, err2), "%s: message '%s' vs OIIO's '%s'", path, err2, err);
    if (took) {
        CHECK_MSG(ok_oiio, "%s: decoded natively but OIIO fails: %s", path, err);
        if (ok_oiio) check_same(path, &nat, &ora);
        native_count++;
    }
    if (ok_load && ok_oiio) check_same(path, &viaload, &ora);
    compared++;

    size_t n = 0;
    unsigned char *data = sl_test_read_file(path, &n);
    if (data && n) {
        use_oiio(true);
        bool m_ok_oiio = sl_image_load_memory(&mem_ora, data, n, path, err, sizeof err);
        use_oiio(false);
        bool m_took = sl_image_decode_native(&mem_nat, path, data, n);
        CHECK_MSG(m_took == took, "%s: from memory the native decoder %s it", path, m_took ? "took" : "left");
        CHECK_MSG(m_ok_oiio == ok_oiio, "%s: from memory OIIO %d", path, m_ok_oiio);
        if (m_took && m_ok_oiio) check_same(path, &mem_nat, &mem_ora);
        if (m_took) sl_image_free(&mem_nat);
        if (m_ok_oiio) sl_image_free(&mem_ora);
    }
    free(data);
    if (took) sl_image_free(&nat);
    if (ok_oiio) sl_image_free(&ora);
    if (ok_load) sl_image_free(&viaload);
    return took;
}

/* A deterministic test pattern: gradients and hash noise, so that every code and the JPEG's chroma
 * upsampling are exercised. */
static float pattern(int x, int y, int c, int w, int h) {
    uint32_t k = (uint32_t)x * 73856093u ^ (uint32_t)y * 19349663u ^ (uint32_t)c * 83492791u;
    k ^= k >> 13, k *= 0x5bd1e995u, k ^= k >> 15;
    float noise = (float)(k & 0xffff) / 65535.0f;
    float grad = c == 0 ? (float)x / (float)(w - 1) : c == 1 ? (float)y / (float)(h - 1) : 0.5f;
    return c == 3 ? noise : 0.6f * grad + 0.4f * noise;
}

static float *make_rgba(int w, int h) {
    float *p = malloc((size_t)w * h * 16);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 4; c++) p[((size_t)y * w + x) * 4 + c] = pattern(x, y, c, w, h);
    return p;
}

/* ---- libpng / libjpeg writers for what OIIO does not write -------------------------------- */

typedef struct png_opts {
    int depth, colour, interlace;
    int gamma;         /* gAMA ×1e5, 0: none */
    bool srgb, chrm, trns, iccp;
    const char *text_key, *text_val;
    int text_kind;     /* 0 tEXt, 1 zTXt, 2 iTXt */
} png_opts;

static void write_png_custom(const char *path, int w, int h, const png_opts *o) {
    FILE *f = fopen(path, "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        CHECK_MSG(0, "%s: libpng could not write it", path);
        png_destroy_write_struct(&png, &info);
        fclose(f);
        return;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, o->depth, o->colour, o->interlace,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    int ch = o->colour == PNG_COLOR_TYPE_GRAY ? 1 : o->colour == PNG_COLOR_TYPE_GRAY_ALPHA ? 2
           : o->colour == PNG_COLOR_TYPE_RGB  ? 3 : o->colour == PNG_COLOR_TYPE_RGBA ? 4 : 1;
    if (o->colour == PNG_COLOR_TYPE_PALETTE) {
        png_color pal[256];
        png_byte alpha[256];
        int n = 1 << o->depth;
        for (int i = 0; i < n; i++)
            pal[i].red = (png_byte)(i * 37), pal[i].green = (png_byte)(255 - i), pal[i].blue = (png_byte)(i * 11),
            alpha[i] = (png_byte)(i * 53);
        png_set_PLTE(png, info, pal, n);
        if (o->trns) png_set_tRNS(png, info, alpha, n / 2, NULL);
    } else if (o->trns) {
        png_color_16 key = {0};
        key.gray = key.red = 3, key.green = 5, key.blue = 7;
        png_set_tRNS(png, info, NULL, 0, &key);
    }
    if (o->srgb) png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    if (o->gamma) png_set_gAMA_fixed(png, info, o->gamma);
    if (o->chrm) png_set_cHRM_fixed(png, info, 31270, 32900, 64000, 33000, 30000, 60000, 15000, 6000);
    if (o->iccp) {
        static png_byte prof[132] = {0};
        png_set_iCCP(png, info, "x", 0, prof, sizeof prof);
    }
    if (o->text_key) {
        png_text t = {0};
        t.compression = o->text_kind == 0 ? PNG_TEXT_COMPRESSION_NONE : o->text_kind == 1 ? PNG_TEXT_COMPRESSION_zTXt
                                                                                         : PNG_ITXT_COMPRESSION_NONE;
        t.key = (char *)o->text_key;
        t.text = (char *)o->text_val;
        png_set_text(png, info, &t, 1);
    }
    png_write_info(png, info);
    int bpp = o->depth == 16 ? 2 : 1;
    size_t rowbytes = o->depth < 8 ? ((size_t)w * o->depth + 7) / 8 : (size_t)w * ch * bpp;
    unsigned char *rows = malloc(rowbytes * h);
    for (int y = 0; y < h; y++)
        for (size_t i = 0; i < rowbytes; i++) {
            uint32_t k = (uint32_t)((y * 7919 + (int)i * 104729) ^ (y * (int)i));
            rows[(size_t)y * rowbytes + i] = (unsigned char)(k ^ (k >> 8));
        }
    png_bytep ptrs[1024];
    for (int y = 0; y < h && y < 1024; y++) ptrs[y] = rows + (size_t)y * rowbytes;
    png_write_image(png, ptrs);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    fclose(f);
    free(rows);
}

/* Every 8-bit code in a 256x1 grey PNG and every 16-bit code in a 256x256 grey PNG. */
static void write_png_codes(const char *path, int depth) {
    int w = 256, h = depth == 16 ? 256 : 1;
    FILE *f = fopen(path, "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) abort();
    png_init_io(png, f);
    png_set_IHDR(png, info, w, h, depth, PNG_COLOR_TYPE_GRAY, 0, 0, 0);
    png_write_info(png, info);
    unsigned char row[512];
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            if (depth == 8) row[x] = (unsigned char)x;
            else row[2 * x] = (unsigned char)y, row[2 * x + 1] = (unsigned char)x; /* code y*256+x, big-endian */
        }
        png_write_row(png, row);
    }
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    fclose(f);
}

typedef struct jpeg_opts {
    bool grey, progressive;
    int h_samp;              /* luma sampling factors (2,2: 4:2:0; 2,1: 4:2:2; 1,1: 4:4:4) */
    int v_samp;
    const char *comment;
    const unsigned char *app1; /* a raw APP1 marker body (Exif…) */
    size_t app1_len;
} jpeg_opts;

static void write_jpeg_custom(const char *path, int w, int h, const jpeg_opts *o) {
    struct jpeg_compress_struct c;
    struct jpeg_error_mgr e;
    c.err = jpeg_std_error(&e);
    jpeg_create_compress(&c);
    FILE *f = fopen(path, "wb");
    jpeg_stdio_dest(&c, f);
    c.image_width = (JDIMENSION)w, c.image_height = (JDIMENSION)h;
    c.input_components = o->grey ? 1 : 3;
    c.in_color_space = o->grey ? JCS_GRAYSCALE : JCS_RGB;
    jpeg_set_defaults(&c);
    jpeg_set_quality(&c, 90, TRUE);
    if (!o->grey && o->h_samp) c.comp_info[0].h_samp_factor = o->h_samp, c.comp_info[0].v_samp_factor = o->v_samp;
    if (o->progressive) jpeg_simple_progression(&c);
    jpeg_start_compress(&c, TRUE);
    if (o->app1) jpeg_write_marker(&c, JPEG_APP0 + 1, o->app1, (unsigned)o->app1_len);
    if (o->comment) jpeg_write_marker(&c, JPEG_COM, (const JOCTET *)o->comment, (unsigned)strlen(o->comment));
    int ch = o->grey ? 1 : 3;
    unsigned char *row = malloc((size_t)w * ch);
    while (c.next_scanline < c.image_height) {
        int y = (int)c.next_scanline;
        for (int x = 0; x < w; x++)
            for (int k = 0; k < ch; k++) row[x * ch + k] = (unsigned char)(pattern(x, y, k, w, h) * 255.0f + 0.5f);
        JSAMPROW r = row;
        jpeg_write_scanlines(&c, &r, 1);
    }
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    fclose(f);
    free(row);
}

/* A little-endian Exif block with IFD0 holding Orientation and, when desc, an ImageDescription. */
static size_t make_exif(unsigned char *b, const char *desc) {
    memset(b, 0, 128);
    memcpy(b, "Exif\0\0II*\0\x08\0\0\0", 14);
    unsigned char *t = b + 6; /* the TIFF structure */
    int n = desc ? 2 : 1;
    t[8] = (unsigned char)n;
    unsigned char *e = t + 10;
    e[0] = 0x12, e[1] = 0x01, e[2] = 3, e[4] = 1, e[8] = 1; /* Orientation SHORT 1 = 1 */
    if (desc) {
        e += 12;
        size_t len = strlen(desc) + 1;
        uint32_t off = 10 + 12 * 2 + 4;
        e[0] = 0x0E, e[1] = 0x01, e[2] = 2, e[4] = (unsigned char)len, e[8] = (unsigned char)off;
        memcpy(t + off, desc, len);
        return 6 + off + len;
    }
    return 6 + 10 + 12 + 4;
}

/* ---- the cases ------------------------------------------------------------------------------ */

static void test_pngs(void) {
    int w = 67, h = 45;
    float *rgba = make_rgba(w, h);
    char err[1024];
    CHECK(sl_image_write(sl_test_path("oiio_rgba.png"), rgba, w, h, true, err, sizeof err)); /* libpng: sRGB+gAMA+cHRM */
    compare_file(sl_test_path("oiio_rgba.png"), NATIVE);
    /* OIIO's own PNG writer: RGB, grey, grey+alpha */
    unsigned char *b = malloc((size_t)w * h * 4);
    sl_image_to_rgba8(rgba, w, h, true, b);
    for (int ch = 1; ch <= 3; ch++) {
        unsigned char *p = malloc((size_t)w * h * ch);
        for (size_t i = 0; i < (size_t)w * h; i++)
            for (int c = 0; c < ch; c++) p[i * ch + c] = b[i * 4 + (ch == 2 && c == 1 ? 3 : c)];
        char name[64];
        snprintf(name, sizeof name, "oiio_%dch.png", ch);
        CHECK(sl_oiio_write(sl_test_path(name), "png", p, NULL, w, h, ch, "uint8", 0, err, sizeof err));
        compare_file(sl_test_path(name), NATIVE);
        free(p);
    }
    free(b);
    write_png_codes(sl_test_path("codes8.png"), 8);
    compare_file(sl_test_path("codes8.png"), NATIVE);
    write_png_codes(sl_test_path("codes16.png"), 16);
    compare_file(sl_test_path("codes16.png"), NATIVE);

    static const struct {
        const char *name;
        png_opts o;
        int expect;
    } cases[] = {
        {"rgba8.png", {8, PNG_COLOR_TYPE_RGBA, 0, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"rgb8.png", {8, PNG_COLOR_TYPE_RGB, 0, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"grey8.png", {8, PNG_COLOR_TYPE_GRAY, 0, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"greyalpha8.png", {8, PNG_COLOR_TYPE_GRAY_ALPHA, 0, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"grey1.png", {1, PNG_COLOR_TYPE_GRAY, 0, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"grey2.png", {2, PNG_COLOR_TYPE_GRAY, 0, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"grey4.png", {4, PNG_COLOR_TYPE_GRAY, 0, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"rgba16.png", {16, PNG_COLOR_TYPE_RGBA, 0, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"rgb16.png", {16, PNG_COLOR_TYPE_RGB, 0, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"grey16.png", {16, PNG_COLOR_TYPE_GRAY, 0, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"greyalpha16.png", {16, PNG_COLOR_TYPE_GRAY_ALPHA, 0, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"palette8.png", {8, PNG_COLOR_TYPE_PALETTE, 0, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"palette4.png", {4, PNG_COLOR_TYPE_PALETTE, 0, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"palette_trns.png", {8, PNG_COLOR_TYPE_PALETTE, 0, 0, 0, 0, 1, 0, 0, 0, 0}, NATIVE},
        {"grey_trns.png", {8, PNG_COLOR_TYPE_GRAY, 0, 0, 0, 0, 1, 0, 0, 0, 0}, NATIVE},
        {"rgb_trns.png", {8, PNG_COLOR_TYPE_RGB, 0, 0, 0, 0, 1, 0, 0, 0, 0}, NATIVE},
        {"rgb16_trns.png", {16, PNG_COLOR_TYPE_RGB, 0, 0, 0, 0, 1, 0, 0, 0, 0}, NATIVE},
        {"interlaced.png", {8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_ADAM7, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"interlaced16.png", {16, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_INTERLACE_ADAM7, 0, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"gamma1.png", {8, PNG_COLOR_TYPE_RGB, 0, 100000, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"gamma22.png", {8, PNG_COLOR_TYPE_RGB, 0, 45455, 0, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"srgb.png", {8, PNG_COLOR_TYPE_RGB, 0, 0, 1, 0, 0, 0, 0, 0, 0}, NATIVE},
        {"srgb_gamma1.png", {8, PNG_COLOR_TYPE_RGB, 0, 45455, 1, 1, 0, 0, 0, 0, 0}, NATIVE},
        {"desc_text.png", {8, PNG_COLOR_TYPE_RGB, 0, 100000, 0, 0, 0, 0, "Description", "shadelab-rgbe8", 0}, NATIVE},
        {"desc_ztxt.png", {8, PNG_COLOR_TYPE_RGB, 0, 0, 0, 0, 0, 0, "description", "zipped words", 1}, NATIVE},
        {"desc_itxt.png", {8, PNG_COLOR_TYPE_RGB, 0, 0, 0, 0, 0, 0, "Description", "\xc3\xa9t\xc3\xa9 UTF-8", 2}, NATIVE},
        {"other_text.png", {8, PNG_COLOR_TYPE_RGB, 0, 0, 0, 0, 0, 0, "Software", "a test", 0}, NATIVE},
        /* left to OIIO: colour chunks not mapped here, metadata that could name our fields */
        {"gamma18.png", {8, PNG_COLOR_TYPE_RGB, 0, 55556, 0, 0, 0, 0, 0, 0, 0}, DEFER},
        {"chrm.png", {8, PNG_COLOR_TYPE_RGB, 0, 0, 0, 1, 0, 0, 0, 0, 0}, DEFER},
        {"xmp.png", {8, PNG_COLOR_TYPE_RGB, 0, 0, 0, 0, 0, 0, "XML:com.adobe.xmp", "<x/>", 2}, DEFER},
        {"imagedesc.png", {8, PNG_COLOR_TYPE_RGB, 0, 0, 0, 0, 0, 0, "ImageDescription", "x", 0}, DEFER},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        write_png_custom(sl_test_path(cases[i].name), 37, 29, &cases[i].o);
        compare_file(sl_test_path(cases[i].name), cases[i].expect);
    }
    /* the descriptions and colour flags themselves, not only their agreement with OIIO */
    sl_image img;
    if (sl_image_decode_native(&img, sl_test_path("desc_text.png"), NULL, 0)) {
        CHECK(!strcmp(img.source_description, "shadelab-rgbe8"));
        CHECK(!img.source_srgb);
        sl_image_free(&img);
    }
    if (sl_image_decode_native(&img, sl_test_path("gamma22.png"), NULL, 0)) {
        CHECK(img.source_srgb);
        sl_image_free(&img);
    }
    free(rgba);
}

static void test_jpegs(void) {
    int w = 77, h = 51;
    float *rgba = make_rgba(w, h);
    char err[1024];
    CHECK(sl_image_write(sl_test_path("oiio.jpg"), rgba, w, h, true, err, sizeof err));
    compare_file(sl_test_path("oiio.jpg"), NATIVE);
    unsigned char *b = malloc((size_t)w * h * 4), *g = malloc((size_t)w * h);
    sl_image_to_rgba8(rgba, w, h, true, b);
    for (size_t i = 0; i < (size_t)w * h; i++) g[i] = b[i * 4 + 1];
    CHECK(sl_oiio_write(sl_test_path("oiio_grey.jpg"), "jpeg", g, NULL, w, h, 1, "uint8", 90, err, sizeof err));
    compare_file(sl_test_path("oiio_grey.jpg"), NATIVE);
    free(b);
    free(g);

    unsigned char exif[160], exif_desc[160];
    size_t exif_n = make_exif(exif, NULL), exif_desc_n = make_exif(exif_desc, "a caption");
    static const unsigned char xmp[] = "http://ns.adobe.com/xap/1.0/\0<x:xmpmeta/>";
    struct {
        const char *name;
        jpeg_opts o;
        int expect;
    } cases[] = {
        {"s420.jpg", {false, false, 2, 2, NULL, NULL, 0}, NATIVE},
        {"s422.jpg", {false, false, 2, 1, NULL, NULL, 0}, NATIVE},
        {"s444.jpg", {false, false, 1, 1, NULL, NULL, 0}, NATIVE},
        {"grey.jpg", {true, false, 0, 0, NULL, NULL, 0}, NATIVE},
        {"progressive.jpg", {false, true, 2, 2, NULL, NULL, 0}, NATIVE},
        {"comment.jpg", {false, false, 2, 2, "a comment", NULL, 0}, NATIVE},
        {"exif.jpg", {false, false, 2, 2, "after exif", exif, exif_n}, NATIVE},
        {"exif_desc.jpg", {false, false, 2, 2, NULL, exif_desc, exif_desc_n}, DEFER},
        {"xmp.jpg", {false, false, 2, 2, NULL, xmp, sizeof xmp}, DEFER},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        write_jpeg_custom(sl_test_path(cases[i].name), w, h, &cases[i].o);
        compare_file(sl_test_path(cases[i].name), cases[i].expect);
    }
    sl_image img;
    if (sl_image_decode_native(&img, sl_test_path("comment.jpg"), NULL, 0)) {
        CHECK(!strcmp(img.source_description, "a comment"));
        CHECK(img.source_srgb && img.source_bits == 8 && !strcmp(img.source_format, "jpeg"));
        sl_image_free(&img);
    }
    free(rgba);
}

static bool have_oiiotool(void) { return system("command -v oiiotool >/dev/null 2>&1") == 0; }

static void test_exrs(void) {
    int w = 61, h = 300; /* more rows than a chunk of any compression (DWAB: 256) */
    float *rgba = make_rgba(w, h);
    /* values a half cannot hold exactly, negatives, the half range's edges, NaN and Inf */
    rgba[0] = -2.5f, rgba[1] = 70000.0f, rgba[2] = 1e-7f, rgba[4] = NAN, rgba[5] = INFINITY, rgba[6] = -INFINITY;
    rgba[8] = 6.1e-5f, rgba[9] = 3.3333333f;
    char err[1024];
    CHECK(sl_image_write(sl_test_path("oiio_half.exr"), rgba, w, h, false, err, sizeof err));
    compare_file(sl_test_path("oiio_half.exr"), NATIVE);
    float *rgb = malloc((size_t)w * h * 12), *one = malloc((size_t)w * h * 4);
    for (size_t i = 0; i < (size_t)w * h; i++) {
        for (int c = 0; c < 3; c++) rgb[i * 3 + c] = rgba[i * 4 + c] * 3.0f;
        one[i] = rgba[i * 4 + 1];
    }
    CHECK(sl_oiio_write(sl_test_path("oiio_float.exr"), "openexr", NULL, rgb, w, h, 3, "float", 0, err, sizeof err));
    compare_file(sl_test_path("oiio_float.exr"), NATIVE);
    CHECK(sl_oiio_write(sl_test_path("oiio_one.exr"), "openexr", NULL, one, w, h, 1, "half", 0, err, sizeof err));
    compare_file(sl_test_path("oiio_one.exr"), EITHER); /* one channel: OIIO names it (Y: native, else OIIO) */
    free(rgb);
    free(one);

    if (!have_oiiotool()) {
        printf("note: oiiotool not found: EXR compressions and channel layouts not compared\n");
        free(rgba);
        return;
    }
    static const char *const comps[] = {"none", "rle", "zips", "zip", "piz", "pxr24", "b44", "b44a", "dwaa", "dwab"};
    for (int t = 0; t < 2; t++) {
        const char *type = t ? "float" : "half";
        char cmd[8192];
        int len = snprintf(cmd, sizeof cmd, "oiiotool '%s' -d %s", sl_test_path("oiio_half.exr"), type);
        for (size_t i = 0; i < sizeof comps / sizeof *comps; i++) {
            char name[64];
            snprintf(name, sizeof name, "%s_%s.exr", type, comps[i]);
            len += snprintf(cmd + len, sizeof cmd - len, " --compression %s -o '%s'", comps[i], sl_test_path(name));
        }
        CHECK_MSG(system(cmd) == 0, "%s", cmd);
        for (size_t i = 0; i < sizeof comps / sizeof *comps; i++) {
            char name[64];
            snprintf(name, sizeof name, "%s_%s.exr", type, comps[i]);
            /* every compression is native: DWA (OpenEXRCore 3.1 cannot decompress it) and B44 on float
             * (3.1.5 gets it wrong) through OpenEXR's C++ library in shadelab-exr.so (image_native.c),
             * still bit for bit OIIO's values */
            compare_file(sl_test_path(name), NATIVE);
        }
    }
    static const char *const variants[][2] = {
        {"ya.exr", "--ch Y=R,A=A"},
        {"y.exr", "--ch Y=G"},
        {"comments.exr", "--attrib ImageDescription 'an EXR comment'"},
        {"rg.exr", "--ch R,G"},
        {"tiled.exr", "--tile 32 32"},
        {"window.exr", "--origin +4+6 --fullsize 80x320+0+0"},
        {"rgbz.exr", "--chnames R,G,B,Z"},
        {"mixed.exr", "-d R=float,G=half,B=half,A=half"},
    };
    for (size_t i = 0; i < sizeof variants / sizeof *variants; i++) {
        char cmd[4096];
        snprintf(cmd, sizeof cmd, "oiiotool '%s' %s -o '%s'", sl_test_path("oiio_half.exr"), variants[i][1], sl_test_path(variants[i][0]));
        CHECK_MSG(system(cmd) == 0, "%s", cmd);
    }
    compare_file(sl_test_path("ya.exr"), NATIVE);
    compare_file(sl_test_path("y.exr"), NATIVE);
    compare_file(sl_test_path("comments.exr"), NATIVE);
    compare_file(sl_test_path("rg.exr"), DEFER);
    compare_file(sl_test_path("tiled.exr"), DEFER);
    compare_file(sl_test_path("window.exr"), DEFER);
    compare_file(sl_test_path("rgbz.exr"), DEFER);
    compare_file(sl_test_path("mixed.exr"), DEFER);
    sl_image img;
    if (sl_image_decode_native(&img, sl_test_path("comments.exr"), NULL, 0)) {
        CHECK(!strcmp(img.source_description, "an EXR comment"));
        CHECK(img.source_float && !img.source_srgb && img.source_bits == 16);
        sl_image_free(&img);
    }
    free(rgba);
}

/* Real files from Debian packages and the shared assets: whichever way each goes, the results agree. */
static void test_real_files(void) {
    static const char *const patterns[] = {
        "/usr/share/blender/datafiles/studiolights/world/*.exr",
        SL_SOURCE_DIR "/../shared/assets/head/*.jpg",
        "/usr/share/assimp/models/*/*.png", /* assimp-testmodels */
        "/usr/share/assimp/models/*/*.jpg",
        "/usr/share/assimp/models/*/*/*.png",
        "/usr/share/assimp/models/*/*/*.jpg",
        "/usr/share/glmark2/textures/*.png",
        "/usr/share/glmark2/textures/*.jpg",
    };
    for (size_t p = 0; p < sizeof patterns / sizeof *patterns; p++) {
        glob_t g;
        if (glob(patterns[p], 0, NULL, &g) != 0) {
            printf("note: no files match %s (package or assets absent): not compared\n", patterns[p]);
            continue;
        }
        int took = 0, n = 0;
        for (size_t i = 0; i < g.gl_pathc && n < 24; i++, n++) took += compare_file(g.gl_pathv[i], EITHER);
        printf("%s: %d files compared, %d decoded natively\n", patterns[p], n, took);
        globfree(&g);
    }
}

/* Damage: truncated and corrupted copies (files and memory) never crash and give what OIIO gives (its
 * message, or its recovered pixels): the native decoder leaves them all to it. */
static void test_damage(void) {
    static const char *const names[] = {"oiio.jpg", "progressive.jpg", "oiio_rgba.png", "interlaced.png",
                                        "oiio_half.exr", "half_piz.exr", "float_dwab.exr"};
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        size_t n = 0;
        unsigned char *d = sl_test_read_file(sl_test_path(names[i]), &n);
        if (!d || n < 64) {
            free(d);
            continue;
        }
        static const double cuts[] = {0.02, 0.3, 0.6, 0.97};
        for (int c = 0; c < 4; c++) {
            char name[96];
            snprintf(name, sizeof name, "trunc%d_%s", c, names[i]);
            sl_test_write_file(sl_test_path(name), d, (size_t)(n * cuts[c]));
            compare_file(sl_test_path(name), DEFER);
        }
        /* corruption: bytes flipped through the middle of the data */
        unsigned char *bad = malloc(n);
        memcpy(bad, d, n);
        for (size_t k = n / 3; k < n - 8; k += n / 16 + 1) bad[k] ^= 0x5a;
        char name[96];
        snprintf(name, sizeof name, "corrupt_%s", names[i]);
        sl_test_write_file(sl_test_path(name), bad, n);
        compare_file(sl_test_path(name), EITHER); /* a flip can land where nothing is checked */
        free(bad);
        free(d);
    }
}

/* Over the limits: the native path leaves the header to OIIO, which gives the "over the limit" message. */
static void test_limits(void) {
    /* a PNG claiming 20000x1: IHDR, a (short) IDAT, IEND */
    static const unsigned char sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    unsigned char f[128];
    size_t len = 8;
    memcpy(f, sig, 8);
    static const unsigned char ihdr[] = {0, 0, 0, 13, 'I', 'H', 'D', 'R', 0, 0, 0x4e, 0x20, 0, 0, 0, 1, 8, 0, 0, 0, 0};
    static const unsigned char idat[] = {0, 0, 0, 2, 'I', 'D', 'A', 'T', 0x78, 0x01};
    static const unsigned char iend[] = {0, 0, 0, 0, 'I', 'E', 'N', 'D'};
    const unsigned char *chunks[] = {ihdr, idat, iend};
    size_t sizes[] = {sizeof ihdr, sizeof idat, sizeof iend};
    for (int k = 0; k < 3; k++) {
        memcpy(f + len, chunks[k], sizes[k]);
        uint32_t c = 0xffffffffu; /* the chunk's CRC-32, over type and data */
        for (size_t i = 4; i < sizes[k]; i++) {
            c ^= chunks[k][i];
            for (int b = 0; b < 8; b++) c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
        }
        c ^= 0xffffffffu;
        unsigned char cb[4] = {(unsigned char)(c >> 24), (unsigned char)(c >> 16), (unsigned char)(c >> 8), (unsigned char)c};
        memcpy(f + len + sizes[k], cb, 4);
        len += sizes[k] + 4;
    }
    sl_test_write_file(sl_test_path("wide.png"), f, len);
    compare_file(sl_test_path("wide.png"), DEFER);
    sl_image img;
    char err[1024] = "";
    CHECK(!sl_image_load(&img, sl_test_path("wide.png"), err, sizeof err));
    CHECK_CONTAINS(err, "over the limit");
}

/* The child: loads a JPEG, a PNG and an EXR (file and memory) and checks that shadelab-oiio.so was not
 * opened; then a .hdr, which only OIIO reads, still loads, and the module is then mapped. */
static bool oiio_mapped(void) { return sl_test_mapped("shadelab-oiio"); }

static int child_lazy(const char *dir) {
    char path[4096], err[1024];
    static const char *const files[] = {"oiio.jpg", "oiio_rgba.png", "oiio_half.exr", "float_piz.exr", "palette_trns.png"};
    sl_image img;
    for (size_t i = 0; i < sizeof files / sizeof *files; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[i]);
        CHECK_MSG(sl_image_load(&img, path, err, sizeof err), "%s", err);
        sl_image_free(&img);
        size_t n = 0;
        unsigned char *d = sl_test_read_file(path, &n);
        CHECK_MSG(d && sl_image_load_memory(&img, d, n, path, err, sizeof err), "%s", err);
        sl_image_free(&img);
        free(d);
    }
    CHECK_MSG(!oiio_mapped(), "shadelab-oiio.so was opened to read JPEG, PNG and EXR files");
    snprintf(path, sizeof path, "%s/%s", dir, "other.hdr");
    CHECK_MSG(sl_image_load(&img, path, err, sizeof err), "%s", err);
    CHECK(!strcmp(img.source_format, "hdr"));
    sl_image_free(&img);
    CHECK_MSG(oiio_mapped(), "a .hdr loaded without OpenImageIO's module?");
    return check_result();
}

static void test_lazy(void) {
    int w = 16, h = 8;
    float *rgba = make_rgba(w, h);
    char err[1024];
    CHECK(sl_image_write(sl_test_path("other.hdr"), rgba, w, h, false, err, sizeof err));
    free(rgba);
    pid_t pid = fork();
    if (pid == 0) {
        unsetenv("SHADELAB_IMAGE_DECODER");
        execl("/proc/self/exe", "test_image_native", "--lazy-child", sl_test_dir(), (char *)NULL);
        _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 0, "the lazy-loading child failed (status %d)", status);
}

int main(int argc, char **argv) {
    /* The decoded-image cache (image_cache.c) off, in the child too: a file deferred to OIIO is then
     * decoded by OIIO, not taken from an entry an earlier run left in the shared test cache, and the
     * .hdr the child loads last must open the module. The cache has its own test (test_image_cache). */
    setenv("SHADELAB_IMAGE_CACHE", "0", 1);
    if (argc == 3 && !strcmp(argv[1], "--lazy-child")) return child_lazy(argv[2]);
    test_pngs();
    test_jpegs();
    test_exrs();
    test_real_files();
    test_damage();
    test_limits();
    test_lazy();
    printf("%d files compared, %d decoded natively\n", compared, native_count);
    return check_result();
}
