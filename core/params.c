#include "params.h"
#include <cjson/cJSON.h>
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static char *dupstr(const char *s) { return s ? strdup(s) : NULL; }

void sl_params_init(sl_params *p) { memset(p, 0, sizeof *p); }

static void free_desc(sl_param_desc *d) {
    free((char *)d->id);
    free((char *)d->unit);
    free((char *)d->group);
    free((char *)d->description);
    free((char *)d->light_type);
    free((char *)d->material_input);
    free((char *)d->zero_label);
    free((char *)d->default_value.s);
    if (d->enum_values) {
        for (const char *const *e = d->enum_values; *e; e++) free((char *)*e);
        free((void *)d->enum_values);
    }
}

void sl_param_free_item(sl_param *q) {
    free(q->full_id);
    free(q->owner);
    free_desc(&q->desc);
}

void sl_params_free(sl_params *p) {
    for (int i = 0; i < p->count; i++) sl_param_free_item(&p->items[i]);
    free(p->items);
    memset(p, 0, sizeof *p);
}

static bool valid_id(const char *id) {
    if (!id || !*id) return false;
    for (const char *c = id; *c; c++)
        if (!(islower((unsigned char)*c) || isdigit((unsigned char)*c) || *c == '_')) return false;
    return true;
}

sl_param *sl_params_find(sl_params *p, const char *full_id) {
    for (int i = 0; i < p->count; i++)
        if (p->items[i].desc.scope == SL_SCOPE_GLOBAL && !strcmp(p->items[i].full_id, full_id))
            return &p->items[i];
    return NULL;
}

sl_param *sl_params_find_key(sl_params *p, sl_param_scope scope, const char *key, const char *light_type) {
    for (int i = 0; i < p->count; i++) {
        sl_param *q = &p->items[i];
        if (q->desc.scope != scope || strcmp(q->full_id, key)) continue;
        if (scope == SL_SCOPE_LIGHT && q->desc.light_type && light_type &&
            strcmp(q->desc.light_type, light_type))
            continue;
        return q;
    }
    return NULL;
}

sl_status sl_params_add(sl_params *p, const char *owner, const sl_param_desc *in, char *err, size_t n) {
    sl_param_desc d = {0};
    memcpy(&d, in, in->struct_size < sizeof d ? in->struct_size : sizeof d); /* zero-fill newer fields */
    if (!valid_id(d.id)) {
        snprintf(err, n, "parameter id \"%s\" must be non-empty [a-z0-9_]", d.id ? d.id : "(null)");
        return SL_ERR_INVALID;
    }
    if (d.type < SL_PARAM_BOOL || d.type > SL_PARAM_TEXTURE) {
        snprintf(err, n, "parameter \"%s\": unknown type %d", d.id, (int)d.type);
        return SL_ERR_INVALID;
    }
    if (d.type == SL_PARAM_TEXTURE && d.scope != SL_SCOPE_MATERIAL) {
        snprintf(err, n, "parameter \"%s\": textures are material keys only", d.id);
        return SL_ERR_INVALID;
    }
    int nenum = 0;
    if (d.type == SL_PARAM_ENUM) {
        while (d.enum_values && d.enum_values[nenum]) nenum++;
        if (nenum == 0) {
            snprintf(err, n, "parameter \"%s\": enum without enum_values", d.id);
            return SL_ERR_INVALID;
        }
    }
    if (d.scope == SL_SCOPE_LIGHT && (d.light_slot < 0 || d.light_slot > 7)) {
        snprintf(err, n, "light key \"%s\": light_slot %d outside 0..7", d.id, d.light_slot);
        return SL_ERR_INVALID;
    }
    char full[256];
    if (d.scope == SL_SCOPE_GLOBAL) snprintf(full, sizeof full, "%s.%s", owner, d.id);
    else snprintf(full, sizeof full, "%s", d.id);
    if (d.scope == SL_SCOPE_GLOBAL) {
        if (sl_params_find(p, full)) {
            snprintf(err, n, "parameter \"%s\" registered twice", full);
            return SL_ERR_DUPLICATE;
        }
    } else {
        sl_param *prev = sl_params_find_key(p, d.scope, full, d.light_type);
        if (prev && (prev->desc.light_type == NULL) == (d.light_type == NULL)) {
            if (prev->desc.type != d.type) {
                snprintf(err, n, "%s key \"%s\" declared by %s as another type than by %s",
                         d.scope == SL_SCOPE_MATERIAL ? "material" : "light", full, owner, prev->owner);
                return SL_ERR_DUPLICATE;
            }
            /* shared vocabulary: first declaration's schema stands (a later declarer may name
             * the standard material input the first did not) */
            if (!prev->desc.material_input && d.material_input) prev->desc.material_input = dupstr(d.material_input);
            return SL_OK;
        }
    }
    if (p->count == p->cap) {
        p->cap = p->cap ? p->cap * 2 : 64;
        p->items = realloc(p->items, p->cap * sizeof *p->items);
    }
    sl_param *q = &p->items[p->count++];
    memset(q, 0, sizeof *q);
    q->full_id = strdup(full);
    q->owner = strdup(owner);
    q->desc = d;
    q->desc.struct_size = sizeof(sl_param_desc);
    q->desc.id = dupstr(d.id);
    q->desc.unit = dupstr(d.unit);
    q->desc.group = dupstr(d.group);
    q->desc.description = dupstr(d.description);
    q->desc.light_type = dupstr(d.light_type);
    q->desc.material_input = dupstr(d.material_input);
    q->desc.zero_label = dupstr(d.zero_label);
    q->desc.default_value.s = dupstr(d.default_value.s);
    if (nenum) {
        const char **e = calloc(nenum + 1, sizeof *e);
        for (int i = 0; i < nenum; i++) e[i] = strdup(d.enum_values[i]);
        q->desc.enum_values = e;
    }
    q->value = q->desc.default_value;
    q->source = SL_SRC_DEFAULT;
    return SL_OK;
}

static bool parse_floats(const char *text, float *out, int count) {
    const char *s = text;
    for (int i = 0; i < count; i++) {
        char *end;
        out[i] = strtof(s, &end);
        if (end == s || !isfinite(out[i])) return false;
        s = end;
        while (isspace((unsigned char)*s)) s++;
        if (i + 1 < count) {
            if (*s != ',') return false;
            s++;
        }
    }
    return *s == 0;
}

bool sl_param_parse(const sl_param *param, const char *text, sl_value *out, char *err, size_t n) {
    const sl_param_desc *d = &param->desc;
    sl_value v = {0};
    bool ranged = d->min != d->max;
    switch (d->type) {
    case SL_PARAM_BOOL:
        if (!strcasecmp(text, "true") || !strcmp(text, "1") || !strcasecmp(text, "on") || !strcasecmp(text, "yes")) v.b = true;
        else if (!strcasecmp(text, "false") || !strcmp(text, "0") || !strcasecmp(text, "off") || !strcasecmp(text, "no")) v.b = false;
        else { snprintf(err, n, "%s: \"%s\" is not a boolean (true/false, on/off, 1/0)", param->full_id, text); return false; }
        break;
    case SL_PARAM_INT: {
        char *end;
        long x = strtol(text, &end, 10);
        if (end == text || *end) { snprintf(err, n, "%s: \"%s\" is not an integer", param->full_id, text); return false; }
        if (ranged && (x < d->min || x > d->max)) {
            snprintf(err, n, "%s: %ld is outside the valid range [%g, %g]%s%s", param->full_id, x, d->min, d->max,
                     d->unit && *d->unit ? " " : "", d->unit ? d->unit : "");
            return false;
        }
        v.i = (int)x;
        break;
    }
    case SL_PARAM_FLOAT: {
        char *end;
        float x = strtof(text, &end);
        if (end == text || *end || !isfinite(x)) { snprintf(err, n, "%s: \"%s\" is not a finite number", param->full_id, text); return false; }
        if (ranged && (x < d->min || x > d->max)) {
            snprintf(err, n, "%s: %g is outside the valid range [%g, %g]%s%s", param->full_id, x, d->min, d->max,
                     d->unit && *d->unit ? " " : "", d->unit ? d->unit : "");
            return false;
        }
        v.f[0] = x;
        break;
    }
    case SL_PARAM_ENUM: {
        int i = 0;
        for (; d->enum_values[i]; i++)
            if (!strcmp(d->enum_values[i], text)) break;
        if (!d->enum_values[i]) {
            char names[512] = "";
            for (int k = 0; d->enum_values[k]; k++) {
                size_t u = strlen(names);
                snprintf(names + u, sizeof names - u, "%s%s", k ? ", " : "", d->enum_values[k]);
            }
            snprintf(err, n, "%s: \"%s\" is not one of: %s", param->full_id, text, names);
            return false;
        }
        v.i = i;
        break;
    }
    case SL_PARAM_COLOR:
    case SL_PARAM_VEC3:
        if (!parse_floats(text, v.f, 3)) {
            snprintf(err, n, "%s: \"%s\" is not three comma-separated numbers (r,g,b)", param->full_id, text);
            return false;
        }
        if (d->type == SL_PARAM_COLOR && (v.f[0] < 0 || v.f[1] < 0 || v.f[2] < 0)) {
            snprintf(err, n, "%s: colour components must be >= 0 (linear RGB)", param->full_id);
            return false;
        }
        /* a colour beyond what a pixel can hold (RGBA16F: 65504) means nothing and overflows shading */
        if (d->type == SL_PARAM_COLOR && (v.f[0] > 65504 || v.f[1] > 65504 || v.f[2] > 65504)) {
            snprintf(err, n, "%s: colour components must be <= 65504 (the largest value a pixel holds)", param->full_id);
            return false;
        }
        break;
    case SL_PARAM_TEXTURE:
        v.s = text; /* caller copies */
        break;
    }
    *out = v;
    return true;
}

bool sl_params_set_value(sl_params *p, sl_param *q, sl_value v, sl_param_source src) {
    if (src < q->source && q->source != SL_SRC_DEFAULT) return false; /* lower precedence */
    bool changed = memcmp(&q->value, &v, sizeof v) != 0;
    q->value = v;
    q->source = src;
    if (changed) {
        p->version++;
        if (q->desc.flags & SL_PARAM_NEEDS_RECOMPILE) p->recompile_version++;
    }
    return true;
}

const char *sl_params_nearest(sl_params *p, sl_param_scope scope, const char *id) {
    const char *best = NULL;
    int best_d = 1 << 30;
    for (int i = 0; i < p->count; i++) {
        if (p->items[i].desc.scope != scope) continue;
        int d = sl_levenshtein(id, p->items[i].full_id);
        if (d < best_d) { best_d = d; best = p->items[i].full_id; }
    }
    return best;
}

const char *sl_params_nearest_light_key(sl_params *p, const char *key, const char *light_type) {
    const char *best = NULL;
    int best_d = 1 << 30;
    for (int i = 0; i < p->count; i++) {
        const sl_param *q = &p->items[i];
        if (q->desc.scope != SL_SCOPE_LIGHT || !strcmp(q->desc.id, key)) continue;
        if (q->desc.light_type && light_type && strcmp(q->desc.light_type, light_type)) continue;
        int d = sl_levenshtein(key, q->desc.id);
        if (d < best_d) { best_d = d; best = q->desc.id; }
    }
    return best;
}

bool sl_params_set(sl_params *p, const char *full_id, const char *text, sl_param_source src, char *err, size_t n) {
    sl_param *q = sl_params_find(p, full_id);
    if (!q) {
        const char *near = sl_params_nearest(p, SL_SCOPE_GLOBAL, full_id);
        snprintf(err, n, "unknown parameter \"%s\"%s%s%s (see --dump-params)", full_id,
                 near ? "; did you mean \"" : "", near ? near : "", near ? "\"?" : "");
        return false;
    }
    sl_value v;
    if (!sl_param_parse(q, text, &v, err, n)) return false;
    sl_params_set_value(p, q, v, src);
    return true;
}

void sl_param_format(const sl_param *q, const sl_value *v, char *buf, size_t n) {
    switch (q->desc.type) {
    case SL_PARAM_BOOL: snprintf(buf, n, "%s", v->b ? "true" : "false"); break;
    case SL_PARAM_INT: snprintf(buf, n, "%d", v->i); break;
    case SL_PARAM_FLOAT: snprintf(buf, n, "%g", v->f[0]); break;
    case SL_PARAM_ENUM: snprintf(buf, n, "%s", q->desc.enum_values[v->i]); break;
    case SL_PARAM_COLOR:
    case SL_PARAM_VEC3: snprintf(buf, n, "%g,%g,%g", v->f[0], v->f[1], v->f[2]); break;
    case SL_PARAM_TEXTURE: snprintf(buf, n, "%s", v->s ? v->s : ""); break;
    }
}

static cJSON *value_json(const sl_param *q, const sl_value *v) {
    switch (q->desc.type) {
    case SL_PARAM_BOOL: return cJSON_CreateBool(v->b);
    case SL_PARAM_INT: return cJSON_CreateNumber(v->i);
    case SL_PARAM_FLOAT: return cJSON_CreateNumber(v->f[0]);
    case SL_PARAM_ENUM: return cJSON_CreateString(q->desc.enum_values[v->i]);
    case SL_PARAM_COLOR:
    case SL_PARAM_VEC3: return cJSON_CreateFloatArray(v->f, 3);
    case SL_PARAM_TEXTURE: return v->s ? cJSON_CreateString(v->s) : cJSON_CreateNull();
    }
    return cJSON_CreateNull();
}

void sl_params_dump_json(sl_params *p, FILE *f) {
    static const char *types[] = {"", "bool", "int", "float", "enum", "color", "vec3", "texture"};
    static const char *scopes[] = {"global", "material", "light"};
    cJSON *root = cJSON_CreateArray();
    for (int i = 0; i < p->count; i++) {
        const sl_param *q = &p->items[i];
        cJSON *o = cJSON_CreateObject();
        char addr[300];
        if (q->desc.scope == SL_SCOPE_GLOBAL) snprintf(addr, sizeof addr, "%s", q->full_id);
        else snprintf(addr, sizeof addr, "%s.<NAME>.%s", q->desc.scope == SL_SCOPE_MATERIAL ? "material" : "light", q->full_id);
        cJSON_AddStringToObject(o, "id", addr);
        cJSON_AddStringToObject(o, "plugin", q->owner);
        cJSON_AddStringToObject(o, "scope", scopes[q->desc.scope]);
        cJSON_AddStringToObject(o, "type", types[q->desc.type]);
        cJSON_AddItemToObject(o, "default", value_json(q, &q->desc.default_value));
        if (q->desc.scope == SL_SCOPE_GLOBAL) cJSON_AddItemToObject(o, "value", value_json(q, &q->value));
        if (q->desc.min != q->desc.max) {
            cJSON_AddNumberToObject(o, "min", q->desc.min);
            cJSON_AddNumberToObject(o, "max", q->desc.max);
        }
        if (q->desc.step) cJSON_AddNumberToObject(o, "step", q->desc.step);
        if (q->desc.unit) cJSON_AddStringToObject(o, "unit", q->desc.unit);
        if (q->desc.zero_label) cJSON_AddStringToObject(o, "zero_label", q->desc.zero_label);
        if (q->desc.group) cJSON_AddStringToObject(o, "group", q->desc.group);
        if (q->desc.description) cJSON_AddStringToObject(o, "description", q->desc.description);
        if (q->desc.enum_values) {
            cJSON *e = cJSON_AddArrayToObject(o, "values");
            for (const char *const *s = q->desc.enum_values; *s; s++) cJSON_AddItemToArray(e, cJSON_CreateString(*s));
        }
        if (q->desc.light_type) cJSON_AddStringToObject(o, "light_type", q->desc.light_type);
        if (q->desc.material_input) cJSON_AddStringToObject(o, "material_input", q->desc.material_input);
        cJSON *flags = cJSON_AddArrayToObject(o, "flags");
        if (q->desc.flags & SL_PARAM_NEEDS_RECOMPILE) cJSON_AddItemToArray(flags, cJSON_CreateString("needs_recompile"));
        if (q->desc.flags & SL_PARAM_QUALITY_KNOB) cJSON_AddItemToArray(flags, cJSON_CreateString("quality_knob"));
        if (q->desc.flags & SL_PARAM_LINEAR_DATA) cJSON_AddItemToArray(flags, cJSON_CreateString("linear_data"));
        if (q->desc.flags & SL_PARAM_HIDDEN) cJSON_AddItemToArray(flags, cJSON_CreateString("hidden"));
        cJSON_AddItemToArray(root, o);
    }
    char *s = cJSON_Print(root);
    fprintf(f, "%s\n", s);
    free(s);
    cJSON_Delete(root);
}

int sl_levenshtein(const char *a, const char *b) {
    size_t la = strlen(a), lb = strlen(b);
    if (la > 255 || lb > 255) return 1 << 20;
    int row[256];
    for (size_t j = 0; j <= lb; j++) row[j] = (int)j;
    for (size_t i = 1; i <= la; i++) {
        int prev = row[0];
        row[0] = (int)i;
        for (size_t j = 1; j <= lb; j++) {
            int cur = row[j];
            int cost = a[i - 1] != b[j - 1];
            int m = row[j] + 1;
            if (row[j - 1] + 1 < m) m = row[j - 1] + 1;
            if (prev + cost < m) m = prev + cost;
            row[j] = m;
            prev = cur;
        }
    }
    return row[lb];
}
