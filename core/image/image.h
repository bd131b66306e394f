/* Images in and out, and procedural textures. Pixels are float RGBA in memory unless stated otherwise.
 * Reading: the plain common JPEG, PNG and OpenEXR files are decoded natively (image_native.c: libjpeg,
 * libpng, OpenEXRCore), giving exactly what OpenImageIO gives for them; every other file (other formats,
 * and any JPEG/PNG/EXR with damage, unusual metadata or layout) goes through OpenImageIO, a module opened
 * on first use (image_oiio.cpp, the only C++ here; see the SL_IMAGE_INTERNAL section for why). Writing:
 * PNG with libpng, other formats through OpenImageIO.
 *
 * Conventions for every function here:
 *  - row 0 is the TOP of the image (file order). OpenGL's glReadPixels returns bottom-up
 *    rows: use sl_image_flip_rows. When an image is uploaded to GL as is (row 0 first), row 0
 *    sits at texture coordinate t = 0, i.e. the glTF convention "uv origin at the top left".
 *  - "linear" means linear-light values in the sRGB/Rec.709 primaries; "encoded" means
 *    sRGB-encoded per IEC 61966-2-1. Alpha is never encoded.
 *  - Error messages are written into err (if err && err_size), NUL-terminated and truncated
 *    to err_size; functions that fail leave their output image zeroed (safe to free). */
#ifndef SL_IMAGE_H
#define SL_IMAGE_H

#include <shadelab/shadelab.h>
#include <stdbool.h>
#include <stddef.h>

/* Largest width or height sl_image_load and sl_image_procedural accept (a 16384² RGBA float
 * image is 4 GiB already); larger files are refused before any pixel memory is allocated. */
#define SL_IMAGE_MAX_DIM 16384
/* Largest pixel count sl_image_load decodes: SL_IMAGE_MAX_PIXELS (the SDK's shadelab.h, 64 Mpixel),
 * checked from the header; resize such images first (oiiotool --resize). */

typedef struct sl_image {
    int width, height;
    int channels;     /* always 4 after loading (RGBA) */
    float *pixels;    /* width*height*4, row 0 = top of the image */
    int source_bits;  /* bits per channel in the file: 8, 16 or 32. 16 is ambiguous (16-bit
                         integer PNG/TIFF or half-float EXR): see source_float */
    bool source_srgb; /* the file stores sRGB-encoded values: true for 8/16-bit integer files
                         (PNG, JPEG, TIFF…) unless OIIO's "oiio:ColorSpace" metadata says linear
                         (e.g. a PNG with gAMA 1.0); false for float files (EXR, HDR) and for
                         procedural textures. Describes the FILE: sl_image_srgb_to_linear does
                         not change it. */
    bool source_float; /* the file stores floating-point samples (half or float) */
    int source_channels;          /* the file's channel count */
    char source_description[128]; /* its ImageDescription metadata, "" when absent */
    char source_format[32];       /* OIIO's reader name: "png", "openexr"… */
} sl_image;

/* Loads any format OpenImageIO reads (PNG, JPEG, HDR, EXR, TIFF…; 8/16-bit integer, half,
 * float) as float RGBA (plain JPEG/PNG/EXR natively, with identical results: see the top of this file;
 * SHADELAB_IMAGE_DECODER=oiio in the environment sends every file to OpenImageIO, for tests and
 * comparisons, and bypasses the cache), unmodified values (integers normalised to [0,1], no colour
 * conversion: see sl_image_srgb_to_linear). Files that need OpenImageIO and decode without damage are
 * cached decoded, keyed by a hash of their bytes, so that a later load of the same content does not
 * open the module (the SL_IMAGE_INTERNAL section: where, the key, the cap); SHADELAB_IMAGE_CACHE=0
 * turns the cache off. One channel = grey, replicated to RGB; two channels = grey +
 * alpha; a missing alpha is 1. Only the first subimage / mip level is read; EXIF orientation
 * is not applied. On failure writes "path: reason" into err (no such file, is a directory,
 * permission denied, empty file, unsupported format, corrupt or truncated data, too large)
 * and returns false with *img zeroed. Never aborts on bad input. */
bool sl_image_load(sl_image *img, const char *path, char *err, size_t err_size);
/* The same for an encoded image held in memory (PNG/JPEG… bytes embedded in a .glb or a data:
 * URI): name (with the format's extension, e.g. "model.glb#image0.png") is used in messages and
 * to pick the reader first; the same limits apply. */
bool sl_image_load_memory(sl_image *img, const void *data, size_t size, const char *name, char *err,
                          size_t err_size);
/* sRGB-encoded → linear in place (RGB only, alpha untouched), per IEC 61966-2-1 (see
 * sl_srgb_decode: inputs are clamped to [0,1] and NaN becomes 0). Call it exactly once, for
 * colour textures whose img->source_srgb is true. */
/* Makes every sample finite and in [0, max]: NaN, −Inf and negative values become 0, +Inf and
 * values above max become max. Returns how many samples changed; the optional out-parameters
 * count NaN/±Inf, finite negatives and finite values over max. Inputs that feed shading use it
 * with one warning naming the file. */
long sl_image_sanitize(sl_image *img, float max, long *nonfinite, long *negative, long *over);
void sl_image_srgb_to_linear(sl_image *img);
/* Writes float RGBA (width*height*4, row 0 = top). Format from the extension
 * (case-insensitive):
 *   .png         8-bit RGBA. If display_encoded, values are taken as already encoded;
 *                otherwise RGB is clamped to [0,1] and sRGB-encoded. Either way each value
 *                is clamped to [0,1] and rounded to nearest (NaN → 0). Alpha is written
 *                linear, clamped: pass alpha 1 for an opaque image.
 *   .jpg/.jpeg   8-bit RGB (alpha dropped), as .png, quality 95.
 *   .exr         half-float RGBA, linear, values as is (NaN/Inf kept; |x| > 65504 → ±Inf,
 *                which is half's range). display_encoded is ignored.
 *   .hdr         Radiance RGBE, float RGB (alpha dropped; ~1% precision, negatives → 0).
 * The file is written to a temporary name in the same directory and renamed into place, so
 * a failed write leaves any existing file untouched. err names the path and the cause
 * (unknown extension, directory missing, permission denied, OIIO's message). */
bool sl_image_write(const char *path, const float *rgba, int width, int height,
                    bool display_encoded, char *err, size_t err_size);
void sl_image_free(sl_image *img);

/* Procedural textures for scenes that need no files. Output is linear RGBA float, size×size,
 * alpha 1 (unless an r,g,b,a colour gives one), source_bits 32, source_srgb false. Colours
 * are linear "r,g,b" or "r,g,b,a", finite and ≥ 0. size is 1..SL_IMAGE_MAX_DIM.
 *   "checker:N:A:B"   N×N squares (N = 1..size); the square holding texel (0,0) (top left) is
 *                     A and colours alternate, texel (x,y) is A when (x*N/size + y*N/size) is
 *                     even (integer division, so squares differ by at most one texel).
 *                     e.g. "checker:8:0.9,0.9,0.9:0.2,0.3,0.8"
 *   "grid:N:A:B"      lines of colour A on background B: N×N cells, a line along the top and
 *                     left edge of each cell (so the texture tiles seamlessly), line width
 *                     max(1, size/(16N)) texels.
 *   "gradient"        red = x/(size-1), green = y/(size-1) (0 at the top-left texel, exactly
 *                     1 at the last), blue 0: a full-range ramp.
 *   "uv"              red = u = (x+0.5)/size, green = v = (y+0.5)/size, blue 0: the texel
 *                     centre's texture coordinate (row 0 = v near 0, see above), so sampling
 *                     it shows the UVs a mesh uses.
 *   "constant:A"      one colour.
 * Tangent-space normal maps (linear data, n·0.5 + 0.5, +Y convention: green = slope toward image
 * up) from height fields over X = u (right) and Y = 1 − v (image up), both 0..1:
 *   "flat"            n = (0, 0, 1)
 *   "tilt:X,Y"        constant n = (X, Y, √(1−X²−Y²)), X² + Y² ≤ 1
 *   "bumps:N:A"       h = A/(2πN)·sin(2πNX)·sin(2πNY): N×N egg-crate bumps (N = 1..4096) of
 *                     slope amplitude A (|A| ≤ 100)
 *   "waves:N:A:SEED"  six plane waves with integer frequencies of length N/2..N (tileable),
 *                     random directions and phases from SEED, total slope amplitude about A
 * A malformed spec gives an error naming the spec, what is wrong and the expected form, e.g.
 * "procedural texture 'checker:8': expected 'checker:N:r,g,b:r,g,b'". */
bool sl_image_procedural(sl_image *img, const char *spec, int size, char *err, size_t err_size);
#define SL_PROCEDURAL_KINDS "checker, grid, gradient, uv, constant, flat, tilt, bumps, waves"
/* Whether a texture spec names a procedural texture (its kind before the first ':') rather than
 * a file. */
bool sl_image_is_procedural(const char *spec);

/* Image comparison (stated metrics, on linear RGB(A) floats). a and b hold width*height
 * pixels of `channels` (1..4) floats each; the metrics use the colour channels only (the
 * first min(channels, 3)). A pixel with a NaN/Inf in any of its channels is "non-finite";
 * pixels non-finite in EITHER image are left out of rmse/psnr/max_abs/mean_abs (and counted
 * in nonfinite_a / nonfinite_b and in pixels_over). */
typedef struct sl_image_diff {
    double rmse;          /* sqrt(mean((a-b)^2)) over RGB of the compared pixels */
    double psnr;          /* 20 log10(peak / rmse), peak = 1, in dB; INFINITY when rmse = 0
                             (identical images) */
    double max_abs;       /* largest |a-b| over RGB */
    double mean_abs;      /* mean |a-b| over RGB */
    long nonfinite_a, nonfinite_b; /* pixels with a NaN/Inf channel (any channel, alpha too) */
    long pixels_over;     /* pixels with any RGB channel |a-b| > threshold, plus every pixel
                             that is non-finite in either image */
    long pixels_compared; /* pixels that entered the sums (finite in both). When it is 0,
                             rmse, psnr, max_abs and mean_abs are NaN (undefined) */
} sl_image_diff;
void sl_image_compare(const float *a, const float *b, int width, int height, int channels,
                      double threshold, sl_image_diff *out);

/* sRGB OETF, IEC 61966-2-1 piecewise (scalar, for tests and CPU paths), computed in double.
 * encode: 12.92·x for x ≤ 0.0031308, else 1.055·x^(1/2.4) − 0.055.
 * decode: x/12.92 for x ≤ 0.04045, else ((x + 0.055)/1.055)^2.4.
 * Both clamp their input to [0,1] first and map NaN to 0, so the result is always finite and
 * in [0,1] (−Inf → 0, +Inf → 1). */
float sl_srgb_encode(float linear);
float sl_srgb_decode(float encoded);

/* The next mip level of an RGBA8 image (w×h → max(1, w/2)×max(1, h/2), row-major): each texel the
 * area-weighted mean of the source texels it covers — a 2×2 block on even sides; on an odd side
 * 2n + 1 → n each texel covers 2 + 1/n source texels, 3 of them in part, so that no texel is left
 * out and each level keeps the content where its texel centres are (a 1-texel side stays 1). With
 * srgb, RGB is averaged in linear light (IEC 61966-2-1 decode, mean, encode rounded to the nearest
 * code) and alpha linearly; otherwise every channel as stored, rounded to nearest. A box filter,
 * sRGB-correct, as glGenerateMipmap means it, on the CPU: llvmpipe compiles a blit shader per
 * format for it, ~60-180 ms per format at start-up. */
void sl_image_mip_rgba8(const unsigned char *src, int w, int h, unsigned char *dst, bool srgb);
/* The same filter on float RGBA, every channel as stored (linear data: procedural textures,
 * 16-bit and float files kept in float storage). */
void sl_image_mip_rgbaf(const float *src, int w, int h, float *dst);

/* Reverses the row order in place (GL reads bottom-up; files are top-down). */
void sl_image_flip_rows(float *pixels, int width, int height, int channels);
/* The same for any pixel layout: `height` rows of `row_bytes` bytes each. */
void sl_image_flip_rows_raw(void *data, size_t row_bytes, int height);
/* Float RGBA (row 0 = top) → 8-bit RGBA for display or PNG: RGB sRGB-encoded unless
 * display_encoded, then every value clamped to [0,1], ×255, rounded to nearest; NaN → 0. out
 * holds width*height*4 bytes. */
void sl_image_to_rgba8(const float *rgba, int width, int height, bool display_encoded,
                       unsigned char *out);

#ifdef SL_IMAGE_INTERNAL
/* The lower-case extension, without the dot, of the last path component ("" when none; for an
 * image in memory, of its name: "x.glb#image0.png" gives "png"). */
void sl_image_path_extension(const char *path, char *ext, size_t size);
/* Internal: the native decoders (image_native.c), used only by image.c's decode() before OpenImageIO.
 * They exist because opening OpenImageIO's module costs ≈ 0.42 s and holds the dynamic loader's lock
 * (see below), while most scenes read only JPEG, PNG and EXR files. Decodes `path` (or `data`/`size`
 * when data is given; path is then the name) when it is a plain JPEG (8-bit grey/YCbCr/RGB), PNG
 * (any bit depth/colour type/interlacing, sRGB/no/gAMA 1.0 or 1/2.2 colour chunks) or single-part
 * scanline EXR (R,G,B[,A] or Y[,A], all half or all float) whose extension names that format, and
 * fills *img exactly as the OpenImageIO path would (pixels, size and every source_* field). Returns
 * false, with *img zeroed and nothing printed, for anything else: other formats, errors and warnings
 * of the libraries (corrupt or truncated data), sizes over the limits, metadata that could change a
 * field (ICC profiles, XMP, Exif/IPTC descriptions, cHRM…), multipart/deep/tiled/windowed EXRs:
 * decode() then goes on with OpenImageIO as before. */
bool sl_image_decode_native(sl_image *img, const char *path, const void *data, size_t size);

/* Internal: the decoded-image cache (image_cache.c), used only by image.c's decode() for files the
 * native decoders leave to OpenImageIO. It exists because the module costs ≈ 0.4 s to open and some
 * files that are read at every start need it (blender-data's DWAB-compressed studio lights, which
 * Debian 12's OpenEXRCore cannot decompress; .hdr, .tif…). A file OIIO decoded cleanly is kept as
 * its sl_image (fields and float RGBA pixels) in $SHADELAB_CACHE/images (else
 * $XDG_CACHE_HOME/shadelab/images, else ~/.cache/shadelab/images) as img-KEY.bin; the 8 most
 * recently used are kept. The key is a 64-bit hash of the encoded bytes (the whole file, or the
 * memory given), seeded with the cache's format version, the OpenImageIO version the module was
 * built against and the name's extension: content-addressed, so an edited file can never find the
 * entry of its old content, whatever its mtime. A missing, short, corrupt or mismatching entry (the
 * header's key and byte count are checked, sizes against the limits, the file's exact size) is a
 * miss, never an error; so is a cache directory that cannot be made. Not used (neither read nor
 * written) with SHADELAB_IMAGE_DECODER=oiio or SHADELAB_IMAGE_CACHE=0. */
typedef struct sl_image_cache_entry {
    bool valid;            /* key and source_bytes were computed */
    bool file;             /* a file (not memory): its identity below, re-checked before storing */
    uint64_t key, source_bytes;
    uint64_t dev, ino;
    int64_t mtime_s, mtime_ns;
} sl_image_cache_entry;
/* False when SHADELAB_IMAGE_CACHE is "0". */
bool sl_image_cache_enabled(void);
/* The key's hash: 8-byte words xor-multiplied by the FNV-1a 64-bit prime with a fold, the tail
 * bytes, the length. */
uint64_t sl_image_cache_hash(const void *data, size_t size, uint64_t seed);
/* Computes the key of `path` (or of data/size when data is given; path is then the name) into *e
 * and, on a hit, fills *img exactly as the OpenImageIO path did and returns true. On a miss returns
 * false with *img untouched; *e is then valid for sl_image_cache_store unless hashing failed. */
bool sl_image_cache_lookup(sl_image *img, const char *path, const void *data, size_t size,
                           sl_image_cache_entry *e);
/* Stores img under e's key (written to a temporary name and renamed into place), then prunes the
 * directory to 8 entries. Silent: a failure only means a later miss. Nothing is stored when the
 * file's size, mtime or inode changed since its key was computed. */
void sl_image_cache_store(const sl_image_cache_entry *e, const char *path, const sl_image *img);

/* Internal: the OpenImageIO adapter (image_oiio.cpp), used only by image.c. Every function
 * catches all C++ exceptions and reports them as errors (message without the path). */
typedef struct sl_oiio_info {
    int width, height, depth, channels;
    int alpha_channel;      /* −1 when none */
    int bits;               /* bits per sample of the file's pixel type (8, 16, 32…) */
    bool is_float;          /* half / float / double samples */
    bool deep;              /* deep (multi-sample) image */
    char format_name[32];   /* OIIO's reader name: "png", "openexr"… */
    char colorspace[64];    /* "oiio:ColorSpace" metadata, "" when absent */
    char description[128];  /* "ImageDescription" metadata, "" when absent */
} sl_oiio_info;
typedef struct sl_oiio_input sl_oiio_input;
sl_oiio_input *sl_oiio_open(const char *path, sl_oiio_info *info, char *err, size_t err_size);
/* The same for an image held in memory; name's extension picks the reader to try first. */
sl_oiio_input *sl_oiio_open_memory(const void *data, size_t size, const char *name, sl_oiio_info *info,
                                   char *err, size_t err_size);
/* Reads channels [chbegin, chend) of subimage 0, mip 0 as float, tightly packed. */
bool sl_oiio_read(sl_oiio_input *in, int chbegin, int chend, float *out, char *err,
                  size_t err_size);
void sl_oiio_close(sl_oiio_input *in);
/* Writes `channels` channels of either uint8 (pixels8) or float (pixelsf) data; file_type is
 * "uint8", "half" or "float". `format` is OIIO's writer name or extension ("png", "exr"…). */
bool sl_oiio_write(const char *path, const char *format, const unsigned char *pixels8,
                   const float *pixelsf, int width, int height, int channels,
                   const char *file_type, int jpeg_quality, char *err, size_t err_size);
/* True when some OIIO reader claims the extension (without the dot, lower case). */
bool sl_oiio_extension_known(const char *ext);

/* The adapter lives in a module of its own, shadelab-oiio.so, opened on first use
 * (oiio_module.c): linking OpenImageIO loads ~250 shared libraries (OpenCV, DCMTK, FFmpeg,
 * OpenVDB… through its plugins' dependencies), ≈ 0.5 s of every process start on this project's
 * machine, while most runs read no image file and write only a PNG (libpng, image.c). The
 * functions above forward to it; a missing module is an error naming the places looked in. It is
 * opened on first use, not ahead on a thread: while it opens it holds the dynamic loader's lock,
 * which Mesa's context creation and shader compiles also take (measured: the first frame came
 * 0.4 s later with a preloading thread). */
typedef struct sl_oiio_api {
    unsigned struct_size;
    sl_oiio_input *(*open)(const char *path, sl_oiio_info *info, char *err, size_t err_size);
    sl_oiio_input *(*open_memory)(const void *data, size_t size, const char *name, sl_oiio_info *info, char *err,
                                  size_t err_size);
    bool (*read)(sl_oiio_input *in, int chbegin, int chend, float *out, char *err, size_t err_size);
    void (*close)(sl_oiio_input *in);
    bool (*write)(const char *path, const char *format, const unsigned char *pixels8, const float *pixelsf, int width,
                  int height, int channels, const char *file_type, int jpeg_quality, char *err, size_t err_size);
    bool (*extension_known)(const char *ext);
} sl_oiio_api;
/* The module's one export. */
const sl_oiio_api *sl_oiio_module_api(void);

/* Internal: the OpenEXR C++ adapter (image_exr.cpp, the module shadelab-exr.so, opened on first use
 * like OpenImageIO's), used only by image_native.c for the compressions OpenEXRCore 3.1 cannot
 * decode. Reads the single-part scanline file (path, or data/size in memory; path is then its name)
 * whose data window is x0, y0, w × h: channels names[0..nch) as stored (half: 2 bytes, else float),
 * interleaved in that order, into out (w·h·nch samples). False with OpenEXR's message in err. */
typedef struct sl_exr_api {
    unsigned struct_size;
    bool (*read)(const char *path, const void *data, size_t size, int x0, int y0, int w, int h, int nch,
                 const char *const *names, bool half, void *out, char *err, size_t err_size);
} sl_exr_api;
const sl_exr_api *sl_exr_module_api(void); /* the module's one export */
/* The same, through the module (false with why in err when it cannot be opened). */
bool sl_exr_read(const char *path, const void *data, size_t size, int x0, int y0, int w, int h, int nch,
                 const char *const *names, bool half, void *out, char *err, size_t err_size);
#endif


#endif
