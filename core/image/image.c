/* Images: the policy side of loading/writing (path checks, size limits, channel layout,
 * colour handling, messages), sRGB transfer functions, procedural textures, comparison and
 * small conversions. OpenImageIO is reached only through image_oiio.cpp (a module opened on first
 * use, image_modules.c); PNG output is written here with libpng. */
#define SL_IMAGE_INTERNAL
#include <png.h>
#include "image/image.h"
#include "log.h"
#include <shadelab/input.h>

#include <ctype.h>
#include <errno.h>
#include <pthread.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

static void set_err(char *err, size_t err_size, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void set_err(char *err, size_t err_size, const char *fmt, ...) {
    if (!err || !err_size) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, err_size, fmt, ap);
    va_end(ap);
}

/* ---- sRGB (IEC 61966-2-1) --------------------------------------------------------------- */

float sl_srgb_encode(float linear) {
    double x = linear;
    if (!(x > 0.0)) return 0.0f; /* NaN, -Inf, negatives, 0 */
    if (x >= 1.0) return 1.0f;   /* +Inf too */
    return (float)(x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055);
}

float sl_srgb_decode(float encoded) {
    double x = encoded;
    if (!(x > 0.0)) return 0.0f;
    if (x >= 1.0) return 1.0f;
    return (float)(x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4));
}

void sl_image_srgb_to_linear(sl_image *img) {
    if (!img || !img->pixels || img->channels < 3) return;
    size_t n = (size_t)img->width * (size_t)img->height;
    int ch = img->channels;
    /* 8-bit sources hold only 256 codes: a table makes this ~6× faster than pow per sample
     * (17 vs 100 ms for 2048², measured). A value is taken from the table only when it is
     * within 1e-4 of a code (×255), where the result differs from the formula's by < 1e-6;
     * anything else (16-bit, float, NaN) uses the formula. */
    float table[256];
    for (int k = 0; k < 256; k++) table[k] = sl_srgb_decode((float)k / 255.0f);
    for (size_t i = 0; i < n; i++) {
        float *p = img->pixels + i * ch;
        for (int c = 0; c < 3; c++) {
            float v = p[c], scaled = v * 255.0f;
            if (scaled >= 0.0f && scaled <= 255.0f) {
                int k = (int)(scaled + 0.5f);
                if (fabsf(scaled - (float)k) < 1e-4f) {
                    p[c] = table[k];
                    continue;
                }
            }
            p[c] = sl_srgb_decode(v);
        }
    }
}

/* ---- small conversions ------------------------------------------------------------------ */

void sl_image_flip_rows_raw(void *data, size_t row_bytes, int height) {
    if (!data || height < 2) return;
    unsigned char *top = data, *bottom = (unsigned char *)data + (size_t)(height - 1) * row_bytes;
    while (top < bottom) {
        for (size_t i = 0; i < row_bytes; i++) {
            unsigned char t = top[i];
            top[i] = bottom[i];
            bottom[i] = t;
        }
        top += row_bytes;
        bottom -= row_bytes;
    }
}

void sl_image_flip_rows(float *pixels, int width, int height, int channels) {
    if (width <= 0 || channels <= 0) return;
    sl_image_flip_rows_raw(pixels, (size_t)width * (size_t)channels * sizeof(float), height);
}

static float mip_decode[256];
static float mip_mid[256]; /* linear value halfway (in code space) between codes k-1 and k */
static void mip_tables(void) {
    for (int k = 0; k < 256; k++) {
        mip_decode[k] = sl_srgb_decode((float)k / 255.0f);
        mip_mid[k] = k ? sl_srgb_decode(((float)k - 0.5f) / 255.0f) : 0.0f;
    }
}

/* The source texels under destination texel i of one axis (size → max(1, size/2)), with the
 * share of each: the destination texel covers source [i·size/n, (i+1)·size/n) with n = size/2, so
 * an even side takes 2 texels by halves and an odd side 2n + 1 = size takes 3, weighted (n − i, n,
 * i + 1)/(2n + 1): the parts of texels 2i, 2i + 1 and 2i + 2 it covers. Every source texel then
 * weighs the same in the next level and a level's texel centre sees the content at its own
 * coordinate; a 2×2 box that drops an odd side's last texel stretches each level by size/(2n) —
 * 211 texels: the logo of BoxTextured.glb half a screen pixel off at 1.5 levels down. (The
 * polyphase box of NVIDIA's "Non-Power-of-Two Mipmap Creation", 2003.) */
static int mip_taps(int size, int i, int idx[3], float w[3]) {
    if (size <= 1) {
        idx[0] = 0, w[0] = 1.0f;
        return 1;
    }
    int n = size / 2;
    if (size % 2 == 0) {
        idx[0] = 2 * i, idx[1] = 2 * i + 1, w[0] = w[1] = 0.5f;
        return 2;
    }
    float d = (float)size;
    idx[0] = 2 * i, idx[1] = 2 * i + 1, idx[2] = 2 * i + 2;
    w[0] = (float)(n - i) / d, w[1] = (float)n / d, w[2] = (float)(i + 1) / d;
    return 3;
}

/* The taps of destination texel (x, y): up to 3 × 3 source offsets (in texels) and weights. */
static int mip_texel_taps(int w, int h, int x, int y, size_t off[9], float wt[9]) {
    int ix[3], iy[3], k = 0;
    float wx[3], wy[3];
    int nx = mip_taps(w, x, ix, wx), ny = mip_taps(h, y, iy, wy);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) off[k] = (size_t)iy[j] * w + (size_t)ix[i], wt[k++] = wx[i] * wy[j];
    return k;
}

void sl_image_mip_rgba8(const unsigned char *src, int w, int h, unsigned char *dst, bool srgb) {
    static pthread_once_t once = PTHREAD_ONCE_INIT;
    pthread_once(&once, mip_tables);
    const float *decode = mip_decode, *mid = mip_mid;
    int w2 = w > 1 ? w / 2 : 1, h2 = h > 1 ? h / 2 : 1;
    for (int y = 0; y < h2; y++)
        for (int x = 0; x < w2; x++) {
            size_t off[9];
            float wt[9];
            int n = mip_texel_taps(w, h, x, y, off, wt);
            unsigned char *d = dst + ((size_t)y * w2 + x) * 4;
            for (int c = 0; c < 4; c++) {
                float v = 0;
                if (srgb && c < 3) {
                    for (int q = 0; q < n; q++) v += decode[src[off[q] * 4 + c]] * wt[q];
                    /* the nearest code in encoded space: the largest k with mid[k] <= v */
                    int lo = 0, hi = 255;
                    while (lo < hi) {
                        int m = (lo + hi + 1) / 2;
                        if (mid[m] <= v) lo = m;
                        else hi = m - 1;
                    }
                    d[c] = (unsigned char)lo;
                } else {
                    for (int q = 0; q < n; q++) v += (float)src[off[q] * 4 + c] * wt[q];
                    int k = (int)floorf(v + 0.5f);
                    d[c] = (unsigned char)(k < 0 ? 0 : k > 255 ? 255 : k);
                }
            }
        }
}

void sl_image_mip_rgbaf(const float *src, int w, int h, float *dst) {
    int w2 = w > 1 ? w / 2 : 1, h2 = h > 1 ? h / 2 : 1;
    for (int y = 0; y < h2; y++)
        for (int x = 0; x < w2; x++) {
            size_t off[9];
            float wt[9];
            int n = mip_texel_taps(w, h, x, y, off, wt);
            float *d = dst + ((size_t)y * w2 + x) * 4;
            for (int c = 0; c < 4; c++) {
                float v = 0;
                for (int q = 0; q < n; q++) v += src[off[q] * 4 + c] * wt[q];
                d[c] = v;
            }
        }
}

static unsigned char to_byte(float v) {
    if (!(v > 0.0f)) return 0; /* NaN too */
    if (v >= 1.0f) return 255;
    return (unsigned char)(v * 255.0f + 0.5f);
}

void sl_image_to_rgba8(const float *rgba, int width, int height, bool display_encoded,
                       unsigned char *out) {
    if (!rgba || !out || width <= 0 || height <= 0) return;
    size_t n = (size_t)width * (size_t)height * 4;
    for (size_t i = 0; i < n; i++) {
        float v = rgba[i];
        if (i % 4 != 3 && !display_encoded) v = sl_srgb_encode(v);
        out[i] = to_byte(v);
    }
}

/* ---- paths ------------------------------------------------------------------------------ */

/* Lower-case extension without the dot ("" when none) of the last path component (image.h). */
void sl_image_path_extension(const char *path, char *ext, size_t size) {
    ext[0] = 0;
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    if (!dot || dot == base) return;
    size_t i = 0;
    for (const char *p = dot + 1; *p && i + 1 < size; p++) ext[i++] = (char)tolower((unsigned char)*p);
    ext[i] = 0;
}

/* ---- loading ---------------------------------------------------------------------------- */

static bool colorspace_is_linear(const char *cs) {
    static const char *const linear_names[] = {"linear", "scene_linear", "lin_srgb", "lin_rec709",
                                               "acescg", "aces2065-1", "lin_ap1", "lin_ap0",
                                               "gammacorrected1.0", "gamma1.0"};
    for (size_t i = 0; i < sizeof linear_names / sizeof *linear_names; i++)
        if (strcasecmp(cs, linear_names[i]) == 0) return true;
    return false;
}

static bool decode(sl_image *img, const char *path, const void *data, size_t size, char *err, size_t err_size);

/* HDR files with NaN/Inf are legal but poison shading: say so. Info, not a warning: the loader is
 * faithful (image comparisons need the values); each consumer that shades with them applies its
 * policy and warns (textures, environments). */
static void report_nonfinite(const sl_image *img, const char *path) {
    if (!img->source_float) return;
    long bad = 0;
    size_t n = (size_t)img->width * (size_t)img->height * 4;
    for (size_t i = 0; i < n; i++) bad += !isfinite(img->pixels[i]);
    if (bad) SL_INFO("%s: %ld sample%s NaN or Inf", path, bad, bad == 1 ? " is" : "s are");
}

bool sl_image_load(sl_image *img, const char *path, char *err, size_t err_size) {
    if (!img) {
        set_err(err, err_size, "%s: no output image given", path ? path : "(null)");
        return false;
    }
    memset(img, 0, sizeof *img);
    if (!path || !*path) {
        set_err(err, err_size, "(empty path): no image path given");
        return false;
    }

    /* File-system problems first: OIIO's messages for these are vague ("could not open"). */
    struct stat st;
    if (stat(path, &st) != 0) {
        int e = errno;
        if (e == ENOENT) set_err(err, err_size, "%s: no such file", path);
        else if (e == ENOTDIR) set_err(err, err_size, "%s: no such file (a parent is not a directory)", path);
        else if (e == EACCES) set_err(err, err_size, "%s: permission denied", path);
        else set_err(err, err_size, "%s: cannot access: %s", path, strerror(e));
        return false;
    }
    if (S_ISDIR(st.st_mode)) {
        set_err(err, err_size, "%s: is a directory, not an image file", path);
        return false;
    }
    if (!S_ISREG(st.st_mode)) { /* a FIFO or device could block or never end: never opened */
        char why[128];
        if (!sl_input_file_problem(path, why, sizeof why)) snprintf(why, sizeof why, "is not a regular file");
        set_err(err, err_size, "%s: %s", path, why);
        return false;
    }
    if (st.st_size == 0) {
        set_err(err, err_size, "%s: empty file (0 bytes)", path);
        return false;
    }
    if (access(path, R_OK) != 0) {
        set_err(err, err_size, "%s: permission denied (cannot read)", path);
        return false;
    }

    return decode(img, path, NULL, 0, err, err_size);
}

bool sl_image_load_memory(sl_image *img, const void *data, size_t size, const char *name, char *err,
                          size_t err_size) {
    if (!name) name = "(in memory)";
    if (!img) {
        set_err(err, err_size, "%s: no output image given", name);
        return false;
    }
    memset(img, 0, sizeof *img);
    if (!data || size == 0) {
        set_err(err, err_size, "%s: empty image data (0 bytes)", name);
        return false;
    }
    return decode(img, name, data, size, err, err_size);
}

/* Opens (a file, or `data` when given) and decodes: the checks and conversions every image gets. */
static bool decode(sl_image *img, const char *path, const void *data, size_t size, char *err, size_t err_size) {
    /* The plain common JPEG, PNG and EXR files without OpenImageIO (image_native.c; image.h says why);
     * SHADELAB_IMAGE_DECODER=oiio sends every file to OIIO (tests compare both paths). */
    const char *decoder = getenv("SHADELAB_IMAGE_DECODER");
    bool force_oiio = decoder && !strcmp(decoder, "oiio");
    if (!force_oiio && sl_image_decode_native(img, path, data, size)) {
        report_nonfinite(img, path);
        return true;
    }
    /* A file only OpenImageIO reads, decoded before: from the cache, without opening the module
     * (image_cache.c; image.h says why and what the key is). Forced OIIO decodes neither read nor
     * write it. */
    sl_image_cache_entry cached = {0};
    bool use_cache = !force_oiio && sl_image_cache_enabled();
    if (use_cache && sl_image_cache_lookup(img, path, data, size, &cached)) {
        report_nonfinite(img, path); /* the same message as the decode gave: the values are the same */
        return true;
    }
    char ext[16], msg[1024] = "";
    sl_image_path_extension(path, ext, sizeof ext);
    sl_oiio_info info;
    sl_oiio_input *in = data ? sl_oiio_open_memory(data, size, path, &info, msg, sizeof msg)
                             : sl_oiio_open(path, &info, msg, sizeof msg);
    if (!in) {
        /* OIIO tries every reader when the one named by the extension fails, so a known
         * extension here means the content is damaged or not what the name says. */
        if (!ext[0])
            set_err(err, err_size, "%s: unsupported format: no OpenImageIO reader recognises it (%s)",
                    path, msg);
        else if (!sl_oiio_extension_known(ext))
            set_err(err, err_size, "%s: unsupported format '.%s': no OpenImageIO reader recognises it (%s)",
                    path, ext, msg);
        else
            set_err(err, err_size, "%s: corrupt, truncated or not a valid .%s file (%s)", path,
                    ext, msg);
        return false;
    }

    bool ok = false;
    if (info.deep) {
        set_err(err, err_size, "%s: deep (multi-sample) images are not supported", path);
    } else if (info.width <= 0 || info.height <= 0 || info.depth > 1 || info.channels < 1) {
        set_err(err, err_size, "%s: invalid image dimensions %dx%dx%d with %d channels", path,
                info.width, info.height, info.depth, info.channels);
    } else if (info.width > SL_IMAGE_MAX_DIM || info.height > SL_IMAGE_MAX_DIM ||
               (long)info.width * info.height > SL_IMAGE_MAX_PIXELS) {
        set_err(err, err_size,
                "%s: image is %dx%d (from its header), over the limit of %d per side and %ld Mpixel in all "
                "(would need %.1f GiB as float RGBA); refusing to decode it (resize it first, e.g. oiiotool --resize)",
                path, info.width, info.height, SL_IMAGE_MAX_DIM, SL_IMAGE_MAX_PIXELS >> 20,
                (double)info.width * info.height * 16.0 / (1024.0 * 1024.0 * 1024.0));
    } else {
        ok = true;
    }
    if (!ok) {
        sl_oiio_close(in);
        return false;
    }

    /* Read the first min(channels, 4) channels packed at the start of the RGBA buffer, then
     * expand in place from the last pixel backwards (a destination pixel never overlaps a
     * source pixel not yet read). An alpha channel beyond index 3 (rare: OIIO orders EXR
     * channels RGBA first) is read separately. */
    int alpha = info.alpha_channel;
    int nread = info.channels < 4 ? info.channels : 4;
    bool alpha_far = alpha >= 4 && alpha < info.channels;
    if (alpha_far) nread = 3;
    size_t npix = (size_t)info.width * (size_t)info.height;
    float *buf = malloc(npix * 4 * sizeof(float));
    float *abuf = alpha_far ? malloc(npix * sizeof(float)) : NULL;
    if (!buf || (alpha_far && !abuf)) {
        set_err(err, err_size, "%s: out of memory for a %dx%d image", path, info.width, info.height);
        free(buf);
        free(abuf);
        sl_oiio_close(in);
        return false;
    }
    if (!sl_oiio_read(in, 0, nread, buf, msg, sizeof msg) ||
        (alpha_far && !sl_oiio_read(in, alpha, alpha + 1, abuf, msg, sizeof msg))) {
        set_err(err, err_size, "%s: corrupt or truncated image data (%s)", path, msg);
        free(buf);
        free(abuf);
        sl_oiio_close(in);
        return false;
    }
    /* read, but the reader recovered from damage (a truncated JPEG is filled with grey): say so,
     * and never cache it, so that the warning is given at every load */
    bool damaged = msg[0] != 0;
    if (damaged) SL_WARN("%s: damaged image data, loaded as the reader recovered it (%s)", path, msg);
    sl_oiio_close(in);

    for (size_t i = npix; i-- > 0;) {
        const float *s = buf + i * nread;
        float r, g, b, a = 1.0f;
        if (nread == 1) {
            r = g = b = s[0];
        } else if (nread == 2) {
            if (alpha == 1) r = g = b = s[0], a = s[1];
            else r = s[0], g = s[1], b = 0.0f;
        } else {
            r = s[0], g = s[1], b = s[2];
            if (alpha == 3 && nread == 4) a = s[3];
            else if (alpha_far) a = abuf[i];
        }
        float *d = buf + i * 4;
        d[0] = r, d[1] = g, d[2] = b, d[3] = a;
    }
    free(abuf);

    img->width = info.width;
    img->height = info.height;
    img->channels = 4;
    img->pixels = buf;
    img->source_bits = info.bits > 32 ? 32 : info.bits;
    img->source_float = info.is_float;
    img->source_srgb = !info.is_float && !colorspace_is_linear(info.colorspace);
    img->source_channels = info.channels;
    snprintf(img->source_description, sizeof img->source_description, "%s", info.description);
    snprintf(img->source_format, sizeof img->source_format, "%s", info.format_name);
    if (use_cache && !damaged) sl_image_cache_store(&cached, data ? NULL : path, img);
    report_nonfinite(img, path);
    return true;
}

void sl_image_free(sl_image *img) {
    if (!img) return;
    free(img->pixels);
    memset(img, 0, sizeof *img);
}

/* ---- writing ---------------------------------------------------------------------------- */

/* 8-bit RGBA PNG with the sRGB chunk (and its gAMA/cHRM fallbacks, as OpenImageIO wrote them),
 * zlib level 4: a rendered frame with tone mapping's dither is noise in its low bits, which
 * level 6's longer match search barely shrinks (the default scene's 1280x720 frame: level 6
 * ≈ +0.25 s over storing, 839 KB; level 4 ≈ +0.05 s, 917 KB; level 1 1075 KB). */
static bool write_png(const char *path, const unsigned char *rgba, int w, int h, char *msg, size_t n) {
    FILE *f = fopen(path, "wb");
    if (!f) {
        snprintf(msg, n, "%s", strerror(errno));
        return false;
    }
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    volatile bool ok = false;
    if (png && info && !setjmp(png_jmpbuf(png))) {
        png_init_io(png, f);
        png_set_compression_level(png, 4);
        png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
                     PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);
        png_write_info(png, info);
        for (int y = 0; y < h; y++) png_write_row(png, rgba + (size_t)y * w * 4);
        png_write_end(png, NULL);
        ok = true;
    }
    png_destroy_write_struct(png ? &png : NULL, info ? &info : NULL);
    if (fclose(f) != 0 && ok) {
        snprintf(msg, n, "%s", strerror(errno));
        return false;
    }
    if (!ok) snprintf(msg, n, "libpng could not write the image (disk full?)");
    return ok;
}

bool sl_image_write(const char *path, const float *rgba, int width, int height,
                    bool display_encoded, char *err, size_t err_size) {
    if (!path || !*path) {
        set_err(err, err_size, "(empty path): no output path given");
        return false;
    }
    if (!rgba || width <= 0 || height <= 0) {
        set_err(err, err_size, "%s: nothing to write (%dx%d image%s)", path, width, height,
                rgba ? "" : ", no pixels");
        return false;
    }

    char ext[16];
    sl_image_path_extension(path, ext, sizeof ext);
    const char *format, *file_type;
    int channels, quality = 0;
    if (!strcmp(ext, "png")) format = "png", file_type = "uint8", channels = 4;
    else if (!strcmp(ext, "jpg") || !strcmp(ext, "jpeg"))
        format = "jpeg", file_type = "uint8", channels = 3, quality = 95;
    else if (!strcmp(ext, "exr")) format = "openexr", file_type = "half", channels = 4;
    else if (!strcmp(ext, "hdr")) format = "hdr", file_type = "float", channels = 3;
    else {
        const char *supported = ".png, .jpg, .jpeg, .exr, .hdr";
        if (ext[0])
            set_err(err, err_size, "%s: unknown extension '.%s' (supported: %s)", path, ext,
                    supported);
        else
            set_err(err, err_size, "%s: no file extension to choose the format (supported: %s)",
                    path, supported);
        return false;
    }

    /* Directory checks, for messages better than "could not open". */
    const char *slash = strrchr(path, '/');
    char dir[4096];
    if (!slash) snprintf(dir, sizeof dir, ".");
    else if (slash == path) snprintf(dir, sizeof dir, "/");
    else snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
    struct stat st;
    if (stat(dir, &st) != 0) {
        int e = errno;
        if (e == ENOENT) set_err(err, err_size, "%s: directory '%s' does not exist", path, dir);
        else set_err(err, err_size, "%s: cannot access directory '%s': %s", path, dir, strerror(e));
        return false;
    }
    if (!S_ISDIR(st.st_mode)) {
        set_err(err, err_size, "%s: '%s' is not a directory", path, dir);
        return false;
    }
    if (access(dir, W_OK) != 0) {
        set_err(err, err_size, "%s: cannot write in directory '%s' (permission denied)", path, dir);
        return false;
    }
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
        set_err(err, err_size, "%s: is a directory", path);
        return false;
    }

    size_t npix = (size_t)width * (size_t)height;
    unsigned char *bytes = NULL;
    float *floats = NULL;
    const float *float_src = NULL;
    if (!strcmp(file_type, "uint8")) {
        bytes = malloc(npix * 4);
        if (!bytes) goto oom;
        sl_image_to_rgba8(rgba, width, height, display_encoded, bytes);
        if (channels == 3) /* pack RGBA → RGB in place (dst never overtakes src) */
            for (size_t i = 0; i < npix; i++) memmove(bytes + i * 3, bytes + i * 4, 3);
    } else if (channels == 4) {
        float_src = rgba;
    } else { /* .hdr: RGB; RGBE holds neither negatives, NaN nor Inf */
        floats = malloc(npix * 3 * sizeof(float));
        if (!floats) goto oom;
        for (size_t i = 0; i < npix; i++)
            for (int c = 0; c < 3; c++) {
                float v = rgba[i * 4 + c];
                floats[i * 3 + c] = !(v > 0.0f) ? 0.0f : v > 1e38f ? 1e38f : v;
            }
        float_src = floats;
    }

    static atomic_uint counter;
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.tmp-%ld-%u", path, (long)getpid(), atomic_fetch_add(&counter, 1));
    char msg[1024] = "";
    /* PNG, what nearly every run writes, through libpng: OpenImageIO's module is opened only when
     * some other format is written or an image file is read (image.h: ≈ 0.5 s of library loading) */
    bool ok = !strcmp(format, "png") ? write_png(tmp, bytes, width, height, msg, sizeof msg)
                                     : sl_oiio_write(tmp, format, bytes, float_src, width, height, channels,
                                                     file_type, quality, msg, sizeof msg);
    free(bytes);
    free(floats);
    if (!ok) {
        unlink(tmp);
        /* OIIO names the temporary file; the user only knows the real one */
        char *at = strstr(msg, tmp);
        if (at) {
            size_t tl = strlen(tmp), pl = strlen(path);
            if (pl <= tl) {
                memcpy(at, path, pl);
                memmove(at + pl, at + tl, strlen(at + tl) + 1);
            }
        }
        set_err(err, err_size, "%s: cannot write %s: %s", path, ext, msg);
        return false;
    }
    if (rename(tmp, path) != 0) {
        int e = errno;
        unlink(tmp);
        set_err(err, err_size, "%s: cannot move the written file into place: %s", path, strerror(e));
        return false;
    }
    return true;

oom:
    free(bytes);
    set_err(err, err_size, "%s: out of memory for a %dx%d image", path, width, height);
    return false;
}

/* ---- comparison ------------------------------------------------------------------------- */

static bool pixel_finite(const float *p, int channels) {
    for (int c = 0; c < channels; c++)
        if (!isfinite(p[c])) return false;
    return true;
}

void sl_image_compare(const float *a, const float *b, int width, int height, int channels,
                      double threshold, sl_image_diff *out) {
    if (!out) return;
    memset(out, 0, sizeof *out);
    out->rmse = out->psnr = out->max_abs = out->mean_abs = NAN;
    if (!a || !b || width <= 0 || height <= 0 || channels < 1) return;
    int nc = channels < 3 ? channels : 3;
    size_t npix = (size_t)width * (size_t)height;
    double sum2 = 0.0, sum1 = 0.0, maxd = 0.0;
    long compared = 0;
    for (size_t i = 0; i < npix; i++) {
        const float *pa = a + i * channels, *pb = b + i * channels;
        bool fa = pixel_finite(pa, channels), fb = pixel_finite(pb, channels);
        if (!fa) out->nonfinite_a++;
        if (!fb) out->nonfinite_b++;
        if (!fa || !fb) {
            out->pixels_over++;
            continue;
        }
        compared++;
        bool over = false;
        for (int c = 0; c < nc; c++) {
            double d = fabs((double)pa[c] - (double)pb[c]);
            sum2 += d * d;
            sum1 += d;
            if (d > maxd) maxd = d;
            if (d > threshold) over = true;
        }
        if (over) out->pixels_over++;
    }
    out->pixels_compared = compared;
    if (compared == 0) return;
    double count = (double)compared * nc;
    out->rmse = sqrt(sum2 / count);
    out->mean_abs = sum1 / count;
    out->max_abs = maxd;
    out->psnr = out->rmse > 0.0 ? -20.0 * log10(out->rmse) : INFINITY;
}

long sl_image_sanitize(sl_image *img, float max, long *nonfinite, long *negative, long *over) {
    long nf = 0, neg = 0, big = 0;
    size_t n = (size_t)img->width * img->height * 4;
    for (size_t i = 0; i < n; i++) {
        float v = img->pixels[i];
        if (!isfinite(v)) img->pixels[i] = v > 0 ? max : 0, nf++; /* +Inf → max; NaN, −Inf → 0 */
        else if (v < 0) img->pixels[i] = 0, neg++;
        else if (v > max) img->pixels[i] = max, big++;
    }
    if (nonfinite) *nonfinite = nf;
    if (negative) *negative = neg;
    if (over) *over = big;
    return nf + neg + big;
}
