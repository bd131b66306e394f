/* A model file, imported under a node or opened as a whole scene: glTF (by name or content) goes
 * to the project's glTF reader (core/scene/gltf_*.c), OBJ by name to its OBJ reader
 * (core/scene/obj_reader.c: streamed, bounded, linear; assimp's took 330-740 s and 5.8 GB for
 * 10 M triangles, the reader 33 s and 0.5 GB), everything else to assimp (scene_assimp.c). */
#include "scene/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

bool sl_scene_import_model(sl_scene *scene, const char *path, int parent_node, const sl_scene_load_opts *opts,
                           char *err, size_t err_size) {
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    bool named = dot && (!slash || dot > slash);
    if ((named && (!strcasecmp(dot, ".gltf") || !strcasecmp(dot, ".glb"))) || sl_file_is_gltf(path))
        return sl_scene_import_gltf(scene, path, parent_node, opts, err, err_size);
    if (opts && (opts->gltf_variant || opts->gltf_animation)) {
        snprintf(err, err_size, "%s: --%s applies to glTF files only", path, opts->gltf_variant ? "variant" : "animation");
        return false;
    }
    if (named && !strcasecmp(dot, ".obj")) return sl_scene_import_obj(scene, path, parent_node, err, err_size);
    return sl_scene_import_assimp(scene, path, parent_node, err, err_size);
}

bool sl_scene_import_file(sl_scene *scene, const char *path, int parent_node, char *err, size_t err_size) {
    return sl_scene_import_model(scene, path, parent_node, NULL, err, err_size);
}

/* A model opened directly must show something and stay where float32 positions hold. */
static bool check_model(const sl_scene *s, const char *path, char *err, size_t err_size) {
    if (!s->mesh_count) {
        snprintf(err, err_size, "%s: nothing to draw: the scene shown has no triangle mesh (a warning above names what "
                 "was dropped, if anything)", path);
        return false;
    }
    double reach = 0;
    for (int c = 0; c < 3; c++) reach = fmax(reach, fmax(fabs(s->bounds_min[c]), fabs(s->bounds_max[c])));
    if (!(reach <= SL_SCENE_MAX_EXTENT)) {
        snprintf(err, err_size, "%s: the geometry reaches %g from the origin; beyond %g float32 positions collapse", path,
                 reach, SL_SCENE_MAX_EXTENT);
        return false;
    }
    return true;
}

bool sl_scene_load_model(sl_scene *scene, const char *path, const sl_scene_load_opts *opts, char *err,
                         size_t err_size) {
    if (err && err_size) err[0] = 0;
    sl_scene s;
    memset(&s, 0, sizeof s);
    char *abs = realpath(path, NULL);
    s.path = strdup(path);
    s.dir = strdup(abs ? abs : path);
    free(abs);
    char *slash = s.dir ? strrchr(s.dir, '/') : NULL;
    if (slash) *slash = 0;
    s.environment.intensity = 1.0f;
    s.from_model = true;
    const char *base = strrchr(path, '/');
    char stem[256];
    snprintf(stem, sizeof stem, "%s", base ? base + 1 : path);
    char *dot = strrchr(stem, '.');
    if (dot && dot != stem) *dot = 0;
    int node = s.path && s.dir ? sl_scene_add_node(&s, stem, -1) : -1;
    bool ok = node >= 0;
    if (!ok && err && err_size) snprintf(err, err_size, "%s: out of memory", path);
    if (ok) {
        sl_scene_update_transforms(&s);
        ok = sl_scene_import_model(&s, path, node, opts, err, err_size);
    }
    if (ok) {
        sl_scene_update_transforms(&s);
        ok = check_model(&s, path, err, err_size);
    }
    if (!ok) {
        sl_scene_free(&s);
        return false;
    }
    *scene = s;
    return true;
}
