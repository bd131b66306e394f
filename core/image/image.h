/* Images in and out, through OpenImageIO (image_oiio.cpp is the only C++ here), and
 * procedural textures. Pixels are float RGBA in memory unless stated otherwise. */
#ifndef SL_IMAGE_H
#define SL_IMAGE_H

#include <stdbool.h>
#include <stddef.h>

typedef struct sl_image {
    int width, height;
    int channels;     /* always 4 after loading (RGBA) */
    float *pixels;    /* width*height*4, row 0 = top of the image */
    int source_bits;  /* 8, 16 or 32 (float) — bit depth of the file */
    bool source_srgb; /* the file stores sRGB-encoded values (8/16-bit PNG/JPEG) */
} sl_image;

/* Loads any format OpenImageIO reads (PNG, JPEG, HDR, EXR, 8/16/32-bit) as float RGBA,
 * unmodified values (no colour conversion: see sl_image_to_linear). On failure writes
 * "path: reason" into err. */
bool sl_image_load(sl_image *img, const char *path, char *err, size_t err_size);
/* sRGB-encoded → linear in place (RGB only), per IEC 61966-2-1. */
void sl_image_srgb_to_linear(sl_image *img);
/* Writes float RGBA. ".exr": linear half float, as is. ".png": `display_encoded` says the
 * pixels are already display-encoded in [0,1] (written as 8-bit); otherwise they are clamped
 * and sRGB-encoded first. Format from the extension; err names the path and cause. */
bool sl_image_write(const char *path, const float *rgba, int width, int height,
                    bool display_encoded, char *err, size_t err_size);
void sl_image_free(sl_image *img);

/* Procedural textures for scenes that need no files: spec strings such as
 * "checker:8:0.9,0.9,0.9:0.2,0.3,0.8" (squares per side, colour A, colour B, linear RGB),
 * "grid:…", "gradient". Output is linear RGBA float. */
bool sl_image_procedural(sl_image *img, const char *spec, int size, char *err, size_t err_size);

/* Image comparison (stated metrics, on linear RGB(A) floats). */
typedef struct sl_image_diff {
    double rmse;          /* sqrt(mean((a-b)^2)) over RGB */
    double psnr;          /* 20 log10(peak / rmse), peak = 1 */
    double max_abs;       /* largest |a-b| over RGB */
    double mean_abs;
    long nonfinite_a, nonfinite_b; /* NaN/Inf counts */
    long pixels_over;     /* pixels with any channel |a-b| > threshold */
} sl_image_diff;
void sl_image_compare(const float *a, const float *b, int width, int height, int channels,
                      double threshold, sl_image_diff *out);

/* sRGB OETF, IEC 61966-2-1 piecewise (scalar, for tests and CPU paths). */
float sl_srgb_encode(float linear);
float sl_srgb_decode(float encoded);

#endif
