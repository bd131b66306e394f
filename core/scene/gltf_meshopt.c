/* EXT_meshopt_compression: a bufferView whose bytes are meshoptimizer's encoding of `count`
 * elements of `byteStride` bytes (mode ATTRIBUTES: meshopt_decodeVertexBuffer, then the filter
 * OCTAHEDRAL, QUATERNION or EXPONENTIAL; TRIANGLES: meshopt_decodeIndexBuffer; INDICES:
 * meshopt_decodeIndexSequence), read from the extension's buffer range; the view's own buffer may
 * be a fallback that holds nothing. Decoded once per view, checked as the extension's
 * specification says (the strides each mode allows, count × byteStride equal to the view's
 * byteLength); a decoder refusing the data is an error naming the view. */
#include "scene/gltf.h"

#include <meshoptimizer.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The extension's members, checked; the compressed bytes in *src. */
static bool read_ext(gltf_doc *d, const cJSON *ext, const char *at, long long *count, long long *stride, const char **mode,
                     const char **filter, const unsigned char **src, size_t *src_len) {
    int buffer = -1;
    long long offset = 0, length = -1;
    if (!cJSON_IsObject(ext)) return gltf_fail(d, at, "must be an object");
    if (!gltf_get_index(d, ext, at, "buffer", "buffers", true, &buffer) || !gltf_get_int(d, ext, at, "byteOffset", 0, 1LL << 40, &offset) ||
        !gltf_get_int(d, ext, at, "byteLength", 1, 1LL << 40, &length) || !gltf_get_int(d, ext, at, "byteStride", 1, 256, stride) ||
        !gltf_get_int(d, ext, at, "count", 1, 1LL << 30, count) || !gltf_get_string(d, ext, at, "mode", mode) ||
        !gltf_get_string(d, ext, at, "filter", filter))
        return false;
    if (length < 0 || *stride < 0 || *count < 0 || !*mode) return gltf_fail(d, at, "byteLength, byteStride, count and mode are required");
    const gltf_buffer *b = gltf_buffer_at(d, buffer);
    if (!b) return false;
    if ((unsigned long long)offset + (unsigned long long)length > b->size)
        return gltf_fail(d, at, "bytes %lld to %lld lie past the end of buffer %d (%zu bytes)", offset, offset + length, buffer, b->size);
    *src = b->data + offset, *src_len = (size_t)length;
    return true;
}

/* Decodes into out (count × stride bytes); 0 when the decoder accepted the data. */
static int decode(const char *mode, const char *filter, unsigned char *out, size_t count, size_t stride,
                  const unsigned char *src, size_t len) {
    if (!strcmp(mode, "TRIANGLES")) return meshopt_decodeIndexBuffer(out, count, stride, src, len);
    if (!strcmp(mode, "INDICES")) return meshopt_decodeIndexSequence(out, count, stride, src, len);
    int rc = meshopt_decodeVertexBuffer(out, count, stride, src, len);
    if (rc == 0 && !strcmp(filter, "OCTAHEDRAL")) meshopt_decodeFilterOct(out, count, stride);
    if (rc == 0 && !strcmp(filter, "QUATERNION")) meshopt_decodeFilterQuat(out, count, stride);
    if (rc == 0 && !strcmp(filter, "EXPONENTIAL")) meshopt_decodeFilterExp(out, count, stride);
    return rc;
}

/* What the extension's specification allows of mode, filter and stride together; NULL if fine. */
static const char *invalid(const char *mode, const char *filter, long long count, long long stride) {
    bool attributes = !strcmp(mode, "ATTRIBUTES"), triangles = !strcmp(mode, "TRIANGLES");
    if (!attributes && !triangles && strcmp(mode, "INDICES")) return "mode is not ATTRIBUTES, TRIANGLES or INDICES";
    if (strcmp(filter, "NONE") && !attributes) return "a filter is only for mode ATTRIBUTES";
    if (attributes && stride % 4) return "byteStride of ATTRIBUTES is not a multiple of 4";
    if (!attributes && stride != 2 && stride != 4) return "byteStride of indices is not 2 or 4";
    if (triangles && count % 3) return "count of TRIANGLES is not a multiple of 3";
    if (!strcmp(filter, "OCTAHEDRAL") && stride != 4 && stride != 8) return "OCTAHEDRAL needs byteStride 4 or 8";
    if (!strcmp(filter, "QUATERNION") && stride != 8) return "QUATERNION needs byteStride 8";
    if (strcmp(filter, "NONE") && strcmp(filter, "OCTAHEDRAL") && strcmp(filter, "QUATERNION") && strcmp(filter, "EXPONENTIAL"))
        return "filter is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL";
    return NULL;
}

bool gltf_meshopt_view(gltf_doc *d, int index, const cJSON *ext, const unsigned char **data, size_t *len,
                       size_t *view_stride_out) {
    char at[96];
    snprintf(at, sizeof at, "/bufferViews/%d/extensions/EXT_meshopt_compression", index);
    if (!d->decoded) {
        d->view_count = gltf_count(d, "bufferViews");
        if (!(d->decoded = calloc((size_t)d->view_count + 1, sizeof *d->decoded))) return gltf_fail(d, NULL, "out of memory");
    }
    long long count = -1, view_len = -1;
    const char *mode = NULL, *filter = "NONE", *why;
    const unsigned char *src = NULL;
    size_t src_len = 0;
    long long stride = -1; /* the extension's byteStride */
    if (!read_ext(d, ext, at, &count, &stride, &mode, &filter, &src, &src_len)) return false;
    if ((why = invalid(mode, filter, count, stride))) return gltf_fail(d, at, "%s", why);
    char vp[48];
    long long view_stride = 0;
    snprintf(vp, sizeof vp, "/bufferViews/%d", index);
    gltf_get_int(d, gltf_item(d, "bufferViews", index), vp, "byteLength", 1, 1LL << 40, &view_len);
    gltf_get_int(d, gltf_item(d, "bufferViews", index), vp, "byteStride", 4, 252, &view_stride);
    bool attributes = !strcmp(mode, "ATTRIBUTES");
    if (attributes && view_stride && view_stride != stride)
        return gltf_fail(d, at, "byteStride %lld differs from the bufferView's %lld", stride, view_stride);
    *view_stride_out = attributes ? (size_t)stride : 0;
    if (count * stride > GLTF_MAX_DECODED_BYTES)
        return gltf_fail(d, at, "%lld decoded bytes, over the %lld shadelab decodes per bufferView", count * stride,
                         (long long)GLTF_MAX_DECODED_BYTES);
    if (count * stride != view_len)
        return gltf_fail(d, at, "count %lld × byteStride %lld is not the bufferView's byteLength %lld", count, stride, view_len);
    if (!d->decoded[index]) {
        unsigned char *out = malloc((size_t)(count * stride));
        if (!out) return gltf_fail(d, at, "out of memory for %lld bytes", count * stride);
        int rc = decode(mode, filter, out, (size_t)count, (size_t)stride, src, src_len);
        if (rc) {
            free(out);
            return gltf_fail(d, at, "the %s data does not decode (meshoptimizer error %d)", mode, rc);
        }
        d->decoded[index] = out;
    }
    *data = d->decoded[index], *len = (size_t)view_len;
    return true;
}
