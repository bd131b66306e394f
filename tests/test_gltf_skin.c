/* Skins and morph targets (glTF 2.0 §3.7.3, §3.7.2.2) on files this test writes itself, drawn by
 * the GPU and compared with the specification's formulas evaluated here on the CPU:
 *
 *  - skin: a strip along x (0..2) bound to two joints, "root" at the origin and "bone" at x = 1
 *    (child of root), the weights blending from root to bone over x in [0.5, 1.5]; the animation
 *    lifts root by 0.5 m/s and turns bone about z by 90°/s. The skinned node itself sits at
 *    (5, 5, 5), which §3.7.3 says to ignore. At t = 0.5 s each vertex is Σ w·J·v with
 *    J = world(joint) · inverseBindMatrix; the CPU rasterises that strip (orthographic, 96 px)
 *    and interpolates its UVs, and the core's "uv" debug view must show the same UVs at every
 *    pixel more than 1.5 px inside the strip, and nothing at every pixel more than 1.5 px outside.
 *    The same strip with a morph target too (its top row raised, weight animated 0 → 1 over 1 s):
 *    the target applies before the skin, Σ w·J·(v + 0.5·Δ).
 *  - morph: a quad with two targets (top edge up, right edge right), mesh weights [0.5, 0] (the
 *    shape at rest) and a LINEAR `weights` animation from [0, 0] to [1, 1] over 1 s: at t = 0.75 s
 *    the quad is base + 0.75·T0 + 0.75·T1, checked the same way.
 *  - motion: the skinned strip's "motion" (through the tp-motion test plugin) between frames 30 and
 *    31 equals, at the pixels of the parts bound to one joint, the closed-form displacement
 *    J(t₁)·J(t₀)⁻¹ of the point seen there, in UV per frame.
 *  - shadow: the strip at t = 0.5 s casts its posed shadow on a wall (spotlight-shadow's map).
 *  - hostile: joint indices, weights, sets, inverse bind matrices, joints and morph weights that
 *    break the specification: each refused naming the file, the JSON pointer and the cause. */
#include "check.h"
#include "gltf_writer.h"
#include "log.h"
#include "scene/scene.h"
#include "test_tmp.h"
#include <shadelab/harness.h>

#include <math.h>

#define W 96
#define H 96
static double HALF = 1.25, CX = 1.0, CY = 0.5; /* the orthographic view: half size, centre */

static char err[8192], logbuf[1 << 16];

/* ---- the files ---------------------------------------------------------------------------- */

enum { COLS = 9, NV = 2 * COLS, NT = 2 * (COLS - 1) };

static void strip_vertex(int v, float p[3], float uv[2]) {
    int c = v % COLS, row = v / COLS;
    p[0] = 0.25f * (float)c, p[1] = row ? 0.25f : -0.25f, p[2] = 0;
    uv[0] = 0.05f + 0.4f * p[0], uv[1] = p[1] + 0.5f;
}

static float bone_weight(float x) { return x < 0.5f ? 0 : x > 1.5f ? 1 : x - 0.5f; }

/* The skinned strip (see the top). Accessors: 0 POSITION, 1 NORMAL, 2 TEXCOORD_0, 3 indices,
 * 4 JOINTS_0 (u8), 5 WEIGHTS_0, 6 inverse bind matrices, 7 key times, 8 root translations,
 * 9 bone rotations. Buffer offsets of the joints and weights: *joints_at, *weights_at. */
static void skinned_strip(gw_doc *g, size_t *joints_at, size_t *weights_at, size_t *ibm_at) {
    memset(g, 0, sizeof *g);
    g->json = cJSON_Parse(
        "{\"asset\": {\"version\": \"2.0\", \"generator\": \"shadelab tests/test_gltf_skin.c\"}, \"scene\": 0,"
        " \"scenes\": [{\"nodes\": [0, 1]}],"
        " \"nodes\": [{\"name\": \"strip\", \"mesh\": 0, \"skin\": 0, \"translation\": [5, 5, 5]},"
        " {\"name\": \"root\", \"children\": [2]}, {\"name\": \"bone\", \"translation\": [1, 0, 0]},"
        " {\"name\": \"outside\"}],"
        " \"skins\": [{\"joints\": [1, 2], \"inverseBindMatrices\": 6}],"
        " \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"NORMAL\": 1, \"TEXCOORD_0\": 2, "
        "\"JOINTS_0\": 4, \"WEIGHTS_0\": 5}, \"indices\": 3, \"material\": 0}]}],"
        " \"materials\": [{\"name\": \"skin\", \"doubleSided\": true}],"
        " \"animations\": [{\"channels\": [{\"sampler\": 0, \"target\": {\"node\": 1, \"path\": \"translation\"}},"
        " {\"sampler\": 1, \"target\": {\"node\": 2, \"path\": \"rotation\"}}],"
        " \"samplers\": [{\"input\": 7, \"output\": 8}, {\"input\": 7, \"output\": 9}]}],"
        " \"buffers\": [{\"byteLength\": 0}], \"bufferViews\": [], \"accessors\": []}");
    float pos[NV][3], nrm[NV][3], uv[NV][2], w[NV][4];
    uint8_t j[NV][4];
    uint16_t idx[3 * NT];
    for (int v = 0; v < NV; v++) {
        strip_vertex(v, pos[v], uv[v]);
        nrm[v][0] = nrm[v][1] = 0, nrm[v][2] = 1;
        float b = bone_weight(pos[v][0]);
        j[v][0] = 0, j[v][1] = 1, j[v][2] = j[v][3] = 0;
        w[v][0] = 1 - b, w[v][1] = b, w[v][2] = w[v][3] = 0;
    }
    for (int c = 0, k = 0; c < COLS - 1; c++) {
        uint16_t a = (uint16_t)c, b = (uint16_t)(c + 1), d = (uint16_t)(c + COLS), e = (uint16_t)(c + 1 + COLS);
        idx[k++] = a, idx[k++] = b, idx[k++] = e, idx[k++] = a, idx[k++] = e, idx[k++] = d;
    }
    const float ibm[32] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 1};
    const float times[2] = {0, 1}, lift[6] = {0, 0, 0, 0, 0.5f, 0};
    const float turn[8] = {0, 0, 0, 1, 0, 0, (float)sin(M_PI / 4), (float)cos(M_PI / 4)};
    gw_data(g, pos, sizeof pos, 5126, NV, "VEC3");
    gw_data(g, nrm, sizeof nrm, 5126, NV, "VEC3");
    gw_data(g, uv, sizeof uv, 5126, NV, "VEC2");
    gw_data(g, idx, sizeof idx, 5123, 3 * NT, "SCALAR");
    *joints_at = gw_append(g, j, sizeof j);
    gw_accessor(g, gw_view(g, *joints_at, sizeof j, 0), 5121, NV, "VEC4", NULL);
    *weights_at = gw_append(g, w, sizeof w);
    gw_accessor(g, gw_view(g, *weights_at, sizeof w, 0), 5126, NV, "VEC4", NULL);
    *ibm_at = gw_append(g, ibm, sizeof ibm);
    gw_accessor(g, gw_view(g, *ibm_at, sizeof ibm, 0), 5126, 2, "MAT4", NULL);
    size_t at = gw_append(g, times, sizeof times);
    gw_accessor(g, gw_view(g, at, sizeof times, 0), 5126, 2, "SCALAR", "{\"min\": [0], \"max\": [1]}");
    gw_data(g, lift, sizeof lift, 5126, 2, "VEC3");
    gw_data(g, turn, sizeof turn, 5126, 2, "VEC4");
}

/* The strip with a morph target as well (skinned and morphing): the top row 0.2 higher at weight
 * 1, the weight animated 0 → 1 over 1 s (a third channel). */
static const float strip_lift = 0.2f;
static void morph_the_strip(gw_doc *g) {
    float d[NV][3] = {{0}};
    for (int v = COLS; v < NV; v++) d[v][1] = strip_lift;
    const float w[2] = {0, 1};
    char s[200];
    snprintf(s, sizeof s, "[{\"POSITION\": %d}]", gw_data(g, d, sizeof d, 5126, NV, "VEC3"));
    gw_set(g, "/meshes/0/primitives/0/targets", s);
    snprintf(s, sizeof s, "{\"input\": 7, \"output\": %d}", gw_data(g, w, sizeof w, 5126, 2, "SCALAR"));
    gw_set(g, "/animations/0/samplers/2", s);
    gw_set(g, "/animations/0/channels/2", "{\"sampler\": 2, \"target\": {\"node\": 0, \"path\": \"weights\"}}");
}

/* The morphing quad: accessors 0 POSITION, 1 NORMAL, 2 TEXCOORD_0, 3 indices, 4 and 5 the
 * targets' POSITION, 6 key times, 7 weights (2 per key); *target_at: target 0's offset. */
static const float quad_pos[4][3] = {{0.2f, 0, 0}, {1.2f, 0, 0}, {1.2f, 0.6f, 0}, {0.2f, 0.6f, 0}};
static const float quad_uv[4][2] = {{0.1f, 0.2f}, {0.9f, 0.2f}, {0.9f, 0.8f}, {0.1f, 0.8f}};
static const float target_up[4][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0.5f, 0}, {0, 0.5f, 0}};
static const float target_right[4][3] = {{0, 0, 0}, {0.5f, 0, 0}, {0.5f, 0, 0}, {0, 0, 0}};
static const uint16_t quad_idx[6] = {0, 1, 2, 0, 2, 3};

static void morphing_quad(gw_doc *g, size_t *target_at) {
    memset(g, 0, sizeof *g);
    g->json = cJSON_Parse(
        "{\"asset\": {\"version\": \"2.0\", \"generator\": \"shadelab tests/test_gltf_skin.c\"}, \"scene\": 0,"
        " \"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"name\": \"quad\", \"mesh\": 0}],"
        " \"meshes\": [{\"weights\": [0.5, 0], \"primitives\": [{\"attributes\": {\"POSITION\": 0, \"NORMAL\": 1, "
        "\"TEXCOORD_0\": 2}, \"indices\": 3, \"targets\": [{\"POSITION\": 4}, {\"POSITION\": 5}]}]}],"
        " \"animations\": [{\"channels\": [{\"sampler\": 0, \"target\": {\"node\": 0, \"path\": \"weights\"}}],"
        " \"samplers\": [{\"input\": 6, \"output\": 7}]}],"
        " \"buffers\": [{\"byteLength\": 0}], \"bufferViews\": [], \"accessors\": []}");
    const float nrm[4][3] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}}, times[2] = {0, 1}, weights[4] = {0, 0, 1, 1};
    gw_data(g, quad_pos, sizeof quad_pos, 5126, 4, "VEC3");
    gw_data(g, nrm, sizeof nrm, 5126, 4, "VEC3");
    gw_data(g, quad_uv, sizeof quad_uv, 5126, 4, "VEC2");
    gw_data(g, quad_idx, sizeof quad_idx, 5123, 6, "SCALAR");
    *target_at = gw_append(g, target_up, sizeof target_up);
    gw_accessor(g, gw_view(g, *target_at, sizeof target_up, 0), 5126, 4, "VEC3", NULL);
    gw_data(g, target_right, sizeof target_right, 5126, 4, "VEC3");
    size_t at = gw_append(g, times, sizeof times);
    gw_accessor(g, gw_view(g, at, sizeof times, 0), 5126, 2, "SCALAR", "{\"min\": [0], \"max\": [1]}");
    gw_data(g, weights, sizeof weights, 5126, 4, "SCALAR");
}

/* ---- the specification's formulas on the CPU ---------------------------------------------- */

typedef struct mat4d { double m[16]; } mat4d; /* column-major */

static mat4d mul(mat4d a, mat4d b) {
    mat4d r = {{0}};
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++)
            for (int k = 0; k < 4; k++) r.m[4 * c + row] += a.m[4 * k + row] * b.m[4 * c + k];
    return r;
}
static mat4d translate(double x, double y, double z) { return (mat4d){{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, y, z, 1}}; }
static mat4d rot_z(double a) { return (mat4d){{cos(a), sin(a), 0, 0, -sin(a), cos(a), 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}; }
static void apply(mat4d m, const double v[2], double out[2]) {
    for (int r = 0; r < 2; r++) out[r] = m.m[r] * v[0] + m.m[4 + r] * v[1] + m.m[12 + r];
}

/* The joint matrices at time t: world(joint) · inverseBindMatrix (the animation: root lifted by
 * 0.5 t, bone turned by 90° t, LINEAR: slerp about one axis is linear in the angle). */
static void joint_matrices(double t, mat4d J[2]) {
    mat4d root = translate(0, 0.5 * t, 0), bone = mul(mul(root, translate(1, 0, 0)), rot_z(M_PI / 2 * t));
    J[0] = root;
    J[1] = mul(bone, translate(-1, 0, 0));
}

/* The strip's vertices (xy) at time t: Σ w·J·v, v the rest position plus `morph` × the target. */
static void skinned_morphed_positions(double t, double morph, double out[NV][2], double uv[NV][2]) {
    mat4d J[2];
    joint_matrices(t, J);
    for (int v = 0; v < NV; v++) {
        float p[3], u[2];
        strip_vertex(v, p, u);
        double b = bone_weight(p[0]), rest[2] = {p[0], p[1] + (v >= COLS ? morph * strip_lift : 0)}, a0[2], a1[2];
        apply(J[0], rest, a0), apply(J[1], rest, a1);
        for (int c = 0; c < 2; c++) out[v][c] = (1 - b) * a0[c] + b * a1[c], uv[v][c] = u[c];
    }
}

static void skinned_positions(double t, double out[NV][2], double uv[NV][2]) { skinned_morphed_positions(t, 0, out, uv); }

/* ---- rasterising the expectation ---------------------------------------------------------- */

static double px_x(double i) { return CX + ((i + 0.5) / W * 2 - 1) * HALF; }
static double px_y(double j) { return CY + (1 - (j + 0.5) / H * 2) * HALF; }

/* The UV of the surface at (x, y) (false: no triangle there). */
static bool uv_at(const double (*p)[2], const double (*uv)[2], const uint16_t *tri, int nt, double x, double y, double out[2]) {
    for (int t = 0; t < nt; t++) {
        const double *a = p[tri[3 * t]], *b = p[tri[3 * t + 1]], *c = p[tri[3 * t + 2]];
        double d = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        if (fabs(d) < 1e-12) continue;
        double l1 = ((x - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (y - a[1])) / d;
        double l2 = ((b[0] - a[0]) * (y - a[1]) - (x - a[0]) * (b[1] - a[1])) / d, l0 = 1 - l1 - l2;
        if (l0 < -1e-9 || l1 < -1e-9 || l2 < -1e-9) continue;
        for (int k = 0; k < 2; k++) out[k] = l0 * uv[tri[3 * t]][k] + l1 * uv[tri[3 * t + 1]][k] + l2 * uv[tri[3 * t + 2]][k];
        return true;
    }
    return false;
}

/* Compares the "uv" view with the expected surface: returns the largest UV error inside, and counts
 * the pixels checked inside (*inside) and those outside showing anything (*stray). */
static double compare_uv(const float *img, const double (*p)[2], const double (*uv)[2], const uint16_t *tri, int nt,
                         long *inside, long *outside, long *stray) {
    double worst = 0, r = 1.5 * 2 * HALF / W, uvv[2];
    *inside = *outside = *stray = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            int hits = 0;
            for (int k = 0; k < 9; k++) { /* the pixel centre and 8 points 1.5 px around it */
                double a = k * M_PI / 4, x = px_x(i) + (k ? r * cos(a) : 0), y = px_y(j) + (k ? r * sin(a) : 0);
                hits += uv_at(p, uv, tri, nt, x, y, uvv);
            }
            const float *g = img + 4 * ((size_t)j * W + i);
            if (hits == 9 && uv_at(p, uv, tri, nt, px_x(i), px_y(j), uvv)) {
                worst = fmax(worst, fmax(fabs(g[0] - uvv[0]), fabs(g[1] - uvv[1])));
                (*inside)++;
            } else if (hits == 0) {
                (*outside)++;
                *stray += fabs(g[0]) + fabs(g[1]) > 1e-3;
            }
        }
    return worst;
}

static char scene[16384];
static const char *const *settings;
/* The scene: the model under node "m", the orthographic camera; `more`: nodes and members after it. */
static void scene_with(const char *model, const char *more) {
    snprintf(scene, sizeof scene,
             "{\"cameras\": [{\"name\": \"c\", \"type\": \"orthographic\", \"ymag\": %g, \"xmag\": %g, \"position\": "
             "[%g, %g, 5], \"target\": [%g, %g, 0], \"near\": 0.1, \"far\": 20}],\n"
             " \"nodes\": [{\"name\": \"m\", \"mesh\": {\"file\": \"%s\"}}%s}",
             HALF, HALF, CX, CY, CX, CY, model, more ? more : "]");
}
static void scene_json(const char *model) { scene_with(model, NULL); }

static sl_harness *harness(const char *const *plugins, const char *view) {
    sl_harness *h = sl_harness_create(&(sl_harness_desc){.struct_size = sizeof(sl_harness_desc), .width = W, .height = H,
                                                         .scene_json = scene, .plugins = plugins, .debug_view = view,
                                                         .strict = true, .settings = settings},
                                      err, sizeof err);
    CHECK_MSG(h != NULL, "harness: %s", err);
    return h;
}

static const uint16_t *strip_triangles(void) {
    static uint16_t idx[3 * NT];
    for (int c = 0, k = 0; c < COLS - 1; c++) {
        uint16_t a = (uint16_t)c, b = (uint16_t)(c + 1), d = (uint16_t)(c + COLS), e = (uint16_t)(c + 1 + COLS);
        idx[k++] = a, idx[k++] = b, idx[k++] = e, idx[k++] = a, idx[k++] = e, idx[k++] = d;
    }
    return idx;
}

/* ---- the tests ------------------------------------------------------------------------------ */

/* The skinned strip at t = 0.5 s, morphing too (its target at weight 0.5) when `morph`. */
static void test_skin_at(bool morph) {
    gw_doc g;
    size_t ja, wa, ia;
    skinned_strip(&g, &ja, &wa, &ia);
    if (morph) morph_the_strip(&g);
    char path[4200];
    snprintf(path, sizeof path, "%s/skinned_strip%s.gltf", sl_test_dir(), morph ? "_morph" : "");
    CHECK(gw_write(&g, path, GW_DATA_URI));
    gw_free(&g);
    scene_json(path);
    sl_harness *h = harness(NULL, "uv");
    if (!h) return;
    float *img = malloc(sizeof(float) * 4 * W * H);
    sl_harness_set_frame(h, 30); /* t = 0.5 s */
    CHECK(sl_harness_render(h, img));
    double p[NV][2], uv[NV][2];
    skinned_morphed_positions(0.5, morph ? 0.5 : 0, p, uv);
    long inside, outside, stray;
    double worst = compare_uv(img, (const double (*)[2])p, (const double (*)[2])uv, strip_triangles(), NT, &inside, &outside, &stray);
    /* the bind pose (unmorphed), to show the comparison can tell */
    double rest[NV][2];
    skinned_positions(0, rest, uv);
    long i2, o2, s2;
    double bind = compare_uv(img, (const double (*)[2])rest, (const double (*)[2])uv, strip_triangles(), NT, &i2, &o2, &s2);
    printf("skin%s: UV of the skinned strip at t = 0.5 s off by at most %.2e over %ld px inside (the bind pose: %.2f, "
           "%ld stray px); %ld of %ld px outside show something\n", morph ? " + morph" : "", worst, inside, bind, s2, stray, outside);
    CHECK_MSG(inside > 1000 && worst < 2e-3, "skinned strip: UV off by %g over %ld px", worst, inside);
    CHECK_MSG(outside > 3000 && stray == 0, "skinned strip: %ld of %ld px outside it drawn", stray, outside);
    CHECK_MSG(bind > 0.05 || s2 > 100, "the bind pose is not told apart (%g, %ld)", bind, s2);
    free(img);
    sl_harness_destroy(h);
}

static void test_skin(void) {
    test_skin_at(false);
    test_skin_at(true);
}

/* One render of the morphing quad at frame f (a fresh harness each: a harness's second render
 * of a still frame is off by up to 2e-3 in UV here, with or without deformation). */
static void test_morph_at(int f) {
    gw_doc g;
    size_t ta;
    morphing_quad(&g, &ta);
    char path[4200];
    snprintf(path, sizeof path, "%s/morphing_quad.glb", sl_test_dir());
    CHECK(gw_write(&g, path, GW_GLB));
    gw_free(&g);
    scene_json(path);
    sl_harness *h = harness(NULL, "uv");
    if (!h) return;
    float *img = malloc(sizeof(float) * 4 * W * H);
    sl_harness_set_frame(h, (uint64_t)f);
    CHECK(sl_harness_render(h, img));
    double w = f / 60.0, p[4][2], uv[4][2];
    for (int v = 0; v < 4; v++)
        for (int c = 0; c < 2; c++) p[v][c] = quad_pos[v][c] + w * target_up[v][c] + w * target_right[v][c], uv[v][c] = quad_uv[v][c];
    long inside, outside, stray;
    double worst = compare_uv(img, (const double (*)[2])p, (const double (*)[2])uv, quad_idx, 2, &inside, &outside, &stray);
    printf("morph: weights [%.2f, %.2f]: UV off by at most %.2e over %ld px inside; %ld of %ld px outside drawn\n", w, w,
           worst, inside, stray, outside);
    CHECK_MSG(inside > 300 && worst < 2e-3, "morphing quad at t = %g: UV off by %g over %ld px", w, worst, inside);
    CHECK_MSG(outside > 3000 && stray == 0, "morphing quad at t = %g: %ld of %ld px outside drawn", w, stray, outside);
    free(img);
    sl_harness_destroy(h);
}

/* t = 0.75 s: weights [0.75, 0.75]; t = 0: [0, 0] (the mesh's [0.5, 0], held by the rest shape, replaced) */
static void test_morph(void) {
    test_morph_at(45);
    test_morph_at(0);
}

/* Motion vectors: at a pixel showing a point bound to joint k alone, the point moved from
 * J_k(t₀)·J_k(t₁)⁻¹·x to x between the frames; "motion" holds that displacement in UV (2·HALF per
 * unit), x and y. */
static void test_motion(void) {
    gw_doc g;
    size_t ja, wa, ia;
    skinned_strip(&g, &ja, &wa, &ia);
    char path[4200];
    snprintf(path, sizeof path, "%s/skinned_strip_motion.gltf", sl_test_dir());
    CHECK(gw_write(&g, path, GW_DATA_URI));
    gw_free(&g);
    scene_json(path);
    const char *plugins[] = {TP_MOTION_PATH, NULL};
    sl_harness *h = harness(plugins, NULL);
    if (!h) return;
    float *img = malloc(sizeof(float) * 4 * W * H);
    sl_harness_set_frame(h, 30);
    CHECK(sl_harness_render(h, img));
    CHECK(sl_harness_render(h, img)); /* frame 31 */
    double t0 = 30 / 60.0, t1 = 31 / 60.0, p[NV][2], uv[NV][2], worst = 0, biggest = 0;
    mat4d J0[2], J1[2];
    joint_matrices(t0, J0), joint_matrices(t1, J1);
    skinned_positions(t1, p, uv);
    long n[2] = {0, 0};
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double x = px_x(i), y = px_y(j), r = 1.5 * 2 * HALF / W, u[2];
            int hits = 0;
            for (int k = 0; k < 9; k++) {
                double a = k * M_PI / 4;
                hits += uv_at((const double (*)[2])p, (const double (*)[2])uv, strip_triangles(), NT, x + (k ? r * cos(a) : 0),
                              y + (k ? r * sin(a) : 0), u);
            }
            if (hits < 9 || !uv_at((const double (*)[2])p, (const double (*)[2])uv, strip_triangles(), NT, x, y, u)) continue;
            double rest_x = (u[0] - 0.05) / 0.4; /* the rest position's x: which joints hold it */
            int k = rest_x < 0.45 ? 0 : rest_x > 1.55 ? 1 : -1;
            if (k < 0) continue;
            /* x = J1·v, so v = J1⁻¹·x; J1 is a rigid motion: invert by hand */
            const double *m = J1[k].m, d[2] = {x - m[12], y - m[13]}, v[2] = {m[0] * d[0] + m[1] * d[1], m[4] * d[0] + m[5] * d[1]};
            double prev[2];
            apply(J0[k], v, prev);
            double want[2] = {(x - prev[0]) / (2 * HALF), (y - prev[1]) / (2 * HALF)};
            const float *gp = img + 4 * ((size_t)j * W + i);
            worst = fmax(worst, fmax(fabs(gp[0] - want[0]), fabs(gp[1] - want[1])));
            biggest = fmax(biggest, hypot(want[0], want[1]));
            n[k]++;
        }
    printf("motion: skinned strip's motion vectors off by at most %.2e UV/frame from J(t0)·J(t1)^-1 (largest %.4f) over "
           "%ld px on the root, %ld on the bone\n", worst, biggest, n[0], n[1]);
    /* 3e-4: 2 % of the largest; a harness's second render is off a little (test_morph_at); motion
     * missing or a frame late is off by the whole displacement */
    CHECK_MSG(n[0] > 100 && n[1] > 100 && worst < 3e-4, "skinned motion off by %g (%ld, %ld px)", worst, n[0], n[1]);
    free(img);
    sl_harness_destroy(h);
}

/* Shadows: a sun travelling along (1, 0, −1) (spotlight-shadow's shadow map, drawn through the
 * core's depth-only path) casts the strip onto a grey wall at z = −1, shifted by +1 in x. At
 * t = 0.5 s every wall pixel more than 3 px from the shifted skinned strip's outline must be dark
 * inside it and lit outside it; the bind pose's shadow, shifted alike, would not match. */
static void test_shadow(void) {
    gw_doc g;
    size_t ja, wa, ia;
    skinned_strip(&g, &ja, &wa, &ia);
    char path[4200];
    snprintf(path, sizeof path, "%s/skinned_strip_shadow.gltf", sl_test_dir());
    CHECK(gw_write(&g, path, GW_DATA_URI));
    gw_free(&g);
    HALF = 1.75, CX = 1.5, CY = 0.5;
    scene_with(path, ", {\"name\": \"wall\", \"translate\": [1.5, 0.5, -1], \"rotate\": [90, 0, 0], \"mesh\": "
               "{\"primitive\": \"plane\", \"size\": 8}, \"material\": \"wall\"}],\n"
               " \"materials\": [{\"name\": \"wall\", \"base_color\": [0.5, 0.5, 0.5]}],\n"
               " \"lights\": [{\"name\": \"sun\", \"type\": \"directional\", \"direction\": [1, 0, -1], \"intensity\": 2, "
               "\"cast_shadows\": true}]");
    const char *plugins[] = {"spotlight-shadow", NULL};
    sl_harness *h = harness(plugins, NULL);
    if (!h) return;
    float *img = malloc(sizeof(float) * 4 * W * H);
    sl_harness_set_frame(h, 30);
    CHECK(sl_harness_render(h, img));
    double p[NV][2], rest[NV][2], uv[NV][2], shifted[NV][2], shifted_rest[NV][2], u[2];
    skinned_positions(0.5, p, uv);
    skinned_positions(0, rest, uv);
    for (int v = 0; v < NV; v++)
        shifted[v][0] = p[v][0] + 1, shifted[v][1] = p[v][1], shifted_rest[v][0] = rest[v][0] + 1, shifted_rest[v][1] = rest[v][1];
    const double lit = 0.5 / M_PI * 2 * sqrt(0.5), r = 3.0 * 2 * HALF / W;
    long shade = 0, light = 0, wrong = 0, wrong_bind = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double x = px_x(i), y = px_y(j);
            int on_strip = 0, in_shadow = 0, in_bind = 0;
            for (int k = 0; k < 9; k++) {
                double a = k * M_PI / 4, xx = x + (k ? r * cos(a) : 0), yy = y + (k ? r * sin(a) : 0);
                on_strip += uv_at((const double (*)[2])p, (const double (*)[2])uv, strip_triangles(), NT, xx, yy, u);
                in_shadow += uv_at((const double (*)[2])shifted, (const double (*)[2])uv, strip_triangles(), NT, xx, yy, u);
                in_bind += uv_at((const double (*)[2])shifted_rest, (const double (*)[2])uv, strip_triangles(), NT, xx, yy, u);
            }
            if (on_strip || (in_shadow % 9) != 0) continue; /* the strip itself, or near the shadow's outline */
            double gval = img[4 * ((size_t)j * W + i) + 1] / lit;
            bool dark = gval < 0.5;
            if (in_shadow) shade++; else light++;
            wrong += dark != (in_shadow == 9);
            if (in_bind % 9 == 0) wrong_bind += dark != (in_bind == 9);
        }
    printf("shadow: the skinned strip's shadow on the wall at t = 0.5 s: %ld px in shadow, %ld lit, %ld not as the "
           "posed strip casts it (as the bind pose would: %ld)\n", shade, light, wrong, wrong_bind);
    CHECK_MSG(shade > 200 && light > 2000 && wrong == 0, "skinned shadow: %ld of %ld px wrong", wrong, shade + light);
    CHECK_MSG(wrong_bind > 100, "the bind pose's shadow is not told apart (%ld px)", wrong_bind);
    free(img);
    sl_harness_destroy(h);
    HALF = 1.25, CX = 1.0, CY = 0.5;
}

/* ---- hostile files ---------------------------------------------------------------------------- */

typedef struct hcase {
    const char *name;
    bool morph;                /* the morphing quad, else the skinned strip */
    const char *edits[4][2];   /* JSON pointer, value (NULL: removed) */
    int patch;                 /* a binary change (below) */
    bool opens;
    const char *expect;        /* in the error, or the warning when it opens */
} hcase;

enum { NO_PATCH, JOINT_5, WEIGHT_NAN, WEIGHT_NEGATIVE, WEIGHTS_ZERO, IBM_NAN, TARGET_NAN, WEIGHTS_OFF };

static void patch(gw_doc *g, int what, size_t ja, size_t wa, size_t ia, size_t ta) {
    float nan = NAN, minus = -0.5f, zero[4] = {0, 0, 0, 0}, half = 0.4f;
    switch (what) {
    case JOINT_5: g->bin.d[ja + 4 * 3 + 1] = 5; break;                        /* vertex 3's second joint */
    case WEIGHT_NAN: memcpy(g->bin.d + wa + 16 * 3, &nan, 4); break;
    case WEIGHT_NEGATIVE: memcpy(g->bin.d + wa + 16 * 3, &minus, 4); break;
    case WEIGHTS_ZERO: memcpy(g->bin.d + wa + 16 * 3, zero, 16); break;
    case IBM_NAN: memcpy(g->bin.d + ia + 4 * 20, &nan, 4); break;
    case TARGET_NAN: memcpy(g->bin.d + ta + 12 * 2 + 4, &nan, 4); break;
    case WEIGHTS_OFF: memcpy(g->bin.d + wa + 16 * 3, &half, 4); break;        /* vertex 3: 0.4 + 0 */
    default: break;
    }
}

static const hcase cases[] = {
    {"skin_valid", false, {{NULL, NULL}}, NO_PATCH, true, NULL},
    {"morph_valid", true, {{NULL, NULL}}, NO_PATCH, true, NULL},
    {"joint_out_of_range", false, {{NULL, NULL}}, JOINT_5, false,
     "/meshes/0/primitives/0/attributes/JOINTS_0: vertex 3's joint 5 is not below the skin's 2 joints"},
    {"weight_nan", false, {{NULL, NULL}}, WEIGHT_NAN, false, "/meshes/0/primitives/0/attributes/WEIGHTS_0: vertex 3's weight nan"},
    {"weight_negative", false, {{NULL, NULL}}, WEIGHT_NEGATIVE, false, "WEIGHTS_0: vertex 3's weight -0.5 is not finite and non-negative"},
    {"weights_zero", false, {{NULL, NULL}}, WEIGHTS_ZERO, false, "WEIGHTS_0: vertex 3's weights sum to 0"},
    {"weights_not_unit", false, {{NULL, NULL}}, WEIGHTS_OFF, true, "the weights of 1 vertices do not sum to 1: normalised"},
    {"joints_without_weights", false, {{"/meshes/0/primitives/0/attributes/WEIGHTS_0", NULL}}, NO_PATCH, false,
     "/meshes/0/primitives/0/attributes/WEIGHTS_0: missing: JOINTS_0 comes with WEIGHTS_0"},
    {"three_sets", false, {{"/meshes/0/primitives/0/attributes/JOINTS_1", "4"}, {"/meshes/0/primitives/0/attributes/WEIGHTS_1", "5"},
      {"/meshes/0/primitives/0/attributes/JOINTS_2", "4"}, {"/meshes/0/primitives/0/attributes/WEIGHTS_2", "5"}}, NO_PATCH, false,
     "/meshes/0/primitives/0/attributes/JOINTS_2: shadelab reads at most 2 JOINTS/WEIGHTS sets"},
    {"two_sets", false, {{"/meshes/0/primitives/0/attributes/JOINTS_1", "4"}, {"/meshes/0/primitives/0/attributes/WEIGHTS_1", "5"}},
     NO_PATCH, true, "do not sum to 1: normalised"},
    {"joints_signed", false, {{"/accessors/4/componentType", "5120"}}, NO_PATCH, false,
     "/accessors/4: componentType 5120 is not allowed for /meshes/0/primitives/0/attributes/JOINTS_0"},
    {"joints_normalized", false, {{"/accessors/4/normalized", "true"}}, NO_PATCH, false, "is not allowed for /meshes/0/primitives/0/attributes/JOINTS_0"},
    {"ibm_too_few", false, {{"/accessors/6/count", "1"}}, NO_PATCH, false,
     "/skins/0/inverseBindMatrices: 1 matrices for 2 joints"},
    {"ibm_wrong_type", false, {{"/accessors/6/type", "\"VEC4\""}, {"/accessors/6/count", "8"}}, NO_PATCH, false,
     "/accessors/6: type VEC4, but /skins/0/inverseBindMatrices needs MAT4"},
    {"ibm_nan", false, {{NULL, NULL}}, IBM_NAN, false, "/skins/0/inverseBindMatrices: matrix 1's element 4 (nan) is not finite"},
    {"joint_not_in_scene", false, {{"/skins/0/joints", "[1, 3]"}}, NO_PATCH, false, "/skins/0/joints/1: node 3 is not in the scene shown"},
    {"joints_twice", false, {{"/skins/0/joints", "[1, 1]"}}, NO_PATCH, false, "/skins/0/joints/1: node 1 is listed twice"},
    {"joints_empty", false, {{"/skins/0/joints", "[]"}}, NO_PATCH, false, "/skins/0: joints is missing or empty"},
    {"joint_index_bad", false, {{"/skins/0/joints", "[1, 99]"}}, NO_PATCH, false, "/skins/0/joints/1: not an index of /nodes"},
    {"skin_index_bad", false, {{"/nodes/0/skin", "3"}}, NO_PATCH, false, "/nodes/0/skin: 3 is not an index of /skins"},
    {"joints_without_skin", false, {{"/nodes/0/skin", NULL}}, NO_PATCH, true, "JOINTS_0 without a skin on the node drawing it"},
    {"morph_weights_count", true, {{"/meshes/0/weights", "[0.5]"}}, NO_PATCH, false,
     "/meshes/0/primitives/0/targets: 2 targets, but the weights (or the mesh's other primitives) have 1"},
    {"morph_node_weights_count", true, {{"/nodes/0/weights", "[0.5, 0, 1]"}}, NO_PATCH, false, "2 targets, but the weights"},
    {"morph_weight_inf", true, {{"/meshes/0/weights", "raw:[1e309, 0]"}}, NO_PATCH, false, "/meshes/0"},
    {"morph_target_nan", true, {{NULL, NULL}}, TARGET_NAN, false,
     "/meshes/0/primitives/0/targets/0/POSITION: the displacement of vertex 2 is not finite"},
    {"morph_target_type", true, {{"/accessors/4/type", "\"VEC2\""}}, NO_PATCH, false,
     "/accessors/4: type VEC2, but /meshes/0/primitives/0/targets/0/POSITION needs VEC3"},
    {"morph_channel_count", true, {{"/accessors/7/count", "3"}}, NO_PATCH, true,
     "/animations/0/samplers/0/output: 3 values are not a whole number of keys of 2 weights"},
    {"morph_channel_no_targets", false, {{"/animations/0/channels/0/target/path", "\"weights\""}}, NO_PATCH, true,
     "node 1 draws no mesh with morph targets: channel not played"},
};

static void test_hostile(void) {
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        const hcase *c = &cases[i];
        gw_doc g;
        size_t ja = 0, wa = 0, ia = 0, ta = 0;
        if (c->morph) morphing_quad(&g, &ta);
        else skinned_strip(&g, &ja, &wa, &ia);
        for (int k = 0; k < 4 && c->edits[k][0]; k++) CHECK_MSG(gw_set(&g, c->edits[k][0], c->edits[k][1]), "%s: edit", c->name);
        patch(&g, c->patch, ja, wa, ia, ta);
        char path[4200];
        snprintf(path, sizeof path, "%s/%s.gltf", sl_test_dir(), c->name);
        CHECK(gw_write(&g, path, GW_DATA_URI));
        const char *seeds = getenv("SL_GLTF_SEEDS"); /* the fuzzer's seeds too (fuzz/README.md) */
        if (seeds) {
            snprintf(path, sizeof path, "%s/%s.gltf", seeds, c->name);
            gw_write(&g, path, GW_DATA_URI);
            snprintf(path, sizeof path, "%s/%s.gltf", sl_test_dir(), c->name);
        }
        gw_free(&g);
        sl_scene s = {0};
        err[0] = 0;
        sl_log_capture(logbuf, sizeof logbuf);
        bool ok = sl_scene_load_file(&s, path, NULL, err, sizeof err);
        sl_log_capture(NULL, 0);
        CHECK_MSG(ok == c->opens, "%s: %s (%s)", c->name, ok ? "opened" : "refused", ok ? logbuf : err);
        if (!ok) CHECK_MSG(strstr(err, path) == err, "%s: the error does not start with the file: %s", c->name, err);
        if (c->expect) CHECK_MSG(strstr(ok ? logbuf : err, c->expect), "%s: expected \"%s\" in: %s", c->name, c->expect, ok ? logbuf : err);
        if (ok && !c->expect) CHECK_MSG(!strstr(logbuf, "warning"), "%s: a valid file warned: %s", c->name, logbuf);
        if (ok && !strcmp(c->name, "skin_valid")) { /* what the reader keeps: one skin, the deformation */
            CHECK(s.skin_count == 1 && s.skins[0].joint_count == 2 && s.skins[0].inverse_bind[16 + 12] == -1);
            CHECK(s.mesh_count == 1 && s.meshes[0].deform && s.meshes[0].deform->influences == 4 && s.meshes[0].deform->skin == 0);
        }
        if (ok && !strcmp(c->name, "morph_valid")) { /* the shape at the mesh's weights [0.5, 0], the targets kept */
            const sl_mesh_deform *d = s.meshes[0].deform;
            CHECK(d && d->target_count == 2 && d->rest_weights[0] == 0.5f && d->target_positions && !d->target_normals);
            CHECK(s.anim_channel_count == 1 && s.anim_channels[0].path == SL_ANIM_WEIGHTS && s.anim_channels[0].components == 2);
        }
        sl_scene_free(&s);
    }
    printf("hostile: %zu skin and morph files, each refused naming the file, pointer and cause, or opened as expected\n",
           sizeof cases / sizeof *cases);
}

int main(void) {
    sl_log_threshold = SL_LOG_WARN;
    test_hostile();
    test_skin();
    test_morph();
    test_motion();
    test_shadow();
    return check_result();
}
