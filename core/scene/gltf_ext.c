/* What assimp (Debian's 5.2) does not expose of a glTF 2.0 file, read from its JSON with cJSON:
 * the extensions it requires and uses. A required extension shadelab does not render is an
 * error naming it (glTF 2.0 §3.12: a loader must not load such a file as if it understood it);
 * a used one is a warning. The JSON is the .gltf text, or a .glb's first chunk (glTF 2.0 §4.4,
 * "GLB File Format Specification": 12-byte header, then chunks of length, type "JSON", data). */
#include "log.h"
#include "scene/scene.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Extensions the import renders as their authors meant (the rest: warned or refused). */
static const char *const understood[] = {"KHR_lights_punctual", "KHR_materials_emissive_strength",
                                        "KHR_texture_transform", "KHR_materials_ior", "KHR_materials_unlit"};

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
 * file's material order): KHR_materials_emissive_strength, KHR_materials_ior, KHR_materials_unlit. */
void sl_gltf_material_inputs(const void *json, unsigned index, sl_prop_list *inputs) {
    const cJSON *mats = cJSON_GetObjectItemCaseSensitive(json, "materials");
    const cJSON *mat = cJSON_IsArray(mats) ? cJSON_GetArrayItem(mats, (int)index) : NULL;
    const cJSON *ext = cJSON_GetObjectItemCaseSensitive(mat, "extensions");
    const cJSON *es = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(ext, "KHR_materials_emissive_strength"),
                                                       "emissiveStrength");
    if (cJSON_IsNumber(es) && es->valuedouble >= 0 && es->valuedouble <= 1e4)
        sl_prop_set_number(inputs, "emissive_strength", (float)es->valuedouble, 0);
    /* KHR_materials_ior: 1 or more, or exactly 0 (F0 = 1); default 1.5 */
    const cJSON *ior = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(ext, "KHR_materials_ior"), "ior");
    if (cJSON_IsNumber(ior) && (ior->valuedouble == 0 || (ior->valuedouble >= 1 && ior->valuedouble <= 10)))
        sl_prop_set_number(inputs, "ior", (float)ior->valuedouble, 0);
    else if (ior)
        SL_WARN("material %u: KHR_materials_ior.ior must be 0 or in [1, 10]: ignored (1.5)", index);
    if (cJSON_IsObject(cJSON_GetObjectItemCaseSensitive(ext, "KHR_materials_unlit")))
        sl_prop_set_bool(inputs, "unlit", true, 0);
}

/* A number member, or fallback when absent or not a finite number. */
static float number_or(const cJSON *obj, const char *key, float fallback) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    return cJSON_IsNumber(n) && isfinite(n->valuedouble) && fabs(n->valuedouble) < 1e6 ? (float)n->valuedouble : fallback;
}

/* Each textureInfo's UV set (texCoord) and KHR_texture_transform (offset, rotation, scale and its
 * texCoord override; the extension's defaults 0, 0, 1), for glTF material `index`, as the
 * material's uv_maps keyed by the standard input the texture feeds. Slots read with UV set 0
 * untransformed get none. A texCoord beyond 1 is read as 0 (*unsupported_texcoord set). */
void sl_gltf_uv_mappings(const void *json, unsigned index, sl_material *m, bool *unsupported_texcoord) {
    const cJSON *mats = cJSON_GetObjectItemCaseSensitive(json, "materials");
    const cJSON *mat = cJSON_IsArray(mats) ? cJSON_GetArrayItem(mats, (int)index) : NULL;
    if (!cJSON_IsObject(mat)) return;
    const cJSON *pbr = cJSON_GetObjectItemCaseSensitive(mat, "pbrMetallicRoughness");
    const struct { const cJSON *info; const char *input; } slots[] = {
        {cJSON_GetObjectItemCaseSensitive(pbr, "baseColorTexture"), "base_color_texture"},
        {cJSON_GetObjectItemCaseSensitive(pbr, "metallicRoughnessTexture"), "metallic_roughness_texture"},
        {cJSON_GetObjectItemCaseSensitive(mat, "normalTexture"), "normal_texture"},
        {cJSON_GetObjectItemCaseSensitive(mat, "occlusionTexture"), "occlusion_texture"},
        {cJSON_GetObjectItemCaseSensitive(mat, "emissiveTexture"), "emissive_texture"},
    };
    for (size_t k = 0; k < sizeof slots / sizeof *slots; k++) {
        const cJSON *info = slots[k].info;
        if (!cJSON_IsObject(info)) continue;
        sl_uv_mapping map = {.texcoord = (int)number_or(info, "texCoord", 0), .scale = {1, 1}};
        const cJSON *tt = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(info, "extensions"),
                                                          "KHR_texture_transform");
        bool transformed = false;
        if (cJSON_IsObject(tt)) {
            const cJSON *off = cJSON_GetObjectItemCaseSensitive(tt, "offset");
            const cJSON *scale = cJSON_GetObjectItemCaseSensitive(tt, "scale");
            for (int c = 0; c < 2; c++) {
                const cJSON *o = cJSON_GetArrayItem(off, c), *s = cJSON_GetArrayItem(scale, c);
                if (cJSON_IsArray(off) && cJSON_IsNumber(o) && isfinite(o->valuedouble)) map.offset[c] = (float)o->valuedouble;
                if (cJSON_IsArray(scale) && cJSON_IsNumber(s) && isfinite(s->valuedouble)) map.scale[c] = (float)s->valuedouble;
            }
            map.rotation = number_or(tt, "rotation", 0);
            map.texcoord = (int)number_or(tt, "texCoord", (float)map.texcoord); /* overrides textureInfo's */
            transformed = map.offset[0] != 0 || map.offset[1] != 0 || map.rotation != 0 || map.scale[0] != 1 ||
                          map.scale[1] != 1;
        }
        if (map.texcoord < 0 || map.texcoord > 1) {
            if (unsupported_texcoord) *unsupported_texcoord = true;
            map.texcoord = 0;
        }
        if (map.texcoord == 0 && !transformed) continue;
        sl_uv_mapping *grown = realloc(m->uv_maps, sizeof *grown * (size_t)(m->uv_map_count + 1));
        if (!grown) return;
        m->uv_maps = grown;
        map.input = strdup(slots[k].input);
        if (!map.input) return;
        m->uv_maps[m->uv_map_count++] = map;
    }
}
