/* glTF files written by the tests themselves, from the specification (glTF 2.0): a document is a
 * cJSON tree plus its binary buffer; edits address members by JSON pointer, so a test states a
 * file as "this valid quad, with /accessors/0/count set to 2147483647". Header-only; include once.
 *
 *   gw_quad(&g)             a valid file: one quad (POSITION, NORMAL, TEXCOORD_0, u16 indices;
 *                           accessors 0-3), a perspective camera at node 1, a translation
 *                           animation of node 0 (accessors 4, 5: 2 keys), and u32 indices that
 *                           nothing uses (accessor 6), all in buffer 0
 *   gw_set(&g, ptr, json)   sets the member at ptr to the JSON value (NULL: removes it;
 *                           "raw:TEXT": TEXT as written); a pointer ending in the array's size
 *                           appends
 *   gw_append / gw_view / gw_accessor   more binary data, bufferViews and accessors
 *   gw_write(&g, path, fmt) GW_GLB (header, JSON and BIN chunks), GW_DATA_URI (.gltf with the
 *                           buffer as base64), GW_EXTERNAL (.gltf + "<path>.bin") or GW_AS_IS
 *                           (.gltf, buffer 0's uri as the edits left it) */
#ifndef SL_TEST_GLTF_WRITER_H
#define SL_TEST_GLTF_WRITER_H
#include "byte_buffer.h"
#include <cjson/cJSON.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct gw_doc { cJSON *json; buf bin; } gw_doc;
enum { GW_GLB, GW_DATA_URI, GW_EXTERNAL, GW_AS_IS };

static inline void gw_free(gw_doc *g) {
    cJSON_Delete(g->json);
    free(g->bin.d);
    memset(g, 0, sizeof *g);
}

/* The parent of the member ptr names (created objects on the way), and its last key. */
static inline cJSON *gw_parent(cJSON *root, const char *ptr, char *key, size_t key_size) {
    cJSON *at = root;
    const char *p = ptr;
    while (*p == '/') {
        const char *end = strchr(p + 1, '/');
        size_t n = end ? (size_t)(end - p - 1) : strlen(p + 1);
        if (n >= key_size) return NULL;
        memcpy(key, p + 1, n);
        key[n] = 0;
        if (!end) return at;
        cJSON *next = cJSON_IsArray(at) ? cJSON_GetArrayItem(at, atoi(key)) : cJSON_GetObjectItemCaseSensitive(at, key);
        if (!next && cJSON_IsObject(at)) next = cJSON_AddObjectToObject(at, key);
        if (!next) return NULL;
        at = next, p = end;
    }
    return NULL;
}

static inline bool gw_set(gw_doc *g, const char *ptr, const char *json) {
    char key[128];
    cJSON *parent = gw_parent(g->json, ptr, key, sizeof key);
    if (!parent) return false;
    /* "raw:TEXT" goes into the file as written (1e309, which cJSON would print as null) */
    cJSON *value = !json ? NULL : !strncmp(json, "raw:", 4) ? cJSON_CreateRaw(json + 4) : cJSON_Parse(json);
    if (cJSON_IsArray(parent)) {
        int i = atoi(key), n = cJSON_GetArraySize(parent);
        if (!value) return cJSON_DeleteItemFromArray(parent, i), true;
        if (i == n) return cJSON_AddItemToArray(parent, value);
        return cJSON_ReplaceItemInArray(parent, i, value);
    }
    if (!value) return cJSON_DeleteItemFromObjectCaseSensitive(parent, key), true;
    if (cJSON_GetObjectItemCaseSensitive(parent, key)) return cJSON_ReplaceItemInObjectCaseSensitive(parent, key, value);
    return cJSON_AddItemToObject(parent, key, value);
}

/* Appends bytes to buffer 0 at a 4-byte boundary; their offset. */
static inline size_t gw_append(gw_doc *g, const void *data, size_t n) {
    static const unsigned char zero[4] = {0};
    if (g->bin.n % 4) put(&g->bin, zero, 4 - g->bin.n % 4);
    size_t at = g->bin.n;
    put(&g->bin, data, n);
    cJSON_SetNumberValue(cJSON_GetObjectItem(cJSON_GetArrayItem(cJSON_GetObjectItem(g->json, "buffers"), 0), "byteLength"),
                         (double)g->bin.n);
    return at;
}

static inline int gw_view(gw_doc *g, size_t offset, size_t length, int stride) {
    cJSON *views = cJSON_GetObjectItem(g->json, "bufferViews"), *v = cJSON_CreateObject();
    cJSON_AddNumberToObject(v, "buffer", 0);
    cJSON_AddNumberToObject(v, "byteOffset", (double)offset);
    cJSON_AddNumberToObject(v, "byteLength", (double)length);
    if (stride) cJSON_AddNumberToObject(v, "byteStride", stride);
    cJSON_AddItemToArray(views, v);
    return cJSON_GetArraySize(views) - 1;
}

/* An accessor (view < 0: none); extra: more members as JSON object text, or NULL. */
static inline int gw_accessor(gw_doc *g, int view, int component_type, long long count, const char *type, const char *extra) {
    cJSON *accs = cJSON_GetObjectItem(g->json, "accessors"), *a = extra ? cJSON_Parse(extra) : cJSON_CreateObject();
    if (view >= 0) cJSON_AddNumberToObject(a, "bufferView", view);
    cJSON_AddNumberToObject(a, "componentType", component_type);
    cJSON_AddNumberToObject(a, "count", (double)count);
    cJSON_AddStringToObject(a, "type", type);
    cJSON_AddItemToArray(accs, a);
    return cJSON_GetArraySize(accs) - 1;
}

/* Binary data as a view and an accessor in one step. */
static inline int gw_data(gw_doc *g, const void *data, size_t n, int component_type, long long count, const char *type) {
    size_t at = gw_append(g, data, n);
    return gw_accessor(g, gw_view(g, at, n, 0), component_type, count, type, NULL);
}

static inline bool gw_quad(gw_doc *g) {
    memset(g, 0, sizeof *g);
    g->json = cJSON_Parse(
        "{\"asset\": {\"version\": \"2.0\", \"generator\": \"shadelab tests/gltf_writer.h\"}, \"scene\": 0,"
        " \"scenes\": [{\"nodes\": [0, 1]}],"
        " \"nodes\": [{\"name\": \"quad\", \"mesh\": 0}, {\"name\": \"eye\", \"camera\": 0, \"translation\": [0, 0, 3]}],"
        " \"cameras\": [{\"type\": \"perspective\", \"perspective\": {\"yfov\": 0.8, \"znear\": 0.1, \"zfar\": 20}}],"
        " \"meshes\": [{\"name\": \"quad\", \"primitives\": [{\"attributes\": {\"POSITION\": 0, \"NORMAL\": 1, "
        "\"TEXCOORD_0\": 2}, \"indices\": 3, \"material\": 0}]}],"
        " \"materials\": [{\"name\": \"paint\", \"pbrMetallicRoughness\": {\"baseColorFactor\": [0.8, 0.3, 0.2, 1], "
        "\"metallicFactor\": 0}}],"
        " \"animations\": [{\"channels\": [{\"sampler\": 0, \"target\": {\"node\": 0, \"path\": \"translation\"}}],"
        " \"samplers\": [{\"input\": 4, \"output\": 5}]}],"
        " \"buffers\": [{\"byteLength\": 0}], \"bufferViews\": [], \"accessors\": []}");
    if (!g->json) return false;
    const float pos[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, nrm[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const float uv[8] = {0, 1, 1, 1, 1, 0, 0, 0}, times[2] = {0, 1}, moves[6] = {0, 0, 0, 0.5f, 0, 0};
    const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    const uint32_t idx32[6] = {0, 1, 2, 0, 2, 3};
    size_t at = gw_append(g, pos, sizeof pos);
    gw_accessor(g, gw_view(g, at, sizeof pos, 0), 5126, 4, "VEC3", "{\"min\": [-1, -1, 0], \"max\": [1, 1, 0]}");
    gw_data(g, nrm, sizeof nrm, 5126, 4, "VEC3");
    gw_data(g, uv, sizeof uv, 5126, 4, "VEC2");
    gw_data(g, idx, sizeof idx, 5123, 6, "SCALAR");
    at = gw_append(g, times, sizeof times);
    gw_accessor(g, gw_view(g, at, sizeof times, 0), 5126, 2, "SCALAR", "{\"min\": [0], \"max\": [1]}");
    gw_data(g, moves, sizeof moves, 5126, 2, "VEC3");
    gw_data(g, idx32, sizeof idx32, 5125, 6, "SCALAR");
    return true;
}

static inline void gw_u32(buf *b, uint32_t v) {
    unsigned char c[4] = {v & 255, v >> 8 & 255, v >> 16 & 255, v >> 24 & 255};
    put(b, c, 4);
}

static inline char *gw_base64(const unsigned char *d, size_t n, const char *prefix) {
    static const char t[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    size_t lp = strlen(prefix);
    char *o = malloc(lp + 4 * ((n + 2) / 3) + 1), *w = o + lp;
    memcpy(o, prefix, lp);
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

static inline bool gw_write_bytes(const char *path, const void *d, size_t n) {
    FILE *f = fopen(path, "wb");
    bool ok = f && fwrite(d, 1, n, f) == n;
    if (f) ok = fclose(f) == 0 && ok;
    return ok;
}

/* The file's bytes (GLB or .gltf text) into out (the caller frees out->d). */
static inline bool gw_bytes(gw_doc *g, const char *path, int format, buf *out) {
    memset(out, 0, sizeof *out);
    cJSON *buffer = cJSON_GetArrayItem(cJSON_GetObjectItem(g->json, "buffers"), 0);
    if (format != GW_AS_IS) cJSON_DeleteItemFromObject(buffer, "uri");
    if (format == GW_DATA_URI) {
        char *uri = gw_base64(g->bin.d ? g->bin.d : (const unsigned char *)"", g->bin.n, "data:application/octet-stream;base64,");
        cJSON_AddStringToObject(buffer, "uri", uri);
        free(uri);
    } else if (format == GW_EXTERNAL) {
        char bin[4200];
        const char *base = strrchr(path, '/');
        snprintf(bin, sizeof bin, "%s.bin", path);
        if (!gw_write_bytes(bin, g->bin.d ? g->bin.d : (const unsigned char *)"", g->bin.n)) return false;
        snprintf(bin, sizeof bin, "%s.bin", base ? base + 1 : path);
        cJSON_AddStringToObject(buffer, "uri", bin);
    }
    char *text = cJSON_PrintUnformatted(g->json);
    if (!text) return false;
    if (format != GW_GLB) {
        put(out, text, strlen(text));
        free(text);
        return true;
    }
    size_t jn = strlen(text), jpad = (4 - jn % 4) % 4, bpad = (4 - g->bin.n % 4) % 4;
    size_t total = 12 + 8 + jn + jpad + (g->bin.n ? 8 + g->bin.n + bpad : 0);
    put(out, "glTF", 4);
    gw_u32(out, 2);
    gw_u32(out, (uint32_t)total);
    gw_u32(out, (uint32_t)(jn + jpad));
    put(out, "JSON", 4);
    put(out, text, jn);
    put(out, "   ", jpad);
    if (g->bin.n) {
        gw_u32(out, (uint32_t)(g->bin.n + bpad));
        put(out, "BIN\0", 4);
        put(out, g->bin.d, g->bin.n);
        put(out, "\0\0\0", bpad);
    }
    free(text);
    return true;
}

static inline bool gw_write(gw_doc *g, const char *path, int format) {
    buf b;
    bool ok = gw_bytes(g, path, format, &b) && gw_write_bytes(path, b.d, b.n);
    free(b.d);
    return ok;
}
#endif
