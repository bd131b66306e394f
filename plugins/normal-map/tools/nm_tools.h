/* normal-map offline tools (linked into shadelab-bake-normals and the plugin tests):
 *   - procedural tangent-space normal maps and property (gloss/AO) maps from analytic height
 *     fields, for scenes and tests that need no files;
 *   - the bake: a tangent-space map → an object-space map for a mesh, using the project's own
 *     tangent frames (the ones the renderer interpolates), by CPU rasterisation in UV space;
 *   - a green-convention detector (+Y or −Y) from the curl of the map's slope field.
 *
 * Image convention (the core's, scenes/README.md; see nm_lib.glsl): sl_image row 0 is the TOP
 * of the image and texture coordinate v = 0 samples the top row, so texel (col, row) has its
 * centre at uv = ((col + 0.5)/W, (row + 0.5)/H), and "image up" is −v. Tangent-space maps here
 * are +Y (green = slope toward image up) unless stated. */
#ifndef NM_TOOLS_H
#define NM_TOOLS_H

#include "toolkit.h" /* the core for tools: sl_image, sl_mesh_data, scene files */
#include <stdbool.h>
#include <stddef.h>

/* Must agree with NM_IMAGE_UP_SIGN in nm_lib.glsl: image up = sign · bitangent. */
#define NM_IMAGE_UP_SIGN (1.0f)

/* Procedural tangent-space normal map, size×size, +Y convention, values n·0.5 + 0.5 (float
 * RGBA; write it as PNG for 8 bits or EXR for half floats). Height fields over image
 * coordinates X = u (right), Y = image up, both 0..1; slopes are dimensionless.
 *   "flat"            (0, 0, 1)
 *   "tilt:X,Y"        constant normal (X, Y, √(1−X²−Y²)), X² + Y² ≤ 1
 *   "bumps:N:A"       h = A/(2πN)·sin(2πNX)·sin(2πNY): N×N egg-crate bumps, slope amplitude A
 *   "waves:N:A:SEED"  six random plane waves with integer frequencies in [N/2, N] (tileable),
 *                     total slope amplitude about A
 * Returns false with a message naming the spec on a malformed spec. */
bool nm_generate_tangent_map(sl_image *out, const char *spec, int size, char *err, size_t err_size);

/* Procedural property map for the phong plugin: R = gloss, G = 0, B = ambient occlusion.
 *   "property:N:A"    gloss 0.85 in a 4×4 checker of squares, 0.35 elsewhere; AO from the
 *                     height of "bumps:N:A": 1 on the crests, 0.45 in the hollows
 *   "constant:G,AO"   constant gloss and AO */
bool nm_generate_property_map(sl_image *out, const char *spec, int size, char *err, size_t err_size);

/* Height of "bumps:N:A" at image coordinates (X, Y) (for tests that compare with geometry). */
float nm_bumps_height(float X, float Y, int n, float amplitude);

typedef struct nm_bake_opts {
    int green_sign;    /* +1: the tangent map is +Y (OpenGL); −1: −Y (DirectX) */
    float strength;    /* tangent-space xy scale, as the shader's normal_strength (1) */
    int dilate;        /* texels of padding grown around UV islands (8 is plenty) */
} nm_bake_opts;

/* Bakes `tangent_map` onto the triangles of `meshes` (object space, with their tangents) into
 * `out` (width×height, allocated here, RGBA, n·0.5 + 0.5, alpha 1 where covered). Texels no
 * triangle covers after dilation are (0.5, 0.5, 0.5): they decode to the zero vector, which
 * the shader replaces by the interpolated normal. Triangles with a zero-area UV footprint cover
 * no texel. Returns the number of covered texels (before dilation), or −1 on error. */
long nm_bake_object_space(const sl_mesh_data *const *meshes, int mesh_count, const sl_image *tangent_map,
                          const nm_bake_opts *opts, int width, int height, sl_image *out, char *err,
                          size_t err_size);

/* Estimates a tangent-space map's green convention: the slope field (−x/z, −y/z) of a height
 * field is curl-free, and it stays so only under the right sign of y. Writes the mean |curl|
 * under each hypothesis; returns +1 (+Y, OpenGL) or −1 (−Y, DirectX). */
int nm_detect_green(const sl_image *map, double *curl_plus_y, double *curl_minus_y);

/* Bilinear sample of an RGBA image at uv with repeat wrapping (v = 0 at the top row). */
void nm_sample_bilinear(const sl_image *img, float u, float v, float out[4]);

#endif
