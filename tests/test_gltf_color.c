/* glTF 2.0 vertex colours (COLOR_0, §3.7.2.1; "base colour = baseColorFactor × baseColorTexture ×
 * COLOR_0", alpha too), on files this test writes (tests/gltf_writer.h): two unlit quads side by
 * side under an orthographic camera framing them exactly, both of one material, the left one
 * carrying COLOR_0, the right one not.
 *
 *  - float_vec3: every pixel of the left quad is baseColorFactor × the colours interpolated at its
 *    centre (barycentric in the quad's triangle: linear under an orthographic view), the right
 *    quad baseColorFactor (a mesh without colours drawn by the same program reads white); the
 *    image with the colours ignored is checked to be far from it.
 *  - u8_vec4_blend: COLOR_0 as normalized unsigned bytes, VEC4, alphaMode BLEND over the constant
 *    environment: a·c + (1 − a)·bg with c and a the factor times the interpolated colour.
 *  - read: the scene's vertex colours are the file's (bytes / 255; VEC3 with alpha 1).
 * The harness's image is linear radiance (no display encoding): the expected values are compared
 * as they are. */
#include "check.h"
#include "gltf_writer.h"
#include "log.h"
#include "scene/scene.h"
#include "test_tmp.h"
#include <shadelab/harness.h>

#include <math.h>

#define W 128
#define H 64

static char err[8192];

static const float colors3[4][3] = {{1, 0.2f, 0}, {0, 1, 0.5f}, {0.1f, 0.3f, 1}, {1, 1, 0.25f}};
static const unsigned char colors4[4][4] = {{255, 51, 0, 255}, {0, 255, 128, 102}, {26, 77, 255, 204}, {255, 255, 64, 153}};
static const float factor[4] = {0.8f, 0.5f, 1.0f, 1.0f};
static const float bg = 0.3f;

/* The file: gw_quad's quad (corners (−1,−1) (1,−1) (1,1) (−1,1), triangles 0 1 2 and 0 2 3) drawn
 * twice, at x − 1 with COLOR_0 (accessor `color`) and at x + 1 without, both material 0 (unlit). */
static bool write_model(const char *path, bool vec4, bool blend) {
    gw_doc g;
    if (!gw_quad(&g)) return false;
    int color = vec4 ? gw_data(&g, colors4, sizeof colors4, 5121, 4, "VEC4") : gw_data(&g, colors3, sizeof colors3, 5126, 4, "VEC3");
    if (vec4) gw_set(&g, "/accessors/7/normalized", "true");
    char attrs[160], mat[400];
    snprintf(attrs, sizeof attrs, "{\"POSITION\": 0, \"NORMAL\": 1, \"TEXCOORD_0\": 2, \"COLOR_0\": %d}", color);
    snprintf(mat, sizeof mat,
             "{\"name\": \"paint\", \"pbrMetallicRoughness\": {\"baseColorFactor\": [%g, %g, %g, %g], \"metallicFactor\": 0}, "
             "\"extensions\": {\"KHR_materials_unlit\": {}}%s}",
             factor[0], factor[1], factor[2], factor[3], blend ? ", \"alphaMode\": \"BLEND\"" : "");
    bool ok = gw_set(&g, "/meshes/0/primitives/0/attributes", attrs) && gw_set(&g, "/materials/0", mat) &&
              gw_set(&g, "/extensionsUsed", "[\"KHR_materials_unlit\"]") && gw_set(&g, "/animations", NULL) &&
              gw_set(&g, "/cameras/0", "{\"type\": \"orthographic\", \"orthographic\": {\"xmag\": 2, \"ymag\": 1, "
                                       "\"znear\": 0.1, \"zfar\": 10}}") &&
              gw_set(&g, "/nodes/0/translation", "[-1, 0, 0]") &&
              gw_set(&g, "/nodes/2", "{\"name\": \"plain\", \"mesh\": 1, \"translation\": [1, 0, 0]}") &&
              gw_set(&g, "/scenes/0/nodes", "[0, 1, 2]") &&
              gw_set(&g, "/meshes/1", "{\"name\": \"plain\", \"primitives\": [{\"attributes\": {\"POSITION\": 0, "
                                      "\"NORMAL\": 1, \"TEXCOORD_0\": 2}, \"indices\": 3, \"material\": 0}]}") &&
              gw_write(&g, path, GW_GLB);
    gw_free(&g);
    return ok;
}

/* COLOR_0 (RGBA) interpolated at (x, y) of the quad: barycentric in triangle 0 1 2 (y < x) or 0 2 3. */
static void color_at(bool vec4, double x, double y, double out[4]) {
    double w[4] = {0};
    if (y <= x) w[0] = (1 - x) / 2, w[1] = (x - y) / 2, w[2] = (y + 1) / 2;
    else w[0] = (1 - y) / 2, w[2] = (x + 1) / 2, w[3] = (y - x) / 2;
    for (int c = 0; c < 4; c++) {
        out[c] = 0;
        for (int v = 0; v < 4; v++) out[c] += w[v] * (vec4 ? colors4[v][c] / 255.0 : c < 3 ? colors3[v][c] : 1.0);
    }
}

/* What pixel (i, j) shows (colours false: as if COLOR_0 were ignored); false near an edge. */
static bool expected(bool vec4, bool blend, bool colours, int i, int j, double out[3]) {
    double xw = ((i + 0.5) / W * 2 - 1) * 2, y = 1 - (j + 0.5) / H * 2;
    if (fabs(xw) < 2.0 * 4 / W || fabs(xw) > 2 - 2.0 * 2 / W || fabs(y) > 1 - 2.0 * 2 / H) return false;
    double col[4] = {1, 1, 1, 1};
    if (xw < 0 && colours) color_at(vec4, xw + 1, y, col);
    double a = blend ? factor[3] * col[3] : 1;
    for (int c = 0; c < 3; c++) out[c] = a * factor[c] * col[c] + (1 - a) * bg;
    return true;
}

static bool render(const char *model, float *img) {
    char json[4600];
    snprintf(json, sizeof json, "{\"nodes\": [{\"name\": \"m\", \"mesh\": {\"file\": \"%s\"}}], \"environment\": {\"color\": [%g, %g, %g]}}",
             model, bg, bg, bg);
    const char *settings[] = {"core.anisotropy=1", NULL};
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                         .scene_json = json, .settings = settings},
                                      err, sizeof err);
    CHECK_MSG(h, "%s", err);
    if (!h) return false;
    bool ok = sl_harness_render(h, img);
    CHECK(ok);
    sl_harness_destroy(h);
    return ok;
}

static void check_image(const char *name, bool vec4, bool blend) {
    char path[4200];
    snprintf(path, sizeof path, "%s/%s.glb", sl_test_dir(), name);
    CHECK(write_model(path, vec4, blend));
    float *img = malloc(sizeof(float) * 4 * W * H);
    if (render(path, img)) {
        double worst = 0, worst_plain = 0, ignored = 0, want[3];
        int n = 0;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++) {
                if (!expected(vec4, blend, true, i, j, want)) continue;
                double e = 0, e0 = 0, w0[3];
                expected(vec4, blend, false, i, j, w0);
                for (int c = 0; c < 3; c++)
                    e = fmax(e, fabs(img[(j * W + i) * 4 + c] - want[c])), e0 = fmax(e0, fabs(img[(j * W + i) * 4 + c] - w0[c]));
                if ((i + 0.5) / W < 0.5) worst = fmax(worst, e), ignored = fmax(ignored, e0), n++;
                else worst_plain = fmax(worst_plain, e);
            }
        CHECK_MSG(n > W * H / 3, "%s: %d pixels checked", name, n);
        CHECK_MSG(worst < 4e-3, "%s: the coloured quad's worst pixel is %.4f from factor x COLOR_0", name, worst);
        CHECK_MSG(worst_plain < 4e-3, "%s: the quad without COLOR_0 is %.4f from the factor (white colours)", name, worst_plain);
        CHECK_MSG(ignored > 0.2, "%s: ignoring COLOR_0 would be off by only %.3f", name, ignored);
        printf("%s: %d pixels within %.5f of factor x interpolated COLOR_0 (ignoring it: off by %.3f); the quad without "
               "colours within %.5f of the factor\n", name, n, worst, ignored, worst_plain);
    }
    free(img);
}

/* The reader's values: bytes / 255 (§3.11's normalized conversion), VEC3 with alpha 1. */
static void test_read(void) {
    for (int k = 0; k < 2; k++) {
        char path[4200];
        snprintf(path, sizeof path, "%s/read%d.glb", sl_test_dir(), k);
        CHECK(write_model(path, k == 1, false));
        sl_scene s = {0};
        CHECK_MSG(sl_scene_load_file(&s, path, NULL, err, sizeof err), "%s", err);
        int coloured = 0;
        for (int m = 0; m < s.mesh_count; m++) {
            const sl_mesh_data *d = &s.meshes[m].data;
            if (!d->colors) continue;
            coloured++;
            CHECK(d->vertex_count == 4);
            double worst = 0;
            for (int v = 0; v < 4 && d->vertex_count == 4; v++)
                for (int c = 0; c < 4; c++)
                    worst = fmax(worst, fabs(d->colors[4 * v + c] - (k ? colors4[v][c] / 255.0 : c < 3 ? colors3[v][c] : 1.0)));
            CHECK_MSG(worst < 1e-6, "read %s: COLOR_0 off by %g", k ? "u8 VEC4" : "float VEC3", worst);
        }
        CHECK_MSG(coloured == 1, "%d meshes with colours, want 1", coloured);
        sl_scene_free(&s);
    }
}

int main(void) {
    sl_log_threshold = SL_LOG_WARN;
    test_read();
    check_image("float_vec3", false, false);
    check_image("u8_vec4_blend", true, true);
    return check_result();
}
