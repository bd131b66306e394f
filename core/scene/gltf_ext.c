/* What assimp (Debian's 5.2) does not expose of a glTF 2.0 file, read from its JSON with cJSON:
 * the extensions it requires and uses. A required extension shadelab does not render is an
 * error naming it (glTF 2.0 §3.12: a loader must not load such a file as if it understood it);
 * a used one is a warning. The JSON is the .gltf text, or a .glb's first chunk (glTF 2.0 §4.4,
 * "GLB File Format Specification": 12-byte header, then chunks of length, type "JSON", data). */
#include "log.h"
#include "scene/scene.h"

#include <cjson/cJSON.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Extensions the import renders as their authors meant (the rest: warned or refused). */
static const char *const understood[] = {"KHR_lights_punctual", "KHR_materials_emissive_strength"};

static bool is_understood(const char *name) {
    for (size_t i = 0; i < sizeof understood / sizeof *understood; i++)
        if (!strcmp(understood[i], name)) return true;
    return false;
}

/* The glTF JSON of the file at path (malloc'd, NUL-terminated), or NULL when it has none. */
static char *gltf_json(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    unsigned char h[20];
    char *text = NULL;
    size_t n = fread(h, 1, sizeof h, f);
    if (n == sizeof h && !memcmp(h, "glTF", 4)) {
        uint32_t len = (uint32_t)h[12] | (uint32_t)h[13] << 8 | (uint32_t)h[14] << 16 | (uint32_t)h[15] << 24;
        if (!memcmp(h + 16, "JSON", 4) && len > 0 && len < (256u << 20) && (text = malloc((size_t)len + 1))) {
            if (fread(text, 1, len, f) == len) text[len] = 0;
            else free(text), text = NULL;
        }
    } else if (n > 0) {
        fseek(f, 0, SEEK_END);
        long size = ftell(f);
        if (size > 0 && size < (256L << 20) && (text = malloc((size_t)size + 1))) {
            fseek(f, 0, SEEK_SET);
            if (fread(text, 1, (size_t)size, f) == (size_t)size) text[size] = 0;
            else free(text), text = NULL;
        }
    }
    fclose(f);
    return text;
}

/* Lists the names in `arr` that shadelab does not understand into out ("A, B"); their count. */
static int not_understood(const cJSON *arr, char *out, size_t size) {
    int count = 0;
    size_t u = 0;
    out[0] = 0;
    const cJSON *e;
    cJSON_ArrayForEach(e, arr) {
        if (!cJSON_IsString(e) || is_understood(e->valuestring)) continue;
        if (u < size) u += snprintf(out + u, size - u, "%s%s", count ? ", " : "", e->valuestring);
        count++;
    }
    return count;
}

void *sl_gltf_read_json(const char *path) {
    char *text = gltf_json(path);
    if (!text) return NULL;
    cJSON *root = cJSON_Parse(text);
    free(text);
    return root;
}

void sl_gltf_free_json(void *json) { cJSON_Delete(json); }

bool sl_gltf_check_extensions(const void *json, const char *path, char *err, size_t err_size) {
    const cJSON *root = json;
    if (!root) return true; /* assimp reports what is wrong with the file */
    char list[1024];
    int n = not_understood(cJSON_GetObjectItemCaseSensitive(root, "extensionsRequired"), list, sizeof list);
    if (n) {
        snprintf(err, err_size, "%s: the file requires glTF extension%s shadelab does not support: %s", path,
                 n > 1 ? "s" : "", list);
        return false;
    }
    if (not_understood(cJSON_GetObjectItemCaseSensitive(root, "extensionsUsed"), list, sizeof list))
        SL_WARN("%s: uses glTF extensions shadelab does not render (ignored, the file shows without them): %s", path,
                list);
    return true;
}

/* Material extensions assimp 5.2 does not expose, for glTF material `index` (assimp keeps the
 * file's material order): KHR_materials_emissive_strength. */
void sl_gltf_material_inputs(const void *json, unsigned index, sl_prop_list *inputs) {
    const cJSON *mats = cJSON_GetObjectItemCaseSensitive(json, "materials");
    const cJSON *mat = cJSON_IsArray(mats) ? cJSON_GetArrayItem(mats, (int)index) : NULL;
    const cJSON *ext = cJSON_GetObjectItemCaseSensitive(mat, "extensions");
    const cJSON *es = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(ext, "KHR_materials_emissive_strength"),
                                                       "emissiveStrength");
    if (cJSON_IsNumber(es) && es->valuedouble >= 0 && es->valuedouble <= 1e4)
        sl_prop_set_number(inputs, "emissive_strength", (float)es->valuedouble, 0);
}
