/* The glTF document: the file read (a .gltf's JSON, or a .glb per glTF 2.0 §4.4: a 12-byte
 * header "glTF", version 2, length, then chunks of length, type and data, JSON first, BIN
 * optionally second), the JSON parsed with cJSON, buffers loaded on first use, and member access
 * that names the JSON pointer of whatever is wrong. */
#include "log.h"
#include "scene/gltf.h"
#include <shadelab/input.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The most a .gltf's JSON may be (a .glb's is bounded by its format: 4 GiB in all). */
#define GLTF_MAX_JSON_BYTES (256u << 20)

bool gltf_fail(gltf_doc *d, const char *at, const char *fmt, ...) {
    if (d->failed) return false;
    d->failed = true;
    if (!d->err || !d->err_size) return false;
    int n = snprintf(d->err, d->err_size, "%s: %s%s", d->path, at ? at : "", at ? ": " : "");
    va_list ap;
    va_start(ap, fmt);
    if (n >= 0 && (size_t)n < d->err_size) vsnprintf(d->err + n, d->err_size - (size_t)n, fmt, ap);
    va_end(ap);
    return false;
}

void gltf_note(gltf_doc *d, const char *at, const char *fmt, ...) {
    char note[600];
    int n = snprintf(note, sizeof note, "%s%s", at ? at : "", at ? ": " : "");
    va_list ap;
    va_start(ap, fmt);
    if (n >= 0 && (size_t)n < sizeof note) vsnprintf(note + n, sizeof note - (size_t)n, fmt, ap);
    va_end(ap);
    if (strstr(d->notes, note)) return; /* said already (a sampler shared by textures…) */
    size_t u = strlen(d->notes);
    if (d->note_count++ >= GLTF_MAX_NOTES || u + strlen(note) + 3 > sizeof d->notes) return; /* counted */
    snprintf(d->notes + u, sizeof d->notes - u, "%s%s", u ? "; " : "", note);
}

/* ---- reading the file --------------------------------------------------------------------- */

/* The whole regular file, at most max bytes (malloc'd, NUL-terminated). */
static unsigned char *read_whole(gltf_doc *d, const char *path, size_t max, size_t *len) {
    char why[600];
    int fd = sl_open_input_file(path, why, sizeof why);
    if (fd < 0) return gltf_fail(d, NULL, "%s", strncmp(why, path, strlen(path)) ? why : why + strlen(path) + 2), NULL;
    struct stat st;
    unsigned char *data = NULL;
    if (fstat(fd, &st) != 0 || st.st_size < 0 || (unsigned long long)st.st_size > max)
        gltf_fail(d, NULL, "the file is %lld bytes, over the %zu a glTF may have here", (long long)st.st_size, max);
    else if (!(data = malloc((size_t)st.st_size + 1)))
        gltf_fail(d, NULL, "out of memory reading %lld bytes", (long long)st.st_size);
    size_t n = 0;
    while (data && n < (size_t)st.st_size) {
        ssize_t r = read(fd, data + n, (size_t)st.st_size - n);
        if (r <= 0) break;
        n += (size_t)r;
    }
    close(fd);
    if (data && n != (size_t)st.st_size) {
        free(data);
        return gltf_fail(d, NULL, "could not read the whole file (%zu of %lld bytes)", n, (long long)st.st_size), NULL;
    }
    if (data) data[n] = 0;
    *len = n;
    return data;
}

static uint32_t u32le(const unsigned char *p) {
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* A .glb's chunks (§4.4.3): the JSON chunk's text into *json, the BIN chunk into d->bin. */
static bool read_glb(gltf_doc *d, size_t size, const char **json, size_t *json_len) {
    const unsigned char *g = d->glb;
    if (size < 20) return gltf_fail(d, NULL, "a .glb of %zu bytes is shorter than its 12-byte header and first chunk", size);
    if (u32le(g + 4) != 2)
        return gltf_fail(d, NULL, "GLB container version %u; shadelab reads version 2 (glTF 2.0)", u32le(g + 4));
    if (u32le(g + 8) != size)
        return gltf_fail(d, NULL, "the GLB header gives a length of %u bytes, the file has %zu (truncated or padded)",
                         u32le(g + 8), size);
    size_t at = 12;
    for (int chunk = 0; at < size; chunk++) {
        if (size - at < 8) return gltf_fail(d, NULL, "GLB chunk %d at byte %zu: its 8-byte header is cut off", chunk, at);
        uint32_t len = u32le(g + at), type = u32le(g + at + 4);
        if (len > size - at - 8)
            return gltf_fail(d, NULL, "GLB chunk %d at byte %zu: its length %u runs past the end of the file", chunk, at, len);
        if (chunk == 0 && type != 0x4E4F534Au) /* "JSON" */
            return gltf_fail(d, NULL, "the first GLB chunk must be JSON (type 0x4E4F534A), found type 0x%08X", type);
        if (chunk == 0) *json = (const char *)g + at + 8, *json_len = len;
        else if (chunk == 1 && type == 0x004E4942u) d->bin = g + at + 8, d->bin_size = len; /* "BIN\0" */
        /* other chunks: ignored, as the specification asks */
        at += 8 + (size_t)len;
    }
    return true;
}

/* "line L, column C" of a position in text. */
static void where(const char *text, const char *pos, char *out, size_t size) {
    int line = 1, col = 1;
    for (const char *c = text; c < pos && *c; c++) col = *c == '\n' ? (line++, 1) : col + 1;
    snprintf(out, size, "line %d, column %d", line, col);
}

/* asset.version 2.x (and asset.minVersion, if any, at most 2.0). */
static bool check_asset(gltf_doc *d) {
    if (!cJSON_IsObject(d->root)) return gltf_fail(d, NULL, "the glTF JSON must be an object { … }");
    const cJSON *asset;
    const char *version = NULL, *min = NULL;
    if (!gltf_get_object(d, d->root, "", "asset", &asset)) return false;
    if (!asset) return gltf_fail(d, "/asset", "missing: a glTF file must name its version (not a glTF 2.0 file?)");
    if (!gltf_get_string(d, asset, "/asset", "version", &version) ||
        !gltf_get_string(d, asset, "/asset", "minVersion", &min))
        return false;
    if (!version) return gltf_fail(d, "/asset/version", "missing");
    if (strncmp(version, "2.", 2))
        return gltf_fail(d, "/asset/version", "\"%.20s\": shadelab reads glTF 2.x only", version);
    if (min && strcmp(min, "2.0"))
        return gltf_fail(d, "/asset/minVersion", "\"%.20s\": the file needs a newer glTF reader than 2.0", min);
    return true;
}

bool gltf_open(gltf_doc *d, const char *path, char *err, size_t err_size) {
    memset(d, 0, sizeof *d);
    d->path = path, d->err = err, d->err_size = err_size;
    if (err && err_size) err[0] = 0;
    const char *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path;
    char *abs = realpath(path, NULL); /* textures and buffers are named by absolute paths */
    const char *full = abs ? abs : path, *cut = strrchr(full, '/');
    snprintf(d->dir, sizeof d->dir, "%.*s", cut ? (int)(cut - full) : 1, cut ? (cut == full ? "/" : full) : ".");
    free(abs);
    snprintf(d->stem, sizeof d->stem, "%s", base);
    char *dot = strrchr(d->stem, '.');
    if (dot && dot != d->stem) *dot = 0;
    size_t size = 0;
    d->glb = read_whole(d, path, 0xFFFFFFFFu, &size);
    if (!d->glb) return false;
    const char *json = (const char *)d->glb;
    size_t json_len = size;
    if (size >= 4 && !memcmp(d->glb, "glTF", 4)) {
        if (!read_glb(d, size, &json, &json_len)) return false;
    } else if (size > GLTF_MAX_JSON_BYTES) {
        return gltf_fail(d, NULL, "%zu bytes of JSON, over the %u a .gltf may have", size, GLTF_MAX_JSON_BYTES);
    }
    if (json_len >= 3 && !memcmp(json, "\xEF\xBB\xBF", 3)) json += 3, json_len -= 3; /* a BOM: ignored (§3.1) */
    const char *end = NULL;
    d->root = cJSON_ParseWithLengthOpts(json, json_len, &end, false);
    if (!d->root) {
        const char *at = cJSON_GetErrorPtr();
        char pos[64] = "the start";
        if (at && at >= json && at <= json + json_len) where(json, at, pos, sizeof pos);
        return gltf_fail(d, NULL, "invalid JSON at %s (or nested deeper than %d levels)", pos, CJSON_NESTING_LIMIT);
    }
    return check_asset(d);
}

void gltf_close(gltf_doc *d) {
    for (int i = 0; i < d->buffer_count; i++) free(d->buffers[i].owned);
    for (int i = 0; i < d->view_count; i++) free(d->decoded[i]);
    free(d->decoded);
    free(d->buffers);
    cJSON_Delete(d->root);
    free(d->glb);
    d->buffers = NULL, d->root = NULL, d->glb = NULL, d->decoded = NULL;
}

/* ---- members ------------------------------------------------------------------------------ */

int gltf_count(const gltf_doc *d, const char *name) {
    const cJSON *a = cJSON_GetObjectItemCaseSensitive(d->root, name);
    return cJSON_IsArray(a) ? cJSON_GetArraySize(a) : 0;
}

const cJSON *gltf_item(const gltf_doc *d, const char *name, int i) {
    return cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(d->root, name), i);
}

static const char *kind(const cJSON *v) {
    return cJSON_IsNumber(v) ? "a number" : cJSON_IsString(v) ? "a string" : cJSON_IsBool(v) ? "a boolean"
         : cJSON_IsNull(v) ? "null" : cJSON_IsArray(v) ? "an array" : cJSON_IsObject(v) ? "an object" : "invalid";
}

/* The member, or NULL; a type check by the caller. */
static const cJSON *member(const cJSON *obj, const char *key) { return cJSON_GetObjectItemCaseSensitive(obj, key); }

static bool wrong(gltf_doc *d, const char *at, const char *key, const char *want, const cJSON *v) {
    char p[600];
    snprintf(p, sizeof p, "%s/%s", at, key);
    return gltf_fail(d, p, "must be %s, found %s", want, kind(v));
}

bool gltf_get_object(gltf_doc *d, const cJSON *obj, const char *at, const char *key, const cJSON **out) {
    const cJSON *v = member(obj, key);
    *out = NULL;
    if (v && !cJSON_IsObject(v)) return wrong(d, at, key, "an object", v);
    *out = v;
    return true;
}

bool gltf_get_array(gltf_doc *d, const cJSON *obj, const char *at, const char *key, const cJSON **out) {
    const cJSON *v = member(obj, key);
    *out = NULL;
    if (v && !cJSON_IsArray(v)) return wrong(d, at, key, "an array", v);
    *out = v;
    return true;
}

bool gltf_get_string(gltf_doc *d, const cJSON *obj, const char *at, const char *key, const char **out) {
    const cJSON *v = member(obj, key);
    if (v && !cJSON_IsString(v)) return wrong(d, at, key, "a string", v);
    if (v) *out = v->valuestring;
    return true;
}

bool gltf_get_bool(gltf_doc *d, const cJSON *obj, const char *at, const char *key, bool *out) {
    const cJSON *v = member(obj, key);
    if (v && !cJSON_IsBool(v)) return wrong(d, at, key, "true or false", v);
    if (v) *out = cJSON_IsTrue(v);
    return true;
}

bool gltf_get_int(gltf_doc *d, const cJSON *obj, const char *at, const char *key, long long min, long long max,
                  long long *out) {
    const cJSON *v = member(obj, key);
    if (!v) return true;
    if (!cJSON_IsNumber(v)) return wrong(d, at, key, "an integer", v);
    double x = v->valuedouble;
    char p[600];
    snprintf(p, sizeof p, "%s/%s", at, key);
    if (!isfinite(x) || x != floor(x)) return gltf_fail(d, p, "must be an integer, found %g", x);
    if (x < (double)min || x > (double)max) return gltf_fail(d, p, "%.17g is out of range [%lld, %lld]", x, min, max);
    *out = (long long)x;
    return true;
}

bool gltf_get_index(gltf_doc *d, const cJSON *obj, const char *at, const char *key, const char *array,
                    bool required, int *out) {
    *out = -1;
    long long i = -1;
    if (!gltf_get_int(d, obj, at, key, 0, 0x7FFFFFFF, &i)) return false;
    char p[600];
    snprintf(p, sizeof p, "%s/%s", at, key);
    if (i < 0) return required ? gltf_fail(d, p, "missing (required)") : true;
    int n = gltf_count(d, array);
    if (i >= n) return gltf_fail(d, p, "%lld is not an index of /%s (%d element%s)", i, array, n, n == 1 ? "" : "s");
    *out = (int)i;
    return true;
}

bool gltf_get_number(gltf_doc *d, const cJSON *obj, const char *at, const char *key, double *out) {
    const cJSON *v = member(obj, key);
    if (!v) return true;
    if (!cJSON_IsNumber(v)) return wrong(d, at, key, "a number", v);
    char p[600];
    snprintf(p, sizeof p, "%s/%s", at, key);
    if (!isfinite(v->valuedouble)) return gltf_fail(d, p, "not a finite number (overflows a double)");
    *out = v->valuedouble;
    return true;
}

bool gltf_get_numbers(gltf_doc *d, const cJSON *obj, const char *at, const char *key, int n, float *out,
                      bool *present) {
    const cJSON *v = member(obj, key), *e;
    if (present) *present = v != NULL;
    if (!v) return true;
    char p[600];
    snprintf(p, sizeof p, "%s/%s", at, key);
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != n) {
        if (cJSON_IsArray(v)) return gltf_fail(d, p, "must hold %d numbers, found %d", n, cJSON_GetArraySize(v));
        return wrong(d, at, key, "an array of numbers", v);
    }
    int i = 0;
    cJSON_ArrayForEach(e, v) {
        if (!cJSON_IsNumber(e)) return gltf_fail(d, p, "element %d must be a number, found %s", i, kind(e));
        if (!isfinite(e->valuedouble) || fabs(e->valuedouble) > 3.4e38)
            return gltf_fail(d, p, "element %d (%g) is not a finite 32-bit float", i, e->valuedouble);
        out[i++] = (float)e->valuedouble;
    }
    return true;
}

/* ---- buffers ------------------------------------------------------------------------------ */

static int b64(int c) {
    return c >= 'A' && c <= 'Z' ? c - 'A' : c >= 'a' && c <= 'z' ? c - 'a' + 26 : c >= '0' && c <= '9' ? c - '0' + 52
         : c == '+' || c == '-' ? 62 : c == '/' || c == '_' ? 63 : -1;
}

unsigned char *gltf_data_uri(const char *uri, size_t *size) {
    const char *comma = strchr(uri, ',');
    if (strncmp(uri, "data:", 5) || !comma || comma - uri < 12 || memcmp(comma - 7, ";base64", 7)) return NULL;
    size_t l = strlen(comma + 1);
    unsigned char *out = malloc(l / 4 * 3 + 3);
    size_t n = 0;
    unsigned acc = 0;
    int bits = 0;
    for (const char *c = comma + 1; out && *c && *c != '='; c++) {
        int v = b64((unsigned char)*c);
        if (v < 0) {
            free(out);
            return NULL;
        }
        acc = (acc << 6 | (unsigned)v) & 0xFFFFFF, bits += 6;
        if (bits >= 8) out[n++] = (unsigned char)(acc >> (bits -= 8));
    }
    *size = n;
    return out;
}

static int hex(int c) { return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1; }

bool gltf_uri_path(const gltf_doc *d, const char *uri, char *out, size_t size) {
    if (strstr(uri, "://") || !uri[0]) return false; /* relative references only (§3.8.4.1) */
    char decoded[4096];
    size_t n = 0;
    for (const char *c = uri; *c; c++) {
        int h1 = *c == '%' ? hex(c[1]) : -1, h2 = h1 >= 0 ? hex(c[2]) : -1;
        if (n + 1 >= sizeof decoded || (h1 == 0 && h2 == 0)) return false; /* too long, or %00 */
        if (h2 >= 0) decoded[n++] = (char)(h1 << 4 | h2), c += 2;
        else decoded[n++] = *c;
    }
    decoded[n] = 0;
    int w = decoded[0] == '/' ? snprintf(out, size, "%s", decoded) : snprintf(out, size, "%s/%s", d->dir, decoded);
    return w > 0 && (size_t)w < size;
}

/* An external buffer file: exactly `want` bytes of it (the file may be longer). */
static unsigned char *read_buffer_file(gltf_doc *d, const char *at, const char *file, size_t want) {
    char why[600];
    int fd = sl_open_input_file(file, why, sizeof why);
    if (fd < 0) return gltf_fail(d, at, "%s", why), NULL;
    struct stat st;
    unsigned char *out = NULL;
    if (fstat(fd, &st) != 0 || (unsigned long long)st.st_size < want)
        gltf_fail(d, at, "%s has %lld bytes, fewer than the buffer's byteLength %zu", file, (long long)st.st_size, want);
    else if (!(out = malloc(want)))
        gltf_fail(d, at, "out of memory for %zu bytes", want);
    size_t n = 0;
    while (out && n < want) {
        ssize_t r = read(fd, out + n, want - n);
        if (r <= 0) break;
        n += (size_t)r;
    }
    close(fd);
    if (out && n < want) {
        free(out);
        return gltf_fail(d, at, "could not read %s (%zu of %zu bytes)", file, n, want), NULL;
    }
    return out;
}

/* Loads buffer i's bytes into b (§3.6.1): no uri = the GLB's BIN chunk (buffer 0 only). */
static bool load_buffer(gltf_doc *d, int i, gltf_buffer *b) {
    char at[64];
    snprintf(at, sizeof at, "/buffers/%d", i);
    const cJSON *buf = gltf_item(d, "buffers", i);
    long long len = -1;
    const char *uri = NULL;
    if (!cJSON_IsObject(buf)) return gltf_fail(d, at, "must be an object");
    if (!gltf_get_int(d, buf, at, "byteLength", 1, 1LL << 40, &len) || !gltf_get_string(d, buf, at, "uri", &uri))
        return false;
    if (len < 0) return gltf_fail(d, at, "byteLength is missing (required)");
    b->size = (size_t)len;
    char p[80];
    snprintf(p, sizeof p, "%s/uri", at);
    if (!uri) {
        if (!d->bin) return gltf_fail(d, at, "has no uri and the file has no GLB BIN chunk to refer to%s",
                                  cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(buf, "extensions"),
                                                                   "EXT_meshopt_compression")
                                      ? " (a meshopt fallback buffer, read by a bufferView without the extension)" : "");
        if (i != 0) return gltf_fail(d, at, "has no uri, which only buffer 0 of a .glb may (its BIN chunk)");
        if (d->bin_size < b->size)
            return gltf_fail(d, at, "byteLength %zu is more than the BIN chunk's %zu bytes", b->size, d->bin_size);
        b->data = d->bin;
        return true;
    }
    if (!strncmp(uri, "data:", 5)) {
        size_t n = 0;
        b->owned = gltf_data_uri(uri, &n);
        if (!b->owned) return gltf_fail(d, p, "not a base64 data: URI (or out of memory)");
        if (n < b->size) return gltf_fail(d, p, "decodes to %zu bytes, fewer than byteLength %zu", n, b->size);
    } else {
        char file[4600];
        if (!gltf_uri_path(d, uri, file, sizeof file))
            return gltf_fail(d, p, "\"%.200s\" is not a relative file reference shadelab reads", uri);
        if (!(b->owned = read_buffer_file(d, p, file, b->size))) return false;
    }
    b->data = b->owned;
    return true;
}

const gltf_buffer *gltf_buffer_at(gltf_doc *d, int index) {
    int n = gltf_count(d, "buffers");
    if (index < 0 || index >= n) return gltf_fail(d, NULL, "buffer %d does not exist", index), NULL;
    if (!d->buffers) {
        d->buffers = calloc((size_t)n, sizeof *d->buffers);
        if (!d->buffers) return gltf_fail(d, NULL, "out of memory"), NULL;
        d->buffer_count = n;
    }
    gltf_buffer *b = &d->buffers[index];
    if (!b->tried) {
        b->tried = true;
        if (!load_buffer(d, index, b)) {
            free(b->owned);
            b->owned = NULL, b->data = NULL;
        }
    }
    if (!b->data) {
        if (!d->failed) gltf_fail(d, NULL, "buffer %d could not be read", index);
        return NULL;
    }
    return b;
}
