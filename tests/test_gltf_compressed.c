/* Compressed glTF content (issue 45, item 4) on files this test writes:
 *  - webp: EXT_texture_webp. A 32×32 WebP of four flat 16×16 blocks (written through
 *    OpenImageIO, lossy) as the texture's extension source, a grey PNG as its fallback source;
 *    the quad fills an orthographic camera's view, and at each block's centre the "diffuse-texture"
 *    debug view shows that block's sRGB-decoded colour (within the codec's loss), not the grey. */
#define SL_IMAGE_INTERNAL /* sl_oiio_write: OpenImageIO writes the WebP */
#include "check.h"
#include "gltf_writer.h"
#include "image/image.h"
#include "log.h"
#include "scene/scene.h"
#include "test_tmp.h"
#include <shadelab/harness.h>

#include <math.h>

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

int main(void) {
    test_webp();
    return check_result();
}
