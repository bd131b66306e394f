/* glTF accessors read under the specification's rules (glTF 2.0 §3.6.2, "Accessors"):
 *  - a bufferView lies inside its buffer; byteStride is 4..252 and a multiple of 4;
 *  - an accessor's byteOffset, and its bufferView's offset plus it, are multiples of the
 *    component size; its last element ends inside the bufferView (offset + stride·(count − 1) +
 *    element size ≤ byteLength), a stride is at least the element size; matrix columns start on
 *    4-byte boundaries (§3.6.2.4);
 *  - normalized is only for 8- and 16-bit integers, read as §3.11 says (c / 255, max(c / 127, −1)…);
 *  - an accessor without a bufferView is zeros; a sparse one (§3.6.2.3) then has `count` values
 *    substituted at strictly increasing indices below its count.
 * Every check names the accessor's JSON pointer and, for the use that reads it, the referring
 * member. Sizes are computed in 64 bits after bounding count, so no product overflows. */
#include "scene/gltf.h"

#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

typedef struct accessor {
    char at[48];               /* "/accessors/7" */
    int count, comps, rows, ctype, csize;
    bool normalized;
    size_t elem, stride, column; /* element size, distance between elements, between matrix columns */
    const unsigned char *data; /* the first element, or NULL (all zeros) */
    const cJSON *sparse;
} accessor;

static int component_size(long long ct) {
    return ct == GLTF_BYTE || ct == GLTF_UNSIGNED_BYTE ? 1 : ct == GLTF_SHORT || ct == GLTF_UNSIGNED_SHORT ? 2
         : ct == GLTF_UNSIGNED_INT || ct == GLTF_FLOAT ? 4 : 0;
}

/* components and rows (a matrix's column height; 1 per component otherwise) of an accessor type */
static int type_components(const char *t, int *rows) {
    static const struct { const char *name; int comps, rows; } types[] = {
        {"SCALAR", 1, 1}, {"VEC2", 2, 2}, {"VEC3", 3, 3}, {"VEC4", 4, 4}, {"MAT2", 4, 2}, {"MAT3", 9, 3}, {"MAT4", 16, 4}};
    for (size_t i = 0; t && i < sizeof types / sizeof *types; i++)
        if (!strcmp(t, types[i].name)) return *rows = types[i].rows, types[i].comps;
    return 0;
}

/* bufferView `i`'s bytes inside its buffer, and its byteStride (0: not given). */
bool gltf_buffer_view(gltf_doc *d, int i, const unsigned char **data, size_t *len, size_t *stride) {
    char at[48];
    snprintf(at, sizeof at, "/bufferViews/%d", i);
    const cJSON *v = gltf_item(d, "bufferViews", i);
    int buffer = -1;
    long long offset = 0, length = -1, st = 0;
    if (!cJSON_IsObject(v)) return gltf_fail(d, at, "must be an object");
    if (!gltf_get_index(d, v, at, "buffer", "buffers", true, &buffer) ||
        !gltf_get_int(d, v, at, "byteOffset", 0, 1LL << 40, &offset) ||
        !gltf_get_int(d, v, at, "byteLength", 1, 1LL << 40, &length) ||
        !gltf_get_int(d, v, at, "byteStride", 4, 252, &st))
        return false;
    if (length < 0) return gltf_fail(d, at, "byteLength is missing (required)");
    if (st % 4) return gltf_fail(d, at, "byteStride %lld is not a multiple of 4", st);
    const cJSON *ext = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(v, "extensions"),
                                                        "EXT_meshopt_compression");
    if (ext) /* the bytes are the extension's, decoded; the view's own buffer is a fallback */
        return gltf_meshopt_view(d, i, ext, data, len, stride);
    const gltf_buffer *b = gltf_buffer_at(d, buffer);
    if (!b) return false;
    if ((unsigned long long)offset + (unsigned long long)length > b->size)
        return gltf_fail(d, at, "bytes %lld to %lld lie past the end of buffer %d (%zu bytes)", offset,
                         offset + length, buffer, b->size);
    *data = b->data + offset, *len = (size_t)length, *stride = (size_t)st;
    return true;
}

/* The accessor's layout, checked against its bufferView (§3.6.2.4). */
static bool load_accessor(gltf_doc *d, int index, accessor *a) {
    memset(a, 0, sizeof *a);
    snprintf(a->at, sizeof a->at, "/accessors/%d", index);
    const cJSON *acc = gltf_item(d, "accessors", index);
    if (!cJSON_IsObject(acc)) return gltf_fail(d, a->at, "must be an object");
    long long ct = -1, count = -1, offset = 0;
    int view = -1;
    const char *type = NULL;
    if (!gltf_get_index(d, acc, a->at, "bufferView", "bufferViews", false, &view) ||
        !gltf_get_int(d, acc, a->at, "byteOffset", 0, 1LL << 40, &offset) ||
        !gltf_get_int(d, acc, a->at, "componentType", 0, 1 << 20, &ct) ||
        !gltf_get_bool(d, acc, a->at, "normalized", &a->normalized) ||
        !gltf_get_int(d, acc, a->at, "count", 1, 0x7FFFFFFF, &count) || !gltf_get_string(d, acc, a->at, "type", &type) ||
        !gltf_get_object(d, acc, a->at, "sparse", &a->sparse))
        return false;
    if (!(a->csize = component_size(ct)))
        return gltf_fail(d, a->at, "componentType %lld is not one of 5120-5123, 5125, 5126%s", ct, ct < 0 ? " (missing)" : "");
    if (!(a->comps = type_components(type, &a->rows)))
        return gltf_fail(d, a->at, "type \"%.20s\" is not SCALAR, VEC2-4 or MAT2-4", type ? type : "(missing)");
    if (count < 0) return gltf_fail(d, a->at, "count is missing (required)");
    if (a->normalized && (ct == GLTF_FLOAT || ct == GLTF_UNSIGNED_INT))
        return gltf_fail(d, a->at, "normalized is only for 8- and 16-bit integer components (componentType %lld)", ct);
    a->ctype = (int)ct, a->count = (int)count;
    bool matrix = a->rows != a->comps && a->comps > 1;
    a->column = matrix ? ((size_t)(a->rows * a->csize) + 3) / 4 * 4 : (size_t)(a->rows * a->csize);
    a->elem = matrix ? a->column * (size_t)(a->comps / a->rows) : (size_t)(a->comps * a->csize);
    if (offset % a->csize) return gltf_fail(d, a->at, "byteOffset %lld is not a multiple of the component size %d", offset, a->csize);
    if (view < 0) {
        if (offset) return gltf_fail(d, a->at, "byteOffset without a bufferView");
        if (count > GLTF_MAX_ZERO_ELEMENTS)
            return gltf_fail(d, a->at, "count %lld without a bufferView is over the %d shadelab allows", count, GLTF_MAX_ZERO_ELEMENTS);
        return true;
    }
    const unsigned char *bytes;
    size_t len, stride;
    if (!gltf_buffer_view(d, view, &bytes, &len, &stride)) return false;
    a->stride = stride ? stride : a->elem;
    if (stride && stride < a->elem)
        return gltf_fail(d, a->at, "bufferView %d's byteStride %zu is less than the element size %zu", view, stride, a->elem);
    unsigned long long view_offset = 0;
    const cJSON *bv = gltf_item(d, "bufferViews", view), *vo = cJSON_GetObjectItemCaseSensitive(bv, "byteOffset");
    if (cJSON_IsNumber(vo)) view_offset = (unsigned long long)vo->valuedouble;
    if ((view_offset + (unsigned long long)offset) % (unsigned long long)a->csize)
        return gltf_fail(d, a->at, "bufferView %d's byteOffset %llu plus the accessor's %lld is not a multiple of the "
                         "component size %d", view, view_offset, offset, a->csize);
    unsigned long long end = (unsigned long long)offset + a->stride * (unsigned long long)(count - 1) + a->elem;
    if (end > len)
        return gltf_fail(d, a->at, "%lld elements of %zu bytes every %zu bytes from byteOffset %lld need %llu bytes; "
                         "bufferView %d has %zu", count, a->elem, a->stride, offset, end, view, len);
    a->data = bytes + offset;
    return true;
}

/* Component c of the element at p, as a float (normalized integers per §3.11). */
static float component(const accessor *a, const unsigned char *p, int c) {
    p += (size_t)(c / a->rows) * a->column + (size_t)(c % a->rows * a->csize);
    switch (a->ctype) {
    case GLTF_FLOAT: {
        uint32_t u = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
        float f;
        memcpy(&f, &u, 4);
        return f;
    }
    case GLTF_UNSIGNED_INT: return (float)((uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24);
    case GLTF_BYTE: return a->normalized ? fmaxf((signed char)p[0] / 127.0f, -1.0f) : (float)(signed char)p[0];
    case GLTF_UNSIGNED_BYTE: return a->normalized ? p[0] / 255.0f : (float)p[0];
    case GLTF_SHORT: {
        int16_t s = (int16_t)(uint16_t)(p[0] | p[1] << 8);
        return a->normalized ? fmaxf(s / 32767.0f, -1.0f) : (float)s;
    }
    default: {
        uint16_t u = (uint16_t)(p[0] | p[1] << 8);
        return a->normalized ? u / 65535.0f : (float)u;
    }
    }
}

static uint32_t unsigned_at(const unsigned char *p, int size) {
    return size == 1 ? p[0] : size == 2 ? (uint32_t)(p[0] | p[1] << 8)
         : (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static unsigned format_bit(const accessor *a) {
    switch (a->ctype) {
    case GLTF_FLOAT: return GLTF_F32;
    case GLTF_BYTE: return a->normalized ? GLTF_I8N : GLTF_I8;
    case GLTF_UNSIGNED_BYTE: return a->normalized ? GLTF_U8N : GLTF_U8;
    case GLTF_SHORT: return a->normalized ? GLTF_I16N : GLTF_I16;
    case GLTF_UNSIGNED_SHORT: return a->normalized ? GLTF_U16N : GLTF_U16;
    default: return 0;
    }
}

static void format_names(unsigned allowed, char *out, size_t size) {
    static const char *const names[] = {"float", "byte normalized", "unsigned byte normalized", "short normalized",
                                        "unsigned short normalized", "byte", "unsigned byte", "short", "unsigned short"};
    size_t u = 0;
    out[0] = 0;
    for (unsigned b = 0; b < sizeof names / sizeof *names; b++)
        if (allowed & (1u << b)) u += snprintf(out + u, u < size ? size - u : 0, "%s%s", u ? ", " : "", names[b]);
}

/* The sparse part's indices and values views (§3.6.2.3), checked; fills idx/values/isize. */
static bool sparse_views(gltf_doc *d, const accessor *a, int *count, const unsigned char **idx, int *isize,
                         const unsigned char **values) {
    char at[80], ai[96], av[96];
    snprintf(at, sizeof at, "%s/sparse", a->at);
    snprintf(ai, sizeof ai, "%s/indices", at);
    snprintf(av, sizeof av, "%s/values", at);
    const cJSON *in, *va;
    long long n = -1, ict = -1, ioff = 0, voff = 0;
    int iview = -1, vview = -1;
    if (!gltf_get_int(d, a->sparse, at, "count", 1, a->count, &n) || !gltf_get_object(d, a->sparse, at, "indices", &in) ||
        !gltf_get_object(d, a->sparse, at, "values", &va))
        return false;
    if (n < 0 || !in || !va) return gltf_fail(d, at, "count, indices and values are required");
    if (!gltf_get_index(d, in, ai, "bufferView", "bufferViews", true, &iview) ||
        !gltf_get_int(d, in, ai, "byteOffset", 0, 1LL << 40, &ioff) || !gltf_get_int(d, in, ai, "componentType", 0, 1 << 20, &ict) ||
        !gltf_get_index(d, va, av, "bufferView", "bufferViews", true, &vview) ||
        !gltf_get_int(d, va, av, "byteOffset", 0, 1LL << 40, &voff))
        return false;
    if (ict != GLTF_UNSIGNED_BYTE && ict != GLTF_UNSIGNED_SHORT && ict != GLTF_UNSIGNED_INT)
        return gltf_fail(d, ai, "componentType %lld is not 5121, 5123 or 5125", ict);
    *isize = component_size(ict);
    const unsigned char *ib, *vb;
    size_t il, vl, is, vs;
    if (!gltf_buffer_view(d, iview, &ib, &il, &is) || !gltf_buffer_view(d, vview, &vb, &vl, &vs)) return false;
    if (is || vs) return gltf_fail(d, at, "the sparse indices' and values' bufferViews must not have a byteStride");
    if (ioff % *isize || voff % a->csize) return gltf_fail(d, at, "a byteOffset is not a multiple of its component size");
    if ((unsigned long long)ioff + (unsigned long long)n * (unsigned)*isize > il)
        return gltf_fail(d, ai, "%lld indices from byteOffset %lld run past bufferView %d (%zu bytes)", n, ioff, iview, il);
    if ((unsigned long long)voff + (unsigned long long)n * a->elem > vl)
        return gltf_fail(d, av, "%lld values from byteOffset %lld run past bufferView %d (%zu bytes)", n, voff, vview, vl);
    *count = (int)n, *idx = ib + ioff, *values = vb + voff;
    return true;
}

/* Substitutes the sparse values into fout (count × comps floats) or uout (count indices). */
static bool apply_sparse(gltf_doc *d, const accessor *a, float *fout, uint32_t *uout) {
    int n = 0, isize = 1;
    const unsigned char *idx = NULL, *values = NULL;
    if (!sparse_views(d, a, &n, &idx, &isize, &values)) return false;
    long long last = -1;
    for (int k = 0; k < n; k++) {
        long long i = unsigned_at(idx + (size_t)k * (size_t)isize, isize);
        if (i <= last || i >= a->count) {
            char at[96];
            snprintf(at, sizeof at, "%s/sparse/indices", a->at);
            return gltf_fail(d, at, "index %d is %lld: sparse indices must increase strictly and stay below count %d",
                             k, i, a->count);
        }
        last = i;
        const unsigned char *p = values + (size_t)k * a->elem;
        if (uout) uout[i] = unsigned_at(p, a->csize);
        for (int c = 0; fout && c < a->comps; c++) fout[i * a->comps + c] = component(a, p, c);
    }
    return true;
}

float *gltf_read_floats(gltf_doc *d, int index, const char *type, unsigned allowed, const char *use, int *count) {
    accessor a;
    if (!load_accessor(d, index, &a)) return NULL;
    int rows;
    if (a.comps != type_components(type, &rows) || rows != a.rows) {
        const cJSON *t = cJSON_GetObjectItemCaseSensitive(gltf_item(d, "accessors", index), "type");
        return gltf_fail(d, a.at, "type %s, but %s needs %s", t->valuestring, use, type), NULL;
    }
    if (!(format_bit(&a) & allowed)) {
        char names[300];
        format_names(allowed, names, sizeof names);
        return gltf_fail(d, a.at, "componentType %d%s is not allowed for %s (allowed: %s)", a.ctype,
                         a.normalized ? " normalized" : "", use, names), NULL;
    }
    float *out = calloc((size_t)a.count * (size_t)a.comps, sizeof(float));
    if (!out) return gltf_fail(d, a.at, "out of memory for %d elements", a.count), NULL;
    for (int i = 0; a.data && i < a.count; i++)
        for (int c = 0; c < a.comps; c++) out[(size_t)i * (size_t)a.comps + (size_t)c] = component(&a, a.data + (size_t)i * a.stride, c);
    if (a.sparse && !apply_sparse(d, &a, out, NULL)) {
        free(out);
        return NULL;
    }
    *count = a.count;
    return out;
}

uint32_t *gltf_read_indices(gltf_doc *d, int index, const char *use, int *count) {
    accessor a;
    if (!load_accessor(d, index, &a)) return NULL;
    if (a.comps != 1 || a.normalized ||
        (a.ctype != GLTF_UNSIGNED_BYTE && a.ctype != GLTF_UNSIGNED_SHORT && a.ctype != GLTF_UNSIGNED_INT))
        return gltf_fail(d, a.at, "%s needs a SCALAR accessor of unsigned byte, short or int, not normalized", use), NULL;
    if (a.data && a.stride != a.elem)
        return gltf_fail(d, a.at, "%s: index data must be tightly packed (byteStride %zu)", use, a.stride), NULL;
    uint32_t *out = calloc((size_t)a.count, sizeof(uint32_t));
    if (!out) return gltf_fail(d, a.at, "out of memory for %d indices", a.count), NULL;
    for (int i = 0; a.data && i < a.count; i++) out[i] = unsigned_at(a.data + (size_t)i * a.stride, a.csize);
    if (a.sparse && !apply_sparse(d, &a, NULL, out)) {
        free(out);
        return NULL;
    }
    *count = a.count;
    return out;
}

int gltf_accessor_count(gltf_doc *d, int index) {
    accessor a;
    return load_accessor(d, index, &a) ? a.count : -1;
}
