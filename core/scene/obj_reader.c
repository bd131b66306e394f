/* The project's own Wavefront OBJ reader (issue 14): sl_scene_import_file hands it every .obj,
 * assimp keeps every other format.
 *
 * Why: assimp 5.2's OBJ reader expands every face corner into a vertex of its own, keeps the
 * whole file's faces as small heap objects and joins identical vertices again afterwards; a
 * 10 M-triangle OBJ took 737.9 s and 5.89 GB (docs/stability.md). This reader streams the file
 * once, in chunks, and joins vertices as it goes, so its memory is the output mesh plus the
 * file's v/vt/vn lists and one hash table, and its time is linear in the file.
 *
 * What it makes is what the assimp import made (tests/test_obj_reader.c compares the two on
 * every OBJ among the test data and assimp's own test models): under the parent a node named
 * after the file, one child node per object ("o", or a change of "g" group), and per object one
 * mesh per run of faces with the same "usemtl" material, named like assimp's (the object's name,
 * or the material's when a usemtl splits the object); vertices are the distinct (position, UV,
 * normal) values in the order their first corner appears (assimp's JoinIdenticalVertices, exact
 * equality with −0 = +0 here); materials from the "mtllib" files, published as the same
 * standard inputs (base_color from Kd, default 0.6 grey; opacity from d or 1 − Tr; textures
 * map_Kd, norm, map_Ke, map_Pr; metallic/roughness from Pm/Pr). Faces are fan-triangulated
 * (v0, vi, vi+1): the same triangle count as assimp's ear clipping and the same vertices; a
 * concave polygon's triangles can differ.
 *
 * Hostile input: every refusal names the file, the line and the cause. A logical line is at
 * most SL_OBJ_MAX_LINE bytes ("\" continuations joined), the file at most SL_OBJ_MAX_FILE_BYTES,
 * each of the v/vt/vn lists at most SL_OBJ_MAX_ELEMENTS, the triangles of a file at most
 * SL_IMPORT_MAX_TRIANGLES, the vertices of one mesh at most 2^26 (sl_mesh_alloc's limit). A
 * number that is not one, or not finite (nan, inf, 1e39 as a float), a missing coordinate, an
 * index of 0, one beyond the vertices defined so far (forward references included) or past
 * ±2^31, and a NUL byte (binary data, UTF-16 text) are errors; statements the reader does not
 * know are ignored with one warning that counts them; points and lines ("p", "l", faces of one
 * or two corners) are not drawn, said once. Negative indices count back from the last vertex
 * defined (OBJ's relative indices). */
#include "log.h"
#include "scene/scene.h"
#include <shadelab/input.h>

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define OBJ_CHUNK (1u << 20)
#define OBJ_MAX_MESH_VERTICES (1u << 26)
#define MTL_MAX_FILE_BYTES (16u << 20)

/* ---- buffered line reader ----------------------------------------------------------------- */

typedef struct line_reader {
    const char *path;
    int fd;
    char *buf;           /* OBJ_CHUNK + SL_OBJ_MAX_LINE bytes (a small file: its size + 8 KiB) */
    size_t cap, start, end;
    bool eof;
    unsigned long long read_bytes, max_bytes;
    long line;           /* 1-based number of the last physical line returned */
    char *joined;        /* a logical line made of "\"-continued physical lines */
    size_t joined_len;
    char *err;
    size_t err_size;
} line_reader;

static bool reader_fail(line_reader *r, const char *fmt, ...) {
    if (r->err && r->err_size) {
        int n = snprintf(r->err, r->err_size, "%s:%ld: ", r->path, r->line);
        va_list ap;
        va_start(ap, fmt);
        if (n >= 0 && (size_t)n < r->err_size) vsnprintf(r->err + n, r->err_size - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return false;
}

/* One physical line without its "\n" (and "\r"): 1, 0 at the end of the file, −1 on error. */
static int physical_line(line_reader *r, char **out, size_t *len) {
    for (;;) {
        char *s = r->buf + r->start;
        size_t avail = r->end - r->start;
        char *nl = avail ? memchr(s, '\n', avail) : NULL;
        if (nl || (r->eof && avail)) {
            size_t n = nl ? (size_t)(nl - s) : avail;
            r->start += nl ? n + 1 : n;
            r->line++;
            if (n > SL_OBJ_MAX_LINE)
                return reader_fail(r, "line longer than %u bytes (SL_OBJ_MAX_LINE): not an OBJ file, or a damaged one",
                                   (unsigned)SL_OBJ_MAX_LINE), -1;
            if (n && s[n - 1] == '\r') n--;
            if (memchr(s, 0, n)) return reader_fail(r, "binary data (a NUL byte): not an OBJ text file (UTF-16 text is not read either)"), -1;
            s[n] = 0;
            *out = s, *len = n;
            return 1;
        }
        if (r->eof) return 0;
        if (avail > SL_OBJ_MAX_LINE) {
            r->line++;
            return reader_fail(r, "line longer than %u bytes (SL_OBJ_MAX_LINE): not an OBJ file, or a damaged one",
                               (unsigned)SL_OBJ_MAX_LINE), -1;
        }
        memmove(r->buf, s, avail);
        r->start = 0, r->end = avail;
        if (r->cap - 1 - r->end < 4096 && r->cap < OBJ_CHUNK + SL_OBJ_MAX_LINE + 2) {
            /* sized for a small file, which is longer than it said: the full buffer */
            char *b = realloc(r->buf, OBJ_CHUNK + SL_OBJ_MAX_LINE + 2);
            if (!b) return reader_fail(r, "out of memory"), -1;
            r->buf = b, r->cap = OBJ_CHUNK + SL_OBJ_MAX_LINE + 2;
        }
        size_t room = r->cap - 1 - r->end;
        ssize_t got;
        do got = read(r->fd, r->buf + r->end, room);
        while (got < 0 && errno == EINTR);
        if (got < 0) return reader_fail(r, "read error: %s", strerror(errno)), -1;
        if (got == 0) r->eof = true;
        r->end += (size_t)got;
        r->read_bytes += (unsigned long long)got;
        if (r->read_bytes > r->max_bytes)
            return reader_fail(r, "the file is larger than %llu bytes (it grew while being read): refused", r->max_bytes), -1;
    }
}

/* One logical line: physical lines ending in "\" are joined (the backslash becomes a space). */
static int next_line(line_reader *r, char **out, size_t *len) {
    char *s;
    size_t n;
    int got = physical_line(r, &s, &n);
    if (got <= 0 || n == 0 || s[n - 1] != '\\') {
        if (got > 0) *out = s, *len = n;
        return got;
    }
    r->joined_len = 0;
    if (!r->joined && !(r->joined = malloc(SL_OBJ_MAX_LINE + 2))) return reader_fail(r, "out of memory"), -1;
    for (;;) {
        bool more = n && s[n - 1] == '\\';
        if (more) s[n - 1] = ' ';
        if (r->joined_len + n + 1 > SL_OBJ_MAX_LINE)
            return reader_fail(r, "continued line longer than %u bytes (SL_OBJ_MAX_LINE)", (unsigned)SL_OBJ_MAX_LINE), -1;
        memcpy(r->joined + r->joined_len, s, n);
        r->joined_len += n;
        r->joined[r->joined_len] = 0;
        if (!more) break;
        got = physical_line(r, &s, &n);
        if (got < 0) return -1;
        if (got == 0) break;
    }
    *out = r->joined, *len = r->joined_len;
    return 1;
}

static bool reader_open(line_reader *r, const char *path, unsigned long long max_bytes, char *err, size_t err_size) {
    memset(r, 0, sizeof *r);
    r->path = path, r->err = err, r->err_size = err_size, r->max_bytes = max_bytes, r->fd = -1;
    char why[600];
    r->fd = sl_open_input_file(path, why, sizeof why); /* a FIFO or device is refused, never read */
    if (r->fd < 0) {
        if (err && err_size) snprintf(err, err_size, "%s", why);
        return false;
    }
    struct stat st;
    bool known = fstat(r->fd, &st) == 0;
    if (known && (unsigned long long)st.st_size > max_bytes) {
        if (err && err_size)
            snprintf(err, err_size, "%s: %llu bytes, over the limit of %llu bytes for this kind of file: refused", path,
                     (unsigned long long)st.st_size, max_bytes);
        close(r->fd);
        r->fd = -1;
        return false;
    }
    /* a small file gets a buffer its size (it grows to the full one if the file does) */
    r->cap = OBJ_CHUNK + SL_OBJ_MAX_LINE + 2;
    if (known && (unsigned long long)st.st_size + 8192 < r->cap) r->cap = (size_t)st.st_size + 8192;
    r->buf = malloc(r->cap);
    if (!r->buf) {
        if (err && err_size) snprintf(err, err_size, "%s: out of memory", path);
        free(r->buf), free(r->joined), close(r->fd);
        r->buf = r->joined = NULL, r->fd = -1;
        return false;
    }
    return true;
}

static void reader_close(line_reader *r) {
    if (r->fd >= 0) close(r->fd);
    free(r->buf);
    free(r->joined);
    r->fd = -1, r->buf = r->joined = NULL;
}

/* ---- numbers ------------------------------------------------------------------------------ */

static const char *skip_space(const char *p) {
    while (*p == ' ' || *p == '\t' || *p == '\v' || *p == '\f' || *p == '\r') p++;
    return p;
}
static bool is_end(char c) { return c == 0 || c == ' ' || c == '\t' || c == '\v' || c == '\f' || c == '\r'; }

/* A decimal number ([+-]digits[.digits][(e|E)[+-]digits]) at *p, advancing past it. Locale-free.
 * Returns 0 and *out (as float) when it is a finite float, 1 when there is no number here (the
 * token is not one), 2 when it is a number beyond float's range or nan/inf, 3 when a finite
 * number is followed by other text in the token ("3.1+e2": 3.1 in *out, as assimp read it). Exact for up to 19
 * significant digits and |exponent| <= 22 (Clinger's fast path: both factors are exact doubles,
 * so the one multiplication or division rounds once); strtod otherwise. */
static int parse_float(const char **pp, float *out) {
    static const double pow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                   1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const char *p = *pp, *start = p;
    bool neg = false;
    if (*p == '+' || *p == '-') neg = *p++ == '-';
    uint64_t mant = 0;
    int digits = 0, exp10 = 0, seen = 0;
    bool exact = true; /* false: digits beyond the 19th were dropped */
    while (*p == '0') p++, seen++;
    for (; *p >= '0' && *p <= '9'; p++, seen++) {
        if (digits < 19) mant = mant * 10 + (uint64_t)(*p - '0'), digits++;
        else exp10++, exact = false;
    }
    if (*p == '.') {
        p++;
        if (!digits)
            while (*p == '0') p++, exp10--, seen++;
        for (; *p >= '0' && *p <= '9'; p++, seen++)
            if (digits < 19) mant = mant * 10 + (uint64_t)(*p - '0'), digits++, exp10--;
            else exact = false;
    }
    if (!seen) {
        /* nan / inf (any case) are numbers, just not finite ones */
        const char *w = p;
        if (!strncasecmp(w, "nan", 3) || !strncasecmp(w, "inf", 3)) {
            while (!is_end(*w)) w++;
            *pp = w;
            return 2;
        }
        return 1;
    }
    if (*p == 'e' || *p == 'E') {
        const char *e = p + 1;
        bool eneg = false;
        if (*e == '+' || *e == '-') eneg = *e++ == '-';
        if (*e >= '0' && *e <= '9') {
            long ev = 0;
            for (; *e >= '0' && *e <= '9'; e++)
                if (ev < 100000) ev = ev * 10 + (*e - '0');
            exp10 += (int)(eneg ? -ev : ev);
            p = e;
        }
    }
    const char *tail = p; /* "3.1+e2", "1,5": the number, then text (3) */
    while (!is_end(*tail)) tail++;
    double v;
    if (mant == 0) v = 0.0;
    else if (exact && mant <= (1ull << 53) && exp10 >= -22 && exp10 <= 22)
        v = exp10 >= 0 ? (double)mant * pow10[exp10] : (double)mant / pow10[-exp10];
    else {
        char tmp[128];
        size_t n = (size_t)(p - start);
        if (n >= sizeof tmp) { /* a very long digit string: strtod on the original text */
            char *copy = strndup(start, n);
            if (!copy) return 1;
            v = strtod(copy, NULL);
            free(copy);
        } else {
            memcpy(tmp, start, n), tmp[n] = 0;
            v = strtod(tmp, NULL);
        }
        neg = false; /* strtod read the sign */
    }
    if (neg) v = -v;
    *pp = tail;
    if (!isfinite(v) || fabs(v) > (double)3.4028234663852886e38) return 2;
    *out = (float)v;
    return !isfinite(*out) ? 2 : tail != p ? 3 : 0;
}

/* ---- the model being read ----------------------------------------------------------------- */

typedef struct obj_mesh {
    char *name;
    char *material;     /* usemtl name, NULL: assimp's "DefaultMaterial" */
    int object;
    float *pos, *uv, *nrm;
    uint32_t *idx;
    size_t nv, cap_v, ni, cap_i;
    bool has_uv, has_nrm;
} obj_mesh;

typedef struct mtl_material {
    char *name;
    float kd[3], ke[3], alpha, metallic, roughness;
    bool has_metallic, has_roughness;
    char *map_kd, *map_norm, *map_ke, *map_pr;
} mtl_material;

typedef struct obj_state {
    sl_scene *scene;
    const char *path;
    char dir[4096], stem[256], base[256];
    line_reader rd;
    float *v, *vt, *vn;             /* the file's lists: 3, 2, 3 floats each */
    size_t nv, nvt, nvn, cap_v, cap_vt, cap_vn;
    char **objects;
    int object_count, object_cap, cur_object;
    char *group;                    /* the active "g" group (assimp: a change starts an object) */
    char *next_mesh_name;
    char *material;                 /* the current usemtl */
    obj_mesh *meshes;
    int mesh_count, mesh_cap, open_mesh;
    uint64_t *table;                /* the open mesh's vertices by value: hash << 32 | index + 1 */
    size_t table_cap;
    uint32_t *corners;              /* the face being read */
    size_t corner_cap;
    unsigned long long triangles;
    long unknown, unknown_line, points_lines, points_lines_line, junk, junk_line;
    char junk_text[48];
    char unknown_word[32];
    mtl_material *mtl;
    int mtl_count, mtl_cap;
    char *err;
    size_t err_size;
} obj_state;

static bool oom(obj_state *s) { return reader_fail(&s->rd, "out of memory"); }

static bool grow(void **p, size_t *cap, size_t need, size_t elem) {
    if (need <= *cap) return true;
    size_t c = *cap ? *cap : 64;
    while (c < need) c *= 2;
    void *q = realloc(*p, c * elem);
    if (!q) return false;
    *p = q, *cap = c;
    return true;
}

/* The rest of the line, trimmed, as a new string (NULL when out of memory). */
static char *rest_of_line(const char *p) {
    p = skip_space(p);
    size_t n = strlen(p);
    while (n && is_end(p[n - 1])) n--;
    return strndup(p, n);
}

static bool add_object(obj_state *s, const char *name) {
    if (s->object_count == s->object_cap) {
        size_t cap = (size_t)s->object_cap;
        if (!grow((void **)&s->objects, &cap, (size_t)s->object_count + 1, sizeof *s->objects)) return oom(s);
        s->object_cap = (int)cap;
    }
    char *n = strdup(name), *m = strdup(name);
    if (!n || !m) return free(n), free(m), oom(s);
    s->objects[s->object_count] = n;
    s->cur_object = s->object_count++;
    free(s->next_mesh_name);
    s->next_mesh_name = m;
    s->open_mesh = -1;
    return true;
}

static uint32_t hash_key(const uint32_t k[8]);
static bool table_insert(uint64_t *t, size_t cap, uint32_t h, uint32_t index);

static bool all_equal(const float *a, size_t n, int dim) {
    for (size_t i = 1; i < n; i++)
        for (int k = 0; k < dim; k++)
            if (a[dim * i + k] != a[k]) return false;
    return true;
}

/* assimp's FindInvalidData, which the assimp import ran and whose result this reader keeps: a
 * mesh's normals are dropped (regenerated by sl_mesh_generate_tangents) when one is zero or all
 * are the same, its UVs when all are the same, the mesh when all its positions are; then the
 * vertices that differed only there are joined (in order, as JoinIdenticalVertices after it). */
static bool assimp_invalid_data(obj_state *s, obj_mesh *m) {
    if (m->nv == 0) return true;
    if (all_equal(m->pos, m->nv, 3)) { /* nothing to draw */
        m->ni = 0;
        return true;
    }
    bool drop_n = false, drop_uv = m->has_uv && all_equal(m->uv, m->nv, 2);
    if (m->has_nrm) {
        drop_n = all_equal(m->nrm, m->nv, 3);
        for (size_t i = 0; i < m->nv && !drop_n; i++)
            drop_n = m->nrm[3 * i] == 0 && m->nrm[3 * i + 1] == 0 && m->nrm[3 * i + 2] == 0;
    }
    if (!drop_n && !drop_uv) return true;
    if (drop_n) memset(m->nrm, 0, 3 * m->nv * sizeof(float)), m->has_nrm = false;
    if (drop_uv) memset(m->uv, 0, 2 * m->nv * sizeof(float)), m->has_uv = false;
    size_t cap = 1024;
    while (cap < 2 * m->nv) cap *= 2;
    uint64_t *t = calloc(cap, sizeof *t);
    uint32_t *map = malloc(m->nv * sizeof *map);
    if (!t || !map) return free(t), free(map), oom(s);
    size_t n = 0;
    for (size_t v = 0; v < m->nv; v++) {
        float val[8];
        memcpy(val, m->pos + 3 * v, 3 * sizeof(float));
        memcpy(val + 3, m->uv + 2 * v, 2 * sizeof(float));
        memcpy(val + 5, m->nrm + 3 * v, 3 * sizeof(float));
        uint32_t key[8];
        for (int i = 0; i < 8; i++) {
            float c = val[i] + 0.0f;
            memcpy(&key[i], &c, 4);
        }
        uint32_t h = hash_key(key);
        size_t i = h & (cap - 1);
        map[v] = UINT32_MAX;
        for (; t[i]; i = (i + 1) & (cap - 1)) {
            uint32_t w = (uint32_t)t[i] - 1u;
            if ((uint32_t)(t[i] >> 32) == h && m->pos[3 * w] == val[0] &&
                m->pos[3 * w + 1] == val[1] && m->pos[3 * w + 2] == val[2] && m->uv[2 * w] == val[3] &&
                m->uv[2 * w + 1] == val[4] && m->nrm[3 * w] == val[5] && m->nrm[3 * w + 1] == val[6] &&
                m->nrm[3 * w + 2] == val[7]) {
                map[v] = w;
                break;
            }
        }
        if (map[v] != UINT32_MAX) continue;
        /* kept: moved down to slot n (n <= v, so the slots read later are untouched) */
        memmove(m->pos + 3 * n, val, 3 * sizeof(float));
        memmove(m->uv + 2 * n, val + 3, 2 * sizeof(float));
        memmove(m->nrm + 3 * n, val + 5, 3 * sizeof(float));
        t[i] = (uint64_t)h << 32 | (uint64_t)(n + 1);
        map[v] = (uint32_t)n++;
    }
    for (size_t i = 0; i < m->ni; i++) m->idx[i] = map[m->idx[i]];
    m->nv = n;
    free(t);
    free(map);
    return true;
}

/* Ends the open mesh: assimp's invalid-data rules, arrays shrunk to size, its vertex table dropped. */
static bool close_mesh(obj_state *s) {
    if (s->open_mesh < 0) return true;
    obj_mesh *m = &s->meshes[s->open_mesh];
    free(s->table);
    s->table = NULL, s->table_cap = 0;
    s->open_mesh = -1;
    if (!assimp_invalid_data(s, m)) return false;
    size_t nv = m->nv ? m->nv : 1, ni = m->ni ? m->ni : 1;
    float *p;
    uint32_t *q;
    if ((p = realloc(m->pos, nv * 3 * sizeof(float)))) m->pos = p;
    if ((p = realloc(m->uv, nv * 2 * sizeof(float)))) m->uv = p;
    if ((p = realloc(m->nrm, nv * 3 * sizeof(float)))) m->nrm = p;
    if ((q = realloc(m->idx, ni * sizeof(uint32_t)))) m->idx = q;
    m->cap_v = nv, m->cap_i = ni;
    return true;
}

static bool open_mesh(obj_state *s) {
    if (s->cur_object < 0 && !add_object(s, "defaultobject")) return false;
    if (s->mesh_count == s->mesh_cap) {
        size_t cap = (size_t)s->mesh_cap;
        if (!grow((void **)&s->meshes, &cap, (size_t)s->mesh_count + 1, sizeof *s->meshes)) return oom(s);
        s->mesh_cap = (int)cap;
    }
    obj_mesh *m = &s->meshes[s->mesh_count];
    memset(m, 0, sizeof *m);
    m->name = strdup(s->next_mesh_name ? s->next_mesh_name : "defaultobject");
    m->material = s->material ? strdup(s->material) : NULL;
    m->object = s->cur_object;
    if (!m->name || (s->material && !m->material)) return free(m->name), free(m->material), oom(s);
    s->open_mesh = s->mesh_count++;
    return true;
}

static uint32_t hash_key(const uint32_t k[8]) {
    uint64_t h = 0x9E3779B97F4A7C15ull;
    for (int i = 0; i < 8; i++) {
        h ^= k[i];
        h *= 0xff51afd7ed558ccdull; /* a 64-bit multiply-xorshift mix (the MurmurHash3 finaliser's constant) */
        h ^= h >> 32;
    }
    return (uint32_t)h;
}

static bool table_insert(uint64_t *t, size_t cap, uint32_t h, uint32_t index) {
    for (size_t i = h & (cap - 1);; i = (i + 1) & (cap - 1))
        if (!t[i]) return t[i] = (uint64_t)h << 32 | (uint64_t)(index + 1u), true;
}

/* The open mesh's vertex with these values, added when new; UINT32_MAX on error (err set). */
static uint32_t mesh_vertex(obj_state *s, const float p[3], const float *uv, const float *n) {
    obj_mesh *m = &s->meshes[s->open_mesh];
    float val[8] = {p[0], p[1], p[2], uv ? uv[0] : 0, uv ? uv[1] : 0, n ? n[0] : 0, n ? n[1] : 0, n ? n[2] : 0};
    uint32_t key[8];
    for (int i = 0; i < 8; i++) {
        float c = val[i] + 0.0f; /* −0 and +0 are one value */
        memcpy(&key[i], &c, 4);
    }
    uint32_t h = hash_key(key);
    if (2 * (m->nv + 1) > s->table_cap) { /* load factor at most 1/2 */
        size_t cap = s->table_cap ? 2 * s->table_cap : 1024;
        uint64_t *t = calloc(cap, sizeof *t);
        if (!t) return oom(s), UINT32_MAX;
        for (size_t i = 0; i < s->table_cap; i++)
            if (s->table[i]) table_insert(t, cap, (uint32_t)(s->table[i] >> 32), (uint32_t)s->table[i] - 1u);
        free(s->table);
        s->table = t, s->table_cap = cap;
    }
    size_t i = h & (s->table_cap - 1);
    for (; s->table[i]; i = (i + 1) & (s->table_cap - 1)) {
        if ((uint32_t)(s->table[i] >> 32) != h) continue;
        uint32_t v = (uint32_t)s->table[i] - 1u;
        const float *a = m->pos + 3 * v, *b = m->uv + 2 * v, *c = m->nrm + 3 * v;
        if (a[0] == val[0] && a[1] == val[1] && a[2] == val[2] && b[0] == val[3] && b[1] == val[4] &&
            c[0] == val[5] && c[1] == val[6] && c[2] == val[7])
            return v;
    }
    if (m->nv >= OBJ_MAX_MESH_VERTICES)
        return reader_fail(&s->rd, "mesh '%s' has more than %u distinct vertices: refused", m->name,
                           (unsigned)OBJ_MAX_MESH_VERTICES), UINT32_MAX;
    if (m->nv == m->cap_v) {
        size_t c1 = m->cap_v, c2 = m->cap_v, c3 = m->cap_v;
        if (!grow((void **)&m->pos, &c1, m->nv + 1, 3 * sizeof(float)) ||
            !grow((void **)&m->uv, &c2, m->nv + 1, 2 * sizeof(float)) ||
            !grow((void **)&m->nrm, &c3, m->nv + 1, 3 * sizeof(float)))
            return oom(s), UINT32_MAX;
        m->cap_v = c1;
    }
    memcpy(m->pos + 3 * m->nv, val, 3 * sizeof(float));
    memcpy(m->uv + 2 * m->nv, val + 3, 2 * sizeof(float));
    memcpy(m->nrm + 3 * m->nv, val + 5, 3 * sizeof(float));
    s->table[i] = (uint64_t)h << 32 | (uint64_t)(m->nv + 1);
    return (uint32_t)m->nv++;
}

/* ---- statements --------------------------------------------------------------------------- */

/* "v x y z [w | r g b]", "vt u [v [w]]", "vn x y z": `need` numbers required, up to `keep` kept. */
static bool read_vector(obj_state *s, const char *p, const char *what, int need, int keep, float **list, size_t *count,
                        size_t *cap) {
    if (*count >= SL_OBJ_MAX_ELEMENTS)
        return reader_fail(&s->rd, "more than %u '%s' lines (SL_OBJ_MAX_ELEMENTS): refused", (unsigned)SL_OBJ_MAX_ELEMENTS,
                           what);
    float v[3] = {0, 0, 0};
    for (int k = 0; k < keep; k++) {
        p = skip_space(p);
        if (!*p) {
            if (k < need)
                return reader_fail(&s->rd, "'%s' has %d of its %d coordinates", what, k, need);
            break;
        }
        const char *t = p;
        int r = parse_float(&p, &v[k]);
        if (r == 1) {
            int n = 0;
            while (!is_end(t[n]) && n < 40) n++;
            return reader_fail(&s->rd, "'%s': '%.*s' is not a number", what, n, t);
        }
        if (r == 2) {
            int n = 0;
            while (!is_end(t[n]) && n < 40) n++;
            return reader_fail(&s->rd, "'%s': %.*s is not a finite float", what, n, t);
        }
        if (r == 3 && !s->junk++) {
            s->junk_line = s->rd.line;
            int n = 0;
            while (!is_end(t[n]) && n < 40) n++;
            snprintf(s->junk_text, sizeof s->junk_text, "%.*s", n, t);
        }
    }
    if (*count == *cap && !grow((void **)list, cap, *count + 1, (size_t)keep * sizeof(float))) return oom(s);
    memcpy(*list + (size_t)keep * *count, v, (size_t)keep * sizeof(float));
    (*count)++;
    return true;
}

/* An OBJ index at *p: positive 1..count, negative −1 = the last defined; 0-based in *out. */
static bool read_index(obj_state *s, const char **pp, size_t count, const char *what, size_t *out) {
    const char *p = *pp;
    bool neg = *p == '-';
    if (*p == '+' || *p == '-') p++;
    if (*p < '0' || *p > '9') {
        int n = 0;
        while (!is_end((*pp)[n]) && n < 40) n++;
        return reader_fail(&s->rd, "face: '%.*s' is not a %s index", n, *pp, what);
    }
    unsigned long long v = 0;
    for (; *p >= '0' && *p <= '9'; p++) {
        v = v * 10 + (unsigned)(*p - '0');
        if (v > (1ull << 31)) return reader_fail(&s->rd, "face: %s index beyond 2^31 (only %zu defined)", what, count);
    }
    *pp = p;
    if (v == 0) return reader_fail(&s->rd, "face: %s index 0 (OBJ indices start at 1, or count back from -1)", what);
    if (neg) {
        if (v > count)
            return reader_fail(&s->rd, "face: %s index -%llu reaches before the first of the %zu defined so far", what, v,
                               count);
        *out = count - (size_t)v;
    } else {
        if (v > count)
            return reader_fail(&s->rd, "face: %s index %llu, but only %zu defined before this line", what, v, count);
        *out = (size_t)v - 1;
    }
    return true;
}

static void note_point_line(obj_state *s) {
    if (!s->points_lines++) s->points_lines_line = s->rd.line;
}

static bool read_face(obj_state *s, const char *p) {
    size_t n = 0;
    bool any_uv = false, any_nrm = false;
    for (;;) {
        p = skip_space(p);
        if (!*p) break;
        size_t vi, ti = SIZE_MAX, ni = SIZE_MAX;
        if (!read_index(s, &p, s->nv, "vertex", &vi)) return false;
        if (*p == '/') {
            p++;
            if (*p != '/' && !is_end(*p)) {
                if (!read_index(s, &p, s->nvt, "texture coordinate", &ti)) return false;
            }
            if (*p == '/') {
                p++;
                if (!is_end(*p) && !read_index(s, &p, s->nvn, "normal", &ni)) return false;
            }
        }
        if (!is_end(*p)) return reader_fail(&s->rd, "face: unexpected '%c' in a vertex (v, v/vt, v//vn or v/vt/vn)", *p);
        if (!grow((void **)&s->corners, &s->corner_cap, 3 * (n + 1), sizeof *s->corners)) return oom(s);
        s->corners[3 * n] = (uint32_t)vi;
        s->corners[3 * n + 1] = (uint32_t)ti; /* UINT32_MAX: none (indices stay below 2^26) */
        s->corners[3 * n + 2] = (uint32_t)ni;
        any_uv |= ti != SIZE_MAX, any_nrm |= ni != SIZE_MAX;
        n++;
    }
    if (n < 3) {
        note_point_line(s); /* one or two corners: a point or a line, not drawn */
        return true;
    }
    if (s->triangles + (n - 2) > SL_IMPORT_MAX_TRIANGLES)
        return reader_fail(&s->rd, "more than %d triangles in the file (SL_IMPORT_MAX_TRIANGLES, about 3 GB with the GPU "
                                   "copy): refused", SL_IMPORT_MAX_TRIANGLES);
    if (s->open_mesh < 0 && !open_mesh(s)) return false;
    obj_mesh *m = &s->meshes[s->open_mesh];
    m->has_uv |= any_uv, m->has_nrm |= any_nrm;
    uint32_t first = 0, prev = 0;
    for (size_t k = 0; k < n; k++) {
        const uint32_t *c = s->corners + 3 * k;
        uint32_t v = mesh_vertex(s, s->v + 3 * (size_t)c[0], c[1] != UINT32_MAX ? s->vt + 2 * (size_t)c[1] : NULL,
                                 c[2] != UINT32_MAX ? s->vn + 3 * (size_t)c[2] : NULL);
        if (v == UINT32_MAX) return false;
        m = &s->meshes[s->open_mesh];
        if (k == 0) first = v;
        else if (k >= 2) { /* fan: (v0, v[k−1], v[k]) */
            if (!grow((void **)&m->idx, &m->cap_i, m->ni + 3, sizeof *m->idx)) return oom(s);
            m->idx[m->ni++] = first, m->idx[m->ni++] = prev, m->idx[m->ni++] = v;
        }
        prev = v;
    }
    s->triangles += n - 2;
    return true;
}

static bool same(const char *a, const char *b) { return (!a && !b) || (a && b && !strcmp(a, b)); }

/* ---- MTL ---------------------------------------------------------------------------------- */

/* A texture statement's file: options ("-o 1 1", "-bm 0.5", "-clamp on"…) skipped, the rest of
 * the line (names may hold spaces). */
static char *texture_name(const char *p) {
    for (;;) {
        p = skip_space(p);
        if (*p != '-') break;
        const char *opt = p;
        while (!is_end(*p)) p++;
        size_t len = (size_t)(p - opt);
        bool vec = len == 2 && (opt[1] == 'o' || opt[1] == 's' || opt[1] == 't'); /* -o u [v [w]] */
        bool mm = len == 3 && !strncmp(opt, "-mm", 3);                           /* -mm base gain */
        int args = vec ? 3 : mm ? 2 : 1; /* -blendu on, -bm f, -clamp on, -texres n, -imfchan c… */
        for (int a = 0; a < args; a++) {
            const char *q = skip_space(p), *t = q;
            float f;
            if (!*q || ((vec || mm) && parse_float(&t, &f) != 0)) break;
            while (!is_end(*q)) q++;
            p = q;
        }
    }
    return rest_of_line(p);
}

static void read_mtl(obj_state *s, const char *file) {
    line_reader r;
    char err[700];
    if (!reader_open(&r, file, MTL_MAX_FILE_BYTES, err, sizeof err)) {
        SL_WARN("%s: material library: %s", s->path, err);
        return;
    }
    mtl_material *cur = NULL;
    char *line;
    size_t len;
    int got;
    while ((got = next_line(&r, &line, &len)) > 0) {
        const char *p = skip_space(line), *w = p;
        while (!is_end(*p)) p++;
        size_t wl = (size_t)(p - w);
        if (!wl || *w == '#') continue;
#define KW(k) (wl == sizeof(k) - 1 && !strncasecmp(w, k, wl))
        if (KW("newmtl")) {
            char *name = rest_of_line(p);
            if (!name) break;
            if (!*name) { /* "newmtl" alone defines assimp's default material (faces without usemtl) */
                free(name);
                if (!(name = strdup("DefaultMaterial"))) break;
            }
            cur = NULL;
            for (int i = 0; i < s->mtl_count; i++)
                if (!strcmp(s->mtl[i].name, name)) cur = &s->mtl[i]; /* a repeated name adds to the first */
            if (cur) {
                free(name);
                continue;
            }
            size_t cap = (size_t)s->mtl_cap;
            if (!grow((void **)&s->mtl, &cap, (size_t)s->mtl_count + 1, sizeof *s->mtl)) {
                free(name);
                break;
            }
            s->mtl_cap = (int)cap;
            cur = &s->mtl[s->mtl_count++];
            memset(cur, 0, sizeof *cur);
            cur->name = name;
            cur->kd[0] = cur->kd[1] = cur->kd[2] = 0.6f; /* assimp's OBJ default diffuse */
            cur->alpha = 1.0f;
            continue;
        }
        if (!cur) continue;
        float f[3];
        int nf = 0;
        bool bad = false;
        if (KW("Kd") || KW("Ke") || KW("d") || KW("Tr") || KW("Pm") || KW("Pr")) {
            const char *q = p;
            while (nf < 3) {
                q = skip_space(q);
                if (!*q) break;
                int r = parse_float(&q, &f[nf]);
                if (r == 1 || r == 2) {
                    bad = true;
                    break;
                }
                nf++;
            }
            if (bad || nf == 0) {
                SL_WARN("%s:%ld: '%.*s' without a finite number: ignored", file, r.line, (int)wl, w);
                continue;
            }
            for (int k = nf; k < 3; k++) f[k] = f[nf - 1]; /* "Kd 0.5" is grey */
        }
        char **map = NULL;
        if (KW("Kd")) memcpy(cur->kd, f, sizeof f);
        else if (KW("Ke")) memcpy(cur->ke, f, sizeof f);
        else if (KW("d")) cur->alpha = f[0];
        else if (KW("Tr")) cur->alpha = 1.0f - f[0];
        else if (KW("Pm")) cur->metallic = f[0], cur->has_metallic = true;
        else if (KW("Pr")) cur->roughness = f[0], cur->has_roughness = true;
        else if (KW("map_Kd")) map = &cur->map_kd;
        else if (KW("norm") || KW("map_Kn")) map = &cur->map_norm;
        else if (KW("map_Ke")) map = &cur->map_ke;
        else if (KW("map_Pr")) map = &cur->map_pr;
#undef KW
        if (map) {
            char *t = texture_name(p);
            if (t && *t) free(*map), *map = t;
            else free(t);
        }
    }
    if (got < 0) SL_WARN("%s: material library: %s (the materials before it are used)", s->path, err);
    reader_close(&r);
}

/* "mtllib a.mtl [b.mtl …]": the rest of the line as one name first (names with spaces), else each
 * word; assimp's fallback, "<file stem>.mtl" beside the OBJ, when none is found. */
static void read_mtllib(obj_state *s, const char *p) {
    char *all = rest_of_line(p);
    if (!all || !*all) {
        free(all);
        return;
    }
    char path[8192], why[200];
    snprintf(path, sizeof path, "%s%s%s", all[0] == '/' ? "" : s->dir, all[0] == '/' ? "" : "/", all);
    errno = 0;
    if (!sl_input_file_problem(path, why, sizeof why) || errno != ENOENT) {
        read_mtl(s, path); /* also a special file: refused there, with its reason */
        free(all);
        return;
    }
    bool found = false;
    for (char *save = NULL, *w = strtok_r(all, " \t", &save); w; w = strtok_r(NULL, " \t", &save)) {
        snprintf(path, sizeof path, "%s%s%s", w[0] == '/' ? "" : s->dir, w[0] == '/' ? "" : "/", w);
        errno = 0;
        if (!sl_input_file_problem(path, why, sizeof why) || errno != ENOENT) read_mtl(s, path), found = true;
    }
    if (!found) {
        snprintf(path, sizeof path, "%s/%s.mtl", s->dir, s->stem);
        if (!sl_input_file_problem(path, why, sizeof why)) read_mtl(s, path);
        else SL_WARN("%s:%ld: material library '%s' not found (materials default to grey)", s->path, s->rd.line, p);
    }
    free(all);
}

/* ---- the scene ---------------------------------------------------------------------------- */

static void unique_name(char *out, size_t size, const char *base, const sl_scene *sc,
                        int (*taken)(const sl_scene *, const char *)) {
    snprintf(out, size, "%s", base);
    for (int i = 2; taken(sc, out) >= 0 && i < INT_MAX; i++) snprintf(out, size, "%s#%d", base, i);
}

/* A texture value: absolute, or relative to the OBJ's directory; missing or unreadable said. */
static void set_texture(obj_state *s, sl_prop_list *in, const char *key, const char *file) {
    if (!file) return;
    char out[8192], why[160];
    if (file[0] == '/') snprintf(out, sizeof out, "%s", file);
    else snprintf(out, sizeof out, "%s/%s", s->dir, file);
    errno = 0;
    if (sl_input_file_problem(out, why, sizeof why)) {
        if (errno == ENOENT) SL_WARN("%s: texture '%s' not found (%s)", s->path, out, file);
        else SL_WARN("%s: texture '%s' (%s) cannot be read: %s", s->path, out, file, why);
    }
    sl_prop_set_string(in, key, out, 0);
}

/* The scene material for usemtl `name` (NULL: assimp's "DefaultMaterial"), made on first use with
 * the standard inputs scene_assimp.c's material_for publishes for an OBJ material. */
static int scene_material(obj_state *s, const char *name) {
    char full[600];
    snprintf(full, sizeof full, "%.250s/%.300s", s->stem, name ? name : "DefaultMaterial");
    int mi = sl_scene_find_material(s->scene, full);
    if (mi >= 0) return mi;
    mi = sl_scene_add_material(s->scene, full, "lambert");
    if (mi < 0) return -1;
    sl_material *sm = &s->scene->materials[mi];
    sm->source = strdup(s->path);
    const mtl_material *m = NULL;
    for (int i = 0; i < s->mtl_count && !m; i++)
        if (!strcmp(s->mtl[i].name, name ? name : "DefaultMaterial")) m = &s->mtl[i];
    mtl_material defaults = {.kd = {0.6f, 0.6f, 0.6f}, .alpha = 1.0f};
    if (!m) m = &defaults;
    sl_prop_list *in = &sm->inputs;
    sl_prop_set_vec(in, "base_color", m->kd, 3, 0);
    if (m->alpha < 1.0f && m->alpha >= 0.0f) sl_prop_set_number(in, "opacity", m->alpha, 0);
    set_texture(s, in, "base_color_texture", m->map_kd);
    if (m->has_metallic || m->has_roughness) {
        sl_prop_set_string(in, "brdf", "metallic-roughness", 0);
        sl_prop_set_number(in, "metallic", m->has_metallic ? fminf(fmaxf(m->metallic, 0.0f), 1.0f) : 1.0f, 0);
        sl_prop_set_number(in, "roughness", m->has_roughness ? fminf(fmaxf(m->roughness, 0.0f), 1.0f) : 1.0f, 0);
        set_texture(s, in, "metallic_roughness_texture", m->map_pr);
    }
    set_texture(s, in, "normal_texture", m->map_norm);
    if (m->ke[0] > 0 || m->ke[1] > 0 || m->ke[2] > 0) sl_prop_set_vec(in, "emissive", m->ke, 3, 0);
    set_texture(s, in, "emissive_texture", m->map_ke);
    return mi;
}

static bool build_scene(obj_state *s, int parent) {
    char prefix[512], base[1200], name[1300];
    sl_scene *sc = s->scene;
    snprintf(prefix, sizeof prefix, "%s", parent >= 0 ? sc->nodes[parent].name : s->stem);
    snprintf(base, sizeof base, "%.500s/%.600s", prefix, s->base);
    unique_name(name, sizeof name, base, sc, sl_scene_find_node);
    int root = sl_scene_add_node(sc, name, parent), first_mesh = sc->mesh_count;
    if (root < 0) return oom(s);
    for (int o = 0; o < s->object_count; o++) {
        snprintf(base, sizeof base, "%.500s/%.600s", prefix, s->objects[o][0] ? s->objects[o] : "node");
        unique_name(name, sizeof name, base, sc, sl_scene_find_node);
        int node = sl_scene_add_node(sc, name, root);
        if (node < 0) return oom(s);
        for (int k = 0; k < s->mesh_count; k++) {
            obj_mesh *m = &s->meshes[k];
            if (m->object != o || m->ni == 0) continue;
            sl_mesh_data d;
            memset(&d, 0, sizeof d);
            d.vertex_count = (int)m->nv, d.index_count = (int)m->ni;
            d.positions = m->pos, d.normals = m->nrm, d.uvs = m->uv, d.indices = m->idx;
            m->pos = m->nrm = m->uv = NULL, m->idx = NULL;
            d.tangents = calloc(4 * m->nv, sizeof(float));
            if (!d.tangents) return sl_mesh_free(&d), oom(s);
            if (m->has_uv)
                for (size_t v = 0; v < m->nv; v++) d.uvs[2 * v + 1] = 1.0f - d.uvs[2 * v + 1]; /* v = 0 at the top */
            else memset(d.uvs, 0, 2 * m->nv * sizeof(float));
            if (!m->has_nrm) memset(d.normals, 0, 3 * m->nv * sizeof(float));
            /* normals the file lacks (zero) become area-weighted vertex normals; tangents from the UVs */
            sl_mesh_generate_tangents(&d);
            sl_mesh_compute_bounds(&d);
            char mesh_name[600];
            if (m->name[0]) snprintf(mesh_name, sizeof mesh_name, "%.250s/%.300s", s->stem, m->name);
            else snprintf(mesh_name, sizeof mesh_name, "%s/mesh%d", s->stem, sc->mesh_count - first_mesh);
            int material = scene_material(s, m->material);
            if (material < 0) return sl_mesh_free(&d), oom(s);
            int mi = sl_scene_add_mesh(sc, mesh_name, &d, material);
            if (mi < 0 || !sl_scene_node_add_mesh(sc, node, mi)) return oom(s);
        }
    }
    if (sc->mesh_count == first_mesh) {
        if (s->err && s->err_size)
            snprintf(s->err, s->err_size, "%s: no mesh left to draw: in every mesh all vertices are one point", s->path);
        return false;
    }
    return true;
}

static void free_state(obj_state *s) {
    reader_close(&s->rd);
    free(s->v), free(s->vt), free(s->vn);
    for (int i = 0; i < s->object_count; i++) free(s->objects[i]);
    free(s->objects);
    free(s->group), free(s->next_mesh_name), free(s->material);
    for (int i = 0; i < s->mesh_count; i++) {
        obj_mesh *m = &s->meshes[i];
        free(m->name), free(m->material), free(m->pos), free(m->uv), free(m->nrm), free(m->idx);
    }
    free(s->meshes);
    free(s->table);
    free(s->corners);
    for (int i = 0; i < s->mtl_count; i++) {
        mtl_material *m = &s->mtl[i];
        free(m->name), free(m->map_kd), free(m->map_norm), free(m->map_ke), free(m->map_pr);
    }
    free(s->mtl);
}

static bool read_statement(obj_state *s, char *line) {
    const char *p = skip_space(line), *w = p;
    while (!is_end(*p)) p++;
    size_t wl = (size_t)(p - w);
    if (!wl || *w == '#') return true;
#define KW(k) (wl == sizeof(k) - 1 && !memcmp(w, k, wl))
    if (KW("v")) return read_vector(s, p, "v", 3, 3, &s->v, &s->nv, &s->cap_v);
    if (KW("f") || KW("fo")) return read_face(s, p);
    if (KW("vt")) return read_vector(s, p, "vt", 1, 2, &s->vt, &s->nvt, &s->cap_vt);
    if (KW("vn")) return read_vector(s, p, "vn", 3, 3, &s->vn, &s->nvn, &s->cap_vn);
    if (KW("o") || KW("g")) {
        char *name = rest_of_line(p);
        if (!name) return oom(s);
        bool group = w[0] == 'g';
        if (group && same(name, s->group ? s->group : "")) return free(name), true; /* the first group is "" */
        if (!*name && !group) return free(name), true; /* "o" without a name: nothing to start */
        bool ok = close_mesh(s) && add_object(s, name);
        if (group) free(s->group), s->group = name;
        else free(name);
        return ok;
    }
    if (KW("usemtl")) {
        char *name = rest_of_line(p);
        if (!name) return oom(s);
        if (!*name || same(name, s->material)) return free(name), true; /* "usemtl" alone: ignored, as assimp does */
        free(s->material);
        s->material = name;
        if (s->open_mesh >= 0) { /* a run of faces ends: the next mesh is named after the material */
            if (!close_mesh(s)) return false;
            free(s->next_mesh_name);
            if (!(s->next_mesh_name = strdup(name))) return oom(s);
        }
        return true;
    }
    if (KW("mtllib")) return read_mtllib(s, p), true;
    if (KW("l") || KW("p")) return note_point_line(s), true;
    /* statements of the format that carry nothing shadelab draws: smoothing groups, free-form
     * geometry, display attributes */
    static const char *const known[] = {"s",    "vp",  "cstype", "deg",   "bmat",     "step",      "curv",
                                        "curv2", "surf", "parm",  "trim",  "hole",     "scrv",      "sp",
                                        "end",  "con", "mg",     "lod",   "usemap",   "maplib",    "shadow_obj",
                                        "trace_obj", "ctech", "stech", "bevel", "c_interp", "d_interp", "call",
                                        "csh"};
    for (size_t i = 0; i < sizeof known / sizeof *known; i++)
        if (strlen(known[i]) == wl && !memcmp(known[i], w, wl)) return true;
#undef KW
    if (!s->unknown++) {
        s->unknown_line = s->rd.line;
        snprintf(s->unknown_word, sizeof s->unknown_word, "%.*s", (int)(wl < 24 ? wl : 24), w);
    }
    return true;
}

bool sl_scene_import_obj(sl_scene *scene, const char *path, int parent_node, char *err, size_t err_size) {
    if (err && err_size) err[0] = 0;
    if (parent_node < -1 || parent_node >= scene->node_count) {
        if (err && err_size) snprintf(err, err_size, "%s: invalid parent node", path);
        return false;
    }
    obj_state *s = calloc(1, sizeof *s);
    if (!s) {
        if (err && err_size) snprintf(err, err_size, "%s: out of memory", path);
        return false;
    }
    s->scene = scene, s->path = path, s->err = err, s->err_size = err_size;
    s->cur_object = s->open_mesh = -1;
    const char *b = strrchr(path, '/');
    snprintf(s->base, sizeof s->base, "%s", b ? b + 1 : path);
    snprintf(s->stem, sizeof s->stem, "%s", s->base);
    char *dot = strrchr(s->stem, '.');
    if (dot && dot != s->stem) *dot = 0;
    char *abs = realpath(path, NULL);
    snprintf(s->dir, sizeof s->dir, "%s", abs ? abs : path);
    free(abs);
    char *slash = strrchr(s->dir, '/');
    if (slash) *slash = 0;
    else snprintf(s->dir, sizeof s->dir, ".");

    if (!reader_open(&s->rd, path, SL_OBJ_MAX_FILE_BYTES, err, err_size)) {
        free_state(s);
        free(s);
        return false;
    }
    struct stat st;
    unsigned long long size = fstat(s->rd.fd, &st) == 0 ? (unsigned long long)st.st_size : 0;
    bool large = size > (16u << 20);
    struct timespec t0, t1, last;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    last = t0;
    if (large) SL_INFO("%s: reading %.1f MB of OBJ…", path, size / 1048576.0);
    char *line;
    size_t len;
    int got;
    bool ok = true;
    while (ok && (got = next_line(&s->rd, &line, &len)) > 0) {
        if (s->rd.line == 1 && len >= 3 && !memcmp(line, "\xEF\xBB\xBF", 3)) line += 3; /* a UTF-8 byte order mark */
        ok = read_statement(s, line);
        if (large && (s->rd.line & 0xFFFFF) == 0) { /* progress every few seconds on long loads */
            clock_gettime(CLOCK_MONOTONIC, &t1);
            if (t1.tv_sec - last.tv_sec >= 5) {
                last = t1;
                SL_INFO("%s: %.0f%% read, %llu triangles so far", path, 100.0 * s->rd.read_bytes / (double)(size ? size : 1),
                        s->triangles);
            }
        }
    }
    if (ok && got < 0) ok = false;
    if (ok) ok = close_mesh(s);
    reader_close(&s->rd);
    free(s->v), free(s->vt), free(s->vn); /* the file's lists are no longer needed */
    s->v = s->vt = s->vn = NULL;
    if (ok && s->triangles == 0) {
        if (err && err_size)
            snprintf(err, err_size, "%s: no mesh left to draw: the file has no faces of three or more vertices (%s)", path,
                     s->points_lines ? "points or lines only: shadelab draws triangles" : "no 'f' lines");
        ok = false;
    }
    if (ok) ok = build_scene(s, parent_node);
    if (ok && s->unknown)
        SL_WARN("%s: %ld line%s with a statement the OBJ reader does not know ignored (the first: line %ld, '%s')", path,
                s->unknown, s->unknown == 1 ? "" : "s", s->unknown_line, s->unknown_word);
    if (ok && s->junk)
        SL_WARN("%s: %ld number%s followed by other text read as the number alone (the first: line %ld, '%s')", path,
                s->junk, s->junk == 1 ? "" : "s", s->junk_line, s->junk_text);
    if (ok && s->points_lines)
        SL_WARN("%s: %ld point or line element%s not drawn (the first: line %ld; shadelab draws triangles)", path,
                s->points_lines, s->points_lines == 1 ? "" : "s", s->points_lines_line);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (ok && large)
        SL_INFO("%s: imported %d meshes, %llu triangles in %.1f s", path, s->mesh_count, s->triangles,
                (t1.tv_sec - t0.tv_sec) + (t1.tv_nsec - t0.tv_nsec) * 1e-9);
    free_state(s);
    free(s);
    return ok;
}
