/* The glTF conformance table (tests/data/gltf_models.tsv): one row per glTF2 model Debian ships
 * (package assimp-testmodels, installed by tools/install-deps.sh with the test dependencies) and
 * one per feature file this test writes from the specification (tests/gltf_writer.h), each opened
 * directly as a scene: it opens with N meshes, M textures (distinct texture values of its
 * materials), C cameras and L lights, or fails with an error containing a stated cause.
 *
 * A feature file states its expectation in itself (asset.extras.expect, computed here from the
 * specification's formulas, not by the reader): the corners of mesh 0's triangles (positions,
 * normals, UVs; a triangle may start at any of its corners, its winding may not change), a
 * texture slot's UV mapping, each mesh's material values, the first camera, the first light, mesh 0's
 * skin and morph targets (sl_mesh_deform). The table's last column names
 * the expectations the file met, so a change in what any one file does shows.
 *
 *   test_gltf_models                 check every row (a model missing from the table, or a row
 *                                    whose file is gone, fails too)
 *   test_gltf_models --print         print the table as the code sees it (to review a change) */
#include "check.h"
#include "gltf_writer.h"
#include "log.h"
#include "scene/scene.h"
#include "test_tmp.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define MODELS "/usr/share/assimp/models/glTF2"
#define TABLE SL_TEST_DATA_DIR "/gltf_models.tsv"

static char keys[320][1024], files[320][1200];
static int nkeys;

static void find(const char *dir, int depth) {
    DIR *d = opendir(dir);
    if (!d || depth > 6) {
        if (d) closedir(d);
        return;
    }
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.') continue;
        char p[1024];
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        struct stat st;
        if (stat(p, &st) != 0) continue;
        if (S_ISDIR(st.st_mode)) find(p, depth + 1);
        size_t n = strlen(p);
        if (S_ISREG(st.st_mode) && nkeys < 256 &&
            ((n > 5 && !strcmp(p + n - 5, ".gltf")) || (n > 4 && !strcmp(p + n - 4, ".glb")))) {
            snprintf(keys[nkeys], sizeof keys[0], "%s", p + strlen(MODELS) + 1);
            snprintf(files[nkeys++], sizeof files[0], "%s", p);
        }
    }
    closedir(d);
}

/* ---- feature files, from the specification ------------------------------------------------ */

/* the base quad (gw_quad): corners of triangles (0, 1, 2) and (0, 2, 3) */
static const float quad_p[4][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
static const float quad_uv[4][2] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
static const int quad_tris[6] = {0, 1, 2, 0, 2, 3};

/* A 1×1 RGBA (255, 255, 255, 255) PNG: the feature files' texture 0, so that each also renders */
static const unsigned char white_png[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00,
    0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1f, 0x15, 0xc4, 0x89, 0x00,
    0x00, 0x00, 0x0b, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0xf8, 0x0f, 0x04, 0x00, 0x09, 0xfb, 0x03,
    0xfd, 0x68, 0xfa, 0x1c, 0xcc, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

/* asset.extras.expect.<key> = the values of `corners` (count × comps floats) */
static void expect_array(gw_doc *g, const char *key, const float *v, int n) {
    char *text = malloc((size_t)n * 24 + 16), ptr[96];
    size_t u = (size_t)sprintf(text, "[");
    for (int i = 0; i < n; i++) u += (size_t)sprintf(text + u, "%s%.9g", i ? ", " : "", v[i]);
    sprintf(text + u, "]");
    snprintf(ptr, sizeof ptr, "/asset/extras/expect/%s", key);
    gw_set(g, ptr, text);
    free(text);
}

/* The expectation of a quad whose triangle corners are tris (vertex indices) of p / uv / normals. */
static void expect_quad(gw_doc *g, const float (*p)[3], const int *tris, int ntris, const float (*n)[3]) {
    float c[3 * 12], nn[3 * 12], uv[2 * 12];
    for (int i = 0; i < 3 * ntris; i++) {
        memcpy(c + 3 * i, p[tris[i]], 12);
        memcpy(uv + 2 * i, quad_uv[tris[i] % 4], 8);
        const float z[3] = {0, 0, 1};
        memcpy(nn + 3 * i, n ? n[i] : z, 12);
    }
    expect_array(g, "corners", c, 9 * ntris);
    expect_array(g, "normals", nn, 9 * ntris);
    if (!n) expect_array(g, "uvs", uv, 6 * ntris);
}

static void f_baseline(gw_doc *g) { expect_quad(g, quad_p, quad_tris, 2, NULL); }

static void f_indices_u8(gw_doc *g) {
    const uint8_t idx[6] = {0, 1, 2, 0, 2, 3};
    char s[16];
    snprintf(s, sizeof s, "%d", gw_data(g, idx, sizeof idx, 5121, 6, "SCALAR"));
    gw_set(g, "/meshes/0/primitives/0/indices", s);
    expect_quad(g, quad_p, quad_tris, 2, NULL);
}

static void f_indices_u32(gw_doc *g) {
    gw_set(g, "/meshes/0/primitives/0/indices", "6"); /* gw_quad's u32 copy */
    expect_quad(g, quad_p, quad_tris, 2, NULL);
}

/* POSITION and NORMAL interleaved in one bufferView, byteStride 24 (§3.6.2.4) */
static void f_interleaved(gw_doc *g) {
    float v[24];
    for (int i = 0; i < 4; i++) memcpy(v + 6 * i, quad_p[i], 12), v[6 * i + 3] = 0, v[6 * i + 4] = 0, v[6 * i + 5] = 1;
    int view = gw_view(g, gw_append(g, v, sizeof v), sizeof v, 24);
    char a[160];
    snprintf(a, sizeof a, "{\"bufferView\": %d, \"byteOffset\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\"}", view);
    gw_set(g, "/accessors/0", a);
    snprintf(a, sizeof a, "{\"bufferView\": %d, \"byteOffset\": 12, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\"}", view);
    gw_set(g, "/accessors/1", a);
    expect_quad(g, quad_p, quad_tris, 2, NULL);
}

/* a sparse accessor (§3.6.2.3): vertex 2 of the positions substituted by (2, 2, 0) */
static void sparse_positions(gw_doc *g, int count, const uint16_t *idx, const float *values, bool zeros) {
    size_t ia = gw_append(g, idx, sizeof(uint16_t) * (size_t)count), va = gw_append(g, values, 12 * (size_t)count);
    char s[300];
    snprintf(s, sizeof s, "{\"count\": %d, \"indices\": {\"bufferView\": %d, \"componentType\": 5123}, \"values\": "
             "{\"bufferView\": %d}}", count, gw_view(g, ia, sizeof(uint16_t) * (size_t)count, 0), gw_view(g, va, 12 * (size_t)count, 0));
    gw_set(g, "/accessors/0/sparse", s);
    if (zeros) gw_set(g, "/accessors/0/bufferView", NULL);
}
static void f_sparse(gw_doc *g) {
    const uint16_t idx[1] = {2};
    const float v[3] = {2, 2, 0};
    sparse_positions(g, 1, idx, v, false);
    float p[4][3];
    memcpy(p, quad_p, sizeof p);
    memcpy(p[2], v, 12);
    expect_quad(g, (const float (*)[3])p, quad_tris, 2, NULL);
}
static void f_sparse_without_view(gw_doc *g) { /* zeros, then all four corners substituted */
    const uint16_t idx[4] = {0, 1, 2, 3};
    sparse_positions(g, 4, idx, &quad_p[0][0], true);
    expect_quad(g, quad_p, quad_tris, 2, NULL);
}

/* TEXCOORD_0 as normalized unsigned bytes / shorts: c / 255, c / 65535 (§3.11) */
static void f_uv_normalized(gw_doc *g, bool shorts) {
    const uint8_t b[8] = {51, 204, 255, 204, 255, 0, 51, 0};
    const uint16_t s[8] = {13107, 52428, 65535, 52428, 65535, 0, 13107, 0};
    char a[200];
    size_t at = shorts ? gw_append(g, s, sizeof s) : gw_append(g, b, sizeof b);
    snprintf(a, sizeof a, "{\"bufferView\": %d, \"componentType\": %d, \"normalized\": true, \"count\": 4, \"type\": \"VEC2\"}",
             gw_view(g, at, shorts ? sizeof s : sizeof b, 0), shorts ? 5123 : 5121);
    gw_set(g, "/accessors/2", a);
    float uv[12];
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 2; c++) uv[2 * i + c] = shorts ? s[2 * quad_tris[i] + c] / 65535.0f : b[2 * quad_tris[i] + c] / 255.0f;
    expect_quad(g, quad_p, quad_tris, 2, NULL);
    expect_array(g, "uvs", uv, 12);
}
static void f_uv_u8n(gw_doc *g) { f_uv_normalized(g, false); }
static void f_uv_u16n(gw_doc *g) { f_uv_normalized(g, true); }

/* KHR_mesh_quantization: positions as shorts, normalized (max(c / 32767, −1)) or not, stride 8 */
static void quantized(gw_doc *g, bool normalized) {
    const int16_t q[16] = {-32767, -32767, 0, 0, 32767, -16384, 0, 0, 16384, 32767, 0, 0, -32768, 100, 0, 0};
    char a[200];
    int view = gw_view(g, gw_append(g, q, sizeof q), sizeof q, 8);
    snprintf(a, sizeof a, "{\"bufferView\": %d, \"componentType\": 5122%s, \"count\": 4, \"type\": \"VEC3\"}", view,
             normalized ? ", \"normalized\": true" : "");
    gw_set(g, "/accessors/0", a);
    gw_set(g, "/extensionsUsed", "[\"KHR_mesh_quantization\"]");
    gw_set(g, "/extensionsRequired", "[\"KHR_mesh_quantization\"]");
    float p[4][3];
    for (int i = 0; i < 4; i++)
        for (int c = 0; c < 3; c++) p[i][c] = normalized ? fmaxf(q[4 * i + c] / 32767.0f, -1.0f) : (float)q[4 * i + c];
    expect_quad(g, (const float (*)[3])p, quad_tris, 2, NULL); /* still planar: NORMAL's +Z stands */
}
static void f_quantized_i16n(gw_doc *g) { quantized(g, true); }
static void f_quantized_i16(gw_doc *g) { quantized(g, false); }

/* modes 5 and 6 (§3.7.2.1): strip triangle i = (v_i, v_{i+1+i%2}, v_{i+2−i%2}), fan (v_{i+1}, v_{i+2}, v_0) */
static void strip_or_fan(gw_doc *g, int mode) {
    const uint16_t strip[4] = {0, 1, 3, 2}, fan[4] = {0, 1, 2, 3};
    const uint16_t *list = mode == 5 ? strip : fan;
    char s[32];
    snprintf(s, sizeof s, "%d", gw_data(g, list, 8, 5123, 4, "SCALAR"));
    gw_set(g, "/meshes/0/primitives/0/indices", s);
    snprintf(s, sizeof s, "%d", mode);
    gw_set(g, "/meshes/0/primitives/0/mode", s);
    int tris[6];
    for (int i = 0; i < 2; i++) {
        const int *t = mode == 5 ? (int[3]){list[i], list[i + 1 + i % 2], list[i + 2 - i % 2]}
                                 : (int[3]){list[i + 1], list[i + 2], list[0]};
        memcpy(tris + 3 * i, t, sizeof(int) * 3);
    }
    expect_quad(g, quad_p, tris, 2, NULL);
}
static void f_strip(gw_doc *g) { strip_or_fan(g, 5); }
static void f_fan(gw_doc *g) { strip_or_fan(g, 6); }

/* no indices: vertices 0, 1, 2 and 0, 2, 3 written out */
static void f_non_indexed(gw_doc *g) {
    float p[18], n[18], uv[12];
    for (int i = 0; i < 6; i++)
        memcpy(p + 3 * i, quad_p[quad_tris[i]], 12), memcpy(uv + 2 * i, quad_uv[quad_tris[i]], 8), n[3 * i] = n[3 * i + 1] = 0,
                                                                                                  n[3 * i + 2] = 1;
    char s[160];
    snprintf(s, sizeof s, "{\"POSITION\": %d, \"NORMAL\": %d, \"TEXCOORD_0\": %d}", gw_data(g, p, sizeof p, 5126, 6, "VEC3"),
             gw_data(g, n, sizeof n, 5126, 6, "VEC3"), gw_data(g, uv, sizeof uv, 5126, 6, "VEC2"));
    gw_set(g, "/meshes/0/primitives/0/attributes", s);
    gw_set(g, "/meshes/0/primitives/0/indices", NULL);
    expect_quad(g, quad_p, quad_tris, 2, NULL);
}

/* no NORMAL: flat normals (§3.7.2.1), the quad folded so its two triangles differ */
static void f_flat_normals(gw_doc *g) {
    float p[4][3];
    memcpy(p, quad_p, sizeof p);
    p[3][2] = 1; /* vertex 3 forward */
    char s[64];
    snprintf(s, sizeof s, "%d", gw_data(g, p, sizeof p, 5126, 4, "VEC3"));
    gw_set(g, "/meshes/0/primitives/0/attributes/POSITION", s);
    gw_set(g, "/meshes/0/primitives/0/attributes/NORMAL", NULL);
    float n[6][3];
    for (int t = 0; t < 2; t++) {
        const float *a = p[quad_tris[3 * t]], *b = p[quad_tris[3 * t + 1]], *c = p[quad_tris[3 * t + 2]];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double x[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double l = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < 3; i++) n[3 * t + k][i] = (float)(x[i] / l);
    }
    expect_quad(g, (const float (*)[3])p, quad_tris, 2, (const float (*)[3])n);
}

/* a morph target moving every vertex by (0.5, 0, 0), the mesh's default weight 0.5 (§3.7.2.2) */
static void f_morph_default_weights(gw_doc *g) {
    const float d[12] = {0.5f, 0, 0, 0.5f, 0, 0, 0.5f, 0, 0, 0.5f, 0, 0};
    char s[96];
    snprintf(s, sizeof s, "[{\"POSITION\": %d}]", gw_data(g, d, sizeof d, 5126, 4, "VEC3"));
    gw_set(g, "/meshes/0/primitives/0/targets", s);
    gw_set(g, "/meshes/0/weights", "[0.5]");
    float p[4][3];
    memcpy(p, quad_p, sizeof p);
    for (int i = 0; i < 4; i++) p[i][0] += 0.25f;
    expect_quad(g, (const float (*)[3])p, quad_tris, 2, NULL);
}

/* a skin (§3.7.3) of one joint, node 2 at (0, 0, 1), its inverse bind matrix T(0, 0, −1); every
 * vertex bound to it alone: the reader keeps the joint, the matrix and 4 influences per vertex */
static void f_skin(gw_doc *g) {
    const uint8_t j[16] = {0};
    const float w[16] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    const float ibm[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -1, 1};
    char s[200];
    snprintf(s, sizeof s, "%d", gw_data(g, j, sizeof j, 5121, 4, "VEC4"));
    gw_set(g, "/meshes/0/primitives/0/attributes/JOINTS_0", s);
    snprintf(s, sizeof s, "%d", gw_data(g, w, sizeof w, 5126, 4, "VEC4"));
    gw_set(g, "/meshes/0/primitives/0/attributes/WEIGHTS_0", s);
    snprintf(s, sizeof s, "[{\"joints\": [2], \"inverseBindMatrices\": %d}]", gw_data(g, ibm, sizeof ibm, 5126, 1, "MAT4"));
    gw_set(g, "/skins", s);
    gw_set(g, "/nodes/0/skin", "0");
    gw_set(g, "/nodes/2", "{\"name\": \"joint\", \"translation\": [0, 0, 1]}");
    gw_set(g, "/scenes/0/nodes/2", "2");
    expect_quad(g, quad_p, quad_tris, 2, NULL);
    gw_set(g, "/asset/extras/expect/deform", "{\"joints\": 1, \"influences\": 4, \"targets\": 0, "
           "\"inverse_bind\": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -1, 1]}");
}

/* two morph targets (§3.7.2.2), mesh weights [0.5, 0] (the shape shown at rest), and a `weights`
 * channel of 2 keys × 2 weights in place of the translation */
static void f_morph_animated(gw_doc *g) {
    const float d[12] = {0.5f, 0, 0, 0.5f, 0, 0, 0.5f, 0, 0, 0.5f, 0, 0}, e[12] = {0, 0.5f, 0, 0, 0.5f, 0, 0, 0.5f, 0, 0, 0.5f, 0};
    const float w[4] = {0, 0, 1, 1};
    char s[200];
    int a = gw_data(g, d, sizeof d, 5126, 4, "VEC3"), b = gw_data(g, e, sizeof e, 5126, 4, "VEC3");
    snprintf(s, sizeof s, "[{\"POSITION\": %d}, {\"POSITION\": %d}]", a, b);
    gw_set(g, "/meshes/0/primitives/0/targets", s);
    gw_set(g, "/meshes/0/weights", "[0.5, 0]");
    snprintf(s, sizeof s, "%d", gw_data(g, w, sizeof w, 5126, 4, "SCALAR"));
    gw_set(g, "/animations/0/samplers/0/output", s);
    gw_set(g, "/animations/0/channels/0/target/path", "\"weights\"");
    float p[4][3];
    memcpy(p, quad_p, sizeof p);
    for (int i = 0; i < 4; i++) p[i][0] += 0.25f;
    expect_quad(g, (const float (*)[3])p, quad_tris, 2, NULL);
    gw_set(g, "/asset/extras/expect/deform", "{\"joints\": 0, \"influences\": 0, \"targets\": 2, \"rest_weights\": [0.5, 0], "
           "\"weights_channel\": 2}");
}

/* a base colour texture on UV set 1 with KHR_texture_transform (the extension's texCoord wins) */
static void f_texture_transform(gw_doc *g) {
    char s[256];
    snprintf(s, sizeof s, "[{\"bufferView\": %d, \"mimeType\": \"image/png\"}]", gw_view(g, gw_append(g, white_png, sizeof white_png), sizeof white_png, 0));
    gw_set(g, "/images", s);
    gw_set(g, "/textures", "[{\"source\": 0}]");
    gw_set(g, "/extensionsUsed", "[\"KHR_texture_transform\"]");
    gw_set(g, "/materials/0/pbrMetallicRoughness/baseColorTexture", "{\"index\": 0, \"texCoord\": 0, \"extensions\": "
           "{\"KHR_texture_transform\": {\"offset\": [0.25, -0.5], \"rotation\": 0.75, \"scale\": [2, 3], \"texCoord\": 1}}}");
    gw_set(g, "/meshes/0/primitives/0/attributes/TEXCOORD_1", "2");
    gw_set(g, "/asset/extras/expect/uv_map", "{\"input\": \"base_color_texture\", \"texcoord\": 1, \"offset\": [0.25, -0.5], "
           "\"rotation\": 0.75, \"scale\": [2, 3]}");
}

/* cameras (§3.10): at node "eye" (0, 0, 3), looking down −Z */
static void f_camera_perspective(gw_doc *g) {
    gw_set(g, "/cameras/0", "{\"type\": \"perspective\", \"perspective\": {\"yfov\": 0.6, \"aspectRatio\": 1.5, \"znear\": 0.25, \"zfar\": 40}}");
    char s[200];
    snprintf(s, sizeof s, "{\"fov_y_deg\": %.9g, \"znear\": 0.25, \"zfar\": 40, \"orthographic\": false, \"position\": [0, 0, 3], "
             "\"target\": [0, 0, 2]}", 0.6 * 180 / M_PI);
    gw_set(g, "/asset/extras/expect/camera", s);
}
static void f_camera_orthographic(gw_doc *g) {
    gw_set(g, "/cameras/0", "{\"type\": \"orthographic\", \"orthographic\": {\"xmag\": 2, \"ymag\": 1.5, \"znear\": 0, \"zfar\": 9}}");
    gw_set(g, "/asset/extras/expect/camera", "{\"ymag\": 1.5, \"znear\": 0, \"zfar\": 9, \"orthographic\": true, "
           "\"position\": [0, 0, 3], \"target\": [0, 0, 2]}");
}

/* KHR_lights_punctual: a spot at node "eye", its cone half-angles in degrees, glTF's fall-off */
static void f_light_spot(gw_doc *g) {
    gw_set(g, "/extensionsUsed", "[\"KHR_lights_punctual\"]");
    gw_set(g, "/extensions", "{\"KHR_lights_punctual\": {\"lights\": [{\"type\": \"spot\", \"color\": [1, 0.5, 0.25], "
           "\"intensity\": 20, \"spot\": {\"innerConeAngle\": 0.25, \"outerConeAngle\": 0.5}}]}}");
    gw_set(g, "/nodes/1/extensions", "{\"KHR_lights_punctual\": {\"light\": 0}}");
    char s[240];
    snprintf(s, sizeof s, "{\"type\": \"spot\", \"intensity\": 20, \"color\": [1, 0.5, 0.25], \"cone_angle\": %.9g, "
             "\"inner_cone_angle\": %.9g, \"position\": [0, 0, 3], \"direction\": [0, 0, -1]}", 0.5 * 180 / M_PI, 0.25 * 180 / M_PI);
    gw_set(g, "/asset/extras/expect/light", s);
}

/* Three meshes, three materials all named "paint", each with its own KHR_materials_ior,
 * emissive strength and texture offset, listed in the file in another order than the meshes use
 * them: every mesh must get its own primitive's material (the file's index, whatever the name). */
static void f_material_identity(gw_doc *g) {
    char s[600];
    snprintf(s, sizeof s, "[{\"bufferView\": %d, \"mimeType\": \"image/png\"}]", gw_view(g, gw_append(g, white_png, sizeof white_png), sizeof white_png, 0));
    gw_set(g, "/images", s);
    gw_set(g, "/textures", "[{\"source\": 0}]");
    gw_set(g, "/extensionsUsed", "[\"KHR_texture_transform\", \"KHR_materials_ior\", \"KHR_materials_emissive_strength\"]");
    const double ior[3] = {1.2, 1.9, 2.6}, strength[3] = {2, 5, 9}, offset[3] = {0.1, 0.4, 0.7};
    for (int m = 0; m < 3; m++) {
        snprintf(s, sizeof s, "{\"name\": \"paint\", \"emissiveFactor\": [1, 1, 1], \"pbrMetallicRoughness\": "
                 "{\"baseColorTexture\": {\"index\": 0, \"extensions\": {\"KHR_texture_transform\": {\"offset\": [%g, 0]}}}}, "
                 "\"extensions\": {\"KHR_materials_ior\": {\"ior\": %g}, \"KHR_materials_emissive_strength\": "
                 "{\"emissiveStrength\": %g}}}", offset[m], ior[m], strength[m]);
        char ptr[32];
        snprintf(ptr, sizeof ptr, "/materials/%d", m);
        gw_set(g, ptr, s);
    }
    /* meshes 0, 1, 2 use materials 2, 0, 1; nodes 0, 2, 3 show them side by side */
    for (int k = 0; k < 3; k++) {
        char ptr[32];
        snprintf(s, sizeof s, "{\"name\": \"quad%d\", \"primitives\": [{\"attributes\": {\"POSITION\": 0, \"NORMAL\": 1, "
                 "\"TEXCOORD_0\": 2}, \"indices\": 3, \"material\": %d}]}", k, (k + 2) % 3);
        snprintf(ptr, sizeof ptr, "/meshes/%d", k);
        gw_set(g, ptr, s);
        snprintf(s, sizeof s, "{\"mesh\": %d, \"translation\": [%d, 0, 0]}", k, 3 * k);
        snprintf(ptr, sizeof ptr, "/nodes/%d", k == 0 ? 0 : k + 1);
        gw_set(g, ptr, s);
    }
    gw_set(g, "/scenes/0/nodes", "[0, 1, 2, 3]");
    size_t u = (size_t)snprintf(s, sizeof s, "[");
    for (int k = 0; k < 3; k++) {
        int m = (k + 2) % 3;
        u += (size_t)snprintf(s + u, sizeof s - u, "%s{\"ior\": %g, \"emissive_strength\": %g, \"offset\": %g}", k ? ", " : "",
                              ior[m], strength[m], offset[m]);
    }
    snprintf(s + u, sizeof s - u, "]");
    gw_set(g, "/asset/extras/expect/materials", s);
}

/* One material with one KHR_materials layer (ext: its JSON, with texture 0 where it names one); the
 * inputs the reader must publish for it (want: {"input": number | true (a texture) | false
 * (absent)}), as the ggx keys that take them read them. */
static void layer_feature(gw_doc *g, const char *name, const char *ext, const char *want) {
    char s[1200];
    snprintf(s, sizeof s, "[{\"bufferView\": %d, \"mimeType\": \"image/png\"}]", gw_view(g, gw_append(g, white_png, sizeof white_png), sizeof white_png, 0));
    gw_set(g, "/images", s);
    gw_set(g, "/textures", "[{\"source\": 0}]");
    snprintf(s, sizeof s, "[\"%s\"]", name);
    gw_set(g, "/extensionsUsed", s);
    snprintf(s, sizeof s, "{\"name\": \"layered\", \"extensions\": {\"%s\": %s}}", name, ext);
    gw_set(g, "/materials/0", s);
    gw_set(g, "/meshes/0/primitives/0/material", "0");
    gw_set(g, "/asset/extras/expect/inputs", want);
}
static void f_clearcoat(gw_doc *g) {
    layer_feature(g, "KHR_materials_clearcoat",
                  "{\"clearcoatFactor\": 0.8, \"clearcoatRoughnessFactor\": 0.25, \"clearcoatTexture\": {\"index\": 0}, "
                  "\"clearcoatNormalTexture\": {\"index\": 0, \"scale\": 0.5}}",
                  "{\"clearcoat\": 0.8, \"clearcoat_roughness\": 0.25, \"clearcoat_texture\": true, "
                  "\"clearcoat_roughness_texture\": false, \"clearcoat_normal_texture\": true, \"clearcoat_normal_scale\": 0.5}");
}
/* clearcoatFactor 0 (the default) is no coat, whatever else is given */
static void f_clearcoat_zero(gw_doc *g) {
    layer_feature(g, "KHR_materials_clearcoat", "{\"clearcoatRoughnessFactor\": 0.25, \"clearcoatTexture\": {\"index\": 0}}",
                  "{\"clearcoat\": false, \"clearcoat_roughness\": false, \"clearcoat_texture\": false}");
}

/* only what differs from the defaults (1, [1, 1, 1]) is published */
static void f_specular(gw_doc *g) {
    layer_feature(g, "KHR_materials_specular",
                  "{\"specularFactor\": 0.5, \"specularColorFactor\": [1, 0.5, 0.25], \"specularTexture\": {\"index\": 0}}",
                  "{\"specular\": 0.5, \"specular_color\": 1, \"specular_texture\": true, \"specular_color_texture\": false}");
}
static void f_specular_defaults(gw_doc *g) {
    layer_feature(g, "KHR_materials_specular", "{\"specularFactor\": 1}", "{\"specular\": false, \"specular_color\": false}");
}
static void f_sheen(gw_doc *g) {
    layer_feature(g, "KHR_materials_sheen",
                  "{\"sheenColorFactor\": [0.9, 0.6, 0.3], \"sheenRoughnessFactor\": 0.4, \"sheenColorTexture\": {\"index\": 0}}",
                  "{\"sheen_color\": 0.9, \"sheen_roughness\": 0.4, \"sheen_color_texture\": true, \"sheen_roughness_texture\": false}");
}
/* a black sheenColorFactor (the default) is no sheen */
static void f_sheen_black(gw_doc *g) {
    layer_feature(g, "KHR_materials_sheen", "{\"sheenRoughnessFactor\": 0.4}", "{\"sheen_color\": false, \"sheen_roughness\": false}");
}
static void f_transmission(gw_doc *g) {
    layer_feature(g, "KHR_materials_transmission", "{\"transmissionFactor\": 0.9, \"transmissionTexture\": {\"index\": 0}}",
                  "{\"transmission\": 0.9, \"transmission_texture\": true}");
}
/* transmissionFactor 0 (the default) is an opaque material, whatever the texture says */
static void f_transmission_zero(gw_doc *g) {
    layer_feature(g, "KHR_materials_transmission", "{\"transmissionTexture\": {\"index\": 0}}",
                  "{\"transmission\": false, \"transmission_texture\": false}");
}
/* KHR_materials_volume over a transmissive material (the extension needs one) */
static void volume_feature(gw_doc *g, const char *ext, const char *want) {
    layer_feature(g, "KHR_materials_volume", ext, want);
    gw_set(g, "/materials/0/extensions/KHR_materials_transmission", "{\"transmissionFactor\": 1}");
    gw_set(g, "/extensionsUsed/1", "\"KHR_materials_transmission\"");
}
static void f_volume(gw_doc *g) {
    volume_feature(g, "{\"thicknessFactor\": 0.25, \"thicknessTexture\": {\"index\": 0}, \"attenuationDistance\": 0.5, "
                      "\"attenuationColor\": [0.8, 0.5, 0.2]}",
                   "{\"transmission\": 1, \"thickness\": 0.25, \"thickness_texture\": true, \"attenuation_distance\": 0.5, "
                   "\"attenuation_color\": 0.8}");
}
/* thicknessFactor 0 (the default) is a thin wall: nothing of the volume is published; an
 * attenuationDistance absent is infinite (no absorption) */
static void f_volume_thin(gw_doc *g) {
    volume_feature(g, "{\"attenuationColor\": [0.8, 0.5, 0.2], \"thicknessTexture\": {\"index\": 0}}",
                   "{\"transmission\": 1, \"thickness\": false, \"thickness_texture\": false, \"attenuation_color\": false}");
}
static void f_volume_no_absorption(gw_doc *g) {
    volume_feature(g, "{\"thicknessFactor\": 2}",
                   "{\"thickness\": 2, \"attenuation_distance\": false, \"attenuation_color\": false}");
}

/* KHR_materials_iridescence: the IOR and thickness range published where not the defaults
 * (1.3, 100, 400 nm) */
static void f_iridescence(gw_doc *g) {
    layer_feature(g, "KHR_materials_iridescence",
                  "{\"iridescenceFactor\": 0.75, \"iridescenceIor\": 1.8, \"iridescenceThicknessMinimum\": 200, "
                  "\"iridescenceThicknessTexture\": {\"index\": 0}}",
                  "{\"iridescence\": 0.75, \"iridescence_ior\": 1.8, \"iridescence_thickness_minimum\": 200, "
                  "\"iridescence_thickness_maximum\": false, \"iridescence_texture\": false, \"iridescence_thickness_texture\": true}");
}
/* iridescenceFactor 0 (the default) is no film, whatever else is given */
static void f_iridescence_zero(gw_doc *g) {
    layer_feature(g, "KHR_materials_iridescence", "{\"iridescenceIor\": 1.8, \"iridescenceTexture\": {\"index\": 0}}",
                  "{\"iridescence\": false, \"iridescence_ior\": false, \"iridescence_texture\": false}");
}
/* a film of thickness 0 (the maximum, without a thickness texture) is no film */
static void f_iridescence_thin(gw_doc *g) {
    layer_feature(g, "KHR_materials_iridescence", "{\"iridescenceFactor\": 1, \"iridescenceThicknessMaximum\": 0}",
                  "{\"iridescence\": false, \"iridescence_thickness_maximum\": false}");
}

/* KHR_materials_dispersion: published where > 0 (here with the volume it builds on) */
static void f_dispersion(gw_doc *g) {
    layer_feature(g, "KHR_materials_dispersion", "{\"dispersion\": 0.36}", "{\"dispersion\": 0.36}");
}
/* dispersion 0 (the default) is none */
static void f_dispersion_zero(gw_doc *g) {
    layer_feature(g, "KHR_materials_dispersion", "{\"dispersion\": 0}", "{\"dispersion\": false}");
}

/* KHR_materials_anisotropy: the rotation published where not 0, reduced to (-2pi, 2pi) */
static void f_anisotropy(gw_doc *g) {
    layer_feature(g, "KHR_materials_anisotropy",
                  "{\"anisotropyStrength\": 0.6, \"anisotropyRotation\": 7.5, \"anisotropyTexture\": {\"index\": 0}}",
                  "{\"anisotropy_strength\": 0.6, \"anisotropy_rotation\": 1.2168147, \"anisotropy_texture\": true}");
}
/* anisotropyStrength 0 (the default) is isotropic, whatever else is given */
static void f_anisotropy_zero(gw_doc *g) {
    layer_feature(g, "KHR_materials_anisotropy", "{\"anisotropyRotation\": 1, \"anisotropyTexture\": {\"index\": 0}}",
                  "{\"anisotropy_strength\": false, \"anisotropy_rotation\": false, \"anisotropy_texture\": false}");
}

static const struct { const char *name; void (*build)(gw_doc *g); } features[] = {
    {"baseline", f_baseline},
    {"indices_u8", f_indices_u8},
    {"indices_u32", f_indices_u32},
    {"interleaved_stride", f_interleaved},
    {"sparse", f_sparse},
    {"sparse_without_bufferview", f_sparse_without_view},
    {"texcoord_u8_normalized", f_uv_u8n},
    {"texcoord_u16_normalized", f_uv_u16n},
    {"quantized_positions_i16_normalized", f_quantized_i16n},
    {"quantized_positions_i16", f_quantized_i16},
    {"triangle_strip", f_strip},
    {"triangle_fan", f_fan},
    {"non_indexed", f_non_indexed},
    {"flat_normals", f_flat_normals},
    {"morph_default_weights", f_morph_default_weights},
    {"morph_animated", f_morph_animated},
    {"skin", f_skin},
    {"texture_transform", f_texture_transform},
    {"camera_perspective", f_camera_perspective},
    {"camera_orthographic", f_camera_orthographic},
    {"light_spot", f_light_spot},
    {"material_identity", f_material_identity},
    {"clearcoat", f_clearcoat},
    {"clearcoat_zero", f_clearcoat_zero},
    {"specular", f_specular},
    {"specular_defaults", f_specular_defaults},
    {"sheen", f_sheen},
    {"sheen_black", f_sheen_black},
    {"transmission", f_transmission},
    {"transmission_zero", f_transmission_zero},
    {"volume", f_volume},
    {"volume_thin", f_volume_thin},
    {"volume_no_absorption", f_volume_no_absorption},
    {"iridescence", f_iridescence},
    {"iridescence_zero", f_iridescence_zero},
    {"iridescence_thin", f_iridescence_thin},
    {"anisotropy", f_anisotropy},
    {"anisotropy_zero", f_anisotropy_zero},
    {"dispersion", f_dispersion},
    {"dispersion_zero", f_dispersion_zero},
};

static void write_features(void) {
    for (size_t i = 0; i < sizeof features / sizeof *features && nkeys < 320; i++) {
        gw_doc g;
        CHECK(gw_quad(&g));
        features[i].build(&g);
        snprintf(keys[nkeys], sizeof keys[0], "feature/%s", features[i].name);
        snprintf(files[nkeys], sizeof files[0], "%s/%s.glb", sl_test_dir(), features[i].name);
        CHECK_MSG(gw_write(&g, files[nkeys], GW_GLB), "writing %s", files[nkeys]);
        nkeys++;
        gw_free(&g);
    }
}

/* ---- the expectation a file states, against the scene read ------------------------------- */

/* asset.extras.expect of a GLB, parsed (NULL when it states none). */
static cJSON *stated_expectation(const char *file) {
    FILE *f = fopen(file, "rb");
    unsigned char h[20];
    if (!f || fread(h, 1, 20, f) != 20 || memcmp(h, "glTF", 4)) {
        if (f) fclose(f);
        return NULL;
    }
    uint32_t len = (uint32_t)h[12] | (uint32_t)h[13] << 8 | (uint32_t)h[14] << 16 | (uint32_t)h[15] << 24;
    char *text = malloc(len + 1);
    bool ok = text && fread(text, 1, len, f) == len;
    fclose(f);
    cJSON *root = ok ? cJSON_ParseWithLength(text, len) : NULL, *expect = NULL;
    free(text);
    expect = cJSON_DetachItemFromObject(cJSON_GetObjectItem(cJSON_GetObjectItem(root, "asset"), "extras"), "expect");
    cJSON_Delete(root);
    return expect;
}

static bool near_values(const cJSON *arr, const float *got, int n, double tol) {
    if (cJSON_GetArraySize(arr) != n) return false;
    for (int i = 0; i < n; i++)
        if (!(fabs(cJSON_GetArrayItem(arr, i)->valuedouble - got[i]) <= tol)) return false;
    return true;
}

/* mesh 0's triangle corners: attribute `attr` (positions/normals/uvs) against the stated ones,
 * each triangle at any starting corner (its winding kept) */
static bool corners_match(const sl_mesh_data *m, const cJSON *expect, const char *key, int comps) {
    const cJSON *want = cJSON_GetObjectItem(expect, key);
    const float *attr = !strcmp(key, "corners") ? m->positions : !strcmp(key, "normals") ? m->normals : m->uvs;
    if (cJSON_GetArraySize(want) != m->index_count * comps) return false;
    for (int t = 0; t < m->index_count / 3; t++) {
        bool any = false;
        for (int r = 0; r < 3 && !any; r++) {
            float got[9];
            for (int k = 0; k < 3; k++) memcpy(got + comps * k, attr + comps * m->indices[3 * t + (k + r) % 3], sizeof(float) * (size_t)comps);
            bool ok = true;
            for (int i = 0; i < 3 * comps && ok; i++)
                ok = fabs(cJSON_GetArrayItem(want, 3 * comps * t + i)->valuedouble - got[i]) <= 1e-6;
            any = ok;
        }
        if (!any) return false;
    }
    return true;
}

static bool uv_map_matches(const sl_scene *s, const cJSON *want) {
    const sl_material *m = &s->materials[s->meshes[0].material];
    const char *input = cJSON_GetObjectItem(want, "input")->valuestring;
    for (int i = 0; i < m->uv_map_count; i++) {
        const sl_uv_mapping *u = &m->uv_maps[i];
        if (strcmp(u->input, input)) continue;
        return u->texcoord == cJSON_GetObjectItem(want, "texcoord")->valueint &&
               near_values(cJSON_GetObjectItem(want, "offset"), u->offset, 2, 1e-7) &&
               fabs(u->rotation - cJSON_GetObjectItem(want, "rotation")->valuedouble) < 1e-7 &&
               near_values(cJSON_GetObjectItem(want, "scale"), u->scale, 2, 1e-7);
    }
    return false;
}

/* Mesh k's material has the stated ior, emissive strength and base colour texture offset. */
static bool materials_match(const sl_scene *s, const cJSON *want) {
    if (s->mesh_count != cJSON_GetArraySize(want)) return false;
    for (int k = 0; k < s->mesh_count; k++) {
        const cJSON *w = cJSON_GetArrayItem(want, k);
        const sl_material *m = &s->materials[s->meshes[k].material];
        const sl_prop *ior = sl_prop_find(&m->inputs, "ior"), *es = sl_prop_find(&m->inputs, "emissive_strength");
        if (!ior || !es || m->uv_map_count != 1 || fabs(ior->v[0] - cJSON_GetObjectItem(w, "ior")->valuedouble) > 1e-6 ||
            fabs(es->v[0] - cJSON_GetObjectItem(w, "emissive_strength")->valuedouble) > 1e-6 ||
            fabs(m->uv_maps[0].offset[0] - cJSON_GetObjectItem(w, "offset")->valuedouble) > 1e-6)
            return false;
    }
    return true;
}

/* the inputs of mesh 0's material: a number its value, true present, false absent */
static bool inputs_match(const sl_scene *s, const cJSON *want) {
    if (s->mesh_count < 1) return false;
    const sl_material *m = &s->materials[s->meshes[0].material];
    const cJSON *w;
    cJSON_ArrayForEach(w, want) {
        const sl_prop *p = sl_prop_find(&m->inputs, w->string);
        if (cJSON_IsFalse(w) ? p != NULL : !p) return false;
        if (cJSON_IsNumber(w) && fabs(p->v[0] - w->valuedouble) > 1e-6) return false;
    }
    return true;
}

static bool camera_matches(const sl_scene *s, const cJSON *want) {
    if (s->camera_count < 1) return false;
    const sl_camera *c = &s->cameras[0];
    const cJSON *v;
    bool ok = cJSON_IsTrue(cJSON_GetObjectItem(want, "orthographic")) == c->orthographic &&
              near_values(cJSON_GetObjectItem(want, "position"), c->position, 3, 1e-6) &&
              near_values(cJSON_GetObjectItem(want, "target"), c->target, 3, 1e-6) &&
              fabs(cJSON_GetObjectItem(want, "znear")->valuedouble - c->znear) < 1e-6 &&
              fabs(cJSON_GetObjectItem(want, "zfar")->valuedouble - c->zfar) < 1e-5;
    if ((v = cJSON_GetObjectItem(want, "fov_y_deg"))) ok = ok && fabs(v->valuedouble - c->fov_y_deg) < 1e-4;
    if ((v = cJSON_GetObjectItem(want, "ymag"))) ok = ok && fabs(v->valuedouble - c->ymag) < 1e-6;
    return ok;
}

static bool light_matches(const sl_scene *s, const cJSON *want) {
    if (s->light_count < 1) return false;
    const sl_light *l = &s->lights[0];
    const sl_prop *cone = sl_prop_find(&l->props, "cone_angle"), *inner = sl_prop_find(&l->props, "inner_cone_angle");
    return !strcmp(l->type, cJSON_GetObjectItem(want, "type")->valuestring) &&
           fabs(l->intensity - cJSON_GetObjectItem(want, "intensity")->valuedouble) < 1e-5 &&
           near_values(cJSON_GetObjectItem(want, "color"), l->color, 3, 1e-6) &&
           near_values(cJSON_GetObjectItem(want, "position"), l->position, 3, 1e-6) &&
           near_values(cJSON_GetObjectItem(want, "direction"), l->direction, 3, 1e-6) && cone && inner &&
           fabs(cone->v[0] - cJSON_GetObjectItem(want, "cone_angle")->valuedouble) < 1e-4 &&
           fabs(inner->v[0] - cJSON_GetObjectItem(want, "inner_cone_angle")->valuedouble) < 1e-4;
}

/* Mesh 0's deformation: its skin's joint count and first inverse bind matrix, influences per
 * vertex, morph targets, the weights its shape holds and the components of a weights channel. */
static bool deform_matches(const sl_scene *s, const cJSON *want) {
    const sl_mesh_deform *d = s->meshes[0].deform;
    const cJSON *v;
    if (!d) return false;
    int joints = d->skin >= 0 ? s->skins[d->skin].joint_count : 0;
    bool ok = joints == cJSON_GetObjectItem(want, "joints")->valueint &&
              d->influences == cJSON_GetObjectItem(want, "influences")->valueint &&
              d->target_count == cJSON_GetObjectItem(want, "targets")->valueint;
    if ((v = cJSON_GetObjectItem(want, "inverse_bind"))) ok = ok && joints && near_values(v, s->skins[d->skin].inverse_bind, 16, 0);
    if ((v = cJSON_GetObjectItem(want, "rest_weights"))) ok = ok && near_values(v, d->rest_weights, d->target_count, 0);
    if ((v = cJSON_GetObjectItem(want, "weights_channel")))
        ok = ok && s->anim_channel_count == 1 && s->anim_channels[0].path == SL_ANIM_WEIGHTS &&
             s->anim_channels[0].components == v->valueint;
    return ok;
}

/* "\t" + the stated expectations met, comma-separated ("!" before one that is not) */
static void check_expectation(const sl_scene *s, const char *file, char *out, size_t size) {
    cJSON *expect = stated_expectation(file), *e;
    size_t u = 0;
    if (!expect) return;
    cJSON_ArrayForEach(e, expect) {
        const char *k = e->string;
        bool ok = s->mesh_count > 0;
        if (!strcmp(k, "corners") || !strcmp(k, "normals")) ok = ok && corners_match(&s->meshes[0].data, expect, k, 3);
        else if (!strcmp(k, "uvs")) ok = ok && corners_match(&s->meshes[0].data, expect, k, 2);
        else if (!strcmp(k, "uv_map")) ok = ok && uv_map_matches(s, e);
        else if (!strcmp(k, "camera")) ok = camera_matches(s, e);
        else if (!strcmp(k, "light")) ok = light_matches(s, e);
        else if (!strcmp(k, "materials")) ok = materials_match(s, e);
        else if (!strcmp(k, "deform")) ok = ok && deform_matches(s, e);
        else if (!strcmp(k, "inputs")) ok = inputs_match(s, e);
        else ok = false;
        u += (size_t)snprintf(out + u, u < size ? size - u : 0, "%s%s%s", u ? "," : "\t", ok ? "" : "!", k);
    }
    cJSON_Delete(expect);
}

/* "ok\tmeshes\ttextures\tcameras\tlights[\texpectations]" or "error\t<message without the path>" */
static void outcome(const char *file, char *out, size_t size) {
    char err[4096] = "";
    sl_scene s = {0};
    static char logbuf[1 << 16];
    sl_log_capture(logbuf, sizeof logbuf); /* warnings are the files' own business here */
    bool ok = sl_scene_load_file(&s, file, NULL, err, sizeof err);
    sl_log_capture(NULL, 0);
    if (!ok) {
        const char *why = strstr(err, file) == err ? err + strlen(file) : err;
        while (*why == ':' || *why == ' ') why++;
        char clean[300];
        snprintf(clean, sizeof clean, "%.*s", (int)strcspn(why, "\t\n"), why);
        snprintf(out, size, "error\t%s", clean);
        return;
    }
    const char *tex[256];
    int ntex = 0;
    for (int m = 0; m < s.material_count; m++)
        for (int k = 0; k < s.materials[m].inputs.count; k++) {
            const sl_prop *p = &s.materials[m].inputs.items[k];
            if (p->kind != SL_PROP_STRING || !strstr(p->key, "texture")) continue;
            bool seen = false;
            for (int t = 0; t < ntex && !seen; t++) seen = !strcmp(tex[t], p->str);
            if (!seen && ntex < 256) tex[ntex++] = p->str;
        }
    int n = snprintf(out, size, "ok\t%d\t%d\t%d\t%d", s.mesh_count, ntex, s.camera_count, s.light_count);
    if (n > 0 && (size_t)n < size) check_expectation(&s, file, out + n, size - (size_t)n);
    sl_scene_free(&s);
}

int main(int argc, char **argv) {
    bool print = argc > 1 && !strcmp(argv[1], "--print");
    struct stat st;
    if (stat(MODELS, &st) != 0) {
        fprintf(stderr, "%s is missing: install assimp-testmodels (tools/install-deps.sh installs it)\n", MODELS);
        return 1;
    }
    find(MODELS, 0);
    for (int i = 0; i < nkeys; i++) /* sorted by key, files alongside */
        for (int j = i + 1; j < nkeys; j++)
            if (strcmp(keys[j], keys[i]) < 0) {
                char t[1200];
                memcpy(t, keys[i], sizeof keys[i]), memcpy(keys[i], keys[j], sizeof keys[i]), memcpy(keys[j], t, sizeof keys[i]);
                memcpy(t, files[i], sizeof files[i]), memcpy(files[i], files[j], sizeof files[i]), memcpy(files[j], t, sizeof files[i]);
            }
    write_features();
    if (print) {
        printf("# model (under %s, or feature/NAME: written by the test)\toutcome\tmeshes|cause\ttextures\tcameras\tlights"
               "\texpectations met\n", MODELS);
        for (int i = 0; i < nkeys; i++) {
            char o[600];
            outcome(files[i], o, sizeof o);
            printf("%s\t%s\n", keys[i], o);
        }
        return 0;
    }
    FILE *f = fopen(TABLE, "r");
    CHECK_MSG(f, "cannot read %s", TABLE);
    if (!f) return check_result();
    char line[2048];
    bool listed[320] = {false};
    int rows = 0;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        if (!line[0] || line[0] == '#') continue;
        char *tab = strchr(line, '\t');
        if (!tab) continue;
        *tab = 0;
        const char *key = line, *want = tab + 1;
        int i = 0;
        while (i < nkeys && strcmp(keys[i], key)) i++;
        CHECK_MSG(i < nkeys, "%s: in the table but neither installed nor written by the test", key);
        if (i == nkeys) continue;
        listed[i] = true;
        rows++;
        char got[600];
        outcome(files[i], got, sizeof got);
        if (!strncmp(want, "error\t", 6)) /* the stated cause must be in the message */
            CHECK_MSG(!strncmp(got, "error\t", 6) && strstr(got, want + 6), "%s: expected an error containing \"%s\", got %s",
                      key, want + 6, got);
        else
            CHECK_MSG(!strcmp(got, want), "%s: expected %s, got %s", key, want, got);
        CHECK_MSG(!strchr(want, '!'), "%s: the table records an expectation the file does not meet", key);
    }
    fclose(f);
    for (int i = 0; i < nkeys; i++) CHECK_MSG(listed[i], "%s: not in %s", keys[i], TABLE);
    printf("%d models and feature files checked against %s\n", rows, TABLE);
    return check_result();
}
