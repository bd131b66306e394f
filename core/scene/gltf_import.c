/* A glTF 2.0 file into the scene graph (the entry of the project's reader; gltf.h says how it
 * reports). The default scene's node trees (glTF 2.0 §3.5: each node has at most one parent, no
 * cycles, roots have none) become scene nodes under the parent node given, named
 * "<prefix>/<node name>" (prefix: the parent's name, or the file's stem at the top level); a scene
 * with several roots hangs them under one node "<prefix>/ROOT". Meshes and materials are made on
 * first use and keep the file's identity (gltf_mesh.c, gltf_material.c); cameras (§3.10) and
 * KHR_lights_punctual lights sit at their node, named after it. Values the specification
 * constrains are checked: a transform must be finite and within SL_SCENE_MAX_EXTENT, a rotation
 * a unit quaternion (a zero one becomes the identity, named), a camera's yfov positive, znear
 * below zfar (invalid values become the defaults, named). */
#include "log.h"
#include "scene/gltf.h"
#include <shadelab/input.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- the node hierarchy ------------------------------------------------------------------- */

/* im->parents from every node's children, refusing a second parent, a cycle or a bad index. */
static bool read_hierarchy(gltf_import *im) {
    gltf_doc *d = &im->doc;
    int n = gltf_count(d, "nodes");
    for (int i = 0; i < n; i++) {
        char at[48];
        snprintf(at, sizeof at, "/nodes/%d", i);
        const cJSON *node = gltf_item(d, "nodes", i), *children, *c;
        if (!cJSON_IsObject(node)) return gltf_fail(d, at, "must be an object");
        if (!gltf_get_array(d, node, at, "children", &children)) return false;
        int k = 0;
        cJSON_ArrayForEach(c, children) {
            char p[80];
            snprintf(p, sizeof p, "%s/children/%d", at, k++);
            double v = cJSON_IsNumber(c) ? c->valuedouble : -1;
            if (!(v >= 0 && v < n && v == floor(v))) return gltf_fail(d, p, "not an index of /nodes (%d elements)", n);
            int child = (int)v;
            if (child == i) return gltf_fail(d, p, "node %d is its own child", i);
            if (im->parents[child] >= 0)
                return gltf_fail(d, p, "node %d already has parent %d (a node has at most one)", child, im->parents[child]);
            im->parents[child] = i;
        }
    }
    /* a cycle: walking up from a node comes back to a node still being walked */
    char *state = calloc((size_t)n + 1, 1); /* 0 unseen, 1 on the current walk, 2 done */
    if (!state) return gltf_fail(d, NULL, "out of memory");
    for (int i = 0; i < n; i++) {
        int v = i;
        while (v >= 0 && state[v] == 0) state[v] = 1, v = im->parents[v];
        bool cycle = v >= 0 && state[v] == 1;
        for (int w = i; w >= 0 && state[w] == 1; w = im->parents[w]) state[w] = 2;
        if (cycle) {
            free(state);
            char at[48];
            snprintf(at, sizeof at, "/nodes/%d", v);
            return gltf_fail(d, at, "is its own ancestor (the children form a cycle)");
        }
    }
    free(state);
    return true;
}

/* The node's local transform: matrix, or T·R·S (§3.5.2), checked. */
static bool node_local(gltf_import *im, const cJSON *node, const char *at, float local[16]) {
    gltf_doc *d = &im->doc;
    float m[16], t[3] = {0, 0, 0}, r[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
    bool has_m, has_t, has_r, has_s;
    if (!gltf_get_numbers(d, node, at, "matrix", 16, m, &has_m) || !gltf_get_numbers(d, node, at, "translation", 3, t, &has_t) ||
        !gltf_get_numbers(d, node, at, "rotation", 4, r, &has_r) || !gltf_get_numbers(d, node, at, "scale", 3, s, &has_s))
        return false;
    const float *check[] = {m, t, s};
    const int counts[] = {has_m ? 16 : 0, 3, 3};
    const char *names[] = {"matrix", "translation", "scale"};
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < counts[k]; i++)
            if (fabsf(check[k][i]) > SL_SCENE_MAX_EXTENT) {
                char p[96];
                snprintf(p, sizeof p, "%s/%s", at, names[k]);
                return gltf_fail(d, p, "element %d (%g) is beyond ±%g, where float32 positions collapse", i, check[k][i],
                                 SL_SCENE_MAX_EXTENT);
            }
    if (has_m) {
        if (has_t || has_r || has_s) gltf_note(d, at, "both a matrix and TRS: the matrix used");
        if (m[3] != 0 || m[7] != 0 || m[11] != 0 || m[15] != 1) {
            gltf_note(d, at, "matrix's last row is not (0, 0, 0, 1): set to it");
            m[3] = m[7] = m[11] = 0, m[15] = 1;
        }
        memcpy(local, m, sizeof m);
        return true;
    }
    double len = sqrt((double)r[0] * r[0] + (double)r[1] * r[1] + (double)r[2] * r[2] + (double)r[3] * r[3]);
    char p[96];
    snprintf(p, sizeof p, "%s/rotation", at);
    if (len < 1e-6) {
        gltf_note(d, p, "a zero quaternion: the identity used");
        r[0] = r[1] = r[2] = 0, r[3] = 1, len = 1;
    } else if (fabs(len - 1) > 1e-3) {
        gltf_note(d, p, "not a unit quaternion (length %g): normalized", len);
    }
    for (int c = 0; c < 4; c++) r[c] = (float)(r[c] / len);
    sl_mat4_from_trs(local, t, r, s);
    return true;
}

/* Scene node for glTF node n under `parent` (and its subtree). */
static bool make_node(gltf_import *im, int n, int parent, int depth) {
    gltf_doc *d = &im->doc;
    char at[48];
    snprintf(at, sizeof at, "/nodes/%d", n);
    if (depth > SL_SCENE_MAX_DEPTH) return gltf_fail(d, at, "nested deeper than %d levels", SL_SCENE_MAX_DEPTH);
    const cJSON *node = gltf_item(d, "nodes", n), *children, *c;
    const char *name = NULL;
    int mesh = -1, skin = -1;
    float local[16];
    if (!gltf_get_string(d, node, at, "name", &name) || !gltf_get_index(d, node, at, "mesh", "meshes", false, &mesh) ||
        !gltf_get_index(d, node, at, "skin", "skins", false, &skin) || !node_local(im, node, at, local) ||
        !gltf_get_array(d, node, at, "children", &children))
        return false;
    char base[1200], unique[1300];
    if (name && name[0]) snprintf(base, sizeof base, "%.500s/%.600s", im->prefix, name);
    else snprintf(base, sizeof base, "%.500s/node%d", im->prefix, n);
    snprintf(unique, sizeof unique, "%s", base);
    for (int k = 2; sl_scene_find_node(im->scene, unique) >= 0; k++) snprintf(unique, sizeof unique, "%s#%d", base, k);
    int ni = sl_scene_add_node(im->scene, unique, parent);
    if (ni < 0) return gltf_fail(d, NULL, "out of memory");
    memcpy(im->scene->nodes[ni].local, local, sizeof local);
    im->nodes[n] = ni;
    if (skin >= 0 && mesh < 0) gltf_note(d, at, "a skin without a mesh: ignored");
    int range[2] = {0, 0};
    if (mesh >= 0 && !gltf_import_mesh(im, mesh, n, skin, range)) return false;
    for (int k = 0; k < range[1]; k++)
        if (!sl_scene_node_add_mesh(im->scene, ni, range[0] + k)) return gltf_fail(d, NULL, "out of memory");
    cJSON_ArrayForEach(c, children) if (!make_node(im, c->valueint, ni, depth + 1)) return false;
    return true;
}

/* ---- cameras and lights --------------------------------------------------------------------- */

static void transform(const float m[16], const float v[3], float w, float out[3]) {
    for (int r = 0; r < 3; r++) out[r] = m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * w;
}

static void normalize(float v[3], const float fallback[3]) {
    double l = sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
    for (int c = 0; c < 3; c++) v[c] = l > 1e-12 && isfinite(l) ? (float)(v[c] / l) : fallback[c];
}

/* The name of what sits at glTF node n: "<prefix>/<node name>", else its own name, else `kind`. */
static void placed_name(gltf_import *im, int n, const char *own, const char *kind, char *out, size_t size,
                        int (*taken)(const sl_scene *, const char *)) {
    const cJSON *nm = cJSON_GetObjectItemCaseSensitive(gltf_item(&im->doc, "nodes", n), "name");
    const char *name = cJSON_IsString(nm) && nm->valuestring[0] ? nm->valuestring : own && own[0] ? own : kind;
    char base[1200];
    snprintf(base, sizeof base, "%.500s/%.600s", im->prefix, name);
    snprintf(out, size, "%s", base);
    for (int k = 2; taken(im->scene, out) >= 0; k++) snprintf(out, size, "%s#%d", base, k);
}

/* A number member that must satisfy ok(); absent or invalid: *v keeps its default (named). */
static bool checked_value(gltf_doc *d, const cJSON *obj, const char *at, const char *key, bool required,
                         bool (*ok)(double, double), double other, double *v) {
    double x = NAN;
    if (!gltf_get_number(d, obj, at, key, &x)) return false;
    char p[128];
    snprintf(p, sizeof p, "%s/%s", at, key);
    if (isnan(x) && required) gltf_note(d, p, "missing (required): %g used", *v);
    else if (!isnan(x) && !ok(x, other)) gltf_note(d, p, "%g is invalid: %g used", x, *v);
    else if (!isnan(x)) *v = x;
    return true;
}
static bool positive(double x, double unused) { return (void)unused, x > 0; }
static bool fov(double x, double unused) { return (void)unused, x > 0 && x < M_PI; }
static bool not_negative(double x, double unused) { return (void)unused, x >= 0; }
static bool beyond(double x, double near) { return x > near; }
static bool nonzero(double x, double unused) { return (void)unused, x != 0; }

/* Camera `ci` (§3.10) at glTF node n, looking down the node's −Z with +Y up. */
static bool place_camera(gltf_import *im, int n, int ci) {
    gltf_doc *d = &im->doc;
    char at[48], pp[96];
    snprintf(at, sizeof at, "/cameras/%d", ci);
    const cJSON *cam = gltf_item(d, "cameras", ci), *persp, *ortho;
    const char *type = "", *name = NULL;
    if (!cJSON_IsObject(cam)) return gltf_fail(d, at, "must be an object");
    if (!gltf_get_string(d, cam, at, "type", &type) || !gltf_get_string(d, cam, at, "name", &name) ||
        !gltf_get_object(d, cam, at, "perspective", &persp) || !gltf_get_object(d, cam, at, "orthographic", &ortho))
        return false;
    bool is_ortho = !strcmp(type, "orthographic");
    const cJSON *p = is_ortho ? ortho : persp;
    snprintf(pp, sizeof pp, "%s/%s", at, is_ortho ? "orthographic" : "perspective");
    if ((!is_ortho && strcmp(type, "perspective")) || !p) {
        gltf_note(d, at, "type \"%.20s\" without its matching object: camera not used", type);
        return true;
    }
    double yfov = 45 * M_PI / 180, znear = 0.05, zfar = NAN, xmag = 1, ymag = 1, far_default = 100;
    if (is_ortho) {
        if (!checked_value(d, p, pp, "xmag", true, nonzero, 0, &xmag) || !checked_value(d, p, pp, "ymag", true, nonzero, 0, &ymag) ||
            !checked_value(d, p, pp, "znear", true, not_negative, 0, &znear))
            return false;
    } else if (!checked_value(d, p, pp, "yfov", true, fov, 0, &yfov) || !checked_value(d, p, pp, "znear", true, positive, 0, &znear)) {
        return false;
    }
    far_default = fmax(100, znear * 1000); /* perspective without zfar: infinite, bounded here */
    zfar = far_default;
    if (!checked_value(d, p, pp, "zfar", is_ortho, beyond, znear, &zfar)) return false;
    char unique[1300];
    placed_name(im, n, name, "camera", unique, sizeof unique, sl_scene_find_camera);
    int c = sl_scene_add_camera(im->scene, unique);
    if (c < 0) return gltf_fail(d, NULL, "out of memory");
    sl_camera *sc = &im->scene->cameras[c];
    const float *w = im->scene->nodes[im->nodes[n]].world, origin[3] = {0, 0, 0}, fwd[3] = {0, 0, -1}, up[3] = {0, 1, 0};
    float dir[3];
    transform(w, origin, 1, sc->position);
    transform(w, fwd, 0, dir);
    transform(w, up, 0, sc->up);
    normalize(dir, fwd);
    normalize(sc->up, up);
    for (int k = 0; k < 3; k++) sc->target[k] = sc->position[k] + dir[k];
    sc->fov_y_deg = (float)(yfov * 180 / M_PI);
    sc->znear = (float)znear, sc->zfar = (float)zfar;
    sc->orthographic = is_ortho, sc->xmag = (float)fabs(xmag), sc->ymag = (float)fabs(ymag);
    return true;
}

/* KHR_lights_punctual light `li` at glTF node n, shining down the node's −Z. */
static bool place_light(gltf_import *im, int n, int li) {
    gltf_doc *d = &im->doc;
    char at[96];
    snprintf(at, sizeof at, "/extensions/KHR_lights_punctual/lights/%d", li);
    const cJSON *lights = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(
        cJSON_GetObjectItemCaseSensitive(d->root, "extensions"), "KHR_lights_punctual"), "lights");
    const cJSON *light = cJSON_GetArrayItem(lights, li), *spot;
    const char *type = "", *name = NULL;
    float color[3] = {1, 1, 1};
    double intensity = 1, inner = 0, outer = M_PI / 4;
    if (!cJSON_IsObject(light)) return gltf_fail(d, at, "no such light");
    if (!gltf_get_string(d, light, at, "type", &type) || !gltf_get_string(d, light, at, "name", &name) ||
        !gltf_get_numbers(d, light, at, "color", 3, color, NULL) || !checked_value(d, light, at, "intensity", false, not_negative, 0, &intensity) ||
        !gltf_get_object(d, light, at, "spot", &spot))
        return false;
    const char *kind = !strcmp(type, "directional") ? "directional" : !strcmp(type, "point") ? "point"
                     : !strcmp(type, "spot") ? "spot" : NULL;
    if (!kind) {
        gltf_note(d, at, "type \"%.20s\" is not directional, point or spot: light not used", type);
        return true;
    }
    char sp[128];
    snprintf(sp, sizeof sp, "%s/spot", at);
    if (spot && !(gltf_get_number(d, spot, sp, "innerConeAngle", &inner) && gltf_get_number(d, spot, sp, "outerConeAngle", &outer)))
        return false;
    if (!(outer > 0 && outer <= M_PI / 2) || !(inner >= 0 && inner < outer)) {
        gltf_note(d, sp, "cone angles %g, %g are outside 0 <= inner < outer <= pi/2: 0, pi/4 used", inner, outer);
        inner = 0, outer = M_PI / 4;
    }
    char unique[1300];
    placed_name(im, n, name, "light", unique, sizeof unique, sl_scene_find_light);
    int l = sl_scene_add_light(im->scene, unique, kind);
    if (l < 0) return gltf_fail(d, NULL, "out of memory");
    sl_light *sl = &im->scene->lights[l];
    const float *w = im->scene->nodes[im->nodes[n]].world, origin[3] = {0, 0, 0}, fwd[3] = {0, 0, -1};
    transform(w, origin, 1, sl->position);
    transform(w, fwd, 0, sl->direction);
    normalize(sl->direction, fwd);
    /* colour × intensity split into a unit-peak colour and the intensity (I or E) */
    float peak = fmaxf(color[0], fmaxf(color[1], color[2])) * (float)intensity;
    for (int k = 0; k < 3; k++) sl->color[k] = peak > 0 ? fmaxf(color[k], 0) * (float)intensity / peak : 1;
    sl->intensity = peak > 0 && isfinite(peak) ? peak : 0;
    if (!strcmp(kind, "spot")) {
        sl_prop_set_number(&sl->props, "cone_angle", (float)(outer * 180 / M_PI), 0);
        sl_prop_set_number(&sl->props, "inner_cone_angle", (float)(inner * 180 / M_PI), 0);
        sl_prop_set_string(&sl->props, "falloff", "gltf", 0);
    }
    return true;
}

/* Cameras and lights of every node made, at the node's world transform. */
static bool place_cameras_and_lights(gltf_import *im) {
    gltf_doc *d = &im->doc;
    sl_scene_update_transforms(im->scene);
    for (int n = 0; n < gltf_count(d, "nodes"); n++) {
        if (im->nodes[n] < 0) continue;
        char at[48], ep[96];
        snprintf(at, sizeof at, "/nodes/%d", n);
        snprintf(ep, sizeof ep, "%s/extensions/KHR_lights_punctual", at);
        const cJSON *node = gltf_item(d, "nodes", n), *ext, *lp = NULL;
        int camera = -1;
        long long light = -1;
        if (!gltf_get_index(d, node, at, "camera", "cameras", false, &camera) || !gltf_get_object(d, node, at, "extensions", &ext) ||
            (ext && !gltf_get_object(d, ext, at, "KHR_lights_punctual", &lp)) ||
            (lp && !gltf_get_int(d, lp, ep, "light", 0, 1 << 30, &light)))
            return false;
        if (camera >= 0 && !place_camera(im, n, camera)) return false;
        if (light >= 0 && !place_light(im, n, (int)light)) return false;
    }
    return true;
}

/* ---- the import ------------------------------------------------------------------------------ */

/* The default scene's roots (scene, else scenes[0]) as scene nodes under `parent`. */
static bool make_scene(gltf_import *im, int parent) {
    gltf_doc *d = &im->doc;
    int which = -1;
    if (!gltf_get_index(d, d->root, "", "scene", "scenes", false, &which)) return false;
    if (which < 0 && !gltf_count(d, "scenes")) return gltf_fail(d, "/scenes", "the file has no scene: nothing to show");
    if (which < 0) which = 0;
    char at[48];
    snprintf(at, sizeof at, "/scenes/%d", which);
    const cJSON *sc = gltf_item(d, "scenes", which), *roots, *r;
    if (!cJSON_IsObject(sc)) return gltf_fail(d, at, "must be an object");
    if (!gltf_get_array(d, sc, at, "nodes", &roots)) return false;
    int count = cJSON_GetArraySize(roots), k = 0, n = gltf_count(d, "nodes");
    cJSON_ArrayForEach(r, roots) {
        char p[80];
        snprintf(p, sizeof p, "%s/nodes/%d", at, k++);
        double v = cJSON_IsNumber(r) ? r->valuedouble : -1;
        if (!(v >= 0 && v < n && v == floor(v))) return gltf_fail(d, p, "not an index of /nodes (%d elements)", n);
        if (im->parents[(int)v] >= 0) return gltf_fail(d, p, "node %d is a child of node %d, not a root", (int)v, im->parents[(int)v]);
        if (im->nodes[(int)v] != -1) return gltf_fail(d, p, "node %d is listed twice", (int)v);
        im->nodes[(int)v] = -2; /* listed */
    }
    if (count > 1) { /* several roots under one node */
        char name[1300];
        snprintf(name, sizeof name, "%.500s/ROOT", im->prefix);
        if ((parent = sl_scene_add_node(im->scene, name, parent)) < 0) return gltf_fail(d, NULL, "out of memory");
    }
    cJSON_ArrayForEach(r, roots) if (!make_node(im, r->valueint, parent, 1)) return false;
    return true;
}

/* The file's one warning: what is not rendered as its author made it. */
static void warn_unrendered(gltf_import *im) {
    static const char *const what[] = {"texCoord beyond 1 (those textures sample UV set 0)"};
    char list[5000] = "";
    size_t u = 0;
    for (unsigned b = 0; b < sizeof what / sizeof *what; b++)
        if (im->unrendered & (1u << b)) u += snprintf(list + u, sizeof list - u, "%s%s", u ? "; " : "", what[b]);
    if (im->doc.notes[0] && u < sizeof list) u += snprintf(list + u, sizeof list - u, "%s%s", u ? "; " : "", im->doc.notes);
    int listed = im->doc.note_count < GLTF_MAX_NOTES ? im->doc.note_count : GLTF_MAX_NOTES;
    if (im->doc.note_count > listed && u < sizeof list)
        u += snprintf(list + u, sizeof list - u, "; and %d more", im->doc.note_count - listed);
    if (u) SL_WARN("%s: not rendered as authored: %s", im->doc.path, list);
}

/* The names of `array`'s elements at the JSON pointer `at` ("0 \"walk\", 1 \"run\""). */
static void list_names(const cJSON *array, char *out, size_t size) {
    const cJSON *e, *name;
    size_t u = 0;
    int i = 0;
    out[0] = 0;
    cJSON_ArrayForEach(e, array) {
        name = cJSON_GetObjectItemCaseSensitive(e, "name");
        if (u < size)
            u += snprintf(out + u, size - u, "%s%d%s%.60s%s", i ? ", " : "", i, cJSON_IsString(name) ? " \"" : "",
                          cJSON_IsString(name) ? name->valuestring : "", cJSON_IsString(name) ? "\"" : "");
        i++;
    }
    if (!i) snprintf(out, size, "none");
}

/* The element of `array` named `which` (its name, or its index as a number); −1 after gltf_fail. */
static int choose(gltf_doc *d, const cJSON *array, const char *at, const char *what, const char *which) {
    const cJSON *e, *name;
    int i = 0;
    cJSON_ArrayForEach(e, array) {
        name = cJSON_GetObjectItemCaseSensitive(e, "name");
        if (cJSON_IsString(name) && !strcmp(name->valuestring, which)) return i;
        i++;
    }
    char *end;
    long n = strtol(which, &end, 10);
    if (*which && !*end && n >= 0 && n < cJSON_GetArraySize(array)) return (int)n;
    char names[1024];
    list_names(array, names, sizeof names);
    gltf_fail(d, at, "no %s \"%.100s\" (the file has: %s)", what, which, names);
    return -1;
}

/* --variant and --animation against what the file has. */
static bool choices(gltf_import *im, const sl_scene_load_opts *opts, int *animation) {
    gltf_doc *d = &im->doc;
    im->variant = -1, *animation = -1; /* −1: the first, named in the warning when there are more */
    if (opts && opts->gltf_variant) {
        const cJSON *variants = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(
            cJSON_GetObjectItemCaseSensitive(d->root, "extensions"), "KHR_materials_variants"), "variants");
        if ((im->variant = choose(d, variants, "/extensions/KHR_materials_variants/variants", "variant", opts->gltf_variant)) < 0)
            return false;
    }
    if (opts && opts->gltf_animation &&
        (*animation = choose(d, cJSON_GetObjectItemCaseSensitive(d->root, "animations"), "/animations", "animation",
                             opts->gltf_animation)) < 0)
        return false;
    return true;
}

static bool import(gltf_import *im, int parent, const sl_scene_load_opts *opts) {
    gltf_doc *d = &im->doc;
    int animation;
    if (!gltf_check_extensions(d) || !choices(im, opts, &animation)) return false;
    int nm = gltf_count(d, "materials"), nmesh = gltf_count(d, "meshes"), nn = gltf_count(d, "nodes");
    im->materials = malloc(sizeof(int) * (size_t)(nm + 1));
    im->meshes = malloc(sizeof *im->meshes * (size_t)(nmesh + 1));
    im->nodes = malloc(sizeof(int) * (size_t)(nn + 1));
    im->parents = malloc(sizeof(int) * (size_t)(nn + 1));
    if (!im->materials || !im->meshes || !im->nodes || !im->parents) return gltf_fail(d, NULL, "out of memory");
    for (int i = 0; i < nm; i++) im->materials[i] = -1;
    for (int i = 0; i < nmesh; i++) im->meshes[i][0] = -1, im->meshes[i][1] = 0;
    for (int i = 0; i < nn; i++) im->nodes[i] = -1, im->parents[i] = -1;
    int meshes = im->scene->mesh_count, lights = im->scene->light_count, cameras = im->scene->camera_count;
    if (!read_hierarchy(im) || !make_scene(im, parent) || !gltf_import_skins(im, meshes) || !place_cameras_and_lights(im))
        return false;
    if (gltf_count(d, "animations") && !gltf_import_animation(im, animation)) return false;
    if (meshes == im->scene->mesh_count && lights == im->scene->light_count && cameras == im->scene->camera_count)
        SL_WARN("%s: the file contains no triangle meshes", d->path);
    warn_unrendered(im);
    return true;
}

bool sl_scene_import_gltf(sl_scene *scene, const char *path, int parent_node, const sl_scene_load_opts *opts,
                          char *err, size_t err_size) {
    gltf_import im = {.scene = scene, .default_material = -1};
    if (parent_node < -1 || parent_node >= scene->node_count) {
        snprintf(err, err_size, "%s: invalid parent node", path);
        return false;
    }
    bool ok = gltf_open(&im.doc, path, err, err_size);
    snprintf(im.prefix, sizeof im.prefix, "%s", parent_node >= 0 ? scene->nodes[parent_node].name : im.doc.stem);
    ok = ok && import(&im, parent_node, opts);
    if (ok) sl_scene_update_transforms(scene);
    gltf_close(&im.doc);
    free(im.materials), free(im.meshes), free(im.nodes), free(im.parents);
    return ok;
}

bool sl_file_is_gltf(const char *path) {
    int fd = sl_open_input_file(path, NULL, 0); /* never blocks on a FIFO */
    if (fd < 0) return false;
    char head[4096];
    ssize_t n = read(fd, head, sizeof head - 1);
    close(fd);
    if (n < 4) return false;
    head[n] = 0;
    if (!memcmp(head, "glTF", 4)) return true;
    ssize_t i = n >= 3 && !memcmp(head, "\xEF\xBB\xBF", 3) ? 3 : 0;
    while (i < n && (head[i] == ' ' || head[i] == '\t' || head[i] == '\r' || head[i] == '\n')) i++;
    return i < n && head[i] == '{' && strstr(head + i, "\"asset\"") != NULL;
}
