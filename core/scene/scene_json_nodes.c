/* Scene nodes (transforms, tags, hierarchy) and their meshes (files, primitives).
 * See scene_json_internal.h. */
#include "scene/scene_json_internal.h"

/* ---- nodes and meshes ------------------------------------------------------------------- */

static int default_material(loader *L) {
    if (L->default_material >= 0) return L->default_material;
    int mi = sl_scene_find_material(L->scene, "default");
    if (mi < 0) {
        mi = sl_scene_add_material(L->scene, "default", "lambert");
        if (mi < 0) return -1;
        float grey[3] = {0.8f, 0.8f, 0.8f};
        if (!sl_prop_set_vec(&L->scene->materials[mi].props, "base_color", grey, 3, 0)) return -1;
    }
    return L->default_material = mi;
}

static const char *const primitive_names[] = {"sphere", "plane", "cube", "torus", "teapot"};
static const char *const sphere_keys[] = {"primitive", "radius", "segments", "rings"};
static const char *const plane_keys[] = {"primitive", "size", "subdivisions"};
static const char *const cube_keys[] = {"primitive", "size"};
static const char *const torus_keys[] = {"primitive", "major_radius", "minor_radius", "segments", "sides"};
static const char *const teapot_keys[] = {"primitive", "size", "tessellation"};
static const char *const file_keys[] = {"file", "model", "flip_v"};

static bool load_primitive(loader *L, const cJSON *mesh, const char *ctx, const char *kind,
                           sl_mesh_data *out) {
    const cJSON *v;
#define OPT_NUM(key, dst, min, excl, max) \
    if ((v = cJSON_GetObjectItemCaseSensitive(mesh, key)) && !sj_get_number(L, v, ctx, dst, min, excl, max)) return false
#define OPT_INT(key, dst, min, max) \
    if ((v = cJSON_GetObjectItemCaseSensitive(mesh, key)) && !sj_get_int(L, v, ctx, dst, min, max)) return false
    bool ok;
    if (strcmp(kind, "sphere") == 0) {
        float radius = 1.0f;
        int segments = 64, rings = 32;
        if (!sj_check_keys(L, mesh, ctx, KEYS(sphere_keys), false)) return false;
        OPT_NUM("radius", &radius, 0.0, true, FLT_MAX);
        OPT_INT("segments", &segments, 3, 2048);
        OPT_INT("rings", &rings, 2, 1024);
        ok = sl_mesh_sphere(out, radius, segments, rings);
    } else if (strcmp(kind, "plane") == 0) {
        float size[2] = {10.0f, 10.0f};
        int subdivisions = 1;
        if (!sj_check_keys(L, mesh, ctx, KEYS(plane_keys), false)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(mesh, "size"))) {
            if (cJSON_IsArray(v)) {
                if (!sj_get_vec(L, v, ctx, 2, size, false)) return false;
                if (!(size[0] > 0 && size[1] > 0))
                    return sj_failf(L, v, "%s: \"size\" must be a number > 0 or an array [x, z] of two numbers > 0", ctx);
            } else {
                if (!sj_get_number(L, v, ctx, &size[0], 0.0, true, FLT_MAX)) return false;
                size[1] = size[0];
            }
        }
        OPT_INT("subdivisions", &subdivisions, 1, 1024);
        ok = sl_mesh_plane(out, size[0], size[1], subdivisions);
    } else if (strcmp(kind, "cube") == 0) {
        float size = 1.0f;
        if (!sj_check_keys(L, mesh, ctx, KEYS(cube_keys), false)) return false;
        OPT_NUM("size", &size, 0.0, true, FLT_MAX);
        ok = sl_mesh_cube(out, size);
    } else if (strcmp(kind, "torus") == 0) {
        float major = 1.0f, minor = 0.25f;
        int segments = 64, sides = 32;
        if (!sj_check_keys(L, mesh, ctx, KEYS(torus_keys), false)) return false;
        OPT_NUM("major_radius", &major, 0.0, true, FLT_MAX);
        OPT_NUM("minor_radius", &minor, 0.0, true, FLT_MAX);
        OPT_INT("segments", &segments, 3, 2048);
        OPT_INT("sides", &sides, 3, 1024);
        if (!(minor < major))
            return sj_failf(L, mesh, "%s: \"minor_radius\" (%g) must be smaller than \"major_radius\" (%g)",
                         ctx, minor, major);
        ok = sl_mesh_torus(out, major, minor, segments, sides);
    } else {
        float size = 1.0f;
        int tessellation = 16;
        if (!sj_check_keys(L, mesh, ctx, KEYS(teapot_keys), false)) return false;
        OPT_NUM("size", &size, 0.0, true, FLT_MAX);
        OPT_INT("tessellation", &tessellation, 1, 128);
        ok = sl_mesh_teapot(out, size, tessellation);
    }
#undef OPT_NUM
#undef OPT_INT
    if (!ok) return sj_failf(L, mesh, "%s: could not build the %s (out of memory?)", ctx, kind);
    return true;
}

static bool load_mesh(loader *L, const cJSON *mesh, int node, int material, const char *node_name) {
    char buf[96], ctx[300];
    snprintf(ctx, sizeof ctx, "mesh of node '%s'", node_name);
    if (!cJSON_IsObject(mesh))
        return sj_failf(L, mesh, "%s: \"mesh\" must be an object ({\"primitive\": …} or {\"file\": …}), found %s",
                     ctx, sj_describe(mesh, buf, sizeof buf));
    const cJSON *prim = cJSON_GetObjectItemCaseSensitive(mesh, "primitive");
    const cJSON *file = cJSON_GetObjectItemCaseSensitive(mesh, "file");
    if (prim && file) return sj_failf(L, mesh, "%s: give either \"primitive\" or \"file\", not both", ctx);
    if (!prim && !file) {
        const char *const both[] = {"primitive", "file"};
        char hint[600] = "";
        if (mesh->child) sj_key_hint(hint, sizeof hint, mesh->child->string, KEYS(both), "keys");
        return sj_failf(L, mesh, "%s: needs \"primitive\" (sphere, plane, cube, torus, teapot) or \"file\"%s",
                     ctx, hint);
    }
    if (prim) {
        const char *kind;
        if (!sj_get_string(L, prim, ctx, &kind)) return false;
        if (!sj_in_list(kind, KEYS(primitive_names))) {
            char hint[600];
            sj_key_hint(hint, sizeof hint, kind, KEYS(primitive_names), "primitives");
            return sj_failf(L, prim, "%s: unknown primitive '%s'%s", ctx, kind, hint);
        }
        sl_mesh_data data;
        if (!load_primitive(L, mesh, ctx, kind, &data)) return false;
        int mat = material >= 0 ? material : default_material(L);
        int mi = mat < 0 ? -1 : sl_scene_add_mesh(L->scene, node_name, &data, mat);
        if (mi < 0 || !sl_scene_node_add_mesh(L->scene, node, mi)) return sj_failf(L, mesh, "out of memory");
        return true;
    }
    const char *rel, *model = NULL;
    if (!sj_get_string(L, file, ctx, &rel)) return false;
    const cJSON *v;
    if ((v = cJSON_GetObjectItemCaseSensitive(mesh, "model")) && !sj_get_string(L, v, ctx, &model)) return false;
    bool flip_v = false;
    if ((v = cJSON_GetObjectItemCaseSensitive(mesh, "flip_v"))) {
        if (!cJSON_IsBool(v)) return sj_failf(L, v, "%s: \"flip_v\" must be true or false", ctx);
        flip_v = cJSON_IsTrue(v);
    }
    if (!sj_check_keys(L, mesh, ctx, KEYS(file_keys), false)) return false;
    char why[2048];
    char *path = sl_scene_resolve_path(L->scene, L->data_dir, rel, why, sizeof why);
    if (!path) return sj_failf(L, file, "%s: mesh file %s", ctx, why);
    int first_material = L->scene->material_count, first_mesh = L->scene->mesh_count;
    sl_scene_update_transforms(L->scene); /* imported lights/cameras need this node's world */
    bool ok = sl_scene_import_model(L->scene, path, node, L->opts, why, sizeof why);
    free(path);
    if (!ok) return sj_failf(L, file, "%s: %s", ctx, why);
    for (int i = first_mesh; i < L->scene->mesh_count; i++) {
        if (material >= 0) L->scene->meshes[i].material = material;
        /* Assets authored for flipped textures (v = 0 at the image bottom, e.g. models whose
         * textures three.js loads with flipY): v becomes 1 − v and the tangent frames are
         * regenerated, since flipping v mirrors the handedness. */
        sl_mesh_data *d = &L->scene->meshes[i].data;
        if (flip_v && d->uvs) {
            for (int k = 0; k < d->vertex_count; k++) d->uvs[2 * k + 1] = 1.0f - d->uvs[2 * k + 1];
            sl_mesh_generate_tangents(d);
        }
    }
    if (model)
        for (int i = first_material; i < L->scene->material_count; i++) {
            char *m = strdup(model);
            if (!m) return sj_failf(L, file, "out of memory");
            free(L->scene->materials[i].model);
            L->scene->materials[i].model = m;
        }
    return true;
}

static const char *const node_keys[] = {"name", "parent", "children", "translate", "rotate",
                                        "scale", "matrix", "material", "mesh", "tags"};
#define SL_NODE_MAX_TAGS 16

/* Whether the linear part of a column-major 4×4 transform has rank ≤ 1 (every 2×2 minor zero,
 * relative to its columns' size): the node collapses to a line or a point, nothing to see. A
 * rank-2 transform (one zero scale, a flattening matrix) draws flat geometry, which the forward
 * pass shades with the geometric normal (stability_core singular_transform). */
static bool transform_collapses(const float *m) {
    const double a[3] = {m[0], m[1], m[2]}, b[3] = {m[4], m[5], m[6]}, c[3] = {m[8], m[9], m[10]};
    const double *col[3] = {a, b, c};
    double big = 0, minor = 0;
    for (int i = 0; i < 3; i++) {
        const double *x = col[i], *y = col[(i + 1) % 3];
        double cx = x[1] * y[2] - x[2] * y[1], cy = x[2] * y[0] - x[0] * y[2], cz = x[0] * y[1] - x[1] * y[0];
        minor = fmax(minor, sqrt(cx * cx + cy * cy + cz * cz));
        big = fmax(big, x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    }
    return !(minor > 1e-12 * big);
}

static bool load_node(loader *L, const cJSON *o, int parent, int depth, int *counter) {
    char buf[96];
    int index = (*counter)++;
    if (index >= MAX_ITEMS) return sj_failf(L, o, "more than %d nodes; at most %d are allowed", MAX_ITEMS, MAX_ITEMS);
    if (!cJSON_IsObject(o)) return sj_failf(L, o, "node #%d must be an object, found %s", index, sj_describe(o, buf, sizeof buf));
    if (depth > SL_SCENE_MAX_DEPTH)
        return sj_failf(L, o, "nodes are nested deeper than %d levels of \"children\"", SL_SCENE_MAX_DEPTH);
    char name[256], ctx[300];
    if (!sj_get_name(L, o, "node", index, false, name, sizeof name)) return false;
    snprintf(ctx, sizeof ctx, "node '%s'", name);
    int prev = sl_scene_find_node(L->scene, name);
    if (prev >= 0)
        return sj_failf(L, cJSON_GetObjectItemCaseSensitive(o, "name"), "duplicate node name '%s' "
                     "(%s); names must be unique", name,
                     sj_first_defined(prev < L->node_lines_n ? L->node_lines[prev] : 0, buf, sizeof buf));
    if (!sj_check_keys(L, o, ctx, KEYS(node_keys), false)) return false;
    const cJSON *v;
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "parent"))) {
        const char *pname;
        if (!sj_get_string(L, v, ctx, &pname)) return false;
        if (parent >= 0)
            return sj_failf(L, v, "%s is inside the \"children\" of '%s' and also names \"parent\": "
                         "use one of the two", ctx, L->scene->nodes[parent].name);
        parent = sl_scene_find_node(L->scene, pname);
        if (parent < 0) {
            const char **names = malloc(sizeof(char *) * (size_t)(L->scene->node_count + 1));
            char hint[600] = "";
            if (names) {
                for (int i = 0; i < L->scene->node_count; i++) names[i] = L->scene->nodes[i].name;
                const char *near = sj_nearest(pname, names, L->scene->node_count);
                if (near) snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
                free(names);
            }
            return sj_failf(L, v, "%s: unknown parent '%s'; a parent must be a node defined earlier "
                         "in the file%s", ctx, pname, hint);
        }
        int d = 0;
        for (int p = parent; p >= 0; p = L->scene->nodes[p].parent) d++;
        if (d > SL_SCENE_MAX_DEPTH)
            return sj_failf(L, v, "%s: nodes are nested deeper than %d levels", ctx, SL_SCENE_MAX_DEPTH);
    }
    int ni = sl_scene_add_node(L->scene, name, parent);
    if (ni < 0 || !sj_remember_line(&L->node_lines, &L->node_lines_n, ni, sj_line_of(L, o)))
        return sj_failf(L, o, "out of memory");

    /* transform: "matrix", or translate · rotate · scale */
    const cJSON *mat = cJSON_GetObjectItemCaseSensitive(o, "matrix");
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(o, "translate");
    const cJSON *r = cJSON_GetObjectItemCaseSensitive(o, "rotate");
    const cJSON *s = cJSON_GetObjectItemCaseSensitive(o, "scale");
    if (mat) {
        if (t || r || s)
            return sj_failf(L, mat, "%s: give either \"matrix\" or \"translate\"/\"rotate\"/\"scale\", not both", ctx);
        float m[16];
        if (!sj_get_vec(L, mat, ctx, 16, m, false)) return false;
        for (int k = 0; k < 16; k++)
            if (fabsf(m[k]) > SL_SCENE_MAX_EXTENT)
                return sj_failf(L, mat, "%s: \"matrix\" element %d is %g; beyond %g float32 positions collapse", ctx, k,
                             m[k], SL_SCENE_MAX_EXTENT);
        if (transform_collapses(m))
            return sj_failf(L, mat, "%s: \"matrix\" collapses the node to a line or a point (its 3x3 part has rank < 2, "
                         "e.g. all zero): nothing would be visible", ctx);
        memcpy(L->scene->nodes[ni].local, m, sizeof m);
    } else {
        float tr[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, sc[3] = {1, 1, 1};
        if (t && !sj_get_vec(L, t, ctx, 3, tr, false)) return false;
        for (int c = 0; t && c < 3; c++)
            if (fabsf(tr[c]) > SL_SCENE_MAX_EXTENT)
                return sj_failf(L, t, "%s: \"translate\" %g is beyond %g, where float32 positions collapse", ctx, tr[c],
                             SL_SCENE_MAX_EXTENT);
        if (r) {
            int n = cJSON_IsArray(r) ? cJSON_GetArraySize(r) : 0;
            if (n == 4) {
                if (!sj_get_vec(L, r, ctx, 4, q, false)) return false;
                double len = sqrt((double)q[0] * q[0] + (double)q[1] * q[1] + (double)q[2] * q[2] + (double)q[3] * q[3]);
                if (!(len > 1e-12) || !isfinite(len))
                    return sj_failf(L, r, "%s: \"rotate\" quaternion [x, y, z, w] must not be zero", ctx);
                for (int c = 0; c < 4; c++) q[c] = (float)(q[c] / len);
            } else {
                float deg[3];
                if (!cJSON_IsArray(r) || n != 3)
                    return sj_failf(L, r, "%s: \"rotate\" must be [x, y, z] Euler angles in degrees or a "
                                 "quaternion [x, y, z, w], found %s", ctx, sj_describe(r, buf, sizeof buf));
                if (!sj_get_vec(L, r, ctx, 3, deg, false)) return false;
                sl_quat_from_euler_deg(q, deg);
            }
        }
        if (s) {
            if (cJSON_IsArray(s)) {
                if (!sj_get_vec(L, s, ctx, 3, sc, false)) return false;
            } else if (sj_number_ok(s)) {
                sc[0] = sc[1] = sc[2] = (float)s->valuedouble;
            } else {
                return sj_failf(L, s, "%s: \"scale\" must be a number or an array of 3 numbers, found %s",
                             ctx, sj_describe(s, buf, sizeof buf));
            }
            if ((sc[0] == 0) + (sc[1] == 0) + (sc[2] == 0) >= 2)
                return sj_failf(L, s, "%s: \"scale\" must not be zero in more than one axis (the node would collapse to "
                             "a line or a point: nothing visible); one zero axis flattens it", ctx);
            for (int c = 0; c < 3; c++)
                if (fabsf(sc[c]) > SL_SCENE_MAX_EXTENT)
                    return sj_failf(L, s, "%s: \"scale\" %g is beyond %g, where float32 positions collapse", ctx, sc[c],
                                 SL_SCENE_MAX_EXTENT);
        }
        sl_mat4_from_trs(L->scene->nodes[ni].local, tr, q, sc);
    }

    /* "tags": names that VERTEX chunks with when_node_tag select (ABI 1.6); inherited by children */
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "tags"))) {
        if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) > SL_NODE_MAX_TAGS)
            return sj_failf(L, v, "%s: \"tags\" must be an array of at most %d names, found %s", ctx, SL_NODE_MAX_TAGS,
                         sj_describe(v, buf, sizeof buf));
        sl_node *nd = &L->scene->nodes[ni];
        nd->tags = calloc(SL_NODE_MAX_TAGS, sizeof *nd->tags);
        if (!nd->tags) return sj_failf(L, v, "out of memory");
        for (const cJSON *e = v->child; e; e = e->next) {
            if (!cJSON_IsString(e))
                return sj_failf(L, e, "%s: each tag must be a string, found %s", ctx, sj_describe(e, buf, sizeof buf));
            const char *tag = e->valuestring;
            size_t len = strlen(tag);
            if (!len || len > 64 || strspn(tag, "abcdefghijklmnopqrstuvwxyz0123456789_-") != len)
                return sj_failf(L, e, "%s: tag '%.80s' must be 1 to 64 characters of a-z, 0-9, '_' and '-'", ctx, tag);
            if (!(nd->tags[nd->tag_count] = strdup(tag))) return sj_failf(L, e, "out of memory");
            nd->tag_count++;
        }
    }

    int material = -1;
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "material"))) {
        const char *mname;
        if (!sj_get_string(L, v, ctx, &mname)) return false;
        material = sl_scene_find_material(L->scene, mname);
        if (material < 0) {
            const char **names = malloc(sizeof(char *) * (size_t)(L->scene->material_count + 1));
            char hint[600] = "";
            if (names) {
                for (int i = 0; i < L->scene->material_count; i++) names[i] = L->scene->materials[i].name;
                const char *near = sj_nearest(mname, names, L->scene->material_count);
                if (near) snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
                free(names);
            }
            return sj_failf(L, v, "%s: unknown material '%s'; materials must be defined in "
                         "\"materials\"%s", ctx, mname, hint);
        }
        if (!cJSON_GetObjectItemCaseSensitive(o, "mesh"))
            sj_warnf(L, v, "%s: \"material\" has no effect on a node without \"mesh\"", ctx);
    }
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "mesh")) && !load_mesh(L, v, ni, material, name)) return false;

    if ((v = cJSON_GetObjectItemCaseSensitive(o, "children"))) {
        if (!cJSON_IsArray(v))
            return sj_failf(L, v, "%s: \"children\" must be an array of nodes, found %s", ctx, sj_describe(v, buf, sizeof buf));
        for (const cJSON *c = v->child; c; c = c->next)
            if (!load_node(L, c, ni, depth + 1, counter)) return false;
    }
    return true;
}

bool sj_load_nodes(loader *L, const cJSON *arr) {
    char buf[96];
    if (!cJSON_IsArray(arr))
        return sj_failf(L, arr, "\"nodes\" must be an array of objects, found %s", sj_describe(arr, buf, sizeof buf));
    int counter = 0;
    for (const cJSON *o = arr->child; o; o = o->next)
        if (!load_node(L, o, -1, 0, &counter)) return false;
    return true;
}

