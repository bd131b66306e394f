#include "render/forward.h"
#include "render/renderer_internal.h"
#include "state.h"
#include "log.h"
#include <ctype.h>
#include <math.h>
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
 * uniforms, never a program; only a light of a new type composes new programs. */
int sl_forward_light_types(sl_app *app, const char **types, int max) {
    int n = 0;
    for (int i = 0; i < app->scene.light_count; i++) {
        const sl_light *L = &app->scene.lights[i];
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
    for (int i = 0; i < app->scene.light_count; i++)
        if (app->scene.lights[i].cast_shadows && sl_forward_light_type_lit(app, app->scene.lights[i].type)) return true;
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

/* The loop over the lights of the types with an l/E pair (ids, in buffer order) in the ranges
 * <prefix>_<type>: the type found by range (else-if), one evaluation of the model with E × `vis`. */
static void emit_lit_loop(sl_strbuf *gen, const char *prefix, const char (*ids)[128], int n,
                          const sl_chunk_reg *const *light_chunks, const int *lit_types, const char *per_light,
                          const char *vis) {
    sl_strbuf b = {0};
    if (n == 1) {
        sl_sb_printf(&b, "            vec3 l, E;\n            if (i < end && %s(L, s, l, E)) Lo += %s(s, l, %s);\n",
                     light_chunks[lit_types[0]]->d.function, per_light, vis);
    } else {
        sl_sb_append(&b, "            vec3 l = vec3(0.0), E = vec3(0.0);\n            bool lit = false;\n");
        for (int k = 0; k < n; k++)
            sl_sb_printf(&b, "            %sif (i >= %s_%s.x && i < %s_%s.y) lit = %s(L, s, l, E);\n", k ? "else " : "",
                         prefix, ids[k], prefix, ids[k], light_chunks[lit_types[k]]->d.function);
        sl_sb_printf(&b, "            if (lit) Lo += %s(s, l, %s);\n", per_light, vis);
    }
    emit_light_loop(gen, prefix, ids, n, b.s ? b.s : "");
    sl_sb_free(&b);
}

static const sl_chunk_reg *find_named(sl_app *app, sl_hook hook, const char *name) {
    for (int i = 0; i < app->plugins.chunk_count; i++) {
        const sl_chunk_reg *c = &app->plugins.chunks[i];
        if (c->d.hook == hook && c->d.name && !strcmp(c->d.name, name) && sl_plugin_enabled(&app->plugins, c->owner)) return c;
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

/* Includes chunk c's file into src as its plugin's (an error in it is blamed on that plugin); a
 * file that cannot be included is blamed on it at once (*culprit). */
static bool include_chunk(sl_plugins *P, sl_source *src, const sl_chunk_reg *c, int *culprit, char *err, size_t n) {
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", P->items[c->owner]->resource_dir, c->d.file);
    if (sl_source_include_from(src, path, c->owner, err, n)) return true;
    *culprit = c->owner;
    return false;
}

/* The tessellation of a displaced material (DISPLACEMENT hooks, shader.h ABI 1.7): tess.vert runs
 * the VERTEX hooks and hands the object-space vertex on; the control stage sets per-edge levels
 * from each edge's endpoints (crack-free), the evaluation stage displaces along the normal. */
static bool compose_tessellation(sl_plugins *P, sl_program *p, const char *pre, const char *uni,
                                 const sl_chunk_reg *const *hooks, int nd, sl_variant_kind kind, int *culprit, char *err,
                                 size_t n) {
    bool ok = sl_source_include(&p->vs, "sl:tess.vert", err, n);
    sl_source *stages[2] = {&p->tcs, &p->tes};
    const char *defines[2] = {"#define SL_TESS_CONTROL_STAGE 1\n", "#define SL_TESS_EVALUATION_STAGE 1\n"};
    sl_strbuf gen = {0};
    sl_sb_append(&gen, "float sl_tess_edge_level(vec3 a, vec3 b) {\n    float level = 1.0;\n");
    for (int i = 0; i < nd; i++) {
        if (hooks[i]->d.tess_level) sl_sb_printf(&gen, "    level = max(level, %s(a, b));\n", hooks[i]->d.tess_level);
        else sl_sb_append(&gen, "    level = max(level, sl_tess_screen_level(a, b, 8.0));\n");
    }
    sl_sb_append(&gen, "    return level;\n}\nfloat sl_run_displacement(SlVertex v) {\n    float h = 0.0;\n");
    for (int i = 0; i < nd; i++) sl_sb_printf(&gen, "    h += %s(v);\n", hooks[i]->d.function);
    sl_sb_append(&gen, "    return h;\n}\n");
    for (int k = 0; k < 2 && ok; k++) {
        sl_sb_append(&stages[k]->text, pre);
        sl_sb_append(&stages[k]->text, defines[k]);
        if (k == 1 && kind == SL_VARIANT_FORWARD) sl_sb_append(&stages[k]->text, "#define SL_TESS_NORMALS 1\n");
        ok = sl_source_include(stages[k], "sl:common.glsl", err, n);
        sl_source_generated(stages[k], uni ? uni : "");
        ok = ok && sl_source_include(stages[k], "sl:tess.glsl", err, n);
        for (int i = 0; i < nd && ok; i++) ok = include_chunk(P, stages[k], hooks[i], culprit, err, n);
        if (ok) sl_source_generated(stages[k], gen.s);
        ok = ok && sl_source_include(stages[k], k == 0 ? "sl:tess.tesc" : "sl:tess.tese", err, n);
    }
    sl_sb_free(&gen);
    p->tessellated = true;
    return ok;
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

bool sl_forward_compose(sl_app *app, int m, sl_variant_kind kind, const char *model_override, sl_forward_variant *out,
                        sl_program ***cache, int *cache_count, char *err, size_t n) {
    return sl_forward_compose_custom(app, m, kind, model_override, NULL, false, out, cache, cache_count, err, n);
}

bool sl_forward_compose_custom(sl_app *app, int m, sl_variant_kind kind, const char *model_override, const char *fragment,
                               bool fullscreen, sl_forward_variant *out, sl_program ***cache, int *cache_count, char *err,
                               size_t n) {
    if (!fragment) fullscreen = false;
    sl_plugins *P = &app->plugins;
    int culprit = 0; /* the plugin whose file could not be included */
    out->failed_plugin = -1;
    const sl_material *mat = &app->scene.materials[m];
    uint64_t owners = 1; /* the core */
    const sl_chunk_reg *list[256];
    int count = 0;
    sl_strbuf explain = {0};

    /* shading model */
    const char *model = model_override ? model_override : mat->model ? mat->model : "lambert";
    const sl_chunk_reg *model_chunk = find_named(app, SL_HOOK_SHADING_MODEL, model);
    if (!model_chunk) {
        model_chunk = find_named(app, SL_HOOK_SHADING_MODEL, "lambert");
        model = "lambert";
    }
    const sl_chunk_reg *model_ambient = find_named(app, SL_HOOK_MODEL_AMBIENT, model);
    /* debug view */
    const sl_chunk_reg *view = NULL;
    if (app->debug_view && !model_override) {
        view = find_named(app, SL_HOOK_DEBUG_VIEW, app->debug_view);
        if (!view) view = find_named(app, SL_HOOK_DEBUG_VIEW_LIGHT, app->debug_view);
    }
    /* light types present */
    const char *types[32];
    int ntypes = sl_forward_light_types(app, types, 32);
    const sl_chunk_reg *light_chunks[32] = {0};
    for (int t = 0; t < ntypes; t++) light_chunks[t] = find_named(app, SL_HOOK_LIGHT, types[t]);
    /* SHADOW hook (shader.h): only when a light casts shadows, enabled or not (like the types
     * above: toggling a light recompiles nothing); the first provider */
    const sl_chunk_reg *shadow = NULL;
    for (int i = 0; i < app->scene.light_count && !shadow; i++)
        for (int c = 0; c < P->chunk_count && !shadow && app->scene.lights[i].cast_shadows; c++)
            if (P->chunks[c].d.hook == SL_HOOK_SHADOW && sl_plugin_enabled(&app->plugins, P->chunks[c].owner)) shadow = &P->chunks[c];
    bool casters = sl_forward_shadow_casters(app); /* the casters' ranges and loop (sl_gpu_pack_lights) */
    /* LIGHT_LOOP hook (ABI 1.7, shader.h): the forward programs' light iteration; the first provider */
    const sl_chunk_reg *loop = NULL;
    for (int c = 0; c < P->chunk_count && !loop && kind == SL_VARIANT_FORWARD && !model_override; c++)
        if (P->chunks[c].d.hook == SL_HOOK_LIGHT_LOOP && sl_plugin_enabled(&app->plugins, P->chunks[c].owner)) loop = &P->chunks[c];

    /* hooks gated on material keys */
    const sl_chunk_reg *vertex_hooks[64], *surface_hooks[64], *ambient_hooks[64], *displacement_hooks[64];
    int nv = 0, ns = 0, na = 0, nd = 0;
    for (int i = 0; i < P->chunk_count; i++) {
        const sl_chunk_reg *c = &P->chunks[i];
        if (!sl_plugin_enabled(&app->plugins, c->owner)) continue;
        if (c->d.hook != SL_HOOK_VERTEX && c->d.hook != SL_HOOK_SURFACE && c->d.hook != SL_HOOK_AMBIENT &&
            c->d.hook != SL_HOOK_DISPLACEMENT)
            continue;
        if (c->d.when_material_has && !material_has(app, m, c->d.when_material_has)) continue;
        /* the material's own model, also in override programs (its surface stays the same) */
        if (c->d.when_model && strcmp(c->d.when_model, mat->model ? mat->model : "lambert")) continue;
        if (c->d.when_node_tag && !material_drawn_with_tag(app, m, c->d.when_node_tag)) continue;
        if (c->d.hook == SL_HOOK_VERTEX && nv < 64) vertex_hooks[nv++] = c;
        if (c->d.hook == SL_HOOK_SURFACE && ns < 64) surface_hooks[ns++] = c;
        if (c->d.hook == SL_HOOK_AMBIENT && na < 64) ambient_hooks[na++] = c;
        if (c->d.hook == SL_HOOK_DISPLACEMENT && nd < 64) displacement_hooks[nd++] = c;
    }
    qsort(displacement_hooks, nd, sizeof *displacement_hooks, cmp_chunk_order);
    qsort(vertex_hooks, nv, sizeof *vertex_hooks, cmp_chunk_order);
    qsort(surface_hooks, ns, sizeof *surface_hooks, cmp_chunk_order);

    /* the fragment-stage chunk list, in include order */
#define ADD(c) do { if ((c) && count < 256) { list[count++] = (c); owners |= 1ull << ((c)->owner & 63); } } while (0)
    if (kind == SL_VARIANT_FORWARD) {
        for (int i = 0; i < ns; i++) ADD(surface_hooks[i]);
        ADD(shadow);
        for (int t = 0; t < ntypes; t++) ADD(light_chunks[t]);
        ADD(model_chunk);
        ADD(model_ambient);
        ADD(loop);
        for (int i = 0; i < na; i++) ADD(ambient_hooks[i]);
        ADD(view);
    }
    for (int i = 0; i < nv; i++) {
        owners |= 1ull << (vertex_hooks[i]->owner & 63);
        sl_sb_printf(&explain, "%s%s:%s (vertex)", explain.len ? ", " : "", P->items[vertex_hooks[i]->owner]->id,
                     vertex_hooks[i]->d.function);
    }
    for (int i = 0; i < nd; i++) {
        owners |= 1ull << (displacement_hooks[i]->owner & 63);
        sl_sb_printf(&explain, "%s%s:%s (displacement)", explain.len ? ", " : "",
                     P->items[displacement_hooks[i]->owner]->id, displacement_hooks[i]->d.function);
    }
#undef ADD

    /* A depth program that reads nothing of its material (no alpha cut-out or blend dither, no
     * VERTEX or DISPLACEMENT hook) is the same text for every such material: no material or
     * model defines, uniforms or textures, so they share one program (one compile less per
     * material in the shadow maps; on llvmpipe each costs tens of ms at its first draw). */
    bool bare_depth = kind == SL_VARIANT_DEPTH && !nv && !nd && !material_has(app, m, "alpha_cutoff") &&
                      !sl_gpu_material_blended(app, m);

    /* ---- common prelude: defines and uniforms for the owners involved ---- */
    sl_strbuf pre = {0};
    sl_sb_append(&pre, "#version 450 core\n");
    /* what the colour target holds: the forward pass clamps its output to it (scene.h) */
    sl_sb_printf(&pre, "#define SL_MAX_RADIANCE %.9g\n", app->opt.float32 ? 3.0e38 : SL_MAX_RADIANCE);
    char model_id[128]; /* SL_MODEL_<NAME>: lets a chunk shared by several models specialise */
    sl_glsl_ident(model, model_id, sizeof model_id, true);
    if (!bare_depth) sl_sb_printf(&pre, "#define SL_MODEL_%s 1\n", model_id);
    if ((model_chunk->d.flags & SL_CHUNK_MASKS_FACING_AWAY) && !bare_depth)
        sl_sb_append(&pre, "#define SL_MODEL_MASKS_FACING_AWAY 1\n");
    /* "motion" (pass.h) is read by an enabled pass: the forward program writes it (location 1) */
    bool motion = kind == SL_VARIANT_FORWARD && !model_override && !fragment && app->renderer && R(app)->motion;
    if (fragment) sl_sb_append(&pre, "#define SL_CUSTOM_MAIN 1\n"); /* a plugin's main (draw_scene fragment, ABI 1.7) */
    if (fullscreen) sl_sb_append(&pre, "#define SL_FULLSCREEN_MATERIAL 1\n");
    if (motion) sl_sb_append(&pre, "#define SL_MOTION_VECTORS 1\n");
    if (view) {
        char id[128];
        sl_glsl_ident(view->d.name, id, sizeof id, true);
        sl_sb_printf(&pre, "#define SL_DEBUG_VIEW_%s 1\n", id);
        /* a view that replaces the whole output (not a per-light one): passes adding light skip it */
        if (view->d.hook == SL_HOOK_DEBUG_VIEW) sl_sb_append(&pre, "#define SL_DEBUG_VIEW_REPLACES_OUTPUT 1\n");
    }
    sl_strbuf uni = {0}, uvf = {0};
    bool uses_uv1 = false;
    out->texture_count = 0;
    for (int i = 0; i < app->params.count; i++) {
        const sl_param *q = &app->params.items[i];
        if (!(owners & declarers_of(P, q))) continue;
        char id[160], up[160];
        if (q->desc.scope == SL_SCOPE_MATERIAL) {
            sl_mat_value *v = bare_depth ? NULL : sl_app_material_value(app, m, q->full_id);
            if (!v) continue;
            sl_glsl_ident(q->full_id, up, sizeof up, true);
            if (v->present) sl_sb_printf(&pre, "#define SL_MAT_HAS_%s 1\n", up);
            if (q->desc.type == SL_PARAM_TEXTURE) {
                if (v->present && out->texture_count < 16) {
                    sl_sb_printf(&uni, "layout(binding = %d) uniform sampler2D sl_mat_%s;\n", out->texture_count, q->full_id);
                    out->texture_params[out->texture_count++] = i;
                    uses_uv1 |= uv_function(&uvf, mat, q);
                }
            } else if (q->desc.flags & SL_PARAM_NEEDS_RECOMPILE) {
                char macro[200];
                snprintf(macro, sizeof macro, "SL_MAT_%s", up);
                define_value(&pre, macro, q, &v->v);
            } else {
                sl_sb_printf(&uni, "uniform %s sl_mat_%s;\n", glsl_type(q->desc.type), q->full_id);
            }
        } else if (q->desc.scope == SL_SCOPE_GLOBAL && strcmp(q->desc.id, "enabled")) {
            char owner_id[128];
            sl_glsl_ident(q->owner, owner_id, sizeof owner_id, false);
            snprintf(id, sizeof id, "%s_%s", owner_id, q->desc.id);
            if (q->desc.flags & SL_PARAM_NEEDS_RECOMPILE) {
                sl_glsl_ident(id, up, sizeof up, true);
                define_value(&pre, up, q, &q->value);
            } else {
                sl_sb_printf(&uni, "uniform %s %s;\n", glsl_type(q->desc.type), id);
            }
        }
    }

    if (uses_uv1) sl_sb_append(&pre, "#define SL_MAT_USES_UV1 1\n");

    sl_program *p = calloc(1, sizeof *p);
    bool ok = true;
    /* ---- vertex stage ---- */
    sl_sb_append(&p->vs.text, pre.s);
    sl_sb_append(&p->vs.text, "#define SL_VERTEX_STAGE 1\n");
    ok = ok && sl_source_include(&p->vs, "sl:common.glsl", err, n);
    sl_source_generated(&p->vs, uni.s ? uni.s : "");
    /* Motion vectors evaluate the VERTEX hooks at the previous frame's time as well: hooks read
     * sl_time, so here it names a variable that forward.vert sets before each evaluation. */
    if (motion)
        sl_source_generated(&p->vs, "uniform float sl_prev_time;\n"
                                    "float sl_motion_time_now() { return sl_time; }\n"
                                    "float sl_hook_time;\n"
                                    "#define sl_time sl_hook_time\n");
    sl_strbuf gen = {0};
    for (int i = 0; i < nv && ok; i++) ok = include_chunk(P, &p->vs, vertex_hooks[i], &culprit, err, n);
    /* hooks for tagged nodes only (when_node_tag, ABI 1.6) run under a bit of a per-draw uniform */
    const char *node_tags[32] = {0};
    int node_tag_count = 0;
    for (int i = 0; i < nv; i++)
        if (vertex_hooks[i]->d.when_node_tag && node_tag_count < 31)
            node_tags[node_tag_count++] = vertex_hooks[i]->d.when_node_tag;
    if (node_tag_count) sl_sb_append(&gen, "uniform int sl_vertex_hook_mask; // bit k: node carries tag k\n");
    sl_sb_append(&gen, "void sl_run_vertex_hooks(inout SlVertex v) {\n");
    for (int i = 0, k = 0; i < nv; i++) {
        if (vertex_hooks[i]->d.when_node_tag && k < 31)
            sl_sb_printf(&gen, "    if ((sl_vertex_hook_mask & %d) != 0) %s(v); // node tag \"%s\"\n", 1 << k++,
                         vertex_hooks[i]->d.function, vertex_hooks[i]->d.when_node_tag);
        else if (!vertex_hooks[i]->d.when_node_tag)
            sl_sb_printf(&gen, "    %s(v);\n", vertex_hooks[i]->d.function);
    }
    sl_sb_append(&gen, "}\n");
    sl_source_generated(&p->vs, gen.s);
    sl_sb_free(&gen);
    /* DISPLACEMENT hooks (shader.h, ABI 1.7): a pass-through vertex stage and the tessellation
     * stages; without them the vertex stage is forward.vert and nothing else changes */
    if (nd && !fullscreen) ok = ok && compose_tessellation(P, p, pre.s, uni.s, displacement_hooks, nd, kind, &culprit, err, n);
    else ok = ok && sl_source_include(&p->vs, fullscreen ? "sl:fullscreen.vert" : "sl:forward.vert", err, n);

    /* ---- fragment stage ---- */
    sl_sb_append(&p->fs.text, pre.s);
    sl_sb_append(&p->fs.text, "#define SL_FRAGMENT_STAGE 1\n");
    ok = ok && sl_source_include(&p->fs, "sl:common.glsl", err, n);
    if (kind == SL_VARIANT_DEPTH) {
        /* glTF alphaMode MASK: what the colour pass cuts out casts no shadow either, in every depth
         * pass (shadow maps); BLEND: a dither keeps the coverage's share of texels (depth.frag);
         * other materials' depth programs stay empty */
        if (material_has(app, m, "alpha_cutoff") || sl_gpu_material_blended(app, m)) {
            sl_source_generated(&p->fs, uni.s ? uni.s : "");
            sl_source_generated(&p->fs, uvf.s ? uvf.s : "");
            ok = ok && sl_source_include(&p->fs, "sl:material.glsl", err, n);
        }
        ok = ok && sl_source_include(&p->fs, "sl:depth.frag", err, n);
    } else {
        sl_strbuf decl = {0};
        sl_sb_append(&decl, uni.s ? uni.s : "");
        sl_sb_append(&decl, uvf.s ? uvf.s : "");
        if (sl_gpu_lights_in_uniform_block(app))
            sl_sb_printf(&decl, "layout(std140, binding = 0) uniform SlLightBlock { SlLight sl_lights[%d]; };\n",
                         sl_gpu_light_block_capacity());
        else
            sl_sb_append(&decl, "layout(std430, binding = 0) readonly buffer SlLightBuffer { SlLight sl_lights[]; };\n");
        sl_sb_append(&decl, "uniform vec3 sl_ambient_irradiance; // π × constant environment radiance\n"
                            "vec3 sl_shading_model(SlSurface s, vec3 l, vec3 E); // the material's model (ABI 1.6)\n");
        for (int t = 0; t < ntypes; t++) {
            char id[128];
            sl_glsl_ident(types[t], id, sizeof id, false);
            sl_sb_printf(&decl, "uniform ivec2 sl_lights_%s; // [first, end) in sl_lights\n", id);
            if (casters) sl_sb_printf(&decl, "uniform ivec2 sl_shadowed_%s; // the casters: [first, end) in sl_lights\n", id);
        }
        if (loop) sl_sb_append(&decl, "vec3 sl_light_radiance(int i, SlSurface s); // one light (LIGHT_LOOP, ABI 1.7)\n");
        if (fullscreen) sl_sb_append(&decl, "uniform int sl_material_index; // full-screen material pass (ABI 1.7)\n");
        sl_source_generated(&p->fs, decl.s);
        sl_sb_free(&decl);
        ok = ok && sl_source_include(&p->fs, "sl:material.glsl", err, n);
        /* chunks, each file once; LIBRARY chunks of every owner involved come first */
        for (int i = 0; i < P->chunk_count && ok; i++) {
            const sl_chunk_reg *c = &P->chunks[i];
            if (c->d.hook != SL_HOOK_LIBRARY || !(owners & (1ull << (c->owner & 63))) || !sl_plugin_enabled(&app->plugins, c->owner)) continue;
            ok = include_chunk(P, &p->fs, c, &culprit, err, n);
        }
        for (int i = 0; i < count && ok; i++) {
            ok = include_chunk(P, &p->fs, list[i], &culprit, err, n);
            sl_sb_printf(&explain, "%s%s:%s%s", explain.len ? ", " : "", P->items[list[i]->owner]->id,
                         list[i]->d.name ? list[i]->d.name : list[i]->d.function,
                         list[i]->d.hook == SL_HOOK_MODEL_AMBIENT ? " (ambient)" : "");
        }
        sl_sb_append(&gen, "void sl_run_surface_hooks(inout SlSurface s) {\n");
        for (int i = 0; i < ns; i++) sl_sb_printf(&gen, "    %s(s);\n", surface_hooks[i]->d.function);
        sl_sb_append(&gen, "}\n");
        /* The light loops (the lights are packed by type, contiguous in the order of types[],
         * core/render/scene_gpu.c; each light's record is read from the buffer once). The light
         * types with an l/E pair share ONE loop over their ranges and ONE evaluation of the model
         * per light: the type, found by range (else-if), only computes l and E. Mesa inlines
         * every call, so a loop per type was a copy of the model and of the shadow filter per
         * type: on llvmpipe the copies were a third of the forward programs' compile time (issue
         * 19). When a light casts shadows, the casters (packed first) have a loop of their own,
         * the only one with the SHADOW hook: llvmpipe runs every branch, so the filter in the
         * shared loop ran for every light (issue 18, tenth round). Radiance types (area lights)
         * keep a loop each. Loops are do-whiles (emit_light_loop). */
        const char *per_light = view && view->d.hook == SL_HOOK_DEBUG_VIEW_LIGHT ? view->d.function : model_chunk->d.function;
        int lit_types[32], radiance_types[32], nlit = 0, nrad = 0;
        for (int t = 0; t < ntypes; t++) {
            if (!light_chunks[t]) continue; /* warned at load: no plugin provides this light type */
            /* a light that integrates the model itself (area lights): radiance, no l/E pair, so
             * no shadow hook and nothing in per-light debug views (shader.h) */
            if (light_chunks[t]->d.flags & SL_CHUNK_LIGHT_RADIANCE) {
                if (!view) radiance_types[nrad++] = t;
            } else {
                lit_types[nlit++] = t;
            }
        }
        char vis[256] = "E";
        if (shadow) snprintf(vis, sizeof vis, "E * %s(i, L, s, l)", shadow->d.function);
        if (loop) {
            /* With a LIGHT_LOOP hook the same code evaluates one light by index: the type is the
             * range holding i, tested in turn; with a single type in the buffer nothing is tested. */
            bool untested = ntypes == 1 && nlit + nrad == 1;
            sl_sb_append(&gen, "vec3 sl_light_radiance(int i, SlSurface s) {\n    vec3 Lo = vec3(0.0);\n"
                               "    SlLight L = sl_lights[i];\n");
            if (nlit) sl_sb_append(&gen, "    vec3 l = vec3(0.0), E = vec3(0.0);\n    bool lit = false;\n");
            int emitted = 0;
            for (int t = 0; t < ntypes; t++) {
                bool is_lit = false, is_rad = false;
                for (int k = 0; k < nlit; k++) is_lit |= lit_types[k] == t;
                for (int k = 0; k < nrad; k++) is_rad |= radiance_types[k] == t;
                if (!is_lit && !is_rad) continue;
                char id[128];
                sl_glsl_ident(types[t], id, sizeof id, false);
                if (untested) sl_sb_printf(&gen, "    /* %s: every light in the buffer */\n    ", id);
                else if (casters && is_lit)
                    sl_sb_printf(&gen, "    %sif ((i >= sl_lights_%s.x && i < sl_lights_%s.y) || (i >= sl_shadowed_%s.x && i < sl_shadowed_%s.y)) ",
                                 emitted++ ? "else " : "", id, id, id, id);
                else sl_sb_printf(&gen, "    %sif (i >= sl_lights_%s.x && i < sl_lights_%s.y) ", emitted++ ? "else " : "", id, id);
                if (is_rad) sl_sb_printf(&gen, "Lo += %s(L, s);\n", light_chunks[t]->d.function);
                else sl_sb_printf(&gen, "lit = %s(L, s, l, E);\n", light_chunks[t]->d.function);
            }
            if (nlit) sl_sb_printf(&gen, "    if (lit) Lo += %s(s, l, %s);\n", per_light, vis);
        } else {
            sl_sb_append(&gen, "vec3 sl_direct_lighting(SlSurface s) {\n    vec3 Lo = vec3(0.0);\n");
            /* in the order of types[]: radiance loops, and the loops of the types with an l/E pair
             * where the first of those is (the shadow casters' first) */
            for (int t = 0; t < ntypes; t++) {
                char id[128];
                sl_glsl_ident(types[t], id, sizeof id, false);
                for (int k = 0; k < nrad; k++)
                    if (radiance_types[k] == t) {
                        sl_strbuf call = {0};
                        sl_sb_printf(&call, "            if (i < end) Lo += %s(L, s);\n", light_chunks[t]->d.function);
                        emit_light_loop(&gen, "sl_lights", &id, 1, call.s);
                        sl_sb_free(&call);
                    }
                if (!nlit || lit_types[0] != t) continue;
                char ids[32][128];
                for (int k = 0; k < nlit; k++) sl_glsl_ident(types[lit_types[k]], ids[k], sizeof ids[k], false);
                if (casters) emit_lit_loop(&gen, "sl_shadowed", ids, nlit, light_chunks, lit_types, per_light, vis);
                emit_lit_loop(&gen, "sl_lights", ids, nlit, light_chunks, lit_types, per_light, "E");
            }
        }
        sl_sb_append(&gen, "    return Lo;\n}\n");
        if (loop) sl_sb_printf(&gen, "vec3 sl_direct_lighting(SlSurface s) { return %s(s); }\n", loop->d.function);
        sl_sb_printf(&gen, "vec3 sl_shading_model(SlSurface s, vec3 l, vec3 E) { return %s(s, l, E); }\n",
                     model_chunk->d.function);
        sl_sb_append(&gen, "vec3 sl_shade_surface(SlSurface s) {\n");
        if (view && view->d.hook == SL_HOOK_DEBUG_VIEW) {
            sl_sb_printf(&gen, "    return %s(s);\n}\n", view->d.function);
        } else if (view) {
            sl_sb_append(&gen, "    return sl_direct_lighting(s);\n}\n");
        } else {
            /* KHR_materials_unlit (the core's key "unlit"): the base colour as radiance */
            sl_sb_append(&gen, "#if defined(SL_MAT_UNLIT) && SL_MAT_UNLIT\n    return s.base_color;\n#endif\n");
            sl_sb_append(&gen, "    vec3 Lo = sl_direct_lighting(s);\n");
            /* An override model (SL_DRAW_MATERIALS) owns its whole output: no AMBIENT hooks. A
             * MODEL_AMBIENT always runs (it may carry more than ambient light, e.g. sss), with
             * vec3(0) where AMBIENT hooks supply the ambient light instead. */
            bool hooks = na && !model_override;
            for (int i = 0; hooks && i < na; i++) sl_sb_printf(&gen, "    Lo += %s(s);\n", ambient_hooks[i]->d.function);
            if (model_ambient)
                sl_sb_printf(&gen, "    Lo += %s(s, %s);\n", model_ambient->d.function, hooks ? "vec3(0.0)" : "sl_ambient_irradiance");
            else if (!hooks)
                sl_sb_append(&gen, "    Lo += s.base_color * SL_INV_PI * sl_ambient_irradiance * s.ao;\n");
            /* glTF emission (shaders/material.glsl), whatever the model */
            sl_sb_append(&gen, "#ifdef SL_MAT_HAS_EMISSIVE\n    Lo += sl_emission(s);\n#endif\n");
            sl_sb_append(&gen, "    return Lo;\n}\n");
        }
        sl_source_generated(&p->fs, gen.s);
        ok = ok && sl_source_include(&p->fs, "sl:forward.frag", err, n);
        if (fragment && ok && !sl_source_include_from(&p->fs, fragment, owner_of_file(P, fragment), err, n))
            ok = false, culprit = owner_of_file(P, fragment);
    }
    sl_sb_free(&gen);
    sl_sb_free(&pre);
    sl_sb_free(&uni);
    sl_sb_free(&uvf);

    char label[512];
    snprintf(label, sizeof label, "material \"%s\" (%s%s)", mat->name, kind == SL_VARIANT_DEPTH ? "depth, " : "", model);
    p->label = strdup(label);
    p->composed = true;
    free(out->chunks);
    out->chunks = explain.s ? explain.s : strdup("");
    out->owners = owners;
    if (!ok) { /* a file could not be included: the plugin that named it is to blame */
        out->failed_plugin = culprit >= 1 ? culprit : -1;
        sl_program_free(p);
        return false;
    }
    /* the program's sl_vertex_hook_mask bits (the tag strings live as long as the plugin) */
    memcpy(out->node_tags, node_tags, sizeof node_tags);
    out->node_tag_count = node_tag_count;
    p->hash = sl_hash64(p->vs.text.s, p->vs.text.len, sl_hash64(p->fs.text.s, p->fs.text.len, 0));
    if (p->tessellated)
        p->hash = sl_hash64(p->tcs.text.s, p->tcs.text.len, sl_hash64(p->tes.text.s, p->tes.text.len, p->hash));
    for (int i = 0; i < *cache_count; i++) {
        if ((*cache)[i]->hash == p->hash && (*cache)[i]->id && !(*cache)[i]->stale) {
            sl_program_free(p);
            out->program = (*cache)[i];
            return true;
        }
    }
    if (!sl_program_build(p, err, n)) {
        out->failed_plugin = blame_compile_error(P, p, owners);
        /* the variant keeps its previous program (hot reload) */
        sl_program_free(p);
        return false;
    }
    *cache = realloc(*cache, (*cache_count + 1) * sizeof **cache);
    (*cache)[(*cache_count)++] = p;
    out->program = p;
    return true;
}
