/* The parameter store: every schema entry (globals of the core and plugins, material keys,
 * light keys) and the current values of globals. Per-material and per-light values live with
 * the materials and lights (render/materials.c) but are parsed and validated here. */
#ifndef SL_PARAMS_H
#define SL_PARAMS_H
#include <shadelab/shadelab.h>
#include <stdio.h>

typedef enum sl_param_source { SL_SRC_DEFAULT, SL_SRC_SCENE, SL_SRC_CLI, SL_SRC_GUI } sl_param_source;

typedef struct sl_param {
    char *full_id;          /* "ggx.zero_specular"; material/light keys: the bare key */
    char *owner;            /* plugin id ("core" for the core) */
    sl_param_desc desc;     /* strings owned by the store (copied) */
    sl_value value;         /* globals only */
    sl_param_source source;
    uint64_t declared_by;   /* bit i: plugin i declared this key (shared material/light keys) */
} sl_param;

typedef struct sl_params {
    sl_param *items;
    int count, cap;
    uint64_t version;       /* bumps on every change */
    uint64_t recompile_version; /* bumps when a NEEDS_RECOMPILE value changes */
} sl_params;

void sl_params_init(sl_params *p);
void sl_params_free(sl_params *p);
/* Frees one entry's strings (the array slot itself stays). */
void sl_param_free_item(sl_param *q);
/* Registers a schema entry (copied). Duplicate global ids are SL_ERR_DUPLICATE; a material or
 * light key may be declared by several plugins when the type agrees (shared vocabulary). */
sl_status sl_params_add(sl_params *p, const char *owner, const sl_param_desc *desc, char *err, size_t n);
sl_param *sl_params_find(sl_params *p, const char *full_id);
/* Material/light key schema (light_type NULL matches keys for every light type). */
sl_param *sl_params_find_key(sl_params *p, sl_param_scope scope, const char *key, const char *light_type);
/* Parses text for a schema entry: "true/false/1/0/on/off", numbers, enum names, "r,g,b".
 * Out-of-range or malformed values fail with a message giving the valid range or names. */
bool sl_param_parse(const sl_param *param, const char *text, sl_value *out, char *err, size_t n);
/* Assigns a global "plugin.param=value"; unknown ids get the nearest valid id suggested. */
bool sl_params_set(sl_params *p, const char *full_id, const char *text, sl_param_source src,
                   char *err, size_t n);
bool sl_params_set_value(sl_params *p, sl_param *param, sl_value v, sl_param_source src);
/* Nearest id among the store's globals (or keys of a scope), for "did you mean". */
const char *sl_params_nearest(sl_params *p, sl_param_scope scope, const char *id);
/* The nearest light key (other than key itself) that lights of light_type have. */
const char *sl_params_nearest_light_key(sl_params *p, const char *key, const char *light_type);
/* Value as text ("0.5", "true", "ggx", "0.1,0.2,0.3"). */
void sl_param_format(const sl_param *param, const sl_value *v, char *buf, size_t n);
/* --dump-params: every schema entry as JSON. */
void sl_params_dump_json(sl_params *p, FILE *f);

int sl_levenshtein(const char *a, const char *b);
#endif
