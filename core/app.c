#include "render/texture_prefetch.h"
#include "app.h"
#include "core_plugin.h"
#include "host/host.h"
#include "image/image.h"
#include "log.h"
#include "startup.h"
#include "render/composer.h"
#include "render/forward.h"
#include "render/renderer.h"
#include "render/post.h"
#include "budget/budget.h"
#include <shadelab/gl.h>
#include <shadelab/input.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>


/* ------------------------------------------------------------ material and light values */


/* A scene prop as text, so one parser (sl_param_parse) validates scene, CLI and GUI input. */
static void prop_text(const sl_prop *p, char *buf, size_t n) {
    switch (p->kind) {
    case SL_PROP_NUMBER: snprintf(buf, n, "%.9g", p->v[0]); break;
    case SL_PROP_BOOL: snprintf(buf, n, "%s", p->v[0] != 0 ? "true" : "false"); break;
    case SL_PROP_STRING: snprintf(buf, n, "%s", p->str ? p->str : ""); break;
    case SL_PROP_VEC: {
        size_t u = 0;
        buf[0] = 0;
        for (int i = 0; i < p->count && u < n; i++) u += snprintf(buf + u, n - u, "%s%.9g", i ? "," : "", p->v[i]);
        break;
    }
    }
}

static bool set_material_value(sl_app *app, int m, sl_mat_value *v, const char *text, char *err, size_t n) {
    sl_param *q = &app->params.items[v->param];
    sl_value val;
    if (!sl_param_parse(q, text, &val, err, n)) return false;
    if (q->desc.type == SL_PARAM_TEXTURE) {
        free(v->str);
        v->str = strdup(text);
        val.s = v->str;
    }
    v->v = val;
    v->present = true;
    app->materials_version++;
    return true;
}


/* Why a light key is refused: it belongs to other light types, or no loaded plugin declares it
 * (with the nearest key that this light's type does have; never the refused key itself). */
static void light_key_error(sl_app *app, const sl_light *L, const char *key, char *err, size_t n) {
    char types[256] = "";
    size_t u = 0;
    for (int i = 0; i < app->params.count; i++) {
        const sl_param *q = &app->params.items[i];
        if (q->desc.scope == SL_SCOPE_LIGHT && q->desc.light_type && !strcmp(q->desc.id, key) && u < sizeof types)
            u += snprintf(types + u, sizeof types - u, "%s%s", u ? ", " : "", q->desc.light_type);
    }
    if (u) {
        snprintf(err, n, "light \"%s\" (type %s): key \"%s\" applies to lights of type %s only", L->name, L->type, key,
                 types);
        return;
    }
    const char *near = sl_params_nearest_light_key(&app->params, key, L->type);
    snprintf(err, n, "light \"%s\" (type %s): no loaded plugin declares key \"%s\"%s%s%s", L->name, L->type, key,
             near ? "; did you mean \"" : "", near ? near : "", near ? "\"?" : "");
}

static bool set_light_value(sl_app *app, int li, const char *key, const char *text, char *err, size_t n) {
    sl_light *L = &app->scene.lights[li];
    sl_param *q = sl_params_find_key(&app->params, SL_SCOPE_LIGHT, key, L->type);
    if (!q) {
        light_key_error(app, L, key, err, n);
        return false;
    }
    sl_value v;
    char what[300];
    snprintf(what, sizeof what, "light.%s.%s", L->name, key);
    sl_param tmp = *q;
    tmp.full_id = what;
    if (!sl_param_parse(&tmp, text, &v, err, n)) return false;
    if (sl_core_light_key(key)) {
        if (!sl_core_light_set(L, key, &v, what, err, n)) return false;
    } else {
        int slot = q->desc.light_slot;
        int comps = q->desc.type == SL_PARAM_COLOR || q->desc.type == SL_PARAM_VEC3 ? 3 : 1;
        if (slot + comps > 8) { snprintf(err, n, "%s: light_slot out of range", what); return false; }
        for (int c = 0; c < comps; c++)
            app->light_params[li][slot + c] = q->desc.type == SL_PARAM_BOOL ? (float)v.b
                                            : q->desc.type == SL_PARAM_INT || q->desc.type == SL_PARAM_ENUM ? (float)v.i
                                            : v.f[c];
    }
    app->lights_version++;
    return true;
}

static int find_material(sl_app *app, const char *name) {
    for (int i = 0; i < app->scene.material_count; i++)
        if (!strcmp(app->scene.materials[i].name, name)) return i;
    return -1;
}

static int find_light(sl_app *app, const char *name) {
    for (int i = 0; i < app->scene.light_count; i++)
        if (!strcmp(app->scene.lights[i].name, name)) return i;
    return -1;
}

static void list_names(char *buf, size_t n, int count, const char *(*get)(sl_app *, int), sl_app *app) {
    size_t u = 0;
    buf[0] = 0;
    for (int i = 0; i < count && u < n; i++) u += snprintf(buf + u, n - u, "%s%s", i ? ", " : "", get(app, i));
    if (!count) snprintf(buf, n, "(none)");
}
static const char *mat_name(sl_app *a, int i) { return a->scene.materials[i].name; }
static const char *light_name(sl_app *a, int i) { return a->scene.lights[i].name; }
static const char *cam_name(sl_app *a, int i) { return a->scene.cameras[i].name; }

bool sl_app_set(sl_app *app, const char *assignment, sl_param_source src, char *err, size_t n) {
    const char *eq = strchr(assignment, '=');
    if (!eq || eq == assignment) {
        snprintf(err, n, "--set expects ID=VALUE, got \"%s\"", assignment);
        return false;
    }
    char id[512];
    snprintf(id, sizeof id, "%.*s", (int)(eq - assignment), assignment);
    const char *value = eq + 1;
    bool is_mat = !strncmp(id, "material.", 9), is_light = !strncmp(id, "light.", 6);
    if (is_mat || is_light) {
        char *name = id + (is_mat ? 9 : 6);
        char *dot = strrchr(name, '.');
        if (!dot || dot == name) {
            snprintf(err, n, "\"%s\": expected %s.NAME.KEY", id, is_mat ? "material" : "light");
            return false;
        }
        *dot = 0;
        const char *key = dot + 1;
        char names[2048];
        if (is_light) {
            int li = find_light(app, name);
            if (li < 0) {
                list_names(names, sizeof names, app->scene.light_count, light_name, app);
                snprintf(err, n, "no light named \"%s\" in the scene (lights: %s)", name, names);
                return false;
            }
            return set_light_value(app, li, key, value, err, n);
        }
        int m = find_material(app, name);
        if (m < 0) {
            list_names(names, sizeof names, app->scene.material_count, mat_name, app);
            snprintf(err, n, "no material named \"%s\" in the scene (materials: %s)", name, names);
            return false;
        }
        sl_mat_value *v = sl_app_material_value(app, m, key);
        if (!v) {
            const char *near = sl_params_nearest(&app->params, SL_SCOPE_MATERIAL, key);
            snprintf(err, n, "material \"%s\": no loaded plugin declares key \"%s\"%s%s%s (see --dump-params)",
                     name, key, near ? "; did you mean \"" : "", near ? near : "", near ? "\"?" : "");
            return false;
        }
        char full[600];
        snprintf(full, sizeof full, "material.%s.%s", name, key);
        char *saved = app->params.items[v->param].full_id;
        app->params.items[v->param].full_id = full; /* messages name the full address */
        bool ok = set_material_value(app, m, v, value, err, n);
        app->params.items[v->param].full_id = saved;
        return ok;
    }
    return sl_params_set(&app->params, id, value, src, err, n);
}

/* ---- standard material inputs of imported assets (sdk params.h, "standard material inputs") -- */

/* Is `input` taken by a plugin already here: a created one by its keys' schema (material_input;
 * the core's own keys among them), one loaded but not yet created by its descriptor's list? */
static bool input_declared(const sl_app *app, const char *input) {
    for (int i = 0; i < app->params.count; i++) {
        const sl_param *q = &app->params.items[i];
        if (q->desc.scope == SL_SCOPE_MATERIAL && q->desc.material_input && !strcmp(q->desc.material_input, input))
            return true;
    }
    for (int i = 0; i < app->plugins.count; i++) {
        const sl_plugin_rec *r = app->plugins.items[i];
        for (int k = 0; r->ok && !r->live && r->desc.material_inputs && r->desc.material_inputs[k] && k < 256; k++)
            if (!strcmp(r->desc.material_inputs[k], input)) return true;
    }
    return false;
}

/* Loads the plugins the scene's imported materials need: for each standard input no plugin here
 * declares, the first installed plugin whose descriptor does (before create_all). An input
 * nobody declares is reported when the material is applied. */
static void load_plugins_for_inputs(sl_app *app) {
    const sl_scene *s = &app->scene;
    char missing[32][64];
    int nmissing = 0;
    for (int m = 0; m < s->material_count; m++) {
        const sl_material *mat = &s->materials[m];
        for (int k = 0; k < mat->inputs.count; k++) {
            const char *input = mat->inputs.items[k].key;
            bool handled = input_declared(app, input), known_missing = false;
            for (int i = 0; i < nmissing && !known_missing; i++) known_missing = !strcmp(missing[i], input);
            if (handled || known_missing) continue;
            char id[256], why[512];
            if (sl_plugin_for_input(input, id, sizeof id)) {
                snprintf(why, sizeof why, "material input \"%s\" of %s", input, mat->source ? mat->source : s->path);
                SL_INFO("loading plugin %s: it handles the %s", id, why);
                sl_plugins_load(&app->plugins, id, why, false);
            } else if (nmissing < 32) {
                snprintf(missing[nmissing++], sizeof missing[0], "%s", input);
            }
        }
    }
}

/* Writes material m's standard inputs into the keys that declare them (the scene's own props,
 * applied after, win). "brdf" also selects the shading model of the plugin whose key takes it.
 * Inputs no loaded plugin declares are named in one warning (the asset file and the material). */
static void apply_material_inputs(sl_app *app, int m) {
    sl_material *mat = &app->scene.materials[m];
    char unhandled[1024] = "";
    size_t u = 0;
    for (int k = 0; k < mat->inputs.count; k++) {
        const sl_prop *p = &mat->inputs.items[k];
        const sl_param *q = NULL;
        for (int i = 0; i < app->params.count && !q; i++) {
            const sl_param *c = &app->params.items[i];
            if (c->desc.scope == SL_SCOPE_MATERIAL && c->desc.material_input && !strcmp(c->desc.material_input, p->key))
                q = c;
        }
        int owner = q ? sl_plugins_find(&app->plugins, q->owner) : -1;
        if (!q || owner < 0 || !app->plugins.items[owner]->ok) {
            if (u < sizeof unhandled) u += snprintf(unhandled + u, sizeof unhandled - u, "%s%s", u ? ", " : "", p->key);
            continue;
        }
        char text[1024], why[1024];
        prop_text(p, text, sizeof text);
        sl_mat_value *v = sl_app_material_value(app, m, q->full_id);
        if (!v || !set_material_value(app, m, v, text, why, sizeof why)) {
            SL_WARN("%s: material \"%s\": %s %s not applied: %s", mat->source ? mat->source : app->scene.path, mat->name,
                    p->key, text, v ? why : "no value slot");
            continue;
        }
        if (!strcmp(p->key, "brdf")) /* the declaring plugin's shading model renders the material */
            for (int c = 0; c < app->plugins.chunk_count; c++) {
                const sl_chunk_reg *ch = &app->plugins.chunks[c];
                if (ch->d.hook == SL_HOOK_SHADING_MODEL && ch->owner == owner && ch->d.name) {
                    char *model = strdup(ch->d.name);
                    if (model) free(mat->model), mat->model = model;
                    break;
                }
            }
    }
    if (u)
        SL_WARN("%s: material \"%s\": %s not rendered: no loaded plugin declares %s (ignored)",
                mat->source ? mat->source : app->scene.path, mat->name, unhandled,
                strchr(unhandled, ',') ? "them" : "it");
}

/* Loads the installed plugins that declare any of `bits` in their descriptor's default_for (the
 * core names none); returns how many declare it, loaded now or already. */
static int load_defaults(sl_app *app, unsigned bits, const char *why) {
    char ids[32][64];
    int n = sl_plugin_defaults(bits, ids, 32);
    for (int i = 0; i < n; i++)
        if (sl_plugins_find(&app->plugins, ids[i]) < 0) sl_plugins_load(&app->plugins, ids[i], why, false);
    return n;
}

/* A model file opened directly: what installed plugins declare as a model file's defaults (the
 * bundled ones: envmap's procedural sky as its environment, tone mapping), or a neutral studio
 * light when no plugin lights it. */
static void model_defaults(sl_app *app) {
    sl_scene *s = &app->scene;
    if (!s->from_model) return;
    if (load_defaults(app, SL_PLUGIN_DEFAULT_MODEL_ENVIRONMENT, "default environment of a model file") == 0 &&
        s->light_count == 0) {
        /* studio: a key light from the upper front left, a dimmer fill, a grey ambient */
        static const float dirs[2][3] = {{0.45f, -0.7f, -0.55f}, {-0.6f, -0.3f, -0.75f}};
        static const float power[2] = {2.5f, 0.8f};
        for (int i = 0; i < 2; i++) {
            int li = sl_scene_add_light(s, i ? "studio-fill" : "studio-key", "directional");
            if (li < 0) break;
            float l = sqrtf(dirs[i][0] * dirs[i][0] + dirs[i][1] * dirs[i][1] + dirs[i][2] * dirs[i][2]);
            for (int c = 0; c < 3; c++) s->lights[li].direction[c] = dirs[i][c] / l;
            s->lights[li].intensity = power[i];
        }
        for (int c = 0; c < 3; c++) s->environment.color[c] = 0.3f;
    }
    load_defaults(app, SL_PLUGIN_DEFAULT_MODEL_FILE, "default of a model file");
}

/* --env FILE: the scene's environment map replaced (checked here, decoded by whoever reads it). */
static bool environment_option(sl_app *app, char *err, size_t n) {
    char why[600];
    if (sl_input_file_problem(app->opt.env_map, why, sizeof why)) {
        snprintf(err, n, "--env %s: %s", app->opt.env_map, why);
        return false;
    }
    char *path = realpath(app->opt.env_map, NULL);
    if (!path) {
        snprintf(err, n, "--env %s: out of memory", app->opt.env_map);
        return false;
    }
    free(app->scene.environment.map);
    app->scene.environment.map = path;
    return true;
}

/* --ground: a grey floor (the standard base_color input, Lambert) at the bottom of the bounds,
 * 2.5 times their horizontal extent, that receives shadows and casts none. */
static bool ground_option(sl_app *app, char *err, size_t n) {
    sl_scene *s = &app->scene;
    float ex = s->bounds_max[0] - s->bounds_min[0], ez = s->bounds_max[2] - s->bounds_min[2];
    float size = 2.5f * fmaxf(fmaxf(ex, ez), 1e-3f);
    sl_mesh_data plane;
    int mi = sl_scene_add_material(s, "ground", "lambert"), node = sl_scene_add_node(s, "ground", -1);
    if (mi < 0 || node < 0 || !sl_mesh_plane(&plane, size, size, 1)) {
        snprintf(err, n, "--ground: out of memory");
        return false;
    }
    const float grey[3] = {0.5f, 0.5f, 0.5f};
    s->materials[mi].cast_shadows = false;
    sl_prop_set_vec(&s->materials[mi].inputs, "base_color", grey, 3, 0);
    int mesh = sl_scene_add_mesh(s, "ground", &plane, mi);
    if (mesh < 0 || !sl_scene_node_add_mesh(s, node, mesh)) {
        snprintf(err, n, "--ground: out of memory");
        return false;
    }
    const float at[3] = {0.5f * (s->bounds_min[0] + s->bounds_max[0]), s->bounds_min[1], 0.5f * (s->bounds_min[2] + s->bounds_max[2])};
    const float turn[4] = {0, 0, 0, 1}, one[3] = {1, 1, 1};
    sl_mat4_from_trs(s->nodes[node].local, at, turn, one);
    sl_scene_update_transforms(s);
    return true;
}

/* --shadows: every light casts them; a key light from the upper front left (E = 3) casts them too,
 * standing in for a sun: it is off while a plugin's own shadow-casting directional light shines
 * (plugin_lights.h; envmap's sky sun), which is added later, with the plugins. */
static bool shadows_option(sl_app *app, char *err, size_t n) {
    sl_scene *s = &app->scene;
    for (int i = 0; i < s->light_count; i++) s->lights[i].cast_shadows = true;
    int li = sl_scene_add_light(s, "key", "directional");
    if (li < 0) {
        snprintf(err, n, "--shadows: out of memory");
        return false;
    }
    const float dir[3] = {0.45f, -0.7f, -0.55f};
    float l = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    for (int c = 0; c < 3; c++) s->lights[li].direction[c] = dir[c] / l;
    s->lights[li].intensity = 3;
    s->lights[li].cast_shadows = true;
    s->lights[li].stand_in = true;
    return true;
}

/* A model needs no JSON scene: --env, --ground and --shadows change the scene loaded. The
 * default camera frames what was loaded, not the floor. */
static bool scene_options(sl_app *app, char *err, size_t n) {
    memcpy(app->frame_min, app->scene.bounds_min, sizeof app->frame_min);
    memcpy(app->frame_max, app->scene.bounds_max, sizeof app->frame_max);
    return (!app->opt.env_map || environment_option(app, err, n)) && (!app->opt.ground || ground_option(app, err, n)) &&
           (!app->opt.shadows || shadows_option(app, err, n));
}

/* Validates and applies material/light props from the scene against the plugins' schema. */
static bool apply_scene_values(sl_app *app, char *err, size_t n) {
    sl_scene *s = &app->scene;
    app->materials = calloc(s->material_count + 1, sizeof *app->materials);
    int nkeys = 0;
    for (int i = 0; i < app->params.count; i++) nkeys += app->params.items[i].desc.scope == SL_SCOPE_MATERIAL;
    for (int m = 0; m < s->material_count; m++) {
        sl_mat_state *ms = &app->materials[m];
        ms->values = calloc(nkeys + 1, sizeof *ms->values);
        for (int i = 0; i < app->params.count; i++) {
            const sl_param *q = &app->params.items[i];
            if (q->desc.scope != SL_SCOPE_MATERIAL) continue;
            sl_mat_value *v = &ms->values[ms->count++];
            v->param = i;
            v->v = q->desc.default_value;
            v->v.s = NULL;
        }
        apply_material_inputs(app, m);
        const sl_material *mat = &s->materials[m];
        for (int k = 0; k < mat->props.count; k++) {
            const sl_prop *p = &mat->props.items[k];
            sl_mat_value *v = sl_app_material_value(app, m, p->key);
            /* where the key was given: the scene line, or the asset an imported material came from */
            char at[1100];
            if (p->line > 0 || !mat->source) snprintf(at, sizeof at, "%.1000s:%d", s->path, p->line);
            else snprintf(at, sizeof at, "%.1000s", mat->source);
            if (!v) {
                const char *near = sl_params_nearest(&app->params, SL_SCOPE_MATERIAL, p->key);
                SL_WARN("%s: material \"%s\": no loaded plugin declares key \"%s\"%s%s%s (ignored; see --dump-params)",
                        at, mat->name, p->key, near ? "; did you mean \"" : "", near ? near : "",
                        near ? "\"?" : "");
                continue;
            }
            char text[1024], why[1024];
            prop_text(p, text, sizeof text);
            if (!set_material_value(app, m, v, text, why, sizeof why)) {
                snprintf(err, n, "%s: material \"%s\": %s", at, mat->name, why);
                return false;
            }
        }
        /* a material naming a model nobody provides falls back to lambert, loudly */
        bool provided = false;
        for (int c = 0; c < app->plugins.chunk_count; c++) {
            const sl_chunk_reg *ch = &app->plugins.chunks[c];
            provided |= ch->d.hook == SL_HOOK_SHADING_MODEL && !strcmp(ch->d.name, mat->model) && app->plugins.items[ch->owner]->ok;
        }
        if (!provided) {
            /* the plugin that provides it, from the installed descriptors (never the model's name) */
            char provider[64], hint[128];
            if (sl_plugin_for_model(mat->model, provider, sizeof provider))
                snprintf(hint, sizeof hint, "load it with --plugin %s", provider);
            else
                snprintf(hint, sizeof hint, "no installed plugin provides it: see --list-plugins");
            SL_WARN("%s:%d: material \"%s\": shading model \"%s\" is not provided by any loaded plugin; using lambert "
                    "(%s)", s->path, mat->line, mat->name, mat->model, hint);
        }
    }
    app->light_params = calloc(s->light_count + 1, sizeof *app->light_params);
    for (int li = 0; li < s->light_count; li++) {
        sl_light *L = &s->lights[li];
        /* light-type keys start at their schema defaults */
        for (int i = 0; i < app->params.count; i++) {
            const sl_param *q = &app->params.items[i];
            if (q->desc.scope != SL_SCOPE_LIGHT || !q->desc.light_type || strcmp(q->desc.light_type, L->type)) continue;
            int comps = q->desc.type == SL_PARAM_COLOR || q->desc.type == SL_PARAM_VEC3 ? 3 : 1;
            for (int c = 0; c < comps && q->desc.light_slot + c < 8; c++)
                app->light_params[li][q->desc.light_slot + c] =
                    q->desc.type == SL_PARAM_BOOL ? q->desc.default_value.b
                    : (q->desc.type == SL_PARAM_INT || q->desc.type == SL_PARAM_ENUM) ? q->desc.default_value.i
                    : q->desc.default_value.f[c];
        }
        /* the scene's intensity and colour obey the same ranges as --set light.NAME.KEY */
        char value[128], problem[1024];
        snprintf(value, sizeof value, "%.9g", L->intensity);
        bool valid = set_light_value(app, li, "intensity", value, problem, sizeof problem);
        snprintf(value, sizeof value, "%.9g,%.9g,%.9g", L->color[0], L->color[1], L->color[2]);
        valid = valid && set_light_value(app, li, "color", value, problem, sizeof problem);
        if (!valid) {
            snprintf(err, n, "%s:%d: %s", s->path, L->line, problem);
            return false;
        }
        for (int k = 0; k < L->props.count; k++) {
            const sl_prop *p = &L->props.items[k];
            char text[1024], why[1024];
            prop_text(p, text, sizeof text);
            if (!sl_params_find_key(&app->params, SL_SCOPE_LIGHT, p->key, L->type)) {
                if (L->plugin) continue; /* a plugin's light: keys of plugins not loaded (add_light) */
                light_key_error(app, L, p->key, why, sizeof why);
                SL_WARN("%s:%d: %s (ignored)", s->path, p->line, why);
                continue;
            }
            if (!set_light_value(app, li, p->key, text, why, sizeof why)) {
                snprintf(err, n, "%s:%d: %s", s->path, p->line, why);
                return false;
            }
        }
        bool provided = false;
        for (int c = 0; c < app->plugins.chunk_count; c++) {
            const sl_chunk_reg *ch = &app->plugins.chunks[c];
            provided |= ch->d.hook == SL_HOOK_LIGHT && !strcmp(ch->d.name, L->type) && app->plugins.items[ch->owner]->ok;
        }
        if (!provided)
            SL_WARN("%s:%d: light \"%s\": type \"%s\" is not provided by any loaded plugin; the light is ignored",
                    s->path, L->line, L->name, L->type);
    }
    /* the forward programs specialise on the set of light types (render/forward.h) */
    const char *types[SL_MAX_LIGHT_TYPES + 1];
    if (sl_forward_light_types(app, types, SL_MAX_LIGHT_TYPES + 1) > SL_MAX_LIGHT_TYPES) {
        for (int li = 0; li < s->light_count; li++)
            if (!strcmp(s->lights[li].type, types[SL_MAX_LIGHT_TYPES])) {
                snprintf(err, n, "%s:%d: light \"%s\": type \"%s\" is one light type too many: a scene has at most %d "
                         "(render/forward.h, SL_MAX_LIGHT_TYPES)", s->path, s->lights[li].line, s->lights[li].name,
                         s->lights[li].type, SL_MAX_LIGHT_TYPES);
                break;
            }
        return false;
    }
    return true;
}

static void default_camera(sl_app *app) {
    sl_camera c = {.fov_y_deg = 45, .znear = 0.05f, .zfar = 100, .up = {0, 1, 0}};
    float radius = 0;
    for (int i = 0; i < 3; i++) {
        c.target[i] = 0.5f * (app->frame_min[i] + app->frame_max[i]);
        float e = app->frame_max[i] - app->frame_min[i];
        radius += e * e;
    }
    radius = sqrtf(radius) * 0.5f;
    if (!(radius > 0) || !isfinite(radius)) radius = 1;
    float dist = radius / sinf(c.fov_y_deg * (float)M_PI / 360.f) * 1.05f;
    c.position[0] = c.target[0];
    c.position[1] = c.target[1] + dist * 0.3f;
    c.position[2] = c.target[2] + dist * 0.95f;
    c.znear = dist * 0.01f;
    c.zfar = dist * 4 + radius * 4;
    sl_camera_from_scene(&app->camera, &c);
}

bool sl_app_set_debug_view(sl_app *app, const char *name, char *err, size_t n) {
    if (!name || !*name || !strcmp(name, "final") || !strcmp(name, "none")) {
        free(app->debug_view);
        app->debug_view = NULL;
        return true;
    }
    const char *best = NULL;
    int best_d = 1 << 30;
    for (int i = 0; i < app->plugins.chunk_count; i++) {
        const sl_chunk_reg *c = &app->plugins.chunks[i];
        if (c->d.hook != SL_HOOK_DEBUG_VIEW && c->d.hook != SL_HOOK_DEBUG_VIEW_LIGHT) continue;
        if (!sl_plugin_enabled(&app->plugins, c->owner)) continue;
        if (!strcmp(c->d.name, name)) {
            free(app->debug_view);
            app->debug_view = strdup(name);
            return true;
        }
        int d = sl_levenshtein(name, c->d.name);
        if (d < best_d) { best_d = d; best = c->d.name; }
    }
    snprintf(err, n, "unknown debug view \"%s\"%s%s%s (see --list-debug-views)", name, best ? "; did you mean \"" : "",
             best ? best : "", best ? "\"?" : "");
    return false;
}

static sl_host *make_host(void *app, int index) { return sl_host_make(app, index); }

bool sl_app_init(sl_app *app, const sl_app_options *opt, char *err, size_t n) {
    memset(app, 0, sizeof *app);
    app->opt = *opt;
    if (app->opt.width <= 0) app->opt.width = 1280;
    if (app->opt.height <= 0) app->opt.height = 720;
    if (app->opt.accumulate < 1) app->opt.accumulate = 1;
    if (app->opt.fixed_dt <= 0) app->opt.fixed_dt = 1.0 / 60.0;
    if (!app->opt.data_dir) app->opt.data_dir = getenv("SHADELAB_DATA");
    sl_params_init(&app->params);

    sl_scene_load_opts lo = {.data_dir = app->opt.data_dir, .gltf_variant = opt->gltf_variant,
                             .gltf_animation = opt->gltf_animation};
    bool ok;
    if (opt->scene_path) ok = sl_scene_load_file(&app->scene, opt->scene_path, &lo, err, n);
    else if (opt->scene_text) ok = sl_scene_load_text(&app->scene, opt->scene_text, "<text>", ".", &lo, err, n);
    else ok = sl_scene_load_text(&app->scene, sl_default_scene_json, "<built-in default scene>", ".", &lo, err, n);
    if (!ok) return false;
    app->scene_loaded = true;
    sl_scene_update_transforms(&app->scene);
    if (!scene_options(app, err, n)) return false;
    sl_startup_mark("scene file (JSON, meshes)");

    /* plugins: the core first, then the command line, then the scene's names */
    app->plugins.params = &app->params;
    app->plugins.make_host = make_host;
    app->plugins.host_ctx = app;
    sl_plugins_add_builtin(&app->plugins, &sl_core_plugin);
    free(app->plugins.items[0]->resource_dir);
    app->plugins.items[0]->resource_dir = strdup(sl_shader_dir());
    sl_plugins_create(&app->plugins, 0); /* its keys declare the material inputs it takes */
    for (int i = 0; i < opt->plugin_count; i++) sl_plugins_load(&app->plugins, opt->plugins[i], "command line", true);
    for (int i = 0; i < app->scene.plugin_count; i++) sl_plugins_load(&app->plugins, app->scene.plugins[i], "scene", false);
    /* Plugins on by default are those whose descriptor says so (the bundled aa: antialiasing on,
     * issue 20); X.enabled=false switches one off and it costs nothing. */
    if (!opt->no_default_plugins) load_defaults(app, SL_PLUGIN_DEFAULT_EVERY_SCENE, "loaded by default");
    model_defaults(app);
    if (opt->env_map) load_defaults(app, SL_PLUGIN_DEFAULT_MODEL_ENVIRONMENT, "--env");
    if (opt->shadows) load_defaults(app, SL_PLUGIN_DEFAULT_SHADOWS, "--shadows");
    load_plugins_for_inputs(app);
    sl_plugins_create_all(&app->plugins);
    sl_startup_mark("plugins loaded and created");
    if (!app->plugins.items[0]->ok) {
        snprintf(err, n, "the core failed to register its shaders (see above)");
        return false;
    }
    if (opt->strict) {
        for (int i = 0; i < app->plugins.count; i++)
            if (!app->plugins.items[i]->ok) {
                snprintf(err, n, "--strict: plugin %s failed: %s", app->plugins.items[i]->id,
                         app->plugins.items[i]->disabled_reason);
                return false;
            }
    }
    /* parameter precedence: defaults < scene < command line (< GUI at run time) */
    for (int i = 0; i < app->scene.params.count; i++) {
        const sl_prop *p = &app->scene.params.items[i];
        char text[1024], why[1024];
        prop_text(p, text, sizeof text);
        if (!sl_params_set(&app->params, p->key, text, SL_SRC_SCENE, why, sizeof why)) {
            snprintf(err, n, "%s:%d: %s", app->scene.path, p->line, why);
            return false;
        }
    }
    if (!apply_scene_values(app, err, n)) return false;
    for (int i = 0; i < opt->setting_count; i++) {
        char why[2048];
        if (!sl_app_set(app, opt->settings[i], SL_SRC_CLI, why, sizeof why)) {
            snprintf(err, n, "--set %s: %s", opt->settings[i], why);
            return false;
        }
    }
    /* camera */
    if (opt->camera) {
        int found = -1;
        for (int i = 0; i < app->scene.camera_count; i++)
            if (!strcmp(app->scene.cameras[i].name, opt->camera)) found = i;
        if (found < 0) {
            char names[1024];
            list_names(names, sizeof names, app->scene.camera_count, cam_name, app);
            snprintf(err, n, "--camera %s: no such camera in %s (cameras: %s)", opt->camera, app->scene.path, names);
            return false;
        }
        sl_camera_from_scene(&app->camera, &app->scene.cameras[found]);
    } else if (app->scene.camera_count) {
        sl_camera_from_scene(&app->camera, &app->scene.cameras[0]);
    } else {
        default_camera(app);
    }
    if (opt->debug_view && !sl_app_set_debug_view(app, opt->debug_view, err, n)) return false;
    return true;
}

static bool is_cpu_renderer(const char *renderer) {
    return renderer && (strstr(renderer, "llvmpipe") || strstr(renderer, "softpipe") || strstr(renderer, "SWR"));
}

bool sl_app_start_gl(sl_app *app, char *err, size_t n) {
    sl_texture_prefetch_start(app); /* decoding the material textures while the context is made */
    char cache[4096];
    sl_startup_shader_cache(cache, sizeof cache); /* before the context: Mesa reads it then */
    if (*cache) SL_DEBUG("Mesa shader cache: %s", cache);
    sl_startup_mark("parameters, camera, shader cache dir");
    if (!sl_backend_create(&app->backend, app->opt.backend, app->opt.width, app->opt.height, "shadelab", err, n))
        return false;
    sl_startup_mark("GL context (%s)", app->backend.name);
    app->gl_ready = true;
    const char *missing = NULL;
    if (!sl_gl_load(app->backend.get_proc_address, &missing)) {
        snprintf(err, n, "%s backend: OpenGL entry point %s is missing", app->backend.name, missing);
        return false;
    }
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    if (is_cpu_renderer(renderer)) app->backend.is_gpu = false;
    SL_DEBUG("backend %s: %s, OpenGL %s", app->backend.name, renderer, glGetString(GL_VERSION));
    sl_host_set_gl_app(app);
    if (!sl_renderer_create(app, err, n)) return false;
    sl_startup_mark("renderer (core programs)");
    for (int i = 1; i < app->plugins.count; i++) {
        sl_plugin_rec *r = app->plugins.items[i];
        if (!r->ok) continue;
        if (r->desc.activate) {
            sl_status st = r->desc.activate(r->user);
            if (st != SL_OK) {
                r->ok = false;
                free(r->disabled_reason);
                char why[128];
                snprintf(why, sizeof why, "activate() failed with status %d", (int)st);
                r->disabled_reason = strdup(why);
                SL_ERROR("plugin %s disabled: %s", r->id, why);
                if (app->opt.strict) { snprintf(err, n, "--strict: plugin %s: %s", r->id, why); return false; }
                continue;
            }
        }
        r->active = true;
        sl_startup_mark("activate %s", r->id);
    }
    bool ok = sl_renderer_load_scene(app, err, n);
    sl_startup_mark("scene to GL (textures, meshes, material programs)");
    return ok;
}

/* A plugin's disabled reason from a compile message: its first line naming an error
 * ("plugins/x/x.glsl:4(22): error: …"), for --list-plugins and the panel. */
static char *glsl_reason(const char *why) {
    const char *line = why;
    for (const char *p = why; p && *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : NULL) {
        const char *end = strchr(p, '\n');
        const char *e = strstr(p, "error");
        if (e && (!end || e < end)) { line = p; break; }
    }
    size_t len = strchr(line, '\n') ? (size_t)(strchr(line, '\n') - line) : strlen(line);
    char buf[1200];
    snprintf(buf, sizeof buf, "its GLSL does not compile: %.*s", (int)(len < 1100 ? len : 1100), line);
    return strdup(buf);
}

/* core.render_scale: the renderer's size is that fraction of the window's (the present scales up). */
static void render_size(sl_app *app, int *w, int *h) {
    sl_param *q = sl_params_find(&app->params, "core.render_scale");
    double s = q ? q->value.f[0] : 1;
    *w = (int)lround(app->backend.width * s), *h = (int)lround(app->backend.height * s);
    if (*w < 1) *w = 1;
    if (*h < 1) *h = 1;
}

static void apply_render_scale(sl_app *app) {
    int w, h;
    render_size(app, &w, &h);
    sl_renderer_resize(app, w, h, app->backend.width, app->backend.height);
}

bool sl_app_render_frame(sl_app *app) {
    sl_budget_before_frame(app); /* the render scale and knob settings of this frame (core.budget) */
    apply_render_scale(app);
    bool ok = sl_renderer_frame(app, 0, app->opt.accumulate);
    /* Plugins' programs compile at their first use (lazy creation, docs/design-notes.md). One
     * that fails disables its plugin, as a failing activate() does, and the frame is rendered
     * again without it, so no image shows a pass that drew nothing; --strict makes it fatal. */
    char why[16384];
    for (int k, tries = 0; (k = sl_renderer_failed_plugin(app, why, sizeof why)) >= 0 && tries < 64; tries++) {
        sl_plugin_rec *r = app->plugins.items[k];
        if (!r->ok) continue; /* already off (its pass program and a material both broke) */
        r->ok = false;
        r->glsl_failed = true;
        free(r->disabled_reason);
        r->disabled_reason = glsl_reason(why);
        /* the one message: the program, file:line and the compiler's words (the window shows it) */
        SL_ERROR("plugin %s disabled, its GLSL does not compile: %s", r->id, why);
        /* as switching it off: its passes leave the plan, its GLSL chunks the materials */
        app->params.version++;
        app->params.recompile_version++;
        sl_renderer_invalidate(app);
        if (app->opt.strict && !app->strict_failure) {
            char msg[4200];
            snprintf(msg, sizeof msg, "--strict: plugin %s: a program failed to compile", r->id);
            app->strict_failure = strdup(msg);
        }
        ok = sl_renderer_frame(app, 0, app->opt.accumulate);
    }
    /* the start-up profile covers the first two frames (main.c ends and prints it after them
     * for a headless run; the window's loop stops recording here, after a third) */
    if (app->frame_index >= 3 && sl_startup_recording()) sl_startup_end();
    /* after the first frame every plugin has had its chance to read the environment */
    const sl_environment *env = &app->scene.environment;
    if (app->frame_index == 1 && env->map && !app->environment_read)
        SL_WARN("%s: environment map '%s' is not used: no loaded plugin reads the environment (the file is never "
                "opened)", app->scene.path, env->map);
    return ok;
}

/* A target at the window's size: scaled up bilinearly (pixel centres, clamped at the edges, as the
 * window's GL_LINEAR present) when it is smaller (core.render_scale < 1 without an upscaler). */
static bool read_at_window_size(sl_app *app, const char *name, float *rgba) {
    int w, h, W = app->backend.width, H = app->backend.height;
    if (!sl_renderer_read_size(app, name, &w, &h)) return false;
    if (w == W && h == H) return sl_renderer_read(app, name, rgba);
    float *src = malloc((size_t)w * h * 4 * sizeof(float));
    bool ok = src && sl_renderer_read(app, name, src);
    for (int y = 0; ok && y < H; y++) {
        double fy = fmin(fmax((y + 0.5) * h / H - 0.5, 0), h - 1);
        int y0 = (int)fy, y1 = y0 + 1 < h ? y0 + 1 : y0;
        for (int x = 0; x < W; x++) {
            double fx = fmin(fmax((x + 0.5) * w / W - 0.5, 0), w - 1);
            int x0 = (int)fx, x1 = x0 + 1 < w ? x0 + 1 : x0;
            double ax = fx - x0, ay = fy - y0;
            for (int c = 0; c < 4; c++) {
                double top = src[((size_t)y0 * w + x0) * 4 + c] * (1 - ax) + src[((size_t)y0 * w + x1) * 4 + c] * ax;
                double bot = src[((size_t)y1 * w + x0) * 4 + c] * (1 - ax) + src[((size_t)y1 * w + x1) * 4 + c] * ax;
                rgba[((size_t)y * W + x) * 4 + c] = (float)(top * (1 - ay) + bot * ay);
            }
        }
    }
    free(src);
    return ok;
}

bool sl_app_read_color(sl_app *app, float *rgba) { return read_at_window_size(app, "color", rgba); }
bool sl_app_read_display(sl_app *app, float *rgba) { return read_at_window_size(app, "display", rgba); }

bool sl_app_save(sl_app *app, const char *path, char *err, size_t n) {
    int w = app->backend.width, h = app->backend.height;
    const sl_frame_stats *st = sl_renderer_stats(app);
    (void)st;
    float *px = malloc((size_t)w * h * 4 * sizeof(float));
    const char *ext = strrchr(path, '.');
    bool hdr = ext && (!strcasecmp(ext, ".exr") || !strcasecmp(ext, ".hdr"));
    bool ok = hdr ? sl_app_read_color(app, px) : sl_app_read_display(app, px);
    if (ok) ok = sl_image_write(path, px, w, h, !hdr, err, n);
    else snprintf(err, n, "nothing rendered yet");
    free(px);
    return ok;
}

void sl_app_resize(sl_app *app, int w, int h) {
    app->backend.width = w;
    app->backend.height = h;
    apply_render_scale(app);
}

void sl_app_shutdown(sl_app *app) {
    sl_texture_prefetch_finish(app);
    free(app->strict_failure);
    app->strict_failure = NULL;
    if (app->gl_ready) {
        for (int i = app->plugins.count - 1; i >= 1; i--) {
            sl_plugin_rec *r = app->plugins.items[i];
            if (r->active && r->desc.deactivate) r->desc.deactivate(r->user);
            r->active = false;
        }
        sl_renderer_destroy(app);
    }
    sl_post_free(app);
    sl_budget_free(app);
    sl_plugins_shutdown(&app->plugins);
    if (app->gl_ready) sl_backend_destroy(&app->backend);
    sl_host_set_gl_app(NULL);
    if (app->materials) {
        for (int m = 0; m < app->scene.material_count; m++) {
            for (int i = 0; i < app->materials[m].count; i++) free(app->materials[m].values[i].str);
            free(app->materials[m].values);
        }
        free(app->materials);
    }
    free(app->light_params);
    if (app->scene_loaded) sl_scene_free(&app->scene);
    sl_params_free(&app->params);
    free(app->debug_view);
    memset(app, 0, sizeof *app);
}
