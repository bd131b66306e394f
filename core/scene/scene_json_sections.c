/* Scene sections: plugins, params, materials, cameras, lights, environment.
 * See scene_json_internal.h. */
#include "scene/scene_json_internal.h"

/* ---- sections --------------------------------------------------------------------------- */


bool sj_load_plugins(loader *L, const cJSON *arr) {
    char buf[96];
    if (!cJSON_IsArray(arr))
        return sj_failf(L, arr, "\"plugins\" must be an array of plugin names, found %s",
                     sj_describe(arr, buf, sizeof buf));
    if (!sj_check_count(L, arr, "plugins")) return false;
    for (const cJSON *e = arr->child; e; e = e->next) {
        if (!cJSON_IsString(e) || !e->valuestring[0])
            return sj_failf(L, e, "\"plugins\": each entry must be a plugin name (a string), found %s",
                         sj_describe(e, buf, sizeof buf));
        const char *name = e->valuestring;
        if (strpbrk(name, "/\\.") || strchr(name, ':'))
            return sj_failf(L, e, "\"plugins\": '%s' is a path; a scene may only name plugins (like "
                         "\"ggx\"), never paths: load plugin files with --plugin or "
                         "SHADELAB_PLUGIN_PATH", name);
        for (const char *c = name; *c; c++)
            if (!isalnum((unsigned char)*c) && *c != '_' && *c != '-')
                return sj_failf(L, e, "\"plugins\": '%s' is not a plugin name (letters, digits, '_' "
                             "and '-' only)", name);
        bool dup = false;
        for (int i = 0; i < L->scene->plugin_count; i++) dup = dup || strcmp(L->scene->plugins[i], name) == 0;
        if (dup) {
            sj_warnf(L, e, "\"plugins\": '%s' is listed twice", name);
            continue;
        }
        char **p = realloc(L->scene->plugins, sizeof(char *) * (size_t)(L->scene->plugin_count + 1));
        if (!p) return sj_failf(L, e, "out of memory");
        L->scene->plugins = p;
        if (!(p[L->scene->plugin_count] = strdup(name))) return sj_failf(L, e, "out of memory");
        L->scene->plugin_count++;
    }
    return true;
}

bool sj_load_params(loader *L, const cJSON *obj) {
    char buf[96];
    if (!cJSON_IsObject(obj))
        return sj_failf(L, obj, "\"params\" must be an object of \"plugin.param\": value, found %s",
                     sj_describe(obj, buf, sizeof buf));
    if (!sj_check_keys(L, obj, "params", NULL, 0, true)) return false;
    for (const cJSON *e = obj->child; e; e = e->next) {
        if (strcmp(e->string, "comment") == 0) continue;
        const char *dot = strchr(e->string, '.');
        if (!dot || dot == e->string || !dot[1] || strpbrk(e->string, " \t\n"))
            return sj_failf(L, e, "\"params\": key \"%s\" must be a parameter id \"plugin.param\" "
                         "(or \"material.NAME.key\" / \"light.NAME.key\")", e->string);
        if (!sj_get_prop(L, e, "params", &L->scene->params)) return false;
    }
    return true;
}

/* The loader's own material keys; every other key is a property whose meaning (and whose near
 * misses) only the loaded plugins' schema knows: the application checks it (sl_app). */
static const char *const material_keys[] = {"name", "model", "cast_shadows"};

bool sj_load_materials(loader *L, const cJSON *arr) {
    char buf[96];
    if (!cJSON_IsArray(arr))
        return sj_failf(L, arr, "\"materials\" must be an array of objects, found %s", sj_describe(arr, buf, sizeof buf));
    if (!sj_check_count(L, arr, "materials")) return false;
    int index = 0;
    for (const cJSON *o = arr->child; o; o = o->next, index++) {
        if (!cJSON_IsObject(o))
            return sj_failf(L, o, "material #%d must be an object, found %s", index, sj_describe(o, buf, sizeof buf));
        char name[256], ctx[300];
        if (!sj_get_name(L, o, "material", index, true, name, sizeof name)) return false;
        snprintf(ctx, sizeof ctx, "material '%s'", name);
        int prev = sl_scene_find_material(L->scene, name);
        if (prev >= 0)
            return sj_failf(L, cJSON_GetObjectItemCaseSensitive(o, "name"), "duplicate material name "
                         "'%s' (%s); names must be unique", name,
                         sj_first_defined(L->scene->materials[prev].line, buf, sizeof buf));
        const char *model = "lambert";
        const cJSON *v;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "model")) && !sj_get_string(L, v, ctx, &model)) return false;
        int mi = sl_scene_add_material(L->scene, name, model);
        if (mi < 0) return sj_failf(L, o, "out of memory");
        L->scene->materials[mi].line = sj_line_of(L, o);
        bool cast = true;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "cast_shadows")) && !sj_get_bool(L, v, ctx, &cast)) return false;
        L->scene->materials[mi].cast_shadows = cast;
        if (!sj_check_keys(L, o, ctx, KEYS(material_keys), true)) return false;
        for (const cJSON *e = o->child; e; e = e->next) {
            if (sj_in_list(e->string, KEYS(material_keys)) || strcmp(e->string, "comment") == 0) continue;
            if (!sj_get_prop(L, e, ctx, &L->scene->materials[mi].props)) return false;
        }
    }
    return true;
}

static const char *const camera_keys[] = {"name", "position", "target", "up", "fov_y", "near", "far",
                                          "type", "xmag", "ymag"};
static const char *const camera_types[] = {"perspective", "orthographic"};

bool sj_load_cameras(loader *L, const cJSON *arr) {
    char buf[96];
    if (!cJSON_IsArray(arr))
        return sj_failf(L, arr, "\"cameras\" must be an array of objects, found %s", sj_describe(arr, buf, sizeof buf));
    if (!sj_check_count(L, arr, "cameras")) return false;
    int index = 0;
    for (const cJSON *o = arr->child; o; o = o->next, index++) {
        if (!cJSON_IsObject(o))
            return sj_failf(L, o, "camera #%d must be an object, found %s", index, sj_describe(o, buf, sizeof buf));
        char name[256], ctx[300];
        if (!sj_get_name(L, o, "camera", index, false, name, sizeof name)) return false;
        snprintf(ctx, sizeof ctx, "camera '%s'", name);
        int prev = sl_scene_find_camera(L->scene, name);
        if (prev >= 0)
            return sj_failf(L, o, "duplicate camera name '%s' (%s); names must be unique", name,
                         sj_first_defined(prev < L->camera_lines_n ? L->camera_lines[prev] : 0, buf, sizeof buf));
        if (!sj_check_keys(L, o, ctx, KEYS(camera_keys), false)) return false;
        int ci = sl_scene_add_camera(L->scene, name);
        if (ci < 0 || !sj_remember_line(&L->camera_lines, &L->camera_lines_n, ci, sj_line_of(L, o)))
            return sj_failf(L, o, "out of memory");
        sl_camera *c = &L->scene->cameras[ci];
        const cJSON *v;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "position")) && !sj_get_vec(L, v, ctx, 3, c->position, false)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "target")) && !sj_get_vec(L, v, ctx, 3, c->target, false)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "up")) && !sj_get_direction(L, v, ctx, c->up)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "fov_y")) &&
            !sj_get_number(L, v, ctx, &c->fov_y_deg, 0.0, true, 179.0)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "near")) && !sj_get_number(L, v, ctx, &c->znear, 0.0, true, FLT_MAX)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "far")) && !sj_get_number(L, v, ctx, &c->zfar, 0.0, true, FLT_MAX)) return false;
        /* glTF 2.0 cameras: "orthographic" with half-extents xmag, ymag (the viewport's aspect
         * decides the width; xmag is kept for --list-cameras and the file's intent) */
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "type"))) {
            const char *type;
            if (!sj_get_string(L, v, ctx, &type)) return false;
            if (!sj_in_list(type, KEYS(camera_types))) {
                char hint[600];
                sj_key_hint(hint, sizeof hint, type, KEYS(camera_types), "types");
                return sj_failf(L, v, "%s: unknown camera type '%s'%s", ctx, type, hint);
            }
            c->orthographic = !strcmp(type, "orthographic");
        }
        c->ymag = c->xmag = 1.0f;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "ymag")) && !sj_get_number(L, v, ctx, &c->ymag, 0.0, true, FLT_MAX)) return false;
        c->xmag = c->ymag;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "xmag")) && !sj_get_number(L, v, ctx, &c->xmag, 0.0, true, FLT_MAX)) return false;
        if (!c->orthographic && (cJSON_GetObjectItemCaseSensitive(o, "xmag") || cJSON_GetObjectItemCaseSensitive(o, "ymag")))
            sj_warnf(L, o, "%s: \"xmag\"/\"ymag\" apply to \"type\": \"orthographic\" cameras only (ignored)", ctx);
        if (!(c->zfar > c->znear))
            return sj_failf(L, o, "%s: \"far\" (%g) must be greater than \"near\" (%g)", ctx, c->zfar, c->znear);
        /* depth precision: measured on the 32-bit float depth buffer, far/near = 1e7 already
         * z-fights where a sphere meets a plane, 1e9 renders black; refuse past 1e7, warn past 1e5 */
        double ratio = (double)c->zfar / c->znear;
        if (ratio > 1e7)
            return sj_failf(L, o, "%s: far/near = %g is beyond the depth buffer's precision (at most 1e7; raise \"near\")",
                         ctx, ratio);
        if (ratio > 1e5)
            sj_warnf(L, o, "%s: far/near = %g loses depth precision (surfaces close together may z-fight); raise \"near\"",
                  ctx, ratio);
        float d[3] = {c->target[0] - c->position[0], c->target[1] - c->position[1], c->target[2] - c->position[2]};
        float dl = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(dl > 0.0f)) return sj_failf(L, o, "%s: \"position\" and \"target\" are the same point", ctx);
        float x[3] = {d[1] * c->up[2] - d[2] * c->up[1], d[2] * c->up[0] - d[0] * c->up[2],
                      d[0] * c->up[1] - d[1] * c->up[0]};
        if (!(sqrtf(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) > 1e-6f * dl))
            return sj_failf(L, o, "%s: \"up\" is parallel to the viewing direction (target − position)", ctx);
    }
    return true;
}

static const char *const light_keys[] = {"name", "type", "position", "direction", "color",
                                         "intensity", "enabled", "cast_shadows"};

bool sj_load_lights(loader *L, const cJSON *arr) {
    char buf[96];
    if (!cJSON_IsArray(arr))
        return sj_failf(L, arr, "\"lights\" must be an array of objects, found %s", sj_describe(arr, buf, sizeof buf));
    if (!sj_check_count(L, arr, "lights")) return false;
    int index = 0;
    for (const cJSON *o = arr->child; o; o = o->next, index++) {
        if (!cJSON_IsObject(o))
            return sj_failf(L, o, "light #%d must be an object, found %s", index, sj_describe(o, buf, sizeof buf));
        char name[256], ctx[300];
        if (!sj_get_name(L, o, "light", index, false, name, sizeof name)) return false;
        snprintf(ctx, sizeof ctx, "light '%s'", name);
        int prev = sl_scene_find_light(L->scene, name);
        if (prev >= 0)
            return sj_failf(L, o, "duplicate light name '%s' (%s); names must be unique", name,
                         sj_first_defined(L->scene->lights[prev].line, buf, sizeof buf));
        const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, "type");
        const char *type = NULL;
        if (!v) return sj_failf(L, o, "%s has no \"type\" (\"directional\", \"point\" or a plugin's light type such as \"spot\")", ctx);
        if (!sj_get_string(L, v, ctx, &type)) return false;
        if (!sj_check_keys(L, o, ctx, KEYS(light_keys), true)) return false;
        int li = sl_scene_add_light(L->scene, name, type);
        if (li < 0) return sj_failf(L, o, "out of memory");
        sl_light *l = &L->scene->lights[li];
        l->line = sj_line_of(L, o);
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "position")) && !sj_get_vec(L, v, ctx, 3, l->position, false)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "direction")) && !sj_get_direction(L, v, ctx, l->direction)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "color")) && !sj_get_vec(L, v, ctx, 3, l->color, true)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "intensity")) && !sj_get_number(L, v, ctx, &l->intensity, 0.0, false, FLT_MAX)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "enabled")) && !sj_get_bool(L, v, ctx, &l->enabled)) return false;
        if ((v = cJSON_GetObjectItemCaseSensitive(o, "cast_shadows")) && !sj_get_bool(L, v, ctx, &l->cast_shadows)) return false;
        if (strcmp(type, "directional") == 0 && cJSON_GetObjectItemCaseSensitive(o, "position"))
            sj_warnf(L, cJSON_GetObjectItemCaseSensitive(o, "position"), "%s: a directional light has no position (ignored)", ctx);
        if (strcmp(type, "point") == 0 && cJSON_GetObjectItemCaseSensitive(o, "direction"))
            sj_warnf(L, cJSON_GetObjectItemCaseSensitive(o, "direction"), "%s: a point light has no direction (ignored)", ctx);
        for (const cJSON *e = o->child; e; e = e->next) {
            if (sj_in_list(e->string, KEYS(light_keys)) || strcmp(e->string, "comment") == 0) continue;
            if (!sj_get_prop(L, e, ctx, &L->scene->lights[li].props)) return false;
        }
    }
    return true;
}

/* Procedural texture specs ("checker:…", "constant:…") are not files. */
static bool is_procedural_spec(const char *s) {
    static const char *const kinds[] = {"checker:", "grid:", "constant:", "gradient", "uv"};
    for (int i = 0; i < 5; i++) {
        size_t n = strlen(kinds[i]);
        if (strncmp(s, kinds[i], n) == 0 && (kinds[i][n - 1] == ':' || s[n] == 0 || s[n] == ':')) return true;
    }
    return false;
}

static const char *const environment_keys[] = {"map", "color", "intensity", "yaw"};

bool sj_load_environment(loader *L, const cJSON *o) {
    char buf[96];
    const char *ctx = "environment";
    if (!cJSON_IsObject(o)) return sj_failf(L, o, "\"environment\" must be an object, found %s", sj_describe(o, buf, sizeof buf));
    if (!sj_check_keys(L, o, ctx, KEYS(environment_keys), true)) return false;
    sl_environment *env = &L->scene->environment;
    const cJSON *v;
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "map"))) {
        const char *map;
        if (!sj_get_string(L, v, ctx, &map)) return false;
        if (is_procedural_spec(map)) {
            env->map = strdup(map);
        } else {
            char why[2048];
            env->map = sl_scene_resolve_path(L->scene, L->data_dir, map, why, sizeof why);
            if (!env->map) return sj_failf(L, v, "environment map: %s", why);
        }
        if (!env->map) return sj_failf(L, v, "out of memory");
    }
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "color")) && !sj_get_vec(L, v, ctx, 3, env->color, true)) return false;
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "intensity")) && !sj_get_number(L, v, ctx, &env->intensity, 0.0, false, FLT_MAX)) return false;
    if ((v = cJSON_GetObjectItemCaseSensitive(o, "yaw")) && !sj_get_number(L, v, ctx, &env->yaw_deg, -FLT_MAX, false, FLT_MAX)) return false;
    /* the constant radiance is what reaches the colour target: it must fit (RGBA16F: 65504) */
    for (int c = 0; c < 3; c++)
        if ((double)env->color[c] * env->intensity > SL_MAX_RADIANCE)
            return sj_failf(L, o, "%s: color x intensity = %g is more radiance than the colour target holds (at most %g)",
                         ctx, (double)env->color[c] * env->intensity, SL_MAX_RADIANCE);
    for (const cJSON *e = o->child; e; e = e->next) {
        if (sj_in_list(e->string, KEYS(environment_keys)) || strcmp(e->string, "comment") == 0) continue;
        if (!sj_get_prop(L, e, ctx, &env->props)) return false;
    }
    return true;
}

