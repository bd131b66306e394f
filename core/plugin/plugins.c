#include "plugin/plugins.h"
#include "log.h"
#include <ctype.h>
#include <dlfcn.h>
#include <errno.h>
#include <libgen.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---------------------------------------------------------------- registrations --------- */
/* Called by the host module (core/host) on behalf of plugin `owner` during its create(). */

static bool in_create(sl_plugins *P, int owner, const char *what) {
    if (!P->items[owner]->creating) {
        SL_ERROR("%s: %s may only be called from create()", P->items[owner]->id, what);
        return false;
    }
    return true;
}

/* Does the NULL-terminated list hold s? */
static bool listed(const char *const *list, const char *s) {
    for (int k = 0; list && list[k] && k < 256; k++)
        if (!strcmp(list[k], s)) return true;
    return false;
}

/* A plugin loaded from a file is found for an imported material by its descriptor's
 * material_inputs (read without create()), so that list and the material_input of its keys must
 * be the same set: a key's input the list lacks is refused here, a listed input no key takes in
 * create_one. (The built-in core is never searched for; its keys alone declare its inputs.) */
static bool material_input_listed(const sl_plugin_rec *r, const sl_param_desc *d) {
    const char *input = d->struct_size >= offsetof(sl_param_desc, material_input) + sizeof(char *) ? d->material_input : NULL;
    if (!r->dl || d->scope != SL_SCOPE_MATERIAL || !input || listed(r->desc.material_inputs, input)) return true;
    SL_ERROR("%s: material key %s takes the material input \"%s\", which its descriptor's material_inputs does not list "
             "(imported materials find plugins by that list)", r->id, d->id ? d->id : "?", input);
    return false;
}

sl_status sl_plugins_add_param(sl_plugins *P, int owner, const sl_param_desc *d) {
    if (!in_create(P, owner, "add_param")) return SL_ERR_INVALID;
    if (!material_input_listed(P->items[owner], d)) return SL_ERR_INVALID;
    char err[512];
    sl_status st = sl_params_add(P->params, P->items[owner]->id, d, err, sizeof err);
    if (st != SL_OK) {
        SL_ERROR("%s: %s", P->items[owner]->id, err);
        return st;
    }
    /* remember every declarer of a shared key: its uniform is declared for any of them */
    sl_params *pp = P->params;
    sl_param *q = d->scope == SL_SCOPE_GLOBAL ? NULL : sl_params_find_key(pp, d->scope, d->id, d->light_type);
    if (q) q->declared_by |= 1ull << (owner & 63);
    return st;
}

static char *dup0(const char *s) { return s ? strdup(s) : NULL; }

/* The host finds the plugin that provides a model by its descriptor's shading_models (ABI 1.15,
 * read without create()), so that list and its SHADING_MODEL chunks must be the same set: a chunk
 * the list lacks is refused here, a listed model no chunk provides in create_one. Plugins built
 * for an older ABI have no list and are not checked; neither is the built-in core. */
static bool declares_models(const sl_plugin_rec *r) { return r->dl && r->desc.abi_minor >= 15; }

static bool model_listed(const sl_plugin_rec *r, const sl_shader_chunk_desc *d) {
    if (d->hook != SL_HOOK_SHADING_MODEL || !declares_models(r) || listed(r->desc.shading_models, d->name)) return true;
    SL_ERROR("%s: shading model \"%s\" is not in its descriptor's shading_models (the host names the plugin that "
             "provides a model by that list)", r->id, d->name);
    return false;
}

sl_status sl_plugins_add_chunk(sl_plugins *P, int owner, const sl_shader_chunk_desc *in) {
    if (!in_create(P, owner, "add_shader_chunk")) return SL_ERR_INVALID;
    sl_shader_chunk_desc d = {0};
    memcpy(&d, in, in->struct_size < sizeof d ? in->struct_size : sizeof d);
    const char *id = P->items[owner]->id;
    if (d.hook < SL_HOOK_VERTEX || d.hook > SL_HOOK_SCENE_BEHIND) {
        SL_ERROR("%s: shader chunk %s: unknown hook %d", id, d.file ? d.file : "?", (int)d.hook);
        return SL_ERR_INVALID;
    }
    if (!d.file || (d.hook != SL_HOOK_LIBRARY && !d.function)) {
        SL_ERROR("%s: shader chunk needs a file and (except LIBRARY) a function", id);
        return SL_ERR_INVALID;
    }
    if (d.when_node_tag && d.hook != SL_HOOK_VERTEX) {
        SL_ERROR("%s: shader chunk %s: when_node_tag is for VERTEX hooks only", id, d.file);
        return SL_ERR_INVALID;
    }
    bool gated = d.hook == SL_HOOK_VERTEX || d.hook == SL_HOOK_SURFACE || d.hook == SL_HOOK_AMBIENT ||
                 d.hook == SL_HOOK_DISPLACEMENT || d.hook == SL_HOOK_SCENE_BEHIND;
    if (d.when_param && !gated) {
        SL_ERROR("%s: shader chunk %s: when_param is for VERTEX, SURFACE, AMBIENT, DISPLACEMENT and SCENE_BEHIND "
                 "hooks only", id, d.file);
        return SL_ERR_INVALID;
    }
    if (d.tess_level && d.hook != SL_HOOK_DISPLACEMENT) {
        SL_ERROR("%s: shader chunk %s: tess_level is for DISPLACEMENT hooks only", id, d.file);
        return SL_ERR_INVALID;
    }
    if ((d.flags & SL_CHUNK_PASS_VIEW) && (d.hook != SL_HOOK_DEBUG_VIEW || !d.resource || !*d.resource)) {
        SL_ERROR("%s: shader chunk %s: SL_CHUNK_PASS_VIEW is for DEBUG_VIEW chunks and needs a resource", id, d.file);
        return SL_ERR_INVALID;
    }
    if (d.resource && !(d.flags & SL_CHUNK_PASS_VIEW)) {
        SL_ERROR("%s: shader chunk %s: resource is for SL_CHUNK_PASS_VIEW views only", id, d.file);
        return SL_ERR_INVALID;
    }
    bool named = d.hook == SL_HOOK_SHADING_MODEL || d.hook == SL_HOOK_MODEL_AMBIENT || d.hook == SL_HOOK_MODEL_LOBES ||
                 d.hook == SL_HOOK_LIGHT || d.hook == SL_HOOK_DEBUG_VIEW || d.hook == SL_HOOK_DEBUG_VIEW_LIGHT;
    if (named && (!d.name || !*d.name)) {
        SL_ERROR("%s: shader chunk %s: this hook needs a name", id, d.file);
        return SL_ERR_INVALID;
    }
    if (!model_listed(P->items[owner], &d)) return SL_ERR_INVALID;
    if (named) {
        for (int i = 0; i < P->chunk_count; i++) {
            sl_chunk_reg *c = &P->chunks[i];
            bool same_kind = c->d.hook == d.hook ||
                             (c->d.hook == SL_HOOK_DEBUG_VIEW && d.hook == SL_HOOK_DEBUG_VIEW_LIGHT) ||
                             (c->d.hook == SL_HOOK_DEBUG_VIEW_LIGHT && d.hook == SL_HOOK_DEBUG_VIEW);
            if (same_kind && !strcmp(c->d.name, d.name)) {
                const char *kind = d.hook == SL_HOOK_SHADING_MODEL ? "shading model"
                                 : d.hook == SL_HOOK_LIGHT ? "light type" : "name";
                SL_ERROR("%s: %s \"%s\" is already provided by plugin %s", id, kind, d.name,
                         P->items[c->owner]->id);
                return SL_ERR_DUPLICATE;
            }
        }
    }
    P->chunks = realloc(P->chunks, (P->chunk_count + 1) * sizeof *P->chunks);
    sl_chunk_reg *r = &P->chunks[P->chunk_count++];
    r->owner = owner;
    r->d = d;
    r->d.struct_size = sizeof d;
    r->d.file = dup0(d.file);
    r->d.function = dup0(d.function);
    r->d.name = dup0(d.name);
    r->d.when_material_has = dup0(d.when_material_has);
    r->d.when_model = dup0(d.when_model);
    r->d.when_node_tag = dup0(d.when_node_tag);
    r->d.tess_level = dup0(d.tess_level);
    r->d.description = dup0(d.description);
    r->d.resource = dup0(d.resource);
    r->d.when_param = dup0(d.when_param);
    return SL_OK;
}

/* The pass's own copies of its inputs and outputs (the plugin's arrays need not outlive the call). */
static void set_pass_io(sl_pass_reg *r, const char *const *inputs, const sl_target_desc *outputs, int output_count) {
    int nin = 0;
    while (inputs && inputs[nin]) nin++;
    r->inputs = calloc(nin + 1, sizeof *r->inputs);
    for (int i = 0; i < nin; i++) r->inputs[i] = strdup(inputs[i]);
    r->d.inputs = r->inputs;
    r->outputs = calloc(output_count ? output_count : 1, sizeof *r->outputs);
    for (int i = 0; i < output_count; i++) {
        r->outputs[i] = outputs[i];
        r->outputs[i].name = strdup(outputs[i].name);
    }
    r->d.outputs = r->outputs;
    r->d.output_count = output_count;
}

sl_status sl_plugins_add_pass(sl_plugins *P, int owner, const sl_pass_desc *in) {
    if (!in_create(P, owner, "add_pass")) return SL_ERR_INVALID;
    sl_pass_desc d = {0};
    memcpy(&d, in, in->struct_size < sizeof d ? in->struct_size : sizeof d);
    const char *id = P->items[owner]->id;
    if (!d.name || !d.execute || d.output_count < 0 || (d.output_count && !d.outputs)) {
        SL_ERROR("%s: pass needs a name, an execute callback and its outputs", id);
        return SL_ERR_INVALID;
    }
    for (int i = 0; i < P->pass_count; i++)
        if (!strcmp(P->passes[i].d.name, d.name)) {
            SL_ERROR("%s: pass \"%s\" already registered by %s", id, d.name, P->items[P->passes[i].owner]->id);
            return SL_ERR_DUPLICATE;
        }
    P->passes = realloc(P->passes, (P->pass_count + 1) * sizeof *P->passes);
    sl_pass_reg *r = &P->passes[P->pass_count++];
    memset(r, 0, sizeof *r);
    r->owner = owner;
    r->d = d;
    r->d.struct_size = sizeof d;
    r->d.name = strdup(d.name);
    set_pass_io(r, d.inputs, d.outputs, d.output_count);
    return SL_OK;
}

static bool same_io(const sl_pass_reg *r, const char *const *inputs, const sl_target_desc *outputs, int output_count) {
    int n = 0;
    for (; inputs && inputs[n]; n++)
        if (!r->inputs[n] || strcmp(r->inputs[n], inputs[n])) return false;
    if (r->inputs[n] || output_count != r->d.output_count) return false;
    for (int i = 0; i < output_count; i++) {
        const sl_target_desc *a = &r->outputs[i], *b = &outputs[i];
        if (!b->name || strcmp(a->name, b->name) || a->format != b->format || a->width != b->width ||
            a->height != b->height || a->scale != b->scale || a->layers != b->layers || a->compare != b->compare)
            return false;
    }
    return true;
}

bool sl_plugins_update_pass_io(sl_plugins *P, int i) {
    sl_pass_reg *r = &P->passes[i];
    if (!r->d.io) return false;
    const char *const *inputs = NULL;
    const sl_target_desc *outputs = NULL;
    int output_count = 0;
    r->d.io(r->d.user, &inputs, &outputs, &output_count);
    if (output_count < 0 || (output_count && !outputs)) {
        SL_ERROR("%s: pass \"%s\": io() gave %d outputs%s; the registered ones are kept", P->items[r->owner]->id,
                 r->d.name, output_count, outputs ? "" : " and no array");
        return false;
    }
    for (int k = 0; k < output_count; k++)
        if (!outputs[k].name) {
            SL_ERROR("%s: pass \"%s\": io() gave an output without a name; the registered ones are kept",
                     P->items[r->owner]->id, r->d.name);
            return false;
        }
    if (same_io(r, inputs, outputs, output_count)) return false;
    for (const char **s = r->inputs; s && *s; s++) free((char *)*s);
    free(r->inputs);
    for (int k = 0; k < r->d.output_count; k++) free((char *)r->outputs[k].name);
    free(r->outputs);
    set_pass_io(r, inputs, outputs, output_count);
    return true;
}

sl_status sl_plugins_add_key(sl_plugins *P, int owner, const sl_key_desc *in) {
    if (!in_create(P, owner, "add_key")) return SL_ERR_INVALID;
    sl_key_desc d = {0};
    memcpy(&d, in, in->struct_size < sizeof d ? in->struct_size : sizeof d);
    if (!d.key || (!d.param && !d.on_press)) {
        SL_ERROR("%s: key binding needs a key and a param or callback", P->items[owner]->id);
        return SL_ERR_INVALID;
    }
    P->keys = realloc(P->keys, (P->key_count + 1) * sizeof *P->keys);
    sl_key_reg *r = &P->keys[P->key_count++];
    r->owner = owner;
    r->d = d;
    r->d.key = strdup(d.key);
    r->d.description = dup0(d.description);
    r->d.param = dup0(d.param);
    return SL_OK;
}

sl_status sl_plugins_set_reference(sl_plugins *P, int owner, const sl_reference_desc *in) {
    if (!in_create(P, owner, "set_reference")) return SL_ERR_INVALID;
    sl_plugin_rec *rec = P->items[owner];
    memset(&rec->reference, 0, sizeof rec->reference);
    memcpy(&rec->reference, in, in->struct_size < sizeof rec->reference ? in->struct_size : sizeof rec->reference);
    rec->reference_settings = dup0(rec->reference.settings);
    rec->reference_description = dup0(rec->reference.description);
    rec->reference.settings = rec->reference_settings;
    rec->reference.description = rec->reference_description;
    rec->has_reference = true;
    return SL_OK;
}

/* The layout of texture units is host.h's (SL_TEXTURE_UNIT_*). The plugin range is 48 units: 16
 * were too few once every bundled plugin is loaded together (aa 5, envmap 6, spotlight-shadow 3,
 * sss 3, phong 1, tonemap 1). */
int sl_plugins_reserve_unit(sl_plugins *P, int owner) {
    if (P->texture_units_used >= SL_TEXTURE_UNIT_PLUGIN_COUNT) {
        SL_ERROR("%s: reserve_texture_unit: all %d plugin texture units are taken (host.h, SL_TEXTURE_UNIT_PLUGIN_COUNT)",
                 P->items[owner]->id, SL_TEXTURE_UNIT_PLUGIN_COUNT);
        return -1;
    }
    return SL_TEXTURE_UNIT_PLUGIN_FIRST + P->texture_units_used++;
}

const void *sl_plugins_extension(const sl_plugins *P, const char *id) {
    for (int i = 0; i < P->count; i++) {
        sl_plugin_rec *r = P->items[i];
        if (!sl_plugin_enabled(P, i) || !r->desc.get_extension) continue;
        const void *e = r->desc.get_extension(r->user, id);
        if (e) return e;
    }
    return NULL;
}

/* ---------------------------------------------------------------- loading --------------- */

int sl_plugins_find(sl_plugins *p, const char *id) {
    for (int i = 0; i < p->count; i++)
        if (!strcmp(p->items[i]->id, id)) return i;
    return -1;
}

/* A plugin runs when it loaded, its own "<id>.enabled" is on and every plugin it requires runs:
 * switching a plugin off switches off what declared that it needs it, so no chunk or pass ever
 * refers to code of a plugin that is off. */
static bool enabled_at(const sl_plugins *P, int index, int depth) {
    sl_plugin_rec *r = P->items[index];
    if (!r->ok) return false;
    if (index == 0) return true; /* the core */
    char id[300];
    snprintf(id, sizeof id, "%s.enabled", r->id);
    sl_param *q = sl_params_find(P->params, id);
    if (q && !q->value.b) return false;
    for (const char *const *req = r->desc.dependencies; req && *req && depth < 16; req++) {
        int j = sl_plugins_find((sl_plugins *)P, *req);
        if (j < 0 || !enabled_at(P, j, depth + 1)) return false;
    }
    return true;
}

bool sl_plugin_enabled(const sl_plugins *P, int index) { return enabled_at(P, index, 0); }

static sl_plugin_rec *new_record(sl_plugins *P, const char *id, const char *requested_by) {
    P->items = realloc(P->items, (P->count + 1) * sizeof *P->items);
    sl_plugin_rec *r = calloc(1, sizeof *r);
    P->items[P->count] = r;
    r->id = strdup(id);
    r->requested_by = strdup(requested_by);
    r->host = P->make_host(P->host_ctx, P->count);
    P->count++;
    return r;
}

static void disable(sl_plugin_rec *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void disable(sl_plugin_rec *r, const char *fmt, ...) {
    char buf[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    free(r->disabled_reason);
    r->disabled_reason = strdup(buf);
    r->ok = false;
    SL_ERROR("plugin %s disabled: %s", r->id, buf);
}

static bool exe_dir(char *out, size_t n) {
    char buf[1024];
    ssize_t len = readlink("/proc/self/exe", buf, sizeof buf - 1);
    if (len <= 0) return false;
    buf[len] = 0;
    snprintf(out, n, "%s", dirname(buf));
    return true;
}

int sl_plugin_search_dirs(char dirs[][1024], int max) {
    int n = 0;
    const char *env = getenv("SHADELAB_PLUGIN_PATH");
    if (env && *env) {
        /* the built-in directories (3) always keep their places: extra entries are dropped, loudly */
        char *copy = strdup(env), *save = NULL;
        int dropped = 0;
        for (char *tok = strtok_r(copy, ":", &save); tok; tok = strtok_r(NULL, ":", &save))
            if (*tok) {
                if (n < max - 3) snprintf(dirs[n++], 1024, "%s", tok);
                else dropped++;
            }
        if (dropped) SL_WARN("SHADELAB_PLUGIN_PATH: %d entries beyond the first %d ignored", dropped, max - 3);
        free(copy);
    }
    char exe[1024];
    if (exe_dir(exe, sizeof exe)) {
        if (n < max) snprintf(dirs[n++], 1024, "%s/plugins", exe);
        if (n < max) snprintf(dirs[n++], 1024, "%s/../%s/shadelab/plugins", exe, SL_INSTALL_LIBDIR);
        /* test binaries live in the build tree's root or tests/: look beside the build root too */
        if (n < max) snprintf(dirs[n++], 1024, "%s/../plugins", exe);
    }
    /* drop duplicates (the same directory reached two ways) */
    int w = 0;
    for (int i = 0; i < n; i++) {
        char *ri = realpath(dirs[i], NULL);
        bool dup = false;
        for (int j = 0; j < w && ri; j++) {
            char *rj = realpath(dirs[j], NULL);
            dup |= rj && !strcmp(ri, rj);
            free(rj);
        }
        free(ri);
        if (!dup) {
            if (w != i) memcpy(dirs[w], dirs[i], 1024);
            w++;
        }
    }
    return w;
}

static bool file_exists(const char *p) {
    struct stat st;
    return stat(p, &st) == 0 && S_ISREG(st.st_mode);
}

/* Turns dlerror() text into the real cause. */
static void describe_dlerror(const char *path, const char *msg, char *out, size_t n) {
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    if (strstr(msg, "undefined symbol")) {
        snprintf(out, n, "missing symbol: %s", strstr(msg, "undefined symbol"));
    } else if (strstr(msg, "cannot open shared object file")) {
        /* "libfoo.so.1: cannot open shared object file" names the dependency first */
        char dep[256];
        snprintf(dep, sizeof dep, "%.*s", (int)strcspn(msg, ":"), msg);
        if (!strstr(dep, base)) snprintf(out, n, "missing dependency library %s (%s)", dep, msg);
        else snprintf(out, n, "cannot open %s (%s)", path, msg);
    } else if (strstr(msg, "invalid ELF header") || strstr(msg, "file too short")) {
        snprintf(out, n, "%s is not a shared library (%s)", path, msg);
    } else {
        snprintf(out, n, "%s", msg);
    }
}

int sl_plugins_load(sl_plugins *P, const char *name, const char *requested_by, bool allow_path) {
    bool is_path = strchr(name, '/') || (strlen(name) > 3 && !strcmp(name + strlen(name) - 3, ".so"));
    if (!is_path) {
        int existing = sl_plugins_find(P, name);
        if (existing >= 0) return existing;
    }
    sl_plugin_rec *r = new_record(P, name, requested_by);
    int index = P->count - 1;
    /* a program's set of plugins is a 64-bit mask (forward.c, sl_forward_variant.owners) */
    if (index >= SL_MAX_PLUGINS) {
        disable(r, "too many plugins: at most %d can be loaded, the core included (plugins.h, SL_MAX_PLUGINS)",
                SL_MAX_PLUGINS);
        return index;
    }
    char path[2048] = "";
    if (is_path) {
        if (!allow_path) {
            disable(r, "a scene may only name plugins, not paths (\"%s\"); use --plugin on the command line", name);
            return index;
        }
        snprintf(path, sizeof path, "%s", name);
        if (!file_exists(path)) {
            struct stat st;
            if (stat(path, &st) != 0) r->not_found = true, disable(r, "plugin file %s does not exist", path);
            else if (S_ISDIR(st.st_mode)) disable(r, "%s is a directory, not a plugin file (name the .so inside it)", path);
            else disable(r, "%s is not a regular file (a device, FIFO or socket), not a plugin", path);
            return index;
        }
    } else {
        for (const char *c = name; *c; c++)
            if (!((*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') || *c == '-' || *c == '_')) {
                char lower[256];
                size_t k = 0;
                for (; name[k] && k + 1 < sizeof lower; k++) lower[k] = (char)tolower((unsigned char)name[k]);
                lower[k] = 0;
                bool valid = true;
                for (const char *l = lower; *l; l++)
                    valid &= (*l >= 'a' && *l <= 'z') || (*l >= '0' && *l <= '9') || *l == '-' || *l == '_';
                r->not_found = true;
                disable(r, "invalid plugin name \"%s\" (lower-case letters, digits, '-' only)%s%s%s", name,
                        valid ? "; did you mean \"" : "", valid ? lower : "", valid ? "\"?" : "");
                return index;
            }
        char dirs[16][1024], looked[4096] = "";
        int nd = sl_plugin_search_dirs(dirs, 16);
        for (int i = 0; i < nd && !path[0]; i++) {
            char cand[2048];
            snprintf(cand, sizeof cand, "%s/%s/%s.so", dirs[i], name, name);
            if (file_exists(cand)) snprintf(path, sizeof path, "%s", cand);
            size_t u = strlen(looked);
            snprintf(looked + u, sizeof looked - u, "%s%s", u ? ", " : "", cand);
        }
        if (!path[0]) {
            r->not_found = true;
            disable(r, "plugin \"%s\" not found; looked for %s (set SHADELAB_PLUGIN_PATH or pass a path)", name, looked);
            return index;
        }
    }
    r->path = realpath(path, NULL);
    if (!r->path) r->path = strdup(path);
    char dir[2048];
    snprintf(dir, sizeof dir, "%s", r->path);
    r->resource_dir = strdup(dirname(dir));

    dlerror();
    r->dl = dlopen(r->path, RTLD_NOW | RTLD_LOCAL);
    if (!r->dl) {
        char why[2048];
        describe_dlerror(r->path, dlerror(), why, sizeof why);
        disable(r, "%s", why);
        return index;
    }
    sl_plugin_entry_fn entry = (sl_plugin_entry_fn)dlsym(r->dl, SL_PLUGIN_ENTRY_SYMBOL);
    if (!entry) {
        disable(r, "%s has no %s() entry symbol (not a shadelab plugin?)", r->path, SL_PLUGIN_ENTRY_SYMBOL);
        return index;
    }
    const sl_plugin_desc *d = entry();
    if (!d) { disable(r, "%s() returned NULL", SL_PLUGIN_ENTRY_SYMBOL); return index; }
    if (d->abi_major != SL_ABI_MAJOR || d->abi_minor > SL_ABI_MINOR) {
        disable(r, "ABI mismatch: plugin built for ABI %u.%u, host provides ABI %u.%u (%s)", d->abi_major,
                d->abi_minor, SL_ABI_MAJOR, SL_ABI_MINOR,
                d->abi_major != SL_ABI_MAJOR ? "major versions must match" : "plugin needs a newer host");
        return index;
    }
    if (d->struct_size < offsetof(sl_plugin_desc, create) + sizeof(void *)) {
        disable(r, "descriptor struct_size %u is too small", d->struct_size);
        return index;
    }
    memcpy(&r->desc, d, d->struct_size < sizeof r->desc ? d->struct_size : sizeof r->desc);
    if (!r->desc.id || !r->desc.create) { disable(r, "descriptor lacks an id or a create callback"); return index; }
    if (strcmp(r->id, r->desc.id)) {
        if (!is_path) {
            disable(r, "file for \"%s\" declares id \"%s\"", name, r->desc.id);
            return index;
        }
        int dup = sl_plugins_find(P, r->desc.id);
        if (dup >= 0 && dup != index) {
            disable(r, "plugin id \"%s\" already loaded from %s", r->desc.id, P->items[dup]->path);
            return index;
        }
        free(r->id);
        r->id = strdup(r->desc.id);
    }
    r->ok = true; /* loaded; create() comes in sl_plugins_create_all */
    return index;
}

bool sl_plugins_add_builtin(sl_plugins *P, const sl_plugin_desc *desc) {
    sl_plugin_rec *r = new_record(P, desc->id, "built-in");
    r->path = strdup("(built-in)");
    r->resource_dir = strdup("");
    r->desc = *desc;
    r->ok = true;
    return true;
}

static void free_chunk(sl_chunk_reg *c) {
    free((char *)c->d.file); free((char *)c->d.function); free((char *)c->d.name);
    free((char *)c->d.when_material_has); free((char *)c->d.description); free((char *)c->d.when_model);
    free((char *)c->d.when_node_tag);
    free((char *)c->d.tess_level);
    free((char *)c->d.resource);
    free((char *)c->d.when_param);
}

static void free_pass(sl_pass_reg *r) {
    free((char *)r->d.name);
    for (const char **s = r->inputs; s && *s; s++) free((char *)*s);
    free(r->inputs);
    for (int k = 0; k < r->d.output_count; k++) free((char *)r->outputs[k].name);
    free(r->outputs);
}

static void free_key(sl_key_reg *k) {
    free((char *)k->d.key); free((char *)k->d.description); free((char *)k->d.param);
}

/* Rolls back everything a plugin registered (its create() failed or was refused). */
static void remove_registrations(sl_plugins *P, int owner) {
    int w = 0;
    for (int i = 0; i < P->chunk_count; i++)
        if (P->chunks[i].owner != owner) P->chunks[w++] = P->chunks[i];
        else free_chunk(&P->chunks[i]);
    P->chunk_count = w;
    w = 0;
    for (int i = 0; i < P->pass_count; i++)
        if (P->passes[i].owner != owner) P->passes[w++] = P->passes[i];
        else free_pass(&P->passes[i]);
    P->pass_count = w;
    w = 0;
    for (int i = 0; i < P->key_count; i++)
        if (P->keys[i].owner != owner) P->keys[w++] = P->keys[i];
        else free_key(&P->keys[i]);
    P->key_count = w;
    sl_params *pp = P->params;
    const char *id = P->items[owner]->id;
    w = 0;
    for (int i = 0; i < pp->count; i++)
        if (strcmp(pp->items[i].owner, id)) pp->items[w++] = pp->items[i];
        else sl_param_free_item(&pp->items[i]);
    pp->count = w;
}

/* The first model plugin i's descriptor lists that none of its chunks provides, or NULL. */
static const char *unprovided_model(const sl_plugins *P, int i) {
    if (!declares_models(P->items[i])) return NULL;
    const char *const *list = P->items[i]->desc.shading_models;
    for (int k = 0; list && list[k] && k < 256; k++) {
        bool provided = false;
        for (int c = 0; c < P->chunk_count && !provided; c++)
            provided = P->chunks[c].owner == i && P->chunks[c].d.hook == SL_HOOK_SHADING_MODEL &&
                       !strcmp(P->chunks[c].d.name, list[k]);
        if (!provided) return list[k];
    }
    return NULL;
}

/* The first when_param (ABI 1.17) of plugin i's chunks that is not one of its bool global
 * parameters declared SL_PARAM_NEEDS_RECOMPILE (a switch that changes which chunks a program
 * holds must recompose it), or NULL. */
static const char *bad_gate_param(const sl_plugins *P, int i) {
    for (int c = 0; c < P->chunk_count; c++) {
        const sl_shader_chunk_desc *d = &P->chunks[c].d;
        if (P->chunks[c].owner != i || !d->when_param) continue;
        char full[300];
        snprintf(full, sizeof full, "%s.%s", P->items[i]->id, d->when_param);
        const sl_param *q = sl_params_find(P->params, full);
        if (!q || q->desc.scope != SL_SCOPE_GLOBAL || q->desc.type != SL_PARAM_BOOL ||
            !(q->desc.flags & SL_PARAM_NEEDS_RECOMPILE))
            return d->when_param;
    }
    return NULL;
}

/* The first input plugin i's descriptor lists that none of its material keys takes, or NULL. */
static const char *unclaimed_input(const sl_plugins *P, int i) {
    const char *const *list = P->items[i]->desc.material_inputs;
    for (int k = 0; list && list[k] && k < 256; k++) {
        bool taken = false;
        for (int j = 0; j < P->params->count && !taken; j++) {
            const sl_param *q = &P->params->items[j];
            taken = q->desc.scope == SL_SCOPE_MATERIAL && (q->declared_by >> (i & 63) & 1) && q->desc.material_input &&
                    !strcmp(q->desc.material_input, list[k]);
        }
        if (!taken) return list[k];
    }
    return NULL;
}

static void create_one(sl_plugins *P, int i, int depth) {
    const char *unclaimed;
    sl_plugin_rec *r = P->items[i];
    if (!r->ok || r->user || depth > 32) return;
    /* conflicts */
    for (const char *const *c = r->desc.conflicts; c && *c; c++) {
        int j = sl_plugins_find(P, *c);
        if (j >= 0 && P->items[j]->ok) {
            disable(r, "conflicts with plugin %s (declared by %s)", *c, r->id);
            return;
        }
    }
    /* requirements first */
    for (const char *const *q = r->desc.dependencies; q && *q; q++) {
        int j = sl_plugins_find(P, *q);
        if (j < 0) {
            char by[300];
            snprintf(by, sizeof by, "required by %s", r->id);
            j = sl_plugins_load(P, *q, by, false);
            r = P->items[i];
        }
        create_one(P, j, depth + 1);
        if (!P->items[j]->ok) {
            disable(r, "requires plugin %s, which is unavailable: %s", *q,
                    P->items[j]->disabled_reason ? P->items[j]->disabled_reason : "not loaded");
            return;
        }
    }
    if (r->user) return;
    /* the automatic on/off parameter */
    if (i != 0) {
        /* NEEDS_RECOMPILE: switching a plugin recomposes every program, so a live toggle gives
         * the frame a fresh start with the same value gives (the toggle matrix test holds it) */
        sl_param_desc en = {.struct_size = sizeof en, .id = "enabled", .type = SL_PARAM_BOOL,
                            .default_value = {.b = true}, .flags = SL_PARAM_NEEDS_RECOMPILE,
                            .description = "Turns the plugin on or off; off costs nothing per frame."};
        char err[256];
        sl_params_add(P->params, r->id, &en, err, sizeof err);
    }
    int before_errors = sl_log_count(SL_LOG_ERROR);
    void *user = NULL;
    r->creating = true;
    sl_status st = r->desc.create(r->host, &user);
    r->creating = false;
    r->user = user ? user : (void *)r; /* non-NULL marks "created" */
    if (st != SL_OK) {
        if (user && r->desc.destroy) r->desc.destroy(user); /* documented in plugin.h */
        remove_registrations(P, i);
        disable(r, "create() failed with status %d (see the messages above)", (int)st);
    } else if (sl_log_count(SL_LOG_ERROR) > before_errors && i != 0) {
        /* a registration was refused (e.g. duplicate shading model): the plugin is unusable */
        if (r->desc.destroy) r->desc.destroy(user);
        remove_registrations(P, i);
        disable(r, "a registration was refused during create() (see the messages above)");
    } else if ((unclaimed = unclaimed_input(P, i))) {
        if (r->desc.destroy) r->desc.destroy(user);
        remove_registrations(P, i);
        disable(r, "its descriptor's material_inputs lists \"%s\", which none of its material keys takes "
                   "(material_input)", unclaimed);
    } else if ((unclaimed = bad_gate_param(P, i))) {
        char gate[128]; /* the chunk's copy goes with its registration */
        snprintf(gate, sizeof gate, "%s", unclaimed);
        if (r->desc.destroy) r->desc.destroy(user);
        remove_registrations(P, i);
        disable(r, "a shader chunk's when_param \"%s\" is not one of its bool global parameters with "
                   "SL_PARAM_NEEDS_RECOMPILE", gate);
    } else if ((unclaimed = unprovided_model(P, i))) {
        if (r->desc.destroy) r->desc.destroy(user);
        remove_registrations(P, i);
        disable(r, "its descriptor's shading_models lists \"%s\", which none of its shading-model chunks provides",
                unclaimed);
    } else {
        r->ok = r->live = true;
    }
}

void sl_plugins_create(sl_plugins *P, int index) { create_one(P, index, 0); }

void sl_plugins_create_all(sl_plugins *P) {
    for (int i = 0; i < P->count; i++) create_one(P, i, 0);
}

void sl_plugins_print(const sl_plugins *P, FILE *f) {
    for (int i = 0; i < P->count; i++) {
        sl_plugin_rec *r = P->items[i];
        const char *state = !r->ok ? "DISABLED" : sl_plugin_enabled(P, i) ? "enabled" : "off";
        fprintf(f, "%-20s %-8s %s%s%s\n", r->id, state, r->path ? r->path : "-",
                r->desc.version ? "  v" : "", r->desc.version ? r->desc.version : "");
        if (r->desc.description && r->ok) fprintf(f, "    %s\n", r->desc.description);
        char models[512];
        sl_plugin_models_text(r->desc.abi_minor >= 15 ? r->desc.shading_models : NULL, models, sizeof models);
        if (*models && r->ok) fprintf(f, "    shading models: %s\n", models);
        if (!r->ok) fprintf(f, "    reason: %s\n", r->disabled_reason ? r->disabled_reason : "?");
        fprintf(f, "    requested by: %s\n", r->requested_by);
    }
    sl_plugin_print_available(P, f);
    char dirs[16][1024];
    int nd = sl_plugin_search_dirs(dirs, 16);
    fprintf(f, "search path:");
    for (int i = 0; i < nd; i++) fprintf(f, " %s", dirs[i]);
    fprintf(f, "\n");
}

void sl_plugins_shutdown(sl_plugins *P) {
    for (int i = P->count - 1; i >= 0; i--) {
        sl_plugin_rec *r = P->items[i];
        if (r->active && r->desc.deactivate) r->desc.deactivate(r->user);
        r->active = false;
        /* r->user == r: create() gave no state (the "created" mark) */
        if (r->live && r->desc.destroy) r->desc.destroy(r->user == (void *)r ? NULL : r->user);
        r->live = false;
        r->user = NULL;
    }
    for (int i = 0; i < P->count; i++) {
        sl_plugin_rec *r = P->items[i];
        if (r->dl) dlclose(r->dl);
        free(r->id); free(r->path); free(r->resource_dir); free(r->requested_by);
        free(r->disabled_reason); free(r->host);
        free(r->reference_settings); free(r->reference_description);
        free(r);
    }
    for (int i = 0; i < P->chunk_count; i++) free_chunk(&P->chunks[i]);
    for (int i = 0; i < P->pass_count; i++) free_pass(&P->passes[i]);
    for (int i = 0; i < P->key_count; i++) free_key(&P->keys[i]);
    free(P->items); free(P->chunks); free(P->passes); free(P->keys);
    memset(P, 0, sizeof *P);
}
