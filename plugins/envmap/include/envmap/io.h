/* envmap's public tool API, part 2 (plugins/envmap/README.md): the environment loader policy
 * shared by the plugin and the cube tool (envmap_load.c, library `envmap_prefilter`), and image
 * files over OpenImageIO for tools and tests (envmap_io.cpp, library `envmap_io`: the plugin
 * does not link it, it reads files through the host, which opens OpenImageIO only when an image
 * is read). Part 1 is <envmap/prefilter.h>. */
#ifndef ENVMAP_IO_H
#define ENVMAP_IO_H
#include "prefilter.h"

#ifdef __cplusplus
extern "C" {
#endif

#define EM_IO_MAX_DIM 16384
/* The ImageDescription of RGBE8 PNGs written by shadelab-cube (also recognised: *.rgbe.png). */
#define EM_RGBE_TAG "shadelab-rgbe8"

typedef struct em_io_info {
    int bits, channels;
    bool is_float;
    bool srgb; /* integer samples sRGB-encoded: not tagged linear (oiio:ColorSpace); false for float */
    char description[128], format[32];
} em_io_info;

/* ---- image files over OpenImageIO (envmap_io.cpp, library envmap_io) ---- */

/* Float RGBA, values as stored (integers normalised to [0,1]); row 0 = top. */
bool em_io_load(const char *path, em_image *out, em_io_info *info, char *err, size_t n);
bool em_io_write_exr(const char *path, const float *rgba, int w, int h, const char *description, char *err, size_t n);
bool em_io_write_png8(const char *path, const unsigned char *rgba, int w, int h, const char *description, char *err,
                      size_t n);
/* Writes six faces as a horizontal cross: .exr (half) or .png (RGBE8, tagged). */
bool em_write_cube(const char *path, float *const faces[6], int size, char *err, size_t n);

/* How em_env_load reads one image file (float RGBA as stored, and what it is): em_io_reader in
 * tools, host->read_image in the plugin. */
typedef struct em_reader {
    bool (*read)(void *ctx, const char *path, em_image *out, em_io_info *info, char *err, size_t n);
    void *ctx;
} em_reader;
/* em_io_load as an em_reader (ctx unused): what tools and tests hand to em_env_load. */
extern const em_reader em_io_reader;

/* ---- environments (envmap_load.c) ---- */

typedef enum em_env_kind { EM_ENV_LATLONG = 1, EM_ENV_CUBE } em_env_kind;

/* A loaded environment in linear radiance, sanitised (see em_sanitize). */
typedef struct em_env {
    em_env_kind kind;
    em_image latlong;        /* EM_ENV_LATLONG */
    float *faces[6];         /* EM_ENV_CUBE: GL order, size² RGBA each */
    int size;
    /* a precomputed specular chain (shadelab-cube --ggx output named X.1.ext … X.N.ext): the
     * levels' faces, level l of face size size >> l; chain_levels = 0 when none */
    float **chain;           /* chain_levels arrays of 6 faces, contiguous per level */
    int chain_levels;
    em_sanitize_stats stats; /* what was replaced */
    char how[256];           /* one line: format, layout, size */
} em_env;
void em_env_free(em_env *e);

/* Loads an environment file: lat-long (2:1), cross (4:3, 3:4), strip (6:1, 1:6), six face
 * files (a name containing _px/_nx/_py/_ny/_pz/_nz, the others found beside it), RGBE8 PNG
 * (shadelab-cube output) or an X.1.ext chain. 8-bit sRGB files are decoded to linear. NaN, Inf
 * and negative values are replaced (counted in e->stats; the caller warns once). */
bool em_env_load(const char *path, const em_reader *read, em_env *e, char *err, size_t n);
/* Procedural environments as lat-long images. The core's texture specs ("constant:r,g,b", "uv",
 * "gradient", "checker:N:r,g,b:r,g,b", "grid:N:…") are parsed and rendered by the core's one
 * parser, reached through `pattern` (the plugin: host->procedural_image; shadelab-cube: the
 * toolkit's sl_image_procedural), so a spec the core refuses ("checker:0:…", "constant:-1,…") is
 * refused here with the core's message; *constant is set for "constant:". envmap's own
 * "sky[:elevation[:azimuth[:sun irradiance]]]" (em_sky, 1024×512) is read strictly: each field
 * a finite number within EM_SKY_* (the envmap.sun_* parameters' ranges). */
typedef float *(*em_pattern_fn)(void *user, const char *spec, int size, char *err, size_t n);
bool em_is_procedural(const char *spec);
bool em_procedural(const char *spec, em_pattern_fn pattern, void *user, em_image *img, bool *constant, char *err,
                   size_t n);
/* "out.exr" + level 3 → "out.3.exr" */
void em_chain_name(const char *path, int level, char *out, size_t n);

#ifdef __cplusplus
}
#endif
#endif
