#include "plugin/plugins.h"
#include "app.h"
#include "log.h"
#include "render/renderer.h"
#include <dlfcn.h>
#include <errno.h>
#include <libgen.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define HOST_APP(h) (((const sl_host_impl *)(h))->app)
#define HOST_IDX(h) (((const sl_host_impl *)(h))->plugin)
#define HOST_REC(h) (HOST_APP(h)->plugins.items[HOST_IDX(h)])

/* ---------------------------------------------------------------- host interface -------- */

static void host_log(const sl_host *h, sl_log_level level, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    sl_logv(level, HOST_REC(h)->id, fmt, ap);
    va_end(ap);
}

static const char *host_resource_dir(const sl_host *h) { return HOST_REC(h)->resource_dir; }

static bool in_create(const sl_host *h, const char *what) {
    if (!HOST_REC(h)->creating) {
        SL_ERROR("%s: %s may only be called from create()", HOST_REC(h)->id, what);
        return false;
    }
    return true;
}

static sl_status host_add_param(const sl_host *h, const sl_param_desc *d) {
    if (!in_create(h, "add_param")) return SL_ERR_INVALID;
    char err[512];
    sl_status st = sl_params_add(&HOST_APP(h)->params, HOST_REC(h)->id, d, err, sizeof err);
    if (st != SL_OK) {
        SL_ERROR("%s: %s", HOST_REC(h)->id, err);
        return st;
    }
    /* remember every declarer of a shared key: its uniform is declared for any of them */
    sl_params *pp = &HOST_APP(h)->params;
    sl_param *q = d->scope == SL_SCOPE_GLOBAL ? NULL : sl_params_find_key(pp, d->scope, d->id, d->light_type);
    if (q) q->declared_by |= 1ull << (HOST_IDX(h) & 63);
    return st;
}

static char *dup0(const char *s) { return s ? strdup(s) : NULL; }

static sl_status host_add_chunk(const sl_host *h, const sl_shader_chunk_desc *in) {
    if (!in_create(h, "add_shader_chunk")) return SL_ERR_INVALID;
    sl_shader_chunk_desc d = {0};
    memcpy(&d, in, in->struct_size < sizeof d ? in->struct_size : sizeof d);
    const char *id = HOST_REC(h)->id;
    if (d.hook < SL_HOOK_VERTEX || d.hook > SL_HOOK_SHADOW) {
        SL_ERROR("%s: shader chunk %s: unknown hook %d", id, d.file ? d.file : "?", (int)d.hook);
        return SL_ERR_INVALID;
    }
    if (!d.file || (d.hook != SL_HOOK_LIBRARY && !d.function)) {
        SL_ERROR("%s: shader chunk needs a file and (except LIBRARY) a function", id);
        return SL_ERR_INVALID;
    }
    bool named = d.hook == SL_HOOK_SHADING_MODEL || d.hook == SL_HOOK_MODEL_AMBIENT ||
                 d.hook == SL_HOOK_LIGHT || d.hook == SL_HOOK_DEBUG_VIEW || d.hook == SL_HOOK_DEBUG_VIEW_LIGHT;
    if (named && (!d.name || !*d.name)) {
        SL_ERROR("%s: shader chunk %s: this hook needs a name", id, d.file);
        return SL_ERR_INVALID;
    }
    sl_plugins *P = &HOST_APP(h)->plugins;
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
    r->owner = HOST_IDX(h);
    r->d = d;
    r->d.struct_size = sizeof d;
    r->d.file = dup0(d.file);
    r->d.function = dup0(d.function);
    r->d.name = dup0(d.name);
    r->d.when_material_has = dup0(d.when_material_has);
    r->d.when_model = dup0(d.when_model);
    r->d.description = dup0(d.description);
    return SL_OK;
}

static sl_status host_add_pass(const sl_host *h, const sl_pass_desc *in) {
    if (!in_create(h, "add_pass")) return SL_ERR_INVALID;
    sl_pass_desc d = {0};
    memcpy(&d, in, in->struct_size < sizeof d ? in->struct_size : sizeof d);
    const char *id = HOST_REC(h)->id;
    if (!d.name || !d.execute || d.output_count < 0 || (d.output_count && !d.outputs)) {
        SL_ERROR("%s: pass needs a name, an execute callback and its outputs", id);
        return SL_ERR_INVALID;
    }
    sl_plugins *P = &HOST_APP(h)->plugins;
    for (int i = 0; i < P->pass_count; i++)
        if (!strcmp(P->passes[i].d.name, d.name)) {
            SL_ERROR("%s: pass \"%s\" already registered by %s", id, d.name, P->items[P->passes[i].owner]->id);
            return SL_ERR_DUPLICATE;
        }
    P->passes = realloc(P->passes, (P->pass_count + 1) * sizeof *P->passes);
    sl_pass_reg *r = &P->passes[P->pass_count++];
    memset(r, 0, sizeof *r);
    r->owner = HOST_IDX(h);
    r->d = d;
    r->d.struct_size = sizeof d;
    r->d.name = strdup(d.name);
    int nin = 0;
    while (d.inputs && d.inputs[nin]) nin++;
    r->inputs = calloc(nin + 1, sizeof *r->inputs);
    for (int i = 0; i < nin; i++) r->inputs[i] = strdup(d.inputs[i]);
    r->d.inputs = r->inputs;
    r->outputs = calloc(d.output_count ? d.output_count : 1, sizeof *r->outputs);
    for (int i = 0; i < d.output_count; i++) {
        r->outputs[i] = d.outputs[i];
        r->outputs[i].name = strdup(d.outputs[i].name);
    }
    r->d.outputs = r->outputs;
    return SL_OK;
}

static sl_status host_add_key(const sl_host *h, const sl_key_desc *in) {
    if (!in_create(h, "add_key")) return SL_ERR_INVALID;
    sl_key_desc d = {0};
    memcpy(&d, in, in->struct_size < sizeof d ? in->struct_size : sizeof d);
    if (!d.key || (!d.param && !d.on_press)) {
        SL_ERROR("%s: key binding needs a key and a param or callback", HOST_REC(h)->id);
        return SL_ERR_INVALID;
    }
    sl_plugins *P = &HOST_APP(h)->plugins;
    P->keys = realloc(P->keys, (P->key_count + 1) * sizeof *P->keys);
    sl_key_reg *r = &P->keys[P->key_count++];
    r->owner = HOST_IDX(h);
    r->d = d;
    r->d.key = strdup(d.key);
    r->d.description = dup0(d.description);
    r->d.param = dup0(d.param);
    return SL_OK;
}

static sl_status host_set_reference(const sl_host *h, const sl_reference_desc *in) {
    if (!in_create(h, "set_reference")) return SL_ERR_INVALID;
    sl_plugin_rec *rec = HOST_REC(h);
    memset(&rec->reference, 0, sizeof rec->reference);
    memcpy(&rec->reference, in, in->struct_size < sizeof rec->reference ? in->struct_size : sizeof rec->reference);
    rec->reference_settings = dup0(rec->reference.settings);
    rec->reference_description = dup0(rec->reference.description);
    rec->reference.settings = rec->reference_settings;
    rec->reference.description = rec->reference_description;
    rec->has_reference = true;
    return SL_OK;
}

static sl_status host_set_bind(const sl_host *h, void (*bind)(void *, unsigned, int, const sl_frame *), void *user) {
    HOST_REC(h)->bind = bind;
    HOST_REC(h)->bind_user = user;
    return SL_OK;
}

/* Texture units: 0..15 belong to material textures, plugins get 16.. upwards. */
static int host_reserve_unit(const sl_host *h) {
    sl_plugins *P = &HOST_APP(h)->plugins;
    if (P->texture_units_used >= 16) {
        SL_ERROR("%s: out of plugin texture units", HOST_REC(h)->id);
        return -1;
    }
    return 16 + P->texture_units_used++;
}

static sl_value host_get_param(const sl_host *h, const char *id) {
    sl_param *q = sl_params_find(&HOST_APP(h)->params, id);
    if (!q) {
        SL_WARN("%s: get_param(\"%s\"): no such parameter", HOST_REC(h)->id, id);
        return (sl_value){0};
    }
    return q->value;
}

static bool host_plugin_enabled(const sl_host *h, const char *id) {
    int i = sl_plugins_find(&HOST_APP(h)->plugins, id);
    return i >= 0 && sl_plugin_enabled(HOST_APP(h), i);
}

static const void *host_get_extension(const sl_host *h, const char *id) {
    sl_app *app = HOST_APP(h);
    for (int i = 0; i < app->plugins.count; i++) {
        sl_plugin_rec *r = app->plugins.items[i];
        if (!sl_plugin_enabled(app, i) || !r->desc.get_extension) continue;
        const void *e = r->desc.get_extension(r->user, id);
        if (e) return e;
    }
    return NULL;
}

static const sl_light_info *host_lights(const sl_host *h, int *count) { return sl_renderer_lights(HOST_APP(h), count); }

static int host_material_count(const sl_host *h) { return HOST_APP(h)->scene.material_count; }

static const char *host_material_name(const sl_host *h, int m) {
    sl_app *app = HOST_APP(h);
    return m >= 0 && m < app->scene.material_count ? app->scene.materials[m].name : NULL;
}

static bool host_material_value(const sl_host *h, int m, const char *key, sl_value *out, char *path, size_t n) {
    sl_app *app = HOST_APP(h);
    sl_mat_value *v = sl_app_material_value(app, m, key);
    if (path && n) path[0] = 0;
    if (!v || !v->present) return false;
    if (out) *out = v->v;
    if (path && n && v->str && app->params.items[v->param].desc.type == SL_PARAM_TEXTURE && !sl_texture_is_procedural(v->str)) {
        char err[1024];
        char *resolved = sl_scene_resolve_path(&app->scene, app->opt.data_dir, v->str, err, sizeof err);
        if (resolved) snprintf(path, n, "%s", resolved);
        free(resolved);
    }
    return true;
}
static void *host_gl_proc(const char *name);
static sl_app *g_gl_app; /* the app whose context is current (one per process) */
static void *host_gl_proc(const char *name) {
    return g_gl_app && g_gl_app->backend.get_proc_address ? g_gl_app->backend.get_proc_address(name) : NULL;
}
static bool host_is_gpu(const sl_host *h) { return HOST_APP(h)->backend.is_gpu; }
static sl_program *host_load_program(const sl_host *h, const sl_program_desc *d) {
    return sl_renderer_load_program(HOST_APP(h), HOST_IDX(h), d);
}
static unsigned host_program_id(const sl_host *h, sl_program *p) { return sl_renderer_program_id(p); }
static unsigned host_pass_texture(const sl_host *h, sl_pass_ctx *c, const char *name) {
    return sl_renderer_pass_texture(HOST_APP(h), c, name);
}
static sl_status host_bind_outputs(const sl_host *h, sl_pass_ctx *c, int layer) {
    return sl_renderer_bind_outputs(HOST_APP(h), c, layer);
}
static void host_draw_scene(const sl_host *h, sl_pass_ctx *c, const sl_draw_scene_desc *d) {
    sl_renderer_draw_scene(HOST_APP(h), c, d);
}
static void host_draw_fullscreen(const sl_host *h, sl_pass_ctx *c) { sl_renderer_draw_fullscreen(HOST_APP(h), c); }
static unsigned host_material_texture(const sl_host *h, int m, const char *key) {
    return sl_renderer_material_texture(HOST_APP(h), m, key);
}

static const char *host_environment(const sl_host *h, float o[5]) {
    const sl_environment *e = &HOST_APP(h)->scene.environment;
    memcpy(o, e->color, 3 * sizeof(float)), o[3] = e->intensity, o[4] = e->yaw_deg;
    return e->map;
}
void sl_plugins_set_gl_app(sl_app *app) { g_gl_app = app; }

static sl_host_impl *make_host(sl_app *app, int index) {
    sl_host_impl *impl = calloc(1, sizeof *impl);
    impl->app = app;
    impl->plugin = index;
    sl_host *h = &impl->host;
    h->struct_size = sizeof *h;
    h->abi_major = SL_ABI_MAJOR;
    h->abi_minor = SL_ABI_MINOR;
    h->host_version = SL_VERSION;
    h->log = host_log;
    h->resource_dir = host_resource_dir;
    h->add_param = host_add_param;
    h->add_shader_chunk = host_add_chunk;
    h->add_pass = host_add_pass;
    h->add_key = host_add_key;
    h->set_reference = host_set_reference;
    h->set_bind_callback = host_set_bind;
    h->reserve_texture_unit = host_reserve_unit;
    h->get_param = host_get_param;
    h->plugin_enabled = host_plugin_enabled;
    h->get_extension = host_get_extension;
    h->lights = host_lights;
    h->material_count = host_material_count;
    h->material_name = host_material_name;
    h->material_value = host_material_value;
    h->gl_get_proc_address = host_gl_proc;
    h->is_gpu = host_is_gpu;
    h->load_program = host_load_program;
    h->program_id = host_program_id;
    h->pass_texture = host_pass_texture;
    h->bind_outputs = host_bind_outputs;
    h->draw_scene = host_draw_scene;
    h->draw_fullscreen = host_draw_fullscreen;
    h->material_texture = host_material_texture;
    h->environment = host_environment;
    return impl;
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
static bool enabled_at(sl_app *app, int index, int depth) {
    sl_plugin_rec *r = app->plugins.items[index];
    if (!r->ok) return false;
    if (index == 0) return true; /* the core */
    char id[300];
    snprintf(id, sizeof id, "%s.enabled", r->id);
    sl_param *q = sl_params_find(&app->params, id);
    if (q && !q->value.b) return false;
    for (const char *const *req = r->desc.dependencies; req && *req && depth < 16; req++) {
        int j = sl_plugins_find(&app->plugins, *req);
        if (j < 0 || !enabled_at(app, j, depth + 1)) return false;
    }
    return true;
}

bool sl_plugin_enabled(sl_app *app, int index) { return enabled_at(app, index, 0); }

static sl_plugin_rec *new_record(sl_app *app, const char *id, const char *requested_by) {
    sl_plugins *P = &app->plugins;
    P->items = realloc(P->items, (P->count + 1) * sizeof *P->items);
    sl_plugin_rec *r = calloc(1, sizeof *r);
    P->items[P->count] = r;
    r->id = strdup(id);
    r->requested_by = strdup(requested_by);
    r->host = make_host(app, P->count);
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
        char *copy = strdup(env), *save = NULL;
        for (char *tok = strtok_r(copy, ":", &save); tok && n < max; tok = strtok_r(NULL, ":", &save))
            if (*tok) snprintf(dirs[n++], 1024, "%s", tok);
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

int sl_plugins_load(sl_app *app, const char *name, const char *requested_by, bool allow_path) {
    sl_plugins *P = &app->plugins;
    bool is_path = strchr(name, '/') || (strlen(name) > 3 && !strcmp(name + strlen(name) - 3, ".so"));
    if (!is_path) {
        int existing = sl_plugins_find(P, name);
        if (existing >= 0) return existing;
    }
    sl_plugin_rec *r = new_record(app, name, requested_by);
    int index = P->count - 1;
    char path[2048] = "";
    if (is_path) {
        if (!allow_path) {
            disable(r, "a scene may only name plugins, not paths (\"%s\"); use --plugin on the command line", name);
            return index;
        }
        snprintf(path, sizeof path, "%s", name);
        if (!file_exists(path)) {
            disable(r, "plugin file %s does not exist", path);
            return index;
        }
    } else {
        for (const char *c = name; *c; c++)
            if (!((*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') || *c == '-' || *c == '_')) {
                disable(r, "invalid plugin name \"%s\" (letters, digits, '-' only)", name);
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

bool sl_plugins_add_builtin(sl_app *app, const sl_plugin_desc *desc) {
    sl_plugin_rec *r = new_record(app, desc->id, "built-in");
    r->path = strdup("(built-in)");
    r->resource_dir = strdup("");
    r->desc = *desc;
    r->ok = true;
    return true;
}

static void free_chunk(sl_chunk_reg *c) {
    free((char *)c->d.file); free((char *)c->d.function); free((char *)c->d.name);
    free((char *)c->d.when_material_has); free((char *)c->d.description); free((char *)c->d.when_model);
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
static void remove_registrations(sl_app *app, int owner) {
    sl_plugins *P = &app->plugins;
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
    sl_params *pp = &app->params;
    const char *id = P->items[owner]->id;
    w = 0;
    for (int i = 0; i < pp->count; i++)
        if (strcmp(pp->items[i].owner, id)) pp->items[w++] = pp->items[i];
        else sl_param_free_item(&pp->items[i]);
    pp->count = w;
}

static void create_one(sl_app *app, int i, int depth) {
    sl_plugins *P = &app->plugins;
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
            j = sl_plugins_load(app, *q, by, false);
            r = P->items[i];
        }
        create_one(app, j, depth + 1);
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
        sl_params_add(&app->params, r->id, &en, err, sizeof err);
    }
    int before_errors = sl_log_count(SL_LOG_ERROR);
    void *user = NULL;
    r->creating = true;
    sl_status st = r->desc.create(&r->host->host, &user);
    r->creating = false;
    r->user = user ? user : (void *)r; /* non-NULL marks "created" */
    if (st != SL_OK) {
        if (user && r->desc.destroy) r->desc.destroy(user); /* documented in plugin.h */
        remove_registrations(app, i);
        disable(r, "create() failed with status %d (see the messages above)", (int)st);
    } else if (sl_log_count(SL_LOG_ERROR) > before_errors && i != 0) {
        /* a registration was refused (e.g. duplicate shading model): the plugin is unusable */
        if (r->desc.destroy) r->desc.destroy(user);
        remove_registrations(app, i);
        disable(r, "a registration was refused during create() (see the messages above)");
    } else {
        r->ok = true;
    }
}

void sl_plugins_create_all(sl_app *app) {
    for (int i = 0; i < app->plugins.count; i++) create_one(app, i, 0);
}

void sl_plugins_print(sl_app *app, FILE *f) {
    sl_plugins *P = &app->plugins;
    for (int i = 0; i < P->count; i++) {
        sl_plugin_rec *r = P->items[i];
        const char *state = !r->ok ? "DISABLED" : sl_plugin_enabled(app, i) ? "enabled" : "off";
        fprintf(f, "%-20s %-8s %s%s%s\n", r->id, state, r->path ? r->path : "-",
                r->desc.version ? "  v" : "", r->desc.version ? r->desc.version : "");
        if (r->desc.description && r->ok) fprintf(f, "    %s\n", r->desc.description);
        if (!r->ok) fprintf(f, "    reason: %s\n", r->disabled_reason ? r->disabled_reason : "?");
        fprintf(f, "    requested by: %s\n", r->requested_by);
    }
    char dirs[16][1024];
    int nd = sl_plugin_search_dirs(dirs, 16);
    fprintf(f, "search path:");
    for (int i = 0; i < nd; i++) fprintf(f, " %s", dirs[i]);
    fprintf(f, "\n");
}

void sl_plugins_shutdown(sl_app *app) {
    sl_plugins *P = &app->plugins;
    for (int i = P->count - 1; i >= 0; i--) {
        sl_plugin_rec *r = P->items[i];
        if (r->active && r->desc.deactivate) r->desc.deactivate(r->user);
        r->active = false;
        if (r->ok && r->user && r->desc.destroy) r->desc.destroy(r->user);
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
