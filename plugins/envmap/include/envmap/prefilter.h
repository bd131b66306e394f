/* envmap's public tool API (library `envmap_prefilter`, documented in plugins/envmap/README.md):
 * everything the envmap plugin, the cube tool (tools/cube) and the tests share. This header and
 * <envmap/io.h> (files, environments) are the only envmap headers another module may include;
 * the rest of plugins/envmap is the plugin's own. One implementation: the plugin links it into
 * envmap.so, shadelab-cube and the tests link it as a static library (envmap_prefilter). Plain C
 * over <shadelab/gl.h>; it never defines the GL function pointers (the module that links it
 * does: the plugin in envmap.c, the tool and the tests through the core library).
 *
 * Conventions (sdk conventions, scenes/README.md):
 *   lat-long   d = (−sinθ cosφ, cosθ, −sinθ sinφ), θ from +Y, φ = atan2(−d.z, −d.x);
 *              u = φ/2π wrapped to [0,1), v = θ/π; row 0 of an image (v = 0) is the top (+Y).
 *              The orientation of Blender and three.js (three.js: u = atan2(d.z, d.x)/2π + ½):
 *              seen from inside, u grows to the right; u = 0 faces −X, ¼ −Z (the default
 *              camera's view), ½ (the image's centre) +X, ¾ +Z.
 *   cube maps  OpenGL's face order (+X, −X, +Y, −Y, +Z, −Z) and face orientation (GL 4.5
 *              §8.13, table 8.19); a face image's row 0 is t = 0, so uploading it as is gives
 *              the GL cube map. Cross layouts: see em_layout.
 *   yaw        the environment turns by yaw degrees about +Y, +Z towards +X: the map's centre
 *              (u = ½) appears at (cos yaw, 0, −sin yaw). Lookups use d_map = R_y(−yaw) d.
 */
#ifndef ENVMAP_PREFILTER_H
#define ENVMAP_PREFILTER_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define EM_HALF_MAX 65504.0f /* largest finite half float: the storage limit of every texture */

/* ---------------------------------------------------------------- images and directions */

typedef struct em_image {
    int w, h;
    float *px; /* RGBA, w*h*4, row 0 = top */
} em_image;
void em_image_free(em_image *img);

void em_latlong_dir(double u, double v, double d[3]);
void em_dir_latlong(const double d[3], double *u, double *v); /* poles give u = 0 */
/* Face f (GL order), face coordinates s, t in [0,1] → unit direction, and back. */
void em_cube_dir(int face, double s, double t, double d[3]);
int em_dir_cube(const double d[3], double *s, double *t);
/* Exact solid angle of texel (x, y) of a size×size face. */
double em_texel_solid_angle(int size, int x, int y);
/* R_y(angle) applied to d (right-handed: +Z towards +X for angle > 0). */
void em_rotate_y(const double d[3], double degrees, double out[3]);

/* ---------------------------------------------------------------- input sanitising */

typedef struct em_sanitize_stats {
    long nan, inf, negative; /* replaced: NaN → 0, −Inf and negatives → 0, +Inf → 65504 */
    long clamped;            /* finite values above 65504 clamped to 65504 (the half limit) */
    float max_value;         /* largest finite value seen (before clamping) */
} em_sanitize_stats;
/* Sanitises the RGB channels of `pixels` RGBA pixels (alpha becomes 1). Returns the number
 * of values replaced (nan + inf + negative). */
long em_sanitize(float *rgba, size_t pixels, em_sanitize_stats *st);

/* ---------------------------------------------------------------- RGBE (Ward 1991) */

void em_rgbe_encode(const float rgb[3], unsigned char out[4]);
void em_rgbe_decode(const unsigned char in[4], float rgb[3]);
/* A float RGBA image as RGBE bytes in an RGBA8 image (exponent in alpha). */
void em_rgbe_encode_image(const float *rgba, size_t pixels, unsigned char *out);

/* ---------------------------------------------------------------- layouts */

typedef enum em_layout {
    EM_LAYOUT_UNKNOWN = 0,
    EM_LAYOUT_LATLONG, /* 2:1 */
    EM_LAYOUT_HCROSS,  /* 4:3:   row 0: +Y over column 1; row 1: −X +Z +X −Z; row 2: −Y */
    EM_LAYOUT_VCROSS,  /* 3:4:   column 1: +Y, +Z, −Y, −Z (−Z turned 180°); −X, +X left/right of +Z */
    EM_LAYOUT_HSTRIP,  /* 6:1:   +X −X +Y −Y +Z −Z left to right */
    EM_LAYOUT_VSTRIP   /* 1:6:   the same top to bottom */
} em_layout;
em_layout em_detect_layout(int w, int h);
const char *em_layout_name(em_layout l);
/* Cuts the six faces (GL order) out of a cross or strip; faces[f] gets size*size*4 floats
 * (malloc'd). Returns false when the layout is not a cube layout. */
bool em_extract_faces(const em_image *img, em_layout layout, float *faces[6], int *size);
/* Six faces → horizontal cross (4:3), unused area black with alpha 0. */
void em_faces_to_hcross(float *const faces[6], int size, em_image *out);

/* ---------------------------------------------------------------- spherical harmonics */

/* Projects a cube (6 faces of size², RGBA, GL order) onto the 9 real SH basis functions of
 * bands 0–2, with exact texel solid angles. */
void em_sh9_project(const float *faces, int size, double sh[9][3]);
/* The same projection of a lat-long image (em_latlong_dir's orientation), every texel weighted by
 * its exact solid angle, (2π/w)(cos θ_top − cos θ_bottom). */
void em_sh9_project_latlong(const em_image *img, double sh[9][3]);
/* Irradiance E(n)/π (the outgoing radiance of a white Lambert surface) from the projection,
 * with Ramamoorthi & Hanrahan's convolution (Â0 = π, Â1 = 2π/3, Â2 = π/4). Not clamped. */
void em_sh9_diffuse(const double sh[9][3], const double n[3], double out[3]);
/* The nine coefficients premultiplied by Â_l/π: what the shader evaluates. */
void em_sh9_diffuse_coefficients(const double sh[9][3], float out[9][3]);

/* ---------------------------------------------------------------- environment importance sampling */

/* A lat-long's radiance as a distribution of directions (PBRT's piecewise-constant 2D sampling,
 * Pharr et al. ch. 13.6 / 14.2): cell (x, y) of a w × h grid (the image, box-averaged down to at
 * most max_width columns) is picked with probability ∝ its weight × its solid angle
 * Ω_y = (2π/w)(cos θ_y − cos θ_{y+1}) — the sin θ weighting — through a marginal CDF over rows and
 * a conditional CDF within the row, then a point uniform in (φ, cos θ) inside it, so the density
 * over solid angle is constant in a cell: pdf = weight / Σ weight·Ω. The weight is the largest
 * luminance of the cell's 3 × 3 neighbourhood (lookups are bilinear: a cell beside a bright one
 * reads some of it) above the map's mean, Y_max − Ȳ (0 when Y_max ≤ 1.01 Ȳ): MIS compensation (Karlík et al. 2019, "MIS
 * compensation: optimizing sampling techniques in multiple importance sampling"), which leaves
 * what BRDF sampling already does well (the even part of the map) to BRDF sampling and spends
 * the environment samples on what stands out — a constant map gets no distribution at all
 * (total 0), so the white furnace stays exact. Cells of weight 0 are never picked (pdf 0: MIS
 * gives BRDF samples there full weight). The GLSL sampler (envmap_shading.glsl,
 * envmap_env_sample) reads these arrays as textures. */
typedef struct em_env_distribution {
    int w, h;
    float *conditional; /* w*h: per row, the CDF over its cells, 1 at the last (rows of weight 0: uniform) */
    float *pdf;         /* w*h: solid-angle density of a direction in the cell (weight / total) */
    float *marginal;    /* h: the CDF over rows, 1 at the last */
    double total;       /* Σ weight·Ω; 0 = nothing to sample (a constant map) */
} em_env_distribution;
bool em_env_distribution_build(const em_image *latlong, int max_width, em_env_distribution *out);
void em_env_distribution_free(em_env_distribution *d);
/* The sampler in C (the GLSL's twin): the map-space direction for (ξ1, ξ2) ∈ [0,1)², and its pdf. */
double em_env_distribution_sample(const em_env_distribution *d, double xi1, double xi2, double dir[3]);
double em_env_distribution_pdf(const em_env_distribution *d, const double dir[3]);

/* ---------------------------------------------------------------- procedural sky */

/* The sky's ranges: the envmap.sun_* parameters and "sky:E:A:I" specs alike. */
#define EM_SKY_ELEVATION_MAX 90.0  /* degrees, -90..90 */
#define EM_SKY_AZIMUTH_MAX 360.0   /* degrees, -360..360 */
#define EM_SKY_IRRADIANCE_MAX 1000.0 /* W/m², 0..1000 */
typedef struct em_sky {
    float sun_elevation_deg, sun_azimuth_deg; /* azimuth as φ: 0 = +Z, 90 = +X */
    float sun_irradiance;                     /* E of the sun disk at normal incidence */
    float sun_radius_deg;
    float ground[3]; /* radiance below the horizon (the ground beyond the scene), linear RGB */
} em_sky;
void em_sky_default(em_sky *s);
void em_sky_radiance(const em_sky *s, const double d[3], double out[3]);
/* Its sun: the unit direction towards it, its angular radius (radians) and the disk's uniform
 * radiance E/Ω times the sun's colour (0 without a sun) — what em_sky_radiance adds inside it. */
void em_sky_sun(const em_sky *s, double dir[3], double *radius, double radiance[3]);
/* Renders the sky as a lat-long image (the sun disk supersampled). */
void em_sky_latlong(const em_sky *s, int w, int h, em_image *out);
/* The procedural sky's set-up on the CPU (issue 19: no GPU programs to compile before the first
 * frame). em_latlong_mips: levels[0] = img (shared), then 2×2 box mips down to 1×1 (at most
 * max_levels; free levels 1..count−1's px). em_latlong_to_cube_levels: envmap_to_cube.frag's
 * conversion (4×4 trilinear sub-samples) and envmap_downsample.frag's solid-angle-weighted mips,
 * `levels` levels of size² faces; out[l] = 6 faces of level l, RGBA (malloc'd). */
void em_latlong_mips(const em_image *img, em_image *levels, int max_levels, int *count);
void em_latlong_to_cube_levels(const em_image *mips, int mip_count, int size, int levels, float **out);

/* ---------------------------------------------------------------- hashing */

uint64_t em_hash(const void *data, size_t bytes, uint64_t seed);

/* ---------------------------------------------------------------- GPU (prefilter.c) */

/* Compiles "sl:fullscreen.vert" + `fragment` (a file of the envmap GLSL directory) with
 * `defines` ("NAME VALUE" lines); returns the GL program or 0 (the loader logs why). */
typedef unsigned (*em_program_loader)(void *user, const char *fragment, const char *defines);
typedef void (*em_progress_fn)(void *user, double fraction, const char *what);

typedef struct em_gpu {
    em_program_loader load;
    void *load_user;
    em_progress_fn progress; /* may be NULL; called between draws (after glFinish) */
    void *progress_user;
    int unit;                /* texture unit the passes may use for their input */
    unsigned vao, fbo;
    /* prog_to_cube converts a lat-long, prog_cube_to_cube a cube (envmap_to_cube.frag with
     * ENVMAP_IN_CUBE): the source kind is a permutation */
    unsigned prog_to_cube, prog_ggx, prog_irradiance, prog_lut, prog_downsample, prog_cube_to_cube;
    /* llvmpipe: draw with blending ONE, ZERO (the identity) so that each program compiles once: an
     * "opaque" draw (no depth, no blending) compiles its shader twice there (prefilter.c, draw_into) */
    bool identity_blend;
} em_gpu;

bool em_gpu_init(em_gpu *g, char *err, size_t n);
void em_gpu_free(em_gpu *g);

/* Uploads a lat-long image as RGBA16F with a full mip chain (values already sanitised). */
unsigned em_upload_latlong(const em_image *img);
/* An empty RGBA16F cube of `levels` mips with the filtering and wrapping every cube here has: the
 * prefilter's outputs and the disk cache's loads are the same texture to the GL (on llvmpipe the
 * sampler state is part of each compiled shader variant's key: a cube loaded from the cache with
 * other wrap modes made a warm start compile the forward programs again). */
unsigned em_new_cube(int size, int levels);
/* Uploads six faces (GL order, size², RGBA) as an RGBA16F cube with `levels` levels
 * (level 0 uploaded, the rest each face's 2×2 box mips, made on the CPU). */
unsigned em_upload_cube(float *const faces[6], int size, int levels);
int em_max_levels(int size); /* floor(log2 size) + 1 */
/* A size² RGBA16F cube with its full mip chain from a lat-long (src_is_cube false) or cube
 * source, each texel the average of 4×4 sub-samples read at the mip level matching their
 * footprint, so the mean radiance is kept and small bright features are not missed. The mips
 * are solid-angle-weighted 2×2 means (see envmap_downsample.frag), so every level keeps the
 * source's mean radiance. */
unsigned em_make_base_cube(em_gpu *g, unsigned src, bool src_is_cube, int src_w, int src_h, int size);
/* The split-sum specular chain: an RGBA16F cube of `levels` levels, level m prefiltered for
 * perceptual roughness m/(levels−1) (α = r²) by GGX importance sampling with `samples` samples
 * per texel (n = v = r), each sample read from the base cube at the mip level given by its PDF
 * (Křivánek & Colbert 2008) plus lod_bias. Level 0 is the base cube itself. */
unsigned em_prefilter_ggx(em_gpu *g, unsigned base, int size, int levels, int samples, float lod_bias);
/* Roughness ↔ level of the chain (issue 16 item 4). EM_LEVEL_MAP_SQRT: level m is for perceptual
 * roughness m/(levels−1), looked up at lod = √α·(levels−1) (em_prefilter_ggx, shadelab-cube's
 * files). EM_LEVEL_MAP_LOG: α halves from level to level, α_m = 2^(m−(levels−1)) for m ≥ 1,
 * lod = (levels−1) + log2 α above α_1 and α/α_1 below it (between the mirror and level 1): the
 * lobe's width doubles as the mip's texel does, and neighbouring levels differ by the same
 * ratio everywhere (SQRT's levels 1 and 2 differ by 4×, its last two by 1.4×). */
typedef enum em_level_map { EM_LEVEL_MAP_SQRT = 0, EM_LEVEL_MAP_LOG = 1 } em_level_map;
double em_level_alpha(int level, int levels, em_level_map map); /* α prefiltered into `level` (0 at level 0) */
double em_alpha_lod(double alpha, int levels, em_level_map map); /* the lookup's lod (the GLSL's twin) */
unsigned em_prefilter_ggx_map(em_gpu *g, unsigned base, int size, int levels, int samples, float lod_bias,
                              em_level_map map);
/* The lobe shapes of the SDK's lobe contract (shaders/common.glsl, ABI 1.19): GGX, or normalised
 * Blinn-Phong about the half vector of the power whose D has the median of GGX's at α,
 * em_blinn_power(α) = 2/log2(1 + α²) − 2 (the GLSL's sl_lobe_blinn_power). A Blinn-Phong chain's
 * level m holds the environment filtered by that lobe for em_level_alpha(m): the lookups are the
 * GGX chain's. */
typedef enum em_lobe_shape { EM_LOBE_GGX = 0, EM_LOBE_BLINN_PHONG = 1 } em_lobe_shape;
double em_blinn_power(double alpha);
unsigned em_prefilter_chain(em_gpu *g, unsigned base, int size, int levels, int samples, float lod_bias, em_level_map map,
                            em_lobe_shape shape);
/* Diffuse irradiance cube (out_size², one level): E(n)/π by summing every texel of the base
 * cube's mip of face size src_size (exact cosine-weighted Riemann sum, no noise). */
unsigned em_convolve_irradiance(em_gpu *g, unsigned base, int base_size, int src_size, int out_size);
/* Diffuse irradiance cube E(n)/π of any face size in O(out_size²) (issue 18 item 6), one of:
 *   EM_IRRADIANCE_DIRECT     em_convolve_irradiance at out_size² (every output texel sums all
 *                            6·src_size² source texels: O(out² · src²), the reference);
 *   EM_IRRADIANCE_CONVOLVED  the same exact sum at min(out_size, 32)² only, then bilinearly
 *                            (seamlessly) resampled to out_size²: E/π is smooth (the cosine
 *                            kernel is a low-pass filter), so the interpolation error is small;
 *   EM_IRRADIANCE_SH         the 9-coefficient projection of the base cube's level 0
 *                            (em_sh9_project) evaluated per texel on the CPU (Ramamoorthi &
 *                            Hanrahan 2001), clamped at 0 as the plugin's `irradiance=sh`.
 * src_size as em_convolve_irradiance's; the result is a one-level RGBA16F cube. The tool's
 * README charts the time and the error of each against DIRECT. */
typedef enum em_irradiance_method { EM_IRRADIANCE_DIRECT, EM_IRRADIANCE_CONVOLVED, EM_IRRADIANCE_SH } em_irradiance_method;
#define EM_IRRADIANCE_GRID 32 /* the face size CONVOLVED integrates at */
unsigned em_irradiance_cube(em_gpu *g, unsigned base, int base_size, int src_size, int out_size,
                            em_irradiance_method method);
/* Environment-BRDF LUT (RGBA16F, size²): x = n·v, y = perceptual roughness r (α = r²), at
 * texel centres x_i = i/(size−1): R, G = (A, B) with ∫ f_s cos = F0·A + B (Schlick), VNDF
 * sampled with `samples` samples and the ggx plugin's separable Smith G; B = the diffuse weight
 * C(n·v) = ∫ (1 − v·h)^5 cos/π dl (independent of r), so ∫ (1 − F(v·h)) cos/π = (1 − F0)(1 − C);
 * A = 1. */
unsigned em_brdf_lut(em_gpu *g, int size, int samples);
/* Reads a cube level (6 faces of size², GL order) or a 2D texture (RGBA floats, GL row order:
 * row 0 = t = 0). Returns malloc'd memory. */
float *em_read_cube(unsigned tex, int level, int size);
float *em_read_2d(unsigned tex, int w, int h);
/* Uploads stored levels as a cube with exactly those levels (cache, precomputed chains). */
unsigned em_upload_cube_levels(float *const *levels_faces, int size, int levels);
/* The source file of a stored prefilter output and the GLSL the results depend on (the plugin's
 * files in glsl_dir and the SDK shader library's ggx_brdf.glsl in shader_dir). */
uint64_t em_glsl_hash(const char *glsl_dir, const char *shader_dir);

#ifdef __cplusplus
}
#endif
#endif
