/* Compressed glTF content (issue 45, item 4) on files this test writes:
 *  - webp: EXT_texture_webp. A 32×32 WebP of four flat 16×16 blocks (written through
 *    OpenImageIO, lossy) as the texture's extension source, a grey PNG as its fallback source;
 *    the quad fills an orthographic camera's view, and at each block's centre the "diffuse-texture"
 *    debug view shows that block's sRGB-decoded colour (within the codec's loss), not the grey.
 *  - meshopt: EXT_meshopt_compression. The quad's positions and UVs (ATTRIBUTES), its normals as
 *    8-bit octahedral vectors (ATTRIBUTES + OCTAHEDRAL, with KHR_mesh_quantization) and its
 *    indices (TRIANGLES, decoded to 16 bits), encoded by meshoptimizer into buffer 0 while the
 *    bufferViews name a fallback buffer that holds nothing: the mesh read equals the
 *    uncompressed file's corner for corner (normals within the 8-bit encoding's step).
 *  - draco: KHR_draco_mesh_compression. The quad encoded by libdraco (tests/draco_encode.cpp, no
 *    quantization) in a bufferView, its accessors without bufferViews: every triangle of the
 *    file comes back with its corners' positions, normals and UVs exactly (Draco may reorder
 *    points and faces and start a triangle at another corner; the winding must stay). */
#define SL_IMAGE_INTERNAL /* sl_oiio_write: OpenImageIO writes the WebP */
#include "check.h"
#include "gltf_writer.h"
#include "image/image.h"
#include "log.h"
#include "scene/scene.h"
#include "test_tmp.h"
#include <shadelab/harness.h>

#include <math.h>
#include <meshoptimizer.h>

#define W 64
static char err[8192];
static const unsigned char blocks[2][2][3] = {{{200, 30, 30}, {30, 200, 30}}, {{30, 30, 200}, {220, 220, 40}}};

static bool read_file(const char *path, buf *out) {
    FILE *f = fopen(path, "rb");
    if (!f) return false;
    unsigned char tmp[4096];
    size_t n;
    while ((n = fread(tmp, 1, sizeof tmp, f)) > 0) put(out, tmp, n);
    fclose(f);
    return true;
}

static double srgb_decode(double e) { return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4); }

/* The quad, its camera orthographic and framing it exactly, its material the texture alone. */
static void textured_quad(gw_doc *g) {
    CHECK(gw_quad(g));
    gw_set(g, "/cameras/0", "{\"type\": \"orthographic\", \"orthographic\": {\"xmag\": 1, \"ymag\": 1, \"znear\": 0.1, \"zfar\": 10}}");
    gw_set(g, "/materials/0", "{\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0}, \"metallicFactor\": 0}}");
    gw_set(g, "/animations", NULL);
}

static float *render(const char *path) {
    const char *settings[] = {"tonemap.enabled=false", "core.anisotropy=1", NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = W,
                                                         .scene_file = path, .settings = settings,
                                                         .debug_view = "diffuse-texture"},
                                      err, sizeof err);
    CHECK_MSG(h, "%s: %s", path, err);
    if (!h) return NULL;
    float *img = malloc(sizeof(float) * 4 * W * W);
    CHECK(sl_harness_render(h, img));
    sl_harness_destroy(h);
    return img;
}

static void test_webp(void) {
    unsigned char px[32 * 32 * 3], grey[2 * 2 * 3];
    for (int y = 0; y < 32; y++)
        for (int x = 0; x < 32; x++) memcpy(px + 3 * (y * 32 + x), blocks[y / 16][x / 16], 3);
    memset(grey, 128, sizeof grey);
    char webp[4200], png[4200], path[4200];
    snprintf(webp, sizeof webp, "%s/blocks.webp", sl_test_dir());
    snprintf(png, sizeof png, "%s/grey.png", sl_test_dir());
    CHECK_MSG(sl_oiio_write(webp, "webp", px, NULL, 32, 32, 3, "uint8", 100, err, sizeof err), "%s", err);
    CHECK_MSG(sl_oiio_write(png, "png", grey, NULL, 2, 2, 3, "uint8", 100, err, sizeof err), "%s", err);
    buf wb = {0}, pb = {0};
    CHECK(read_file(webp, &wb) && read_file(png, &pb));
    gw_doc g;
    textured_quad(&g);
    char s[300];
    snprintf(s, sizeof s, "[{\"bufferView\": %d, \"mimeType\": \"image/png\"}, {\"bufferView\": %d, \"mimeType\": \"image/webp\"}]",
             gw_view(&g, gw_append(&g, pb.d, pb.n), pb.n, 0), gw_view(&g, gw_append(&g, wb.d, wb.n), wb.n, 0));
    gw_set(&g, "/images", s);
    gw_set(&g, "/textures", "[{\"source\": 0, \"extensions\": {\"EXT_texture_webp\": {\"source\": 1}}}]");
    gw_set(&g, "/extensionsUsed", "[\"EXT_texture_webp\"]");
    snprintf(path, sizeof path, "%s/webp.glb", sl_test_dir());
    CHECK(gw_write(&g, path, GW_GLB));
    gw_free(&g);
    free(wb.d), free(pb.d);
    float *img = render(path);
    double worst = 0;
    for (int k = 0; img && k < 4; k++) {
        int by = k / 2, bx = k % 2, i = bx * W / 2 + W / 4, j = by * W / 2 + W / 4;
        for (int c = 0; c < 3; c++) {
            double e = fabs(img[4 * (j * W + i) + c] - srgb_decode(blocks[by][bx][c] / 255.0));
            if (e > worst) worst = e;
        }
    }
    printf("webp: block centres within %.4f of the blocks' colours\n", worst);
    CHECK_MSG(img && worst < 0.02, "EXT_texture_webp: the WebP's blocks are not where the texture puts them (off by %.4f)", worst);
    free(img);
}

/* A meshopt bufferView: the encoded bytes appended to buffer 0, the view on fallback buffer 1. */
static int meshopt_view(gw_doc *g, const unsigned char *enc, size_t enc_len, size_t count, size_t stride, const char *mode,
                        const char *filter, size_t *fallback_at) {
    size_t at = gw_append(g, enc, enc_len);
    char s[400];
    snprintf(s, sizeof s, "{\"buffer\": 1, \"byteOffset\": %zu, \"byteLength\": %zu, \"extensions\": {\"EXT_meshopt_compression\": "
             "{\"buffer\": 0, \"byteOffset\": %zu, \"byteLength\": %zu, \"byteStride\": %zu, \"count\": %zu, \"mode\": \"%s\", "
             "\"filter\": \"%s\"}}}", *fallback_at, count * stride, at, enc_len, stride, count, mode, filter);
    *fallback_at += (count * stride + 3) / 4 * 4;
    cJSON *views = cJSON_GetObjectItem(g->json, "bufferViews");
    cJSON_AddItemToArray(views, cJSON_Parse(s));
    return cJSON_GetArraySize(views) - 1;
}

static void test_meshopt(void) {
    const float pos[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, uv[8] = {0, 1, 1, 1, 1, 0, 0, 0};
    const float nrm4[16] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    const unsigned idx[6] = {0, 1, 2, 0, 2, 3};
    signed char oct[16];
    meshopt_encodeFilterOct(oct, 4, 4, 8, nrm4);
    unsigned char enc[4][512];
    size_t n_pos = meshopt_encodeVertexBuffer(enc[0], sizeof enc[0], pos, 4, 12);
    size_t n_uv = meshopt_encodeVertexBuffer(enc[1], sizeof enc[1], uv, 4, 8);
    size_t n_nrm = meshopt_encodeVertexBuffer(enc[2], sizeof enc[2], oct, 4, 4);
    size_t n_idx = meshopt_encodeIndexBuffer(enc[3], sizeof enc[3], idx, 6);
    CHECK(n_pos && n_uv && n_nrm && n_idx);
    gw_doc g;
    CHECK(gw_quad(&g));
    size_t fallback = 0;
    int vp = meshopt_view(&g, enc[0], n_pos, 4, 12, "ATTRIBUTES", "NONE", &fallback);
    int vu = meshopt_view(&g, enc[1], n_uv, 4, 8, "ATTRIBUTES", "NONE", &fallback);
    int vn = meshopt_view(&g, enc[2], n_nrm, 4, 4, "ATTRIBUTES", "OCTAHEDRAL", &fallback);
    int vi = meshopt_view(&g, enc[3], n_idx, 6, 2, "TRIANGLES", "NONE", &fallback);
    char s[300];
    snprintf(s, sizeof s, "{\"byteLength\": %zu, \"extensions\": {\"EXT_meshopt_compression\": {\"fallback\": true}}}", fallback);
    gw_set(&g, "/buffers/1", s);
    snprintf(s, sizeof s, "{\"bufferView\": %d, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\"}", vp);
    gw_set(&g, "/accessors/0", s);
    snprintf(s, sizeof s, "{\"bufferView\": %d, \"componentType\": 5120, \"normalized\": true, \"count\": 4, \"type\": \"VEC3\"}", vn);
    gw_set(&g, "/accessors/1", s);
    snprintf(s, sizeof s, "{\"bufferView\": %d, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC2\"}", vu);
    gw_set(&g, "/accessors/2", s);
    snprintf(s, sizeof s, "{\"bufferView\": %d, \"componentType\": 5123, \"count\": 6, \"type\": \"SCALAR\"}", vi);
    gw_set(&g, "/accessors/3", s);
    gw_set(&g, "/extensionsUsed", "[\"EXT_meshopt_compression\", \"KHR_mesh_quantization\"]");
    gw_set(&g, "/extensionsRequired", "[\"EXT_meshopt_compression\", \"KHR_mesh_quantization\"]");
    char path[4200];
    snprintf(path, sizeof path, "%s/meshopt.glb", sl_test_dir());
    CHECK(gw_write(&g, path, GW_GLB));
    gw_free(&g);
    sl_scene s1 = {0};
    bool ok = sl_scene_load_file(&s1, path, NULL, err, sizeof err);
    CHECK_MSG(ok, "meshopt: %s", err);
    if (ok && s1.mesh_count == 1) {
        const sl_mesh_data *m = &s1.meshes[0].data;
        CHECK(m->index_count == 6 && m->vertex_count == 4);
        double worst_n = 0;
        for (int i = 0; i < m->index_count && m->index_count == 6; i++) {
            int v = (int)m->indices[i], want = (int)idx[i];
            for (int c = 0; c < 3; c++) CHECK(m->positions[3 * v + c] == pos[3 * want + c]);
            for (int c = 0; c < 2; c++) CHECK(m->uvs[2 * v + c] == uv[2 * want + c]);
            for (int c = 0; c < 3; c++) worst_n = fmax(worst_n, fabs(m->normals[3 * v + c] - nrm4[4 * want + c]));
        }
        printf("meshopt: positions, UVs and indices exact, normals within %.4f\n", worst_n);
        CHECK(worst_n <= 1.0 / 127);
    }
    sl_scene_free(&s1);
}

unsigned char *sl_test_draco_encode(const float *pos, const float *nrm, const float *uv, const unsigned *idx, int faces,
                                    int ids[3], size_t *size);

/* Whether triangle t of m has corners a, b, c's values (attributes as in the quad arrays). */
static bool same_triangle(const sl_mesh_data *m, int t, const int want[3], const float *pos, const float *nrm, const float *uv) {
    for (int r = 0; r < 3; r++) {
        bool ok = true;
        for (int k = 0; k < 3 && ok; k++) {
            uint32_t v = m->indices[3 * t + (k + r) % 3];
            for (int c = 0; c < 3; c++) ok = ok && m->positions[3 * v + c] == pos[3 * want[k] + c] && m->normals[3 * v + c] == nrm[3 * want[k] + c];
            for (int c = 0; c < 2; c++) ok = ok && m->uvs[2 * v + c] == uv[2 * want[k] + c];
        }
        if (ok) return true;
    }
    return false;
}

static void test_draco(void) {
    const float pos[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, nrm[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const float uv[8] = {0, 1, 1, 1, 1, 0, 0, 0};
    const unsigned idx[6] = {0, 1, 2, 0, 2, 3};
    int ids[3];
    size_t n = 0;
    unsigned char *enc = sl_test_draco_encode(pos, nrm, uv, idx, 2, ids, &n);
    CHECK(enc && n);
    if (!enc) return;
    gw_doc g;
    CHECK(gw_quad(&g));
    char s[400];
    snprintf(s, sizeof s, "{\"KHR_draco_mesh_compression\": {\"bufferView\": %d, \"attributes\": {\"POSITION\": %d, "
             "\"NORMAL\": %d, \"TEXCOORD_0\": %d}}}", gw_view(&g, gw_append(&g, enc, n), n, 0), ids[0], ids[1], ids[2]);
    free(enc);
    gw_set(&g, "/meshes/0/primitives/0/extensions", s);
    for (int a = 0; a < 4; a++) { /* the accessors describe the decoded data and have no bufferView */
        char ptr[48];
        snprintf(ptr, sizeof ptr, "/accessors/%d/bufferView", a);
        gw_set(&g, ptr, NULL);
    }
    gw_set(&g, "/extensionsUsed", "[\"KHR_draco_mesh_compression\"]");
    gw_set(&g, "/extensionsRequired", "[\"KHR_draco_mesh_compression\"]");
    char path[4200];
    snprintf(path, sizeof path, "%s/draco.glb", sl_test_dir());
    CHECK(gw_write(&g, path, GW_GLB));
    gw_free(&g);
    sl_scene sc = {0};
    bool ok = sl_scene_load_file(&sc, path, NULL, err, sizeof err);
    CHECK_MSG(ok, "draco: %s", err);
    if (ok && sc.mesh_count == 1) {
        const sl_mesh_data *m = &sc.meshes[0].data;
        CHECK(m->index_count == 6);
        int found = 0;
        for (int t = 0; t < 2 && m->index_count == 6; t++) {
            const int want[3] = {(int)idx[3 * t], (int)idx[3 * t + 1], (int)idx[3 * t + 2]};
            found += same_triangle(m, 0, want, pos, nrm, uv) || same_triangle(m, 1, want, pos, nrm, uv);
        }
        CHECK_MSG(found == 2, "draco: %d of the quad's 2 triangles came back with their corners", found);
        printf("draco: %d of 2 triangles with every corner's position, normal and UV exact\n", found);
    }
    sl_scene_free(&sc);
}

int main(void) {
    test_webp();
    test_meshopt();
    test_draco();
    return check_result();
}
