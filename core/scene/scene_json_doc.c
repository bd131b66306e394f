/* The JSON document under a scene: source positions, messages naming file:line:column, parse
 * errors, typed getters and key checks. See scene_json_internal.h. */
#include "scene/scene_json_internal.h"

/* Remembers the line of scene item `index` in *lines (grown and zero-filled as needed). */
bool sj_remember_line(int **lines, int *n, int index, int line) {
    if (index >= *n) {
        int cap = index + 16;
        int *p = realloc(*lines, sizeof(int) * (size_t)cap);
        if (!p) return false;
        memset(p + *n, 0, sizeof(int) * (size_t)(cap - *n));
        *lines = p, *n = cap;
    }
    (*lines)[index] = line;
    return true;
}

/* " (first defined at line N)" or " (already used by an imported item)" */
const char *sj_first_defined(int line, char *buf, size_t size) {
    if (line > 0) snprintf(buf, size, "first defined at line %d", line);
    else snprintf(buf, size, "already used by an item imported from a mesh file");
    return buf;
}

/* ---- positions -------------------------------------------------------------------------- */

typedef struct scan { const char *s; size_t i, n; int line; size_t line_start; } scan;

static void sc_ws(scan *c) {
    while (c->i < c->n && (unsigned char)c->s[c->i] <= 32 && c->s[c->i] != 0) {
        if (c->s[c->i] == '\n') c->line++, c->line_start = c->i + 1;
        c->i++;
    }
}

static void sc_string(scan *c) {
    c->i++; /* opening quote */
    while (c->i < c->n && c->s[c->i] != '"') {
        if (c->s[c->i] == '\\' && c->i + 1 < c->n) c->i++;
        if (c->s[c->i] == '\n') c->line++, c->line_start = c->i + 1;
        c->i++;
    }
    if (c->i < c->n) c->i++;
}

static void record(loader *L, const cJSON *item, int line, int col) {
    if (L->pos_count == L->pos_cap) {
        size_t cap = L->pos_cap ? L->pos_cap * 2 : 256;
        pos_entry *p = realloc(L->pos, cap * sizeof *p);
        if (!p) return; /* positions are a nicety: without memory, messages say line 0 */
        L->pos = p, L->pos_cap = cap;
    }
    L->pos[L->pos_count++] = (pos_entry){item, line, col};
}

/* Walks the value starting at c->i that cJSON parsed into `item`. line/col > 0: position of
 * the member's key, recorded for the item instead of the value's own position. */
static bool sj_walk(loader *L, scan *c, const cJSON *item, int line, int col) {
    sc_ws(c);
    if (c->i >= c->n) return false;
    int vline = c->line, vcol = (int)(c->i - c->line_start) + 1;
    record(L, item, line > 0 ? line : vline, line > 0 ? col : vcol);
    char ch = c->s[c->i];
    if (ch == '{' || ch == '[') {
        char close = ch == '{' ? '}' : ']';
        c->i++;
        for (const cJSON *child = item->child; child; child = child->next) {
            sc_ws(c);
            int kl = 0, kc = 0;
            if (ch == '{') {
                if (c->i >= c->n || c->s[c->i] != '"') return false;
                kl = c->line, kc = (int)(c->i - c->line_start) + 1;
                sc_string(c);
                sc_ws(c);
                if (c->i >= c->n || c->s[c->i] != ':') return false;
                c->i++;
            }
            if (!sj_walk(L, c, child, kl, kc)) return false;
            sc_ws(c);
            if (c->i < c->n && c->s[c->i] == ',') c->i++;
        }
        sc_ws(c);
        if (c->i >= c->n || c->s[c->i] != close) return false;
        c->i++;
        return true;
    }
    if (ch == '"') {
        sc_string(c);
        return true;
    }
    while (c->i < c->n && (unsigned char)c->s[c->i] > 32 && !strchr(",]}", c->s[c->i])) c->i++;
    return true;
}

static int sj_cmp_pos(const void *a, const void *b) {
    uintptr_t x = (uintptr_t)((const pos_entry *)a)->item, y = (uintptr_t)((const pos_entry *)b)->item;
    return x < y ? -1 : x > y;
}

void sj_index_positions(loader *L, const cJSON *root) {
    scan sc = {L->text, 0, L->len, 1, 0};
    sj_walk(L, &sc, root, 0, 0);
    if (L->pos) qsort(L->pos, L->pos_count, sizeof *L->pos, sj_cmp_pos);
}

static void where(const loader *L, const cJSON *item, int *line, int *col) {
    *line = *col = 0;
    if (!item || !L->pos) return;
    pos_entry key = {item, 0, 0};
    const pos_entry *e = bsearch(&key, L->pos, L->pos_count, sizeof key, sj_cmp_pos);
    if (e) *line = e->line, *col = e->col;
}

int sj_line_of(const loader *L, const cJSON *item) {
    int line, col;
    where(L, item, &line, &col);
    return line;
}

/* ---- messages --------------------------------------------------------------------------- */

bool sj_failf(loader *L, const cJSON *at, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
bool sj_failf(loader *L, const cJSON *at, const char *fmt, ...) {
    if (L->failed) return false; /* keep the first error */
    L->failed = true;
    if (!L->err || !L->err_size) return false;
    int line, col;
    where(L, at, &line, &col);
    int n;
    if (line > 0) n = snprintf(L->err, L->err_size, "%s:%d:%d: ", L->file, line, col);
    else n = snprintf(L->err, L->err_size, "%s: ", L->file);
    if (n < 0) n = 0;
    if ((size_t)n < L->err_size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(L->err + n, L->err_size - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return false;
}

void sj_warnf(loader *L, const cJSON *at, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
void sj_warnf(loader *L, const cJSON *at, const char *fmt, ...) {
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    int line, col;
    where(L, at, &line, &col);
    if (line > 0) SL_WARN("%s:%d:%d: %s", L->file, line, col, msg);
    else SL_WARN("%s: %s", L->file, msg);
}

/* Levenshtein distance, case-insensitive, on at most 64 characters. */
static int edit_distance(const char *a, const char *b) {
    size_t la = strlen(a), lb = strlen(b);
    if (la > 64) la = 64;
    if (lb > 64) lb = 64;
    int row[65];
    for (size_t j = 0; j <= lb; j++) row[j] = (int)j;
    for (size_t i = 1; i <= la; i++) {
        int diag = row[0];
        row[0] = (int)i;
        for (size_t j = 1; j <= lb; j++) {
            int up = row[j];
            int cost = tolower((unsigned char)a[i - 1]) != tolower((unsigned char)b[j - 1]);
            int best = diag + cost;
            if (up + 1 < best) best = up + 1;
            if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[lb];
}

/* The candidate nearest to `key` if it is near enough to be a likely typo, else NULL. */
const char *sj_nearest(const char *key, const char *const *candidates, int count) {
    const char *best = NULL;
    int best_d = INT_MAX;
    for (int i = 0; i < count; i++) {
        int d = edit_distance(key, candidates[i]);
        if (d < best_d) best_d = d, best = candidates[i];
    }
    int klen = (int)strlen(key);
    int limit = klen <= 3 ? 1 : klen <= 6 ? 2 : 3;
    if (best && best_d <= limit) return best;
    /* a prefix is a good hint too: "fov" → "fov_y" */
    for (int i = 0; i < count; i++)
        if (klen >= 3 && strncasecmp(candidates[i], key, (size_t)klen) == 0) return candidates[i];
    return NULL;
}

static void join_list(char *out, size_t size, const char *const *items, int count) {
    size_t used = 0;
    out[0] = 0;
    for (int i = 0; i < count && used < size; i++) {
        int w = snprintf(out + used, size - used, "%s%s", i ? ", " : "", items[i]);
        if (w < 0) break;
        used += (size_t)w;
    }
}

/* " (did you mean 'x'?)" or " (valid keys: a, b, c)" */
void sj_key_hint(char *out, size_t size, const char *key, const char *const *valid, int count,
                     const char *what) {
    const char *near = sj_nearest(key, valid, count);
    if (near) {
        snprintf(out, size, " (did you mean '%s'?)", near);
    } else {
        char list[512];
        join_list(list, sizeof list, valid, count);
        snprintf(out, size, " (valid %s: %s)", what, list);
    }
}

/* A short description of what a JSON value is, for "found …". */
const char *sj_describe(const cJSON *v, char *buf, size_t size) {
    if (!v) return "nothing";
    if (cJSON_IsNull(v)) return "null";
    if (cJSON_IsBool(v)) return cJSON_IsTrue(v) ? "true" : "false";
    if (cJSON_IsNumber(v)) {
        snprintf(buf, size, "the number %g", v->valuedouble);
        return buf;
    }
    if (cJSON_IsString(v)) {
        snprintf(buf, size, "the string \"%.40s%s\"", v->valuestring,
                 strlen(v->valuestring) > 40 ? "…" : "");
        return buf;
    }
    if (cJSON_IsArray(v)) {
        int n = cJSON_GetArraySize(v), numbers = 0;
        for (const cJSON *e = v->child; e; e = e->next) numbers += cJSON_IsNumber(e) != 0;
        if (n == 0) snprintf(buf, size, "an empty array");
        else if (n == numbers) snprintf(buf, size, "an array of %d number%s", n, n == 1 ? "" : "s");
        else snprintf(buf, size, "an array of %d value%s, not all numbers", n, n == 1 ? "" : "s");
        return buf;
    }
    if (cJSON_IsObject(v)) return "an object";
    return "an invalid value";
}

/* ---- typed getters ---------------------------------------------------------------------- */

/* All report "<ctx>: "<key>" must be <expected>, found <what>". ctx names the object. */

bool sj_number_ok(const cJSON *v) {
    return cJSON_IsNumber(v) && isfinite(v->valuedouble) && fabs(v->valuedouble) <= FLT_MAX;
}

bool sj_get_number(loader *L, const cJSON *v, const char *ctx, float *out, double min,
                       bool min_exclusive, double max) {
    char buf[96];
    if (!sj_number_ok(v)) {
        if (cJSON_IsNumber(v))
            return sj_failf(L, v, "%s: \"%s\" must be a finite number (at most %g in magnitude), found %s",
                         ctx, v->string, (double)FLT_MAX, sj_describe(v, buf, sizeof buf));
        return sj_failf(L, v, "%s: \"%s\" must be a number, found %s", ctx, v->string,
                     sj_describe(v, buf, sizeof buf));
    }
    double x = v->valuedouble;
    if ((min_exclusive ? !(x > min) : !(x >= min)) || !(x <= max)) {
        char range[96];
        if (max >= FLT_MAX) snprintf(range, sizeof range, "%s %g", min_exclusive ? ">" : "≥", min);
        else snprintf(range, sizeof range, "in %s%g, %g]", min_exclusive ? "(" : "[", min, max);
        return sj_failf(L, v, "%s: \"%s\" must be a number %s, found %g", ctx, v->string, range, x);
    }
    *out = (float)x;
    return true;
}

bool sj_get_int(loader *L, const cJSON *v, const char *ctx, int *out, int min, int max) {
    char buf[96];
    if (!sj_number_ok(v) || v->valuedouble != floor(v->valuedouble))
        return sj_failf(L, v, "%s: \"%s\" must be an integer in [%d, %d], found %s", ctx, v->string,
                     min, max, sj_describe(v, buf, sizeof buf));
    if (v->valuedouble < min || v->valuedouble > max)
        return sj_failf(L, v, "%s: \"%s\" must be an integer in [%d, %d], found %g", ctx, v->string,
                     min, max, v->valuedouble);
    *out = (int)v->valuedouble;
    return true;
}

bool sj_get_bool(loader *L, const cJSON *v, const char *ctx, bool *out) {
    char buf[96];
    if (!cJSON_IsBool(v))
        return sj_failf(L, v, "%s: \"%s\" must be true or false, found %s", ctx, v->string,
                     sj_describe(v, buf, sizeof buf));
    *out = cJSON_IsTrue(v);
    return true;
}

bool sj_get_string(loader *L, const cJSON *v, const char *ctx, const char **out) {
    char buf[96];
    if (!cJSON_IsString(v) || !v->valuestring[0])
        return sj_failf(L, v, "%s: \"%s\" must be a non-empty string, found %s", ctx, v->string,
                     sj_describe(v, buf, sizeof buf));
    *out = v->valuestring;
    return true;
}

/* An array of exactly n finite numbers (each ≥ 0 when non_negative). */
bool sj_get_vec(loader *L, const cJSON *v, const char *ctx, int n, float *out, bool non_negative) {
    char buf[96];
    int count = cJSON_IsArray(v) ? cJSON_GetArraySize(v) : -1;
    bool ok = count == n;
    for (const cJSON *e = ok ? v->child : NULL; e; e = e->next) ok = ok && sj_number_ok(e);
    if (!ok)
        return sj_failf(L, v, "%s: \"%s\" must be an array of %d numbers, found %s", ctx, v->string, n,
                     sj_describe(v, buf, sizeof buf));
    int i = 0;
    for (const cJSON *e = v->child; e; e = e->next, i++) {
        if (non_negative && e->valuedouble < 0)
            return sj_failf(L, v, "%s: \"%s\" must not be negative, found %g in element %d", ctx,
                         v->string, e->valuedouble, i);
        out[i] = (float)e->valuedouble;
    }
    return true;
}

bool sj_get_direction(loader *L, const cJSON *v, const char *ctx, float out[3]) {
    if (!sj_get_vec(L, v, ctx, 3, out, false)) return false;
    double len = sqrt((double)out[0] * out[0] + (double)out[1] * out[1] + (double)out[2] * out[2]);
    if (!(len > 1e-12) || !isfinite(len))
        return sj_failf(L, v, "%s: \"%s\" must be a non-zero vector", ctx, v->string);
    for (int c = 0; c < 3; c++) out[c] = (float)(out[c] / len);
    return true;
}

/* A free-form property: number, bool, string or array of 2–4 numbers. */
bool sj_get_prop(loader *L, const cJSON *v, const char *ctx, sl_prop_list *list) {
    char buf[96];
    int line = sj_line_of(L, v);
    sl_prop *p = NULL;
    if (cJSON_IsNumber(v)) {
        if (!sj_number_ok(v))
            return sj_failf(L, v, "%s: \"%s\" must be a finite number, found %s", ctx, v->string,
                         sj_describe(v, buf, sizeof buf));
        p = sl_prop_set_number(list, v->string, (float)v->valuedouble, line);
    } else if (cJSON_IsBool(v)) {
        p = sl_prop_set_bool(list, v->string, cJSON_IsTrue(v), line);
    } else if (cJSON_IsString(v)) {
        p = sl_prop_set_string(list, v->string, v->valuestring, line);
    } else {
        int n = cJSON_IsArray(v) ? cJSON_GetArraySize(v) : 0;
        bool ok = n >= 2 && n <= 4;
        for (const cJSON *e = ok ? v->child : NULL; e; e = e->next) ok = ok && sj_number_ok(e);
        if (!ok)
            return sj_failf(L, v, "%s: \"%s\" must be a number, true/false, a string or an array of "
                         "2 to 4 finite numbers, found %s", ctx, v->string, sj_describe(v, buf, sizeof buf));
        float f[4];
        int i = 0;
        for (const cJSON *e = v->child; e; e = e->next) f[i++] = (float)e->valuedouble;
        p = sl_prop_set_vec(list, v->string, f, n, line);
    }
    if (!p) return sj_failf(L, v, "out of memory");
    return true;
}

/* ---- key checks ------------------------------------------------------------------------- */

/* A table and its length, counted by the compiler: a key added to a table is never both read and
 * reported as unknown because a hand-written count was not bumped. */

bool sj_in_list(const char *key, const char *const *list, int count) {
    for (int i = 0; i < count; i++)
        if (strcmp(key, list[i]) == 0) return true;
    return false;
}

/* Warns about unknown keys (structural objects) and duplicate keys (any object); fails on an
 * object with more than MAX_KEYS keys. */
bool sj_check_keys(loader *L, const cJSON *obj, const char *ctx, const char *const *valid,
                       int count, bool unknown_is_prop) {
    if (cJSON_GetArraySize(obj) > MAX_KEYS)
        return sj_failf(L, obj, "%s has %d keys; at most %d are allowed", ctx, cJSON_GetArraySize(obj), MAX_KEYS);
    for (const cJSON *k = obj->child; k; k = k->next) {
        for (const cJSON *e = obj->child; e != k; e = e->next)
            if (strcmp(e->string, k->string) == 0) {
                sj_warnf(L, k, "%s: duplicate key \"%s\" (the first one, line %d, is used)", ctx,
                      k->string, sj_line_of(L, e));
                break;
            }
        if (strcmp(k->string, "comment") == 0 || sj_in_list(k->string, valid, count)) continue;
        if (!unknown_is_prop) {
            char hint[600];
            sj_key_hint(hint, sizeof hint, k->string, valid, count, "keys");
            sj_warnf(L, k, "%s: unknown key \"%s\" ignored%s", ctx, k->string, hint);
        } else {
            /* kept as a property for the plugins, but a near miss of a base key is a typo */
            const char *near = sj_nearest(k->string, valid, count);
            if (near && strlen(k->string) >= 4)
                sj_warnf(L, k, "%s: \"%s\" is kept as a plugin property; did you mean '%s'?", ctx,
                      k->string, near);
        }
    }
    return true;
}

bool sj_check_count(loader *L, const cJSON *arr, const char *what) {
    int n = cJSON_GetArraySize(arr);
    if (n > MAX_ITEMS) return sj_failf(L, arr, "\"%s\" has %d entries; at most %d are allowed", what, n, MAX_ITEMS);
    return true;
}

/* Names: non-empty strings without control characters, at most 255 bytes. */
bool sj_get_name(loader *L, const cJSON *obj, const char *kind, int index, bool required,
                     char *out, size_t size) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "name");
    if (!v) {
        if (required) return sj_failf(L, obj, "%s #%d has no \"name\" (every %s needs one)", kind, index, kind);
        snprintf(out, size, "%s%d", kind, index);
        return true;
    }
    char ctx[64], buf[96];
    snprintf(ctx, sizeof ctx, "%s #%d", kind, index);
    if (!cJSON_IsString(v) || !v->valuestring[0])
        return sj_failf(L, v, "%s: \"name\" must be a non-empty string, found %s", ctx,
                     sj_describe(v, buf, sizeof buf));
    if (strlen(v->valuestring) >= size || strlen(v->valuestring) > 255)
        return sj_failf(L, v, "%s: \"name\" is longer than 255 bytes", ctx);
    for (const char *c = v->valuestring; *c; c++)
        if ((unsigned char)*c < 32)
            return sj_failf(L, v, "%s: \"name\" must not contain control characters", ctx);
    snprintf(out, size, "%s", v->valuestring);
    return true;
}

/* ---- parse errors ----------------------------------------------------------------------- */

/* Why cJSON stopped at `at`: a best guess at the usual mistakes. */
static void parse_cause(const char *text, size_t len, size_t at, char *out, size_t size) {
    size_t first = 0;
    while (first < len && strchr(" \t\r\n", text[first]) && text[first]) first++;
    if (first >= len) {
        snprintf(out, size, "the file is empty (expected a JSON object { … })");
        return;
    }
    /* depth and string state up to `at` */
    int depth = 0, max_depth = 0;
    bool in_string = false;
    char last = 0; /* last significant character before `at` */
    for (size_t i = 0; i < at && i < len; i++) {
        char c = text[i];
        if (in_string) {
            if (c == '\\') i++;
            else if (c == '"') in_string = false, last = '"';
            continue;
        }
        if (c == '"') in_string = true;
        else if (c == '{' || c == '[') depth++;
        else if (c == '}' || c == ']') depth--;
        if (depth > max_depth) max_depth = depth;
        if ((unsigned char)c > 32) last = c;
    }
    char c = at < len ? text[at] : 0;
    if (max_depth >= CJSON_NESTING_LIMIT - 1)
        snprintf(out, size, "nested deeper than %d levels", CJSON_NESTING_LIMIT);
    else if (in_string || (c == 0 && last == '"' && at >= len))
        snprintf(out, size, "unterminated string");
    else if (at < len && c == 0)
        snprintf(out, size, "unexpected byte 0x00 (a NUL byte: is this a binary file?)");
    else if (at >= len)
        snprintf(out, size, "unexpected end of file (%d unclosed '{' or '[')", depth > 0 ? depth : 1);
    else if (c == '"') {
        size_t i = at + 1;
        while (i < len && text[i] != '"' && text[i] != '\n') i += text[i] == '\\' ? 2 : 1;
        if (i >= len || text[i] == '\n') snprintf(out, size, "unterminated string");
        else if (last && !strchr("{[,:", last)) snprintf(out, size, "missing ',' before this value");
        else snprintf(out, size, "invalid string (bad escape sequence or control character?)");
    } else if (c == '/')
        snprintf(out, size, "comments are not allowed in JSON (use a \"comment\" key)");
    else if (c == '\'')
        snprintf(out, size, "strings and keys must use double quotes");
    else if ((c == '}' || c == ']') && last == ',')
        snprintf(out, size, "trailing comma before '%c'", c);
    else if ((c == '}' || c == ']' || c == ',') && last == ':')
        snprintf(out, size, "missing value after ':'");
    else if (depth == 0 && at > first)
        snprintf(out, size, "unexpected text after the end of the top-level object");
    else if (c == 'N' || c == 'I' || (c == '-' && at + 1 < len && text[at + 1] == 'I'))
        snprintf(out, size, "NaN and Infinity are not JSON numbers");
    else if ((c == '"' || isalnum((unsigned char)c) || c == '-' || c == '{' || c == '[') &&
             last && !strchr("{[,:", last))
        snprintf(out, size, "missing ',' before this value");
    else if (isalpha((unsigned char)c))
        snprintf(out, size, "unexpected '%c' (keys and strings must be quoted; the literals are "
                 "true, false and null)", c);
    else if ((unsigned char)c < 32 || (unsigned char)c >= 127)
        snprintf(out, size, "unexpected byte 0x%02x", (unsigned char)c);
    else
        snprintf(out, size, "unexpected '%c'", c);
}

bool sj_fail_parse(loader *L, size_t at) {
    /* cJSON skips every byte < 32 as whitespace; JSON allows only space, tab, CR and LF, so a
     * stray control byte before the failure point is the likelier culprit. */
    bool in_string = false;
    for (size_t i = 0; i < at && i < L->len; i++) {
        char c = L->text[i];
        if (in_string) {
            if (c == '\\') i++;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if ((unsigned char)c < 32 && !strchr("\t\r\n", c)) {
            at = i;
            break;
        }
    }
    /* Where cJSON expected a string (a key after '{' or ',') it reports the byte AFTER the
     * offending one: step back onto it. */
    if (at > 0 && at <= L->len) {
        char culprit = L->text[at - 1];
        size_t j = at - 1;
        while (j > 0 && strchr(" \t\r\n", L->text[j - 1])) j--;
        char before = j > 0 ? L->text[j - 1] : 0;
        /* innermost open bracket before the culprit: only objects expect keys */
        char stack[CJSON_NESTING_LIMIT + 2];
        int depth = 0;
        bool str = false;
        for (size_t i = 0; i + 1 < at; i++) {
            char c = L->text[i];
            if (str) {
                if (c == '\\') i++;
                else if (c == '"') str = false;
            } else if (c == '"') {
                str = true;
            } else if ((c == '{' || c == '[') && depth < CJSON_NESTING_LIMIT + 1) {
                stack[depth++] = c;
            } else if ((c == '}' || c == ']') && depth > 0) {
                depth--;
            }
        }
        bool in_object = depth > 0 && stack[depth - 1] == '{';
        if (in_object && !str && culprit != '"' && !strchr(" \t\r\n,{[:", culprit) &&
            (before == '{' || before == ','))
            at--;
    }
    int line = 1;
    size_t line_start = 0;
    for (size_t i = 0; i < at && i < L->len; i++)
        if (L->text[i] == '\n') line++, line_start = i + 1;
    char cause[256];
    parse_cause(L->text, L->len, at, cause, sizeof cause);
    /* the offending line with a caret under the column */
    size_t end = line_start;
    while (end < L->len && L->text[end] != '\n' && end - line_start < 100) end++;
    size_t col = at - line_start;
    char snippet[256] = "";
    if (end > line_start && col <= end - line_start) {
        char caret[128];
        size_t n = col < sizeof caret - 2 ? col : sizeof caret - 2;
        for (size_t i = 0; i < n; i++) caret[i] = L->text[line_start + i] == '\t' ? '\t' : ' ';
        caret[n] = '^', caret[n + 1] = 0;
        snprintf(snippet, sizeof snippet, "\n    %.*s\n    %s", (int)(end - line_start),
                 L->text + line_start, caret);
    }
    L->failed = true;
    if (L->err && L->err_size)
        snprintf(L->err, L->err_size, "%s:%d:%zu: malformed JSON: %s%s", L->file, line, col + 1,
                 cause, snippet);
    return false;
}

