/* glTF alphaMode BLEND and animated nodes' motion vectors (issue 15), on glTF files this test
 * writes itself (unit quads placed by node translation and scale, data: URI buffers), inside JSON
 * scenes that add an orthographic camera (4 m square on 64 px: 16 px per metre), lights and the
 * environment. Expected values come from a compositor in C, independent of the renderer:
 *
 *  - over_background: an unlit BLEND quad over the constant environment is alpha·c + (1−alpha)·bg.
 *  - order: two overlapping BLEND quads, an opaque quad behind them and one in front, with the
 *    nodes and materials in either order in the file: the CPU's back-to-front "over" of the quads
 *    covering each pixel (the front-to-back result differs by far more than the tolerance).
 *    The same with core.ssaa=2, with TAA (aa) after 8 frames of a still, and live: alpha_blend
 *    switched off and on again through sl_harness_set gives the fresh image.
 *  - envmap: over envmap's procedural sky (drawn after the forward pass), the quad is
 *    alpha·c + (1−alpha)·sky, with sky from a render of the scene without the quad.
 *  - shadow: a BLEND quad of coverage 0.25 under a shadow-casting directional light at 45°: the
 *    ground in its shadow (seen beside the quad) receives 1 − 0.25 of the light on average
 *    (dithered depth, spotlight-shadow's PCF); an opaque shadow (0) or a MASK at 0.5 (1) fails.
 *  - motion: a node translated by a LINEAR glTF animation (2 m/s along x): the core's "motion"
 *    (read back through the tp-motion test plugin) equals the closed-form UV displacement between
 *    frames 30 and 31, Δx / (2·2 m) = 1/120; the background's is 0. */
#include "check.h"
#include "test_tmp.h"
#include <shadelab/harness.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 64
#define H 64
#define HALF_VIEW 2.0 /* the camera's ymag: the view spans [-2, 2]² */

static char err[8192];

typedef struct quad { float pos[3], half[2]; int material; } quad;
typedef struct mat { const char *name; float rgba[4]; bool blend, unlit; } mat;

#include "byte_buffer.h"

static char *base64(const unsigned char *d, size_t n) {
    static const char t[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    char *o = malloc(4 * ((n + 2) / 3) + 1), *w = o;
    for (size_t i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)d[i] << 16 | (i + 1 < n ? (uint32_t)d[i + 1] << 8 : 0) | (i + 2 < n ? d[i + 2] : 0);
        *w++ = t[v >> 18 & 63];
        *w++ = t[v >> 12 & 63];
        *w++ = i + 1 < n ? t[v >> 6 & 63] : '=';
        *w++ = i + 2 < n ? t[v & 63] : '=';
    }
    *w = 0;
    return o;
}

/* A .gltf: one unit quad (±1, facing +Z) as mesh i with material i, one node per quad
 * (translation = its centre, scale = its half sizes); anim (6 floats: from, to) moves node 0 from
 * `from` at t = 0 to `to` at t = 1 s (LINEAR translation). */
static bool write_quads(const char *path, const quad *q, int nq, const mat *m, int nm, const float *anim) {
    static const float pos[12] = {-1, 1, 0, 1, 1, 0, 1, -1, 0, -1, -1, 0};
    static const float nrm[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    static const float uv[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    static const uint16_t idx[6] = {0, 3, 2, 0, 2, 1}; /* counter-clockwise seen from +Z */
    static const float times[2] = {0, 1};
    buf bin = {0};
    put(&bin, pos, sizeof pos), put(&bin, nrm, sizeof nrm), put(&bin, uv, sizeof uv), put(&bin, idx, sizeof idx);
    if (anim) put(&bin, times, sizeof times), put(&bin, anim, 6 * sizeof(float));
    char *b64 = base64(bin.d, bin.n);
    size_t cap = 65536 + strlen(b64);
    char *j = malloc(cap);
    size_t n = 0;
#define J(...) (n += (size_t)snprintf(j + n, cap - n, __VA_ARGS__))
    J("{\"asset\": {\"version\": \"2.0\", \"generator\": \"shadelab test_gltf_blend\"},\n"
      " \"extensionsUsed\": [\"KHR_materials_unlit\"],\n \"scene\": 0, \"scenes\": [{\"nodes\": [");
    for (int i = 0; i < nq; i++) J("%s%d", i ? ", " : "", i);
    J("]}],\n \"nodes\": [");
    for (int i = 0; i < nq; i++)
        J("%s{\"name\": \"q%d\", \"mesh\": %d, \"translation\": [%g, %g, %g], \"scale\": [%g, %g, 1]}", i ? ", " : "", i,
          q[i].material, q[i].pos[0], q[i].pos[1], q[i].pos[2], q[i].half[0], q[i].half[1]);
    J("],\n \"meshes\": [");
    for (int i = 0; i < nm; i++)
        J("%s{\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"NORMAL\": 1, \"TEXCOORD_0\": 2}, \"indices\": 3, "
          "\"material\": %d}]}",
          i ? ", " : "", i);
    J("],\n \"materials\": [");
    for (int i = 0; i < nm; i++)
        J("%s{\"name\": \"%s\", \"pbrMetallicRoughness\": {\"baseColorFactor\": [%g, %g, %g, %g], \"metallicFactor\": 0, "
          "\"roughnessFactor\": 1}%s%s}",
          i ? ", " : "", m[i].name, m[i].rgba[0], m[i].rgba[1], m[i].rgba[2], m[i].rgba[3],
          m[i].blend ? ", \"alphaMode\": \"BLEND\"" : "", m[i].unlit ? ", \"extensions\": {\"KHR_materials_unlit\": {}}" : "");
    J("],\n \"buffers\": [{\"byteLength\": %zu, \"uri\": \"data:application/octet-stream;base64,%s\"}],\n", bin.n, b64);
    J(" \"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 48}, {\"buffer\": 0, \"byteOffset\": 48, "
      "\"byteLength\": 48}, {\"buffer\": 0, \"byteOffset\": 96, \"byteLength\": 32}, {\"buffer\": 0, \"byteOffset\": 128, "
      "\"byteLength\": 12}%s],\n",
      anim ? ", {\"buffer\": 0, \"byteOffset\": 140, \"byteLength\": 8}, {\"buffer\": 0, \"byteOffset\": 148, "
             "\"byteLength\": 24}"
           : "");
    J(" \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\", \"min\": [-1, -1, 0], "
      "\"max\": [1, 1, 0]}, {\"bufferView\": 1, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\"}, {\"bufferView\": "
      "2, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC2\"}, {\"bufferView\": 3, \"componentType\": 5123, "
      "\"count\": 6, \"type\": \"SCALAR\"}%s]",
      anim ? ", {\"bufferView\": 4, \"componentType\": 5126, \"count\": 2, \"type\": \"SCALAR\", \"min\": [0], \"max\": [1]}, "
             "{\"bufferView\": 5, \"componentType\": 5126, \"count\": 2, \"type\": \"VEC3\"}"
           : "");
    if (anim)
        J(",\n \"animations\": [{\"channels\": [{\"sampler\": 0, \"target\": {\"node\": 0, \"path\": \"translation\"}}], "
          "\"samplers\": [{\"input\": 4, \"output\": 5, \"interpolation\": \"LINEAR\"}]}]");
    J("}\n");
#undef J
    FILE *f = fopen(path, "wb");
    bool ok = f && n < cap && fputs(j, f) >= 0;
    if (f) fclose(f);
    free(j), free(b64), free(bin.d);
    return ok;
}

/* A JSON scene around the model file (NULL: none): the orthographic camera, `lights`, the
 * constant environment bg (NULL: none) and `extra` nodes/members. */
static bool g_perspective; /* a perspective camera instead (its rays see the sky in many directions) */
static void scene_json(char *out, size_t n, const char *model, const float bg[3], const char *lights, const char *extra_nodes,
                       const char *extra) {
    char env[200] = ""; /* bg NULL: none (envmap then draws its procedural sky) */
    if (bg) snprintf(env, sizeof env, ",\n \"environment\": {\"color\": [%g, %g, %g]}", bg[0], bg[1], bg[2]);
    char cam[200];
    if (g_perspective) snprintf(cam, sizeof cam, "\"fov_y\": 40");
    else snprintf(cam, sizeof cam, "\"type\": \"orthographic\", \"ymag\": %g, \"xmag\": %g", HALF_VIEW, HALF_VIEW);
    snprintf(out, n,
             "{\"cameras\": [{\"name\": \"c\", %s, \"position\": [0, 0, 5], \"target\": [0, 0, 0], "
             "\"near\": 0.1, \"far\": 20}],\n"
             " \"nodes\": [%s%s%s%s%s],\n \"lights\": [%s]%s%s}",
             cam, model ? "{\"name\": \"m\", \"mesh\": {\"file\": \"" : "", model ? model : "",
             model ? "\"}}" : "", model && extra_nodes ? ", " : "", extra_nodes ? extra_nodes : "", lights ? lights : "",
             env, extra ? extra : "");
}

static sl_harness *harness(const char *json, const char *const *plugins, const char *const *settings) {
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                         .scene_json = json, .plugins = plugins, .settings = settings,
                                                         .strict = true},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "harness: %s", err);
    return h;
}

/* pixel centre → world x, y on the view plane */
static double px_x(int i) { return (i + 0.5) / W * 2 * HALF_VIEW - HALF_VIEW; }
static double px_y(int j) { return HALF_VIEW - (j + 0.5) / H * 2 * HALF_VIEW; }

/* The CPU compositor: the quads covering (x, y), back to front; opaque ones cover what is behind,
 * blended ones go "over" (glTF: alpha·c + (1 − alpha)·behind). bg: what is behind them all.
 * Returns false when the point lies within `margin` of a quad's edge (not checked). */
static bool composite(const quad *q, int nq, const mat *m, double x, double y, const double bg[3], double margin,
                      bool front_to_back, double out[3]) {
    int order[16], k = 0;
    for (int i = 0; i < nq; i++) {
        double dx = fabs(x - q[i].pos[0]) - q[i].half[0], dy = fabs(y - q[i].pos[1]) - q[i].half[1];
        if ((fabs(dx) < margin && dy < margin) || (fabs(dy) < margin && dx < margin)) return false; /* near an edge */
        if (dx < 0 && dy < 0) order[k++] = i;
    }
    for (int a = 1; a < k; a++) /* by z, farthest first (the camera looks down -z) */
        for (int b = a; b > 0 && q[order[b - 1]].pos[2] > q[order[b]].pos[2]; b--) {
            int t = order[b]; order[b] = order[b - 1]; order[b - 1] = t;
        }
    if (front_to_back) { /* the wrong order, to show the test can tell */
        int firstb = 0;
        for (int a = 0; a < k; a++)
            if (!m[q[order[a]].material].blend) firstb = a + 1;
        for (int a = firstb, b = k - 1; a < b; a++, b--) { int t = order[a]; order[a] = order[b]; order[b] = t; }
    }
    for (int c = 0; c < 3; c++) out[c] = bg[c];
    for (int a = 0; a < k; a++) {
        const mat *mm = &m[q[order[a]].material];
        double al = mm->blend ? mm->rgba[3] : 1;
        for (int c = 0; c < 3; c++) out[c] = al * mm->rgba[c] + (1 - al) * out[c];
    }
    return true;
}

/* Largest difference between the image and the compositor over the checked pixels (bg_img: the
 * background per pixel, or NULL for the constant bg). */
static double worst_error(const float *img, const quad *q, int nq, const mat *m, const float bg[3], const float *bg_img,
                          bool front_to_back, long *checked) {
    double worst = 0;
    *checked = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double b[3], want[3];
            for (int c = 0; c < 3; c++) b[c] = bg_img ? bg_img[(j * W + i) * 4 + c] : bg[c];
            if (!composite(q, nq, m, px_x(i), px_y(j), b, 1.01 * 2 * HALF_VIEW / W, front_to_back, want)) continue;
            ++*checked;
            for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(img[(j * W + i) * 4 + c] - want[c]));
        }
    return worst;
}

static const float bg[3] = {0.05f, 0.3f, 0.3f};

static void test_over_background(void) {
    const mat m[] = {{"glass", {0.8f, 0.2f, 0.1f, 0.4f}, true, true}};
    const quad q[] = {{{0, 0, 0}, {1, 1}, 0}};
    char path[4200], json[16384];
    snprintf(path, sizeof path, "%s/over.gltf", sl_test_dir());
    CHECK(write_quads(path, q, 1, m, 1, NULL));
    scene_json(json, sizeof json, path, bg, NULL, NULL, NULL);
    sl_harness *h = harness(json, NULL, NULL);
    if (!h) return;
    float *img = malloc(sizeof(float) * 4 * W * H);
    CHECK(sl_harness_render(h, img));
    long n;
    double e = worst_error(img, q, 1, m, bg, NULL, false, &n);
    /* the centre pixel in closed form, written out */
    int c = (H / 2) * W + W / 2;
    printf("over_background: centre (%.4f, %.4f, %.4f), closed form 0.4·c + 0.6·bg = (%.4f, %.4f, %.4f); worst of %ld "
           "pixels %.5f\n",
           img[c * 4], img[c * 4 + 1], img[c * 4 + 2], 0.4 * 0.8 + 0.6 * 0.05, 0.4 * 0.2 + 0.6 * 0.3, 0.4 * 0.1 + 0.6 * 0.3, n,
           e);
    CHECK_MSG(n > 900 && e < 2e-3, "a BLEND quad over the background: off by %.5f from alpha·c + (1-alpha)·bg", e);
    CHECK_NEAR(img[c * 4], 0.4 * 0.8 + 0.6 * 0.05, 2e-3);
    free(img);
    sl_harness_destroy(h);
}

/* The order scene: A (front, z 0.5) and B (z 0) overlap in the middle; C opaque behind both
 * covers the lower half; D opaque in front covers a corner of A. */
static const mat order_m[] = {{"a", {0.9f, 0.1f, 0.1f, 0.5f}, true, true},
                              {"b", {0.1f, 0.2f, 0.9f, 0.7f}, true, true},
                              {"c", {0.2f, 0.7f, 0.2f, 1}, false, true},
                              {"d", {0.9f, 0.9f, 0.1f, 1}, false, true}};
static const quad order_q[] = {{{-0.5f, 0.25f, 0.5f}, {1, 1}, 0},
                               {{0.5f, 0.25f, 0}, {1, 1}, 1},
                               {{0, -1.2f, -0.5f}, {1.8f, 0.6f}, 2},
                               {{-1.25f, 1.0f, 1}, {0.5f, 0.5f}, 3}};

/* the same scene with the nodes and the materials listed in reverse */
static void reversed(quad *q, mat *m) {
    int n = 4;
    for (int i = 0; i < n; i++) {
        q[i] = order_q[n - 1 - i];
        q[i].material = n - 1 - order_q[n - 1 - i].material;
        m[i] = order_m[n - 1 - i];
    }
}

static void check_order(const char *label, const char *model, const char *const *plugins, const char *const *settings,
                        int frames, const quad *q, const mat *m) {
    char json[16384];
    scene_json(json, sizeof json, model, bg, NULL, NULL, NULL);
    sl_harness *h = harness(json, plugins, settings);
    if (!h) return;
    float *img = malloc(sizeof(float) * 4 * W * H);
    for (int f = 0; f < frames; f++) CHECK(sl_harness_render(h, img));
    long n, n2;
    double e = worst_error(img, q, 4, m, bg, NULL, false, &n), wrong = worst_error(img, q, 4, m, bg, NULL, true, &n2);
    printf("order (%s): worst of %ld pixels %.5f from back-to-front; %.4f from front-to-back\n", label, n, e, wrong);
    CHECK_MSG(n > 2000 && e < 2e-3, "%s: off by %.5f from the back-to-front composite", label, e);
    CHECK_MSG(wrong > 0.1, "%s: front-to-back is within %.4f: the test cannot tell the order", label, wrong);
    if (!strcmp(label, "file order")) { /* live: alpha_blend off for both, then on again = fresh */
        char a[256];
        snprintf(a, sizeof a, "material.%s.alpha_blend=false", "order/a");
        bool set = sl_harness_set(h, a, err, sizeof err);
        CHECK_MSG(set, "%s", err);
        snprintf(a, sizeof a, "material.%s.alpha_blend=false", "order/b");
        CHECK(sl_harness_set(h, a, err, sizeof err));
        float *opaque = malloc(sizeof(float) * 4 * W * H);
        CHECK(sl_harness_render(h, opaque));
        /* opaque now: where A covers, A's colour exactly (and B where only B) */
        int ia = (int)((-1.2 + HALF_VIEW) / (2 * HALF_VIEW) * W), ja = (int)((HALF_VIEW - 0.25) / (2 * HALF_VIEW) * H);
        CHECK_NEAR(opaque[(ja * W + ia) * 4], 0.9, 2e-3);
        snprintf(a, sizeof a, "material.%s.alpha_blend=true", "order/a");
        CHECK(sl_harness_set(h, a, err, sizeof err));
        snprintf(a, sizeof a, "material.%s.alpha_blend=true", "order/b");
        CHECK(sl_harness_set(h, a, err, sizeof err));
        CHECK(sl_harness_render(h, opaque));
        sl_compare cmp;
        sl_harness_compare(opaque, img, W, H, 1e-6, &cmp);
        CHECK_MSG(cmp.max_abs == 0, "alpha_blend off and on again live differs from the fresh image by %g", cmp.max_abs);
        free(opaque);
    }
    free(img);
    sl_harness_destroy(h);
}

static void test_order(void) {
    char path[4200], rpath[4200];
    snprintf(path, sizeof path, "%s/order.gltf", sl_test_dir());
    CHECK(write_quads(path, order_q, 4, order_m, 4, NULL));
    quad rq[4];
    mat rm[4];
    reversed(rq, rm);
    snprintf(rpath, sizeof rpath, "%s/order_reversed.gltf", sl_test_dir());
    CHECK(write_quads(rpath, rq, 4, rm, 4, NULL));
    check_order("file order", path, NULL, NULL, 1, order_q, order_m);
    check_order("reversed file order", rpath, NULL, NULL, 1, rq, rm);
    const char *ssaa[] = {"core.ssaa=2", NULL};
    check_order("core.ssaa=2", path, NULL, ssaa, 1, order_q, order_m);
    const char *aa[] = {"aa", NULL}, *taa[] = {"aa.method=taa", NULL};
    check_order("aa taa, 8 frames", path, aa, taa, 8, order_q, order_m);
}

/* Over envmap's sky (its background pass runs after the forward pass): alpha·c + (1−alpha)·sky,
 * through a perspective camera (an orthographic one sees one sky direction) and a quad larger than
 * the view (so every pixel is covered whatever the projection). */
static void test_envmap(void) {
    const mat m[] = {{"glass", {0.8f, 0.2f, 0.1f, 0.4f}, true, true}};
    const quad q[] = {{{0, 0, 0}, {3, 3}, 0}};
    char path[4200], json[16384];
    snprintf(path, sizeof path, "%s/sky.gltf", sl_test_dir());
    CHECK(write_quads(path, q, 1, m, 1, NULL));
    const char *plugins[] = {"ggx", "envmap", NULL};
    g_perspective = true;
    float *img = malloc(sizeof(float) * 4 * W * H), *sky = malloc(sizeof(float) * 4 * W * H);
    scene_json(json, sizeof json, NULL, NULL, NULL, NULL, NULL);
    sl_harness *h = harness(json, plugins, NULL);
    bool ok = h && sl_harness_render(h, sky);
    if (h) sl_harness_destroy(h);
    scene_json(json, sizeof json, path, NULL, NULL, NULL, NULL);
    h = harness(json, plugins, NULL);
    ok = ok && h && sl_harness_render(h, img);
    if (h) sl_harness_destroy(h);
    g_perspective = false;
    CHECK(ok);
    if (ok) {
        long n;
        double e = worst_error(img, q, 1, m, bg, sky, false, &n);
        double spread = 0; /* the sky is not constant: the check sees the per-pixel background */
        for (int i = 0; i < W * H; i++) spread = fmax(spread, fabs(sky[i * 4] - sky[0]));
        CHECK_MSG(spread > 0.01, "the sky is uniform (%g): envmap's background pass did not run", spread);
        printf("envmap: worst of %ld pixels %.5f from alpha·c + (1-alpha)·sky (sky red varies by %.3f)\n", n, e, spread);
        CHECK_MSG(n > 1000 && e < 3e-3, "over envmap's sky: off by %.5f", e);
    }
    free(img), free(sky);
}

/* Shadow of a BLEND quad (coverage 0.25): a 45° directional light (travelling +x, −z) casts the
 * quad at x ∈ [−1.25, −0.25], z = 0 onto the ground at z = −1, x ∈ [−0.25, 0.75]; the camera sees
 * that ground beside the quad. Lit ground: k_d/π · E cos 45°. */
static void test_shadow(void) {
    const double alpha = 0.25;
    const mat m[] = {{"veil", {0.9f, 0.9f, 0.9f, (float)alpha}, true, true}};
    const quad q[] = {{{-0.75f, 0, 0}, {0.5f, 0.5f}, 0}};
    char path[4200], json[16384];
    snprintf(path, sizeof path, "%s/shadow.gltf", sl_test_dir());
    CHECK(write_quads(path, q, 1, m, 1, NULL));
    const float black[3] = {0, 0, 0};
    scene_json(json, sizeof json, path, black,
               "{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [1, 0, -1], \"intensity\": 2, "
               "\"cast_shadows\": true}",
               "{\"name\": \"ground\", \"translate\": [0, 0, -1], \"rotate\": [90, 0, 0], \"mesh\": {\"primitive\": "
               "\"plane\", \"size\": 6}, \"material\": \"ground\"}",
               ", \"materials\": [{\"name\": \"ground\", \"base_color\": [0.5, 0.5, 0.5]}]");
    const char *plugins[] = {"spotlight-shadow", NULL};
    const char *variants[][3] = {{"spotlight-shadow.filter=pcf", NULL}, {"spotlight-shadow.filter=pcf", "spotlight-shadow.pcf_size=9", NULL}};
    for (int v = 0; v < 2; v++) {
        sl_harness *h = harness(json, plugins, variants[v]);
        if (!h) return;
        float *img = malloc(sizeof(float) * 4 * W * H);
        CHECK(sl_harness_render(h, img));
        const double lit = 0.5 / M_PI * 2 * sqrt(0.5);
        double sum = 0, lit_sum = 0, lo = 1e9, hi = -1e9;
        long n = 0, nl = 0;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++) {
                double x = px_x(i), y = px_y(j), g = img[(j * W + i) * 4 + 1];
                if (x > -0.1 && x < 0.6 && fabs(y) < 0.35) sum += g, n++, lo = fmin(lo, g), hi = fmax(hi, g);
                if (x > 1.0 && fabs(y) < 0.35) lit_sum += g, nl++;
            }
        double mean = sum / n / lit, lit_mean = lit_sum / nl / lit;
        printf("shadow (%s%s%s): ground behind the BLEND quad (coverage %.2f) receives %.4f of the light on average over "
               "%ld px (pixels %.3f..%.3f); unshadowed ground %.4f\n",
               variants[v][0], variants[v][1] ? ", " : "", variants[v][1] ? variants[v][1] : "", alpha, mean, n, lo / lit,
               hi / lit, lit_mean);
        CHECK_MSG(fabs(lit_mean - 1) < 0.01, "unshadowed ground at %.4f of k_d/pi E cos", lit_mean);
        CHECK_MSG(fabs(mean - (1 - alpha)) < 0.03, "BLEND shadow lets %.4f of the light through, not 1 - %.2f", mean, alpha);
        CHECK(sl_harness_count_nonfinite(img, W, H) == 0);
        free(img);
        sl_harness_destroy(h);
    }
}

/* Motion vectors of an animated node: node 0 moves from x = −1 (t = 0) to x = 1 (t = 1 s), LINEAR;
 * between frames 30 and 31 (1/60 s apart) it moves 2/60 m: UV x grows by (2/60) / (2·HALF_VIEW). */
static void test_motion(void) {
    const mat m[] = {{"mover", {0.6f, 0.6f, 0.6f, 1}, false, true}};
    const quad q[] = {{{-1, 0, 0}, {0.5f, 0.5f}, 0}};
    const float anim[6] = {-1, 0, 0, 1, 0, 0};
    char path[4200], json[16384];
    snprintf(path, sizeof path, "%s/motion.gltf", sl_test_dir());
    CHECK(write_quads(path, q, 1, m, 1, anim));
    scene_json(json, sizeof json, path, bg, NULL, NULL, NULL);
    const char *plugins[] = {TP_MOTION_PATH, NULL};
    sl_harness *h = harness(json, plugins, NULL);
    if (!h) return;
    float *img = malloc(sizeof(float) * 4 * W * H);
    sl_harness_set_frame(h, 30);
    CHECK(sl_harness_render(h, img));
    CHECK(sl_harness_render(h, img)); /* frame 31 */
    const double t = 31 / 60.0, x = -1 + 2 * t, want = (2 / 60.0) / (2 * HALF_VIEW);
    double worst = 0, worst_bg = 0;
    long n = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double dx = fabs(px_x(i) - x) - 0.5, dy = fabs(px_y(j)) - 0.5, margin = 2.0 * 2 * HALF_VIEW / W;
            const float *p = img + (j * W + i) * 4;
            if (dx < -margin && dy < -margin) {
                worst = fmax(worst, fmax(fabs(p[0] - want), fabs(p[1])));
                n++;
            } else if (dx > margin || dy > margin) {
                worst_bg = fmax(worst_bg, fmax(fabs(p[0]), fabs(p[1])));
            }
        }
    printf("motion: animated node's motion vector off by %.2e from the closed form %.6f (UV/frame) over %ld px; "
           "background %.2e\n",
           worst, want, n, worst_bg);
    CHECK_MSG(n > 100 && worst < 2e-5, "animated node: motion off by %g from %g", worst, want);
    CHECK_MSG(worst_bg < 1e-6, "background motion %g", worst_bg);
    free(img);
    sl_harness_destroy(h);
}

int main(void) {
    test_over_background();
    test_order();
    test_envmap();
    test_shadow();
    test_motion();
    return check_result();
}
