/* The JSON scene loader (format: scenes/README.md).
 *
 * Parsing is cJSON's. cJSON keeps no source positions, so after a successful parse a small
 * scanner walks the text and the tree side by side (same order, valid JSON) and records the
 * line and column of every key and array element: error messages name exact positions.
 *
 * Every error stops the load with "file:line:column: what is wrong (what was expected)";
 * unknown keys in structural objects are warnings that name the nearest valid key. Nothing
 * here may crash on hostile input: every value is type- and range-checked before use, nesting
 * is bounded, and allocation failures are errors. */
#include "scene/scene_json_internal.h"

extern const char sl_default_scene_json[]; /* generated from scenes/default.json */

/* ---- entry points ----------------------------------------------------------------------- */

/* "gallery" is tools/gallery.sh's (scenes/README.md); the viewer ignores it. "generated_by" is
 * the command that writes the scene's generated files, named when one is missing. */
static const char *const top_keys[] = {"plugins", "params", "cameras", "materials", "nodes",
                                       "lights", "environment", "gallery", "generated_by"};

static bool load(loader *L, const char *dir) {
    const char *text = L->text;
    if (L->len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) { /* UTF-8 byte order mark */
        L->text += 3;
        L->len -= 3;
    }
    const char *nul = memchr(L->text, 0, L->len);
    if (nul) return sj_fail_parse(L, (size_t)(nul - L->text));
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithLengthOpts(L->text, L->len + 1, &end, true);
    if (!root) {
        size_t at = end && end >= L->text ? (size_t)(end - L->text) : 0;
        if (at > L->len) at = L->len;
        return sj_fail_parse(L, at);
    }
    sj_index_positions(L, root);

    char buf[96];
    bool ok = true;
    sl_scene *s = L->scene;
    if (!cJSON_IsObject(root)) {
        ok = sj_failf(L, root, "the top level must be a JSON object { … }, found %s",
                   sj_describe(root, buf, sizeof buf));
        goto done;
    }
    if (!(s->path = strdup(L->file)) || (dir && !(s->dir = strdup(dir)))) {
        ok = sj_failf(L, NULL, "out of memory");
        goto done;
    }
    s->environment.intensity = 1.0f;
    if (!sj_check_keys(L, root, "top level", KEYS(top_keys), false)) {
        ok = false;
        goto done;
    }
    const cJSON *v;
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "generated_by"))) {
        if (!cJSON_IsString(v) || !v->valuestring[0] || strlen(v->valuestring) > 512)
            ok = sj_failf(L, v, "\"generated_by\" must be the command (a string of 1-512 characters) that "
                                "writes the scene's generated files");
        else if (!(s->generated_by = strdup(v->valuestring)))
            ok = sj_failf(L, NULL, "out of memory");
    }
    if (ok && (v = cJSON_GetObjectItemCaseSensitive(root, "plugins"))) ok = sj_load_plugins(L, v);
    if (ok && (v = cJSON_GetObjectItemCaseSensitive(root, "params"))) ok = sj_load_params(L, v);
    if (ok && (v = cJSON_GetObjectItemCaseSensitive(root, "materials"))) ok = sj_load_materials(L, v);
    if (ok && (v = cJSON_GetObjectItemCaseSensitive(root, "cameras"))) ok = sj_load_cameras(L, v);
    if (ok && (v = cJSON_GetObjectItemCaseSensitive(root, "nodes"))) ok = sj_load_nodes(L, v);
    if (ok && (v = cJSON_GetObjectItemCaseSensitive(root, "lights"))) ok = sj_load_lights(L, v);
    if (ok && (v = cJSON_GetObjectItemCaseSensitive(root, "environment"))) ok = sj_load_environment(L, v);
    if (ok) sl_scene_update_transforms(s);
    if (ok && s->node_count) { /* how far the geometry reaches (imported meshes included) */
        double reach = 0;
        for (int c = 0; c < 3; c++) reach = fmax(reach, fmax(fabs(s->bounds_min[c]), fabs(s->bounds_max[c])));
        const cJSON *nodes = cJSON_GetObjectItemCaseSensitive(root, "nodes");
        if (!(reach <= SL_SCENE_MAX_EXTENT))
            ok = sj_failf(L, nodes, "the scene's geometry reaches %g from the origin; beyond %g float32 positions "
                       "collapse (move it toward the origin or scale it down)", reach, SL_SCENE_MAX_EXTENT);
        else if (reach > SL_SCENE_WARN_EXTENT)
            sj_warnf(L, nodes, "the scene's geometry reaches %g from the origin: float32 positions there have steps "
                  "of %g; detail smaller than that jitters", reach, reach / 8388608.0);
    }
done:
    cJSON_Delete(root);
    return ok && !L->failed;
}

static bool load_common(sl_scene *out, const char *text, size_t len, const char *name,
                        const char *dir, const sl_scene_load_opts *opts, char *err, size_t err_size) {
    if (err && err_size) err[0] = 0;
    sl_scene scene;
    memset(&scene, 0, sizeof scene);
    loader L = {.scene = &scene, .text = text, .len = len, .file = name ? name : "<scene>", .opts = opts,
                .data_dir = opts && opts->data_dir && opts->data_dir[0] ? opts->data_dir : getenv("SHADELAB_DATA"),
                .err = err, .err_size = err_size, .default_material = -1};
    bool ok = load(&L, dir);
    free(L.pos);
    free(L.node_lines);
    free(L.camera_lines);
    if (!ok) {
        if (err && err_size && !err[0]) snprintf(err, err_size, "%s: could not load the scene", L.file);
        sl_scene_free(&scene);
        return false;
    }
    *out = scene;
    return true;
}

bool sl_scene_load_text(sl_scene *scene, const char *text, const char *name, const char *dir,
                        const sl_scene_load_opts *opts, char *err, size_t err_size) {
    if (!scene || !text) {
        if (err && err_size) snprintf(err, err_size, "sl_scene_load_text: no scene or no text");
        return false;
    }
    return load_common(scene, text, strlen(text), name, dir, opts, err, err_size);
}

bool sl_scene_load_default(sl_scene *scene, const sl_scene_load_opts *opts, char *err, size_t err_size) {
    return sl_scene_load_text(scene, sl_default_scene_json, "<default>", NULL, opts, err, err_size);
}

/* Detection by content, not by the extension: a binary glTF ("glTF" magic) or any file whose
 * first character is not '{' or '[' (OBJ, FBX, PLY… text or binary) is a model for assimp; a
 * JSON object with a top-level "asset" is a glTF document; other JSON is a shadelab scene. */
static bool is_model_head(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return false;
    unsigned char head[64];
    size_t n = fread(head, 1, sizeof head, f);
    fclose(f);
    if (n >= 4 && !memcmp(head, "glTF", 4)) return true;
    size_t i = n >= 3 && !memcmp(head, "\xEF\xBB\xBF", 3) ? 3 : 0;
    while (i < n && (head[i] == ' ' || head[i] == '\t' || head[i] == '\r' || head[i] == '\n')) i++;
    return i < n && head[i] != '{' && head[i] != '[';
}

static bool is_gltf_json(const char *text, size_t len) {
    if (!strstr(text, "\"asset\"")) return false; /* the scene format has no such key */
    cJSON *root = cJSON_ParseWithLength(text, len);
    bool yes = cJSON_IsObject(cJSON_GetObjectItemCaseSensitive(root, "asset"));
    cJSON_Delete(root);
    return yes;
}

bool sl_scene_load_file(sl_scene *scene, const char *path, const sl_scene_load_opts *opts,
                        char *err, size_t err_size) {
    if (err && err_size) err[0] = 0;
    if (!scene || !path || !path[0]) {
        if (err && err_size) snprintf(err, err_size, "no scene file given");
        return false;
    }
    struct stat st;
    if (stat(path, &st) != 0) {
        if (err && err_size) snprintf(err, err_size, "%s: %s", path, strerror(errno));
        return false;
    }
    if (S_ISDIR(st.st_mode)) {
        if (err && err_size) snprintf(err, err_size, "%s: is a directory, not a scene file", path);
        return false;
    }
    const char *ext = strrchr(path, '.'), *base = strrchr(path, '/');
    bool gltf_name = ext && (!base || ext > base) && (!strcasecmp(ext, ".gltf") || !strcasecmp(ext, ".glb"));
    if (S_ISREG(st.st_mode) && (gltf_name || is_model_head(path))) /* the glTF reader names its JSON errors */
        return sl_scene_load_model(scene, path, opts, err, err_size);
    if (st.st_size > (off_t)MAX_SCENE_FILE_BYTES) {
        if (err && err_size)
            snprintf(err, err_size, "%s: %lld bytes is too large for a scene file (limit %u MiB)", path,
                     (long long)st.st_size, MAX_SCENE_FILE_BYTES >> 20);
        return false;
    }
    size_t len;
    char *text = sl_read_file(path, &len, err, err_size);
    if (!text) return false;
    if (is_gltf_json(text, len)) { /* a .gltf document, whatever its name */
        free(text);
        return sl_scene_load_model(scene, path, opts, err, err_size);
    }
    /* relative assets resolve against the scene file's directory (made absolute) */
    char *copy = strdup(path);
    char *slash = copy ? strrchr(copy, '/') : NULL;
    const char *dir = ".";
    if (slash) {
        if (slash == copy) slash[1] = 0;
        else *slash = 0;
        dir = copy;
    }
    char *abs_dir = realpath(dir, NULL);
    bool ok = load_common(scene, text, len, path, abs_dir ? abs_dir : dir, opts, err, err_size);
    free(abs_dir);
    free(copy);
    free(text);
    return ok;
}

