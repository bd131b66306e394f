/* Hostile and unusual glTF, written by the test from a valid file (tests/gltf_writer.h) with one
 * thing changed each: truncated and damaged containers, huge counts and lengths, cycles in the
 * node graph, NaN and 1e30 values, bad data: URIs, out-of-range indices, invalid camera values,
 * unplayable animation channels. Each file is opened as a model (sl_scene_load_file) and must
 * either fail with a message naming the file, the JSON pointer and the cause, or open with a
 * warning naming what was dropped or replaced; none may crash, and each load must finish within
 * a bound (SL_HOSTILE_SECONDS, generous for sanitizer builds). Valid edge cases (a BOM, a
 * sparse accessor without a bufferView, a million animation keys) must open without a word. */
#include "check.h"
#include "gltf_writer.h"
#include "log.h"
#include "scene/scene.h"
#include "test_tmp.h"

#include <math.h>
#include <time.h>

#define SL_HOSTILE_SECONDS 20.0

static char err[8192], logbuf[1 << 16];

typedef struct hcase {
    const char *name;
    const char *edits[6][2];   /* JSON pointer, JSON value (NULL: removed) */
    void (*build)(gw_doc *g);  /* more changes, or NULL */
    int format;
    bool opens;
    const char *expect[3];     /* in the error (or, when it opens, in the log) */
} hcase;

/* ---- changes the edits cannot make ------------------------------------------------------- */

static void patch_float(gw_doc *g, size_t at, float v) { memcpy(g->bin.d + at, &v, 4); }
static void patch_u32(gw_doc *g, size_t at, uint32_t v) { memcpy(g->bin.d + at, &v, 4); }
/* the base's binary layout (gw_quad): positions at 0, key times at 140, u32 indices at 172 */
static void nan_position(gw_doc *g) { patch_float(g, 12 + 4, NAN); }        /* vertex 1: triangle 0 only */
static void nan_key(gw_doc *g) { patch_float(g, 140, NAN); }
static void keys_decreasing(gw_doc *g) { patch_float(g, 140, 1), patch_float(g, 144, 0); }
static void index_max(gw_doc *g) { patch_u32(g, 172 + 4, 0xFFFFFFFFu); }   /* triangle 0 */
static void all_indices_out(gw_doc *g) {
    for (int i = 0; i < 6; i++) patch_u32(g, 172 + 4 * (size_t)i, 4 + (uint32_t)i);
}
static void empty_object(gw_doc *g) {
    cJSON_Delete(g->json);
    g->json = cJSON_Parse("{}");
}
static void deep_chain(gw_doc *g) { /* node 0 under 100 ancestors */
    cJSON *nodes = cJSON_GetObjectItem(g->json, "nodes");
    for (int i = 0; i < 100; i++) {
        char text[64];
        snprintf(text, sizeof text, "{\"children\": [%d]}", i == 0 ? 0 : 1 + i);
        cJSON_AddItemToArray(nodes, cJSON_Parse(text));
    }
    gw_set(g, "/scenes/0/nodes", "[101, 1]");
}
static void million_keys(gw_doc *g) {
    int n = 1000000;
    float *t = malloc(sizeof(float) * (size_t)n), *v = calloc((size_t)n * 3, sizeof(float));
    for (int i = 0; i < n; i++) t[i] = (float)i * 1e-3f, v[3 * i] = sinf((float)i);
    int ti = gw_data(g, t, sizeof(float) * (size_t)n, 5126, n, "SCALAR");
    int vi = gw_data(g, v, sizeof(float) * 3 * (size_t)n, 5126, n, "VEC3");
    char s[64];
    snprintf(s, sizeof s, "{\"input\": %d, \"output\": %d}", ti, vi);
    gw_set(g, "/animations/0/samplers/0", s);
    free(t), free(v);
}
static void sparse_positions(gw_doc *g) { /* zeros with the four corners substituted */
    const uint16_t idx[4] = {0, 1, 2, 3};
    const float pos[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    size_t ia = gw_append(g, idx, sizeof idx), va = gw_append(g, pos, sizeof pos);
    char s[300];
    snprintf(s, sizeof s, "{\"count\": 4, \"indices\": {\"bufferView\": %d, \"componentType\": 5123}, \"values\": "
             "{\"bufferView\": %d}}", gw_view(g, ia, sizeof idx, 0), gw_view(g, va, sizeof pos, 0));
    gw_set(g, "/accessors/0/bufferView", NULL);
    gw_set(g, "/accessors/0/sparse", s);
}
static void sparse_unsorted(gw_doc *g) {
    const uint16_t idx[2] = {2, 1};
    const float pos[6] = {0};
    size_t ia = gw_append(g, idx, sizeof idx), va = gw_append(g, pos, sizeof pos);
    char s[300];
    snprintf(s, sizeof s, "{\"count\": 2, \"indices\": {\"bufferView\": %d, \"componentType\": 5123}, \"values\": "
             "{\"bufferView\": %d}}", gw_view(g, ia, sizeof idx, 0), gw_view(g, va, sizeof pos, 0));
    gw_set(g, "/accessors/0/sparse", s);
}

#define NONE {{NULL, NULL}}
static const hcase cases[] = {
    {"valid", NONE, NULL, GW_GLB, true, {NULL}},
    {"valid_data_uri", NONE, NULL, GW_DATA_URI, true, {NULL}},
    {"valid_external", NONE, NULL, GW_EXTERNAL, true, {NULL}},
    {"empty_object", NONE, empty_object, GW_DATA_URI, false, {"/asset: missing"}},
    {"gltf_1", {{"/asset/version", "\"1.0\""}}, NULL, GW_DATA_URI, false, {"/asset/version: \"1.0\": shadelab reads glTF 2.x only"}},
    {"min_version", {{"/asset/minVersion", "\"2.1\""}}, NULL, GW_GLB, false, {"/asset/minVersion"}},
    {"required_basisu", {{"/extensionsRequired", "[\"KHR_texture_basisu\"]"}}, NULL, GW_GLB, false,
     {"requires glTF extension shadelab does not support: KHR_texture_basisu"}},
    {"count_huge", {{"/accessors/0/count", "2147483647"}}, NULL, GW_GLB, false,
     {"/accessors/0: 2147483647 elements", "bufferView 0 has 48"}},
    {"count_over_int", {{"/accessors/0/count", "4294967296"}}, NULL, GW_GLB, false, {"/accessors/0/count: 4294967296 is out of range"}},
    {"zeros_huge", {{"/accessors/1/bufferView", NULL}, {"/accessors/1/count", "1000000000"}}, NULL, GW_GLB, false,
     {"/accessors/1: count 1000000000 without a bufferView is over"}},
    {"buffer_huge", {{"/buffers/0/byteLength", "1000000000000"}}, NULL, GW_GLB, false,
     {"/buffers/0: byteLength 1000000000000 is more than the BIN chunk's"}},
    {"buffer_huge_external", {{"/buffers/0/byteLength", "1000000000000"}}, NULL, GW_EXTERNAL, false,
     {"/buffers/0/uri: ", "fewer than the buffer's byteLength 1000000000000"}},
    {"view_past_buffer", {{"/bufferViews/0/byteLength", "100000"}}, NULL, GW_GLB, false,
     {"/bufferViews/0: bytes 0 to 100000 lie past the end of buffer 0"}},
    {"stride_small", {{"/bufferViews/0/byteStride", "8"}}, NULL, GW_GLB, false, {"byteStride 8 is less than the element size 12"}},
    {"stride_odd", {{"/bufferViews/0/byteStride", "14"}}, NULL, GW_GLB, false, {"/bufferViews/0: byteStride 14 is not a multiple of 4"}},
    {"offset_misaligned", {{"/accessors/0/byteOffset", "2"}}, NULL, GW_GLB, false,
     {"/accessors/0: byteOffset 2 is not a multiple of the component size 4"}},
    {"normalized_float", {{"/accessors/0/normalized", "true"}}, NULL, GW_GLB, false, {"/accessors/0: normalized is only for 8- and 16-bit"}},
    {"type_mismatch", {{"/accessors/0/type", "\"VEC2\""}}, NULL, GW_GLB, false,
     {"/accessors/0: type VEC2, but /meshes/0/primitives/0/attributes/POSITION needs VEC3"}},
    {"integer_positions", {{"/accessors/0/componentType", "5123"}}, NULL, GW_GLB, false,
     {"/accessors/0: componentType 5123 is not allowed for /meshes/0/primitives/0/attributes/POSITION"}},
    {"count_mismatch", {{"/accessors/1/count", "3"}}, NULL, GW_GLB, false,
     {"/meshes/0/primitives/0/attributes/NORMAL: 3 elements, but POSITION has 4"}},
    {"color_vec2", {{"/meshes/0/primitives/0/attributes/COLOR_0", "2"}}, NULL, GW_GLB, false,
     {"/meshes/0/primitives/0/attributes/COLOR_0: accessor 2 is VEC2: COLOR_0 must be VEC3 or VEC4"}},
    {"color_count", {{"/meshes/0/primitives/0/attributes/COLOR_0", "5"}}, NULL, GW_GLB, false,
     {"/meshes/0/primitives/0/attributes/COLOR_0: 2 elements, but POSITION has 4"}},
    {"color_signed_bytes", {{"/accessors/7", "{\"bufferView\": 0, \"componentType\": 5120, \"normalized\": true, "
                                             "\"count\": 4, \"type\": \"VEC4\"}"},
                            {"/meshes/0/primitives/0/attributes/COLOR_0", "7"}}, NULL, GW_GLB, false,
     {"/accessors/7: componentType 5120 normalized is not allowed for /meshes/0/primitives/0/attributes/COLOR_0"}},
    {"color_target", {{"/meshes/0/primitives/0/attributes/COLOR_0", "1"},
                      {"/meshes/0/primitives/0/targets", "[{\"POSITION\": 1, \"COLOR_0\": 1}]"}}, NULL, GW_GLB, true,
     {"/meshes/0/primitives/0/targets/0: COLOR_0 displacements not applied"}},
    {"color_valid", {{"/meshes/0/primitives/0/attributes/COLOR_0", "1"}}, NULL, GW_GLB, true, {NULL}},
    {"cycle", {{"/nodes/0/children", "[1]"}, {"/nodes/1/children", "[0]"}}, NULL, GW_GLB, false, {"is its own ancestor"}},
    {"self_child", {{"/nodes/0/children", "[0]"}}, NULL, GW_GLB, false, {"/nodes/0/children/0: node 0 is its own child"}},
    {"two_parents", {{"/nodes/2", "{\"children\": [1]}"}, {"/nodes/0/children", "[1]"}}, NULL, GW_GLB, false,
     {"/nodes/2/children/0: node 1 already has parent 0"}},
    {"root_is_child", {{"/nodes/0/children", "[1]"}}, NULL, GW_GLB, false, {"/scenes/0/nodes/1: node 1 is a child of node 0, not a root"}},
    {"deep_chain", NONE, deep_chain, GW_GLB, false, {"nested deeper than 64 levels"}},
    {"bad_mesh_index", {{"/nodes/0/mesh", "7"}}, NULL, GW_GLB, false, {"/nodes/0/mesh: 7 is not an index of /meshes (1 element)"}},
    {"matrix_1e30", {{"/nodes/0/matrix", "[1e30, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]"}}, NULL, GW_GLB, false,
     {"/nodes/0/matrix: element 0 (1e+30) is beyond"}},
    {"matrix_inf", {{"/nodes/0/matrix", "raw:[1e309, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]"}}, NULL, GW_DATA_URI, false,
     {"/nodes/0/matrix: element 0", "not a finite 32-bit float"}},
    {"zero_quaternion", {{"/nodes/0/rotation", "[0, 0, 0, 0]"}}, NULL, GW_GLB, true, {"/nodes/0/rotation: a zero quaternion: the identity used"}},
    {"zero_scale", {{"/nodes/0/scale", "[0, 0, 0]"}}, NULL, GW_GLB, true, {NULL}},
    {"yfov_negative", {{"/cameras/0/perspective/yfov", "-1"}}, NULL, GW_GLB, true, {"/cameras/0/perspective/yfov: -1 is invalid"}},
    {"zfar_below_znear", {{"/cameras/0/perspective/zfar", "0.01"}}, NULL, GW_GLB, true, {"/cameras/0/perspective/zfar: 0.01 is invalid"}},
    {"ortho_zero_xmag", {{"/cameras/0", "{\"type\": \"orthographic\", \"orthographic\": {\"xmag\": 0, \"ymag\": 1, \"znear\": 0, \"zfar\": 5}}"}},
     NULL, GW_GLB, true, {"/cameras/0/orthographic/xmag: 0 is invalid"}},
    {"nan_key", NONE, nan_key, GW_GLB, true, {"/animations/0/samplers/0/input: key 0's time nan", "channel not played"}},
    {"keys_decreasing", NONE, keys_decreasing, GW_GLB, true, {"key 1's time 0 is not finite, non-negative and after the previous one"}},
    {"keys_count_mismatch", {{"/accessors/5/count", "1"}}, NULL, GW_GLB, true, {"/animations/0/samplers/0/output: 1 values for 2 keys"}},
    {"channel_without_node", {{"/animations/0/channels/0/target/node", NULL}}, NULL, GW_GLB, true,
     {"/animations/0/channels/0/target: path \"translation\" without a node: channel not played"}},
    {"empty_scene_and_channel_without_node", {{"/scenes", "[{}]"}, {"/animations/0/channels/0/target/node", NULL}}, NULL, GW_GLB,
     false, {"nothing to draw"}},
    {"animation_pointer", {{"/extensionsUsed", "[\"KHR_animation_pointer\"]"},
      {"/animations/0/channels/0/target", "{\"path\": \"pointer\", \"extensions\": {\"KHR_animation_pointer\": {\"pointer\": \"/nodes/0/translation\"}}}"}},
     NULL, GW_GLB, true, {"path \"pointer\" without a node: channel not played"}},
    {"interpolation_unknown", {{"/animations/0/samplers/0/interpolation", "\"BEZIER\""}}, NULL, GW_GLB, false,
     {"/animations/0/samplers/0: interpolation \"BEZIER\" is not LINEAR, STEP or CUBICSPLINE"}},
    {"index_uint32_max", {{"/meshes/0/primitives/0/indices", "6"}}, index_max, GW_GLB, true,
     {"/meshes/0/primitives/0: 1 triangle with an index past the 4 vertices dropped"}},
    {"all_indices_out_of_range", {{"/meshes/0/primitives/0/indices", "6"}}, all_indices_out, GW_GLB, false, {"nothing to draw"}},
    {"nan_position", NONE, nan_position, GW_GLB, true, {"/meshes/0/primitives/0: 1 triangle with a non-finite position dropped"}},
    {"lines_beside_triangles", {{"/meshes/0/primitives/1", "{\"attributes\": {\"POSITION\": 0}, \"mode\": 1}"}}, NULL, GW_GLB, true,
     {"/meshes/0/primitives/1: mode 1 (LINES) not drawn"}},
    {"no_primitives", {{"/meshes/0/primitives", "[]"}}, NULL, GW_GLB, false, {"nothing to draw"}},
    {"data_uri_garbage", {{"/buffers/0/uri", "\"data:application/octet-stream;base64,@@@@\""}}, NULL, GW_AS_IS, false,
     {"/buffers/0/uri: not a base64 data: URI"}},
    {"data_uri_short", {{"/buffers/0/uri", "\"data:application/octet-stream;base64,AAAA\""}}, NULL, GW_AS_IS, false,
     {"/buffers/0/uri: decodes to 3 bytes, fewer than byteLength"}},
    {"uri_to_device", {{"/buffers/0/uri", "\"../../../../../../../../dev/zero\""}}, NULL, GW_AS_IS, false,
     {"/buffers/0/uri: ", "is not a regular file (a device)"}},
    {"uri_remote", {{"/buffers/0/uri", "\"https://example.com/x.bin\""}}, NULL, GW_AS_IS, false,
     {"/buffers/0/uri: \"https://example.com/x.bin\" is not a relative file reference"}},
    {"sparse_positions", NONE, sparse_positions, GW_GLB, true, {NULL}},
    {"sparse_unsorted", NONE, sparse_unsorted, GW_GLB, false,
     {"/accessors/0/sparse/indices: index 1 is 1: sparse indices must increase strictly"}},
    {"spot_cone_inverted", {{"/extensionsUsed", "[\"KHR_lights_punctual\"]"},
      {"/extensions", "{\"KHR_lights_punctual\": {\"lights\": [{\"type\": \"spot\", \"spot\": {\"innerConeAngle\": 0.8, \"outerConeAngle\": 0.2}}]}}"},
      {"/nodes/1/extensions", "{\"KHR_lights_punctual\": {\"light\": 0}}"}}, NULL, GW_GLB, true,
     {"/extensions/KHR_lights_punctual/lights/0/spot: cone angles 0.8, 0.2 are outside"}},
    {"million_keys", NONE, million_keys, GW_GLB, true, {NULL}},
};

/* Opens the file as a model; checks the outcome and the words; returns the seconds it took. */
static double open_case(const hcase *c, const char *path) {
    sl_scene s = {0};
    err[0] = 0;
    struct timespec t0, t1;
    sl_log_capture(logbuf, sizeof logbuf);
    clock_gettime(CLOCK_MONOTONIC, &t0);
    bool ok = sl_scene_load_file(&s, path, NULL, err, sizeof err);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    sl_log_capture(NULL, 0);
    double seconds = (double)(t1.tv_sec - t0.tv_sec) + (t1.tv_nsec - t0.tv_nsec) * 1e-9;
    CHECK_MSG(ok == c->opens, "%s: %s, expected it to %s (%s)", c->name, ok ? "opened" : "failed",
              c->opens ? "open" : "fail", ok ? logbuf : err);
    if (!ok) CHECK_MSG(strstr(err, path) == err, "%s: the error does not start with the file: %s", c->name, err);
    for (int k = 0; k < 3 && c->expect[k]; k++)
        CHECK_MSG(strstr(ok ? logbuf : err, c->expect[k]), "%s: expected \"%s\" in: %s", c->name, c->expect[k],
                  ok ? logbuf : err);
    if (ok && !c->expect[0])
        CHECK_MSG(!strstr(logbuf, "warning"), "%s: a valid file warned: %s", c->name, logbuf);
    CHECK_MSG(seconds < SL_HOSTILE_SECONDS, "%s: took %.1f s", c->name, seconds);
    if (ok && !strcmp(c->name, "sparse_positions") && s.mesh_count == 1) /* the substituted corners */
        CHECK(s.meshes[0].data.positions[3] == 1 && s.meshes[0].data.positions[7] == 1 && s.meshes[0].data.positions[9] == -1);
    if (ok && !strcmp(c->name, "million_keys")) CHECK(s.anim_channel_count == 1 && s.anim_channels[0].key_count == 1000000);
    sl_scene_free(&s);
    return seconds;
}

/* A valid GLB cut at many lengths, and a header whose length lies: refused, never a crash. */
static void test_truncated(void) {
    gw_doc g;
    CHECK(gw_quad(&g));
    char path[4200];
    snprintf(path, sizeof path, "%s/truncated.glb", sl_test_dir());
    buf full;
    CHECK(gw_bytes(&g, path, GW_GLB, &full));
    int refused = 0, tried = 0;
    for (size_t len = 0; len < full.n; len += len < 64 ? 1 : 37, tried++) {
        gw_write_bytes(path, full.d, len);
        sl_scene s = {0};
        sl_log_capture(logbuf, sizeof logbuf);
        bool ok = sl_scene_load_file(&s, path, NULL, err, sizeof err);
        sl_log_capture(NULL, 0);
        refused += !ok && strstr(err, path) == err;
        sl_scene_free(&s);
    }
    CHECK_MSG(refused == tried, "%d of %d truncated GLBs refused with a message naming the file", refused, tried);
    full.d[8] ^= 0x40; /* the header's total length */
    gw_write_bytes(path, full.d, full.n);
    sl_scene s = {0};
    CHECK(!sl_scene_load_file(&s, path, NULL, err, sizeof err));
    CHECK_CONTAINS(err, "the GLB header gives a length of");
    sl_scene_free(&s);
    printf("truncated: %d cut GLBs refused, each naming the file\n", refused);
    free(full.d);
    gw_free(&g);
}

/* A .gltf cut mid-JSON names the line and column; one with a byte-order mark opens. */
static void test_json_text(void) {
    gw_doc g;
    CHECK(gw_quad(&g));
    char path[4200];
    snprintf(path, sizeof path, "%s/text.gltf", sl_test_dir());
    buf text, bom = {0};
    CHECK(gw_bytes(&g, path, GW_DATA_URI, &text));
    gw_write_bytes(path, text.d, text.n / 2);
    sl_scene s = {0};
    CHECK(!sl_scene_load_file(&s, path, NULL, err, sizeof err));
    CHECK_CONTAINS(err, "text.gltf: invalid JSON at line 1, column");
    put(&bom, "\xEF\xBB\xBF", 3);
    put(&bom, text.d, text.n);
    gw_write_bytes(path, bom.d, bom.n);
    bool ok = sl_scene_load_file(&s, path, NULL, err, sizeof err);
    CHECK_MSG(ok, "a .gltf with a BOM: %s", err);
    sl_scene_free(&s);
    free(text.d), free(bom.d);
    gw_free(&g);
}

/* Every file in tests/data/fuzz_gltf/ (the seeds this test writes, and inputs the fuzzer found):
 * a scene or an error naming the file, never a crash. */
static void test_fuzz_corpus(void) {
    const char *dir = SL_TEST_DATA_DIR "/fuzz_gltf";
    DIR *d = opendir(dir);
    CHECK_MSG(d != NULL, "cannot open %s", dir);
    int files = 0, opened = 0;
    for (struct dirent *e; d && (e = readdir(d));) {
        if (e->d_name[0] == '.') continue;
        char path[4200];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        sl_scene s = {0};
        sl_log_capture(logbuf, sizeof logbuf);
        bool ok = sl_scene_import_gltf(&s, path, -1, NULL, err, sizeof err);
        sl_log_capture(NULL, 0);
        files++, opened += ok;
        if (!ok) CHECK_MSG(strstr(err, path) == err, "%s: the error does not name the file: %s", e->d_name, err);
        sl_scene_free(&s);
    }
    if (d) closedir(d);
    printf("fuzz corpus: %d files, %d opened, the rest refused naming the file\n", files, opened);
}

int main(void) {
    sl_log_threshold = SL_LOG_WARN;
    const char *seeds = getenv("SL_GLTF_SEEDS"); /* writes each case's file there too (fuzz/README.md) */
    double worst = 0;
    const char *slowest = "";
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        const hcase *c = &cases[i];
        gw_doc g;
        CHECK(gw_quad(&g));
        for (int k = 0; k < 6 && c->edits[k][0]; k++)
            CHECK_MSG(gw_set(&g, c->edits[k][0], c->edits[k][1]), "%s: edit %s", c->name, c->edits[k][0]);
        if (c->build) c->build(&g);
        char path[4200];
        snprintf(path, sizeof path, "%s/%s.%s", sl_test_dir(), c->name, c->format == GW_GLB ? "glb" : "gltf");
        CHECK_MSG(gw_write(&g, path, c->format), "%s: writing %s", c->name, path);
        if (seeds && c->format != GW_EXTERNAL && strcmp(c->name, "million_keys")) {
            char seed[4200];
            snprintf(seed, sizeof seed, "%s/%s.%s", seeds, c->name, c->format == GW_GLB ? "glb" : "gltf");
            gw_write(&g, seed, c->format);
        }
        double t = open_case(c, path);
        if (t > worst) worst = t, slowest = c->name;
        gw_free(&g);
    }
    test_truncated();
    test_json_text();
    test_fuzz_corpus();
    printf("%zu hostile files; the slowest (%s) took %.2f s\n", sizeof cases / sizeof *cases, slowest, worst);
    return check_result();
}
