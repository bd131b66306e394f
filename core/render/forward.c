#include "render/forward.h"
#include "render/renderer_internal.h"
#include "plugin_lights.h"
#include "state.h"
#include "log.h"
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

void sl_glsl_ident(const char *in, char *out, size_t n, bool upper) {
    size_t i = 0;
    for (; in[i] && i + 1 < n; i++) {
        char c = in[i];
        out[i] = isalnum((unsigned char)c) ? (upper ? toupper((unsigned char)c) : c) : '_';
    }
    out[i] = 0;
}

/* The light types the forward programs specialise on: the SET of types of the scene's lights,
 * enabled or not (issue 18). A type with no enabled light keeps its loop and gets an empty range,
 * so toggling or adding a light of a present type changes only the light buffer and the range
 * uniforms, never a program; only a light of a new type composes new programs. A plugin's light
 * (plugin_lights.h) counts only while it is on: a scene pays nothing for one it does not use. */
static bool counts(sl_app *app, const sl_light *L) { return !L->plugin || sl_light_on(app, L); }

int sl_forward_light_types(sl_app *app, const char **types, int max) {
    int n = 0;
    for (int i = 0; i < app->scene.light_count; i++) {
        const sl_light *L = &app->scene.lights[i];
        if (!counts(app, L)) continue;
        bool seen = false;
        for (int k = 0; k < n; k++) seen |= !strcmp(types[k], L->type);
        if (!seen && n < max) types[n++] = L->type;
    }
    return n;
}

/* Whether the forward programs have a loop of their own for the lights that cast shadows: a
 * light of the scene casts them, enabled or not (as the SHADOW hook; toggling a light recompiles
 * nothing). sl_gpu_pack_lights puts the enabled casters of the types with an l/E pair first in the
 * light buffer, in ranges sl_shadowed_<type>, the rest in sl_lights_<type>; only the casters' loop
 * calls the SHADOW hook. */
bool sl_forward_shadow_casters(sl_app *app) {
    for (int i = 0; i < app->scene.light_count; i++) {
        const sl_light *L = &app->scene.lights[i];
        if (counts(app, L) && L->cast_shadows && sl_forward_light_type_lit(app, L->type)) return true;
    }
    return false;
}

/* A light type with an l/E pair (a LIGHT chunk without SL_CHUNK_LIGHT_RADIANCE), from the loaded
 * plugins, enabled or not: the light buffer's layout does not change when a plugin is toggled. */
bool sl_forward_light_type_lit(sl_app *app, const char *type) {
    for (int i = 0; i < app->plugins.chunk_count; i++) {
        const sl_chunk_reg *c = &app->plugins.chunks[i];
        if (c->d.hook == SL_HOOK_LIGHT && c->d.name && !strcmp(c->d.name, type)) return !(c->d.flags & SL_CHUNK_LIGHT_RADIANCE);
    }
    return false;
}

/* A loop over the lights in [<prefix>_<ids[0]>.x, <prefix>_<ids[n-1]>.y) of sl_lights, as a
 * do-while: llvmpipe runs a loop's body under a mask of the lanes still in it, and a for loop's
 * test at the top runs the body once more after the last light with every lane masked (at full
 * cost: 4 runs for 3 lights). The body runs once for an empty range, masked off by i < end (the
 * ranges do not hold end, and `body` tests it where it calls without a range test); the record
 * read is clamped into the buffer. */
static void emit_light_loop(sl_strbuf *gen, const char *prefix, const char (*ids)[128], int n, const char *body) {
    sl_sb_printf(gen,
                 "    {\n"
                 "        int i = %s_%s.x, end = %s_%s.y;\n"
                 "        do {\n"
                 "            SlLight L = sl_lights[max(min(i, end - 1), 0)];\n"
                 "%s"
                 "            ++i;\n"
                 "        } while (i < end);\n"
                 "    }\n",
                 prefix, ids[0], prefix, ids[n - 1], body);
}

/* After a model evaluated one light of the loop: the light's state (common.glsl) back to what
 * the code outside the light loop sees. */
#define LIGHT_DONE "sl_light_spread = 0.0; sl_light_in_loop = false;"

/* The loop over the lights of the types with an l/E pair (ids, in buffer order) in the ranges
 * <prefix>_<type>: the type found by range (else-if), one evaluation of the model with E × `vis`. */
static void emit_lit_loop(sl_strbuf *gen, const char *prefix, const char (*ids)[128], int n,
                          const sl_chunk_reg *const *light_chunks, const int *lit_types, const char *per_light,
                          const char *vis) {
    sl_strbuf b = {0};
    if (n == 1) {
        sl_sb_printf(&b, "            vec3 l, E;\n            sl_light_in_loop = true;\n"
                         "            if (i < end && %s(L, s, l, E)) Lo += %s(s, l, %s);\n"
                         "            " LIGHT_DONE "\n",
                     light_chunks[lit_types[0]]->d.function, per_light, vis);
    } else {
        sl_sb_append(&b, "            vec3 l = vec3(0.0), E = vec3(0.0);\n            bool lit = false;\n"
                         "            sl_light_in_loop = true;\n");
        for (int k = 0; k < n; k++)
            sl_sb_printf(&b, "            %sif (i >= %s_%s.x && i < %s_%s.y) lit = %s(L, s, l, E);\n", k ? "else " : "",
                         prefix, ids[k], prefix, ids[k], light_chunks[lit_types[k]]->d.function);
        sl_sb_printf(&b, "            if (lit) Lo += %s(s, l, %s);\n            " LIGHT_DONE "\n", per_light, vis);
    }
    emit_light_loop(gen, prefix, ids, n, b.s ? b.s : "");
    sl_sb_free(&b);
}

/* The enabled chunk of this hook and name; a view of a pass's resource (SL_CHUNK_PASS_VIEW) is the
 * display pass's, never part of a material program. */
static const sl_chunk_reg *find_named(sl_app *app, sl_hook hook, const char *name) {
    for (int i = 0; i < app->plugins.chunk_count; i++) {
        const sl_chunk_reg *c = &app->plugins.chunks[i];
        if (c->d.hook == hook && c->d.name && !strcmp(c->d.name, name) && sl_plugin_enabled(&app->plugins, c->owner) &&
            !(c->d.flags & SL_CHUNK_PASS_VIEW))
            return c;
    }
    return NULL;
}

/* The plugins that declared a parameter (its owner and, for shared material/light keys, every
 * other declarer), as a bit mask over plugin indices. */
static uint64_t declarers_of(sl_plugins *P, const sl_param *q) {
    int owner = sl_plugins_find(P, q->owner);
    return q->declared_by | (owner >= 0 ? 1ull << (owner & 63) : 0);
}

/* A material "has" a key when it carries a value and a plugin that declares the key is on: a
 * chunk gated on normal_map (ggx's specular AA) drops out with the normal-map plugin. */
static bool material_has(sl_app *app, int m, const char *key) {
    sl_mat_value *v = sl_app_material_value(app, m, key);
    if (!v || !v->present) return false;
    uint64_t declarers = declarers_of(&app->plugins, &app->params.items[v->param]);
    for (int i = 0; i < app->plugins.count && i < 64; i++)
        if ((declarers & (1ull << i)) && sl_plugin_enabled(&app->plugins, i)) return true;
    return false;
}

/* Whether some node carrying `tag` (its own or an ancestor's) draws a mesh of material m: a
 * VERTEX hook gated on the tag (when_node_tag) is left out of programs no such node uses. */
static bool material_drawn_with_tag(sl_app *app, int m, const char *tag) {
    const sl_scene *s = &app->scene;
    for (int ni = 0; ni < s->node_count; ni++)
        for (int k = 0; k < s->nodes[ni].mesh_count; k++)
            if (s->meshes[s->nodes[ni].meshes[k]].material == m && sl_scene_node_has_tag(s, ni, tag)) return true;
    return false;
}

/* Whether a mesh with vertex colours (sl_mesh_data.colors) is drawn with material m: its programs
 * then read them (SL_MAT_USES_VERTEX_COLOR); others fetch nothing more. */
static bool material_has_vertex_colors(const sl_app *app, int m) {
    for (int i = 0; i < app->scene.mesh_count; i++)
        if (app->scene.meshes[i].material == m && app->scene.meshes[i].data.colors) return true;
    return false;
}

/* A chunk's when_param (ABI 1.17): its plugin's bool parameter of that id is on (checked at load:
 * a bool global with SL_PARAM_NEEDS_RECOMPILE). */
static bool gate_param_on(sl_app *app, const sl_chunk_reg *h) {
    char full[300];
    snprintf(full, sizeof full, "%s.%s", app->plugins.items[h->owner]->id, h->d.when_param);
    const sl_param *q = sl_params_find(&app->params, full);
    return q && q->value.b;
}

/* Whether hook chunk h's gates let it into material m's programs: its plugin is on, and
 * when_material_has, when_model (the material's own model, also in override programs: its surface
 * stays the same), when_node_tag and when_param pass. */
static bool gates_pass(sl_app *app, const sl_chunk_reg *h, int m) {
    const sl_material *mat = &app->scene.materials[m];
    return sl_plugin_enabled(&app->plugins, h->owner) &&
           (!h->d.when_material_has || material_has(app, m, h->d.when_material_has)) &&
           (!h->d.when_model || !strcmp(h->d.when_model, mat->model ? mat->model : "lambert")) &&
           (!h->d.when_node_tag || material_drawn_with_tag(app, m, h->d.when_node_tag)) &&
           (!h->d.when_param || gate_param_on(app, h));
}

bool sl_forward_reads_scene_behind(sl_app *app, int m) {
    for (int i = 0; i < app->plugins.chunk_count; i++) {
        const sl_chunk_reg *h = &app->plugins.chunks[i];
        if (h->d.hook == SL_HOOK_SCENE_BEHIND && gates_pass(app, h, m)) return true;
    }
    return false;
}

static int cmp_chunk_order(const void *a, const void *b) {
    const sl_chunk_reg *x = *(const sl_chunk_reg *const *)a, *y = *(const sl_chunk_reg *const *)b;
    if (x->d.order != y->d.order) return x->d.order < y->d.order ? -1 : 1;
    return x->owner - y->owner;
}

/* #define lines for a value that needs recompiling (bools 0/1, enums by index + names). */
static void define_value(sl_strbuf *b, const char *macro, const sl_param *q, const sl_value *v) {
    switch (q->desc.type) {
    case SL_PARAM_BOOL: sl_sb_printf(b, "#define %s %d\n", macro, v->b ? 1 : 0); break;
    case SL_PARAM_INT: sl_sb_printf(b, "#define %s %d\n", macro, v->i); break;
    case SL_PARAM_FLOAT: sl_sb_printf(b, "#define %s %.9g\n", macro, v->f[0]); break;
    case SL_PARAM_ENUM:
        sl_sb_printf(b, "#define %s %d\n", macro, v->i);
        for (int k = 0; q->desc.enum_values[k]; k++) {
            char id[128];
            sl_glsl_ident(q->desc.enum_values[k], id, sizeof id, true);
            sl_sb_printf(b, "#define %s_%s %d\n", macro, id, k);
        }
        break;
    case SL_PARAM_COLOR:
    case SL_PARAM_VEC3: sl_sb_printf(b, "#define %s vec3(%.9g, %.9g, %.9g)\n", macro, v->f[0], v->f[1], v->f[2]); break;
    case SL_PARAM_TEXTURE: break;
    }
}

static const char *glsl_type(sl_param_type t) {
    switch (t) {
    case SL_PARAM_BOOL: return "bool";
    case SL_PARAM_INT: case SL_PARAM_ENUM: return "int";
    case SL_PARAM_FLOAT: return "float";
    case SL_PARAM_COLOR: case SL_PARAM_VEC3: return "vec3";
    case SL_PARAM_TEXTURE: return "sampler2D";
    }
    return "float";
}

/* vec2 sl_uv_<key>(SlSurface s): where the material's texture `q` is read. s.uv unless the
 * material maps the slot otherwise (sl_uv_mapping: glTF texCoord 1, KHR_texture_transform
 * uv' = T(offset) R(rotation) S(scale) uv, R = [cos sin; −sin cos]), as constants: a transform
 * costs a few multiply-adds, none when absent. Returns whether it reads UV set 1. */
static bool uv_function(sl_strbuf *b, const sl_material *mat, const sl_param *q) {
    const sl_uv_mapping *map = NULL;
    for (int k = 0; q->desc.material_input && k < mat->uv_map_count; k++)
        if (!strcmp(mat->uv_maps[k].input, q->desc.material_input)) map = &mat->uv_maps[k];
    if (!map) {
        sl_sb_printf(b, "vec2 sl_uv_%s(SlSurface s) { return s.uv; }\n", q->full_id);
        return false;
    }
    double c = cos(map->rotation), sn = sin(map->rotation);
    sl_sb_printf(b,
                 "vec2 sl_uv_%s(SlSurface s) { // %s: UV set %d, offset (%g, %g), rotation %g, scale (%g, %g)\n"
                 "    vec2 t = s.uv%s;\n"
                 "    return vec2(%.9g * t.x + %.9g * t.y + %.9g, %.9g * t.x + %.9g * t.y + %.9g);\n}\n",
                 q->full_id, map->input, map->texcoord, map->offset[0], map->offset[1], map->rotation, map->scale[0],
                 map->scale[1], map->texcoord == 1 ? "1" : "", map->scale[0] * c, map->scale[1] * sn, map->offset[0],
                 -map->scale[0] * sn, map->scale[1] * c, map->offset[1]);
    return map->texcoord == 1;
}

/* The plugin whose resource directory holds `path` (a draw_scene fragment), or 0. */
static int owner_of_file(const sl_plugins *P, const char *path) {
    for (int i = 1; i < P->count; i++) {
        const char *dir = P->items[i]->resource_dir;
        size_t l = dir ? strlen(dir) : 0;
        if (l && !strncmp(path, dir, l) && path[l] == '/') return i;
    }
    return 0;
}

/* The plugin to blame for a material program that failed to compile, or -1: the owner of the
 * file the first error names (sl_source_include_from); else the plugin with a chunk function the
 * log quotes (a generated call to a function its file lacks); else the one plugin contributing. */
static int blame_compile_error(const sl_plugins *P, const sl_program *p, uint64_t owners) {
    if (p->error_owner >= 1) return p->error_owner;
    for (int i = 0; p->error && i < P->chunk_count; i++) {
        const sl_chunk_reg *c = &P->chunks[i];
        if (c->owner < 1 || !(owners & (1ull << (c->owner & 63))) || !c->d.function) continue;
        char quoted[2][300];
        snprintf(quoted[0], sizeof quoted[0], "'%s'", c->d.function);
        snprintf(quoted[1], sizeof quoted[1], "`%s'", c->d.function);
        if (strstr(p->error, quoted[0]) || strstr(p->error, quoted[1])) return c->owner;
    }
    int only = -1;
    for (int i = 1; i < P->count && i < 64; i++)
        if (owners & (1ull << i)) only = only < 0 ? i : 64;
    return only < 64 ? only : -1;
}

/* ------------------------------------------------------------------ composition ----- */

/* What one material program is made of, gathered step by step by sl_forward_compose: each step
 * below fills its part, and a step that meets a limit fails with a message naming what overflowed
 * and the plugin to blame. */
typedef struct composition {
    sl_app *app;
    sl_plugins *P;
    int m;
    const sl_material *mat;
    const sl_variant_request *req;
    /* choose_model_and_view, choose_lights */
    const char *model;                                 /* the shading model's name */
    const sl_chunk_reg *model_chunk, *model_ambient, *model_lobes, *view, *shadow, *loop;
    const char *types[SL_MAX_LIGHT_TYPES];             /* the scene's light types, packing order */
    const sl_chunk_reg *light_chunks[SL_MAX_LIGHT_TYPES];
    int ntypes;
    bool casters;                                      /* the shadow casters have a loop of their own */
    /* gather_gated_hooks: the hooks this material gets, in their order */
    const sl_chunk_reg *vertex[SL_MAX_HOOKS], *surface[SL_MAX_HOOKS], *ambient[SL_MAX_HOOKS], *displacement[SL_MAX_HOOKS],
        *behind[SL_MAX_HOOKS];
    int nv, ns, na, nd, nb;
    const char *node_tags[SL_MAX_NODE_TAGS];           /* when_node_tag of the VERTEX hooks, bit order */
    int node_tag_count;
    /* list_fragment_chunks: the fragment stage's chunks in include order (at most every hook of three
     * kinds, a chunk per light type and six single ones), and every plugin involved */
    const sl_chunk_reg *list[3 * SL_MAX_HOOKS + SL_MAX_LIGHT_TYPES + 6];
    int count;
    uint64_t owners;                                   /* bit i: plugin i (sl_plugins_load keeps i < 64) */
    /* write_prelude */
    bool bare_depth, motion, normal, uses_uv1;
    sl_strbuf pre, uni, uvf, explain;                  /* defines; uniforms; sl_uv_<key>(); --explain text */
    int culprit;                                       /* the plugin a failure is blamed on, or 0 */
    char *err;
    size_t n;
} composition;

static bool compose_fail(composition *c, int culprit, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static bool compose_fail(composition *c, int culprit, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->err, c->n, fmt, ap);
    va_end(ap);
    c->culprit = culprit;
    return false;
}

static bool include_chunk(composition *c, sl_source *src, const sl_chunk_reg *chunk) {
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", c->P->items[chunk->owner]->resource_dir, chunk->d.file);
    if (sl_source_include_from(src, path, chunk->owner, c->err, c->n)) return true;
    c->culprit = chunk->owner; /* a file that cannot be included: its plugin is to blame */
    return false;
}

/* The shading model (the material's, an override's, or Lambert when none is provided), the
 * model's MODEL_AMBIENT chunk and the active debug view. */
static void choose_model_and_view(composition *c) {
    sl_app *app = c->app;
    c->model = c->req->model_override ? c->req->model_override : c->mat->model ? c->mat->model : "lambert";
    c->model_chunk = find_named(app, SL_HOOK_SHADING_MODEL, c->model);
    if (!c->model_chunk) {
        c->model_chunk = find_named(app, SL_HOOK_SHADING_MODEL, "lambert");
        c->model = "lambert";
    }
    c->model_ambient = find_named(app, SL_HOOK_MODEL_AMBIENT, c->model);
    c->model_lobes = find_named(app, SL_HOOK_MODEL_LOBES, c->model); /* ABI 1.14 */
    if (app->debug_view && !c->req->model_override) {
        c->view = find_named(app, SL_HOOK_DEBUG_VIEW, app->debug_view);
        if (!c->view) c->view = find_named(app, SL_HOOK_DEBUG_VIEW_LIGHT, app->debug_view);
    }
}

/* The light types present and their LIGHT chunks, the SHADOW hook (only when a light casts
 * shadows, enabled or not, like the types: toggling a light recompiles nothing; the first
 * provider) and the LIGHT_LOOP hook (ABI 1.7: the forward programs' light iteration; the first
 * provider). */
static void choose_lights(composition *c) {
    sl_app *app = c->app;
    sl_plugins *P = c->P;
    c->ntypes = sl_forward_light_types(app, c->types, SL_MAX_LIGHT_TYPES);
    for (int t = 0; t < c->ntypes; t++) c->light_chunks[t] = find_named(app, SL_HOOK_LIGHT, c->types[t]);
    for (int i = 0; i < app->scene.light_count && !c->shadow; i++)
        for (int k = 0; k < P->chunk_count && !c->shadow && app->scene.lights[i].cast_shadows &&
                        counts(app, &app->scene.lights[i]); k++)
            if (P->chunks[k].d.hook == SL_HOOK_SHADOW && sl_plugin_enabled(P, P->chunks[k].owner)) c->shadow = &P->chunks[k];
    c->casters = sl_forward_shadow_casters(app); /* the casters' ranges and loop (sl_gpu_pack_lights) */
    bool forward = c->req->kind == SL_VARIANT_FORWARD && !c->req->model_override;
    for (int k = 0; k < P->chunk_count && !c->loop && forward; k++)
        if (P->chunks[k].d.hook == SL_HOOK_LIGHT_LOOP && sl_plugin_enabled(P, P->chunks[k].owner)) c->loop = &P->chunks[k];
}

static const char *hook_name(sl_hook h) {
    switch (h) {
    case SL_HOOK_VERTEX: return "VERTEX";
    case SL_HOOK_SURFACE: return "SURFACE";
    case SL_HOOK_AMBIENT: return "AMBIENT";
    case SL_HOOK_DISPLACEMENT: return "DISPLACEMENT";
    case SL_HOOK_SCENE_BEHIND: return "SCENE_BEHIND";
    default: return "?";
    }
}

/* The VERTEX, SURFACE, AMBIENT, DISPLACEMENT and SCENE_BEHIND hooks whose gates this material
 * passes (gates_pass), sorted by order; SCENE_BEHIND only in the core's own forward programs (the
 * forward-behind pass binds what it reads). More than SL_MAX_HOOKS of one kind, or more than
 * SL_MAX_NODE_TAGS node tags, is an error blamed on the hook one too many. */
static bool gather_gated_hooks(composition *c) {
    bool forward_main = c->req->kind == SL_VARIANT_FORWARD && !c->req->model_override && !c->req->fragment;
    for (int i = 0; i < c->P->chunk_count; i++) {
        const sl_chunk_reg *h = &c->P->chunks[i];
        const sl_chunk_reg **into;
        int *count;
        switch (h->d.hook) {
        case SL_HOOK_VERTEX: into = c->vertex, count = &c->nv; break;
        case SL_HOOK_SURFACE: into = c->surface, count = &c->ns; break;
        case SL_HOOK_AMBIENT: into = c->ambient, count = &c->na; break;
        case SL_HOOK_DISPLACEMENT: into = c->displacement, count = &c->nd; break;
        case SL_HOOK_SCENE_BEHIND:
            if (!forward_main) continue;
            into = c->behind, count = &c->nb;
            break;
        default: continue;
        }
        if (!gates_pass(c->app, h, c->m)) continue;
        if (*count == SL_MAX_HOOKS)
            return compose_fail(c, h->owner, "material \"%s\": plugin %s's %s hook %s is one too many: a material takes "
                                "at most %d %s hooks (forward.h, SL_MAX_HOOKS)", c->mat->name, c->P->items[h->owner]->id,
                                hook_name(h->d.hook), h->d.function, SL_MAX_HOOKS, hook_name(h->d.hook));
        if (h->d.when_node_tag && c->node_tag_count == SL_MAX_NODE_TAGS)
            return compose_fail(c, h->owner, "material \"%s\": plugin %s's VERTEX hook %s is gated on a node tag one too "
                                "many: a material's hooks use at most %d node tags (forward.h, SL_MAX_NODE_TAGS)",
                                c->mat->name, c->P->items[h->owner]->id, h->d.function, SL_MAX_NODE_TAGS);
        into[(*count)++] = h;
        if (h->d.when_node_tag) c->node_tag_count++;
    }
    qsort(c->displacement, c->nd, sizeof *c->displacement, cmp_chunk_order);
    qsort(c->vertex, c->nv, sizeof *c->vertex, cmp_chunk_order);
    qsort(c->surface, c->ns, sizeof *c->surface, cmp_chunk_order);
    /* the bits of sl_vertex_hook_mask, in the hooks' order */
    c->node_tag_count = 0;
    for (int i = 0; i < c->nv; i++)
        if (c->vertex[i]->d.when_node_tag) c->node_tags[c->node_tag_count++] = c->vertex[i]->d.when_node_tag;
    return true;
}

static void add_owner(composition *c, const sl_chunk_reg *chunk) { c->owners |= 1ull << chunk->owner; }

/* The fragment stage's chunks in include order, and the plugins involved (their parameters
 * become the program's uniforms, their bind callbacks run when it is bound). */
static void list_fragment_chunks(composition *c) {
    c->owners = 1; /* the core */
    const sl_chunk_reg *single[] = {c->shadow, c->model_chunk, c->model_ambient, c->model_lobes, c->loop, c->view};
    if (c->req->kind == SL_VARIANT_FORWARD) {
        for (int i = 0; i < c->ns; i++) c->list[c->count++] = c->surface[i];
        if (single[0]) c->list[c->count++] = single[0];
        for (int t = 0; t < c->ntypes; t++)
            if (c->light_chunks[t]) c->list[c->count++] = c->light_chunks[t];
        for (int k = 1; k < 5; k++)
            if (single[k]) c->list[c->count++] = single[k];
        for (int i = 0; i < c->na; i++) c->list[c->count++] = c->ambient[i];
        for (int i = 0; i < c->nb; i++) c->list[c->count++] = c->behind[i];
        if (single[5]) c->list[c->count++] = single[5];
    }
    for (int i = 0; i < c->count; i++) add_owner(c, c->list[i]);
    for (int i = 0; i < c->nv; i++) {
        add_owner(c, c->vertex[i]);
        sl_sb_printf(&c->explain, "%s%s:%s (vertex)", c->explain.len ? ", " : "", c->P->items[c->vertex[i]->owner]->id,
                     c->vertex[i]->d.function);
    }
    for (int i = 0; i < c->nd; i++) {
        add_owner(c, c->displacement[i]);
        sl_sb_printf(&c->explain, "%s%s:%s (displacement)", c->explain.len ? ", " : "",
                     c->P->items[c->displacement[i]->owner]->id, c->displacement[i]->d.function);
    }
}

/* The defines every stage starts with: version, radiance limit, model, program kind, debug view. */
static void write_defines(composition *c) {
    const sl_variant_request *req = c->req;
    sl_strbuf *pre = &c->pre;
    sl_sb_append(pre, "#version 450 core\n");
    /* what the colour target holds: the forward pass clamps its output to it (scene.h) */
    sl_sb_printf(pre, "#define SL_MAX_RADIANCE %.9g\n", c->app->opt.float32 ? 3.0e38 : SL_MAX_RADIANCE);
    char model_id[128]; /* SL_MODEL_<NAME>: lets a chunk shared by several models specialise */
    sl_glsl_ident(c->model, model_id, sizeof model_id, true);
    if (!c->bare_depth) sl_sb_printf(pre, "#define SL_MODEL_%s 1\n", model_id);
    if (c->model_lobes && req->kind == SL_VARIANT_FORWARD) sl_sb_append(pre, "#define SL_MODEL_HAS_LOBES 1\n");
    if ((c->model_chunk->d.flags & SL_CHUNK_MASKS_FACING_AWAY) && !c->bare_depth)
        sl_sb_append(pre, "#define SL_MODEL_MASKS_FACING_AWAY 1\n");
    if (req->fragment) sl_sb_append(pre, "#define SL_CUSTOM_MAIN 1\n"); /* a plugin's main (draw_scene fragment, ABI 1.7) */
    if (req->fullscreen) sl_sb_append(pre, "#define SL_FULLSCREEN_MATERIAL 1\n");
    if (c->nb) sl_sb_append(pre, "#define SL_SCENE_BEHIND 1\n"); /* drawn by forward-behind (ABI 1.17) */
    if (sl_environment_is_constant(&c->app->scene.environment)) sl_sb_append(pre, "#define SL_ENVIRONMENT_CONSTANT 1\n");
    if (c->motion) sl_sb_append(pre, "#define SL_MOTION_VECTORS 1\n");
    if (c->normal) sl_sb_printf(pre, "#define SL_NORMAL_TARGET 1\n#define SL_NORMAL_LOCATION %d\n", c->motion ? 2 : 1);
    if (c->view) {
        char id[128];
        sl_glsl_ident(c->view->d.name, id, sizeof id, true);
        sl_sb_printf(pre, "#define SL_DEBUG_VIEW_%s 1\n", id);
        /* a view that replaces the whole output (not a per-light one): passes adding light skip it */
        if (c->view->d.hook == SL_HOOK_DEBUG_VIEW) sl_sb_append(pre, "#define SL_DEBUG_VIEW_REPLACES_OUTPUT 1\n");
    }
}

/* A material key of the plugins involved: a define for its presence, then a sampler (textures, on
 * the material units of host.h), a define (needs recompile) or a uniform. More texture keys than
 * units is an error naming the first key left out (reported once per variant). */
static void write_material_key(composition *c, int i, sl_forward_variant *out) {
    const sl_param *q = &c->app->params.items[i];
    sl_mat_value *v = c->bare_depth ? NULL : sl_app_material_value(c->app, c->m, q->full_id);
    if (!v) return;
    char up[160];
    sl_glsl_ident(q->full_id, up, sizeof up, true);
    if (v->present) sl_sb_printf(&c->pre, "#define SL_MAT_HAS_%s 1\n", up);
    if (q->desc.type == SL_PARAM_TEXTURE) {
        if (!v->present) return;
        if (out->texture_count == SL_TEXTURE_UNIT_MATERIAL_COUNT) {
            if (!out->texture_overflow_reported)
                SL_ERROR("material \"%s\": texture \"%s\" is left out: a material program binds at most %d textures "
                         "(host.h, SL_TEXTURE_UNIT_MATERIAL_COUNT)", c->mat->name, q->full_id, SL_TEXTURE_UNIT_MATERIAL_COUNT);
            out->texture_overflow_reported = true;
            return;
        }
        sl_sb_printf(&c->uni, "layout(binding = %d) uniform sampler2D sl_mat_%s;\n",
                     SL_TEXTURE_UNIT_MATERIAL_FIRST + out->texture_count, q->full_id);
        out->texture_params[out->texture_count++] = i;
        c->uses_uv1 |= uv_function(&c->uvf, c->mat, q);
    } else if (q->desc.flags & SL_PARAM_NEEDS_RECOMPILE) {
        char macro[200];
        snprintf(macro, sizeof macro, "SL_MAT_%s", up);
        define_value(&c->pre, macro, q, &v->v);
    } else {
        sl_sb_printf(&c->uni, "uniform %s sl_mat_%s;\n", glsl_type(q->desc.type), q->full_id);
    }
}

/* A global parameter of a plugin involved: a define (needs recompile) or a uniform <plugin>_<id>. */
static void write_global_param(composition *c, const sl_param *q) {
    char owner_id[128], id[160], up[160];
    sl_glsl_ident(q->owner, owner_id, sizeof owner_id, false);
    snprintf(id, sizeof id, "%s_%s", owner_id, q->desc.id);
    if (q->desc.flags & SL_PARAM_NEEDS_RECOMPILE) {
        sl_glsl_ident(id, up, sizeof up, true);
        define_value(&c->pre, up, q, &q->value);
    } else {
        sl_sb_printf(&c->uni, "uniform %s %s;\n", glsl_type(q->desc.type), id);
    }
}

/* The prelude every stage shares: defines, then the uniforms of the plugins involved. */
static void write_prelude(composition *c, sl_forward_variant *out) {
    sl_app *app = c->app;
    /* A depth program that reads nothing of its material (no alpha cut-out or blend dither, no
     * VERTEX or DISPLACEMENT hook) is the same text for every such material: no material or
     * model defines, uniforms or textures, so they share one program (one compile less per
     * material in the shadow maps; on llvmpipe each costs tens of ms at its first draw). */
    c->bare_depth = c->req->kind == SL_VARIANT_DEPTH && !c->nv && !c->nd && !material_has(app, c->m, "alpha_cutoff") &&
                    !sl_gpu_material_blended(app, c->m);
    /* "motion" (pass.h) is read by an enabled pass: the forward program writes it (location 1) */
    bool forward_main = c->req->kind == SL_VARIANT_FORWARD && !c->req->model_override && !c->req->fragment && app->renderer;
    c->motion = forward_main && R(app)->motion;
    c->normal = forward_main && R(app)->normal; /* "normal" (ABI 1.13): location 1, or 2 after "motion" */
    write_defines(c);
    out->texture_count = 0;
    for (int i = 0; i < app->params.count; i++) {
        const sl_param *q = &app->params.items[i];
        if (!(c->owners & declarers_of(c->P, q))) continue;
        if (q->desc.scope == SL_SCOPE_MATERIAL) write_material_key(c, i, out);
        else if (q->desc.scope == SL_SCOPE_GLOBAL && strcmp(q->desc.id, "enabled")) write_global_param(c, q);
    }
    if (c->uses_uv1) sl_sb_append(&c->pre, "#define SL_MAT_USES_UV1 1\n");
    /* vertex colours: the colour pass, and a depth pass that reads the coverage (alpha cut-out or
     * blend dither); never a full-screen material (no vertices) */
    bool coverage = material_has(app, c->m, "alpha_cutoff") || sl_gpu_material_blended(app, c->m);
    if (!c->bare_depth && !c->req->fullscreen && (c->req->kind == SL_VARIANT_FORWARD || coverage) &&
        material_has_vertex_colors(app, c->m))
        sl_sb_append(&c->pre, "#define SL_MAT_USES_VERTEX_COLOR 1\n");
}

/* The tessellation of a displaced material (DISPLACEMENT hooks, shader.h ABI 1.7): tess.vert runs
 * the VERTEX hooks and hands the object-space vertex on; the control stage sets per-edge levels
 * from each edge's endpoints (crack-free), the evaluation stage displaces along the normal. */
static bool compose_tessellation(composition *c, sl_program *p) {
    bool ok = sl_source_include(&p->vs, "sl:tess.vert", c->err, c->n);
    sl_source *stages[2] = {&p->tcs, &p->tes};
    const char *defines[2] = {"#define SL_TESS_CONTROL_STAGE 1\n", "#define SL_TESS_EVALUATION_STAGE 1\n"};
    sl_strbuf gen = {0};
    sl_sb_append(&gen, "float sl_tess_edge_level(vec3 a, vec3 b) {\n    float level = 1.0;\n");
    for (int i = 0; i < c->nd; i++) {
        if (c->displacement[i]->d.tess_level)
            sl_sb_printf(&gen, "    level = max(level, %s(a, b));\n", c->displacement[i]->d.tess_level);
        else sl_sb_append(&gen, "    level = max(level, sl_tess_screen_level(a, b, 8.0));\n");
    }
    sl_sb_append(&gen, "    return level;\n}\nfloat sl_run_displacement(SlVertex v) {\n    float h = 0.0;\n");
    for (int i = 0; i < c->nd; i++) sl_sb_printf(&gen, "    h += %s(v);\n", c->displacement[i]->d.function);
    sl_sb_append(&gen, "    return h;\n}\n");
    for (int k = 0; k < 2 && ok; k++) {
        sl_sb_append(&stages[k]->text, c->pre.s);
        sl_sb_append(&stages[k]->text, defines[k]);
        if (k == 1 && c->req->kind == SL_VARIANT_FORWARD) sl_sb_append(&stages[k]->text, "#define SL_TESS_NORMALS 1\n");
        ok = sl_source_include(stages[k], "sl:common.glsl", c->err, c->n);
        sl_source_generated(stages[k], c->uni.s ? c->uni.s : "");
        ok = ok && sl_source_include(stages[k], "sl:tess.glsl", c->err, c->n);
        for (int i = 0; i < c->nd && ok; i++) ok = include_chunk(c, stages[k], c->displacement[i]);
        if (ok) sl_source_generated(stages[k], gen.s);
        ok = ok && sl_source_include(stages[k], k == 0 ? "sl:tess.tesc" : "sl:tess.tese", c->err, c->n);
    }
    sl_sb_free(&gen);
    p->tessellated = true;
    return ok;
}

/* The vertex stage: the VERTEX hooks (those gated on a node tag under a bit of a per-draw
 * uniform, ABI 1.6), then forward.vert, the full-screen triangle, or the tessellation stages. */
static bool compose_vertex_stage(composition *c, sl_program *p) {
    bool ok = true;
    sl_sb_append(&p->vs.text, c->pre.s);
    sl_sb_append(&p->vs.text, "#define SL_VERTEX_STAGE 1\n");
    ok = ok && sl_source_include(&p->vs, "sl:common.glsl", c->err, c->n);
    sl_source_generated(&p->vs, c->uni.s ? c->uni.s : "");
    /* Motion vectors evaluate the VERTEX hooks at the previous frame's time as well: hooks read
     * sl_time, so here it names a variable that forward.vert sets before each evaluation. */
    if (c->motion)
        sl_source_generated(&p->vs, "uniform float sl_prev_time;\n"
                                    "float sl_motion_time_now() { return sl_time; }\n"
                                    "float sl_hook_time;\n"
                                    "#define sl_time sl_hook_time\n");
    for (int i = 0; i < c->nv && ok; i++) ok = include_chunk(c, &p->vs, c->vertex[i]);
    sl_strbuf gen = {0};
    if (c->node_tag_count) sl_sb_append(&gen, "uniform int sl_vertex_hook_mask; // bit k: node carries tag k\n");
    sl_sb_append(&gen, "void sl_run_vertex_hooks(inout SlVertex v) {\n");
    for (int i = 0, k = 0; i < c->nv; i++) {
        if (c->vertex[i]->d.when_node_tag)
            sl_sb_printf(&gen, "    if ((sl_vertex_hook_mask & %d) != 0) %s(v); // node tag \"%s\"\n", 1 << k++,
                         c->vertex[i]->d.function, c->vertex[i]->d.when_node_tag);
        else
            sl_sb_printf(&gen, "    %s(v);\n", c->vertex[i]->d.function);
    }
    sl_sb_append(&gen, "}\n");
    sl_source_generated(&p->vs, gen.s);
    sl_sb_free(&gen);
    /* DISPLACEMENT hooks (shader.h, ABI 1.7): a pass-through vertex stage and the tessellation
     * stages; without them the vertex stage is forward.vert and nothing else changes */
    if (c->nd && !c->req->fullscreen) ok = ok && compose_tessellation(c, p);
    else ok = ok && sl_source_include(&p->vs, c->req->fullscreen ? "sl:fullscreen.vert" : "sl:forward.vert", c->err, c->n);
    return ok;
}

/* The depth variant's fragment stage. glTF alphaMode MASK: what the colour pass cuts out casts no
 * shadow either, in every depth pass (shadow maps); BLEND: a dither keeps the coverage's share of
 * texels (depth.frag); other materials' depth programs stay empty. */
static bool compose_depth_fragment(composition *c, sl_program *p) {
    bool ok = true;
    if (material_has(c->app, c->m, "alpha_cutoff") || sl_gpu_material_blended(c->app, c->m)) {
        sl_source_generated(&p->fs, c->uni.s ? c->uni.s : "");
        sl_source_generated(&p->fs, c->uvf.s ? c->uvf.s : "");
        ok = sl_source_include(&p->fs, "sl:material.glsl", c->err, c->n);
    }
    return ok && sl_source_include(&p->fs, "sl:depth.frag", c->err, c->n);
}

/* What the forward fragment stage declares before the chunks: uniforms, the light buffer, the
 * light ranges by type, the functions chunks may call before they are defined. */
static void write_fragment_declarations(composition *c, sl_program *p) {
    sl_strbuf decl = {0};
    sl_sb_append(&decl, c->uni.s ? c->uni.s : "");
    sl_sb_append(&decl, c->uvf.s ? c->uvf.s : "");
    if (sl_gpu_lights_in_uniform_block(c->app))
        sl_sb_printf(&decl, "layout(std140, binding = 0) uniform SlLightBlock { SlLight sl_lights[%d]; };\n",
                     sl_gpu_light_block_capacity());
    else
        sl_sb_append(&decl, "layout(std430, binding = 0) readonly buffer SlLightBuffer { SlLight sl_lights[]; };\n");
    sl_sb_append(&decl, "uniform vec3 sl_ambient_irradiance; // π × constant environment radiance\n"
                        "vec3 sl_shading_model(SlSurface s, vec3 l, vec3 E); // the material's model (ABI 1.6)\n"
                        "SlLobes sl_model_lobes(SlSurface s); // its lobes or the fallback (ABI 1.14)\n");
    for (int t = 0; t < c->ntypes; t++) {
        char id[128];
        sl_glsl_ident(c->types[t], id, sizeof id, false);
        sl_sb_printf(&decl, "uniform ivec2 sl_lights_%s; // [first, end) in sl_lights\n", id);
        if (c->casters) sl_sb_printf(&decl, "uniform ivec2 sl_shadowed_%s; // the casters: [first, end) in sl_lights\n", id);
    }
    if (c->loop) sl_sb_append(&decl, "vec3 sl_light_radiance(int i, SlSurface s); // one light (LIGHT_LOOP, ABI 1.7)\n");
    if (c->req->fullscreen) sl_sb_append(&decl, "uniform int sl_material_index; // full-screen material pass (ABI 1.7)\n");
    sl_source_generated(&p->fs, decl.s);
    sl_sb_free(&decl);
}

/* The chunks' files, each once: LIBRARY chunks of every plugin involved first, then the list. */
static bool include_fragment_chunks(composition *c, sl_program *p) {
    bool ok = true;
    for (int i = 0; i < c->P->chunk_count && ok; i++) {
        const sl_chunk_reg *k = &c->P->chunks[i];
        if (k->d.hook != SL_HOOK_LIBRARY || !(c->owners & (1ull << k->owner)) || !sl_plugin_enabled(c->P, k->owner)) continue;
        ok = include_chunk(c, &p->fs, k);
    }
    for (int i = 0; i < c->count && ok; i++) {
        const sl_chunk_reg *k = c->list[i];
        ok = include_chunk(c, &p->fs, k);
        sl_sb_printf(&c->explain, "%s%s:%s%s", c->explain.len ? ", " : "", c->P->items[k->owner]->id,
                     k->d.name ? k->d.name : k->d.function, k->d.hook == SL_HOOK_MODEL_AMBIENT ? " (ambient)" : "");
    }
    return ok;
}

/* Which light types have an l/E pair (lit) and which integrate the model themselves (radiance:
 * area lights; no shadow hook, nothing in per-light debug views, shader.h), in types[] order. */
typedef struct light_kinds { int lit[SL_MAX_LIGHT_TYPES], radiance[SL_MAX_LIGHT_TYPES], nlit, nrad; } light_kinds;

static light_kinds sort_light_kinds(const composition *c) {
    light_kinds k = {.nlit = 0};
    for (int t = 0; t < c->ntypes; t++) {
        if (!c->light_chunks[t]) continue; /* warned at load: no plugin provides this light type */
        if (c->light_chunks[t]->d.flags & SL_CHUNK_LIGHT_RADIANCE) {
            if (!c->view) k.radiance[k.nrad++] = t;
        } else {
            k.lit[k.nlit++] = t;
        }
    }
    return k;
}

/* With a LIGHT_LOOP hook: sl_light_radiance(i, s) evaluates one light by index, the type being
 * the range holding i, tested in turn (nothing tested with a single type in the buffer). */
static void emit_light_radiance(const composition *c, const light_kinds *k, sl_strbuf *gen, const char *per_light,
                                const char *vis) {
    bool untested = c->ntypes == 1 && k->nlit + k->nrad == 1;
    sl_sb_append(gen, "vec3 sl_light_radiance(int i, SlSurface s) {\n    vec3 Lo = vec3(0.0);\n"
                      "    SlLight L = sl_lights[i];\n");
    if (k->nlit) sl_sb_append(gen, "    vec3 l = vec3(0.0), E = vec3(0.0);\n    bool lit = false;\n    sl_light_in_loop = true;\n");
    int emitted = 0;
    for (int t = 0; t < c->ntypes; t++) {
        bool is_lit = false, is_rad = false;
        for (int j = 0; j < k->nlit; j++) is_lit |= k->lit[j] == t;
        for (int j = 0; j < k->nrad; j++) is_rad |= k->radiance[j] == t;
        if (!is_lit && !is_rad) continue;
        char id[128];
        sl_glsl_ident(c->types[t], id, sizeof id, false);
        if (untested) sl_sb_printf(gen, "    /* %s: every light in the buffer */\n    ", id);
        else if (c->casters && is_lit)
            sl_sb_printf(gen, "    %sif ((i >= sl_lights_%s.x && i < sl_lights_%s.y) || (i >= sl_shadowed_%s.x && i < sl_shadowed_%s.y)) ",
                         emitted++ ? "else " : "", id, id, id, id);
        else sl_sb_printf(gen, "    %sif (i >= sl_lights_%s.x && i < sl_lights_%s.y) ", emitted++ ? "else " : "", id, id);
        if (is_rad) sl_sb_printf(gen, "Lo += %s(L, s);\n", c->light_chunks[t]->d.function);
        else sl_sb_printf(gen, "lit = %s(L, s, l, E);\n", c->light_chunks[t]->d.function);
    }
    if (k->nlit)
        sl_sb_printf(gen, "    if (lit) Lo += %s(s, l, %s);\n    " LIGHT_DONE "\n", per_light, vis);
}

/* Without one: sl_direct_lighting(s) loops over the lights itself, in the order of types[]: a
 * loop per radiance type, and the loops of the types with an l/E pair where the first of those
 * is (the shadow casters' loop first). */
static void emit_light_loops(const composition *c, const light_kinds *k, sl_strbuf *gen, const char *per_light,
                             const char *vis) {
    sl_sb_append(gen, "vec3 sl_direct_lighting(SlSurface s) {\n    vec3 Lo = vec3(0.0);\n");
    for (int t = 0; t < c->ntypes; t++) {
        char id[128];
        sl_glsl_ident(c->types[t], id, sizeof id, false);
        for (int j = 0; j < k->nrad; j++)
            if (k->radiance[j] == t) {
                sl_strbuf call = {0};
                sl_sb_printf(&call, "            if (i < end) Lo += %s(L, s);\n", c->light_chunks[t]->d.function);
                emit_light_loop(gen, "sl_lights", &id, 1, call.s);
                sl_sb_free(&call);
            }
        if (!k->nlit || k->lit[0] != t) continue;
        char ids[SL_MAX_LIGHT_TYPES][128];
        for (int j = 0; j < k->nlit; j++) sl_glsl_ident(c->types[k->lit[j]], ids[j], sizeof ids[j], false);
        if (c->casters) emit_lit_loop(gen, "sl_shadowed", ids, k->nlit, c->light_chunks, k->lit, per_light, vis);
        emit_lit_loop(gen, "sl_lights", ids, k->nlit, c->light_chunks, k->lit, per_light, "E");
    }
}

/* The light loops (the lights are packed by type, contiguous in the order of types[],
 * core/render/scene_gpu.c; each light's record is read from the buffer once). The light types
 * with an l/E pair share ONE loop over their ranges and ONE evaluation of the model per light:
 * the type, found by range (else-if), only computes l and E. Mesa inlines every call, so a loop
 * per type was a copy of the model and of the shadow filter per type: on llvmpipe the copies were
 * a third of the forward programs' compile time (issue 19). When a light casts shadows, the
 * casters (packed first) have a loop of their own, the only one with the SHADOW hook: llvmpipe
 * runs every branch, so the filter in the shared loop ran for every light (issue 18). Radiance
 * types (area lights) keep a loop each. Loops are do-whiles (emit_light_loop). */
static void emit_direct_lighting(const composition *c, sl_strbuf *gen) {
    const sl_chunk_reg *view = c->view;
    const char *per_light = view && view->d.hook == SL_HOOK_DEBUG_VIEW_LIGHT ? view->d.function : c->model_chunk->d.function;
    light_kinds k = sort_light_kinds(c);
    char vis[256] = "E";
    if (c->shadow) snprintf(vis, sizeof vis, "E * %s(i, L, s, l)", c->shadow->d.function);
    if (c->loop) emit_light_radiance(c, &k, gen, per_light, vis);
    else emit_light_loops(c, &k, gen, per_light, vis);
    sl_sb_append(gen, "    return Lo;\n}\n");
    if (c->loop) sl_sb_printf(gen, "vec3 sl_direct_lighting(SlSurface s) { return %s(s); }\n", c->loop->d.function);
}

/* sl_shade_surface(s): the debug view, or direct light + ambient light + emission. */
static void emit_shade_surface(const composition *c, sl_strbuf *gen) {
    const sl_chunk_reg *view = c->view;
    sl_sb_append(gen, "vec3 sl_shade_surface(SlSurface s) {\n");
    if (view && view->d.hook == SL_HOOK_DEBUG_VIEW) {
        sl_sb_printf(gen, "    return %s(s);\n}\n", view->d.function);
        return;
    }
    if (view) {
        sl_sb_append(gen, "    return sl_direct_lighting(s);\n}\n");
        return;
    }
    /* KHR_materials_unlit (the core's key "unlit"): the base colour as radiance */
    sl_sb_append(gen, "#if defined(SL_MAT_UNLIT) && SL_MAT_UNLIT\n    return s.base_color;\n#endif\n");
    sl_sb_append(gen, "    vec3 Lo = sl_direct_lighting(s);\n");
    /* An override model (SL_DRAW_MATERIALS) owns its whole output: no AMBIENT hooks. A
     * MODEL_AMBIENT always runs (it may carry more than ambient light, e.g. sss), with
     * vec3(0) where AMBIENT hooks supply the ambient light instead. */
    bool hooks = c->na && !c->req->model_override;
    for (int i = 0; hooks && i < c->na; i++) sl_sb_printf(gen, "    Lo += %s(s);\n", c->ambient[i]->d.function);
    if (c->model_ambient)
        sl_sb_printf(gen, "    Lo += %s(s, %s);\n", c->model_ambient->d.function, hooks ? "vec3(0.0)" : "sl_ambient_irradiance");
    else if (!hooks)
        sl_sb_append(gen, "    Lo += s.base_color * SL_INV_PI * sl_ambient_irradiance * s.ao;\n");
    /* SCENE_BEHIND hooks (ABI 1.17): what the surface passes on from the opaque scene behind it */
    for (int i = 0; i < c->nb; i++) sl_sb_printf(gen, "    Lo += %s(s);\n", c->behind[i]->d.function);
    /* glTF emission (shaders/material.glsl), whatever the model */
    sl_sb_append(gen, "#ifdef SL_MAT_HAS_EMISSIVE\n    Lo += sl_emission(s);\n#endif\n");
    sl_sb_append(gen, "    return Lo;\n}\n");
}

/* The forward fragment stage: declarations, material.glsl, the chunks, the generated functions
 * tying them together, forward.frag (or a plugin's main). */
/* sl_model_lobes (shader.h, ABI 1.14): the model's MODEL_LOBES hook, or the fallback (a Lambert
 * diffuse of s.base_color, no lobe). A model without lobes that an integrator lights (an AMBIENT
 * hook or an area light in the program) is named once per run. */
static void emit_model_lobes(const composition *c, sl_strbuf *gen) {
    if (c->model_lobes) {
        sl_sb_printf(gen, "SlLobes sl_model_lobes(SlSurface s) { return %s(s); }\n", c->model_lobes->d.function);
        return;
    }
    sl_sb_append(gen, "SlLobes sl_model_lobes(SlSurface s) { SlLobes L = sl_lobes_none(); L.diffuse = s.base_color; return L; }\n");
    bool integrated = c->na > 0;
    for (int t = 0; t < c->ntypes; t++)
        integrated |= c->light_chunks[t] && (c->light_chunks[t]->d.flags & SL_CHUNK_LIGHT_RADIANCE);
    static char warned[32][64];
    static int nwarned;
    if (!integrated) return;
    for (int i = 0; i < nwarned; i++)
        if (!strncmp(warned[i], c->model, sizeof warned[i] - 1)) return;
    if (nwarned < 32) snprintf(warned[nwarned++], sizeof warned[0], "%s", c->model);
    SL_WARN("shading model \"%s\" (plugin %s) describes no lobes (MODEL_LOBES): environment light reaches it as a "
            "Lambert diffuse of its base_color, an area light as one evaluation of the model (the lobe contract's fallback)",
            c->model, c->P->items[c->model_chunk->owner]->id);
}

static bool compose_forward_fragment(composition *c, sl_program *p) {
    write_fragment_declarations(c, p);
    bool ok = sl_source_include(&p->fs, "sl:material.glsl", c->err, c->n);
    if (c->nb) ok = ok && sl_source_include(&p->fs, "sl:scene_behind.glsl", c->err, c->n);
    ok = ok && include_fragment_chunks(c, p);
    sl_strbuf gen = {0};
    sl_sb_append(&gen, "void sl_run_surface_hooks(inout SlSurface s) {\n");
    for (int i = 0; i < c->ns; i++) sl_sb_printf(&gen, "    %s(s);\n", c->surface[i]->d.function);
    sl_sb_append(&gen, "}\n");
    emit_direct_lighting(c, &gen);
    sl_sb_printf(&gen, "vec3 sl_shading_model(SlSurface s, vec3 l, vec3 E) { return %s(s, l, E); }\n",
                 c->model_chunk->d.function);
    emit_model_lobes(c, &gen);
    emit_shade_surface(c, &gen);
    sl_source_generated(&p->fs, gen.s);
    sl_sb_free(&gen);
    ok = ok && sl_source_include(&p->fs, "sl:forward.frag", c->err, c->n);
    const char *fragment = c->req->fragment;
    if (fragment && ok && !sl_source_include_from(&p->fs, fragment, owner_of_file(c->P, fragment), c->err, c->n))
        ok = false, c->culprit = owner_of_file(c->P, fragment);
    return ok;
}

/* Compiles p unless the cache holds a program of the same text (then p is freed), and keeps it
 * in the cache. A failure keeps the variant's previous program (hot reload). */
static bool build_or_reuse(composition *c, sl_program *p, sl_forward_variant *out, sl_program_cache *cache) {
    p->hash = sl_hash64(p->vs.text.s, p->vs.text.len, sl_hash64(p->fs.text.s, p->fs.text.len, 0));
    if (p->tessellated)
        p->hash = sl_hash64(p->tcs.text.s, p->tcs.text.len, sl_hash64(p->tes.text.s, p->tes.text.len, p->hash));
    for (int i = 0; i < cache->count; i++) {
        if (cache->items[i]->hash == p->hash && cache->items[i]->id && !cache->items[i]->stale) {
            sl_program_free(p);
            out->program = cache->items[i];
            return true;
        }
    }
    if (!sl_program_build(p, c->err, c->n)) {
        c->culprit = blame_compile_error(c->P, p, c->owners);
        sl_program_free(p);
        return false;
    }
    sl_program **grown = realloc(cache->items, (cache->count + 1) * sizeof *grown);
    if (!grown) {
        sl_program_free(p);
        return compose_fail(c, 0, "material \"%s\": out of memory for its program (%d programs cached)", c->mat->name,
                            cache->count);
    }
    cache->items = grown;
    cache->items[cache->count++] = p;
    out->program = p;
    return true;
}

bool sl_forward_compose(sl_app *app, int m, const sl_variant_request *request, sl_forward_variant *out,
                        sl_program_cache *cache, char *err, size_t n) {
    sl_variant_request req = *request;
    if (!req.fragment) req.fullscreen = false;
    composition *c = calloc(1, sizeof *c);
    *c = (composition){.app = app, .P = &app->plugins, .m = m, .mat = &app->scene.materials[m], .req = &req,
                       .err = err, .n = n};
    out->failed_plugin = -1;
    choose_model_and_view(c);
    choose_lights(c);
    bool ok = gather_gated_hooks(c);
    sl_program *p = NULL;
    if (ok) {
        list_fragment_chunks(c);
        write_prelude(c, out);
        p = calloc(1, sizeof *p);
        ok = compose_vertex_stage(c, p);
        sl_sb_append(&p->fs.text, c->pre.s);
        sl_sb_append(&p->fs.text, "#define SL_FRAGMENT_STAGE 1\n");
        ok = ok && sl_source_include(&p->fs, "sl:common.glsl", err, n);
        if (req.kind == SL_VARIANT_DEPTH) ok = ok && compose_depth_fragment(c, p);
        else ok = ok && compose_forward_fragment(c, p);
        char label[512];
        snprintf(label, sizeof label, "material \"%s\" (%s%s)", c->mat->name, req.kind == SL_VARIANT_DEPTH ? "depth, " : "",
                 c->model);
        p->label = strdup(label);
        p->composed = true;
        free(out->chunks);
        out->chunks = c->explain.s ? c->explain.s : strdup("");
        c->explain = (sl_strbuf){0};
        out->owners = c->owners;
    }
    if (ok) {
        /* the program's sl_vertex_hook_mask bits (the tag strings live as long as the plugin) */
        memcpy(out->node_tags, c->node_tags, sizeof c->node_tags);
        out->node_tag_count = c->node_tag_count;
        ok = build_or_reuse(c, p, out, cache);
    } else {
        sl_program_free(p);
    }
    if (!ok) out->failed_plugin = c->culprit >= 1 ? c->culprit : -1;
    sl_sb_free(&c->pre);
    sl_sb_free(&c->uni);
    sl_sb_free(&c->uvf);
    sl_sb_free(&c->explain);
    free(c);
    return ok;
}
