/* The JSON scene loader's private ground, shared by its files (nothing else includes it):
 *   scene_json.c            entry points: load a file or text, the top level, bounds checks
 *   scene_json_doc.c        the JSON document: source positions, messages with file:line:col,
 *                           parse errors, typed getters, key checks with "did you mean"
 *   scene_json_sections.c   plugins, params, materials, cameras, lights, environment
 *   scene_json_nodes.c      nodes (transforms, tags, hierarchy) and meshes (files, primitives)
 * Format: scenes/README.md. */
#ifndef SL_SCENE_JSON_INTERNAL_H
#define SL_SCENE_JSON_INTERNAL_H
#include "fileio.h"
#include "log.h"
#include "scene/scene.h"

#include <cjson/cJSON.h>
#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define MAX_SCENE_FILE_BYTES (64u << 20)
/* Name and key checks are linear scans: bounded counts keep hostile files from taking
 * quadratic time. Far above any hand-written scene. */
#define MAX_ITEMS 20000 /* materials, cameras, lights, nodes (each) */
#define MAX_KEYS 1024   /* keys in one object */

typedef struct pos_entry { const cJSON *item; int line, col; } pos_entry;

typedef struct loader {
    sl_scene *scene;
    const char *text; /* NUL-terminated */
    size_t len;
    const char *file; /* name used in messages */
    const char *data_dir;
    const sl_scene_load_opts *opts; /* the caller's (glTF choices), or NULL */
    char *err;
    size_t err_size;
    bool failed;
    pos_entry *pos;
    size_t pos_count, pos_cap;
    int default_material;
    int *node_lines, *camera_lines; /* line of each scene node/camera (0: imported) */
    int node_lines_n, camera_lines_n;
} loader;

/* Table arguments carry their own length. */
#define KEYS(table) (table), (int)(sizeof(table) / sizeof *(table))

/* scene_json_doc.c */
/* Records the line and column of every key and array element of root (after a successful parse). */
void sj_index_positions(loader *L, const cJSON *root);
bool sj_remember_line(int **lines, int *n, int index, int line);
const char *sj_first_defined(int line, char *buf, size_t size);
int sj_line_of(const loader *L, const cJSON *item);
bool sj_failf(loader *L, const cJSON *at, const char *fmt, ...);
void sj_warnf(loader *L, const cJSON *at, const char *fmt, ...);
const char *sj_nearest(const char *key, const char *const *candidates, int count);
void sj_key_hint(char *out, size_t size, const char *key, const char *const *valid, int count, const char *what);
const char *sj_describe(const cJSON *v, char *buf, size_t size);
bool sj_number_ok(const cJSON *v);
bool sj_get_number(loader *L, const cJSON *v, const char *ctx, float *out, double min, bool min_exclusive, double max);
bool sj_get_int(loader *L, const cJSON *v, const char *ctx, int *out, int min, int max);
bool sj_get_bool(loader *L, const cJSON *v, const char *ctx, bool *out);
bool sj_get_string(loader *L, const cJSON *v, const char *ctx, const char **out);
bool sj_get_vec(loader *L, const cJSON *v, const char *ctx, int n, float *out, bool non_negative);
bool sj_get_direction(loader *L, const cJSON *v, const char *ctx, float out[3]);
bool sj_get_prop(loader *L, const cJSON *v, const char *ctx, sl_prop_list *list);
bool sj_in_list(const char *key, const char *const *list, int count);
bool sj_check_keys(loader *L, const cJSON *obj, const char *ctx, const char *const *valid, int count, bool unknown_is_prop);
bool sj_check_count(loader *L, const cJSON *arr, const char *what);
bool sj_get_name(loader *L, const cJSON *obj, const char *kind, int index, bool required, char *out, size_t size);
bool sj_fail_parse(loader *L, size_t at);

/* scene_json_sections.c */
bool sj_load_plugins(loader *L, const cJSON *arr);
bool sj_load_params(loader *L, const cJSON *obj);
bool sj_load_materials(loader *L, const cJSON *arr);
bool sj_load_cameras(loader *L, const cJSON *arr);
bool sj_load_lights(loader *L, const cJSON *arr);
bool sj_load_environment(loader *L, const cJSON *o);

/* scene_json_nodes.c */
bool sj_load_nodes(loader *L, const cJSON *arr);
#endif
