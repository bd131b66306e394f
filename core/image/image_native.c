/* Native decoders for the common image formats: JPEG (libjpeg), PNG (libpng) and OpenEXR (OpenEXRCore, the
 * C library of OpenEXR: libz and libc only). Why: OpenImageIO's module costs ≈ 0.42 s to open (≈ 250 shared
 * libraries) and holds the dynamic loader's lock meanwhile, which delays Mesa's context creation on the main
 * thread (image.h). The rule: a file is decoded here only when it is the plain common case and the result is
 * exactly what the OpenImageIO path gives (same size, the same float bits, the same source_* fields); anything
 * else, including every error and warning a library reports, returns "not handled" and image.c's decode() goes
 * on with OpenImageIO as before, so its messages, its damage recovery and every exotic feature stay as they
 * were. tests/test_image_native.c compares both paths bit for bit. */
#define SL_IMAGE_INTERNAL
#include "image/image.h"
#include "log.h"

#include <ctype.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <jpeglib.h>
#include <png.h>
#include <OpenEXR/openexr.h>

/* ---- shared ----------------------------------------------------------------------------- */

/* Integer samples to float as OpenImageIO 2.4 converts them (convert_type<uint8_t/uint16_t, float>: a
 * multiplication by the float reciprocal, which differs from v/255.0f in 126 of the 256 codes);
 * tests/test_image_native.c checks every 8- and 16-bit code against OIIO. */
static inline float from_u8(unsigned v) { return (float)v * (1.0f / 255.0f); }
static inline float from_u16(unsigned v) { return (float)v * (1.0f / 65535.0f); }

static bool dims_ok(uint64_t w, uint64_t h) {
    return w >= 1 && h >= 1 && w <= SL_IMAGE_MAX_DIM && h <= SL_IMAGE_MAX_DIM && w * h <= (uint64_t)SL_IMAGE_MAX_PIXELS;
}

static bool ext_in(const char *ext, const char *const *list) {
    for (; *list; list++)
        if (!strcmp(ext, *list)) return true;
    return false;
}

/* Expands n pixels of `ch` interleaved float channels (1 grey, 2 grey+alpha, 3 RGB, 4 RGBA) to RGBA in
 * place, from the last pixel back, as decode() does for OIIO's channels. */
static void expand_rgba(float *buf, size_t n, int ch) {
    if (ch == 4) return;
    for (size_t i = n; i-- > 0;) {
        const float *s = buf + i * ch;
        float r, g, b, a = 1.0f;
        if (ch == 1) r = g = b = s[0];
        else if (ch == 2) r = g = b = s[0], a = s[1];
        else r = s[0], g = s[1], b = s[2];
        float *d = buf + i * 4;
        d[0] = r, d[1] = g, d[2] = b, d[3] = a;
    }
}

static void fill(sl_image *img, int w, int h, float *pixels, int bits, bool is_float, bool srgb, int channels,
                 const char *desc, size_t desc_len, const char *format) {
    img->width = w;
    img->height = h;
    img->channels = 4;
    img->pixels = pixels;
    img->source_bits = bits;
    img->source_float = is_float;
    img->source_srgb = srgb;
    img->source_channels = channels;
    /* what OIIO's string holds, read as a C string (copy_str in image_oiio.cpp): up to the first NUL */
    size_t n = 0;
    while (desc && n < desc_len && desc[n]) n++;
    snprintf(img->source_description, sizeof img->source_description, "%.*s", (int)n, desc ? desc : "");
    snprintf(img->source_format, sizeof img->source_format, "%s", format);
}

/* ---- JPEG ------------------------------------------------------------------------------- */

struct jpeg_err {
    struct jpeg_error_mgr pub;
    jmp_buf jump;
};

/* Errors and warnings (corrupt data, a truncated file's inserted EOI) both end the attempt: OIIO then
 * reads the file and reports the damage as before. libjpeg never prints nor calls exit(). */
static void jpeg_fail(j_common_ptr c) { longjmp(((struct jpeg_err *)c->err)->jump, 1); }
static void jpeg_message(j_common_ptr c, int level) {
    if (level < 0) longjmp(((struct jpeg_err *)c->err)->jump, 1);
}
static void jpeg_quiet(j_common_ptr c) { (void)c; }

static uint32_t rd16(const unsigned char *p, bool le) { return le ? p[0] | (uint32_t)p[1] << 8 : (uint32_t)p[0] << 8 | p[1]; }
static uint32_t rd32(const unsigned char *p, bool le) {
    return le ? p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24
              : (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* Whether an Exif block (the TIFF structure after "Exif\0\0") is one whose metadata cannot change our fields:
 * OIIO maps its ImageDescription tag (0x010E) to ImageDescription. IFD0 and the Exif, GPS and interoperability
 * IFDs it points to are searched; anything malformed is "not plain" too. */
static bool exif_plain(const unsigned char *p, size_t n) {
    if (n < 8) return false;
    bool le;
    if (p[0] == 'I' && p[1] == 'I') le = true;
    else if (p[0] == 'M' && p[1] == 'M') le = false;
    else return false;
    if (rd16(p + 2, le) != 42) return false;
    uint32_t todo[8];
    int ntodo = 0, visited = 0;
    todo[ntodo++] = rd32(p + 4, le);
    while (ntodo > 0) {
        uint32_t off = todo[--ntodo];
        if (++visited > 8 || off < 8 || off > n - 2) return false;
        uint32_t count = rd16(p + off, le);
        if ((uint64_t)off + 2 + 12ull * count > n) return false;
        for (uint32_t i = 0; i < count; i++) {
            const unsigned char *e = p + off + 2 + 12 * i;
            uint32_t tag = rd16(e, le);
            if (tag == 0x010E) return false;
            if (tag == 0x8769 || tag == 0x8825 || tag == 0xA005) {
                if (ntodo == (int)(sizeof todo / sizeof *todo)) return false;
                todo[ntodo++] = rd32(e + 8, le);
            }
        }
    }
    return true;
}

static bool native_jpeg(sl_image *img, FILE *f, const unsigned char *data, size_t size) {
    struct jpeg_decompress_struct cinfo;
    struct jpeg_err jerr;
    float *volatile out = NULL;
    volatile bool created = false;
    cinfo.err = jpeg_std_error(&jerr.pub);
    jerr.pub.error_exit = jpeg_fail;
    jerr.pub.emit_message = jpeg_message;
    jerr.pub.output_message = jpeg_quiet;
    if (setjmp(jerr.jump)) {
        if (created) jpeg_destroy_decompress(&cinfo);
        free(out);
        return false;
    }
    jpeg_create_decompress(&cinfo);
    created = true;
    if (f) jpeg_stdio_src(&cinfo, f);
    else jpeg_mem_src(&cinfo, data, (unsigned long)size);
    /* the markers OIIO reads metadata from: Exif/XMP (APP1), ICC (APP2), IPTC (APP13), comments */
    jpeg_save_markers(&cinfo, JPEG_APP0 + 1, 0xFFFF);
    jpeg_save_markers(&cinfo, JPEG_APP0 + 2, 0xFFFF);
    jpeg_save_markers(&cinfo, JPEG_APP0 + 13, 0xFFFF);
    jpeg_save_markers(&cinfo, JPEG_COM, 0xFFFF);
    if (jpeg_read_header(&cinfo, TRUE) != JPEG_HEADER_OK) longjmp(jerr.jump, 1);

    int ncomp = cinfo.num_components;
    bool plain = cinfo.data_precision == 8 && dims_ok(cinfo.image_width, cinfo.image_height) &&
                 ((cinfo.jpeg_color_space == JCS_GRAYSCALE && ncomp == 1) ||
                  ((cinfo.jpeg_color_space == JCS_YCbCr || cinfo.jpeg_color_space == JCS_RGB) && ncomp == 3));
    const char *desc = NULL;
    size_t desc_len = 0;
    for (jpeg_saved_marker_ptr m = cinfo.marker_list; plain && m; m = m->next) {
        if (m->marker == JPEG_APP0 + 1) {
            /* Exif without an ImageDescription; XMP and anything else in APP1 go to OIIO */
            plain = m->data_length >= 6 && !memcmp(m->data, "Exif\0", 5) && exif_plain(m->data + 6, m->data_length - 6);
        } else if (m->marker == JPEG_APP0 + 2) {
            plain = !(m->data_length >= 12 && !memcmp(m->data, "ICC_PROFILE", 12)); /* a colour profile */
        } else if (m->marker == JPEG_APP0 + 13) {
            plain = !(m->data_length >= 13 && !memcmp(m->data, "Photoshop 3.0", 13)); /* IPTC: a caption */
        } else if (m->marker == JPEG_COM && !desc) {
            desc = (const char *)m->data; /* OIIO keeps the first comment */
            desc_len = m->data_length;
        }
    }
    if (!plain) longjmp(jerr.jump, 1);

    /* OIIO's settings: libjpeg's defaults (JDCT_ISLOW, fancy upsampling), RGB or grey output */
    jpeg_start_decompress(&cinfo);
    int w = (int)cinfo.output_width, h = (int)cinfo.output_height, ch = cinfo.output_components;
    if ((ch != 1 && ch != 3) || ch != ncomp || w != (int)cinfo.image_width || h != (int)cinfo.image_height)
        longjmp(jerr.jump, 1);
    size_t npix = (size_t)w * (size_t)h;
    out = malloc(npix * 4 * sizeof(float));
    if (!out) longjmp(jerr.jump, 1);
    JSAMPARRAY row = (*cinfo.mem->alloc_sarray)((j_common_ptr)&cinfo, JPOOL_IMAGE, (JDIMENSION)(w * ch), 1);
    float lut[256];
    for (int v = 0; v < 256; v++) lut[v] = from_u8((unsigned)v);
    while (cinfo.output_scanline < cinfo.output_height) {
        JDIMENSION y = cinfo.output_scanline;
        if (jpeg_read_scanlines(&cinfo, row, 1) != 1) longjmp(jerr.jump, 1);
        float *d = out + (size_t)y * w * 4;
        const JSAMPLE *s = row[0];
        if (ch == 1)
            for (int x = 0; x < w; x++, d += 4) d[0] = d[1] = d[2] = lut[s[x]], d[3] = 1.0f;
        else
            for (int x = 0; x < w; x++, d += 4, s += 3) d[0] = lut[s[0]], d[1] = lut[s[1]], d[2] = lut[s[2]], d[3] = 1.0f;
    }
    /* not jpeg_finish_decompress: OIIO stops after the last scanline too, so what follows is never read */
    fill(img, w, h, out, 8, false, true, ch, desc, desc_len, "jpeg");
    created = false;
    jpeg_destroy_decompress(&cinfo);
    return true;
}

/* ---- PNG -------------------------------------------------------------------------------- */

struct png_mem {
    const unsigned char *data;
    size_t size, pos;
};

static void png_read_mem(png_structp png, png_bytep out, size_t n) {
    struct png_mem *m = png_get_io_ptr(png);
    if (n > m->size - m->pos) png_error(png, "truncated");
    memcpy(out, m->data + m->pos, n);
    m->pos += n;
}
/* errors and warnings alike end the attempt (OIIO then reads it as before); nothing is printed */
static void png_fail(png_structp png, png_const_charp msg) {
    (void)msg;
    png_longjmp(png, 1);
}

static bool key_is(const char *key, const char *name) { return key && !strcasecmp(key, name); }
static bool key_starts(const char *key, const char *prefix) { return key && !strncasecmp(key, prefix, strlen(prefix)); }

static bool native_png(sl_image *img, FILE *f, const unsigned char *data, size_t size) {
    struct png_mem mem = {data, size, 0};
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, png_fail, png_fail);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    float *volatile out = NULL;
    png_bytep *volatile rows = NULL;
    if (!png || !info || setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(png ? &png : NULL, info ? &info : NULL, NULL);
        free(out);
        free(rows);
        return false;
    }
    if (f) png_init_io(png, f);
    else png_set_read_fn(png, &mem, png_read_mem);
    png_read_info(png, info);

    png_uint_32 w, h;
    int depth, color, interlace;
    png_get_IHDR(png, info, &w, &h, &depth, &color, &interlace, NULL, NULL);
    if (!dims_ok(w, h)) png_longjmp(png, 1);
    /* colour: OIIO 2.4 says sRGB for an sRGB chunk, "linear" for gAMA 1.0, a gamma name for other gAMA
     * values and sRGB when there is neither. Only the cases tested against it are decoded here: sRGB (cHRM
     * beside it is ignored), none, gAMA 1.0 and gAMA 1/2.2. ICC profiles and Exif go to OIIO. */
    bool srgb = true;
    if (png_get_valid(png, info, PNG_INFO_iCCP) || png_get_valid(png, info, PNG_INFO_eXIf)) png_longjmp(png, 1);
    if (!png_get_valid(png, info, PNG_INFO_sRGB)) {
        if (png_get_valid(png, info, PNG_INFO_cHRM)) png_longjmp(png, 1);
        png_fixed_point gamma;
        if (png_get_gAMA_fixed(png, info, &gamma)) {
            if (gamma == PNG_FP_1) srgb = false;
            else if (gamma != 45455) png_longjmp(png, 1);
        }
    }
    /* text before the image data: OIIO maps "Description" (any case, the last one) to ImageDescription;
     * keys it decodes into other metadata (XMP, Exif) or that could name our fields go to OIIO */
    const char *desc = NULL;
    png_textp text;
    int ntext = png_get_text(png, info, &text, NULL);
    for (int i = 0; i < ntext; i++) {
        const char *key = text[i].key;
        if (key_is(key, "Description")) desc = text[i].text ? text[i].text : "";
        else if (key && !strcmp(key, "oiio:ColorSpace") && text[i].text && !strcmp(text[i].text, "sRGB"))
            srgb = true; /* OIIO's own PNG writer adds it; OIIO reads it back as the colour space */
        else if (key && !strcmp(key, "oiio:ColorSpace") && text[i].text && !strcmp(text[i].text, "Linear"))
            srgb = false;
        else if (key_is(key, "XML:com.adobe.xmp") || key_starts(key, "Raw profile type") ||
                 key_is(key, "ImageDescription") || key_starts(key, "oiio:"))
            png_longjmp(png, 1);
    }

    /* OIIO's transformations: palette → RGB, grey < 8 bits → 8, tRNS → alpha (png_set_expand) */
    png_set_expand(png);
    png_set_interlace_handling(png); /* what png_read_image would turn on, with a warning */
    png_read_update_info(png, info);
    int ch = png_get_channels(png, info), bits = png_get_bit_depth(png, info);
    size_t rowbytes = png_get_rowbytes(png, info);
    if (ch < 1 || ch > 4 || (bits != 8 && bits != 16) || rowbytes != (size_t)w * ch * (bits / 8))
        png_longjmp(png, 1);
    /* the file's rows are read into the tail of the float buffer and converted forward: a float pixel
     * written never reaches a source pixel not yet read (16 bytes per pixel ≥ the source's) */
    size_t npix = (size_t)w * h, total = npix * 4 * sizeof(float), raw = rowbytes * h;
    out = malloc(total);
    rows = malloc(h * sizeof *rows);
    if (!out || !rows) png_longjmp(png, 1);
    unsigned char *base = (unsigned char *)out + (total - raw);
    for (png_uint_32 y = 0; y < h; y++) rows[y] = base + (size_t)y * rowbytes;
    png_read_image(png, rows);
    png_read_end(png, NULL); /* trailing chunks' damage: an error, hence OIIO */

    size_t nsamp = npix * ch;
    float *d = out;
    if (bits == 8) {
        float lut[256];
        for (int v = 0; v < 256; v++) lut[v] = from_u8((unsigned)v);
        for (size_t i = 0; i < nsamp; i++) d[i] = lut[base[i]];
    } else {
        for (size_t i = 0; i < nsamp; i++) d[i] = from_u16((unsigned)base[2 * i] << 8 | base[2 * i + 1]);
    }
    expand_rgba(out, npix, ch);
    fill(img, (int)w, (int)h, out, bits, false, srgb, ch, desc, desc ? strlen(desc) : 0, "png");
    out = NULL;
    free(rows);
    png_destroy_read_struct(&png, &info, NULL);
    return true;
}

/* ---- OpenEXR ---------------------------------------------------------------------------- */

struct exr_mem {
    const unsigned char *data;
    size_t size;
};

static int64_t exr_read_mem(exr_const_context_t c, void *user, void *buf, uint64_t sz, uint64_t off,
                            exr_stream_error_func_ptr_t error_cb) {
    (void)c, (void)error_cb;
    const struct exr_mem *m = user;
    if (off >= m->size) return 0;
    uint64_t n = m->size - off;
    if (n > sz) n = sz;
    memcpy(buf, m->data + off, n);
    return (int64_t)n;
}
static int64_t exr_size_mem(exr_const_context_t c, void *user) {
    (void)c;
    return (int64_t)((const struct exr_mem *)user)->size;
}
static void exr_quiet(exr_const_context_t c, exr_result_t code, const char *msg) { (void)c, (void)code, (void)msg; }

/* Exact half → float, NaN payloads kept (what Imath's table holds). */
static float half_to_float(uint16_t h) {
    uint32_t sign = (uint32_t)(h & 0x8000) << 16, exp = (h >> 10) & 0x1f, mant = h & 0x3ff, bits;
    if (exp == 0) {
        if (mant == 0) bits = sign;
        else { /* subnormal: normalise */
            int e = -1;
            do {
                e++;
                mant <<= 1;
            } while (!(mant & 0x400));
            bits = sign | (uint32_t)(127 - 15 - e) << 23 | (mant & 0x3ff) << 13;
        }
    } else if (exp == 31) {
        bits = sign | 0x7f800000u | mant << 13;
    } else {
        bits = sign | (exp + 127 - 15) << 23 | mant << 13;
    }
    float v;
    memcpy(&v, &bits, sizeof v);
    return v;
}

/* n pixels of nch interleaved samples (half: bpe 2, else float) → RGBA in OIIO's order: file channel i
 * goes to slot[i] (R,G,B,A or Y,A); grey is replicated, a missing alpha is 1. */
static void convert(const unsigned char *tmp, size_t n, int nch, size_t bpe, const int *slot, bool grey, float *d) {
    for (size_t p = 0; p < n; p++, d += 4) {
        float v[4] = {0, 0, 0, 1};
        for (int i = 0; i < nch; i++) {
            const unsigned char *s = tmp + (p * nch + i) * bpe;
            if (bpe == 2) {
                uint16_t hv;
                memcpy(&hv, s, 2);
                v[slot[i]] = half_to_float(hv);
            } else {
                memcpy(&v[slot[i]], s, 4);
            }
        }
        if (grey) d[0] = d[1] = d[2] = v[0], d[3] = nch == 2 ? v[1] : 1.0f;
        else d[0] = v[0], d[1] = v[1], d[2] = v[2], d[3] = nch == 4 ? v[3] : 1.0f;
    }
}

static bool native_exr(sl_image *img, const char *path, const unsigned char *data, size_t size) {
    struct exr_mem mem = {data, size};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_quiet;
    /* damaged chunk tables are an error here (OIIO has its own recovery and messages) */
    init.flags = EXR_CONTEXT_FLAG_SILENT_HEADER_PARSE | EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    if (data) {
        init.user_data = &mem;
        init.read_fn = exr_read_mem;
        init.size_fn = exr_size_mem;
    }
    exr_context_t ctx = NULL;
    if (exr_start_read(&ctx, path, &init) != EXR_ERR_SUCCESS) {
        exr_finish(&ctx);
        return false;
    }
    bool ok = false;
    float *out = NULL;
    unsigned char *tmp = NULL;
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    bool dec_init = false;

    int parts = 0;
    exr_storage_t storage;
    exr_attr_box2i_t dw, disp;
    exr_compression_t comp;
    const exr_attr_chlist_t *chl = NULL;
    int32_t lpc = 0;
    if (exr_get_count(ctx, &parts) || parts != 1 || exr_get_storage(ctx, 0, &storage) ||
        storage != EXR_STORAGE_SCANLINE || exr_get_data_window(ctx, 0, &dw) || exr_get_display_window(ctx, 0, &disp) ||
        exr_get_compression(ctx, 0, &comp) || exr_get_channels(ctx, 0, &chl) || !chl ||
        exr_get_scanlines_per_chunk(ctx, 0, &lpc) || lpc < 1)
        goto done;
    /* OIIO reads the data window; only files whose data window is the display window are decoded here */
    if (memcmp(&dw, &disp, sizeof dw)) goto done;
    int64_t w64 = (int64_t)dw.max.x - dw.min.x + 1, h64 = (int64_t)dw.max.y - dw.min.y + 1;
    if (w64 < 1 || h64 < 1 || !dims_ok((uint64_t)w64, (uint64_t)h64)) goto done;
    int w = (int)w64, h = (int)h64;
    /* the compressions whose results are checked bit for bit against OpenEXR's C++ library through OIIO
     * (tests/test_image_native.c). DWAA/DWAB (OpenEXRCore 3.1 cannot decompress them: "not yet
     * implemented, please use C++ library") and B44/B44A on float channels (3.1.5 decodes them wrongly:
     * every sample differed in the test; on half channels they agree) are read by OpenEXR's C++ library,
     * the one OIIO reads them with, in the module shadelab-exr.so (image_exr.cpp), opened only then. */
    if (comp != EXR_COMPRESSION_NONE && comp != EXR_COMPRESSION_RLE && comp != EXR_COMPRESSION_ZIPS &&
        comp != EXR_COMPRESSION_ZIP && comp != EXR_COMPRESSION_PIZ && comp != EXR_COMPRESSION_PXR24 &&
        comp != EXR_COMPRESSION_B44 && comp != EXR_COMPRESSION_B44A && comp != EXR_COMPRESSION_DWAA &&
        comp != EXR_COMPRESSION_DWAB)
        goto done;

    /* channels: exactly R,G,B[,A] or Y[,A] (the file lists them sorted: A first), one sample type (half
     * or float), no subsampling. slot[] is each file channel's place in OIIO's order (R,G,B,A / Y,A). */
    int nch = chl->num_channels, slot[4];
    if (nch < 1 || nch > 4) goto done;
    exr_pixel_type_t type = chl->entries[0].pixel_type;
    if (type != EXR_PIXEL_HALF && type != EXR_PIXEL_FLOAT) goto done;
    bool grey = nch <= 2;
    unsigned seen = 0;
    for (int i = 0; i < nch; i++) {
        const exr_attr_chlist_entry_t *e = &chl->entries[i];
        if (e->pixel_type != type || e->x_sampling != 1 || e->y_sampling != 1 || !e->name.str) goto done;
        static const char *const rgba[] = {"R", "G", "B", "A"}, *const ya[] = {"Y", "A"};
        const char *const *names = grey ? ya : rgba;
        int s = -1;
        for (int k = 0; k < nch; k++)
            if (e->name.length == 1 && !strcmp(e->name.str, names[k])) s = k;
        if (s < 0 || (seen & (1u << s))) goto done;
        seen |= 1u << s;
        slot[i] = s;
    }
    if (nch == 3 && grey) goto done;
    bool by_cpp_library = comp == EXR_COMPRESSION_DWAA || comp == EXR_COMPRESSION_DWAB ||
                          ((comp == EXR_COMPRESSION_B44 || comp == EXR_COMPRESSION_B44A) && type != EXR_PIXEL_HALF);

    /* metadata: OIIO maps "comments" to ImageDescription; an attribute of that very name goes to OIIO */
    const exr_attribute_t *attr = NULL;
    const char *desc = NULL;
    size_t desc_len = 0;
    if (exr_get_attribute_by_name(ctx, 0, "ImageDescription", &attr) == EXR_ERR_SUCCESS) goto done;
    if (exr_get_attribute_by_name(ctx, 0, "comments", &attr) == EXR_ERR_SUCCESS) {
        if (attr->type != EXR_ATTR_STRING || !attr->string) goto done;
        desc = attr->string->str;
        desc_len = attr->string->length > 0 ? (size_t)attr->string->length : 0;
    }

    size_t bpe = type == EXR_PIXEL_HALF ? 2 : 4, npix = (size_t)w * h;
    out = malloc(npix * 4 * sizeof(float));
    tmp = malloc((by_cpp_library ? npix : (size_t)lpc * w) * nch * bpe);
    if (!out || !tmp) goto done;
    if (by_cpp_library) {
        const char *names[4];
        for (int i = 0; i < nch; i++) names[i] = chl->entries[i].name.str;
        char why[512];
        if (!sl_exr_read(path, data, size, dw.min.x, dw.min.y, w, h, nch, names, bpe == 2, tmp, why, sizeof why)) {
            SL_DEBUG("%s: %s; OpenImageIO reads it", path, why);
            goto done;
        }
        convert(tmp, npix, nch, bpe, slot, grey, out);
    } else {
        for (int64_t y = dw.min.y; y <= dw.max.y; y += lpc) {
            exr_chunk_info_t ci;
            if (exr_read_scanline_chunk_info(ctx, 0, (int)y, &ci) != EXR_ERR_SUCCESS) goto done;
            if (ci.start_y != y || ci.height < 1 || ci.height > lpc || ci.start_y + (int64_t)ci.height - 1 > dw.max.y ||
                ci.width != w)
                goto done;
            exr_result_t r = dec_init ? exr_decoding_update(ctx, 0, &ci, &dec) : exr_decoding_initialize(ctx, 0, &ci, &dec);
            if (r != EXR_ERR_SUCCESS) goto done;
            dec_init = true;
            if (dec.channel_count != nch) goto done;
            for (int i = 0; i < nch; i++) {
                exr_coding_channel_info_t *c = &dec.channels[i];
                if (c->width != w || c->height != ci.height || c->bytes_per_element != (int)bpe) goto done;
                c->decode_to_ptr = tmp + (size_t)i * bpe;
                c->user_pixel_stride = (int32_t)(nch * bpe);
                c->user_line_stride = (int32_t)((size_t)w * nch * bpe);
                c->user_bytes_per_element = (int16_t)bpe;
                c->user_data_type = (uint16_t)type;
            }
            if (exr_decoding_choose_default_routines(ctx, 0, &dec) != EXR_ERR_SUCCESS ||
                exr_decoding_run(ctx, 0, &dec) != EXR_ERR_SUCCESS)
                goto done;
            convert(tmp, (size_t)ci.height * w, nch, bpe, slot, grey, out + (size_t)(ci.start_y - dw.min.y) * w * 4);
        }
    }
    fill(img, w, h, out, (int)bpe * 8, true, false, nch, desc, desc_len, "openexr");
    out = NULL;
    ok = true;
done:
    if (dec_init) exr_decoding_destroy(ctx, &dec);
    exr_finish(&ctx);
    free(out);
    free(tmp);
    return ok;
}

/* ---- entry ------------------------------------------------------------------------------ */

bool sl_image_decode_native(sl_image *img, const char *path, const void *data, size_t size) {
    static const char *const jpeg_ext[] = {"jpg", "jpe", "jpeg", "jif", "jfif", "jfi", NULL};
    static const char *const png_ext[] = {"png", NULL};
    static const char *const exr_ext[] = {"exr", "sxr", "mxr", NULL};
    char ext[16];
    sl_image_path_extension(path, ext, sizeof ext);
    /* the reader OIIO tries first is the extension's; a file whose content is another format goes to OIIO,
     * which tries its readers in turn */
    enum { NONE, JPEG, PNG, EXR } kind = ext_in(ext, jpeg_ext) ? JPEG : ext_in(ext, png_ext) ? PNG
                                       : ext_in(ext, exr_ext)  ? EXR : NONE;
    if (kind == NONE) return false;

    unsigned char magic[8];
    size_t have = 0;
    FILE *f = NULL;
    if (data) {
        have = size < sizeof magic ? size : sizeof magic;
        memcpy(magic, data, have);
    } else {
        f = fopen(path, "rb");
        if (!f) return false;
        have = fread(magic, 1, sizeof magic, f);
        rewind(f);
    }
    bool ok = false;
    if (kind == JPEG && have >= 3 && magic[0] == 0xFF && magic[1] == 0xD8 && magic[2] == 0xFF)
        ok = native_jpeg(img, f, data, size);
    else if (kind == PNG && have == 8 && !png_sig_cmp(magic, 0, 8))
        ok = native_png(img, f, data, size);
    else if (kind == EXR && have >= 4 && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01) {
        if (f) fclose(f), f = NULL; /* OpenEXRCore opens the file itself */
        ok = native_exr(img, path, data, size);
    }
    if (f) fclose(f);
    if (!ok) memset(img, 0, sizeof *img);
    return ok;
}
