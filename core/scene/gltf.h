/* The project's glTF 2.0 reader (core/scene/gltf_*.c), private to the scene module: the document
 * (JSON + buffers), checked member access that names the JSON path of what is wrong, accessors
 * read under the specification's rules, and the importer's pieces.
 *
 * Messages: an error is "<file>: <JSON pointer>: <cause>" ("model.glb: /accessors/7/byteOffset:
 * 6 is not a multiple of the component size 4"); it ends the import. What the importer drops or
 * replaces (a line primitive, a zero quaternion, a camera's invalid yfov) is a note with the same
 * form; all notes of a file go out in one warning at the end. */
#ifndef SL_GLTF_H
#define SL_GLTF_H

#include "scene/scene.h"

#include <cjson/cJSON.h>
#include <stdarg.h>
#include <stdint.h>

/* glTF 2.0 §3.6.2 componentType values */
enum { GLTF_BYTE = 5120, GLTF_UNSIGNED_BYTE = 5121, GLTF_SHORT = 5122, GLTF_UNSIGNED_SHORT = 5123,
       GLTF_UNSIGNED_INT = 5125, GLTF_FLOAT = 5126 };

/* Bits naming the accessor formats a use accepts (gltf_read_floats' `allowed`) */
enum {
    GLTF_F32 = 1 << 0,
    GLTF_I8N = 1 << 1, GLTF_U8N = 1 << 2, GLTF_I16N = 1 << 3, GLTF_U16N = 1 << 4, /* normalized */
    GLTF_I8 = 1 << 5, GLTF_U8 = 1 << 6, GLTF_I16 = 1 << 7, GLTF_U16 = 1 << 8,     /* plain integers */
    GLTF_NORMALIZED = GLTF_I8N | GLTF_U8N | GLTF_I16N | GLTF_U16N,
    GLTF_INTEGERS = GLTF_I8 | GLTF_U8 | GLTF_I16 | GLTF_U16,
};

/* The most elements an accessor without a bufferView (all zeros, or sparse) may declare: such
 * an accessor costs memory without costing file size. */
#define GLTF_MAX_ZERO_ELEMENTS (1 << 26)
/* The most bytes one compressed bufferView may decode to (EXT_meshopt_compression). */
#define GLTF_MAX_DECODED_BYTES (1LL << 30)
/* The most notes the file's warning lists (it counts the rest). */
#define GLTF_MAX_NOTES 12
/* The most morph target vertices one primitive may hold (targets × vertices): 36 bytes each on
 * the CPU and the GPU. */
#define GLTF_MAX_MORPH_VALUES (1 << 24)
/* The most animation keys one file may hold (all channels): 16 bytes per key and more. */
#define GLTF_MAX_KEYS (1 << 26)

typedef struct gltf_buffer {
    const unsigned char *data; /* byteLength bytes, or NULL until loaded */
    size_t size;
    unsigned char *owned;      /* what to free (data: URIs, external files) */
    bool tried;
} gltf_buffer;

typedef struct gltf_doc {
    const char *path;          /* the file as named (messages start with it) */
    char dir[4096];            /* its directory (relative URIs) */
    char stem[256];            /* its name without the extension */
    cJSON *root;
    unsigned char *glb;        /* a .glb's bytes (the BIN chunk lies in it) */
    const unsigned char *bin;  /* the BIN chunk, or NULL */
    size_t bin_size;
    gltf_buffer *buffers;
    int buffer_count;
    unsigned char **decoded;   /* per bufferView: its EXT_meshopt_compression data decoded, or NULL */
    int view_count;
    char *err;                 /* the first error */
    size_t err_size;
    bool failed;
    char notes[4096];          /* dropped/replaced, "; "-separated, the first GLTF_MAX_NOTES */
    int note_count;            /* all of them */
} gltf_doc;

/* ---- the document (gltf_doc.c) ----------------------------------------------------------- */

/* Reads the file (a .gltf's JSON, or a .glb's header and chunks), parses the JSON and checks
 * asset.version. false with d->err set when it cannot. */
bool gltf_open(gltf_doc *d, const char *path, char *err, size_t err_size);
void gltf_close(gltf_doc *d);
/* Records the error (only the first one) and returns false. at: a JSON pointer or NULL. */
bool gltf_fail(gltf_doc *d, const char *at, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* Records what is dropped or replaced, for the file's one warning. */
void gltf_note(gltf_doc *d, const char *at, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* The top-level array `name`'s element count (0 when absent). */
int gltf_count(const gltf_doc *d, const char *name);
/* Element i of top-level array `name` (the caller checked the index). */
const cJSON *gltf_item(const gltf_doc *d, const char *name, int i);

/* Checked members. Each returns false after gltf_fail when the member has the wrong type or
 * value; an absent member leaves *out at the default given. `at` is the object's JSON pointer. */
bool gltf_get_object(gltf_doc *d, const cJSON *obj, const char *at, const char *key, const cJSON **out);
bool gltf_get_array(gltf_doc *d, const cJSON *obj, const char *at, const char *key, const cJSON **out);
bool gltf_get_string(gltf_doc *d, const cJSON *obj, const char *at, const char *key, const char **out);
bool gltf_get_bool(gltf_doc *d, const cJSON *obj, const char *at, const char *key, bool *out);
/* An integer in [min, max]. */
bool gltf_get_int(gltf_doc *d, const cJSON *obj, const char *at, const char *key, long long min, long long max,
                  long long *out);
/* An index into top-level array `array`: *out −1 when absent (and !required). */
bool gltf_get_index(gltf_doc *d, const cJSON *obj, const char *at, const char *key, const char *array,
                    bool required, int *out);
/* A finite number. */
bool gltf_get_number(gltf_doc *d, const cJSON *obj, const char *at, const char *key, double *out);
/* An array of exactly n finite numbers; *present tells whether it was there. */
bool gltf_get_numbers(gltf_doc *d, const cJSON *obj, const char *at, const char *key, int n, float *out,
                      bool *present);
/* Buffer `index`'s bytes (loaded on first use: the GLB's BIN chunk, a data: URI or a file beside
 * the glTF), bounded by its byteLength. NULL after gltf_fail. */
const gltf_buffer *gltf_buffer_at(gltf_doc *d, int index);
/* Decodes a data: URI's base64 payload (malloc'd); NULL when it is not base64 data. */
unsigned char *gltf_data_uri(const char *uri, size_t *size);
/* A relative URI as a path beside the file (percent-decoded) into out; false when unusable. */
bool gltf_uri_path(const gltf_doc *d, const char *uri, char *out, size_t size);

/* ---- accessors (gltf_accessor.c) --------------------------------------------------------- */

/* Accessor `index` read as count × comps floats (malloc'd) under glTF 2.0 §3.6: bufferView and
 * byteStride bounds, alignment, normalized integers (§3.11's conversion), sparse substitution,
 * no bufferView = zeros. `type` is the accessor type the use needs ("VEC3"); `allowed` the
 * GLTF_* formats it accepts; `use` the JSON pointer of the referring member (messages). NULL
 * after gltf_fail. */
float *gltf_read_floats(gltf_doc *d, int index, const char *type, unsigned allowed, const char *use, int *count);
/* An index accessor (SCALAR, unsigned byte/short/int, not normalized, no byteStride). */
uint32_t *gltf_read_indices(gltf_doc *d, int index, const char *use, int *count);
/* bufferView `index`'s bytes, bounds-checked inside its buffer, and its byteStride (0: none). */
bool gltf_buffer_view(gltf_doc *d, int index, const unsigned char **data, size_t *len, size_t *stride);
/* gltf_meshopt.c: the bytes of bufferView `index` whose EXT_meshopt_compression object is ext
 * (decoded once, kept in d->decoded), and its stride (ATTRIBUTES: the extension's byteStride,
 * which the view's must equal when given; indices: 0). false after gltf_fail. */
bool gltf_meshopt_view(gltf_doc *d, int index, const cJSON *ext, const unsigned char **data, size_t *len, size_t *stride);
/* The element count of accessor `index` without reading it (−1 after gltf_fail). */
int gltf_accessor_count(gltf_doc *d, int index);

/* ---- the pieces of the import (gltf_import.c and its helpers) ---------------------------- */

typedef struct gltf_import {
    gltf_doc doc;
    sl_scene *scene;
    char prefix[512];       /* node, light and camera names: "<prefix>/<name>" */
    int *materials;         /* glTF material → scene material (−1: not made yet) */
    int default_material;   /* for primitives without one */
    int (*meshes)[2];       /* glTF mesh → [first scene mesh, count] ([−1, 0]: not made yet) */
    int *nodes;             /* glTF node → scene node (−1: not in the scene) */
    int *parents;           /* glTF node → its parent glTF node (−1: a root) */
    long long triangles, vertices; /* import budget spent (SL_IMPORT_MAX_TRIANGLES) */
    long long keys;         /* animation keys read (GLTF_MAX_KEYS) */
    int variant;            /* KHR_materials_variants variant shown, −1: the default materials */
    unsigned unrendered;    /* GLTF_UNRENDERED_* bits for the file's one warning */
} gltf_import;

enum {
    GLTF_UNRENDERED_TEXCOORD2 = 1u << 0,
};

/* gltf_mesh.c: glTF mesh `index`'s primitives as scene meshes for glTF node `node` with glTF skin
 * `skin` (−1: none): made once and shared by the nodes drawing it, or, with morph targets or a
 * skin, made for this node (its weights, its pose: sl_mesh_deform, whose skin holds the glTF
 * skin until gltf_import_skins). false after gltf_fail. */
bool gltf_import_mesh(gltf_import *im, int index, int node, int skin, int range[2]);
/* gltf_skin.c: the skins the deformed meshes made since scene mesh `first_mesh` use, as scene
 * skins (§3.7.3: joints in the scene shown, inverse bind matrices MAT4 float, finite, at least
 * one per joint); false after gltf_fail. */
bool gltf_import_skins(gltf_import *im, int first_mesh);
/* gltf_material.c: the scene material for glTF material `index` (−1: the default material). */
int gltf_import_material(gltf_import *im, int index);
/* gltf_animation.c: animation `which` (−1: the first, noted when the file has more) as node
 * channels. */
bool gltf_import_animation(gltf_import *im, int which);
/* gltf_extensions.c: false (an error naming them) when extensionsRequired names one not read;
 * a warning for used ones not rendered. */
bool gltf_check_extensions(gltf_doc *d);
/* Whether the extension is read (rendered or approximated). */
bool gltf_extension_read(const char *name);
/* Whether the file lists it in extensionsUsed. */
bool gltf_uses_extension(const gltf_doc *d, const char *name);

#endif
